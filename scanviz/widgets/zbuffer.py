"""Step through the z-buffer one depth test at a time.

`ZBufferView` shows, after each step, the depth buffer and the color buffer
as the ``depth_test`` events so far left them, beside the final image, and
the depth-test history of one picked pixel. `zbuffer_stepper` renders a
scene with a filtered `Recorder` and wraps the view in a `Stepper`.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Rectangle

from ..pipeline import RenderResult, render
from ..trace import Recorder, Trace
from ..trace.display import scroll_box
from ._common import (
    WIDEST,
    fmt,
    html_table,
    new_figure,
    note_label,
    parse_pixel,
    pixel_image,
    say,
    status_label,
)
from .stepper import Stepper, figure_widget, refresh_figure

HISTORY_COLUMNS = ("step", "polygon", "incoming z", "stored z", "test")


def _distinct(a: float, b: float) -> tuple[str, str]:
    """`a` and `b` to the fewest significant digits (at least 2) that tell them apart.

    >>> _distinct(0.4213, 0.6), _distinct(0.50012, 0.50031)
    (('0.42', '0.6'), ('0.5001', '0.5003'))
    """
    for digits in range(2, 17):
        left, right = f"{a:.{digits}g}", f"{b:.{digits}g}"
        if left != right:
            return left, right
    return left, right


class ZBufferView:
    """Depth and color buffers after `step` depth tests, and one pixel's test history.

    Parameters
    ----------
    trace : Trace
        Events of a traced `render`; its ``depth_test`` events are shown.
    result : RenderResult
        The same render: the final image, and per pixel the final polygon
        (whose shaded color the color buffer shows once that polygon wins).
    background : (3,) array_like of float, optional
        Color of pixels nothing has been drawn on yet.
    pixel : (int, int), optional
        The pixel whose history is shown, as if the student had picked it.
        By default the history follows the pixel tested at each step.
    region : (x_start, y_start, x_end, y_end), optional
        Outlined on the images (the region the trace was filtered to).
    note : str, optional
        Shown above the images (e.g. how the trace was filtered).

    Attributes
    ----------
    widget : ipywidgets.VBox
    pixel_text : ipywidgets.Text
        "x, y" of the pixel whose history is shown; typing one (or clicking
        an image) picks it and stops following the step.
    follow : ipywidgets.Checkbox
        Whether the history follows the pixel tested at each step (ticked
        until the student picks a pixel; ticking it again follows again).
    history : ipywidgets.HTML
        The pixel's depth tests; the step shown is highlighted, later ones gray.
    note : ipywidgets.HTML
        What the trace holds when it had to be filtered or cut.
    status : ipywidgets.HTML
        Bad pixel input.
    depth_image, color_image : matplotlib AxesImage
        Their arrays are the buffers at the step shown.

    Examples
    --------
    >>> from scanviz.scene.builtin import builtin_scene
    >>> view = zbuffer_stepper(builtin_scene("umbc_zbuffer"), 12, 12).views[0]
    >>> view.show(53)
    >>> event = view.trace[52]
    >>> view.pixel == (event.x, event.y)
    True
    >>> print(view.narrate(53))
    Depth test at pixel (2, 5): polygon 2's z = 0.29 < 0.31 stored, so the new fragment is nearer and is written.

    Notes
    -----
    Shading is deferred in `render`: a pixel is shaded once, for the polygon
    that wins it. The color buffer therefore shows a polygon's final shaded
    color where it is the final winner, its flat color elsewhere when it
    wins some other pixel in the end, and a categorical color otherwise.
    """

    def __init__(
        self,
        trace: Trace,
        result: RenderResult,
        *,
        background=(0.0, 0.0, 0.0),
        pixel: tuple[int, int] | None = None,
        region: tuple[int, int, int, int] | None = None,
        note: str = "",
    ) -> None:
        self.trace, self.result = trace, result
        self._read_tests(trace)
        self._palette = self._polygon_colors(result)
        self._background = np.asarray(background, np.float64)[:3]
        self.step = 0
        self._build_figure(result, region)
        self._build_controls(pixel, note)
        self.show(0)

    def _read_tests(self, trace: Trace) -> None:
        """The trace's depth tests as parallel arrays: event index, x, y, z, polygon, passed."""
        tests = [(i, e) for i, e in enumerate(trace) if e.kind == "depth_test"]
        self._index = np.array([i for i, _ in tests], np.int64)
        self._x = np.array([e.x for _, e in tests], np.int64)
        self._y = np.array([e.y for _, e in tests], np.int64)
        self._z = np.array([e.z for _, e in tests], np.float64)
        self._polygon = np.array([e.polygon for _, e in tests], np.int64)
        self._passed = np.array([e.passed for _, e in tests], bool)

    def _build_figure(self, result: RenderResult, region) -> None:
        """Depth so far, colour so far and the final image, with the step and pixel markers."""
        height, width = result.depth.shape
        fig, (ax_depth, ax_color, ax_final) = new_figure(3, width=WIDEST, height=3.0)
        finite = self._z[np.isfinite(self._z)]
        low, high = (finite.min(), finite.max()) if len(finite) else (0.0, 1.0)
        self.depth_image = pixel_image(
            ax_depth,
            np.full((height, width), np.nan),
            cmap="viridis_r",
            vmin=low,
            vmax=high if high > low else low + 1,
        )
        fig.colorbar(self.depth_image, ax=ax_depth, fraction=0.046, label="z (smaller = nearer)")
        self.color_image = pixel_image(ax_color, np.zeros((height, width, 3)))
        pixel_image(ax_final, result.image)
        for ax, title in zip(
            (ax_depth, ax_color, ax_final), ("depth so far", "color so far", "final"), strict=True
        ):
            ax.set_title(title, fontsize=10)
            ax.set_xlim(0, width)
            ax.set_ylim(0, height)
            if region is not None:
                x0, y0, x1, y1 = region
                ax.add_patch(
                    Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, ec="white", ls="--", lw=1)
                )
        self.current_marker = Rectangle((0, 0), 1, 1, fill=False, ec="orange", lw=2, visible=False)
        self.pixel_marker = Rectangle((0, 0), 1, 1, fill=False, ec="red", lw=1.5)
        ax_depth.add_patch(self.current_marker)
        ax_depth.add_patch(self.pixel_marker)
        self.figure, self.axes = fig, (ax_depth, ax_color, ax_final)
        fig.tight_layout()
        fig.canvas.mpl_connect("button_press_event", self._clicked)

    def _build_controls(self, pixel: tuple[int, int] | None, note: str) -> None:
        """The pixel box, the follow checkbox, the history and the layout around the figure."""
        self.follow = widgets.Checkbox(
            value=pixel is None, description="follow the step", indent=False
        )
        if pixel is None:
            pixel = (int(self._x[0]), int(self._y[0])) if len(self._x) else (0, 0)
        self.pixel = tuple(pixel)
        self.pixel_text = widgets.Text(
            value=f"{self.pixel[0]}, {self.pixel[1]}",
            description="pixel (x, y)",
            continuous_update=False,
        )
        self._following = False  # True while the view itself moves pixel_text
        self.pixel_text.observe(self._pixel_typed, names="value")
        self.follow.observe(self._follow_ticked, names="value")
        self.history = widgets.HTML()
        self.status = status_label()
        self.note = note_label(note)
        self._canvas = figure_widget(self.figure)
        self.widget = widgets.VBox(
            [
                self.note,
                self._canvas,
                widgets.HBox([self.pixel_text, self.follow, self.status]),
                self.history,
            ]
        )

    @staticmethod
    def _polygon_colors(result: RenderResult) -> dict[int, np.ndarray]:
        """The shaded color of each polygon at one pixel it finally wins (flat: its color)."""
        ys, xs = np.nonzero(result.polygon >= 0)
        winners = result.polygon[ys, xs]
        _, first = np.unique(winners, return_index=True)
        return {int(winners[k]): result.image[ys[k], xs[k]] for k in first}

    def buffers(self, step: int) -> tuple[np.ndarray, np.ndarray]:
        """(depth, polygon) after the first `step` events: (H, W) float64 (+inf empty), int64 (-1)."""
        height, width = self.result.depth.shape
        done = (self._index < step) & self._passed
        depth = np.full((height, width), np.inf)
        polygon = np.full((height, width), -1, np.int64)
        # Each pixel keeps its last passing test (a pass always lowers the stored depth).
        flat = (self._y[done] * width + self._x[done])[::-1]
        _, first = np.unique(flat, return_index=True)
        last = np.flatnonzero(done)[::-1][first]
        depth[self._y[last], self._x[last]] = self._z[last]
        polygon[self._y[last], self._x[last]] = self._polygon[last]
        return depth, polygon

    def colors(self, polygon: np.ndarray) -> np.ndarray:
        """The color buffer for a buffer of winning polygons (see Notes of the class)."""
        import matplotlib

        image = np.empty((*polygon.shape, 3))
        image[...] = self._background
        final = (polygon >= 0) & (polygon == self.result.polygon)
        image[final] = self.result.image[final]
        tab = matplotlib.colormaps["tab10"]
        for p in np.unique(polygon[(polygon >= 0) & ~final]):
            color = self._palette.get(int(p), np.array(tab(int(p) % 10)[:3]))
            image[(polygon == p) & ~final] = color
        return image

    def show(self, step: int) -> None:
        """Show the buffers after `step` events and the picked pixel's history at that step."""
        self.step = int(step)
        depth, polygon = self.buffers(self.step)
        self.depth_image.set_data(np.where(np.isfinite(depth), depth, np.nan))
        self.color_image.set_data(self.colors(polygon))
        tested = self.tested(self.step)
        self.current_marker.set_visible(tested is not None)
        if tested is not None:
            self.current_marker.set_xy(tested)
        if self.follow.value and (tested is not None or self.step == 0) and len(self._x):
            self._follow(tested or (int(self._x[0]), int(self._y[0])))
        self._show_history()
        refresh_figure(self.figure, self._canvas)

    def tested(self, step: int) -> tuple[int, int] | None:
        """The pixel that event `step` depth-tests (None at step 0 or for another event)."""
        current = np.flatnonzero(self._index == step - 1)
        return (int(self._x[current[0]]), int(self._y[current[0]])) if len(current) else None

    def narrate(self, step: int) -> str:
        """What depth test `step` decided and why, in one sentence (step 0: the start)."""
        if step == 0:
            return (
                "The start: every pixel's stored depth is +∞, so the first fragment drawn "
                "at a pixel always passes."
            )
        event = self.trace[step - 1]
        if event.kind != "depth_test":
            return event.kind.replace("_", " ") + "."
        at = f"Depth test at pixel ({event.x}, {event.y}): "
        if event.stored is None:
            return at + (
                f"nothing is stored there yet (+∞), so polygon {event.polygon}'s fragment at "
                f"z = {event.z:.4g} is nearer and is written."
            )
        z, stored = _distinct(event.z, event.stored)
        if event.passed:
            return at + (
                f"polygon {event.polygon}'s z = {z} < {stored} stored, so the new fragment is "
                "nearer and is written."
            )
        if event.z == event.stored:
            return at + (
                f"polygon {event.polygon}'s z = {z} equals the {stored} stored; a tie keeps "
                "the earlier polygon, so the new fragment is discarded."
            )
        return at + (
            f"polygon {event.polygon}'s z = {z} > {stored} stored, so the new fragment is "
            "behind and is discarded."
        )

    def _follow_ticked(self, change) -> None:
        if change["new"]:
            self.show(self.step)

    def _follow(self, pixel: tuple[int, int]) -> None:
        self.pixel = pixel
        self._following = True
        try:
            self.pixel_text.value = f"{pixel[0]}, {pixel[1]}"
        finally:
            self._following = False

    def _show_history(self) -> None:
        x, y = self.pixel
        self.pixel_marker.set_xy((x, y))
        here = np.flatnonzero((self._x == x) & (self._y == y))
        rows, states = [], []
        for k in here:
            event = self.trace[int(self._index[k])]
            rows.append(
                (int(self._index[k]) + 1, event.polygon, event.z, event.stored, event.passed)
            )
            done = self._index[k] < self.step
            states.append(
                "current" if self._index[k] == self.step - 1 else "done" if done else "pending"
            )
        tested = self.tested(self.step)
        if tested == (x, y):
            whose = "the pixel this step tests"
        elif self.follow.value:
            whose = "the first pixel to be tested" if self.step == 0 else "no test at this step"
        else:
            elsewhere = "" if tested is None else f"; this step tests ({tested[0]}, {tested[1]})"
            whose = f"picked by you{elsewhere}; tick 'follow the step' to follow the tests"
        title = f"<b>pixel ({x}, {y})</b>, {whose}: {len(rows)} depth test{'s' * (len(rows) != 1)}"
        if not rows:
            title += " in this trace (none: outside the region or not covered)"
        self.history.value = title + html_table(HISTORY_COLUMNS, rows, states=states)

    def pick(self, x: int, y: int) -> None:
        """Show pixel (x, y)'s history (same as typing it or clicking it)."""
        self.pixel_text.value = f"{int(x)}, {int(y)}"

    def _pixel_typed(self, change) -> None:
        if self._following:
            return
        try:
            x, y = parse_pixel(change["new"])
        except ValueError as error:
            say(self.status, str(error), error=True)
            return
        height, width = self.result.depth.shape
        if not (0 <= x < width and 0 <= y < height):
            say(self.status, f"pixel ({x}, {y}) is outside the {width}x{height} raster", error=True)
            return
        say(self.status, "")
        self.pixel = (x, y)
        with self.follow.hold_trait_notifications():
            self.follow.value = False  # the student chose: keep this pixel while stepping
        self._show_history()
        refresh_figure(self.figure, self._canvas)

    def _clicked(self, event) -> None:
        if event.inaxes in self.axes and event.xdata is not None:
            self.pick(int(np.floor(event.xdata)), int(np.floor(event.ydata)))


def _auto_region(result: RenderResult, budget: int) -> tuple[int, int, int, int]:
    """A square around the middle of the drawn pixels whose depth tests should fit `budget`."""
    height, width = result.depth.shape
    ys, xs = np.nonzero(result.polygon >= 0)
    if not len(xs):
        return (0, 0, width, height)
    tests_per_pixel = result.stats.fragments / len(xs)
    side = max(1, int(np.sqrt(0.8 * budget / max(tests_per_pixel, 1.0))))
    cx, cy = int(np.median(xs)), int(np.median(ys))
    x0, y0 = max(0, min(cx - side // 2, width - side)), max(0, min(cy - side // 2, height - side))
    return (x0, y0, min(width, x0 + side), min(height, y0 + side))


def zbuffer_stepper(
    scene,
    width: int,
    height: int,
    *,
    shading: str = "flat",
    region: tuple[int, int, int, int] | None = None,
    pixel: tuple[int, int] | None = None,
) -> Stepper:
    """Render `scene` tracing its depth tests and step through them with a `ZBufferView`.

    Parameters
    ----------
    scene : Scene
    width, height : int
        Raster size.
    shading : {"flat", "gouraud", "phong", "gooch"}
    region : (x_start, y_start, x_end, y_end), optional
        Record only the depth tests of these pixels (half-open). Without it,
        a scene with more depth tests than ``Stepper.MAX_STEPS`` is traced in
        a region around the middle of its drawn pixels, and the view says so.
    pixel : (int, int), optional
        The pixel whose depth-test history is shown first.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `ZBufferView`.

    Examples
    --------
    >>> from scanviz.scene.builtin import builtin_scene
    >>> stepper = zbuffer_stepper(builtin_scene("umbc_zbuffer"), 12, 12)
    >>> stepper.slider.max, stepper.views[0].pixel
    (54, (1, 2))
    """
    notes = []
    if region is None:
        estimate = render(scene, width, height, shading=shading)  # compiled: counts the tests
        if estimate.stats.fragments > Stepper.MAX_STEPS:
            region = _auto_region(estimate, Stepper.MAX_STEPS)
            notes.append(
                f"{estimate.stats.fragments} depth tests exceed the stepper's limit of "
                f"{Stepper.MAX_STEPS}: tracing only region {region} (pass region= to choose)."
            )
    result = render(
        scene, width, height, shading=shading, trace=Recorder(kinds=["depth_test"], region=region)
    )
    trace = result.trace
    if len(trace) > Stepper.MAX_STEPS:
        notes.append(
            f"The trace holds {len(trace)} depth tests: showing the first {Stepper.MAX_STEPS}."
        )
        trace = trace[: Stepper.MAX_STEPS]
    view = ZBufferView(
        trace,
        result,
        background=scene.background,
        pixel=pixel,
        region=region,
        note=" ".join(notes),
    )
    return Stepper(trace, [view], title="z-buffer: one depth test per step")


INTERPOLATION_KINDS = ("polygon_setup", "edge_values", "span_values")


def _value_names(setup) -> list[str]:
    """Column names of a polygon's interpolated values: a0, a1, ... or a0/w, ..., 1/w."""
    count = len(setup.values[0]) if setup is not None and setup.values else 0
    if setup is not None and setup.perspective and count:
        return [f"a{k}/w" for k in range(count - 1)] + ["1/w"]
    return [f"a{k}" for k in range(count)]


def _values(values) -> str:
    return "(" + ", ".join(fmt(v, 3) for v in values) + ")"


def narrate_interpolation(event, name: str = "values") -> str:
    """One sentence for a ``polygon_setup``, ``edge_values`` or ``span_values`` event.

    `name` is what the interpolated values are called ("values", or "C" for
    a fill's colour).

    Examples
    --------
    >>> from scanviz.trace import SpanValues
    >>> narrate_interpolation(SpanValues(3, 2, 6, 1.5, 5.25, 0.5, 0.125, (1.0,), (-0.25,), polygon=0))
    'Row y = 3: span 2 ≤ x < 6 between the crossings x = 1.5 and 5.25 starts with z = 0.5 and values (1) at x = 2, then adds dz/dx = 0.125 and (-0.25) per pixel: one addition each, no multiplication.'
    """
    if event.kind == "polygon_setup":
        count = len(event.values[0]) if event.values else 0
        plane = (
            "its plane is seen edge-on (no dz/dx)"
            if event.dzdx is None
            else f"its plane gives dz/dx = {fmt(event.dzdx, 3)} and dz/dy = {fmt(event.dzdy, 3)}"
        )
        carried = f"each vertex carries {count} {name}" if count else "no vertex values"
        divided = ", each divided by w so that they step linearly on screen" * event.perspective
        return (
            f"Polygon {event.polygon} is set up: {len(event.vertices)} vertices; {plane}; "
            f"{carried}{divided}."
        )
    if event.kind == "edge_values":
        edges = "; ".join(
            f"e{e.edge} at x = {fmt(e.x, 4)} with {_values(e.values)}" for e in event.entries
        )
        return (
            f"Row y = {event.y}: each active edge's x and {name} moved up to this row by their "
            f"d/dy: {edges or 'no active edge'}."
        )
    if event.kind == "span_values":
        z = f"z = {fmt(event.z, 4)} and " if name == "values" else ""
        dz = f"dz/dx = {fmt(event.dzdx, 3)} and " if name == "values" else ""
        return (
            f"Row y = {event.y}: span {event.x_start} ≤ x < {event.x_end} between the crossings "
            f"x = {fmt(event.x_left, 4)} and {fmt(event.x_right, 4)} starts with {z}{name} "
            f"{_values(event.values)} at x = {event.x_start}, then adds {dz}"
            f"{_values(event.dvdx)} per pixel: one addition each, no multiplication."
        )
    return event.kind.replace("_", " ") + "."


class InterpolationView:
    """Edge and span values of the row being scanned, and the current span on the image.

    Parameters
    ----------
    trace : Trace
        ``polygon_setup``, ``edge_values`` and ``span_values`` events of a traced render.
    image : (H, W, 3) ndarray of float64
        The final image, row 0 at the bottom.
    note : str, optional
        Shown above the view (e.g. that the trace was cut).

    Attributes
    ----------
    widget : ipywidgets.VBox
    setup : ipywidgets.HTML
        The current polygon: snapped vertices, depth plane, dz/dx, dz/dy.
    edges : ipywidgets.HTML
        The current row's active edges: x, values and their d/dy.
    spans : ipywidgets.HTML
        The current row's spans so far: start values and d/dx; the newest highlighted.
    span_patch : matplotlib Rectangle
        Over the current span (hidden when the step is not on a span).
    outline : matplotlib Line2D
        The current polygon's snapped outline.
    """

    def __init__(self, trace: Trace, image: np.ndarray, *, note: str = "") -> None:
        self.trace = trace
        height, width = image.shape[:2]
        fig, (ax,) = new_figure(1, width=4.5, height=4.5)
        pixel_image(ax, image)
        ax.set_xlim(0, width)
        ax.set_ylim(0, height)
        (self.outline,) = ax.plot([], [], color="crimson", lw=1.5)
        self.scanline = ax.axhline(0, color="orange", lw=1, visible=False)
        self.span_patch = Rectangle((0, 0), 0, 1, fill=False, ec="yellow", lw=2.5, visible=False)
        ax.add_patch(self.span_patch)
        fig.tight_layout()
        self.figure, self.ax = fig, ax
        self.setup, self.edges, self.spans = widgets.HTML(), widgets.HTML(), widgets.HTML()
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        tables = widgets.VBox(
            [self.setup, self.edges, self.spans], layout={"min_width": "0", "flex": "1 1 30em"}
        )
        self.widget = widgets.VBox(
            [self.note, widgets.HBox([self._canvas, tables], layout={"flex_flow": "row wrap"})]
        )
        self.step = 0
        self.show(0)

    def narrate(self, step: int) -> str:
        """What event `step` computed, in one sentence (step 0: the start)."""
        if step == 0:
            return "The start: no polygon is set up yet."
        return narrate_interpolation(self.trace[step - 1])

    def _latest(self, kind: str, step: int):
        return next((e for e in reversed(self.trace[:step]) if e.kind == kind), None)

    def show(self, step: int) -> None:
        """Show the polygon, row and span that the first `step` events reached."""
        self.step = int(step)
        setup = self._latest("polygon_setup", self.step)
        row = self._latest("edge_values", self.step)
        if row is not None and setup is not None and row.polygon != setup.polygon:
            row = None  # the new polygon has not reached a row yet
        names = _value_names(setup)
        if setup is None:
            self.setup.value = "<i>no polygon set up yet</i>"
            self.outline.set_data([], [])
        else:
            xs = [v[0] for v in setup.vertices] + [setup.vertices[0][0]]
            ys = [v[1] for v in setup.vertices] + [setup.vertices[0][1]]
            self.outline.set_data(xs, ys)
            self.setup.value = f"<b>polygon {setup.polygon}</b>" + scroll_box(
                html_table(
                    ("vertices (x, y, z)", "plane (A, B, C, D)", "dz/dx", "dz/dy"),
                    [(setup.vertices, setup.plane, setup.dzdx, setup.dzdy)],
                )
            )
        self.scanline.set_visible(row is not None)
        if row is None:
            self.edges.value = self.spans.value = ""
            self.span_patch.set_visible(False)
        else:
            self.scanline.set_ydata([row.y, row.y])
            self.edges.value = f"<b>row y = {row.y}</b>, z at x = 0: {row.z_row:.6g}" + scroll_box(
                html_table(
                    ("edge", "x", *names, *(f"d{n}/dy" for n in names)),
                    [(e.edge, e.x, *e.values, *e.dvdy) for e in row.entries],
                )
            )
            self._show_spans(row, names)
        refresh_figure(self.figure, self._canvas)

    def _show_spans(self, row, names) -> None:
        here = [
            (i, e)
            for i, e in enumerate(self.trace[: self.step])
            if e.kind == "span_values" and e.polygon == row.polygon and e.y == row.y
        ]
        current = here[-1][1] if here and here[-1][0] == self.step - 1 else None
        self.spans.value = "<b>spans</b>" + scroll_box(
            html_table(
                ("x_start", "x_end", "x_left", "x_right", "z", "dz/dx", *names)
                + tuple(f"d{n}/dx" for n in names),
                [
                    (e.x_start, e.x_end, e.x_left, e.x_right, e.z, e.dzdx, *e.values, *e.dvdx)
                    for _, e in here
                ],
                states=["current" if e is current else "done" for _, e in here],
            )
        )
        self.span_patch.set_visible(current is not None)
        if current is not None:
            self.span_patch.set_xy((current.x_start, current.y))
            self.span_patch.set_width(current.x_end - current.x_start)


def interpolation_stepper(
    scene_or_builtin,
    width: int | None = None,
    height: int | None = None,
    *,
    shading: str = "gouraud",
    polygons=None,
    rows: tuple[int, int] | None = None,
) -> Stepper:
    """Render with the interpolation traced and step through rows and spans.

    Parameters
    ----------
    scene_or_builtin : Scene or str
        A scene, or the name of a built-in scene (`scanviz.scene.builtin.BUILTIN_SCENES`).
    width, height : int, optional
        Raster size; defaults to the built-in scene's.
    shading : {"flat", "gouraud", "phong", "gooch"}
        Gouraud (default) interpolates the vertex colors.
    polygons : iterable of int, optional
        Record only these polygons.
    rows : (int, int), optional
        Record only these rows (half-open).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `InterpolationView`. A trace longer than
        ``Stepper.MAX_STEPS`` is cut, and the stepper's view says so.

    Examples
    --------
    >>> stepper = interpolation_stepper("umbc_zbuffer")
    >>> stepper.slider.max
    28
    """
    from ..scene.builtin import BUILTIN_SCENES, builtin_scene

    scene = scene_or_builtin
    if isinstance(scene_or_builtin, str):
        scene = builtin_scene(scene_or_builtin)
        width = width or BUILTIN_SCENES[scene_or_builtin].width
        height = height or BUILTIN_SCENES[scene_or_builtin].height
    if width is None or height is None:
        raise ValueError("'width' and 'height' are required for a Scene")
    recorder = Recorder(kinds=INTERPOLATION_KINDS, polygons=polygons, rows=rows)
    result = render(scene, width, height, shading=shading, trace=recorder)
    trace, note = result.trace, ""
    if len(trace) > Stepper.MAX_STEPS:
        note = (
            f"The trace holds {len(trace)} events: showing the first {Stepper.MAX_STEPS} "
            "(pass polygons= or rows= to choose)."
        )
        trace = trace[: Stepper.MAX_STEPS]
    view = InterpolationView(trace, result.image, note=note)
    return Stepper(trace, [view], title="interpolation along edges and spans")

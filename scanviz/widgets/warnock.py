"""Step through Warnock's area subdivision one area at a time.

`WarnockView` draws, after each ``area_classified`` event, the quadtree of
the areas visited so far over the image (each area outlined in the colour
of its case, the current one highlighted, with its case and polygons as
text), the image decided so far (the areas classified without subdividing),
the final image and the z-buffer's. `warnock_stepper` solves screen
polygons with a recording tracer and wraps the view in a `Stepper`.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.colors import to_rgb, to_rgba_array
from matplotlib.patches import Patch, Rectangle

from ..trace import Trace
from ..visibility.warnock import CASES, Warnock
from ._common import WIDEST, html_table, listed, new_figure, note_label, pixel_image
from .stepper import Stepper, figure_widget, first_steps, refresh_figure
from .visibility import against_zbuffer, polygon_colors, solve_traced

# Dark outlines, apart from the polygons' bright `PALETTE` fills; none red: red marks differences.
CASE_COLORS = {
    "empty": "#b8b8b8",
    "surrounding": "#00441b",
    "single": "#08306b",
    "subdivide": "#595959",
    "pixel": "#7b3294",
}
UNDECIDED = "#d9d9d9"  # samples no area has decided yet
LEAF_ALPHA = 0.15  # areas decided without subdividing are tinted with their case's colour
COUNT_COLUMNS = ("areas so far", *CASES)


class WarnockView:
    """The quadtree so far over the image, the image decided so far, the final and the z-buffer's.

    Parameters
    ----------
    trace : Trace
        Events of a traced Warnock solve; its ``area_classified`` events are the steps shown.
    result : VisibilityResult
        The same solve: its final ``polygon`` buffer.
    zbuffer_result : ZBufferResult or VisibilityResult
        The z-buffer's solve of the same polygons, for comparison.
    note : str, optional
        Shown above the figure (e.g. that the trace was cut).

    Attributes
    ----------
    widget : ipywidgets.VBox
    areas : matplotlib PolyCollection
        One rectangle per area in the trace, outlined in its case's colour (leaves
        also tinted with it); those not visited yet are transparent.
    current : matplotlib Rectangle
        Around the area of the step shown (hidden at step 0).
    decided_image : matplotlib AxesImage
        The visible polygon of the samples decided so far, `UNDECIDED` elsewhere.
    text : ipywidgets.HTML
        The current area: level, extent, case, polygon shown, polygons meeting it;
        and the areas so far per case.
    """

    def __init__(self, trace: Trace, result, zbuffer_result, *, note: str = "") -> None:
        self.events = [e for e in trace if e.kind == "area_classified"]
        steps = [i for i, e in enumerate(trace) if e.kind == "area_classified"]
        self._index = np.array(steps, np.int64)
        self.result = result
        height, width = result.polygon.shape
        self._case = np.array([CASES.index(e.case) for e in self.events], np.int64)
        # The step after which each sample is decided: the area that classified it without cutting.
        self._decided_at = np.full((height, width), np.iinfo(np.int64).max)
        for k, e in enumerate(self.events):
            if e.case != "subdivide":
                self._decided_at[e.y_start : e.y_end, e.x_start : e.x_end] = self._index[k]
        self._final_colors = polygon_colors(result.polygon)
        self.step = 0

        fig, axes = new_figure(4, width=WIDEST, height=2.9, per_row=4)
        ax_tree, ax_decided, ax_final, ax_zbuffer = axes
        pixel_image(ax_tree, self._final_colors, alpha=0.35)
        boxes = [
            [(e.x_start, e.y_start), (e.x_end, e.y_start), (e.x_end, e.y_end), (e.x_start, e.y_end)]
            for e in self.events
        ]
        cases = [CASE_COLORS[e.case] for e in self.events]
        self._edge_colors = to_rgba_array(cases).reshape(-1, 4)
        self._face_colors = self._edge_colors.copy()
        self._face_colors[:, 3] = np.where(self._case == CASES.index("subdivide"), 0.0, LEAF_ALPHA)
        levels = np.array([e.level for e in self.events], float)
        widths = np.maximum(2.4 - 0.4 * levels, 0.6)  # the larger the area, the bolder its outline
        self.areas = PolyCollection(boxes, linewidths=widths)
        ax_tree.add_collection(self.areas)
        self.current = Rectangle((0, 0), 1, 1, fill=False, lw=2.5, ls="--", visible=False)
        ax_tree.add_patch(self.current)
        self.decided_image = pixel_image(ax_decided, self._final_colors)
        against_zbuffer(ax_final, ax_zbuffer, result.polygon, zbuffer_result.polygon)
        titles = ("quadtree so far", "decided so far", "Warnock (final)", "z-buffer (red: differs)")
        for ax, title in zip(axes, titles, strict=True):
            ax.set_title(title, fontsize=10)
            ax.set_xlim(0, width)
            ax.set_ylim(0, height)
        handles = [Patch(fc="none", ec=CASE_COLORS[c], lw=2, label=c) for c in CASES]
        fig.legend(handles=handles, loc="lower center", ncol=len(CASES), fontsize=9)
        fig.tight_layout(rect=(0, 0.09, 1, 1))
        self.figure, self.axes = fig, axes
        self.text = widgets.HTML()
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox([self.note, self._canvas, self.text])
        self.show(0)

    def visited(self, step: int) -> int:
        """How many areas the first `step` events of the trace classified."""
        return int(np.searchsorted(self._index, step))

    def show(self, step: int) -> None:
        """Show the quadtree, the decided samples and the current area after `step` events."""
        self.step = int(step)
        done = self.visited(self.step)
        edges, faces = self._edge_colors.copy(), self._face_colors.copy()
        edges[done:, 3] = faces[done:, 3] = 0.0  # not visited yet
        self.areas.set_edgecolors(edges)
        self.areas.set_facecolors(faces)
        decided = self._decided_at < self.step
        image = np.where(decided[..., None], self._final_colors, to_rgb(UNDECIDED))
        self.decided_image.set_data(image)
        current = self.events[done - 1] if done and self._index[done - 1] == self.step - 1 else None
        self.current.set_visible(current is not None)
        if current is not None:
            self.current.set_xy((current.x_start, current.y_start))
            self.current.set_width(current.x_end - current.x_start)
            self.current.set_height(current.y_end - current.y_start)
            self.current.set_edgecolor(CASE_COLORS[current.case])
        self.text.value = self._describe(current, done)
        refresh_figure(self.figure, self._canvas)

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the area, the polygons meeting it, its case and why."""
        if step == 0:
            height, width = self.result.polygon.shape
            return (
                f"The start: the whole {width} x {height} screen is one area; each area is "
                "decided at once if it is simple enough, else cut into four quadrants."
            )
        area = self.events[self.visited(step) - 1]
        where = f"Area x {_range(area.x_start, area.x_end)}, y {_range(area.y_start, area.y_end)}"
        if area.case == "pixel":
            where = f"Pixel ({area.x_start}, {area.y_start})"
        where += f" (level {area.level})"
        meeting = _polygons(area.polygons)
        if area.case == "empty":
            return f"{where} meets no polygon, so it is all background."
        if area.case == "single":
            return (
                f"{where} meets only polygon {area.visible}, so it is drawn where it covers "
                "the area and the rest is background."
            )
        if area.case == "surrounding":
            others = [p for p in area.polygons if p != area.visible]
            nearer = f", nearer than {_polygons(others)} everywhere" if others else ""
            return f"{where}: polygon {area.visible} covers it all{nearer}, so it fills the area."
        if area.case == "pixel":
            shown = (
                f"polygon {area.visible} is nearest at its sample"
                if area.visible >= 0
                else "no polygon covers its sample: background"
            )
            return f"{where} meets {meeting}: {shown}."
        return (
            f"{where} meets {meeting} and no one of them decides it, so it is cut into "
            "four quadrants."
        )

    def _describe(self, area, done: int) -> str:
        counts = np.bincount(self._case[:done], minlength=len(CASES)).tolist()
        table = html_table(COUNT_COLUMNS, [(done, *counts)])
        if area is None:
            return "<i>no area classified yet</i>" + table
        shown = "background" if area.visible < 0 else f"polygon {area.visible}"
        if area.case == "subdivide":
            shown = "cut into quadrants"
        meeting = ", ".join(map(str, area.polygons)) or "none"
        return (
            f"<b>level {area.level}: area x [{area.x_start}, {area.x_end}) "
            f"y [{area.y_start}, {area.y_end})</b> &mdash; "
            f"<span style='color:{CASE_COLORS[area.case]}'><b>{html.escape(area.case)}</b></span>"
            f": {html.escape(shown)}; polygons meeting it: {html.escape(meeting)}" + table
        )


def _range(start: int, end: int) -> str:
    """The half-open range [start, end) of pixels as people count them: '3' or '0..7'."""
    return f"{start}" if end - start == 1 else f"{start}..{end - 1}"


def _polygons(ids) -> str:
    """'polygon 2', 'polygons 0 and 1', 'polygons 0, 1 and 2'."""
    ids = [str(p) for p in ids]
    if not ids:
        return "no polygon"
    if len(ids) == 1:
        return f"polygon {ids[0]}"
    return "polygons " + listed(ids)


def warnock_stepper(polygons, width: int, height: int, *, prune: bool = True, **options) -> Stepper:
    """Solve `polygons` with Warnock's algorithm, tracing each area, and step through the quadtree.

    Parameters
    ----------
    polygons : ScreenPolygons
        The scene in display coordinates (e.g. `scanviz.visibility.examples`).
    width, height : int
        Raster size.
    prune : bool
        As `Warnock`: pass sub-areas only the polygons not hidden behind a surrounding one.
    **options
        ``sample``, ``subpixel_bits``, ``perspective``: as `scanviz.visibility.solve`.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `WarnockView`. A trace longer than
        ``Stepper.MAX_STEPS`` is cut, and the view says so.

    Examples
    --------
    >>> from scanviz.visibility import examples
    >>> stepper = warnock_stepper(examples.slides_painter(), 16, 12)
    >>> stepper.slider.max == stepper.views[0].result.algorithm.areas
    True
    """
    chosen, kinds = Warnock(prune=prune), ["area_classified"]
    result, reference = solve_traced(chosen, polygons, width, height, kinds, **options)
    trace, note = first_steps(result.trace, "areas")
    view = WarnockView(trace, result, reference, note=note)
    return Stepper(trace, [view], title="Warnock's area subdivision: one area per step")

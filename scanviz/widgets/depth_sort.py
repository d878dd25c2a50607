"""Step through depth sort pair by pair, and through the painter's algorithm pixel by pixel.

`DepthSortView` shows, after each step of a traced depth sort, the list
(the pieces still to paint, far end first) with the pair being tested
highlighted, the tests run on that pair and the one that settled it, the
swaps and splits so far, and the image of the pieces painted so far beside
the final image and the z-buffer's. `PainterView` shows the painter's
sorted list and the image as it is painted, beside the z-buffer's, with the
samples where the painter's order is wrong outlined. `depth_sort_stepper`
and `painter_stepper` solve screen polygons with a `Recorder` and wrap the
view in a `Stepper`.

Both views draw what the trace recorded: the list after each swap and
split (``pieces_swapped``, ``polygons_sorted``), the pairs
(``pair_tested``) and the samples painted (``pixel_painted``). A piece
leaves the list when it is painted: that is when the next pair names a
later piece as S.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Polygon as PolygonPatch
from matplotlib.patches import Rectangle

from ..trace import Recorder, Trace
from ..visibility import ScreenPolygons, solve, zbuffer
from ..visibility.painter import Painter, sort_key
from ._common import WIDEST, html_table, new_figure, say, status_label
from .stepper import Stepper, figure_widget, first_steps, refresh_figure
from .visibility import outline_samples, polygon_colors

DECISION_KINDS = (
    "polygons_sorted",
    "pair_tested",
    "pieces_swapped",
    "polygon_split",
    "paint_order",
)
LIST_COLUMNS = ("#", "piece", "polygon", "zmin", "zmax", "role")
TEST_COLUMNS = ("test", "result")


def _image_axes(axes, ids: np.ndarray, title: str):
    height, width = ids.shape
    image = axes.imshow(
        polygon_colors(ids), origin="lower", extent=(0, width, 0, height), interpolation="nearest"
    )
    axes.set_title(title, fontsize=10)
    axes.set_xlim(0, width)
    axes.set_ylim(0, height)
    return image


class _Painting:
    """The samples each piece wrote (its ``pixel_painted`` events), to paint any prefix of pieces."""

    def __init__(self, trace: Trace, shape: tuple[int, int]) -> None:
        self.shape = shape
        self.events = [e for e in trace if e.kind == "pixel_painted"]
        self.writes: dict[str, list] = {}
        for e in self.events:
            if e.painted:
                self.writes.setdefault(e.piece, []).append((e.y, e.x, e.polygon))

    def pieces(self, labels) -> np.ndarray:
        """(H, W) polygon ids after painting the pieces `labels` in order (-1: nothing yet)."""
        ids = np.full(self.shape, -1, np.int64)
        for label in labels:
            for y, x, polygon in self.writes.get(label, ()):
                ids[y, x] = polygon
        return ids

    def first(self, count: int) -> np.ndarray:
        """(H, W) polygon ids after the first `count` pixel_painted events."""
        ids = np.full(self.shape, -1, np.int64)
        for e in self.events[:count]:
            if e.painted:
                ids[e.y, e.x] = e.polygon
        return ids


def list_states(steps: Trace) -> list[tuple[list, list, object]]:
    """Per step 0..len(steps): (list of records still to paint, labels painted, current pair).

    The list is the last one recorded (``polygons_sorted`` at the start and
    after each split, ``pieces_swapped``) less the pieces painted since: the
    ones before the S of the latest pair; ``paint_order`` ends it.
    """
    records: dict[str, object] = {}
    order: list[str] = []
    painted: list[str] = []
    pair = None
    states = [([], [], None)]
    for e in steps:
        if e.kind == "polygons_sorted":
            records.update((p.label, p) for p in e.pieces)
            order = [p.label for p in e.pieces]
        elif e.kind == "pieces_swapped":
            order = list(e.order)
        elif e.kind == "polygon_split":
            records.update((p.label, p) for p in (e.front, e.behind))
        elif e.kind == "pair_tested":
            head = order.index(e.piece)
            painted, order, pair = painted + order[:head], order[head:], e
        elif e.kind == "paint_order":
            records.update((p.label, p) for p in e.pieces)
            painted, order, pair = [p.label for p in e.pieces], [], None
        states.append(([records[label] for label in order], list(painted), pair))
    return states


class DepthSortView:
    """The list, the pair being tested and its tests, swaps and splits, the image painted so far.

    Parameters
    ----------
    trace : Trace
        Events of a traced ``solve("depth_sort", ...)``: the decision
        (``polygons_sorted``, ``pair_tested``, ``pieces_swapped``,
        ``polygon_split``, ``paint_order``) and its ``pixel_painted`` events.
    result : VisibilityResult
        The same run (its final polygon per sample).
    zbuffer_result : ZBufferResult
        The z-buffer on the same polygons; samples where depth sort shows
        another polygon are outlined.
    note : str, optional
        Shown above the view.

    Attributes
    ----------
    steps : Trace
        The decision events: one step each (give it to the `Stepper`).
    widget : ipywidgets.VBox
    list_table : ipywidgets.HTML
        The list, far end first; S and S' of the current pair highlighted.
    tests_table : ipywidgets.HTML
        The current pair's tests in order with pass/fail; the one that settled it highlighted.
    settled : ipywidgets.HTML
        What settled the current pair and what followed ("order ok", "swap", "split").
    log : ipywidgets.HTML
        The swaps and splits so far, the latest first.
    painted_image : matplotlib AxesImage
        The pieces painted so far (polygon colors, white where nothing is).
    """

    def __init__(self, trace: Trace, result, zbuffer_result, *, note: str = "") -> None:
        self.steps = Trace(e for e in trace if e.kind in DECISION_KINDS)
        self.result, self.zbuffer_result = result, zbuffer_result
        height, width = result.polygon.shape
        self._painting = _Painting(trace, (height, width))
        self._states = list_states(self.steps)
        fig, (ax_painted, ax_final, ax_z) = new_figure(3, width=WIDEST, height=3.3)
        self.painted_image = _image_axes(
            ax_painted, np.full((height, width), -1), "painted so far (S solid, S' dashed)"
        )
        _image_axes(ax_final, result.polygon, "depth sort")
        _image_axes(ax_z, zbuffer_result.polygon, "z-buffer (red: differs)")
        wrong = result.polygon != zbuffer_result.polygon
        for ax in (ax_final, ax_z):
            outline_samples(ax, wrong)
        self.s_outline = PolygonPatch(np.zeros((3, 2)), fill=False, ec="black", lw=2.5)
        self.other_outline = PolygonPatch(np.zeros((3, 2)), fill=False, ec="black", lw=1.5, ls="--")
        ax_painted.add_patch(self.s_outline)
        ax_painted.add_patch(self.other_outline)
        fig.tight_layout()
        self.figure, self.axes = fig, (ax_painted, ax_final, ax_z)
        self.list_table, self.tests_table = widgets.HTML(), widgets.HTML()
        self.settled, self.log = widgets.HTML(), widgets.HTML()
        self.note = status_label()
        say(self.note, note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox(
            [
                self.note,
                self._canvas,
                widgets.HBox(
                    [self.list_table, widgets.VBox([self.settled, self.tests_table, self.log])]
                ),
            ]
        )
        self.step = 0
        self.show(0)

    def show(self, step: int) -> None:
        """Show the list, the pair and the image after the first `step` decision events."""
        self.step = int(step)
        pending, painted, pair = self._states[self.step]
        self.painted_image.set_data(polygon_colors(self._painting.pieces(painted)))
        roles = {pair.piece: "S", pair.other: "S'"} if pair is not None else {}
        rows = [
            (k + 1, r.label, r.polygon, r.zmin, r.zmax, roles.get(r.label, ""))
            for k, r in enumerate(pending)
        ]
        states = ["current" if r.label in roles else "" for r in pending]
        done = html.escape(", ".join(painted)) or "none"
        heading = f"<b>the list</b> ({len(pending)} to paint, far end first; painted: {done})"
        self.list_table.value = heading + html_table(LIST_COLUMNS, rows, states=states)
        self._show_pair(pair)
        self._show_log()
        by_label = {r.label: r for r in pending}
        for patch, label in ((self.s_outline, "piece"), (self.other_outline, "other")):
            record = by_label.get(getattr(pair, label, None))
            patch.set_visible(record is not None)
            if record is not None:
                patch.set_xy(np.array([v[:2] for v in record.vertices]))
        refresh_figure(self.figure, self._canvas)

    def _show_pair(self, pair) -> None:
        if pair is None:
            self.settled.value = "<i>no pair under test</i>"
            self.tests_table.value = ""
            return
        outcome = {
            "no_overlap": "S' is wholly nearer (minimax): S may go first",
            "order_ok": "S may be painted before S'",
            "swap": "S' must go first: it moves to the far end",
            "split": "no order works: a piece is split",
            "unresolved": "no split breaks it (budget or cycle without straddling): kept as is",
        }.get(pair.outcome, pair.outcome)
        by = (
            f"settled by <b>{html.escape(pair.settled_by)}</b>"
            if pair.settled_by
            else "<b>no test settles it</b>"
        )
        pieces = f"S = {html.escape(pair.piece)}, S' = {html.escape(pair.other)}"
        self.settled.value = f"<b>{pieces}:</b> {by} &rarr; {html.escape(outcome)}"
        rows = [(t.name, t.passed) for t in pair.tests]
        states = ["current" if t.passed else "" for t in pair.tests]
        self.tests_table.value = html_table(TEST_COLUMNS, rows, states=states)

    def _show_log(self) -> None:
        lines = []
        for e in self.steps[: self.step]:
            if e.kind == "pieces_swapped":
                lines.append(f"swap: {e.moved} moved to the far end, ahead of {e.piece}")
            elif e.kind == "polygon_split":
                lines.append(
                    f"split ({e.why}): {e.piece} cut by the plane of polygon {e.by} into "
                    f"{e.front.label} (in front) and {e.behind.label} (behind)"
                )
        shown = "<br>".join(html.escape(line) for line in lines[::-1][:8])
        self.log.value = f"<b>swaps and splits</b> ({len(lines)})<br>{shown}"


class PainterView:
    """The painter's sorted list and the image painted sample by sample, beside the z-buffer's.

    Parameters
    ----------
    trace : Trace
        ``polygons_sorted`` and ``pixel_painted`` events of a traced ``solve("painter", ...)``.
    result, zbuffer_result
        The painter's result and the z-buffer's on the same polygons.
    note : str, optional

    Attributes
    ----------
    steps : Trace
        ``polygons_sorted`` then one ``pixel_painted`` per step.
    widget : ipywidgets.VBox
    list_table : ipywidgets.HTML
        The sorted list (the key, zmin, zmax); the polygon being painted highlighted.
    painted_image : matplotlib AxesImage
    """

    def __init__(self, trace: Trace, result, zbuffer_result, *, key: str, note: str = "") -> None:
        self.steps = Trace(e for e in trace if e.kind in ("polygons_sorted", "pixel_painted"))
        self.result, self.zbuffer_result, self.key = result, zbuffer_result, key
        height, width = result.polygon.shape
        self._painting = _Painting(self.steps, (height, width))
        self._sorted = next((e.pieces for e in self.steps if e.kind == "polygons_sorted"), ())
        fig, (ax_painted, ax_final, ax_z) = new_figure(3, width=WIDEST, height=3.3)
        self.painted_image = _image_axes(ax_painted, np.full((height, width), -1), "painted so far")
        _image_axes(ax_final, result.polygon, f"painter's ({key})")
        _image_axes(ax_z, zbuffer_result.polygon, "z-buffer (red: painter differs)")
        wrong = result.polygon != zbuffer_result.polygon
        for ax in (ax_final, ax_z):
            outline_samples(ax, wrong)
        self.current_marker = Rectangle((0, 0), 1, 1, fill=False, ec="black", lw=2, visible=False)
        ax_painted.add_patch(self.current_marker)
        fig.tight_layout()
        self.figure = fig
        self.list_table = widgets.HTML()
        self.summary = widgets.HTML(
            f"{int(wrong.sum())} samples differ from the z-buffer (outlined in red)"
        )
        self.note = status_label()
        say(self.note, note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox([self.note, self._canvas, self.summary, self.list_table])
        self.step = 0
        self.show(0)

    def show(self, step: int) -> None:
        """Show the image after the first `step` events and the polygon being painted."""
        self.step = int(step)
        painted = max(self.step - 1, 0)  # the first step is the sort
        self.painted_image.set_data(polygon_colors(self._painting.first(painted)))
        current = self._painting.events[painted - 1] if painted else None
        self.current_marker.set_visible(current is not None)
        if current is not None:
            self.current_marker.set_xy((current.x, current.y))
        label = current.piece if current is not None else None
        rows = [
            (k + 1, r.label, r.polygon, sort_key(_piece(r), self.key), r.zmin, r.zmax)
            for k, r in enumerate(self._sorted)
        ]
        states = ["current" if r.label == label else "" for r in self._sorted]
        self.list_table.value = f"<b>sorted on {self.key}, farthest first</b>" + html_table(
            ("#", "piece", "polygon", f"key ({self.key})", "zmin", "zmax"), rows, states=states
        )
        refresh_figure(self.figure, self._canvas)


def _piece(record):
    from ..visibility import Piece

    return Piece(record.polygon, record.label, np.array(record.vertices))


def depth_sort_stepper(polygons: ScreenPolygons, width: int, height: int, **options) -> Stepper:
    """Solve `polygons` with depth sort, traced, and step through its decision with a `DepthSortView`.

    Parameters
    ----------
    polygons : ScreenPolygons
    width, height : int
    **options
        Those of `scanviz.visibility.solve` (``sample``, ``subpixel_bits``, ...)
        and ``max_splits`` of `DepthSort`.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `DepthSortView`; one step per decision event.

    Examples
    --------
    >>> from scanviz.visibility.examples import interpenetrating
    >>> stepper = depth_sort_stepper(interpenetrating(), 16, 12)
    >>> stepper.slider.max, stepper.views[0].steps[-1].kind
    (8, 'paint_order')
    """
    from ..visibility.depth_sort import DepthSort

    algorithm = DepthSort(max_splits=options.pop("max_splits", None))
    result = solve(algorithm, polygons, width, height, trace=Recorder(), **options)
    reference = zbuffer(polygons, width, height, **options)
    view = DepthSortView(result.trace, result, reference)
    view.steps, note = first_steps(view.steps, "steps of the decision")
    if note:
        say(view.note, note)
    return Stepper(view.steps, [view], title="depth sort: one pair, swap or split per step")


def painter_stepper(
    polygons: ScreenPolygons, width: int, height: int, key: str = "zmin", **options
) -> Stepper:
    """Solve `polygons` with the painter's algorithm, traced, and watch it paint sample by sample.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `PainterView`: the sort, then one sample per step.

    Examples
    --------
    >>> from scanviz.visibility.examples import long_behind_short
    >>> stepper = painter_stepper(long_behind_short(), 16, 12)
    >>> stepper.views[0].summary.value
    '20 samples differ from the z-buffer (outlined in red)'
    """
    recorder = Recorder(kinds=["polygons_sorted", "pixel_painted"])
    result = solve(Painter(key=key), polygons, width, height, trace=recorder, **options)
    reference = zbuffer(polygons, width, height, **options)
    trace, note = first_steps(result.trace)
    view = PainterView(trace, result, reference, key=key, note=note)
    return Stepper(view.steps, [view], title=f"painter's algorithm (sorted on {key})")

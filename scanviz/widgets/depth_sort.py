"""Step through depth sort pair by pair, and the painter's algorithm polygon by polygon.

`DepthSortView` shows, after each step of a traced depth sort, the list
(the pieces still to paint, far end first) with the pair being tested
highlighted, the tests run on that pair and the one that settled it, the
swaps and splits so far, and the image of the pieces painted so far beside
the final image and the z-buffer's. A piece is painted when it leaves the
far end of the list: that is a step of its own. `PainterView` shows the
painter's sorted list and the image as it is painted, one polygon per step
(or one sample per step, ``steps="pixel"``), beside the z-buffer's, with the
samples where the painter's order is wrong outlined. `depth_sort_stepper`
and `painter_stepper` solve screen polygons with a `Recorder` and wrap the
view in a `Stepper`. Each view's ``narrate(step)`` says what the step did.

Both views draw what the trace recorded: the list after each swap and
split (``pieces_swapped``, ``polygons_sorted``), the pairs
(``pair_tested``) and the samples painted (``pixel_painted``). A piece
leaves the list when it is painted: that is when the next pair names a
later piece as S. A painting step is marked in the stepper's trace by the
piece's last ``pixel_painted`` event (in pixel steps, by each of them).
"""

from __future__ import annotations

import html
from typing import NamedTuple

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Polygon as PolygonPatch
from matplotlib.patches import Rectangle

from ..trace import Trace
from ..visibility import ScreenPolygons
from ..visibility.painter import Painter, sort_key
from ._common import WIDEST, fmt, html_table, new_figure, note_label, pixel_image
from .stepper import Stepper, figure_widget, refresh_figure, stepper_of
from .visibility import against_zbuffer, polygon_colors, solve_traced

DECISION_KINDS = (
    "polygons_sorted",
    "pair_tested",
    "pieces_swapped",
    "polygon_split",
    "paint_order",
)
STEP_CHOICES = ("polygon", "pixel")  # what a painting step paints: one piece, or one sample
LIST_COLUMNS = ("#", "piece", "polygon", "zmin", "zmax", "role")
TEST_COLUMNS = ("test", "result")
# The ambiguity tests as the slides number them, each as the question it asks of S and S'.
TEST_QUESTIONS = {
    "minimax": ("0", "is {o} wholly nearer than {s}?"),
    "x_extent": ("1", "are the x extents of {s} and {o} apart?"),
    "y_extent": ("2", "are their y extents apart?"),
    "s_behind_plane": ("3", "is {s} entirely behind the plane of {o}?"),
    "other_in_front": ("4", "is {o} entirely in front of the plane of {s}?"),
    "no_overlap": ("5", "do their projections not overlap?"),
    "other_behind_plane": ("3'", "is {o} entirely behind the plane of {s}?"),
    "s_in_front": ("4'", "is {s} entirely in front of the plane of {o}?"),
}
DIGITS = 3  # significant digits of the depths in the narration


def _painting_figure(result, zbuffer_result, titles: tuple[str, str, str]):
    """(figure, axes, painted image, samples that differ): painted so far, final and z-buffer."""
    height, width = result.polygon.shape
    fig, axes = new_figure(3, width=WIDEST, height=3.3)
    painted_image = pixel_image(axes[0], polygon_colors(np.full((height, width), -1)))
    wrong = against_zbuffer(axes[1], axes[2], result.polygon, zbuffer_result.polygon)
    for ax, title in zip(axes, titles, strict=True):
        ax.set_title(title, fontsize=10)
        ax.set_xlim(0, width)
        ax.set_ylim(0, height)
    return fig, axes, painted_image, wrong


def _check_steps(steps: str) -> str:
    if steps not in STEP_CHOICES:
        raise ValueError(f"'steps' must be one of {STEP_CHOICES}; got {steps!r}")
    return steps


class _Painting:
    """The ``pixel_painted`` events of each piece, in painting order, to paint any prefix."""

    def __init__(self, trace: Trace, shape: tuple[int, int]) -> None:
        self.shape = shape
        self.events = [e for e in trace if e.kind == "pixel_painted"]
        self.of_piece: dict[str, list] = {}
        for e in self.events:
            self.of_piece.setdefault(e.piece, []).append(e)

    def image(self, labels, partial: str | None = None, count: int = 0) -> np.ndarray:
        """(H, W) polygon ids after painting the pieces `labels`, then `count` samples of `partial`."""
        events = [e for label in labels for e in self.of_piece.get(label, ())]
        return self.ids(events + self.of_piece.get(partial, [])[:count])

    def ids(self, events) -> np.ndarray:
        """(H, W) polygon ids after the ``pixel_painted`` `events`, in order (-1: none painted)."""
        ids = np.full(self.shape, -1, np.int64)
        for e in events:
            if e.painted:
                ids[e.y, e.x] = e.polygon
        return ids

    def written(self, label: str) -> list:
        """The samples piece `label` wrote (its ``pixel_painted`` events with ``painted``)."""
        return [e for e in self.of_piece.get(label, ()) if e.painted]


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


class _Shown(NamedTuple):
    """What the depth sort view shows after a step."""

    pending: list  # PieceRecords still to paint, far end first
    painted: list  # labels of the pieces painted whole
    pair: object  # the PairTested under test, or None
    painting: object  # the PieceRecord being painted at this step, or None
    samples: int  # how many of its pixel_painted events are shown (pixel steps)


def _display(decisions: Trace, painting: _Painting, steps: str) -> tuple[list, list]:
    """(steps, shown): the decision events with a step per piece painted (or per sample), and
    what each step shows (`_Shown`, step 0 first).

    A piece is painted where it leaves the list: before the pair whose S lies
    beyond it, or after ``paint_order`` for the pieces left. A step that
    paints is marked by the piece's last ``pixel_painted`` event (pixel
    steps: by each); a piece that covers no sample, by the decision event.
    """
    states = list_states(decisions)
    marks, shown = [], [_Shown([], [], None, None, 0)]
    for k, event in enumerate(decisions):
        before, after = states[k], states[k + 1]
        pending, done = list(before[0]), list(before[1])
        newly = after[1][len(done) :]
        if event.kind == "paint_order":  # the settled list first, then its pieces one by one
            marks.append(event)
            shown.append(_Shown(pending, done, None, None, 0))
        records = {r.label: r for r in pending}
        records.update((r.label, r) for r in getattr(event, "pieces", ()))
        for label in newly:
            pending = [r for r in pending if r.label != label]
            events = painting.of_piece.get(label, [])
            counts = range(1, len(events) + 1) if steps == "pixel" and events else [len(events)]
            for count in counts:
                marks.append(events[count - 1] if count else event)
                shown.append(_Shown(pending, done, None, records[label], count))
            done = done + [label]
        if event.kind != "paint_order":
            marks.append(event)
            shown.append(_Shown(after[0], after[1], after[2], None, 0))
    return marks, shown


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
    steps : {"polygon", "pixel"}
        A piece leaving the list is painted in one step ("polygon"), or one
        step per sample it paints ("pixel").

    Attributes
    ----------
    steps : Trace
        One event per step (give it to the `Stepper`): each decision event,
        and, where a piece is painted, its last ``pixel_painted`` event (each
        of them for pixel steps).
    widget : ipywidgets.VBox
    list_table : ipywidgets.HTML
        The list, far end first; S and S' of the current pair highlighted,
        or the piece being painted.
    tests_table : ipywidgets.HTML
        The current pair's tests in order with pass/fail; the one that settled it highlighted.
    settled : ipywidgets.HTML
        What settled the current pair and what followed ("order ok", "swap", "split").
    log : ipywidgets.HTML
        The swaps and splits so far, the latest first.
    painted_image : matplotlib AxesImage
        The pieces painted so far (polygon colors, white where nothing is).
    """

    def __init__(
        self, trace: Trace, result, zbuffer_result, *, note: str = "", steps: str = "polygon"
    ) -> None:
        self.decisions = Trace(e for e in trace if e.kind in DECISION_KINDS)
        self.result, self.zbuffer_result = result, zbuffer_result
        height, width = result.polygon.shape
        self._painting = _Painting(trace, (height, width))
        self.steps_mode = _check_steps(steps)
        marks, self._shown = _display(self.decisions, self._painting, self.steps_mode)
        self.steps = Trace(marks)
        titles = ("painted so far (S solid, S' dashed)", "depth sort", "z-buffer (red: differs)")
        fig, axes, self.painted_image, _ = _painting_figure(result, zbuffer_result, titles)
        self.s_outline = PolygonPatch(np.zeros((3, 2)), fill=False, ec="black", lw=2.5)
        self.other_outline = PolygonPatch(np.zeros((3, 2)), fill=False, ec="black", lw=1.5, ls="--")
        axes[0].add_patch(self.s_outline)
        axes[0].add_patch(self.other_outline)
        fig.tight_layout()
        self.figure, self.axes = fig, tuple(axes)
        self.list_table, self.tests_table = widgets.HTML(), widgets.HTML()
        self.settled, self.log = widgets.HTML(), widgets.HTML()
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox(
            [
                self.note,
                self._canvas,
                widgets.HBox(
                    [self.list_table, widgets.VBox([self.settled, self.tests_table, self.log])],
                    layout={"flex_flow": "row wrap"},
                ),
            ]
        )
        self.step = 0
        self.show(0)

    def show(self, step: int) -> None:
        """Show the list, the pair and the image after the first `step` steps."""
        self.step = int(step)
        shown = self._shown[self.step]
        partial = shown.painting.label if shown.painting is not None else None
        ids = self._painting.image(shown.painted, partial, shown.samples)
        self.painted_image.set_data(polygon_colors(ids))
        pair = shown.pair
        roles = {pair.piece: "S", pair.other: "S'"} if pair is not None else {}
        listed = ([shown.painting] if shown.painting is not None else []) + shown.pending
        if shown.painting is not None:
            roles = {partial: "painted now"}
        rows = [
            (k + 1, r.label, r.polygon, r.zmin, r.zmax, roles.get(r.label, ""))
            for k, r in enumerate(listed)
        ]
        states = ["current" if r.label in roles else "" for r in listed]
        done = html.escape(", ".join(shown.painted)) or "none"
        heading = f"<b>the list</b> ({len(shown.pending)} to paint, far end first; painted: {done})"
        self.list_table.value = heading + html_table(LIST_COLUMNS, rows, states=states)
        self._show_pair(pair, shown.painting)
        self._show_log()
        by_label = {r.label: r for r in listed}
        outlined = (
            (partial, None)
            if partial
            else (getattr(pair, "piece", None), getattr(pair, "other", None))
        )
        for patch, label in zip((self.s_outline, self.other_outline), outlined, strict=True):
            record = by_label.get(label)
            patch.set_visible(record is not None)
            if record is not None:
                patch.set_xy(np.array([v[:2] for v in record.vertices]))
        refresh_figure(self.figure, self._canvas)

    def _show_pair(self, pair, painting) -> None:
        if pair is None:
            self.settled.value = (
                f"<i>no pair under test: piece {html.escape(painting.label)} is painted</i>"
                if painting is not None
                else "<i>no pair under test</i>"
            )
            self.tests_table.value = ""
            return
        outcome = {
            "no_overlap": "S' is wholly nearer (minimax): S may go first",
            "order_ok": "S may be painted before S'",
            "swap": "S' must go first: it moves to the far end",
            "split": "no order works: a piece is split",
            "no_shared_sample": "no split breaks it, but they share no sample: any order paints the same",
            "unresolved": "no split breaks it (budget or cycle without straddling): kept as is",
        }.get(pair.outcome, pair.outcome)
        by = (
            f"settled by <b>{html.escape(pair.settled_by)}</b>"
            if pair.settled_by
            else "<b>no test settles it</b>"
        )
        pieces = f"S = {html.escape(pair.piece)}, S' = {html.escape(pair.other)}"
        self.settled.value = f"<b>{pieces}:</b> {by} &rarr; {html.escape(outcome)}"
        rows = [(f"{TEST_QUESTIONS[t.name][0]}. {t.name}", t.passed) for t in pair.tests]
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

    def step_kind(self, step: int) -> str:
        """`piece_painted` for a step that paints a whole piece; "" for the trace's own kinds."""
        painted = step and self._shown[step].painting is not None and self.steps_mode == "polygon"
        return "piece_painted" if painted else ""

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the pair and the test that settled it, the swap,
        the split, or the piece painted."""
        if step == 0:
            count = len(self._shown[1].pending) if len(self._shown) > 1 else 0
            return (
                f"The start: {count} polygons, to be sorted on their farthest depth (zmax) and "
                "checked pair by pair before each is painted."
            )
        event, shown, before = self.steps[step - 1], self._shown[step], self._shown[step - 1]
        if shown.painting is not None:
            return _painted_sentence(
                shown, self._painting, len(shown.pending), self.steps_mode == "pixel"
            )
        if event.kind == "polygons_sorted":
            order = ", ".join(p.label for p in event.pieces)
            again = "re-sorted with the two new pieces" if step > 1 else "sorted"
            return f"The list is {again} on zmax, farthest first: {order}."
        if event.kind == "pair_tested":
            records = {r.label: r for r in shown.pending}
            following = self.steps[step] if step < len(self.steps) else None
            return _pair_sentence(event, records[event.piece], records[event.other], following)
        if event.kind == "pieces_swapped":
            return (
                f"Piece {event.moved} must be painted before {event.piece}, so it moves to the far "
                f"end of the list: {', '.join(event.order)}."
            )
        if event.kind == "polygon_split":
            reason = {"cycle": "to break a cycle", "interpenetration": "where they interpenetrate"}
            return (
                f"Piece {event.piece} is cut by the plane of polygon {event.by} "
                f"{reason.get(event.why, f'({event.why})')}: {event.front.label} lies in front "
                f"of it and {event.behind.label} behind."
            )
        left = ", ".join(r.label for r in before.pending) or "none"
        return (
            f"The order is settled: {len(event.pieces)} pieces, far to near "
            f"{', '.join(p.label for p in event.pieces)}; still to paint: {left}."
        )


def _test_name(name: str, s: str, other: str) -> str:
    number, question = TEST_QUESTIONS[name]
    return f"test {number} ({question.format(s=s, o=other)})"


def _pair_sentence(pair, s, other, following) -> str:
    """What a ``pair_tested`` event found, with the depths of S and S' (`PieceRecord`s)."""
    depths = (
        f"S = {s.label} (z {fmt(s.zmin, DIGITS)}..{fmt(s.zmax, DIGITS)}) and "
        f"S' = {other.label} (z {fmt(other.zmin, DIGITS)}..{fmt(other.zmax, DIGITS)})"
    )
    if pair.outcome == "no_overlap":
        return (
            f"{depths} do not overlap in z: S' is wholly nearer (minimax), so {s.label} may be "
            f"painted before {other.label}."
        )
    failed = [t.name for t in pair.tests[1:] if not t.passed]
    tried = f"test{'s' if len(failed) > 1 else ''} " + ", ".join(
        TEST_QUESTIONS[n][0] for n in failed
    )
    head = f"{depths} overlap in z"
    if pair.outcome == "order_ok":
        fails = f"; {tried} fail{'' if len(failed) > 1 else 's'}" if failed else ""
        return (
            f"{head}{fails}; {_test_name(pair.settled_by, s.label, other.label)} passes, so "
            f"{s.label} may be painted before {other.label}."
        )
    if pair.outcome == "swap":
        return (
            f"{head}; {tried} fail, but {_test_name(pair.settled_by, s.label, other.label)} "
            f"passes, so {other.label} must be painted first."
        )
    if pair.outcome == "split":
        cut = (
            f": {following.piece} is cut by the plane of polygon {following.by} next"
            if following is not None and following.kind == "polygon_split"
            else ""
        )
        why = "they form a cycle" if pair.settled_by else "they interpenetrate"
        return f"{head}; {tried} fail, so no order works ({why}) and a piece is split{cut}."
    return (
        f"{head}; {tried} fail and no split can break the tie (the split budget is spent, or no "
        "piece straddles another's plane), so the pair is kept in list order."
    )


def _painted_sentence(shown: _Shown, painting: _Painting, left: int, by_sample: bool) -> str:
    """The piece painted at a step: all its samples, or (`by_sample`) the latest one."""
    piece = shown.painting
    written = painting.written(piece.label)
    events = painting.of_piece.get(piece.label, [])
    if not events:
        return f"Piece {piece.label} (polygon {piece.polygon}) covers no sample: painting it changes nothing."
    if by_sample:
        e = events[shown.samples - 1]
        under = f"over polygon {e.previous}" if e.previous >= 0 else "on the background"
        done = "paints" if e.painted else "skips (it lies outside the piece's cuts)"
        return (
            f"Piece {piece.label} {done} sample ({e.x}, {e.y}) at z = {fmt(e.z, DIGITS)}, "
            f"{under}: sample {shown.samples} of {len(events)}."
        )
    over = sorted({e.previous for e in written if e.previous not in (-1, piece.polygon)})
    covers = ", ".join(f"polygon {p}" for p in over)
    why = (
        "is the last piece in the list"
        if not left
        else "passed every test against the pieces still in the list"
    )
    return (
        f"Piece {piece.label} (polygon {piece.polygon}) {why}, so it is painted: "
        f"{len(written)} samples"
        + (f", over {covers} where they overlap" if over else "")
        + (f"; {left} piece{'s' if left != 1 else ''} left." if left else ".")
    )


class PainterView:
    """The painter's sorted list and the image painted polygon by polygon, beside the z-buffer's.

    Parameters
    ----------
    trace : Trace
        ``polygons_sorted`` and ``pixel_painted`` events of a traced ``solve("painter", ...)``.
    result, zbuffer_result
        The painter's result and the z-buffer's on the same polygons.
    key : str
        The key the list was sorted on (as `Painter`).
    note : str, optional
    steps : {"polygon", "pixel"}
        After the sort, one polygon painted per step ("polygon"), or one sample ("pixel").

    Attributes
    ----------
    steps : Trace
        ``polygons_sorted``, then per step the last ``pixel_painted`` event of
        the polygon painted (pixel steps: each ``pixel_painted`` event).
    widget : ipywidgets.VBox
    list_table : ipywidgets.HTML
        The sorted list (the key, zmin, zmax); the polygon being painted highlighted.
    painted_image : matplotlib AxesImage
    """

    def __init__(
        self,
        trace: Trace,
        result,
        zbuffer_result,
        *,
        key: str,
        note: str = "",
        steps: str = "polygon",
    ) -> None:
        self.steps_mode = _check_steps(steps)
        self.result, self.zbuffer_result, self.key = result, zbuffer_result, key
        height, width = result.polygon.shape
        self._painting = _Painting(trace, (height, width))
        sort = [e for e in trace if e.kind == "polygons_sorted"]
        self._sorted = sort[0].pieces if sort else ()
        pixels = self._painting.events
        if self.steps_mode == "pixel":
            self._ends = list(range(1, len(pixels) + 1))
        else:  # the index after each piece's last sample
            self._ends = [
                k + 1
                for k, e in enumerate(pixels)
                if k + 1 == len(pixels) or pixels[k + 1].piece != e.piece
            ]
        self.steps = Trace(sort[:1] + [pixels[end - 1] for end in self._ends])
        titles = ("painted so far", f"painter's ({key})", "z-buffer (red: painter differs)")
        fig, (ax_painted, _, _), self.painted_image, wrong = _painting_figure(
            result, zbuffer_result, titles
        )
        self.current_outline = PolygonPatch(np.zeros((3, 2)), fill=False, ec="black", lw=2.5)
        self.current_marker = Rectangle((0, 0), 1, 1, fill=False, ec="black", lw=2, visible=False)
        ax_painted.add_patch(self.current_outline)
        ax_painted.add_patch(self.current_marker)
        fig.tight_layout()
        self.figure = fig
        self.list_table = widgets.HTML()
        self.summary = widgets.HTML(
            f"{int(wrong.sum())} samples differ from the z-buffer (outlined in red)"
        )
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox([self.note, self._canvas, self.summary, self.list_table])
        self.step = 0
        self.show(0)

    def painted(self, step: int) -> int:
        """How many ``pixel_painted`` events the first `step` steps have painted."""
        return self._ends[step - 2] if step >= 2 else 0

    def show(self, step: int) -> None:
        """Show the image after the first `step` steps and the polygon being painted."""
        self.step = int(step)
        count = self.painted(self.step)
        ids = self._painting.ids(self._painting.events[:count])
        self.painted_image.set_data(polygon_colors(ids))
        current = self._painting.events[count - 1] if count else None
        self.current_marker.set_visible(current is not None and self.steps_mode == "pixel")
        label = current.piece if current is not None else None
        record = next((r for r in self._sorted if r.label == label), None)
        self.current_outline.set_visible(record is not None)
        if current is not None:
            self.current_marker.set_xy((current.x, current.y))
        if record is not None:
            self.current_outline.set_xy(np.array([v[:2] for v in record.vertices]))
        rows = [
            (k + 1, r.label, r.polygon, sort_key(_piece(r), self.key), r.zmin, r.zmax)
            for k, r in enumerate(self._sorted)
        ]
        states = ["current" if r.label == label else "" for r in self._sorted]
        self.list_table.value = f"<b>sorted on {self.key}, farthest first</b>" + html_table(
            ("#", "piece", "polygon", f"key ({self.key})", "zmin", "zmax"), rows, states=states
        )
        refresh_figure(self.figure, self._canvas)

    def step_kind(self, step: int) -> str:
        """`polygon_painted` for a step that paints a whole polygon; "" for the trace's own kinds."""
        return "polygon_painted" if step > 1 and self.steps_mode == "polygon" else ""

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the sort, the polygon painted, or the sample."""
        count = len(self._sorted)
        if step == 0:
            return (
                f"The start: {count} polygons, to be sorted on {self.key} and painted far to "
                "near, each over whatever is already there, with no depth test."
            )
        if step == 1:
            keys = ", ".join(
                f"{r.label} ({fmt(sort_key(_piece(r), self.key), DIGITS)})" for r in self._sorted
            )
            return f"The polygons are sorted on {self.key}, farthest first: {keys}."
        event = self.steps[step - 1]
        if self.steps_mode == "pixel":
            under = f"over polygon {event.previous}" if event.previous >= 0 else "on the background"
            return (
                f"Polygon {event.polygon} paints sample ({event.x}, {event.y}) at z = "
                f"{fmt(event.z, DIGITS)}, {under}: the painter never compares depths."
            )
        written = self._painting.written(event.piece)
        rank = next(k for k, r in enumerate(self._sorted) if r.label == event.piece) + 1
        over = {}
        for e in written:
            if e.previous >= 0 and e.previous != e.polygon:
                over[e.previous] = over.get(e.previous, 0) + 1
        covers = ", ".join(f"{n} of polygon {p}" for p, n in sorted(over.items()))
        return (
            f"Polygon {event.polygon}, number {rank} of {count} in the list, is painted: "
            f"{len(written)} samples"
            + (f", covering {covers} painted before it" if over else ", none painted before")
            + "."
        )


def _piece(record):
    from ..visibility import Piece

    return Piece(record.polygon, record.label, np.array(record.vertices))


def depth_sort_stepper(
    polygons: ScreenPolygons, width: int, height: int, *, steps: str = "polygon", **options
) -> Stepper:
    """Solve `polygons` with depth sort, traced, and step through its decision with a `DepthSortView`.

    Parameters
    ----------
    polygons : ScreenPolygons
    width, height : int
    steps : {"polygon", "pixel"}
        A piece leaving the list is painted in one step, or one step per sample.
    **options
        Those of `scanviz.visibility.solve` (``sample``, ``subpixel_bits``, ...)
        and ``max_splits`` of `DepthSort`.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `DepthSortView`; one step per decision event and
        per piece painted.

    Examples
    --------
    >>> from scanviz.visibility.examples import interpenetrating
    >>> stepper = depth_sort_stepper(interpenetrating(), 16, 12)
    >>> stepper.slider.max, [e.kind for e in stepper.views[0].steps][-4:]
    (11, ['pair_tested', 'paint_order', 'pixel_painted', 'pixel_painted'])
    """
    from ..visibility.depth_sort import DepthSort

    _check_steps(steps)
    algorithm = DepthSort(max_splits=options.pop("max_splits", None))
    result, reference = solve_traced(algorithm, polygons, width, height, **options)
    view = DepthSortView(result.trace, result, reference, steps=steps)
    painted = "piece" if steps == "polygon" else "sample"
    title = f"depth sort: one pair, swap or split per step, then one {painted} painted per step"
    return stepper_of(view, title, "steps")


def painter_stepper(
    polygons: ScreenPolygons,
    width: int,
    height: int,
    key: str = "zmin",
    *,
    steps: str = "polygon",
    **options,
) -> Stepper:
    """Solve `polygons` with the painter's algorithm, traced, and watch it paint polygon by polygon.

    Parameters
    ----------
    polygons : ScreenPolygons
    width, height : int
    key : {"zmin", "zmax", "centroid"}
        The depth the list is sorted on (as `Painter`).
    steps : {"polygon", "pixel"}
        After the sort, one polygon painted per step, or one sample.
    **options
        Those of `scanviz.visibility.solve` (``sample``, ``subpixel_bits``, ...).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `PainterView`: the sort, then one polygon (or sample) per step.

    Examples
    --------
    >>> from scanviz.visibility.examples import long_behind_short
    >>> stepper = painter_stepper(long_behind_short(), 16, 12)
    >>> stepper.slider.max, stepper.views[0].summary.value
    (3, '20 samples differ from the z-buffer (outlined in red)')
    """
    _check_steps(steps)
    kinds = ["polygons_sorted", "pixel_painted"]
    result, reference = solve_traced(Painter(key=key), polygons, width, height, kinds, **options)
    view = PainterView(result.trace, result, reference, key=key, steps=steps)
    painted = "polygon" if steps == "polygon" else "sample"
    return stepper_of(view, f"painter's algorithm (sorted on {key}): one {painted} per step")

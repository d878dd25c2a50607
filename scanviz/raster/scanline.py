"""Polygon scan conversion with an edge table and an active edge table (reference, traced).

The algorithm of the CS184 scanline notes and the UMBC CMSC 435 slides:

1. Build the edge table (ET): every non-horizontal edge goes into bucket
   ceil(ymin) and stays active for sample rows ymin <= y < ymax
   (step ``edge_table_entry``).
2. For each sample row from the first bucket up: retire edges whose ymax has
   been passed, step the x of the others by dx/dy, add the edges of this
   row's bucket, re-sort the active edge table (AET) by x (step ``aet_update``).
3. Walk the AET left to right keeping a winding count; between consecutive
   crossings where the count says "inside", emit the span
   [ceil(x_in), ceil(x_out)) (step ``span_rule``).

The three steps come from the step table (`scanviz.steps`) and work on
textbook values in pixels, with sample rows at integer y: exact `Fraction`
coordinates, and in the AET an exact `Fraction` x stepped by an exact dx/dy,
so there is no drift at any edge length. The loop sets each entering edge's
first x from its integer crossing, x = q + r/den (quotient plus remainder), and
from then on the AET holds the x that ``aet_update`` returns, so a replaced
step shows its consequences in the trace. The textbook ``x += dx/dy`` in
float32 or float64 is there to show the drift: then the AET's x and dx/dy are
numpy floats of that type. Steps 2 and 3 are one walk, `scan_rows`, which
`scan_reference` and the interpolating walk of the traced z-buffer
(`scanviz.raster.interpolate.interpolate_rows`) both consume, so a replaced
step shows in both. This module is the readable reference;
`scanviz.raster.scan_compiled` is its compiled twin and produces the same spans.
"""

from __future__ import annotations

import math
import numbers
import operator
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from .. import steps
from ..limits import check_memory, current_memory_limit
from ..trace.display import RichDisplay
from ..trace.events import (
    AetEntry,
    AetSorted,
    EdgeRecord,
    EdgesActivated,
    EdgesRetired,
    EdgeTableBuilt,
    Span,
)
from ..trace.schema import shown
from .fixed import SnappedPolygon

FLOAT_X_LIMIT = 2.0**40  # float-mode crossings are clamped here before ceil (spans clip anyway)
LISTED_SPAN_BYTES = 160  # a span as a tuple of three Python ints in a list, with its array row


def _ceil_div(a: int, b: int) -> int:
    return -((-a) // b)


class ExactCrossing:
    """Where an edge crosses the current sample row: x = q + r/den pixels, 0 <= r < den."""

    def __init__(self, xl: int, yl: int, dx: int, dy: int, scale: int) -> None:
        self.xl, self.yl, self.dx, self.dy, self.scale = xl, yl, dx, dy, scale
        self.den = dy * scale
        self.q_step, r_step = divmod(dx, dy)  # dx/dy = q_step + r_step/dy pixels per row
        self.r_step = r_step * scale

    def start(self, row: int) -> None:
        """Jump to `row` directly (exact, so rows below the raster are never stepped through)."""
        self.q, self.r = divmod(
            self.xl * self.dy + self.dx * (row * self.scale - self.yl), self.den
        )

    def step(self) -> None:
        self.q += self.q_step
        self.r += self.r_step
        if self.r >= self.den:  # carry the remainder into the integer part
            self.r -= self.den
            self.q += 1

    def ceil(self) -> int:
        return self.q + (self.r > 0)

    def exact(self) -> Fraction:
        return self.q + Fraction(self.r, self.den)

    def dxdy(self) -> Fraction:
        return Fraction(self.dx, self.dy)


class FloatCrossing:
    """The textbook crossing in float32/float64: x on its first row and dx/dy, both of `dtype`.

    The AET then advances x by ``x += dx/dy`` in that type (``aet_update``), so it drifts.
    """

    def __init__(self, xl: int, yl: int, dx: int, dy: int, scale: int, dtype: type) -> None:
        self.dtype = dtype
        self.xl = dtype(xl / scale)
        self.yl = dtype(yl / scale)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            slope = (dtype((xl + dx) / scale) - self.xl) / (dtype((yl + dy) / scale) - self.yl)
        # Where dy rounds to 0 or dx/dy overflows, the textbook code breaks; keep x at the lower end.
        self.slope = slope if np.isfinite(slope) else dtype(0)

    def start(self, row: int) -> None:
        with np.errstate(over="ignore"):
            self.x = self.xl + self.slope * (self.dtype(row) - self.yl)

    def ceil(self) -> int:
        # x may have overflowed to +-inf; any value beyond +-2**40 lies far off every raster.
        return math.ceil(min(max(float(self.x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT))

    def exact(self) -> None:
        return None

    def dxdy(self) -> None:
        return None


@dataclass
class ActiveEdge:
    """An edge of the edge table, with its crossing of the current row once active."""

    edge: int
    contour: int
    lower: tuple[int, int]
    upper: tuple[int, int]
    winding: int
    bucket: int
    row_end: int
    crossing: ExactCrossing | FloatCrossing | None  # None for horizontal edges

    @property
    def crosses_rows(self) -> bool:
        """Whether the edge crosses a sample row; if not, it is kept for topology only."""
        return self.crossing is not None and self.bucket < self.row_end


@dataclass
class ScanStats(RichDisplay):
    """What one scan conversion did."""

    edges: int = 0
    kept_for_topology: int = 0
    rows_scanned: int = 0
    spans: int = 0
    swaps: int = 0
    max_active: int = 0
    path: str = "reference"


class EdgeEntry(NamedTuple):
    """An edge-table entry as `edge_table_entry` returns it, in pixels (sample rows at integer y).

    The edge is active for the sample rows ``bucket <= y < row_end``; `winding`
    is +1 for an edge that runs downward in contour order, -1 for an upward one.
    """

    lower: tuple[Fraction, Fraction]
    upper: tuple[Fraction, Fraction]
    winding: int
    bucket: int
    row_end: int


@steps.step(
    "edge_table_entry",
    takes="start, end: one polygon edge's endpoints in contour order, (x, y) pairs of Fractions "
    "in pixels (sample rows at integer y)",
    returns="EdgeEntry(lower, upper, winding, bucket, row_end): the endpoints ordered by y, winding "
    "+1 for a downward edge and -1 for an upward one, bucket = ceil(ymin), row_end = ceil(ymax) "
    "(active for rows bucket <= y < row_end); None for a horizontal edge",
)
def edge_table_entry(start: tuple, end: tuple) -> EdgeEntry | None:
    """The edge-table entry of the polygon edge from `start` to `end`; None if it is horizontal.

    Examples
    --------
    >>> from fractions import Fraction
    >>> edge_table_entry((4, 1), (Fraction(5, 2), 6))
    EdgeEntry(lower=(4, 1), upper=(Fraction(5, 2), 6), winding=-1, bucket=1, row_end=6)
    >>> edge_table_entry((0, 2), (3, 2)) is None
    True
    """
    if start[1] == end[1]:
        return None  # crosses no sample row: kept for topology only
    lower, upper = (start, end) if start[1] < end[1] else (end, start)
    winding = 1 if end[1] < start[1] else -1  # downward edges enter a CCW polygon from the left
    return EdgeEntry(lower, upper, winding, math.ceil(lower[1]), math.ceil(upper[1]))


def build_edge_table(snapped: SnappedPolygon, arithmetic: str = "exact") -> list[ActiveEdge]:
    """All edges of `snapped`, in contour order, with rows and crossings set up.

    Each edge's entry comes from the step ``edge_table_entry``, in pixels; it is
    turned back into grid units exactly, and the crossing is set up from it.
    """
    scale = snapped.scale
    entry_of = steps.get("edge_table_entry")
    edges = []
    for contour in range(len(snapped.offsets) - 1):
        first, stop = int(snapped.offsets[contour]), int(snapped.offsets[contour + 1])
        ends = [_vertex(snapped.units[i], scale) for i in range(first, stop)]
        for start, end in zip(ends, ends[1:] + ends[:1], strict=True):
            entry = entry_of(start[1], end[1])
            edges.append(_table_edge(len(edges), contour, start, end, entry, scale, arithmetic))
    return edges


def _vertex(row: np.ndarray, scale: int) -> tuple[tuple[int, int], tuple[Fraction, Fraction]]:
    """A vertex in grid units and in pixels, (x, y) each."""
    x, y = int(row[0]), int(row[1])
    return (x, y), (Fraction(x, scale), Fraction(y, scale))


def _table_edge(edge, contour, start, end, entry, scale: int, arithmetic: str) -> ActiveEdge:
    """The ET edge of an ``edge_table_entry`` result, in grid units, with its crossing.

    `start` and `end` are the edge's endpoints as (units, pixels) pairs.
    """
    if entry is None:  # not in the table (a horizontal edge): kept for topology only
        a, b = start[0], end[0]
        lower, upper = (a, b) if (a[1], a[0]) <= (b[1], b[0]) else (b, a)
        row = _ceil_div(lower[1], scale)
        return ActiveEdge(edge, contour, lower, upper, 0, row, row, None)
    lower, upper, winding, bucket, row_end = _entry_in_units(entry, (start, end), scale)
    crossing = _crossing(lower, upper, scale, arithmetic)
    return ActiveEdge(edge, contour, lower, upper, winding, bucket, row_end, crossing)


def _entry_in_units(entry: object, ends: tuple, scale: int) -> tuple:
    """An ``edge_table_entry`` result as (lower, upper, winding, bucket, row_end), in grid units."""
    try:
        lower, upper, winding, bucket, row_end = entry  # type: ignore[misc]
    except (TypeError, ValueError):
        raise TypeError(
            "edge_table_entry must return None or (lower, upper, winding, bucket, row_end); "
            f"got {shown(entry)}"
        ) from None
    return (
        _grid_point("lower", lower, ends, scale),
        _grid_point("upper", upper, ends, scale),
        _entry_int("winding", winding),
        _entry_int("bucket", bucket),
        _entry_int("row_end", row_end),
    )


def _grid_point(name: str, point: object, ends: tuple, scale: int) -> tuple[int, int]:
    """An entry's end, (x, y) in pixels, in grid units: it must lie on the sub-pixel grid."""
    for units, pixels in ends:
        if type(point) is tuple and point == pixels:  # one of the edge's endpoints, as given
            return units
    try:
        x, y = point  # type: ignore[misc]
    except (TypeError, ValueError):
        raise TypeError(
            f"edge_table_entry's {name!r} must be an (x, y) point; got {shown(point)}"
        ) from None
    return _grid_units(name, x, scale), _grid_units(name, y, scale)


def _grid_units(name: str, value: object, scale: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"edge_table_entry's {name!r} must hold numbers; got {shown(value)}")
    try:
        exact = value if isinstance(value, numbers.Rational) else Fraction(float(value))
    except (ValueError, OverflowError):  # nan, inf
        raise ValueError(
            f"edge_table_entry's {name!r} must be finite; got {shown(value)}"
        ) from None
    units, rest = divmod(int(exact.numerator) * scale, int(exact.denominator))
    if rest:
        raise ValueError(
            f"edge_table_entry's {name!r} has {shown(value)}, off the 1/{scale} pixel grid "
            "of the vertices: the entry's ends must be the edge's endpoints"
        )
    return units


def _entry_int(name: str, value: object) -> int:
    if type(value) is int:
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"edge_table_entry's {name!r} must be an int; got {shown(value)}")
    return int(value)


def _crossing(lower, upper, scale: int, arithmetic: str) -> ExactCrossing | FloatCrossing | None:
    """The crossing of the line through two grid points, from the lower one; None if horizontal."""
    if upper[1] < lower[1]:
        lower, upper = upper, lower  # an entry with its ends swapped: the same line
    dx, dy = upper[0] - lower[0], upper[1] - lower[1]
    if dy == 0:
        return None
    if arithmetic == "exact":
        return ExactCrossing(lower[0], lower[1], dx, dy, scale)
    return FloatCrossing(lower[0], lower[1], dx, dy, scale, getattr(np, arithmetic))


def _crossing_value(crossing: ExactCrossing | FloatCrossing) -> Fraction | np.floating:
    """The crossing's x on its current row as the AET holds it: a Fraction, or a numpy float."""
    exact = crossing.exact()
    return crossing.x if exact is None else exact


def _x_values(x: object, offset: Fraction) -> tuple[float, Fraction | None]:
    """(x, x_exact) of an AET x in the caller's frame: exact for ints and Fractions, else a float."""
    if isinstance(x, int | Fraction) and not isinstance(x, bool):
        exact = x + offset
        return float(exact), exact
    return float(x) + float(offset), None  # type: ignore[arg-type]


def _slope_values(crossing) -> tuple[float, Fraction | None]:
    """(dxdy, dxdy_exact) of a crossing."""
    exact = crossing.dxdy()
    return (float(crossing.slope), None) if exact is None else (_saturating_float(exact), exact)


def _saturating_float(value: Fraction) -> float:
    """`value` as a float, +-inf past the float range (dx/dy of near-horizontal subnormal edges)."""
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def _edge_record(edge: ActiveEdge, snapped: SnappedPolygon) -> EdgeRecord:
    px = snapped.to_pixels
    if edge.crosses_rows:
        edge.crossing.start(edge.bucket)
        x, x_exact = _x_values(_crossing_value(edge.crossing), px(0))
        dxdy, dxdy_exact = _slope_values(edge.crossing)
    else:  # crosses no sample row: no crossing to show, so show the lower endpoint
        x, x_exact, dxdy, dxdy_exact = float(px(edge.lower[0])), px(edge.lower[0]), 0.0, None
        if edge.crossing is not None:
            dxdy, dxdy_exact = _slope_values(edge.crossing)
    return EdgeRecord(
        edge=edge.edge,
        contour=edge.contour,
        x0=float(px(edge.lower[0])),
        y0=float(px(edge.lower[1])),
        x1=float(px(edge.upper[0])),
        y1=float(px(edge.upper[1])),
        ymin=float(px(edge.lower[1])),
        ymax=float(px(edge.upper[1])),
        bucket=edge.bucket,
        row_end=edge.row_end,
        x=x,
        x_exact=x_exact,
        dxdy=dxdy,
        dxdy_exact=dxdy_exact,
        winding=edge.winding,
        horizontal=edge.crossing is None,
        kept_for_topology=not edge.crosses_rows,
    )


def _aet_entry(edge: ActiveEdge, snapped: SnappedPolygon, x: object) -> AetEntry:
    """The trace record of an active edge whose AET x is `x`."""
    x_float, x_exact = _x_values(x, snapped.to_pixels(0))
    dxdy, dxdy_exact = _slope_values(edge.crossing)
    return AetEntry(
        edge=edge.edge,
        x=x_float,
        x_exact=x_exact,
        dxdy=dxdy,
        dxdy_exact=dxdy_exact,
        ymax=float(snapped.to_pixels(edge.upper[1])),
        winding=edge.winding,
    )


def _insertion_sort(items: list, before) -> int:
    """Sort `items` in place, as the notes' bubble sort does; return the swaps made.

    ``before(a, b)`` says whether `a` goes strictly before `b`. Ties keep their order.
    """
    swaps = 0
    for i in range(1, len(items)):
        j = i
        while j > 0 and before(items[j], items[j - 1]):
            items[j - 1], items[j] = items[j], items[j - 1]
            swaps += 1
            j -= 1
    return swaps


@dataclass(slots=True)
class AetItem:
    """One active edge as `aet_update` sees it, in pixels (sample rows at integer y).

    `x` is where the edge crosses the current row and `dxdy` its x step per
    row: exact Fractions (numpy floats in float arithmetic). The edge is active
    for the rows ``bucket <= y < row_end``; `winding` is +1 or -1.
    """

    edge: int
    x: Fraction | float
    dxdy: Fraction | float
    bucket: int
    row_end: int
    winding: int


@steps.step(
    "aet_update",
    takes="active: the AET after the previous row, sorted (AetItems: edge, x, dxdy, bucket, "
    "row_end, winding; x a Fraction, or a float in float arithmetic); y: the row; entering: this "
    "row's ET bucket as AetItems with x at row y (and any entering edge an earlier call left out)",
    returns="(retired, active): the items with row_end <= y, and row y's AET: the others with "
    "x + dxdy, then the entering items with bucket <= y, insertion-sorted by x (ties keep that "
    "order)",
)
def aet_update(active: list[AetItem], y: int, entering: list[AetItem]) -> tuple[list, list]:
    """Row `y`'s active edge table from the previous row's: retire, step x, add, re-sort.

    Examples
    --------
    >>> from fractions import Fraction
    >>> left, right = AetItem(0, Fraction(4), Fraction(-3, 10), 1, 11, 1), AetItem(3, 12, 0, 1, 8, -1)
    >>> retired, aet = aet_update([left, right], 2, [])
    >>> retired, [(e.edge, e.x) for e in aet]
    ([], [(0, Fraction(37, 10)), (3, 12)])
    """
    retired = [e for e in active if e.row_end <= y]
    aet = [
        AetItem(e.edge, e.x + e.dxdy, e.dxdy, e.bucket, e.row_end, e.winding)
        for e in active
        if e.row_end > y
    ]
    aet += [e for e in entering if e.bucket <= y]
    _insertion_sort(aet, lambda a, b: a.x < b.x)  # the AET is nearly sorted; ties keep their order
    return retired, aet


def _entering_item(edge: ActiveEdge, y: int) -> AetItem:
    """An edge entering the AET on row `y`, its x where it crosses that row (the crossing setup)."""
    crossing = edge.crossing
    crossing.start(y)
    exact_slope = crossing.dxdy()
    dxdy = crossing.slope if exact_slope is None else exact_slope
    return AetItem(
        edge.edge, _crossing_value(crossing), dxdy, edge.bucket, edge.row_end, edge.winding
    )


def _update_aet(aet: list[AetItem], y: int, waiting: list[ActiveEdge], edges, arithmetic: str):
    """Row y's AET from the step ``aet_update``: (retired, entered, aet, swaps).

    `retired` and `entered` are the ET edges it retired and took in; `swaps` is
    the number of exchanges an insertion sort makes from the order before the
    update (the previous AET, then the entering edges) to the order it returned.
    A replaced step's result is checked first.
    """
    offered = [_entering_item(edge, y) for edge in waiting]
    before = [item.edge for item in aet + offered]
    count = len(aet)
    update = steps.get("aet_update")
    if arithmetic == "exact":
        returned = update(aet, y, offered)
    else:
        with np.errstate(over="ignore"):  # float x may overflow to +-inf, as the textbook's does
            returned = update(aet, y, offered)
    if update is aet_update:
        retired, updated = [item.edge for item in returned[0]], returned[1]
    else:
        retired, updated = _checked_update(returned, before[:count], before[count:], y)
    after = [item.edge for item in updated]
    swaps = 0 if after == before else _exchanges(before, after)
    taken = set(after) if offered else set()
    entered = [edges[edge] for edge in before[count:] if edge in taken]
    return [edges[edge] for edge in retired], entered, updated, swaps


def _exchanges(before: list[int], after: list[int]) -> int:
    """The swaps an insertion sort makes to put the ids of `after` from their order in `before`."""
    order = {edge: k for k, edge in enumerate(before)}
    return _insertion_sort([order[edge] for edge in after], operator.lt)


def _checked_update(returned: object, previous: list[int], entering: list[int], y: int):
    """What ``aet_update`` returned, as (retired edge ids, AET items), or a clear error."""
    try:
        retired, updated = returned  # type: ignore[misc]
        retired, updated = list(retired), list(updated)
    except (TypeError, ValueError):
        raise TypeError(
            "aet_update must return (retired, active): two lists of AET items; "
            f"got {shown(returned)}"
        ) from None
    retired_ids = [_item_edge(item, y) for item in retired]
    seen: set[int] = set()
    known = set(previous) | set(entering)
    for edge in retired_ids + [_item_edge(item, y, with_x=True) for item in updated]:
        if edge not in known:
            raise ValueError(
                f"aet_update returned edge {edge} on row {y}; it is neither active nor entering"
            )
        if edge in seen:
            raise ValueError(f"aet_update returned edge {edge} twice on row {y}")
        seen.add(edge)
    dropped = [edge for edge in previous if edge not in seen]
    if dropped:
        raise ValueError(
            f"aet_update dropped edge {dropped[0]} on row {y}: an active edge leaves the AET "
            "only by being retired"
        )
    return retired_ids, updated


def _item_edge(item: object, y: int, with_x: bool = False) -> int:
    """The edge id of an AET item ``aet_update`` returned (whose x must be a number if `with_x`)."""
    edge = getattr(item, "edge", None)
    if isinstance(edge, bool) or not isinstance(edge, int):
        raise TypeError(
            f"aet_update must return AET items (with .edge and .x) on row {y}; got {shown(item)}"
        )
    x = getattr(item, "x", None)
    if with_x and (isinstance(x, bool) or not isinstance(x, numbers.Real)):
        raise TypeError(f"aet_update returned edge {edge} with x = {shown(x)} on row {y}")
    return edge


@steps.step(
    "span_rule",
    takes="crossings: one row's AET as (x, winding) pairs sorted by x (x a Fraction, or a float "
    "in float arithmetic); rule: 'nonzero' or 'evenodd'",
    returns="the row's inside runs as (x_start, x_end, winding) with x_start = ceil(x_in), "
    "x_end = ceil(x_out) (half-open), winding the count inside; in order, unclipped",
)
def span_rule(crossings: list[tuple], rule: str) -> list[tuple[int, int, int]]:
    """The spans between consecutive crossings where the winding count says "inside"."""
    spans = []
    winding = 0
    for (x_in, step), (x_out, _) in zip(crossings, crossings[1:], strict=False):
        winding += step
        inside = winding % 2 if rule == "evenodd" else winding != 0
        if inside and math.ceil(x_in) < math.ceil(x_out):
            spans.append((math.ceil(x_in), math.ceil(x_out), winding))
    return spans


def _span_x(x: object) -> Fraction | float:
    """An AET x as `span_rule` takes it (floats clamped where they lie far off the raster)."""
    if isinstance(x, int | Fraction):
        return x
    return min(max(float(x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT)  # type: ignore[arg-type]


def _row_spans(crossings: list[tuple], rule: str, width: int) -> list[tuple[int, int, int]]:
    """(x_start, x_end, winding) of the inside runs of one row's (x, winding), clipped to the raster."""
    clipped = [
        (max(start, 0), min(end, width), winding)
        for start, end, winding in steps.get("span_rule")(
            [(_span_x(x), winding) for x, winding in crossings], rule
        )
    ]
    return [span for span in clipped if span[0] < span[1]]


class EdgeTable(NamedTuple):
    """The edge table: every edge (in contour order), and those that cross raster rows by first row."""

    edges: list[ActiveEdge]
    buckets: dict[int, list[ActiveEdge]]


def bucketed_edge_table(
    snapped: SnappedPolygon, height: int, arithmetic: str = "exact", trace=None, polygon: int = 0
) -> EdgeTable:
    """The edge table (traced as ``edge_table_built``) and its edges by the first raster row they cross.

    Rows below the raster are never scanned: an edge starting there enters at row 0.
    """
    edges = build_edge_table(snapped, arithmetic)
    if trace is not None and trace.wants("edge_table_built", polygon=polygon):
        trace.emit(EdgeTableBuilt(polygon, tuple(_edge_record(e, snapped) for e in edges)))
    buckets: dict[int, list[ActiveEdge]] = {}
    for edge in edges:
        row_start = max(edge.bucket, 0)
        if edge.crossing is not None and row_start < min(edge.row_end, height):
            buckets.setdefault(row_start, []).append(edge)
    return EdgeTable(edges, buckets)


class ScanRow(NamedTuple):
    """One scanned row of the ET/AET walk.

    `retired` and `entering` are the ET edges ``aet_update`` retired and took
    in on row `y`; `aet` is the row's AET as it returned it (the reference
    sorts it by x), and `swaps` the exchanges its re-sort made; `spans` are
    ``span_rule``'s (x_start, x_end, winding), clipped to the raster.
    """

    y: int
    retired: list[ActiveEdge]
    entering: list[ActiveEdge]
    aet: list[AetItem]
    swaps: int
    spans: list[tuple[int, int, int]]


def scan_rows(
    snapped: SnappedPolygon,
    table: EdgeTable,
    width: int,
    height: int,
    *,
    rule: str = "nonzero",
    arithmetic: str = "exact",
    trace=None,
    polygon: int = 0,
) -> Iterator[ScanRow]:
    """Walk the edge table up the raster: yield a `ScanRow` per scanned row, emitting its events.

    Steps 2 and 3 of the module docstring, from the step table: ``aet_update``
    makes each row's AET and ``span_rule`` cuts its spans, so a replaced step
    drives every traced loop built on this walk. `table` is
    `bucketed_edge_table`'s, built with the same `arithmetic`. Rows from the
    first bucket up are scanned until the AET empties; empty rows are skipped.

    Examples
    --------
    >>> from scanviz import Polygon
    >>> from scanviz.raster.fixed import snap
    >>> square = snap(Polygon([(0, 0), (2, 0), (2, 2), (0, 2)]))
    >>> for row in scan_rows(square, bucketed_edge_table(square, 4), 4, 4):
    ...     print(row.y, [item.x for item in row.aet], row.spans)
    0 [Fraction(0, 1), Fraction(2, 1)] [(0, 2, 1)]
    1 [Fraction(0, 1), Fraction(2, 1)] [(0, 2, 1)]
    2 [] []
    """
    edges, buckets = table
    aet: list[AetItem] = []
    waiting: list[ActiveEdge] = []  # entering edges `aet_update` did not take (none by default)
    pending = sorted(buckets)
    y = pending[0] if pending else height
    while y < height and (aet or waiting or pending):
        if not aet and not waiting and pending[0] > y:
            y = pending[0]  # skip empty rows
            if y >= height:
                break
        if pending and pending[0] == y:
            waiting += buckets[pending.pop(0)]
        retired, entering, aet, swaps = _update_aet(aet, y, waiting, edges, arithmetic)
        if waiting:
            gone = {e.edge for e in entering + retired}  # out of the ET: into the AET or retired
            waiting = [e for e in waiting if e.edge not in gone]
        # An empty AET has no spans: the span rule is not asked (one call per aet_sorted event).
        spans = _row_spans([(i.x, edges[i.edge].winding) for i in aet], rule, width) if aet else []
        row = ScanRow(y, retired, entering, aet, swaps, spans)
        if trace is not None:
            _emit_row(trace, polygon, row, edges, snapped)
        yield row
        y += 1


def scan_reference(
    snapped: SnappedPolygon,
    width: int,
    height: int,
    *,
    rule: str = "nonzero",
    arithmetic: str = "exact",
    trace=None,
    polygon: int = 0,
) -> tuple[np.ndarray, ScanStats]:
    """Scan-convert a snapped polygon with ET/AET, emitting events to `trace`.

    Returns the spans as a (K, 3) ndarray of int64 rows (y, x_start, x_end),
    sorted by y then x, clipped to the raster, and the `ScanStats`.
    Raises `scanviz.limits.ResourceLimitError` as soon as the spans found
    outgrow the memory limit.
    """
    most_spans = current_memory_limit() // LISTED_SPAN_BYTES
    table = bucketed_edge_table(snapped, height, arithmetic, trace, polygon)
    edges = table.edges
    stats = ScanStats(edges=len(edges), kept_for_topology=sum(not e.crosses_rows for e in edges))
    spans: list[tuple[int, int, int]] = []
    walk = scan_rows(
        snapped,
        table,
        width,
        height,
        rule=rule,
        arithmetic=arithmetic,
        trace=trace,
        polygon=polygon,
    )
    for row in walk:
        stats.rows_scanned += 1
        stats.swaps += row.swaps
        stats.max_active = max(stats.max_active, len(row.aet))
        spans.extend((row.y, start, end) for start, end, _ in row.spans)
        if len(spans) > most_spans:
            check_memory(
                len(spans) * LISTED_SPAN_BYTES,
                f"scan conversion (reference): {len(spans)} spans by row {row.y} of {height}",
            )
    stats.spans = len(spans)
    return np.array(spans, dtype=np.int64).reshape(-1, 3), stats


def _emit_row(trace, polygon: int, row: ScanRow, edges: list[ActiveEdge], snapped) -> None:
    """The events of one scanned row, the AET entries showing the x that ``aet_update`` returned."""
    y = row.y
    if row.retired and trace.wants("edges_retired", polygon=polygon, y=y):
        trace.emit(EdgesRetired(polygon, y, tuple(e.edge for e in row.retired)))
    if row.entering and trace.wants("edges_activated", polygon=polygon, y=y):
        trace.emit(EdgesActivated(polygon, y, tuple(e.edge for e in row.entering)))
    if row.aet and trace.wants("aet_sorted", polygon=polygon, y=y):
        entries = tuple(_aet_entry(edges[item.edge], snapped, item.x) for item in row.aet)
        trace.emit(AetSorted(polygon, y, entries, row.swaps))
    if trace.wants("span", polygon=polygon, y=y):
        for start, end, winding in row.spans:
            trace.emit(Span(polygon, y, start, end, winding))

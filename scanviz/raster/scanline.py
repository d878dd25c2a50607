"""Polygon scan conversion with an edge table and an active edge table (reference, traced).

The algorithm of Foley, van Dam, Feiner & Hughes (1990, §3.6, "Filling
Polygons"), as the UMBC CMSC 435 slides and the CS184 scanline notes teach it:

1. Build the edge table (ET): every non-horizontal edge goes into bucket
   ceil(ymin) and stays active for the sample rows ymin <= y < ymax
   (step ``edge_table_entry``).
2. For each sample row from the first bucket up: retire the edges whose ymax
   has been passed, step the x of the others by dx/dy, add the edges of this
   row's bucket and re-sort the active edge table (AET) by x (step ``aet_update``).
3. Walk the AET left to right keeping a winding count; between consecutive
   crossings where the count says "inside", fill the span
   [ceil(x_in), ceil(x_out)) (step ``span_rule``).

The steps work in pixels with sample rows at integer y: exact `Fraction`
coordinates, and in the AET an exact x stepped by an exact dx/dy, so nothing
drifts at any edge length. The textbook ``x += dx/dy`` in float32 or float64
is there to show the drift (``arithmetic=``): the AET's x and dx/dy are then
numpy floats. One `Edge` record holds each edge: its ends on the integer grid
of `scanviz.raster.fixed`, its rows, its winding and its `crossing` of the
current row; the trace's records are built from it when an event is emitted.

The three steps come from the step table (`scanviz.steps`), so a replaced step
drives the real loop and its consequences show in the trace. The loop trusts
its steps: a replaced one is called through its check
(`scanviz.exercises.scan_checks`). Steps 2 and 3 are one walk, `scan_rows`,
which `scan_reference`, the traced z-buffer (`scanviz.raster.interpolate`) and
the mask buffer (`scanviz.abuffer.masks`) consume. `scanviz.raster.scan_compiled`
is the compiled twin: the same spans.
"""

from __future__ import annotations

import math
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
from .fixed import SnappedPolygon
from .sorting import inversions

FLOAT_X_LIMIT = 2.0**40  # float-mode crossings are clamped here before ceil (spans clip anyway)
LISTED_SPAN_BYTES = 160  # a span as a tuple of three Python ints in a list, with its array row

# --- the edge record -----------------------------------------------------------------------


@dataclass
class Edge:
    """One polygon edge: its ends in grid units, its rows, its winding, its crossing.

    The edge is active for the sample rows ``bucket <= y < row_end``; `winding`
    is +1 for an edge that runs downward in contour order, -1 for an upward one.
    `crossing` follows the edge from row to row; it is None for a horizontal
    edge, which crosses no sample row and is kept for topology only.
    """

    edge: int
    contour: int
    lower: tuple[int, int]
    upper: tuple[int, int]
    winding: int
    bucket: int
    row_end: int
    crossing: ExactCrossing | FloatCrossing | None

    @property
    def crosses_rows(self) -> bool:
        """Whether the edge crosses a sample row; if not, it is kept for topology only."""
        return self.crossing is not None and self.bucket < self.row_end


class ExactCrossing:
    """Where an edge crosses the current row, exactly: x = q + r/den pixels, 0 <= r < den.

    Built from the lower end (xl, yl) and the rise (dx, dy), in grid units of
    `scale`; the AET takes `x` and `dxdy` as Fractions. Derivation:
    docs/scan-conversion.md, "Exact crossings".
    """

    def __init__(self, xl: int, yl: int, dx: int, dy: int, scale: int) -> None:
        self.xl, self.yl, self.dx, self.dy, self.scale = xl, yl, dx, dy, scale
        self.den = dy * scale

    def start(self, row: int) -> None:
        """Jump to `row` directly (exact, so rows below the raster are never stepped through)."""
        self.q, self.r = divmod(
            self.xl * self.dy + self.dx * (row * self.scale - self.yl), self.den
        )

    @property
    def x(self) -> Fraction:
        return self.q + Fraction(self.r, self.den)

    @property
    def dxdy(self) -> Fraction:
        return Fraction(self.dx, self.dy)


class FloatCrossing:
    """The textbook crossing in float32/float64: `x` on the current row and `dxdy`, of `dtype`."""

    def __init__(self, xl: int, yl: int, dx: int, dy: int, scale: int, dtype: type) -> None:
        self.dtype = dtype
        self.xl = dtype(xl / scale)
        self.yl = dtype(yl / scale)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            dxdy = (dtype((xl + dx) / scale) - self.xl) / (dtype((yl + dy) / scale) - self.yl)
        # Where dy rounds to 0 or dx/dy overflows, the textbook code breaks; keep x at the lower end.
        self.dxdy = dxdy if np.isfinite(dxdy) else dtype(0)

    def start(self, row: int) -> None:
        with np.errstate(over="ignore"):
            self.x = self.xl + self.dxdy * (self.dtype(row) - self.yl)


# --- step 1: the edge table ----------------------------------------------------------------


class EdgeEntry(NamedTuple):
    """An edge-table entry as `edge_table_entry` returns it, in pixels (sample rows at integer y)."""

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


def build_edge_table(snapped: SnappedPolygon, arithmetic: str = "exact") -> list[Edge]:
    """Every edge of `snapped` in contour order, its rows from the step ``edge_table_entry``."""
    scale = snapped.scale
    entry_of = steps.get("edge_table_entry", scale=scale)  # a replaced one's ends: on the grid
    edges: list[Edge] = []
    for contour in range(len(snapped.offsets) - 1):
        units = snapped.units[snapped.offsets[contour] : snapped.offsets[contour + 1]]
        corners = [(int(x), int(y)) for x, y in units]
        for start, end in zip(corners, corners[1:] + corners[:1], strict=True):
            entry = entry_of(_pixels(start, scale), _pixels(end, scale))
            edges.append(_edge(len(edges), contour, start, end, entry, scale, arithmetic))
    return edges


def _edge(index, contour, start, end, entry: EdgeEntry | None, scale, arithmetic) -> Edge:
    """The `Edge` from `start` to `end` (grid units) with the rows and winding of its `entry`."""
    if entry is None:  # horizontal: kept for topology, in no bucket
        lower, upper = sorted((start, end), key=lambda point: (point[1], point[0]))
        row = -(-lower[1] // scale)  # ceil
        return Edge(index, contour, lower, upper, 0, row, row, None)
    lower, upper = _units(entry.lower, scale), _units(entry.upper, scale)
    crossing = _crossing(lower, upper, scale, arithmetic)
    return Edge(index, contour, lower, upper, entry.winding, entry.bucket, entry.row_end, crossing)


def _pixels(point: tuple[int, int], scale: int) -> tuple[Fraction, Fraction]:
    return Fraction(point[0], scale), Fraction(point[1], scale)


def _units(point: tuple, scale: int) -> tuple[int, int]:
    return int(point[0] * scale), int(point[1] * scale)


def _crossing(lower, upper, scale: int, arithmetic: str) -> ExactCrossing | FloatCrossing | None:
    """The crossing of the line through two grid points, from the lower one; None if horizontal."""
    (xl, yl), (xu, yu) = sorted((lower, upper), key=lambda point: point[1])
    if yu == yl:
        return None
    if arithmetic == "exact":
        return ExactCrossing(xl, yl, xu - xl, yu - yl, scale)
    return FloatCrossing(xl, yl, xu - xl, yu - yl, scale, getattr(np, arithmetic))


class EdgeTable(NamedTuple):
    """The edge table: every edge (in contour order), and those that cross raster rows by first row."""

    edges: list[Edge]
    buckets: dict[int, list[Edge]]


def bucketed_edge_table(
    snapped: SnappedPolygon, height: int, arithmetic: str = "exact", trace=None, polygon: int = 0
) -> EdgeTable:
    """The edge table (traced as ``edge_table_built``) and its edges by the first raster row they cross.

    Rows below the raster are never scanned: an edge starting there enters at row 0.
    """
    edges = build_edge_table(snapped, arithmetic)
    if trace is not None and trace.wants("edge_table_built", polygon=polygon):
        trace.emit(EdgeTableBuilt(polygon, tuple(_edge_record(e, snapped) for e in edges)))
    buckets: dict[int, list[Edge]] = {}
    for edge in edges:
        row_start = max(edge.bucket, 0)
        if edge.crossing is not None and row_start < min(edge.row_end, height):
            buckets.setdefault(row_start, []).append(edge)
    return EdgeTable(edges, buckets)


# --- step 2: the active edge table, row by row ---------------------------------------------


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
    # The insertion sort's order (stable: ties keep their order) in O(n log n) even when the
    # rows scramble it: `_insertion_sort` would take O(n^2) on a star of many crossing spikes.
    aet.sort(key=_x_of)
    return retired, aet


def _x_of(item: AetItem) -> Fraction | float:
    return item.x


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


# --- step 3: the spans ---------------------------------------------------------------------


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


# --- the walk: steps 2 and 3, row by row ---------------------------------------------------


class ScanRow(NamedTuple):
    """One scanned row of the ET/AET walk.

    `retired` and `entering` are the edges ``aet_update`` retired and took in
    on row `y`; `aet` is the row's AET as it returned it (the reference sorts
    it by x), and `swaps` the exchanges from the previous order (the previous
    AET, then the entering edges in edge order) to it; `spans` are
    ``span_rule``'s (x_start, x_end, winding), clipped to the raster.
    """

    y: int
    retired: list[Edge]
    entering: list[Edge]
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
    first bucket up are scanned while an edge is active or due; others are skipped.

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
    update = steps.get("aet_update")
    rows = sorted(buckets, reverse=True)  # the buckets' rows, the next one last
    aet: list[AetItem] = []
    due_until = 0  # below this row, an edge of a bucket reached is due (active, or to be taken in)
    y = rows[-1] if rows else height
    while y < height:
        bucket = buckets[rows.pop()] if rows and rows[-1] == y else []
        due_until = max([due_until] + [edge.row_end for edge in bucket])
        previous = [item.edge for item in aet]
        with np.errstate(over="ignore"):  # float x may overflow to +-inf, as the textbook's does
            retired, aet = update(aet, y, [_aet_item(edge, y) for edge in bucket])
        entering = sorted({item.edge for item in aet}.difference(previous))
        swaps = _exchanges(previous + entering, [item.edge for item in aet])
        # An empty AET has no spans: the span rule is not asked (one call per aet_sorted event).
        spans = _row_spans(aet, edges, rule, width) if aet else []
        retired_edges = [edges[item.edge] for item in retired]
        row = ScanRow(y, retired_edges, [edges[e] for e in entering], aet, swaps, spans)
        if trace is not None:
            _emit_row(trace, polygon, row, edges, snapped)
        yield row
        y += 1
        if not aet and y >= due_until:  # no edge active or due: skip to the next bucket
            y = rows[-1] if rows else height


def _aet_item(edge: Edge, y: int) -> AetItem:
    """An edge entering the AET on row `y`, with x where it crosses that row."""
    crossing = edge.crossing
    crossing.start(y)
    return AetItem(edge.edge, crossing.x, crossing.dxdy, edge.bucket, edge.row_end, edge.winding)


def _exchanges(before: list[int], after: list[int]) -> int:
    """The swaps an insertion sort makes to put the ids of `after` from their order in `before`.

    Each swap exchanges one out-of-order pair, so they are the inversions of
    the positions, counted by merge sort in O(n log n) (the insertion sort
    itself would take O(n^2) when the order is scrambled).

    >>> _exchanges([0, 1, 2, 3], [3, 1, 0, 2]), _insertion_sort([3, 1, 0, 2], lambda a, b: a < b)
    (4, 4)
    """
    if after == before:
        return 0
    order = {edge: k for k, edge in enumerate(before)}
    positions = np.array([order[edge] for edge in after], np.int64)
    return int(inversions(positions, np.empty_like(positions)))


def _row_spans(aet: list[AetItem], edges: list[Edge], rule: str, width: int) -> list[tuple]:
    """``span_rule``'s (x_start, x_end, winding) of one row's AET, clipped to the raster."""
    crossings = [(_span_x(item.x), edges[item.edge].winding) for item in aet]
    spans = steps.get("span_rule")(crossings, rule)
    clipped = [(max(start, 0), min(end, width), winding) for start, end, winding in spans]
    return [span for span in clipped if span[0] < span[1]]


def _span_x(x: Fraction | float) -> Fraction | float:
    """An exact x as it is; a float x clamped where it lies far off the raster (it may be +-inf)."""
    if isinstance(x, int | Fraction):
        return x
    return min(max(float(x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT)


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
    options = {"rule": rule, "arithmetic": arithmetic, "trace": trace, "polygon": polygon}
    for row in scan_rows(snapped, table, width, height, **options):
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


# --- trace records, built from the edges at emit time --------------------------------------


def _emit_row(trace, polygon: int, row: ScanRow, edges: list[Edge], snapped) -> None:
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


def _edge_record(edge: Edge, snapped: SnappedPolygon) -> EdgeRecord:
    """The trace record of an ET edge, x where it crosses its bucket row (else its lower end)."""
    (x0, y0), (x1, y1) = [[snapped.to_pixels(u) for u in end] for end in (edge.lower, edge.upper)]
    crossing = edge.crossing
    if edge.crosses_rows:
        crossing.start(edge.bucket)
        x, x_exact = _float_and_exact(crossing.x, snapped.to_pixels(0))
    else:  # crosses no sample row: no crossing to show, so show the lower end
        x, x_exact = float(x0), x0
    dxdy, dxdy_exact = (0.0, None) if crossing is None else _float_and_exact(crossing.dxdy)
    return EdgeRecord(
        edge=edge.edge,
        contour=edge.contour,
        x0=float(x0),
        y0=float(y0),
        x1=float(x1),
        y1=float(y1),
        ymin=float(y0),
        ymax=float(y1),
        bucket=edge.bucket,
        row_end=edge.row_end,
        x=x,
        x_exact=x_exact,
        dxdy=dxdy,
        dxdy_exact=dxdy_exact,
        winding=edge.winding,
        horizontal=crossing is None,
        kept_for_topology=not edge.crosses_rows,
    )


def _aet_entry(edge: Edge, snapped: SnappedPolygon, x: object) -> AetEntry:
    """The trace record of an active edge whose AET x is `x`."""
    x_float, x_exact = _float_and_exact(x, snapped.to_pixels(0))
    dxdy, dxdy_exact = _float_and_exact(edge.crossing.dxdy)
    return AetEntry(
        edge=edge.edge,
        x=x_float,
        x_exact=x_exact,
        dxdy=dxdy,
        dxdy_exact=dxdy_exact,
        ymax=float(snapped.to_pixels(edge.upper[1])),
        winding=edge.winding,
    )


def _float_and_exact(value, offset: Fraction | None = None) -> tuple[float, Fraction | None]:
    """(float, exact) of an x or dx/dy plus `offset` (into the caller's frame); exact is None
    for a float x. Past the float range the float is +-inf (dx/dy of a near-horizontal edge)."""
    if isinstance(value, int | Fraction) and not isinstance(value, bool):
        exact = value if offset is None else value + offset
        try:
            return float(exact), exact
        except OverflowError:
            return (math.inf if exact > 0 else -math.inf), exact
    return (float(value) if offset is None else float(value) + float(offset)), None

"""Polygon scan conversion with an edge table and an active edge table (reference, traced).

The algorithm of the CS184 scanline notes and the UMBC CMSC 435 slides:

1. Build the edge table (ET): every non-horizontal edge goes into bucket
   ceil(ymin) and stays active for sample rows ymin <= y < ymax.
2. For each sample row from the first bucket up: retire edges whose ymax has
   been passed, step the x of the others by dx/dy, add the edges of this
   row's bucket, re-sort the active edge table (AET) by x.
3. Walk the AET left to right keeping a winding count; between consecutive
   crossings where the count says "inside", emit the span
   [ceil(x_in), ceil(x_out)).

Crossings are exact by default: x = q + r/den with integers (an incremental
DDA, quotient plus remainder), so there is no drift at any edge length. The
textbook ``x += dx/dy`` in float32 or float64 is there to show the drift.
This module is the readable reference; `scanviz.raster.kernels` is its
compiled twin and produces the same spans.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from .. import steps
from ..limits import check_memory, current_memory_limit
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

    def before(self, other: ExactCrossing) -> bool:
        return self.q < other.q or (self.q == other.q and self.r * other.den < other.r * self.den)

    def exact(self) -> Fraction:
        return self.q + Fraction(self.r, self.den)

    def dxdy(self) -> Fraction:
        return Fraction(self.dx, self.dy)


class FloatCrossing:
    """The textbook crossing: x in float32/float64, advanced by ``x += dx/dy`` (drifts)."""

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

    def step(self) -> None:
        with np.errstate(over="ignore"):
            self.x = self.x + self.slope

    def ceil(self) -> int:
        # x may have overflowed to +-inf; any value beyond +-2**40 lies far off every raster.
        return math.ceil(min(max(float(self.x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT))

    def before(self, other: FloatCrossing) -> bool:
        return self.x < other.x

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


@dataclass
class ScanStats:
    """What one scan conversion did."""

    edges: int = 0
    kept_for_topology: int = 0
    rows_scanned: int = 0
    spans: int = 0
    swaps: int = 0
    max_active: int = 0
    path: str = "reference"


def build_edge_table(snapped: SnappedPolygon, arithmetic: str = "exact") -> list[ActiveEdge]:
    """All edges of `snapped`, in contour order, with rows and crossings set up."""
    units, scale = snapped.units, snapped.scale
    edges = []
    for contour in range(len(snapped.offsets) - 1):
        first, stop = int(snapped.offsets[contour]), int(snapped.offsets[contour + 1])
        for i in range(first, stop):
            a = (int(units[i, 0]), int(units[i, 1]))
            b = (
                int(units[i + 1 if i + 1 < stop else first, 0]),
                int(units[i + 1 if i + 1 < stop else first, 1]),
            )
            lower, upper = (a, b) if (a[1], a[0]) <= (b[1], b[0]) else (b, a)
            dx, dy = upper[0] - lower[0], upper[1] - lower[1]
            # Downward edges enter a counter-clockwise polygon from the left: winding +1.
            winding = 0 if dy == 0 else (1 if b[1] < a[1] else -1)
            if dy == 0:
                crossing = None
            elif arithmetic == "exact":
                crossing = ExactCrossing(lower[0], lower[1], dx, dy, scale)
            else:
                crossing = FloatCrossing(lower[0], lower[1], dx, dy, scale, getattr(np, arithmetic))
            row_start, row_end = _ceil_div(lower[1], scale), _ceil_div(upper[1], scale)
            edges.append(
                ActiveEdge(len(edges), contour, lower, upper, winding, row_start, row_end, crossing)
            )
    return edges


def _crossing_values(
    crossing, offset: Fraction
) -> tuple[float, Fraction | None, float, Fraction | None]:
    """(x, x_exact, dxdy, dxdy_exact) of a crossing, x in the caller's frame."""
    exact = crossing.exact()
    if exact is None:
        return float(crossing.x) + float(offset), None, *_slope_values(crossing)
    return float(exact + offset), exact + offset, *_slope_values(crossing)


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
    if edge.bucket < edge.row_end:
        edge.crossing.start(edge.bucket)
        x, x_exact, dxdy, dxdy_exact = _crossing_values(edge.crossing, px(0))
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
        kept_for_topology=edge.bucket >= edge.row_end,
    )


def _aet_entry(edge: ActiveEdge, snapped: SnappedPolygon) -> AetEntry:
    x, x_exact, dxdy, dxdy_exact = _crossing_values(edge.crossing, snapped.to_pixels(0))
    ymax = float(snapped.to_pixels(edge.upper[1]))
    return AetEntry(
        edge=edge.edge,
        x=x,
        x_exact=x_exact,
        dxdy=dxdy,
        dxdy_exact=dxdy_exact,
        ymax=ymax,
        winding=edge.winding,
    )


def _insertion_sort(active: list[ActiveEdge]) -> int:
    """Re-sort the AET by x in place, as the notes' bubble sort does; return the swaps made."""
    swaps = 0
    for i in range(1, len(active)):
        j = i
        while j > 0 and active[j].crossing.before(active[j - 1].crossing):
            active[j - 1], active[j] = active[j], active[j - 1]
            swaps += 1
            j -= 1
    return swaps


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


def _crossing_x(crossing: ExactCrossing | FloatCrossing) -> Fraction | float:
    """The crossing's x as `span_rule` takes it (floats clamped where they lie far off the raster)."""
    exact = crossing.exact()
    if exact is not None:
        return exact
    return min(max(float(crossing.x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT)


def _row_spans(active: list[ActiveEdge], rule: str, width: int) -> list[tuple[int, int, int]]:
    """(x_start, x_end, winding) of the inside runs of one sorted row, clipped to the raster."""
    crossings = [(_crossing_x(e.crossing), e.winding) for e in active]
    clipped = [
        (max(start, 0), min(end, width), winding)
        for start, end, winding in steps.get("span_rule")(crossings, rule)
    ]
    return [span for span in clipped if span[0] < span[1]]


def bucketed_edge_table(
    snapped: SnappedPolygon, height: int, arithmetic: str = "exact", trace=None, polygon: int = 0
) -> tuple[list[ActiveEdge], dict[int, list[ActiveEdge]]]:
    """The edge table (traced as ``edge_table_built``) and its edges by the first raster row they cross.

    Rows below the raster are never scanned: an edge starting there enters at row 0.
    """
    edges = build_edge_table(snapped, arithmetic)
    if trace is not None and trace.wants("edge_table_built", polygon=polygon):
        trace.emit(EdgeTableBuilt(polygon, tuple(_edge_record(e, snapped) for e in edges)))
    buckets: dict[int, list[ActiveEdge]] = {}
    for edge in edges:
        row_start = max(edge.bucket, 0)
        if row_start < min(edge.row_end, height):
            buckets.setdefault(row_start, []).append(edge)
    return edges, buckets


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
    edges, buckets = bucketed_edge_table(snapped, height, arithmetic, trace, polygon)
    stats = ScanStats(edges=len(edges), kept_for_topology=sum(e.bucket >= e.row_end for e in edges))
    spans: list[tuple[int, int, int]] = []
    active: list[ActiveEdge] = []
    pending = sorted(buckets)
    y = pending[0] if pending else height
    while y < height and (active or pending):
        if not active and pending[0] > y:
            y = pending[0]  # skip empty rows
            if y >= height:
                break
        retired = [e for e in active if e.row_end <= y]
        active = [e for e in active if e.row_end > y]
        for edge in active:
            edge.crossing.step()
        entering = buckets.get(y, [])
        if pending and pending[0] == y:
            pending.pop(0)
        for edge in entering:
            edge.crossing.start(y)
        active.extend(entering)
        swaps = _insertion_sort(active)
        stats.rows_scanned += 1
        stats.swaps += swaps
        stats.max_active = max(stats.max_active, len(active))
        row_spans = _row_spans(active, rule, width)
        spans.extend((y, start, end) for start, end, _ in row_spans)
        if len(spans) > most_spans:
            check_memory(
                len(spans) * LISTED_SPAN_BYTES,
                f"scan conversion (reference): {len(spans)} spans by row {y} of {height}",
            )
        if trace is not None:
            _emit_row(trace, polygon, y, retired, entering, active, swaps, row_spans, snapped)
        y += 1
    stats.spans = len(spans)
    return np.array(spans, dtype=np.int64).reshape(-1, 3), stats


def _emit_row(trace, polygon, y, retired, entering, active, swaps, row_spans, snapped) -> None:
    if retired and trace.wants("edges_retired", polygon=polygon, y=y):
        trace.emit(EdgesRetired(polygon, y, tuple(e.edge for e in retired)))
    if entering and trace.wants("edges_activated", polygon=polygon, y=y):
        trace.emit(EdgesActivated(polygon, y, tuple(e.edge for e in entering)))
    if active and trace.wants("aet_sorted", polygon=polygon, y=y):
        trace.emit(AetSorted(polygon, y, tuple(_aet_entry(e, snapped) for e in active), swaps))
    if trace.wants("span", polygon=polygon, y=y):
        for start, end, winding in row_spans:
            trace.emit(Span(polygon, y, start, end, winding))

"""Scanline visibility (Watkins; the UMBC slides): one scanline at a time, span by span.

As on the slides:

1. Sort the polygons into the sorted surface table (SST) by their first
   sample row (step ``surface_table_built``).
2. y = the first nonempty scanline; the active surface table (AST) = SST[y].
3. Until the AST and the SST are empty: remove the exhausted polygons, add
   the entering ones, update their edges' x intercepts and sort them on x
   (``active_surfaces``); the crossings cut the row into spans, sorted on x;
   in each span decide the visible surface by depth (``visible_span``) and
   record it; y += 1.

Spans are exact: each polygon keeps the z-buffer's edge table and exact
crossings (`scanviz.raster.scanline.bucketed_edge_table`), so on each row it
covers [ceil(x_in), ceil(x_out)) exactly as the z-buffer draws it, and a span
runs between consecutive distinct crossing ceilings, clipped to the raster.
Over a span the same surfaces cover every sample.

The visible surface of a sample is the surface of least (depth, index)
there, the depth from its plane (`Surfaces.depth`, the z-buffer's plane):
ties go to the lower index, as the z-buffer keeps the earlier polygon. When
two surfaces' planes cross inside a span (interpenetration) the visible one
changes there, and the span is split at that sample into pieces, each with
its own visible surface.

Coherence: a span with the same ends and the same surfaces as a span of the
row below reuses its visible surface, but only while the depth certificate of
`scanline_kernels` proves it still nearest at every sample (planar depth
differences change linearly from row to row), so coherence never changes a
pixel. Untraced, the compiled kernel `scanline_kernels.scanline_ids` runs;
it decides exactly as this reference. The derivations: docs/visibility-scanline.md.

    >>> from scanviz.visibility import examples, solve
    >>> result = solve("scanline", examples.slides_painter(), 16, 12)
    >>> result.polygon[5, 6], result.algorithm.spans_decided > 0
    (np.int64(2), True)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .. import steps
from ..raster.fixed import SnappedPolygon
from ..raster.scanline import ScanRow, bucketed_edge_table, scan_rows
from ..trace.display import RichDisplay
from ..trace.events import ActiveSurfaces, SurfaceRecord, SurfaceTableBuilt, VisibleSpan
from . import scanline_compiled
from .interface import Decision, Visibility, register
from .screen_polygons import Surfaces


@dataclass
class ScanlineStats(RichDisplay):
    """What the scanline algorithm did.

    rows: scanlines with a nonempty AST; spans: spans on them (background
    ones included, ``background_spans`` of them); spans_decided: spans of two
    or more surfaces decided by depth; spans_reused: such spans whose decision
    came from the row below (coherence); spans_split: decided spans cut by an
    interpenetration into pieces; max_active: the largest AST.
    """

    rows: int = 0
    spans: int = 0
    background_spans: int = 0
    spans_decided: int = 0
    spans_reused: int = 0
    spans_split: int = 0
    max_active: int = 0
    path: str = "reference"

    @property
    def reused_fraction(self) -> float:
        """Spans reused over spans needing a decision (0 if none did)."""
        needing = self.spans_decided + self.spans_reused
        return self.spans_reused / needing if needing else 0.0


@dataclass(frozen=True)
class ScanlineDetail:
    """The SST as arrays, and the planes the depths come from (for widgets and tests).

    ``y_start``, ``y_end`` (P,) int64: polygon p's rows [y_start, y_end) (0, 0
    when it takes no part); ``planes`` (P, 5): `Surfaces.planes`.
    """

    y_start: np.ndarray
    y_end: np.ndarray
    planes: np.ndarray


@register
@dataclass(frozen=True)
class Scanline(Visibility):
    """Scanline visibility (option ``coherence``: reuse the row below's decisions when certain)."""

    name: ClassVar[str] = "scanline"
    coherence: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.coherence, bool | np.bool_):
            raise TypeError(f"'coherence' must be a bool; got {self.coherence!r}")

    def decide(self, surfaces: Surfaces, tracer) -> Decision:
        # As painting: a replaced step (the edge table's) runs in the reference only.
        if tracer is None and surfaces.units.dtype == np.int64 and not steps.replaced():
            ids, counts, y_start, y_end = scanline_compiled.scanline_ids(
                surfaces.units, surfaces.polygons.offsets, surfaces.drawn, surfaces.planes,
                surfaces.scale, surfaces.width, surfaces.height, bool(self.coherence),
            )  # fmt: skip
            stats = ScanlineStats(*(int(c) for c in counts), path="compiled")
        else:
            ids, stats, y_start, y_end = scanline_reference(surfaces, bool(self.coherence), tracer)
        return Decision(stats, target=ids, detail=ScanlineDetail(y_start, y_end, surfaces.planes))

    def depth_slack(self, surfaces: Surfaces, stats: object) -> float:
        """The tolerance: each sample shows the nearest by its plane's depth, which differs from
        the z-buffer's interpolated depth only by rounding (far below the tolerance)."""
        return surfaces.tolerance


class ActiveSurface:
    """A polygon in the AST: its edges crossing the current row, from the ET/AET walk (`scan_rows`).

    The walk takes its AET update from the step table, as the scan converter
    and the z-buffer do; only the crossings are used here (the spans are cut
    across all the active surfaces by `row_spans`).
    """

    def __init__(self, surfaces: Surfaces, p: int) -> None:
        first, stop = surfaces.polygons.offsets[p], surfaces.polygons.offsets[p + 1]
        snapped = SnappedPolygon(
            surfaces.units[first:stop], np.array([0, stop - first]), surfaces.bits, surfaces.sample
        )
        self.polygon = p
        table = bucketed_edge_table(snapped, surfaces.height)
        rows = [(row, e.row_end) for row, edges in table[1].items() for e in edges]
        self.y_start = min((row for row, _ in rows), default=0)  # rows [y_start, y_end)
        self.y_end = min(max((end for _, end in rows), default=0), surfaces.height)
        self.rows = scan_rows(snapped, table, surfaces.width, surfaces.height)
        self.row: ScanRow | None = None
        self.y = self.y_start

    def update(self, y: int) -> None:
        """Row y: the walk's row y (edges past their last row retired, the others stepped)."""
        self.y = y
        while self.row is None or self.row.y < y:
            self.row = next(self.rows, ScanRow(y + 1, [], [], [], 0, []))

    def crossings(self, width: int) -> list[tuple[int, int]]:
        """(ceil(x) clipped to [0, width], winding) of each edge on the current row."""
        if self.row is None or self.row.y != self.y:
            return []
        return [(min(max(math.ceil(item.x), 0), width), item.winding) for item in self.row.aet]


def row_spans(active: list[ActiveSurface], width: int) -> list[tuple[int, int, tuple[int, ...]]]:
    """The row's spans (x_start, x_end, surfaces over them), sorted on x, background included.

    A span ends at each distinct crossing ceiling; a polygon covers it where
    its winding number, summed over its crossings left of the span, is nonzero.
    """
    crossings = sorted((x, s.polygon, w) for s in active for x, w in s.crossings(width))
    windings = {s.polygon: 0 for s in active}
    spans, start, i = [], 0, 0
    while start < width:
        end = crossings[i][0] if i < len(crossings) else width
        if end > start:
            spans.append((start, end, tuple(p for p in sorted(windings) if windings[p])))
            start = end
        while i < len(crossings) and crossings[i][0] == end:
            windings[crossings[i][1]] += crossings[i][2]
            i += 1
    return spans


def nearest(surfaces: Surfaces, over: tuple[int, ...], x: int, y: int) -> int:
    """The surface of least (depth, index) at sample (x, y): the z-buffer's winner."""
    return min(over, key=lambda p: (surfaces.depth(p, x, y), p))


def pieces(surfaces: Surfaces, over, start: int, end: int, y: int) -> list[tuple[int, int, int]]:
    """(x_start, x_end, visible) runs of span [start, end): a new run where the nearest changes."""
    runs: list[list[int]] = []
    for x in range(start, end):
        visible = nearest(surfaces, over, x, y)
        if runs and runs[-1][2] == visible:
            runs[-1][1] = x + 1
        else:
            runs.append([x, x + 1, visible])
    return [tuple(run) for run in runs]


def crossing_x(surfaces: Surfaces, before: int, after: int, x: int, y: int) -> float:
    """Where `after` overtakes `before` between samples x - 1 and x (the planes' crossing)."""
    gap_before = surfaces.depth(after, x - 1, y) - surfaces.depth(before, x - 1, y)
    gap_after = surfaces.depth(after, x, y) - surfaces.depth(before, x, y)
    if gap_before == gap_after:  # parallel planes (a tie settled by index): the sample itself
        return float(x)
    return float(x - 1 + gap_before / (gap_before - gap_after))


def certificate(surfaces: Surfaces, over, w: int, start: int, end: int, y: int):
    """(slack, rate) proving w nearest on samples [start, end) of row y (slack > 0), as compiled."""
    last = end - 1
    near = surfaces.depth(w, start, y), surfaces.depth(w, last, y)
    error = _error(surfaces, w, start, y), _error(surfaces, w, last, y)
    slack, rate = np.inf, 0.0
    for s in over:
        if s != w:
            pair = scanline_compiled.pair_slack(
                near[0], near[1], surfaces.depth(s, start, y), surfaces.depth(s, last, y),
                error[0] + _error(surfaces, s, start, y), error[1] + _error(surfaces, s, last, y),
            )  # fmt: skip
            slack = min(slack, pair)
            rate = max(
                rate, scanline_compiled.pair_rate(surfaces.planes[w, 4], surfaces.planes[s, 4])
            )
    return slack, rate


def _error(surfaces: Surfaces, p: int, x: int, y: int) -> float:
    return scanline_compiled.depth_error(*surfaces.planes[p], x, y)


@dataclass
class _Decided:
    """A span kept for the row above: its ends, surfaces, visible one and certificate."""

    over: tuple[int, ...]
    visible: int
    row: int
    slack: float
    rate: float


def scanline_reference(surfaces: Surfaces, coherence: bool, tracer=None):
    """The traced scanline algorithm: (ids (H, W) int64, ScanlineStats, y_start, y_end)."""
    width, height = surfaces.width, surfaces.height
    ids = np.full((height, width), -1, np.int64)
    stats = ScanlineStats()
    drawn = (ActiveSurface(surfaces, p) for p in np.flatnonzero(surfaces.drawn).tolist())
    table = sorted((s for s in drawn if s.y_start < s.y_end), key=lambda s: (s.y_start, s.polygon))
    y_start, y_end = np.zeros(surfaces.count, np.int64), np.zeros(surfaces.count, np.int64)
    for s in table:
        y_start[s.polygon], y_end[s.polygon] = s.y_start, s.y_end
    if tracer is not None and tracer.wants("surface_table_built"):
        records = (SurfaceRecord(s.polygon, s.y_start, s.y_end) for s in table)
        tracer.emit(SurfaceTableBuilt(tuple(records)))
    pending, active, exhausted = list(table), [], []
    below: dict[tuple[int, int], _Decided] = {}  # the previous row's spans, if it was y - 1
    y = table[0].y_start if table else height
    while y < height and (active or pending):
        if not active and pending[0].y_start > y:
            y, below = pending[0].y_start, {}  # skip empty rows (coherence needs the row below)
        exhausted += [s.polygon for s in active if s.y_end <= y]
        active = [s for s in active if s.y_end > y]
        entered = []
        while pending and pending[0].y_start == y:
            entered.append(pending.pop(0))
        active += entered
        if not active:
            continue  # the last polygons were exhausted: on to the next entering one, if any
        for s in active:
            s.update(y)
        active.sort(key=lambda s: (min(x for x, _ in s.crossings(width)), s.polygon))
        stats.rows += 1
        stats.max_active = max(stats.max_active, len(active))
        if tracer is not None and tracer.wants("active_surfaces", y=y):
            entering, now = tuple(s.polygon for s in entered), tuple(s.polygon for s in active)
            tracer.emit(ActiveSurfaces(y, entering, tuple(exhausted), now))
        exhausted = []
        decided: dict[tuple[int, int], _Decided] = {}
        for start, end, over in row_spans(active, width):
            stats.spans += 1
            kept = _span(surfaces, ids, stats, y, start, end, over, below, coherence, tracer)
            if kept is not None:
                decided[start, end] = kept
        below = decided
        y += 1
    return ids, stats, y_start, y_end


def _span(surfaces, ids, stats, y, start, end, over, below, coherence, tracer):
    """Decide span [start, end) of row y over surfaces `over`; return it if the row above may reuse it."""
    if not over:
        stats.background_spans += 1
        _emit_span(surfaces, tracer, y, start, end, over, -1, False, None)
        return None
    if len(over) == 1:
        ids[y, start:end] = over[0]
        _emit_span(surfaces, tracer, y, start, end, over, over[0], False, None)
        return None
    earlier = below.get((start, end)) if coherence else None
    if (
        earlier is not None
        and earlier.over == over
        and scanline_compiled.still_certain(earlier.slack, earlier.rate, y - earlier.row)
    ):
        stats.spans_reused += 1
        ids[y, start:end] = earlier.visible
        _emit_span(surfaces, tracer, y, start, end, over, earlier.visible, True, None)
        return earlier
    stats.spans_decided += 1
    runs = pieces(surfaces, over, start, end, y)
    stats.spans_split += len(runs) > 1
    for k, (run_start, run_end, visible) in enumerate(runs):
        ids[y, run_start:run_end] = visible
        split_at = crossing_x(surfaces, runs[k - 1][2], visible, run_start, y) if k else None
        _emit_span(surfaces, tracer, y, run_start, run_end, over, visible, False, split_at)
    if coherence:
        slack, rate = certificate(surfaces, over, runs[0][2], start, end, y)
        if scanline_compiled.still_certain(slack, rate, 1):  # the row above may reuse it
            return _Decided(over, runs[0][2], y, slack, rate)
    return None


def _emit_span(surfaces, tracer, y, start, end, over, visible, reused, split_at) -> None:
    if tracer is not None and tracer.wants("visible_span", y=y):
        depths = tuple(float(surfaces.depth(p, start, y)) for p in over)
        tracer.emit(VisibleSpan(y, start, end, over, depths, visible, reused, split_at))

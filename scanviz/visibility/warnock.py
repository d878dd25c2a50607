"""Warnock's area subdivision: the taxonomy's "subdivide to simplify".

An area of the raster (a rectangle of samples, the whole raster first) is
decided at once when it is simple, and cut into four quadrants otherwise,
down to single samples (Warnock 1969; Foley et al. §15.7.1). Against the
area every polygon is disjoint, surrounding (it covers every sample),
intersecting or contained (it covers some). The area is

- ``"empty"`` when no polygon meets it: background;
- ``"pixel"`` when it is one sample (one pixel) that several polygons
  cover: the nearest at the sample, ties to the lower index (as the
  z-buffer keeps the earlier polygon);
- ``"surrounding"`` when a surrounding polygon is in front of every other
  polygon meeting it, over the whole area: that polygon (also when it is
  the only polygon there);
- ``"single"`` when exactly one polygon meets it, not surrounding: that
  polygon where it covers, background elsewhere;
- ``"subdivide"`` otherwise.

Exactness. "Meets" and "covers" are counted on the z-buffer's own spans of
each polygon (`scanviz.raster.api.scan_snapped`: the snapped integer
vertices and the ownership rule of DESIGN §2), relative to the area's
samples: a polygon over the area's pixel squares but over none of its
samples is disjoint. So the samples shown are exactly those the z-buffer
covers. "In front over the whole area" compares the planes (`Surfaces.planes`,
the z-buffer's) at the area's four extreme samples: the depth difference of
two planes is linear, so its least value over the area's samples is at one
of them. A surrounding polygon s is in front of q when z_q - z_s >
`Surfaces.tolerance` at all four; nearer calls are left to the sub-areas and
in the end to single samples. So every sample shows the first nearest
covering polygon by plane depth, as if decided alone.

Polygons hidden behind the nearest surrounding polygon over the whole area
(by more than the tolerance at the four corners) are not passed to the
sub-areas (``prune=True``, the default; ``prune=False`` passes every polygon
that meets the area, as the textbook does: the same image, more tests).

Traced, each area visited emits ``area_classified`` (level, extent, case,
visible polygon, the polygons meeting it), depth first: lower left, lower
right, upper left, upper right. The compiled walk
(`scanviz.visibility.warnock_compiled.subdivide`) visits the same areas.

    >>> from scanviz.trace import Recorder
    >>> from scanviz.visibility import ScreenPolygons, solve
    >>> scene = ScreenPolygons.from_polygons([
    ...     [(0, 0, 9), (8, 0, 9), (8, 8, 9), (0, 8, 9)],  # far, over everything
    ...     [(4, 4, 1), (8, 4, 1), (8, 8, 1), (4, 8, 1)],  # near, the upper right quadrant
    ...     [(0, 0, 5), (2, 0, 5), (2, 2, 5), (0, 2, 5)],  # between, in the lower left corner
    ... ])
    >>> result = solve("warnock", scene, 8, 8, trace=Recorder(kinds=["area_classified"]))
    >>> for e in result.trace:
    ...     print(e.level, (e.x_start, e.x_end, e.y_start, e.y_end), e.case, e.visible, e.polygons)
    0 (0, 8, 0, 8) subdivide -1 (0, 1, 2)
    1 (0, 4, 0, 4) subdivide -1 (0, 2)
    2 (0, 2, 0, 2) surrounding 2 (0, 2)
    2 (2, 4, 0, 2) surrounding 0 (0,)
    2 (0, 2, 2, 4) surrounding 0 (0,)
    2 (2, 4, 2, 4) surrounding 0 (0,)
    1 (4, 8, 0, 4) surrounding 0 (0,)
    1 (0, 4, 4, 8) surrounding 0 (0,)
    1 (4, 8, 4, 8) surrounding 1 (0, 1)
    >>> result.algorithm.areas, result.algorithm.surrounding, result.algorithm.depth
    (9, 7, 2)
    >>> result.polygon[::-1]
    array([[0, 0, 0, 0, 1, 1, 1, 1],
           [0, 0, 0, 0, 1, 1, 1, 1],
           [0, 0, 0, 0, 1, 1, 1, 1],
           [0, 0, 0, 0, 1, 1, 1, 1],
           [0, 0, 0, 0, 0, 0, 0, 0],
           [0, 0, 0, 0, 0, 0, 0, 0],
           [2, 2, 0, 0, 0, 0, 0, 0],
           [2, 2, 0, 0, 0, 0, 0, 0]])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .. import steps
from ..limits import check_memory, current_memory_limit
from ..raster.api import SPAN_BUFFER_BYTES, paint_spans, scan_snapped
from ..raster.fixed import SnappedPolygon
from ..raster.interpolate import plane_depth
from ..trace.display import RichDisplay
from ..trace.events import AreaClassified
from . import warnock_compiled
from .interface import Decision, Visibility, register
from .screen_polygons import Surfaces
from .warnock_compiled import AREA_FIELDS, PIXEL, SINGLE, SUBDIVIDE, SURROUNDING, area_case

CASES = ("empty", "surrounding", "single", "subdivide", "pixel")  # by code, as `area_case`


@dataclass
class WarnockStats(RichDisplay):
    """Areas visited, per case; ``depth`` the deepest level (the raster is level 0).

    ``pixel`` counts the one-sample areas decided by depth at their sample;
    ``tests`` the polygon-area classifications made.
    """

    areas: int = 0
    empty: int = 0
    surrounding: int = 0
    single: int = 0
    subdivide: int = 0
    pixel: int = 0
    depth: int = 0
    tests: int = 0
    path: str = "compiled"


@dataclass(frozen=True)
class Quadtree:
    """The areas Warnock visited, in visiting order (depth first), as (n,) int64 arrays.

    Area i is [x_start[i], x_end[i]) x [y_start[i], y_end[i]) at quadtree
    ``level[i]``, classified ``CASES[case[i]]``, showing ``visible[i]`` (-1:
    background or subdivided), child of area ``parent[i]`` (-1: the raster),
    met by ``meeting[i]`` of the polygons passed to it.
    """

    level: np.ndarray
    x_start: np.ndarray
    x_end: np.ndarray
    y_start: np.ndarray
    y_end: np.ndarray
    case: np.ndarray
    visible: np.ndarray
    parent: np.ndarray
    meeting: np.ndarray

    @classmethod
    def from_rows(cls, rows: np.ndarray) -> Quadtree:
        """From (n, AREA_FIELDS) rows (the compiled walk's), columns as `warnock_kernels`."""
        columns = np.asarray(rows, np.int64).reshape(-1, AREA_FIELDS).T.copy()
        for column in columns:
            column.setflags(write=False)
        return cls(*columns)

    def __len__(self) -> int:
        return len(self.level)

    def cases(self) -> list[str]:
        """The case name of each area."""
        return [CASES[c] for c in self.case.tolist()]

    def leaves(self) -> np.ndarray:
        """(n,) bool: the areas decided without subdividing."""
        return self.case != SUBDIVIDE

    def children(self, area: int) -> np.ndarray:
        """Indices of the areas area `area` was cut into (none for a leaf)."""
        return np.flatnonzero(self.parent == area)


def polygon_spans(surfaces: Surfaces) -> tuple[np.ndarray, np.ndarray]:
    """((K, 3) spans y, x_start, x_end, (P + 1,) start of each polygon's): the z-buffer's coverage.

    Each polygon's spans are `scan_snapped`'s (compiled in one call when it
    would run its kernel); polygons not drawn (edge-on, off the raster) get none.
    """
    if surfaces.units.dtype == np.int64 and not steps.replaced():
        spans, starts, refused = warnock_compiled.polygon_spans(
            surfaces.units, surfaces.polygons.offsets, surfaces.drawn, surfaces.scale,
            surfaces.width, surfaces.height, current_memory_limit() // SPAN_BUFFER_BYTES,
        )  # fmt: skip
        if refused:
            check_memory(refused * SPAN_BUFFER_BYTES, f"the spans of {surfaces.count} polygons")
        return spans, starts
    offsets = surfaces.polygons.offsets
    parts = []
    for p in range(surfaces.count):
        spans = np.zeros((0, 3), np.int64)
        if surfaces.drawn[p]:
            units = surfaces.units[offsets[p] : offsets[p + 1]]
            snapped = SnappedPolygon(
                units, np.array([0, len(units)]), surfaces.bits, surfaces.sample
            )
            spans = np.asarray(scan_snapped(snapped, surfaces.width, surfaces.height)[0], np.int64)
        parts.append(spans.reshape(-1, 3))
    starts = np.concatenate([[0], np.cumsum([len(part) for part in parts])]).astype(np.int64)
    return np.concatenate([np.zeros((0, 3), np.int64), *parts]), starts


def _corner_depths(planes: np.ndarray, x0: int, x1: int, y0: int, y1: int) -> np.ndarray:
    """(n, 4) depth of each plane at the area's extreme samples, lower left first."""
    xs, ys = np.array([x0, x1 - 1, x0, x1 - 1], float), np.array([y0, y0, y1 - 1, y1 - 1], float)
    return plane_depth(*(planes[:, k, None] for k in range(5)), xs, ys)


def _stats(quadtree: Quadtree, tests: int, path: str) -> WarnockStats:
    counts = np.bincount(quadtree.case, minlength=len(CASES))
    return WarnockStats(
        len(quadtree), *counts.tolist(), int(quadtree.level.max(initial=0)), tests, path
    )


@register
@dataclass(frozen=True)
class Warnock(Visibility):
    """Warnock's area subdivision (option ``prune``: drop polygons hidden behind a surrounding one)."""

    name: ClassVar[str] = "warnock"
    prune: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.prune, bool | np.bool_):
            raise TypeError(f"'prune' must be a bool; got {self.prune!r}")

    def decide(self, surfaces: Surfaces, tracer) -> Decision:
        spans, span_start = polygon_spans(surfaces)
        candidates = np.flatnonzero(np.diff(span_start) > 0).astype(np.int64)
        if tracer is None:
            levels = max(surfaces.width, surfaces.height, 1).bit_length() + 2
            check_memory(
                8 * (levels * len(candidates) + 2 * len(spans) + surfaces.width * surfaces.height),
                f"a {surfaces.width}x{surfaces.height} Warnock subdivision of {len(candidates)} polygons",
            )
            rows = warnock_compiled.row_index(spans, span_start, surfaces.height)
            target, areas, tests = warnock_compiled.subdivide(
                spans, rows, surfaces.planes, candidates, surfaces.width, surfaces.height,
                surfaces.tolerance, bool(self.prune),
            )  # fmt: skip
            quadtree = Quadtree.from_rows(areas)
            return Decision(_stats(quadtree, tests, "compiled"), target=target, detail=quadtree)
        target, quadtree, tests = self._subdivide_traced(
            surfaces, spans, span_start, candidates, tracer
        )
        return Decision(_stats(quadtree, tests, "traced reference"), target=target, detail=quadtree)

    def depth_slack(self, surfaces: Surfaces, stats: object) -> float:
        """The tolerance: each sample shows the nearest by its plane's depth, which differs from
        the z-buffer's interpolated depth only by rounding (far below the tolerance)."""
        return surfaces.tolerance

    def _subdivide_traced(self, surfaces, spans, span_start, candidates, tracer):
        """The reference walk: explicit stack of (level, parent, x0, x1, y0, y1, polygons)."""
        width, height = surfaces.width, surfaces.height
        check_memory(
            surfaces.count * width * height,
            f"a traced {width}x{height} Warnock subdivision of {surfaces.count} polygons",
        )
        covers = np.zeros((surfaces.count, height, width), bool)  # each polygon's samples
        for p in candidates.tolist():
            covers[p] = paint_spans(spans[span_start[p] : span_start[p + 1]], width, height)
        target = np.full((height, width), -1, np.int64)
        rows, tests = [], 0
        stack = [(0, -1, 0, width, 0, height, candidates)] if width * height else []
        while stack:
            level, parent, x0, x1, y0, y1, listed = stack.pop()
            covered = covers[listed, y0:y1, x0:x1].sum(axis=(1, 2)).astype(np.int64)
            corners = _corner_depths(surfaces.planes[listed], x0, x1, y0, y1)
            samples = (x1 - x0) * (y1 - y0)
            case, index, kept = area_case(covered, samples, corners, surfaces.tolerance)
            tests += len(listed)
            visible = int(listed[index]) if index >= 0 else -1
            meeting = listed[covered > 0]
            if tracer.wants("area_classified"):
                polygons = tuple(meeting.tolist())
                tracer.emit(AreaClassified(level, x0, x1, y0, y1, CASES[case], visible, polygons))
            area = len(rows)
            rows.append((level, x0, x1, y0, y1, case, visible, parent, len(meeting)))
            if case in (SURROUNDING, PIXEL):
                target[y0:y1, x0:x1] = visible
            elif case == SINGLE:
                target[y0:y1, x0:x1][covers[visible, y0:y1, x0:x1]] = visible
            elif case == SUBDIVIDE:
                passed = listed[kept] if self.prune else meeting
                for a, b, c, d in reversed(quadrants(x0, x1, y0, y1)):  # popped lower left first
                    stack.append((level + 1, area, a, b, c, d, passed))
        return target, Quadtree.from_rows(np.array(rows, np.int64)), tests


def quadrants(x0: int, x1: int, y0: int, y1: int) -> list[tuple[int, int, int, int]]:
    """The nonempty quadrants (x0, x1, y0, y1) of an area: lower left, lower right, upper left, upper right.

    >>> quadrants(0, 5, 0, 1)  # one row: two halves, the right one wider
    [(0, 2, 0, 1), (2, 5, 0, 1)]
    """
    xm, ym = x0 + (x1 - x0) // 2, y0 + (y1 - y0) // 2
    return [
        (a, b, c, d)
        for c, d in ((y0, ym), (ym, y1))
        for a, b in ((x0, xm), (xm, x1))
        if a < b and c < d
    ]

"""The Floating Perimeter Algorithm (Wang 1989, §2.3): hidden lines and hidden surfaces of a grid.

Steps I-V live in `view`, `enumeration` and `facet_edges`; this module is
Step VI, the floating perimeter and its visibility test (Fig. 2-4, spec
§1.6.5), and the hidden-surface variant (§1.6.7). Derivations, the choices
made where the dissertation is silent, and when the perimeter test is exact:
``docs/surfaces-fpa.md``.

Lines mode
----------
Four 1-D arrays bound what the facets processed so far cover on the screen::

    top[0:W] = 0;  bottom[0:W] = H;  right[0:H] = 0;  left[0:H] = W

Facets are taken in enumeration order (nearest first). Each edge a facet
processes is rasterised into points (`edge_points`: one per unit step of the
major axis, from its first grid point to its second). A point (x, y) is
**hidden** iff ``bottom[x] < y < top[x]`` and ``left[y] < x < right[y]``
(strictly inside the perimeter), otherwise visible (on the perimeter counts
as visible, which keeps shared vertices joined). Every point of a facet's
edges is tested against the perimeter the facets before it left; after the
facet, its visible points (Bbuf) raise top and right and lower bottom and
left. The visible runs of each edge are the hidden-line drawing.

Surface mode
------------
The 1-bit coverage mask instead of the four arrays: the facets' triangles are
painted front to back by the z-buffer's own scan conversion and shading
(`render` with `FacetOrder`), each sample written only by the first triangle
to cover it; ``painting="painter"`` paints back to front with no mask, the
alternative of §1.6.7. Within a facet the triangle on the viewpoint's side of
its diagonal goes first, so the order is a valid occlusion order.

Screen coordinates are those of `View.screen_from_world` (y up, row 0 at the
bottom, fitted to all grid points); a raster point is the pixel whose sample
is nearest, floor(s + 1/2).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numba import njit

from .. import steps
from ..conventions import check_choice, check_raster_size, short_repr
from ..limits import check_memory
from ..raster.api import as_tracer
from ..scene import Scene
from ..trace import Recorder, Trace
from ..trace.display import RichDisplay
from ..trace.events import (
    FacetsEnumerated,
    GridEdge,
    PerimeterEdge,
    PerimeterFacet,
    PerimeterUpdate,
)
from ..trace.recorder import Filter
from ..visibility.interface import Decision, Visibility
from .enumeration import Enumeration, enumerate_facets
from .facet_edges import KINDS, FacetEdges, facet_edges
from .grid import GridSurface
from .horizon import LINE_IMAGE_PIXEL_BYTES
from .view import View

MODES = ("lines", "surface")
PAINTINGS = ("mask", "painter")
_BYTES_PER_EDGE_POINT = 64  # coordinates, flags, the facet and edge index of each raster point


@dataclass(frozen=True)
class PerimeterStats(RichDisplay):
    """What the floating perimeter did.

    Lines mode: ``facets``, ``edges`` processed, raster ``points`` tested and
    how many were ``visible``; edges completely visible (tvifg),
    completely ``hidden`` (tivfg) and ``partial``; visible ``segments``
    drawn; ``updates``: visible points merged into the perimeter (the sum of
    Tvp). Surface mode: ``facets`` and the ``samples`` painted; the other
    counts are 0.
    """

    facets: int
    edges: int = 0
    points: int = 0
    visible: int = 0
    edges_visible: int = 0
    edges_hidden: int = 0
    edges_partial: int = 0
    segments: int = 0
    updates: int = 0
    samples: int = 0


@dataclass(frozen=True)
class Perimeter:
    """The four perimeter arrays: top, bottom (W,) and right, left (H,) int64."""

    top: np.ndarray
    bottom: np.ndarray
    right: np.ndarray
    left: np.ndarray

    @classmethod
    def empty(cls, width: int, height: int) -> Perimeter:
        """The dissertation's initial values: top 0, bottom H, right 0, left W (nothing hides)."""
        return cls(
            np.zeros(width, np.int64),
            np.full(width, height, np.int64),
            np.zeros(height, np.int64),
            np.full(height, width, np.int64),
        )

    def bounds(self, x: int, y: int) -> bool:
        """Whether raster point (x, y) lies inside the perimeter or on it."""
        return bool(self.bottom[x] <= y <= self.top[x] and self.left[y] <= x <= self.right[y])


@steps.step(
    "perimeter_test",
    takes="the perimeter arrays top, bottom (per column), right, left (per row) and a raster point x, y",
    returns="True iff the point is hidden: bottom[x] < y < top[x] and left[y] < x < right[y]",
)
def perimeter_test(top, bottom, right, left, x: int, y: int) -> bool:
    """The FPA's visibility test (Fig. 2-4(a)): hidden iff strictly inside the floating perimeter.

    On the perimeter counts as visible, which keeps the vertices shared by a
    visible and a hidden edge drawn.

    >>> top, bottom, right, left = [0, 5, 5, 0], [4, 1, 1, 4], [0, 2, 2, 2, 0], [4, 1, 1, 1, 4]
    >>> perimeter_test(top, bottom, right, left, 1, 3), perimeter_test(top, bottom, right, left, 2, 3)
    (False, False)
    >>> perimeter_test(top, bottom, right, left, 1, 2)  # column 1 spans 1..5, row 2 spans 1..2
    False
    """
    return bool(bottom[x] < y < top[x] and left[y] < x < right[y])


@steps.step(
    "perimeter_merge",
    takes="the perimeter arrays top, bottom, right, left (numpy int64, changed in place) and Bbuf, "
    "the facet's visible points [(x, y), ...]",
    returns="None: top[x], right[y] raised and bottom[x], left[y] lowered to every point",
)
def perimeter_merge(top, bottom, right, left, bbuf) -> None:
    """Fig. 2-4(b): after all of a facet's edges, widen the perimeter to its visible points.

    >>> top, bottom = np.zeros(3, np.int64), np.full(3, 4, np.int64)
    >>> right, left = np.zeros(4, np.int64), np.full(4, 3, np.int64)
    >>> perimeter_merge(top, bottom, right, left, [(1, 2), (1, 0)])
    >>> top.tolist(), bottom.tolist(), right.tolist(), left.tolist()
    ([0, 2, 0], [4, 0, 4], [1, 0, 1, 0], [1, 3, 1, 3])
    """
    for x, y in bbuf:
        top[x] = max(top[x], y)
        bottom[x] = min(bottom[x], y)
        right[y] = max(right[y], x)
        left[y] = min(left[y], x)


@dataclass(frozen=True)
class PerimeterResult:
    """The Floating Perimeter Algorithm's picture and state.

    Attributes
    ----------
    mode : {"lines", "surface"}
    image : (H, W, 3) ndarray of float64
        Lines: black visible lines on white; surface: the shaded render.
    lines : (H, W) ndarray of bool or None
        Lines mode: the visible raster points (row 0 at the bottom).
    facet : (H, W) ndarray of int64 or None
        Surface mode: the grid element k = r (Nx - 1) + c seen at each pixel, -1 for none.
    case : int
        The viewing case 1-9.
    enumeration : Enumeration
    edges : FacetEdges
        The edges each facet processes, in processing order.
    points : (P, 2) ndarray of int64
        Lines mode: every raster point tested, edge after edge in processing order.
    visible : (P,) ndarray of bool
        Lines mode: each point's flag.
    on_perimeter : (P,) ndarray of bool
        Lines mode: visible only because it lies on the perimeter (``>=`` or
        ``<=`` with equality), not strictly outside it.
    point_edge : (P,) ndarray of int64
        Lines mode: the row of ``edges.edges`` each point belongs to.
    segments : (K, 4) ndarray of int64
        Lines mode: the visible runs (x0, y0, x1, y1), in drawing order.
    perimeter : Perimeter or None
        Lines mode: the arrays after the last facet.
    stats : PerimeterStats
    render : RenderResult or None
        Surface mode: the render that painted the facets.
    trace : Trace or None
    """

    mode: str
    image: np.ndarray
    lines: np.ndarray | None
    facet: np.ndarray | None
    case: int
    enumeration: Enumeration
    edges: FacetEdges
    points: np.ndarray
    visible: np.ndarray
    on_perimeter: np.ndarray
    point_edge: np.ndarray
    segments: np.ndarray
    perimeter: Perimeter | None
    stats: PerimeterStats
    render: object = None
    trace: Trace | None = field(default=None)


@dataclass(frozen=True)
class FacetOrderStats(RichDisplay):
    """polygons: triangles in the order; left_out: those the z-buffer never scans (edge-on)."""

    polygons: int
    left_out: int


@dataclass(frozen=True)
class FacetOrder(Visibility):
    """Visibility by a given order of polygons: front to back with the coverage mask, or painted over.

    The hidden-surface FPA passes the triangles of its facet enumeration;
    ``mode`` "under" writes a sample only once (the mask), "over" paints back
    to front (the painter's alternative). `render(scene, w, h, visibility=FacetOrder(...))`.
    """

    name: ClassVar[str] = "fpa"
    polygons: tuple[int, ...] = ()
    mode: str = "under"

    def __post_init__(self) -> None:
        check_choice("mode", self.mode, ("under", "over"))

    def decide(self, surfaces, tracer) -> Decision:
        drawn = {piece.polygon: piece for piece in surfaces.pieces()}
        pieces = tuple(drawn[p] for p in self.polygons if p in drawn)
        stats = FacetOrderStats(len(pieces), surfaces.count - len(pieces))
        return Decision(stats, pieces, self.mode)


def floating_perimeter(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    mode: str = "lines",
    trace: object = None,
    *,
    shading: str = "phong",
    painting: str = "mask",
    sample: str = "corner",
    scene: Scene | None = None,
) -> PerimeterResult:
    """Hidden lines or hidden surfaces of a grid surface by the Floating Perimeter Algorithm.

    Parameters
    ----------
    surface : GridSurface
    view : View
        Viewpoint, direction and projection; the grid is fitted to the raster.
    width, height : int
        Raster size: at least 1 (lines) or 2 (surface).
    mode : {"lines", "surface"}
        The perimeter test on the edges (hidden lines), or the facets' triangles
        painted front to back with the coverage mask (hidden surfaces).
    trace : None, True or Tracer
        Lines: ``facets_enumerated``, then per facet ``perimeter_facet``, one
        ``perimeter_edge`` per edge and ``perimeter_update``; None runs the
        compiled pass, a tracer the traced reference (same arrays). Surface:
        ``facets_enumerated`` and the render's own events.
    shading : str
        Surface mode: a shading mode of `render` ("flat", "gouraud", "phong", "gooch").
    painting : {"mask", "painter"}
        Surface mode: front to back with the coverage mask (§1.6.7), or back
        to front with no mask.
    sample : {"corner", "center"}
        Surface mode: the render's sampling (``render``'s default, "corner",
        matches ``render(surface.scene(view, width, height), width, height)``).
    scene : Scene, optional
        Surface mode: the scene painted in facet order (default
        ``surface.scene(view, width, height)``), e.g. `phase_scene`'s, with other
        materials; one object whose faces 2k, 2k + 1 are grid element k.

    Returns
    -------
    PerimeterResult

    Raises
    ------
    TypeError
        If `surface` is not a GridSurface, `view` not a View, `trace` not a
        tracer, or width/height not an int.
    ValueError
        If the raster is too small, `mode`, `painting` or `shading` is
        unknown; the View's error if a grid point is not in front of a
        perspective viewpoint.

    Examples
    --------
    A ridge seen along the valley behind it: the far side's near edges are hidden.

    >>> ridge = GridSurface([0.0, 1.0], [0.0, 1.0, 2.0], [[0, 0], [1, 1], [0, 0]])
    >>> result = floating_perimeter(ridge, View((0.5, -6, 0.5), (0, 1, 0)), 9, 9)
    >>> result.case, result.stats.edges, result.stats.edges_hidden
    (2, 7, 1)
    """
    width, height = _check(surface, view, width, height, mode, painting)
    tracer = as_tracer(trace)
    enumeration = enumerate_facets(surface.x, surface.y, view)
    edges = facet_edges(enumeration)
    if tracer is not None and tracer.wants("facets_enumerated"):
        tracer.emit(
            FacetsEnumerated(
                case=enumeration.case,
                vp_cell=enumeration.vp_cell,
                order=tuple(map(tuple, enumeration.order.tolist())),
                classes=tuple(map(tuple, enumeration.classes.tolist())),
            )
        )
    if mode == "surface":
        return _surface(surface, view, width, height, enumeration, edges, tracer, shading, painting, sample, scene)  # fmt: skip
    screen = view.screen_from_world(surface.points(), width, height)[0]
    pixels = np.floor(screen + 0.5).astype(np.int64)
    starts, ends = edge_endpoints(edges.edges, surface.nx)
    counts = np.abs(pixels[ends] - pixels[starts]).max(axis=1) + 1
    check_memory(
        int(counts.sum()) * _BYTES_PER_EDGE_POINT + LINE_IMAGE_PIXEL_BYTES * width * height,
        f"the floating perimeter of a {surface.nx}x{surface.ny} grid at {width}x{height}",
    )
    points, point_edge = edge_points(pixels[starts], pixels[ends])
    perimeter = Perimeter.empty(width, height)
    if tracer is None and not steps.replaced():
        facet_starts = np.searchsorted(edges.facet[point_edge], np.arange(1, surface.facets + 2))
        visible, on_perimeter = np.empty(len(points), bool), np.empty(len(points), bool)
        _perimeter_pass(points, facet_starts, *_arrays(perimeter), visible, on_perimeter)
    else:
        visible, on_perimeter = _traced_pass(
            enumeration, edges, points, point_edge, perimeter, tracer or Filter(kinds=())
        )
    flags = (visible, on_perimeter)
    return _lines_result(enumeration, edges, points, flags, point_edge, perimeter, width, height, tracer)  # fmt: skip


def _check(surface, view, width, height, mode, painting) -> tuple[int, int]:
    if not isinstance(surface, GridSurface):
        raise TypeError(f"'surface' must be a GridSurface; got {short_repr(surface)}")
    if not isinstance(view, View):
        raise TypeError(f"'view' must be a View; got {short_repr(view)}")
    check_choice("mode", mode, MODES)
    check_choice("painting", painting, PAINTINGS)
    width, height = check_raster_size(width, height)
    least = 2 if mode == "surface" else 1
    if width < least or height < least:
        raise ValueError(
            f"'width' and 'height' must be at least {least} in {mode} mode; got {width} x {height}"
        )
    return width, height


def edge_endpoints(edges: np.ndarray, nx: int) -> tuple[np.ndarray, np.ndarray]:
    """Grid point indices (j Nx + i) of each edge's first and second point.

    An "h" edge (kind 0) runs from (column, row) to (column + 1, row), a "v"
    edge (kind 1) from (column, row) to (column, row + 1).

    >>> edge_endpoints(np.array([[0, 1, 0], [1, 0, 2]]), 3)
    (array([3, 2]), array([4, 5]))
    """
    edges = np.asarray(edges, np.int64).reshape(-1, 3)
    starts = edges[:, 1] * nx + edges[:, 2]
    return starts, starts + np.where(edges[:, 0] == 0, 1, nx)


def edge_points(first: np.ndarray, last: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The raster points of integer segments: a DDA with one point per unit step of the major axis.

    Segment e from ``first[e]`` to ``last[e]`` has n = m + 1 points,
    m = max(|dx|, |dy|); point k is first + (round(k dx / m), round(k dy / m)),
    rounding halves up (exact integer arithmetic: floor((2 k d + m) / 2m)).

    Returns
    -------
    points : (P, 2) ndarray of int64
        All segments' points, segment after segment, each from first to last.
    segment : (P,) ndarray of int64
        The segment each point belongs to.

    >>> points, segment = edge_points(np.array([[0, 0], [2, 2]]), np.array([[3, 1], [2, 2]]))
    >>> points.tolist(), segment.tolist()
    ([[0, 0], [1, 0], [2, 1], [3, 1], [2, 2]], [0, 0, 0, 0, 1])
    """
    first, last = np.asarray(first, np.int64), np.asarray(last, np.int64)
    delta = last - first
    steps = np.abs(delta).max(axis=1)
    counts = steps + 1
    segment = np.repeat(np.arange(len(first)), counts)
    offsets = np.concatenate([[0], np.cumsum(counts)[:-1]])
    k = np.arange(len(segment)) - offsets[segment]
    m = np.maximum(steps, 1)[segment, None]
    points = first[segment] + (2 * k[:, None] * delta[segment] + m) // (2 * m)
    return points, segment


def _arrays(perimeter: Perimeter) -> tuple[np.ndarray, ...]:
    return perimeter.top, perimeter.bottom, perimeter.right, perimeter.left


@njit(cache=True)
def _perimeter_pass(
    points, facet_starts, top, bottom, right, left, visible, on_perimeter
):  # pragma: no cover - compiled
    """Step VI over all facets: test each facet's points, then merge its visible ones (Bbuf)."""
    width, height = top.shape[0], right.shape[0]
    for f in range(facet_starts.shape[0] - 1):
        first, stop = facet_starts[f], facet_starts[f + 1]
        for i in range(first, stop):
            x, y = points[i, 0], points[i, 1]
            if 0 <= x < width and 0 <= y < height:
                visible[i] = not (bottom[x] < y < top[x] and left[y] < x < right[y])
                on_perimeter[i] = (
                    visible[i] and bottom[x] <= y <= top[x] and left[y] <= x <= right[y]
                )
            else:  # off the raster: visible, and it never moves the perimeter
                visible[i] = True
                on_perimeter[i] = False
        for i in range(first, stop):
            x, y = points[i, 0], points[i, 1]
            if visible[i] and 0 <= x < width and 0 <= y < height:
                top[x] = max(top[x], y)
                bottom[x] = min(bottom[x], y)
                right[y] = max(right[y], x)
                left[y] = min(left[y], x)


def _traced_pass(enumeration, edges, points, point_edge, perimeter, tracer) -> np.ndarray:
    """Step VI as Fig. 2-4 writes it, point by point with vifg/ivfg, emitting every step."""
    hides = steps.get("perimeter_test")
    width, height = len(perimeter.top), len(perimeter.right)
    visible, on_perimeter = np.zeros(len(points), bool), np.zeros(len(points), bool)
    bounds = np.searchsorted(point_edge, np.arange(len(edges.edges) + 1))
    edge_rows = np.searchsorted(edges.facet, np.arange(1, len(edges.taken) + 2))
    for number, (row, column) in enumerate(enumeration.sequence.tolist(), start=1):
        if tracer.wants("perimeter_facet"):
            tracer.emit(
                PerimeterFacet(
                    number=number,
                    row=row,
                    column=column,
                    region_class=int(enumeration.classes[row, column]),
                    sides=edges.sides[number - 1],
                    edges=tuple(GridEdge(*edge) for edge in edges.per_facet[number - 1]),
                )
            )
        bbuf: list[tuple[int, int]] = []
        for e in range(edge_rows[number - 1], edge_rows[number]):
            first, stop = bounds[e], bounds[e + 1]
            vifg, segments, start = [], [], None
            for i in range(first, stop):
                x, y = (int(v) for v in points[i])
                inside = 0 <= x < width and 0 <= y < height
                if not inside or not hides(*_arrays(perimeter), x, y):
                    vifg.append(True)
                    if inside:
                        bbuf.append((x, y))
                        on_perimeter[i] = perimeter.bounds(x, y)
                    if start is None:  # p[1], or the point after a hidden one, opens a segment
                        start = (x, y)
                    if i == stop - 1:
                        segments.append((*start, x, y))
                else:
                    vifg.append(False)
                    if start is not None:  # the point before closes the segment
                        segments.append((*start, *(int(v) for v in points[i - 1])))
                        start = None
            visible[first:stop] = vifg
            if tracer.wants("perimeter_edge"):
                kind, r, c = (int(v) for v in edges.edges[e])
                verdict = "visible" if all(vifg) else "hidden" if not any(vifg) else "partial"
                tracer.emit(
                    PerimeterEdge(
                        facet=number,
                        edge=GridEdge(KINDS[kind], r, c),
                        points=tuple((int(x), int(y)) for x, y in points[first:stop]),
                        visible=tuple(vifg),
                        segments=tuple(segments),
                        verdict=verdict,
                    )
                )
        _merge(perimeter, bbuf, number, tracer)
    return visible, on_perimeter


def _merge(perimeter: Perimeter, bbuf, number: int, tracer) -> None:
    """After all of a facet's edges: every visible point widens the perimeter (Fig. 2-4(b))."""
    before = [array.copy() for array in _arrays(perimeter)]
    steps.get("perimeter_merge")(*_arrays(perimeter), list(bbuf))
    if tracer.wants("perimeter_update"):
        top, bottom, right, left = _arrays(perimeter)
        columns = np.flatnonzero((top != before[0]) | (bottom != before[1]))
        rows = np.flatnonzero((right != before[2]) | (left != before[3]))
        tracer.emit(
            PerimeterUpdate(
                facet=number,
                points=len(bbuf),
                columns=tuple((int(x), int(top[x]), int(bottom[x])) for x in columns),
                rows=tuple((int(y), int(right[y]), int(left[y])) for y in rows),
            )
        )


def visible_runs(visible: np.ndarray, point_edge: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(first, last) point index of every maximal visible run that stays within one edge.

    >>> visible_runs(np.array([1, 1, 0, 1, 1, 1], bool), np.array([0, 0, 0, 0, 1, 1]))
    (array([0, 3, 4]), array([1, 3, 5]))
    """
    visible = np.asarray(visible, bool)
    new_edge = np.r_[True, point_edge[1:] != point_edge[:-1]]
    opens = visible & (new_edge | ~np.r_[False, visible[:-1]])
    last_of_edge = np.r_[new_edge[1:], True]
    closes = visible & (last_of_edge | ~np.r_[visible[1:], False])
    return np.flatnonzero(opens), np.flatnonzero(closes)


def _lines_result(enumeration, edges, points, flags, point_edge, perimeter, width, height, tracer):
    visible, on_perimeter = flags
    first, last = visible_runs(visible, point_edge)
    segments = np.hstack([points[first], points[last]]).reshape(-1, 4)
    lines = np.zeros((height, width), bool)
    shown = points[visible]
    on_raster = (
        (shown[:, 0] >= 0) & (shown[:, 0] < width) & (shown[:, 1] >= 0) & (shown[:, 1] < height)
    )
    lines[shown[on_raster, 1], shown[on_raster, 0]] = True
    image = np.repeat(np.where(lines, 0.0, 1.0)[..., None], 3, axis=-1)
    per_edge_points = np.bincount(point_edge, minlength=len(edges.edges))
    per_edge_visible = np.bincount(point_edge, weights=visible, minlength=len(edges.edges))
    all_visible = int((per_edge_visible == per_edge_points).sum())
    all_hidden = int((per_edge_visible == 0).sum())
    stats = PerimeterStats(
        facets=len(edges.taken),
        edges=len(edges.edges),
        points=len(points),
        visible=int(visible.sum()),
        edges_visible=all_visible,
        edges_hidden=all_hidden,
        edges_partial=len(edges.edges) - all_visible - all_hidden,
        segments=len(segments),
        updates=int(on_raster.sum()),
    )
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return PerimeterResult(
        "lines", image, lines, None, enumeration.case, enumeration, edges, points, visible,
        on_perimeter, point_edge, segments, perimeter, stats, None, recorded,
    )  # fmt: skip


def facet_polygons(
    enumeration: Enumeration, x: np.ndarray, y: np.ndarray, view: View
) -> tuple[int, ...]:
    """The mesh triangles (2k, 2k + 1 of `GridSurface.to_mesh`) of the facets, front to back.

    Within a facet, the triangle on the viewpoint's side of the diagonal from
    (c, r) to (c + 1, r + 1) comes first: a ray from the viewpoint to a point
    on that side never crosses the other triangle's XY region. A parallel view
    puts the viewpoint at infinity against its direction.

    >>> from scanviz.surfaces import enumerate_facets
    >>> x = y = np.array([0.0, 1.0])
    >>> view = View((5, -1, 3), (-1, 0.2, -0.5))  # below-right of the diagonal
    >>> facet_polygons(enumerate_facets(x, y, view), x, y, view)
    (0, 1)
    """
    columns = len(x) - 1
    rows, cols = enumeration.sequence[:, 0], enumeration.sequence[:, 1]
    # Side of the diagonal line through (x_c, y_r) and (x_c+1, y_r+1): the cross product's sign.
    dx, dy = x[cols + 1] - x[cols], y[rows + 1] - y[rows]
    if view.projection == "parallel":
        side = dx * -view.direction[1] - dy * -view.direction[0]
    else:
        side = dx * (view.point[1] - y[rows]) - dy * (view.point[0] - x[cols])
    k = rows * columns + cols
    below_first = side <= 0  # the viewpoint is right of / below the diagonal: triangle 2k first
    order = np.stack(
        [np.where(below_first, 2 * k, 2 * k + 1), np.where(below_first, 2 * k + 1, 2 * k)], axis=1
    )
    return tuple(order.reshape(-1).tolist())


def _surface(
    surface, view, width, height, enumeration, edges, tracer, shading, painting, sample, scene
):
    from ..pipeline import render  # the pipeline imports the visibility package; import it late

    if scene is None:
        scene = surface.scene(view, width, height)
    elif not isinstance(scene, Scene):
        raise TypeError(f"'scene' must be a scanviz Scene; got {short_repr(scene)}")
    elif len(scene.objects) != 1 or len(scene.objects[0].mesh.faces) != 2 * surface.facets:
        faces = [len(o.mesh.faces) for o in scene.objects]
        raise ValueError(
            f"'scene' must hold one object of 2 x {surface.facets} faces (grid element k: faces "
            f"2k, 2k + 1); got {len(faces)} object{'s' * (len(faces) != 1)} of {sum(faces)} faces"
        )
    polygons = facet_polygons(enumeration, surface.x, surface.y, view)
    if painting == "painter":
        order = FacetOrder(polygons[::-1], mode="over")
    else:
        order = FacetOrder(polygons, mode="under")
    result = render(
        scene, width, height, shading=shading, visibility=order, sample=sample, trace=tracer
    )
    facet = np.where(result.polygon >= 0, result.polygon // 2, -1)
    stats = PerimeterStats(facets=surface.facets, samples=int(result.visibility.stats.depth_passed))
    none = np.zeros(0, np.int64)
    return PerimeterResult(
        "surface", result.image, None, facet, enumeration.case, enumeration, edges,
        np.zeros((0, 2), np.int64), np.zeros(0, bool), np.zeros(0, bool), none,
        np.zeros((0, 4), np.int64),
        None, stats, result, result.trace,
    )  # fmt: skip

"""Interpolating depth and vertex values during scan conversion (reference, traced).

The thesis (§6.2 "Interpolating Values"), the UMBC z-buffer slides and the
CS184 notes extend the ET/AET of `scanviz.raster.scanline` so that every
sample a polygon covers gets a depth and values:

* **Depth** comes from the plane A x + B y + C z + D = 0 of the snapped
  vertices (Newell's method): z = (-A x - B y - D) / C. On the first row the
  depth at x = 0, z_row, is computed from the plane; each later row steps it
  by dz/dy = -B/C. A span starts at z_row + dz/dx * x_start and steps by
  dz/dx = -A/C per pixel (the slides' z' = z - A/C).
* **Values** (colors, normals, ...) go along the edges, then along the spans:
  each active edge carries its value on the current row, computed from its
  lower end on its first row and then stepped by d(value)/dy; a span between
  crossings x_left < x_right steps by (v_right - v_left) / (x_right - x_left)
  from v_left + (x_start - x_left) * d(value)/dx.
* **Perspective-correct** interpolation runs the same scheme on value/w and
  1/w, and divides per sample.

Coordinates here are in the *sample frame*: pixels with the sample of pixel
(x, y) at (x, y), i.e. the grid of `scanviz.raster.fixed` divided by its
scale, so a pixel index is a coordinate. Trace events use the caller's frame.

The step from one sample of a span to the next is the replaceable step
``span_step`` (`scanviz.steps`): the depth by dz/dx, compensated, and each
value by d(value)/dx.

The formulas (`depth_plane` to `perspective_divide`) are plain Python on
floats and sequences; the compiled z-buffer (`scanviz.visibility.zbuffer_compiled`)
compiles these same functions with numba, so both paths run one definition
in one order of operations and agree to the bit. Derivations and error
bounds: docs/interpolation.md.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction

import numpy as np
from numba import njit, prange

from .. import steps
from ..threads import use_threads
from ..trace.events import (
    EdgeValueEntry,
    EdgeValues,
    InterpolatedSpan,
    PolygonSetup,
    SpanValues,
)
from .fixed import SnappedPolygon
from .scanline import AetItem, Edge, ScanRow, bucketed_edge_table, scan_rows

# --- the formulas, shared with the compiled kernel -----------------------------------------


def depth_plane(xs, ys, zs):
    """Newell's plane through the vertices (xs[i], ys[i], zs[i]) of a polygon.

    Returns (A, B, C, dzdx, dzdy, z_first): the normal (A, B, C), with C
    twice the signed area in xy; the depth steps -A/C and -B/C; and the
    plane's depth at (xs[0], ys[0]). The plane passes through the centroid of
    the vertices (through each of them when they are coplanar). Sums run
    relative to vertex 0, where snapped coordinates are exact. When C == 0
    (seen edge-on) the steps are 0 and z_first is zs[0].

    >>> depth_plane([0.0, 4.0, 0.0], [0.0, 0.0, 2.0], [1.0, 3.0, 2.0])
    (-4.0, -4.0, 8.0, 0.5, 0.5, 1.0)
    """
    n = len(xs)
    x0, y0, z0 = xs[0], ys[0], zs[0]
    a = b = c = x_sum = y_sum = z_sum = 0.0
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        xi, yi, zi = xs[i] - x0, ys[i] - y0, zs[i] - z0
        xj, yj, zj = xs[j] - x0, ys[j] - y0, zs[j] - z0
        a += (yi - yj) * (zi + zj)
        b += (zi - zj) * (xi + xj)
        c += (xi - xj) * (yi + yj)
        x_sum += xi
        y_sum += yi
        z_sum += zi
    if c == 0.0:
        return a, b, c, 0.0, 0.0, z0
    dzdx, dzdy = -a / c, -b / c
    # The plane through the centroid (x_sum, y_sum, z_sum) / n, evaluated at vertex 0.
    return a, b, c, dzdx, dzdy, z0 + (z_sum / n - (dzdx * (x_sum / n) + dzdy * (y_sum / n)))


def plane_depth(x_first, y_first, z_first, dzdx, dzdy, x, y):
    """Depth of the plane through (x_first, y_first, z_first) with steps dzdx, dzdy at (x, y).

    >>> plane_depth(0.0, 0.0, 1.0, 0.5, 0.5, 2.0, 2.0)
    3.0
    """
    return z_first + dzdx * (x - x_first) + dzdy * (y - y_first)


def compensated_step(total, carry, step):
    """total + step, carrying the rounding error to the next step (Kahan): (total, carry).

    A plain ``z += dz/dx`` rounds once per step at the magnitude of z, so n
    steps drift by up to n ulps of z: too much for depths clustered near 1
    (NDC), or for z_row, the plane at x = 0, far from a steep polygon.

    >>> total, carry = 1.0, 0.0
    >>> for _ in range(10):
    ...     total, carry = compensated_step(total, carry, 0.1)
    >>> total, 1.0 + 0.1 * 10
    (2.0, 2.0)
    """
    corrected = step - carry
    new_total = total + corrected
    return new_total, (new_total - total) - corrected


def reaches_raster(x_min, x_max, y_min, y_max, scale, width, height):
    """Whether grid bounds (integer units, `scale` a pixel) leave a sample of the raster to cover.

    Spans run from ceil(x) of crossings in [x_min, x_max] and are clipped to
    [0, width); rows are [ceil(y_min), ceil(y_max)) clipped to [0, height).

    >>> reaches_raster(-8, -1, 0, 8, 4, 5, 5), reaches_raster(-8, 1, 0, 8, 4, 5, 5)
    (False, True)
    """
    return (
        -(-x_max // scale) > 0
        and -(-x_min // scale) < width
        and -(-y_max // scale) > 0
        and -(-y_min // scale) < height
    )


def crossing_x(q, r, den):
    """An exact crossing x = q + r/den (0 <= r < den) as a float.

    With int64 operands (numpy or numba) r/den divides their float64 values;
    with Python ints it is correctly rounded. On int64 grids both paths pass
    int64s, so the bits agree; either way the result is within an ulp of x.

    >>> crossing_x(3, 1, 4)
    3.25
    """
    return q + r / den


def edge_slope(v_lower, v_upper, y_lower, y_upper):
    """d(value)/dy along an edge from its lower end to its upper end (y_upper > y_lower).

    >>> edge_slope(1.0, 4.0, 0.5, 2.0)
    2.0
    """
    return (v_upper - v_lower) / (y_upper - y_lower)


def edge_start(v_lower, dvdy, y_lower, y):
    """The edge's value on row y, computed directly from its lower end.

    >>> edge_start(1.0, 2.0, 0.5, 1)
    2.0
    """
    return v_lower + (y - y_lower) * dvdy


def span_slope(v_left, v_right, x_left, x_right):
    """d(value)/dx along a span between crossings x_left < x_right (0 if they round equal).

    >>> span_slope(1.0, 2.0, 0.25, 4.25)
    0.25
    """
    width = x_right - x_left
    return (v_right - v_left) / width if width > 0.0 else 0.0


def span_start(v_left, dvdx, x_left, x):
    """A span's value at its first sample x (x_left <= x < x_right).

    >>> span_start(1.0, 0.25, 0.25, 1)
    1.1875
    """
    return v_left + (x - x_left) * dvdx


def perspective_divide(value_over_w, one_over_w):
    """A perspective-correct value: interpolated value/w over interpolated 1/w.

    1/w is positive at every vertex, so it is inside a polygon; 0 is returned
    only if rounding took it to 0 or below (1/w varying by a factor over ~1e10
    across one polygon).

    >>> perspective_divide(1.5, 0.5)
    3.0
    """
    return value_over_w / one_over_w if one_over_w > 0.0 else 0.0


# --- the reference --------------------------------------------------------------------------


def vertex_channels(values: np.ndarray, inv_w: np.ndarray, perspective: bool) -> np.ndarray:
    """The per-vertex quantities interpolated: (M, K) values, or (M, K + 1) value/w then 1/w.

    >>> vertex_channels(np.array([[2.0], [4.0]]), np.array([0.5, 0.25]), True).tolist()
    [[1.0, 0.5], [1.0, 0.25]]
    """
    if not perspective:
        return np.array(values, dtype=np.float64)
    values, inv_w = np.asarray(values, np.float64), np.asarray(inv_w, np.float64)
    out = np.empty((len(values), values.shape[1] + 1))
    (_over_w_shared if use_threads(len(values), PARALLEL_VERTICES) else _over_w_here)(
        values, inv_w, out
    )
    return out


PARALLEL_VERTICES = 2**16  # more vertices are divided by w on numba's threads


@njit(cache=True, parallel=True)
def _over_w_shared(values, inv_w, out):  # pragma: no cover - compiled
    for i in prange(values.shape[0]):
        _over_w_row(i, values, inv_w, out)


@njit(cache=True)
def _over_w_here(values, inv_w, out):  # pragma: no cover - compiled
    for i in range(values.shape[0]):
        _over_w_row(i, values, inv_w, out)


@njit(cache=True, inline="always")
def _over_w_row(i, values, inv_w, out):  # pragma: no cover - compiled
    """Row i of ``column_stack([values * inv_w[:, None], inv_w])`` (the same products)."""
    k = values.shape[1]
    for j in range(k):
        out[i, j] = values[i, j] * inv_w[i]
    out[i, k] = inv_w[i]


@dataclass(frozen=True)
class Plane:
    """A polygon's depth plane, sample frame: z(x, y) = z_first + dzdx (x - x_first) + dzdy (y - y_first).

    (a, b, c) is Newell's normal; c == 0 means the polygon is seen edge-on.
    """

    a: float
    b: float
    c: float
    x_first: float
    y_first: float
    z_first: float
    dzdx: float
    dzdy: float

    @property
    def edge_on(self) -> bool:
        return self.c == 0.0

    def depth(self, x: float, y: float) -> float:
        return plane_depth(self.x_first, self.y_first, self.z_first, self.dzdx, self.dzdy, x, y)


def polygon_plane(snapped: SnappedPolygon, z: Sequence[float]) -> Plane:
    """The depth plane of a one-contour snapped polygon with depths `z` per vertex.

    Examples
    --------
    >>> from scanviz import Polygon
    >>> from scanviz.raster.fixed import snap
    >>> plane = polygon_plane(snap(Polygon([(0, 0), (4, 0), (0, 2)])), [1.0, 3.0, 2.0])
    >>> plane.dzdx, plane.dzdy, plane.depth(2.0, 2.0)
    (0.5, 0.5, 3.0)
    """
    xs = [int(u) / snapped.scale for u in snapped.units[:, 0]]
    ys = [int(u) / snapped.scale for u in snapped.units[:, 1]]
    a, b, c, dzdx, dzdy, z_first = depth_plane(xs, ys, [float(v) for v in z])
    return Plane(a, b, c, xs[0], ys[0], z_first, dzdx, dzdy)


def polygon_reaches_raster(snapped: SnappedPolygon, width: int, height: int) -> bool:
    """Whether `snapped` can cover a sample of a width x height raster (else it is not scanned)."""
    xs, ys = [int(u) for u in snapped.units[:, 0]], [int(u) for u in snapped.units[:, 1]]
    return reaches_raster(min(xs), max(xs), min(ys), max(ys), snapped.scale, width, height)


@steps.step(
    "span_step",
    takes="a span's depth z, its carry, its values (tuple of floats), and their steps dzdx, dvdx",
    returns="(z, carry, values) one sample right: z by compensated_step, each value + its d/dx",
)
def span_step(z, carry, values, dzdx, dvdx):
    """One sample to the right along a span: depth stepped by Kahan's sum, values by plain sums.

    >>> span_step(1.0, 0.0, (0.5, 2.0), 0.25, (0.125, -1.0))
    (1.25, 0.0, (0.625, 1.0))
    """
    z, carry = compensated_step(z, carry, dzdx)
    return z, carry, tuple(v + d for v, d in zip(values, dvdx, strict=True))


def span_samples(span: InterpolatedSpan) -> Iterator[tuple[int, float, tuple[float, ...]]]:
    """Yield (x, z, values) per sample of `span`, each from the previous one by `span_step`."""
    step = steps.get("span_step")
    z, z_carry, values = span.z, 0.0, span.values
    for x in range(span.x_start, span.x_end):
        if x > span.x_start:
            z, z_carry, values = step(z, z_carry, values, span.dzdx, span.dvdx)
        yield x, z, values


class EdgeInterpolant:
    """An active edge's values on the current row and their steps d/dy (the thesis' Fig. 6.3)."""

    def __init__(self, lower: list, upper: list, y_lower: float, y_upper: float, row: int):
        self.dvdy = [edge_slope(a, b, y_lower, y_upper) for a, b in zip(lower, upper, strict=True)]
        self.values = [
            edge_start(a, d, y_lower, row) for a, d in zip(lower, self.dvdy, strict=True)
        ]

    def step(self) -> None:
        self.values = [v + d for v, d in zip(self.values, self.dvdy, strict=True)]


def emit_polygon_setup(
    trace, polygon: int, snapped: SnappedPolygon, z, plane: Plane, channels, perspective: bool
) -> None:
    """Emit `polygon_setup`: snapped vertices, plane (A, B, C, D) and steps, caller's frame."""
    if trace is None or not trace.wants("polygon_setup", polygon=polygon):
        return
    offset = snapped.shift / snapped.scale  # sample frame -> caller's frame
    vertices = tuple(
        (float(snapped.to_pixels(int(ux))), float(snapped.to_pixels(int(uy))), float(depth))
        for (ux, uy), depth in zip(snapped.units, z, strict=True)
    )
    d = -(
        plane.a * (plane.x_first + offset)
        + plane.b * (plane.y_first + offset)
        + plane.c * plane.z_first
    )
    trace.emit(
        PolygonSetup(
            polygon=polygon,
            vertices=vertices,
            plane=(float(plane.a), float(plane.b), float(plane.c), float(d)),
            dzdx=None if plane.edge_on else float(plane.dzdx),
            dzdy=None if plane.edge_on else float(plane.dzdy),
            values=tuple(tuple(float(v) for v in row) for row in channels),
            perspective=perspective,
        )
    )


def _vertex_ends(edge: Edge, units: np.ndarray) -> tuple[int, int]:
    """(lower, upper) vertex indices of edge i, which joins vertex i to vertex i + 1 (mod n)."""
    i, j = edge.edge, (edge.edge + 1) % len(units)
    return (i, j) if edge.lower == (int(units[i, 0]), int(units[i, 1])) else (j, i)


def _edge_interpolant(edge: Edge, snapped: SnappedPolygon, vertex_values, y: int):
    """The values of an edge entering the AET on row y, directly from its lower end."""
    lower, upper = _vertex_ends(edge, snapped.units)
    y_lower, y_upper = edge.lower[1] / snapped.scale, edge.upper[1] / snapped.scale
    return EdgeInterpolant(vertex_values[lower], vertex_values[upper], y_lower, y_upper, y)


def _crossing_float(x: object, edge: Edge, exact: type) -> float:
    """An AET x as the float `crossing_x` makes of it, its operands of type `exact`.

    The reference ``aet_update`` keeps x = q + r/den on the grid of the edge's
    crossing (x's denominator divides den), and (q, r, den) give the compiled
    kernel's float to the bit. Any other x (a replaced step's) is rounded directly.
    """
    den = edge.crossing.den
    if isinstance(x, int | Fraction) and den % x.denominator == 0:
        q, rest = divmod(x.numerator, x.denominator)
        return float(crossing_x(exact(q), exact(rest * (den // x.denominator)), exact(den)))
    return float(x)  # type: ignore[arg-type]


def _bounding_pair(aet: list[AetItem], y: int, start: int, end: int) -> int:
    """k such that AET items k and k + 1 bound the span [start, end) of row y.

    The span must lie within [ceil(x_k), ceil(x_k+1)) of a consecutive pair of
    crossings: the reference ``span_rule`` cuts exactly those runs (clipped to
    the raster), and a replaced one may shorten them.
    """
    for k in range(len(aet) - 1):
        if math.ceil(aet[k].x) <= start and end <= math.ceil(aet[k + 1].x):
            return k
    raise ValueError(
        f"span_rule returned the span [{start}, {end}) on row {y}, which lies between no two "
        "consecutive crossings of the AET: its values cannot be interpolated between two edges"
    )


def _span(
    y, start, end, x_left, x_right, left: EdgeInterpolant, right: EdgeInterpolant, z_row, dzdx
):
    """The span [start, end) between two crossings: values at `start` and their steps d/dx."""
    pairs = zip(left.values, right.values, strict=True)
    dvdx = tuple(span_slope(a, b, x_left, x_right) for a, b in pairs)
    values = tuple(span_start(a, d, x_left, start) for a, d in zip(left.values, dvdx, strict=True))
    return InterpolatedSpan(
        y, start, end, x_left, x_right, z_row + dzdx * start, dzdx, values, dvdx
    )


def _interpolated_spans(row: ScanRow, xs: list[float], interpolants, z_row: float, dzdx: float):
    """The `InterpolatedSpan` of each span of `row`, between the AET edges that bound it."""
    spans = []
    for start, end, _ in row.spans:
        k = _bounding_pair(row.aet, row.y, start, end)
        left, right = interpolants[row.aet[k].edge], interpolants[row.aet[k + 1].edge]
        spans.append(_span(row.y, start, end, xs[k], xs[k + 1], left, right, z_row, dzdx))
    return spans


def interpolate_rows(
    snapped: SnappedPolygon,
    plane: Plane,
    channels: np.ndarray,
    width: int,
    height: int,
    *,
    trace=None,
    polygon: int = 0,
) -> Iterator[tuple[int, list[InterpolatedSpan]]]:
    """Scan-convert one contour with ET/AET, interpolating depth and values; yield each row.

    The rows, AETs and spans are those of `scan_rows` (nonzero rule), the walk
    `scan_convert` makes, so the steps ``aet_update`` and ``span_rule`` drive
    it as they drive `scan_convert`. Each active edge also carries its values
    and d/dy; each span is interpolated between the two AET edges that bound
    it, x_k and x_k+1 with ceil(x_k) <= x_start and x_end <= ceil(x_k+1).
    Rows yield (y, spans) for every scanned row. A tracer receives the scan
    events (`edge_table_built`, `edges_retired`, `edges_activated`,
    `aet_sorted`, `span`) and, per row, `edge_values` and one `span_values`
    per span.

    Parameters
    ----------
    snapped : SnappedPolygon
        One contour on the integer grid.
    plane : Plane
        Its depth plane (`polygon_plane`); must not be edge-on.
    channels : (n, C) ndarray of float64
        Per-vertex quantities to interpolate (see `vertex_channels`).
    width, height : int
        Raster size; spans are clipped to it.

    Raises
    ------
    ValueError
        If a replaced ``span_rule`` returns a span that no two consecutive AET
        crossings bound.

    Examples
    --------
    >>> from scanviz import Polygon
    >>> from scanviz.raster.fixed import snap
    >>> square = snap(Polygon([(0, 0), (2, 0), (2, 2), (0, 2)]))
    >>> plane = polygon_plane(square, [0.0, 1.0, 1.0, 0.0])
    >>> channels = np.array([[0.0], [2.0], [2.0], [0.0]])
    >>> for y, spans in interpolate_rows(square, plane, channels, 4, 4):
    ...     print(y, [(x, z, v) for s in spans for x, z, v in span_samples(s)])
    0 [(0, 0.0, (0.0,)), (1, 0.5, (1.0,))]
    1 [(0, 0.0, (0.0,)), (1, 0.5, (1.0,))]
    2 []

    Row 2 is scanned to retire the edges (as in `scan_convert`); it has no span.
    """
    exact = np.int64 if snapped.compilable else int  # operand type of `crossing_x`, as compiled
    vertex_values = channels.tolist()
    table = bucketed_edge_table(snapped, height, trace=trace, polygon=polygon)
    interpolants: dict[int, EdgeInterpolant] = {}  # by edge id, for the active edges
    z_row, z_carry, previous_row = 0.0, 0.0, -2  # no row yet
    for row in scan_rows(snapped, table, width, height, trace=trace, polygon=polygon):
        y = row.y
        for edge in row.retired:
            interpolants.pop(edge.edge, None)
        for interpolant in interpolants.values():  # the values one row up
            interpolant.step()
        for edge in row.entering:
            interpolants[edge.edge] = _edge_interpolant(edge, snapped, vertex_values, y)
        if y == previous_row + 1:  # between rows: z_row += dz/dy
            z_row, z_carry = compensated_step(z_row, z_carry, plane.dzdy)
        else:
            z_row, z_carry = plane.depth(0.0, y), 0.0
        previous_row = y
        xs = [_crossing_float(item.x, table.edges[item.edge], exact) for item in row.aet]
        spans = _interpolated_spans(row, xs, interpolants, z_row, plane.dzdx)
        if trace is not None:
            _emit_values(trace, polygon, y, z_row, row.aet, xs, spans, interpolants, snapped)
        yield y, spans


def _emit_values(trace, polygon, y, z_row, aet, xs, spans, interpolants, snapped) -> None:
    """`edge_values` and `span_values` of row y, x in the caller's frame (`xs`: the AET's x)."""
    offset = snapped.shift / snapped.scale
    if aet and trace.wants("edge_values", polygon=polygon, y=y):
        entries = tuple(
            EdgeValueEntry(
                edge=item.edge,
                x=x + offset,
                values=tuple(interpolants[item.edge].values),
                dvdy=tuple(interpolants[item.edge].dvdy),
            )
            for item, x in zip(aet, xs, strict=True)
        )
        trace.emit(EdgeValues(polygon, y, float(z_row), entries))
    if spans and trace.wants("span_values", polygon=polygon, y=y):
        for span in spans:
            trace.emit(
                SpanValues.of(
                    polygon,
                    replace(
                        span,
                        x_left=span.x_left + offset,
                        x_right=span.x_right + offset,
                        z=float(span.z),
                        dzdx=float(span.dzdx),
                    ),
                )
            )

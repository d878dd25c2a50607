"""DISLOP_E: area coverage of a polygon, its boundary by the edge algorithm (Wang 1989, §4.3).

Each edge is walked column by column in its first-octant frame (as DISLOP_L,
`scanviz.antialias.line`); in every column it spans fully, the pixels it cuts
get the area on the polygon's side from `columns.edge_column`, whose flag says
which side is inside (flag 1: inside below the edge in that frame). The
interior comes from `scanviz.raster.scan_convert` (centre samples, unsnapped).

The dissertation leaves the ends of an edge to "the other edges" (§4.3, not
specified further). scanviz splits edges where they cross, so that each piece
has one inside side, and takes the exact area of the pixels a piece passes
through in its end columns (the vertex pixels) and of any pixel two pieces
cut: the polygon clipped to the pixel (Sutherland-Hodgman, signed areas), or,
where the pixel holds winding numbers of both signs or beyond +-1 (crossings,
overlapping contours), `scanviz.abuffer.area` on that pixel. So the result is
the exact nonzero-winding area of any polygon.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..abuffer.area import MAX_WORK, _coverage_kernel, area_coverage
from ..conventions import COORD_LIMIT
from ..geometry import Polygon
from ..raster import scan_convert
from ..raster.scan_compiled import has_three_distinct
from ..trace.events import DislopColumn
from . import columns
from ._inputs import as_tracer, finish, new_raster
from .line import canonical, raster_pixel, raster_pixel_compiled

SIDE_STEP = 1e-7  # how far beside a piece's midpoint its two sides are tested for inside
# Per pixel: the image and hit counts (8 + 8), the marks (1 + 1), the scan-converted mask (1).
PIXEL_BYTES = 19
PLUS, MINUS, MIXED = 1, 2, 4  # which pieces touch a pixel: winding 0|+1, 0|-1, anything else
CENTRE_MARGIN = 1e-6  # a fill sample this close to a crossing is decided by `scan_convert`
# Steps before a polygon is refused: each pair of edges is tested for a crossing, each piece
# tests both its sides against every edge, each fill row meets every edge (see `_work`).
MAX_STEPS = 2**31


def dislop_edge(polygon: object, width: int, height: int, *, trace: object = None):
    """Coverage of every pixel by a polygon: DISLOP_E on its boundary, scan conversion inside.

    Parameters
    ----------
    polygon : Polygon or array_like
        Anything `Polygon` accepts; the inside is nonzero winding.
    width, height : int
        Raster size in pixels, in 0..2**16.
    trace : None, True or Tracer
        Gets one ``dislop_column`` per column an edge spans fully (True: a new
        Recorder, returned with the image). The walk is the same either way.

    Returns
    -------
    (height, width) ndarray of float64
        Covered area of each pixel, row 0 at the bottom; with ``trace=True``
        the pair (image, Trace).

    Raises
    ------
    TypeError, ValueError
        As `Polygon`; or if the size is not an int in 0..2**16, or `trace` is
        not a tracer; or if the polygon needs more than `MAX_STEPS` steps
        (2**31): n**2 edge pairs tested for crossings, 2 n per boundary piece
        (an edge splits into a piece per crossing), n per raster row. So about
        25,000 vertices at most, or about 1,500 that cross each other everywhere.

    Examples
    --------
    >>> dislop_edge([(0.5, 0.5), (3.5, 0.5), (3.5, 2.0), (0.5, 2.0)], 4, 3)[::-1]
    array([[0.  , 0.  , 0.  , 0.  ],
           [0.5 , 1.  , 1.  , 0.5 ],
           [0.25, 0.5 , 0.5 , 0.25]])
    """
    polygon = Polygon(polygon)
    tracer = as_tracer(trace)
    image = new_raster(width, height, "dislop_edge", PIXEL_BYTES)
    height, width = image.shape
    starts = polygon.vertices
    ends = np.concatenate([np.roll(c, -1, axis=0) for c in polygon.contours])
    _check_work(starts, ends, height)
    if tracer is None:
        unsure, deferred = _edge_kernel(starts, ends, polygon.offsets, image)
        if unsure:  # a fill pixel whose centre is within rounding of an edge: decide it exactly
            inside = scan_convert(polygon, width, height, sample="center", subpixel_bits=None).mask
            for y, x in unsure:
                image[y, x] = inside[y, x]
        for y, x in deferred:  # pixels the kernel's exact area cannot mirror bit for bit
            image[y, x] = _exact_area(polygon, int(x), int(y))
    else:
        inside = scan_convert(polygon, width, height, sample="center", subpixel_bits=None).mask
        _edge_reference(polygon, starts, ends, inside, image, tracer)
    return finish(image, trace, tracer)


def _check_work(starts: np.ndarray, ends: np.ndarray, height: int) -> None:
    """Refuse, with the figure and the limit, a polygon whose walk would take over `MAX_STEPS` steps."""
    n = len(starts)
    least = n * n + n * height
    pieces = _count_pieces(starts, ends) if least <= MAX_STEPS else 0
    work = least + 2 * pieces * n
    if work > MAX_STEPS:
        figure = f"at least {least:.3g}" if not pieces else f"{work:.3g} for {pieces} pieces"
        raise ValueError(
            f"dislop_edge: the polygon's {n} edges need too many steps ({figure}, limit "
            f"{MAX_STEPS}): every pair of edges is tested for a crossing, every piece between "
            "crossings tests its two sides against every edge, every raster row every edge; "
            "use fewer vertices or fewer self-crossings"
        )


@njit(cache=True)
def _count_pieces(starts, ends):  # pragma: no cover - compiled
    """The pieces `_split_edges` walks, at most: each edge's crossings with the others, plus one."""
    d = ends - starts
    pieces = 0
    for k in range(len(starts)):
        if starts[k, 0] == ends[k, 0] and starts[k, 1] == ends[k, 1]:
            continue
        pieces += 1
        for j in range(len(starts)):
            denominator = d[k, 0] * d[j, 1] - d[k, 1] * d[j, 0]
            if denominator == 0.0:
                continue
            ox, oy = starts[j, 0] - starts[k, 0], starts[j, 1] - starts[k, 1]
            t = (ox * d[j, 1] - oy * d[j, 0]) / denominator
            u = (ox * d[k, 1] - oy * d[k, 0]) / denominator
            pieces += 0.0 < t < 1.0 and 0.0 <= u <= 1.0
    return pieces


def _edge_reference(polygon: Polygon, starts, ends, inside, image, tracer) -> None:
    hits = np.zeros(image.shape, dtype=np.int64)  # boundary pieces cutting each pixel
    needs_exact = np.zeros(image.shape, dtype=bool)
    touched = np.zeros(image.shape, dtype=np.int8)  # PLUS | MINUS | MIXED of all pieces
    for a, b in _pieces(starts, ends):
        left, right = (_winding(p, starts, ends) for p in _beside(a, b))
        kind = PLUS if {left, right} == {0, 1} else MINUS if {left, right} == {0, -1} else MIXED
        flag = _flag(a, b, left != 0) if (left != 0) != (right != 0) else None
        _walk_piece(a, b, flag, kind, image, hits, needs_exact, touched, tracer)
    image[hits == 0] = inside[hits == 0]
    for y, x in zip(*np.nonzero(needs_exact | (hits > 1)), strict=True):
        simple = touched[y, x] in (PLUS, MINUS)
        image[y, x] = (_clipped_area if simple else _exact_area)(polygon, int(x), int(y))


def _pieces(starts: np.ndarray, ends: np.ndarray):
    """Yield the non-degenerate pieces (a, b) of every edge, split where other edges cross it."""
    d = ends - starts
    for k, (a, b) in enumerate(zip(starts, ends, strict=True)):
        if np.array_equal(a, b):
            continue
        denominator = d[k, 0] * d[:, 1] - d[k, 1] * d[:, 0]  # 0: parallel, no crossing point
        offset = starts - a
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (offset[:, 0] * d[:, 1] - offset[:, 1] * d[:, 0]) / denominator  # along edge k
            u = (offset[:, 0] * d[k, 1] - offset[:, 1] * d[k, 0]) / denominator  # along the other
        crossing = (denominator != 0) & (t > 0) & (t < 1) & (u >= 0) & (u <= 1)
        cuts = np.unique(np.concatenate([[0.0], t[crossing], [1.0]]))
        points = [a + c * d[k] for c in cuts[1:-1]]
        corners = [a.tolist(), *(p.tolist() for p in points), b.tolist()]
        for p, q in zip(corners, corners[1:], strict=False):
            if _walkable(p[0], p[1], q[0], q[1]):
                yield p, q


def _beside(a, b) -> tuple[np.ndarray, np.ndarray]:
    """Two points just left and just right of the midpoint of a -> b."""
    direction = np.subtract(b, a)
    normal = np.array([-direction[1], direction[0]]) / math.hypot(*direction)
    middle = 0.5 * (np.asarray(a) + np.asarray(b))
    return middle + SIDE_STEP * normal, middle - SIDE_STEP * normal


def _winding(point: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> int:
    """Winding number of the polygon around `point` (crossings of a ray toward +x)."""
    (px, py), (ax, ay), (bx, by) = point, starts.T, ends.T
    cross = (bx - ax) * (py - ay) - (px - ax) * (by - ay)  # > 0: point left of a -> b
    up = (ay <= py) & (py < by) & (cross > 0)
    down = (by <= py) & (py < ay) & (cross < 0)
    return int(up.sum() - down.sum())


def _flag(a, b, left_inside: bool) -> int:
    """DISLOP_E's flag of piece a -> b in its first-octant frame: 1 if inside is below."""
    u0, v0, u1, v1, steep, flip = canonical(a, b)
    point = _beside(a, b)[0 if left_inside else 1] - 0.5  # an inside point, centred coordinates
    pu, pv = (point[1], point[0]) if steep else (point[0], point[1])
    pv = -pv if flip else pv
    return 1 if pv < v0 + (pu - u0) * (v1 - v0) / (u1 - u0) else 0


@njit(cache=True)
def _walkable(ax, ay, bx, by) -> bool:
    """Whether piece a -> b is still a segment in the walk's centred coordinates (ours - 1/2).

    A piece shorter than the rounding of its coordinates there, e.g. (0, 1e-104) -> (0, 0),
    has no slope and no area; the pieces beside it mark its pixels.
    """
    return ax - 0.5 != bx - 0.5 or ay - 0.5 != by - 0.5


def _walk_piece(a, b, flag, kind, image, hits, needs_exact, touched, tracer) -> None:
    """Write the cut pixels of the full columns of a boundary piece; mark its end columns' pixels.

    `flag` None: not a boundary piece (the same inside-ness on both sides); it
    only marks the pixels it touches, for the choice of the exact method.
    """
    u0, v0, u1, v1, steep, flip = canonical(a, b)
    slope = (v1 - v0) / (u1 - u0)
    first, last = math.ceil(u0 + 0.5), math.floor(u1 - 0.5)  # columns the piece spans fully
    for column in range(max(first, 0), min(last, image.shape[0 if steep else 1] - 1) + 1):
        centre = v0 + (column - u0) * slope
        row = math.ceil(centre - 0.5)
        dxy = centre - row
        up, mid, low, cv, corner, branch = columns.edge_column(slope, dxy, 1 if flag else 0)
        neighbour = row + 1 if dxy > 0.0 else row - 1
        cut = 2 if branch == 1 and cv > 0.0 else 1  # cv == 0 only touches the neighbour's corner
        for r, area in ((row, mid), (neighbour, up + low))[:cut]:
            pixel = _pixel(column, r, steep, flip, image.shape)
            if pixel is not None:
                touched[pixel] |= kind
                if flag is not None:
                    image[pixel], hits[pixel] = area, hits[pixel] + 1
        if flag is not None and tracer is not None:
            x, y = raster_pixel(column, row, steep, flip)
            if tracer.wants("dislop_column", y=y):
                major, name = "y" if steep else "x", columns.EDGE_BRANCHES[branch]
                event = (x, y, major, slope, dxy, cv, corner, name, up, mid, low, 0.0)
                tracer.emit(DislopColumn(*event))
    for column in {math.floor(u0 + 0.5), math.floor(u1 + 0.5)} - set(range(first, last + 1)):
        left, right = max(u0, column - 0.5), min(u1, column + 0.5)
        low_v, high_v = v0 + (left - u0) * slope, v0 + (right - u0) * slope
        for row in range(math.ceil(low_v - 0.5), math.floor(high_v + 0.5) + 1):
            pixel = _pixel(column, row, steep, flip, image.shape)
            if pixel is not None:
                touched[pixel] |= kind
                needs_exact[pixel] |= flag is not None
    for x, y in (a, b):  # every pixel whose closed square holds an end, also across a border
        for py in range(max(math.ceil(y) - 1, 0), min(math.floor(y), image.shape[0] - 1) + 1):
            for px in range(max(math.ceil(x) - 1, 0), min(math.floor(x), image.shape[1] - 1) + 1):
                touched[py, px] |= kind
                needs_exact[py, px] |= flag is not None


def _pixel(column, row, steep, flip, shape) -> tuple[int, int] | None:
    """The (y, x) index of first-octant pixel (column, row), or None off the raster."""
    x, y = raster_pixel(column, row, steep, flip)
    return (y, x) if 0 <= x < shape[1] and 0 <= y < shape[0] else None


def _clipped_area(polygon: Polygon, x: int, y: int) -> float:
    """Area in pixel (x, y) by clipping every contour, signed and summed (windings 0 and +-1)."""
    area = 0.0
    for contour in polygon.contours:
        work = np.empty((4, 2 * len(contour) + 8))
        xs, ys = np.ascontiguousarray(contour[:, 0]), np.ascontiguousarray(contour[:, 1])
        box = (float(x), float(y), x + 1.0, y + 1.0)
        area += columns.clip_area_compiled(xs, ys, len(contour), *box, work)
    return min(abs(area), 1.0)


def _exact_area(polygon: Polygon, x: int, y: int) -> float:
    """Area in pixel (x, y) by `area_coverage` of a one-pixel raster there (any winding)."""
    shifted = Polygon([contour - (x, y) for contour in polygon.contours])  # exact: integer shift
    return float(area_coverage(shifted, 1, 1, subpixel_bits=None)[0, 0])


# ---------------------------------------------------------------- the compiled kernel
# The same float arithmetic as the reference above, in the same order (traced == untraced).

_canonical_compiled = njit(cache=True)(canonical)


@njit(cache=True)
def _hypot(x, y):  # pragma: no cover - compiled
    """`math.hypot(x, y)` as CPython computes it (vector_norm), which numba's differs from."""
    x, y = abs(x), abs(y)
    largest = max(x, y)
    if largest == 0.0:
        return largest
    if math.frexp(largest)[1] < -1023:  # deep subnormal: bring both up into the normal range
        return 2.0**-1022 * _hypot(x / 2.0**-1022, y / 2.0**-1022)
    scale = math.ldexp(1.0, -math.frexp(largest)[1])
    total, frac1, frac2 = 1.0, 0.0, 0.0
    for value in (x * scale, y * scale):
        square, square_lo = _exact_product(value, value)
        total, total_lo = _fast_sum(total, square)
        frac1 += square_lo
        frac2 += total_lo
    h = math.sqrt(total - 1.0 + (frac1 + frac2))
    square, square_lo = _exact_product(-h, h)
    total, total_lo = _fast_sum(total, square)
    frac1 += square_lo
    frac2 += total_lo
    h += (total - 1.0 + (frac1 + frac2)) / (2.0 * h)  # differential correction
    return h / scale


@njit(cache=True)
def _exact_product(a, b):  # pragma: no cover - compiled
    """(a b rounded, its exact error): Dekker's product, |a|, |b| < 2**996."""
    product = a * b
    split = 134217729.0  # 2**27 + 1
    a_hi = split * a - (split * a - a)
    b_hi = split * b - (split * b - b)
    a_lo, b_lo = a - a_hi, b - b_hi
    return product, ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo


@njit(cache=True)
def _fast_sum(a, b):  # pragma: no cover - compiled
    """(a + b rounded, its exact error) for |a| >= |b|."""
    total = a + b
    return total, b - (total - a)


@njit(cache=True)
def _beside_compiled(ax, ay, bx, by):  # pragma: no cover - compiled `_beside`
    dx, dy = bx - ax, by - ay
    length = _hypot(dx, dy)
    nx, ny = -dy / length, dx / length
    mx, my = 0.5 * (ax + bx), 0.5 * (ay + by)
    return mx + SIDE_STEP * nx, my + SIDE_STEP * ny, mx - SIDE_STEP * nx, my - SIDE_STEP * ny


@njit(cache=True)
def _winding_compiled(px, py, starts, ends):  # pragma: no cover - compiled `_winding`
    winding = 0
    for e in range(len(starts)):
        ax, ay, bx, by = starts[e, 0], starts[e, 1], ends[e, 0], ends[e, 1]
        if (ay <= py < by) or (by <= py < ay):
            cross = (bx - ax) * (py - ay) - (px - ax) * (by - ay)
            if ay <= py < by and cross > 0:
                winding += 1
            elif by <= py < ay and cross < 0:
                winding -= 1
    return winding


@njit(cache=True)
def _flag_compiled(ax, ay, bx, by, left_inside):  # pragma: no cover - compiled `_flag`
    u0, v0, u1, v1, steep, flip = _canonical_compiled((ax, ay), (bx, by))
    lx, ly, rx, ry = _beside_compiled(ax, ay, bx, by)
    px, py = (lx - 0.5, ly - 0.5) if left_inside else (rx - 0.5, ry - 0.5)
    pu, pv = (py, px) if steep else (px, py)
    pv = -pv if flip else pv
    return 1 if pv < v0 + (pu - u0) * (v1 - v0) / (u1 - u0) else 0


@njit(cache=True)
def _mark(touched, needs_exact, x, y, kind, boundary):  # pragma: no cover - compiled
    """Mark raster pixel (x, y), if on the raster, as touched by a piece of this kind."""
    if 0 <= x < touched.shape[1] and 0 <= y < touched.shape[0]:
        touched[y, x] |= kind
        needs_exact[y, x] |= boundary


@njit(cache=True)
def _walk_piece_compiled(ax, ay, bx, by, flag, kind, image, hits, needs_exact, touched):
    # pragma: no cover - compiled `_walk_piece`; flag -1: not a boundary piece
    u0, v0, u1, v1, steep, flip = _canonical_compiled((ax, ay), (bx, by))
    slope = (v1 - v0) / (u1 - u0)
    first, last = math.ceil(u0 + 0.5), math.floor(u1 - 0.5)
    for column in range(max(first, 0), min(last, image.shape[0 if steep else 1] - 1) + 1):
        centre = v0 + (column - u0) * slope
        row = math.ceil(centre - 0.5)
        dxy = centre - row
        up, mid, low, cv, _, branch = columns.edge_column_compiled(
            slope, dxy, 1 if flag == 1 else 0
        )
        neighbour = row + 1 if dxy > 0.0 else row - 1
        cut = 2 if branch == 1 and cv > 0.0 else 1
        for k in range(cut):
            r, area = (row, mid) if k == 0 else (neighbour, up + low)
            x, y = raster_pixel_compiled(column, r, steep, flip)
            if 0 <= x < image.shape[1] and 0 <= y < image.shape[0]:
                touched[y, x] |= kind
                if flag >= 0:
                    image[y, x], hits[y, x] = area, hits[y, x] + 1
    end_columns = (math.floor(u0 + 0.5), math.floor(u1 + 0.5))
    for k in range(2):
        column = end_columns[k]
        if (k == 1 and column == end_columns[0]) or first <= column <= last:
            continue
        left, right = max(u0, column - 0.5), min(u1, column + 0.5)
        low_v, high_v = v0 + (left - u0) * slope, v0 + (right - u0) * slope
        for row in range(math.ceil(low_v - 0.5), math.floor(high_v + 0.5) + 1):
            x, y = raster_pixel_compiled(column, row, steep, flip)
            _mark(touched, needs_exact, x, y, kind, flag >= 0)
    for x, y in ((ax, ay), (bx, by)):
        for py in range(max(math.ceil(y) - 1, 0), min(math.floor(y), image.shape[0] - 1) + 1):
            for px in range(max(math.ceil(x) - 1, 0), min(math.floor(x), image.shape[1] - 1) + 1):
                _mark(touched, needs_exact, px, py, kind, flag >= 0)


@njit(cache=True)
def _piece_compiled(ax, ay, bx, by, starts, ends, image, hits, needs_exact, touched):
    # pragma: no cover - compiled: one piece of the reference's loop
    lx, ly, rx, ry = _beside_compiled(ax, ay, bx, by)
    left, right = _winding_compiled(lx, ly, starts, ends), _winding_compiled(rx, ry, starts, ends)
    low, high = min(left, right), max(left, right)
    kind = PLUS if (low, high) == (0, 1) else MINUS if (low, high) == (-1, 0) else MIXED
    flag = _flag_compiled(ax, ay, bx, by, left != 0) if (left != 0) != (right != 0) else -1
    _walk_piece_compiled(ax, ay, bx, by, flag, kind, image, hits, needs_exact, touched)


@njit(cache=True)
def _split_edges(starts, ends, image, hits, needs_exact, touched):  # pragma: no cover - compiled
    """`_pieces` and the per-piece work: every edge split where other edges cross it."""
    d = ends - starts
    cuts = np.empty(len(starts) + 2)
    for k in range(len(starts)):
        ax, ay, bx, by = starts[k, 0], starts[k, 1], ends[k, 0], ends[k, 1]
        if ax == bx and ay == by:
            continue
        count = 1
        cuts[0] = 0.0
        for j in range(len(starts)):
            denominator = d[k, 0] * d[j, 1] - d[k, 1] * d[j, 0]
            if denominator == 0.0:
                continue
            ox, oy = starts[j, 0] - ax, starts[j, 1] - ay
            t = (ox * d[j, 1] - oy * d[j, 0]) / denominator
            u = (ox * d[k, 1] - oy * d[k, 0]) / denominator
            if 0.0 < t < 1.0 and 0.0 <= u <= 1.0:
                cuts[count] = t
                count += 1
        cuts[count] = 1.0
        ordered = np.unique(cuts[: count + 1])
        px, py = ax, ay
        for i in range(1, len(ordered)):
            last = i == len(ordered) - 1
            qx = bx if last else ax + ordered[i] * d[k, 0]
            qy = by if last else ay + ordered[i] * d[k, 1]
            if _walkable(px, py, qx, qy):
                _piece_compiled(px, py, qx, qy, starts, ends, image, hits, needs_exact, touched)
            px, py = qx, qy


@njit(cache=True)
def _clipped_area_compiled(xs, ys, offsets, x, y, work):  # pragma: no cover - `_clipped_area`
    area = 0.0
    for c in range(len(offsets) - 1):
        contour_xs, contour_ys = xs[offsets[c] : offsets[c + 1]], ys[offsets[c] : offsets[c + 1]]
        n = offsets[c + 1] - offsets[c]
        area += columns.clip_area_compiled(
            contour_xs, contour_ys, n, float(x), float(y), x + 1.0, y + 1.0, work
        )
    return min(abs(area), 1.0)


@njit(cache=True)
def _exact_area_compiled(starts, ends, offsets, x, y):  # pragma: no cover - `_exact_area`
    """`_exact_area`, or -1.0 where it would not give the same bits (the caller defers).

    `area_coverage` of the shifted polygon sees only the edges crossing its one
    row, sorted stably by their lower y: the same kernel on just those gives
    the same area. Deferred: a shift that `Polygon` would refuse (past 2**20,
    or merging a contour to under 3 distinct vertices) and a pixel past the
    kernel's work limit (`area_coverage` raises).
    """
    shift = np.array([float(x), float(y)])
    for c in range(len(offsets) - 1):
        if not has_three_distinct(starts[offsets[c] : offsets[c + 1]] - shift):
            return -1.0
    count = 0
    ax, ay = np.empty(len(starts)), np.empty(len(starts))
    bx, by = np.empty(len(starts)), np.empty(len(starts))
    winding = np.empty(len(starts), np.int64)
    for e in range(len(starts)):
        x0, y0, x1, y1 = starts[e, 0] - x, starts[e, 1] - y, ends[e, 0] - x, ends[e, 1] - y
        if max(abs(x0), abs(y0)) > COORD_LIMIT:
            return -1.0
        if y0 == y1 or max(y0, y1) <= 0.0 or min(y0, y1) >= 1.0:
            continue  # horizontal edges bound no strip; the others never enter the row
        up = y1 > y0
        ax[count], ay[count] = (x0, y0) if up else (x1, y1)
        bx[count], by[count] = (x1, y1) if up else (x0, y0)
        winding[count] = 1 if up else -1
        count += 1
    order = np.argsort(ay[:count], kind="mergesort")
    rows, work = _coverage_kernel(
        ax[:count][order], ay[:count][order], bx[:count][order], by[:count][order],
        winding[:count][order], 1, 1, False, 0, 1, MAX_WORK,
    )  # fmt: skip
    if work > MAX_WORK:
        return -1.0
    return min(max(rows[0, 0], 0.0), 1.0)


@njit(cache=True)
def _centre_samples(starts, ends, shape):  # pragma: no cover - compiled
    """Nonzero winding at every pixel centre, and where that float decision may be wrong.

    `scan_convert` (centre samples, unsnapped) decides exactly; a crossing x
    computed in float64 is within 1e-8 of the exact one for coordinates up to
    2**20, so a centre farther than `CENTRE_MARGIN` from every crossing of its
    row gets the same answer. Rows and their active edges are compared exactly.
    """
    inside = np.zeros(shape, np.bool_)
    unsure = np.zeros(shape, np.bool_)
    crossings, directions = np.empty(len(starts)), np.empty(len(starts), np.int64)
    for y in range(shape[0]):
        sample = y + 0.5
        count = 0
        for e in range(len(starts)):
            (x0, y0), (x1, y1) = (starts[e, 0], starts[e, 1]), (ends[e, 0], ends[e, 1])
            if y1 < y0:
                x0, y0, x1, y1 = x1, y1, x0, y0
            if y0 <= sample < y1:
                crossings[count] = x0 + (sample - y0) * (x1 - x0) / (y1 - y0)
                directions[count] = 1 if ends[e, 1] > starts[e, 1] else -1
                count += 1
        order = np.argsort(crossings[:count])
        winding, next_crossing = 0, 0
        for x in range(shape[1]):
            centre = x + 0.5
            while next_crossing < count and crossings[order[next_crossing]] < centre:
                winding += directions[order[next_crossing]]
                next_crossing += 1
            inside[y, x] = winding != 0
        for k in range(count):
            near = crossings[k] - 0.5
            for x in range(max(math.ceil(near - CENTRE_MARGIN), 0), shape[1]):
                if x > near + CENTRE_MARGIN:
                    break
                unsure[y, x] = True
    return inside, unsure


@njit(cache=True)
def _edge_kernel(starts, ends, offsets, image):  # pragma: no cover - compiled
    """The reference's loop untraced; returns the (y, x) fill pixels it is unsure of, and
    the pixels left to `_exact_area`."""
    hits = np.zeros(image.shape, np.int64)
    needs_exact = np.zeros(image.shape, np.bool_)
    touched = np.zeros(image.shape, np.int8)
    _split_edges(starts, ends, image, hits, needs_exact, touched)
    inside, unsure_inside = _centre_samples(starts, ends, image.shape)
    xs, ys = starts[:, 0].copy(), starts[:, 1].copy()
    work = np.empty((4, 2 * int(np.max(offsets[1:] - offsets[:-1])) + 8))
    unsure, deferred = [(0, 0)][:0], [(0, 0)][:0]
    for y in range(image.shape[0]):
        for x in range(image.shape[1]):
            exact = needs_exact[y, x] or hits[y, x] > 1
            if hits[y, x] == 0:
                image[y, x] = 1.0 if inside[y, x] else 0.0
                if unsure_inside[y, x] and not exact:
                    unsure.append((y, x))
            if not exact:
                continue
            if touched[y, x] == PLUS or touched[y, x] == MINUS:
                image[y, x] = _clipped_area_compiled(xs, ys, offsets, x, y, work)
            else:
                area = _exact_area_compiled(starts, ends, offsets, x, y)
                if area < 0.0:
                    deferred.append((y, x))
                image[y, x] = area
    return unsure, deferred

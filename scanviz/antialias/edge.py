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

from ..abuffer.area import area_coverage
from ..geometry import Polygon
from ..raster import scan_convert
from ..trace.events import DislopColumn
from . import columns
from ._inputs import as_tracer, finish, new_raster
from .line import canonical, raster_pixel

SIDE_STEP = 1e-7  # how far beside a piece's midpoint its two sides are tested for inside
# Per pixel: the image and hit counts (8 + 8), the marks (1 + 1), the scan-converted mask (1).
PIXEL_BYTES = 19
PLUS, MINUS, MIXED = 1, 2, 4  # which pieces touch a pixel: winding 0|+1, 0|-1, anything else


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
        not a tracer.

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
    inside = scan_convert(polygon, width, height, sample="center", subpixel_bits=None).mask
    hits = np.zeros(image.shape, dtype=np.int64)  # boundary pieces cutting each pixel
    needs_exact = np.zeros(image.shape, dtype=bool)
    touched = np.zeros(image.shape, dtype=np.int8)  # PLUS | MINUS | MIXED of all pieces
    starts = polygon.vertices
    ends = np.concatenate([np.roll(c, -1, axis=0) for c in polygon.contours])
    for a, b in _pieces(starts, ends):
        left, right = (_winding(p, starts, ends) for p in _beside(a, b))
        kind = PLUS if {left, right} == {0, 1} else MINUS if {left, right} == {0, -1} else MIXED
        flag = _flag(a, b, left != 0) if (left != 0) != (right != 0) else None
        _walk_piece(a, b, flag, kind, image, hits, needs_exact, touched, tracer)
    image[hits == 0] = inside[hits == 0]
    for y, x in zip(*np.nonzero(needs_exact | (hits > 1)), strict=True):
        simple = touched[y, x] in (PLUS, MINUS)
        image[y, x] = (_clipped_area if simple else _exact_area)(polygon, int(x), int(y))
    return finish(image, trace, tracer)


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
            if p != q:
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

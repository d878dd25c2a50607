"""Exact area coverage: the area of (polygon ∩ pixel square) for every pixel it touches.

This is the "exact area" a-buffer fragments carry next to their pixel masks,
and the reference every anti-aliasing method is measured against.

Vertices are snapped as the scan converter snaps them (``rint(v * 2**bits) /
2**bits``), so coverage and sample masks describe the same polygon.

Algorithm (one compiled pass, bottom row to top):

1. Per pixel row, split the row into horizontal strips at every vertex y and
   every y where two active edges cross, one strip at a time from the bottom:
   the next crossing above a height is between two edges adjacent in x order
   there (Bentley-Ottmann), so memory stays linear in the edges. Inside a
   strip the edges are non-crossing segments, so their left-to-right order
   is fixed.
2. Sort the strip's edges by x at mid-height and walk them with a winding
   count; an edge where "inside" (nonzero or odd winding) switches on or off
   is a left or right boundary of an inside trapezoid.
3. The area of a trapezoid between boundaries L and R within column c is
   ``F_R(c) - F_L(c)`` with ``F_E(c) = ∫ clamp(x_E(t) - c, 0, 1) dt`` over the
   strip: in closed form, the time the edge spends in the column times its
   mean offset there, plus the time it spends right of the column. Columns
   left of an edge get the full strip height, an integer multiple of the
   strip height per column (a prefix sum of boundary signs), so shapes that
   miss a pixel leave exactly 0 there.

Work is the strips times the edges of their rows, so it grows with the
square of the vertices or crossings in one pixel row. Past MAX_WORK edge
visits a polygon is refused: at once when a lower bound (one strip per
distinct vertex height and per edge crossing, counted by sorting) already
exceeds it, else when the kernel gets there.

Rounding: coordinates are float64, so the per-pixel error is a few ulps of
the coordinate magnitude (about 1e-13 for a 256-pixel raster).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..conventions import RULES, check_choice, check_raster_size, check_subpixel_bits
from ..geometry import Polygon
from ..limits import check_memory

EDGE_BYTES = 12 * 8  # per edge: its arrays, the active list and the per-strip x values
MAX_WORK = 2**26  # edge visits (strips x edges of a row) before a polygon is refused


def snapped_vertices(polygon: Polygon, subpixel_bits: int | None) -> np.ndarray:
    """All vertices snapped to 1/2**bits pixel as `raster.fixed.snap` does: (M, 2) float64."""
    vertices = polygon.vertices
    if subpixel_bits is None:
        return vertices
    return np.rint(vertices * 2.0**subpixel_bits) / 2.0**subpixel_bits


def _edge_arrays(vertices: np.ndarray, offsets: np.ndarray) -> tuple[np.ndarray, ...]:
    """Non-horizontal edges as (ax, ay, bx, by, winding) with ay < by, sorted by ay."""
    starts = np.arange(offsets[-1])
    contour = np.searchsorted(offsets, starts, side="right") - 1
    following = np.where(starts + 1 == offsets[contour + 1], offsets[contour], starts + 1)
    x0, y0 = vertices[starts, 0], vertices[starts, 1]
    x1, y1 = vertices[following, 0], vertices[following, 1]
    keep = y0 != y1  # horizontal edges bound no strip
    x0, y0, x1, y1 = x0[keep], y0[keep], x1[keep], y1[keep]
    up = y1 > y0
    ax, ay = np.where(up, x0, x1), np.where(up, y0, y1)
    bx, by = np.where(up, x1, x0), np.where(up, y1, y0)
    order = np.argsort(ay, kind="stable")
    winding = np.where(up, 1, -1).astype(np.int64)
    return ax[order], ay[order], bx[order], by[order], winding[order]


@njit(cache=True, inline="always")
def _x_at(ax, ay, bx, by, y):
    """x of the edge at height y, exact at its ends."""
    if y == ay:
        return ax
    if y == by:
        return bx
    return ax + (y - ay) * (bx - ax) / (by - ay)


@njit(cache=True)
def _add_edge(row, counts, xa, xb, h, sign, width):
    """Add sign * F_E(c) for one boundary edge of a strip of height h to `row`.

    Columns left of the edge's first column get the full height h; that part
    is counted in `counts` (boundary signs) and added as an integer times h.
    Returns the first column (clamped to 0..width), where `counts` changed.
    """
    lo, hi = min(xa, xb), max(xa, xb)
    first = min(max(int(np.floor(lo)), 0), width)
    counts[first] -= sign  # from column `first` on, this edge no longer lies right of the column
    last = min(int(np.floor(hi)), width - 1)
    span = hi - lo
    for c in range(first, last + 1):
        if span == 0.0:
            row[c] += sign * h * (lo - c)
            continue
        u0, u1 = max(lo, float(c)), min(hi, c + 1.0)
        inside_time = h * (u1 - u0) / span
        right_time = h * (hi - u1) / span
        row[c] += sign * (inside_time * (0.5 * (u0 + u1) - c) + right_time)
    return first


@njit(cache=True)
def _crossing(ax, ay, bx, by, e, f, y):
    """Where edges e and f cross strictly inside row [y, y + 1], else +inf.

    Found from the pair's ends within the row alone, so the same pair gives
    the same height whichever strip asks.
    """
    lo = max(max(ay[e], ay[f]), y)
    hi = min(min(by[e], by[f]), y + 1.0)
    if hi <= lo:
        return np.inf
    d_lo = _x_at(ax[e], ay[e], bx[e], by[e], lo) - _x_at(ax[f], ay[f], bx[f], by[f], lo)
    d_hi = _x_at(ax[e], ay[e], bx[e], by[e], hi) - _x_at(ax[f], ay[f], bx[f], by[f], hi)
    if d_lo * d_hi < 0.0:
        return lo + (hi - lo) * (d_lo / (d_lo - d_hi))
    return np.inf


@njit(cache=True)
def _strip_top(ax, ay, bx, by, present, n, s, t, y, x_lo, x_hi):
    """The first height in (s, t] where two of the n `present` edges cross, else t.

    Sorted by x just above s (x at s, ties by x at t), the first pair to cross
    is adjacent in that order (Bentley-Ottmann): a pair whose order at t is
    reversed crosses, and the earliest such crossing ends the strip.
    """
    for i in range(n):
        e = present[i]
        x_lo[i] = _x_at(ax[e], ay[e], bx[e], by[e], s)
        x_hi[i] = _x_at(ax[e], ay[e], bx[e], by[e], t)
    by_top = np.argsort(x_hi[:n], kind="mergesort")
    order = by_top[np.argsort(x_lo[:n][by_top], kind="mergesort")]
    # A pair reversed at t that crosses at s (rounding may leave it unswapped there) is swapped.
    for j in range(1, n):
        k = j
        while k > 0 and x_hi[order[k]] < x_hi[order[k - 1]]:
            if s < _crossing(ax, ay, bx, by, present[order[k - 1]], present[order[k]], y):
                break
            order[k - 1], order[k] = order[k], order[k - 1]
            k -= 1
    top = t
    for j in range(n - 1):
        left, right = order[j], order[j + 1]
        if x_hi[right] < x_hi[left]:
            crossing = _crossing(ax, ay, bx, by, present[left], present[right], y)
            if s < crossing < top:
                top = crossing
    return top


@njit(cache=True)
def _add_strip(row, counts, ax, ay, bx, by, winding, present, n, y_lo, y_hi, mids, width, evenodd):
    """Add the inside trapezoids of strip [y_lo, y_hi], bounded by the n `present` edges, to `row`."""
    h = y_hi - y_lo
    y_mid = 0.5 * (y_lo + y_hi)
    for i in range(n):
        e = present[i]
        mids[i] = _x_at(ax[e], ay[e], bx[e], by[e], y_mid)
    order = np.argsort(mids[:n], kind="mergesort")  # no crossing inside: one order throughout
    # Walk left to right with the winding count; add each inside trapezoid's boundaries.
    wind = 0
    c_lo, c_hi = width, 0  # the range of `counts` this strip touches
    for j in range(n):
        e = present[order[j]]
        was_inside = (wind % 2 != 0) if evenodd else (wind != 0)
        wind += winding[e]
        is_inside = (wind % 2 != 0) if evenodd else (wind != 0)
        if was_inside == is_inside:
            continue
        xa = _x_at(ax[e], ay[e], bx[e], by[e], y_lo)
        xb = _x_at(ax[e], ay[e], bx[e], by[e], y_hi)
        first = _add_edge(row, counts, xa, xb, h, -1 if is_inside else 1, width)
        c_lo, c_hi = min(c_lo, first), max(c_hi, first)
    # A left boundary (sign -1) makes `counts` +1 from its first column on: the columns
    # between a left and a right boundary's first columns lie fully inside.
    covered = 0
    for c in range(c_lo, c_hi):
        covered += counts[c]
        counts[c] = 0
        if covered != 0:
            row[c] += covered * h
    counts[c_hi] = 0


@njit(cache=True)
def _update_active(ay, by, active, n_active, next_edge, y):
    """Active edge table for row y: retire the edges below it, activate those starting in it.

    Returns the new (n_active, next_edge); `active[:n_active]` holds the row's edges.
    """
    kept = 0
    for k in range(n_active):
        if by[active[k]] > y:
            active[kept] = active[k]
            kept += 1
    n_active = kept
    while next_edge < len(ay) and ay[next_edge] < y + 1.0:
        if by[next_edge] > y:
            active[n_active] = next_edge
            n_active += 1
        next_edge += 1
    return n_active, next_edge


@njit(cache=True)
def _inversions(values, scratch):
    """Pairs i < j with values[i] > values[j], by a bottom-up merge sort that overwrites both arrays."""
    n = len(values)
    inversions = 0
    run = 1
    while run < n:
        for lo in range(0, n, 2 * run):
            mid, hi = min(lo + run, n), min(lo + 2 * run, n)
            i, j = lo, mid
            for k in range(lo, hi):
                if j < hi and (i == mid or values[j] < values[i]):
                    scratch[k] = values[j]
                    inversions += mid - i  # values[j] is below every value left in [i, mid)
                    j += 1
                else:
                    scratch[k] = values[i]
                    i += 1
        values, scratch = scratch, values
        run *= 2
    return inversions


@njit(cache=True)
def _slab_crossings(ax, ay, bx, by, active, n_active, lo, hi, x_lo, x_hi, scratch):
    """Crossings strictly inside [lo, hi] of the active edges spanning it: pairs whose x order flips."""
    n = 0
    for k in range(n_active):
        e = active[k]
        if ay[e] <= lo and by[e] >= hi:
            x_lo[n] = _x_at(ax[e], ay[e], bx[e], by[e], lo)
            x_hi[n] = _x_at(ax[e], ay[e], bx[e], by[e], hi)
            n += 1
    by_hi = np.argsort(x_hi[:n], kind="mergesort")
    order = by_hi[np.argsort(x_lo[:n][by_hi], kind="mergesort")]  # by x at lo, ties by x at hi
    return _inversions(x_hi[:n][order], scratch)


@njit(cache=True)
def _least_work(ax, ay, bx, by, row0, row1, max_work):
    """A lower bound on the kernel's edge visits in rows [row0, row1); stops past `max_work`.

    The distinct vertex heights inside a row cut it into slabs that every
    active edge spans or misses; a row has at least one strip per slab plus
    one per crossing inside a slab (a pair of the slab's edges whose x order
    at its bottom and top differ), and each strip visits every active edge.
    O(n log n) per slab; crossings at one shared height count once per pair.
    """
    count = len(ay)
    active = np.empty(count, np.int64)
    heights = np.empty(2 * count + 2)
    x_lo, x_hi, scratch = np.empty(count), np.empty(count), np.empty(count)
    work = 0.0
    next_edge = n_active = 0
    for y in range(row0, row1):
        top = y + 1.0
        n_active, next_edge = _update_active(ay, by, active, n_active, next_edge, y)
        heights[0], heights[1] = y, top
        n_heights = 2
        for k in range(n_active):
            for v in (ay[active[k]], by[active[k]]):
                if y < v < top:
                    heights[n_heights] = v
                    n_heights += 1
        slabs = np.unique(heights[:n_heights])
        work += n_active * (len(slabs) - 1.0)
        for j in range(len(slabs) - 1):
            if work > max_work:
                return work
            crossings = _slab_crossings(
                ax, ay, bx, by, active, n_active, slabs[j], slabs[j + 1], x_lo, x_hi, scratch
            )
            work += n_active * float(crossings)
    return work


@njit(cache=True)
def _coverage_kernel(ax, ay, bx, by, winding, width, height, evenodd, row0, row1, max_work):
    """Exact coverage of rows [row0, row1): ((row1 - row0, width) float64 array, work).

    Memory is linear in the edges: strips are found one at a time, bottom to top.
    Work counts edges visited, strip by strip; past `max_work` the kernel
    stops and returns the work reached (the caller refuses the polygon).
    """
    work = 0
    count = len(ay)
    image = np.zeros((max(row1 - row0, 0), width))
    counts = np.zeros(width + 1, np.int64)
    active = np.empty(count, np.int64)
    present = np.empty(count, np.int64)
    x_lo, x_hi, mids = np.empty(count), np.empty(count), np.empty(count)
    next_edge = 0
    n_active = 0
    for y in range(row0, row1):
        top = y + 1.0
        n_active, next_edge = _update_active(ay, by, active, n_active, next_edge, y)
        s = float(y)
        while n_active and s < top:
            # The edges spanning upward from s, and the next vertex height above s.
            t, n = top, 0
            for k in range(n_active):
                e = active[k]
                if ay[e] > s:
                    t = min(t, ay[e])
                elif by[e] > s:
                    present[n] = e
                    n += 1
                    t = min(t, by[e])
            work += n_active + n
            if work > max_work:
                return image, work
            if n:
                t = _strip_top(ax, ay, bx, by, present, n, s, t, float(y), x_lo, x_hi)
                row = image[y - row0]
                _add_strip(
                    row, counts, ax, ay, bx, by, winding, present, n, s, t, mids, width, evenodd
                )
            s = t
    return image, work


def _row_range(ay: np.ndarray, by: np.ndarray, height: int) -> tuple[int, int]:
    """Rows [row0, row1) of the raster that the edges (lower ends ay, upper by) reach."""
    if ay.size == 0:
        return 0, 0
    row0 = min(max(0, math.floor(ay.min())), height)
    return row0, max(min(height, math.ceil(by.max())), row0)


def _coverage_rows(polygon, width, height, rule, subpixel_bits, what, extra_bytes=0):
    """Validate like `scan_convert`, then run the kernel: (row0, (rows, width) float64 in [0, 1]).

    The kernel's rows, its working memory and `extra_bytes` (the caller's
    output) are checked against the memory limit first, as `what`.
    """
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    check_choice("rule", rule, RULES)
    bits = check_subpixel_bits(subpixel_bits)
    edges = _edge_arrays(snapped_vertices(polygon, bits), polygon.offsets)
    row0, row1 = _row_range(edges[1], edges[3], height)
    check_memory(
        extra_bytes + 8 * (row1 - row0) * width + 8 * width + EDGE_BYTES * len(edges[0]),
        f"{what}: {row1 - row0} rows of {width} float64 areas",
    )
    # Refuse at once what surely needs too many edge visits; the kernel stops at the rest.
    least = _least_work(*edges[:4], row0, row1, MAX_WORK)
    if least > MAX_WORK:
        raise _too_many_strips(what, len(edges[0]), f"at least {least:.3g}")
    rows, work = _coverage_kernel(*edges, width, height, rule == "evenodd", row0, row1, MAX_WORK)
    if work > MAX_WORK:
        raise _too_many_strips(what, len(edges[0]), f"over {work}")
    return row0, np.clip(rows, 0.0, 1.0, out=rows)


def _too_many_strips(what: str, edges: int, visits: str) -> ValueError:
    return ValueError(
        f"{what}: the polygon's {edges} edges cut its rows into too many strips "
        f"({visits} edge visits, limit {MAX_WORK}): every vertex height and "
        "every crossing of two edges inside a pixel row starts a strip that visits all the "
        "edges of the row; use fewer vertices or edge crossings per pixel row"
    )


def pixel_areas(
    polygon: object,
    width: int,
    height: int,
    *,
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact area of (polygon ∩ pixel) for every pixel of the raster the polygon overlaps.

    Parameters
    ----------
    polygon : Polygon or array_like
        Anything `Polygon` accepts: one (N, 2) contour or a list of contours;
        holes and self-intersections are allowed.
    width, height : int
        Raster size in pixels; only pixels inside it are computed.
    rule : {"nonzero", "evenodd"}
        Fill rule deciding which regions are inside.
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel as `scan_convert` does; None keeps them.

    Returns
    -------
    ys, xs : (K,) ndarray of int64
        Pixels with positive covered area, sorted by y then x.
    areas : (K,) ndarray of float64
        Covered area of each pixel, in (0, 1].

    Examples
    --------
    >>> ys, xs, areas = pixel_areas([(0, 0), (2, 0), (0, 1)], 3, 2)
    >>> ys.tolist(), xs.tolist(), areas.tolist()
    ([0, 0], [0, 1], [0.75, 0.25])
    """
    row0, rows = _coverage_rows(polygon, width, height, rule, subpixel_bits, "pixel_areas")
    ys, xs = np.nonzero(rows)
    return (ys + row0).astype(np.int64), xs.astype(np.int64), rows[ys, xs]


def area_coverage(
    polygon: object,
    width: int,
    height: int,
    *,
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
) -> np.ndarray:
    """Exact covered area of every pixel: the dense form of `pixel_areas`.

    Parameters
    ----------
    polygon : Polygon or array_like
        Anything `Polygon` accepts.
    width, height : int
        Raster size in pixels.
    rule : {"nonzero", "evenodd"}
        Fill rule.
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None keeps them.

    Returns
    -------
    (height, width) ndarray of float64
        Area of (inside region ∩ [x, x+1) x [y, y+1)) at ``[y, x]``, row 0 at the bottom.

    Raises
    ------
    TypeError
        If a coordinate is not a real number (bool, str, complex, object), or
        an option has the wrong type.
    ValueError
        If `polygon` is malformed (see `Polygon`: shape, non-finite values,
        coordinates beyond +-2**20, fewer than 3 distinct vertices), or an
        option is unknown or out of range; or if the polygon needs over
        2**26 edge visits (its strips times the edges of their rows: many
        vertices or crossings in one pixel row), refused at once when a lower
        bound on them already says so.
    scanviz.limits.ResourceLimitError
        (a ValueError) If the output (8 bytes a pixel), the rows the polygon
        reaches (8 bytes a pixel again) and the edges' working memory would
        exceed the memory limit (`scanviz.limits`).

    Examples
    --------
    >>> area_coverage([(0, 0), (2, 0), (2, 2)], 2, 2)[::-1]  # top row first
    array([[0. , 0.5],
           [0.5, 1. ]])
    """
    width, height = check_raster_size(width, height)  # before the estimate uses them
    what = f"area_coverage: a {width}x{height} float64 raster"
    row0, rows = _coverage_rows(
        polygon, width, height, rule, subpixel_bits, what, extra_bytes=8 * width * height
    )
    image = np.zeros((height, width))
    image[row0 : row0 + len(rows)] = rows
    return image

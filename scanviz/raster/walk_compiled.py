"""The compiled edge walker (numba): one edge table, one active edge table, one row step.

Every compiled scan converter walks a polygon's edges up the sample rows the
same way, so they share these steps: `edge_table` builds the ET, `step_row`
takes the AET from one row to the next (edges_retired, the kept crossings
stepped, edges_activated, aet_sorted), and `triangle_walk` / `triangle_span`
are the same walk specialised to a triangle's two active edges. Users:
`scan_compiled.scan_polygon` (coverage and spans), `scan_compiled.rasterize_triangles`,
`visibility.zbuffer_compiled.draw_polygon`, `visibility.scanline_compiled.scanline_ids`
and `shading.fast_phong_compiled`.

The AET is sorted in one of two orders (`sort_active`):

* by ceil(x), for coverage. A span runs between the ceilings of two
  consecutive crossings; crossings with equal ceilings bound only empty spans
  among themselves, and the winding after the last of them is their sum,
  whatever their order. So every order by ceiling emits the same spans.
* by the exact crossing x = Q + R/DEN, where a span takes interpolated values
  from the two crossings that bound it, so the order within a pixel matters;
  ties (equal x) keep their AET order, as the reference's insertion sort does.
  The comparison r1/den1 < r2/den2 needs r1*den2 up to 2**110: `wide_product`
  forms it in two 64-bit words.

An edge entering at row y starts at x = (xl + dx*(y*scale - yl)/dy) / scale.
On the finest grid (2**17 units a pixel, +-2**20 pixels) dx and y*scale - yl
reach 2**38, their product 2**76, beyond int64: `mul_divmod` divides it
exactly all the same.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .scanline import FLOAT_X_LIMIT

# Fields of the edge table (rows; column e is edge e) and of the active edge table
# (column i is the i-th active edge from the left: the textbook AET entry). Both
# share WINDING and ROW_END. LOWER and UPPER are the vertex indices of the edge's
# ends (for interpolating vertex values). The AET crossing is x = Q + R/DEN pixels,
# stepped by dx/dy = Q_STEP + R_STEP/DEN; in float arithmetic x and dx/dy are X and SLOPE.
WINDING, ROW_END, ROW_START, X0, Y0, X1, Y1, LOWER, UPPER = range(9)
Q, R, Q_STEP, R_STEP, DEN, CEIL = range(2, 8)
X, SLOPE = range(2)
TABLE_FIELDS, AET_FIELDS = 9, 8
SORTED_IN_PLACE = 64  # polygons up to this many edges sort their edge table by insertion
SORT_MOVES_PER_EDGE = 16  # the AET's insertion sort hands over to a merge sort past this many


@njit(cache=True, inline="always")
def mul_divmod(a, b, d):
    """(floor(a*b / d), a*b mod d) for int64 a, b, d with d > 0, |a|, |b| < 2**53, |a*b/d| < 2**50.

    a*b itself may overflow int64. The quotient is estimated in float64: two
    roundings of relative error 2**-53 put it within 2**50 * 2**-51.9 < 1 of the
    truth, so its floor is off by at most one. The remainder a*b - q*d is then
    in [-d, 2d), small, so computing it modulo 2**64 (uint64 arithmetic wraps by
    definition; int64 overflow would be undefined) gives it exactly.

    >>> a, b = 2**38 + 12345, -(2**37) - 999
    >>> mul_divmod(a, b, 2**38 + 7) == divmod(a * b, 2**38 + 7)
    True
    """
    q = np.int64(math.floor(float(a) * float(b) / float(d)))
    r = np.int64(np.uint64(a) * np.uint64(b) - np.uint64(q) * np.uint64(d))
    while r < 0:
        r += d
        q -= 1
    while r >= d:
        r -= d
        q += 1
    return q, r


@njit(cache=True, inline="always")
def wide_product(a, b):
    """(high, low) 64-bit words of a*b for int64 0 <= a, b < 2**63, as uint64.

    >>> high, low = wide_product(2**62 + 3, 2**40 + 5)
    >>> (int(high) << 64) + int(low) == (2**62 + 3) * (2**40 + 5)
    True
    """
    half, mask = np.uint64(32), np.uint64(0xFFFFFFFF)
    a, b = np.uint64(a), np.uint64(b)
    a_high, a_low, b_high, b_low = a >> half, a & mask, b >> half, b & mask
    low_low, high_low, low_high = a_low * b_low, a_high * b_low, a_low * b_high
    middle = (low_low >> half) + (high_low & mask) + (low_high & mask)  # < 3 * 2**32
    high = a_high * b_high + (high_low >> half) + (low_high >> half) + (middle >> half)
    return high, (low_low & mask) | (middle << half)


@njit(cache=True, inline="always")
def ceil_div(a, b):
    return -((-a) // b)


@njit(cache=True, inline="always")
def exact_crossing(edge, scale, row):
    """Crossing of edge (x0, y0, x1, y1) with sample row `row`: (q, r, q_step, r_step, den).

    x = q + r/den pixels with 0 <= r < den = dy*scale, as `ExactCrossing.start`.
    Needs y0 <= row*scale < y1, so t = row*scale - y0 is in [0, dy): then
    dx*t = along*dy + rest, the crossing is x0 + along + rest/dy grid units, and
    |along| <= |dx| keeps every other product within int64 (den < 2**56).
    """
    x0, y0, x1, y1 = edge
    dx, dy = x1 - x0, y1 - y0
    along, rest = mul_divmod(dx, row * scale - y0, dy)
    x_units = x0 + along
    q = x_units // scale
    q_step, r_step = divmod(dx, dy)  # dx/dy = q_step + r_step/dy pixels per row
    return q, (x_units - q * scale) * dy + rest, q_step, r_step * scale, dy * scale


@njit(cache=True, inline="always")
def exact_step(q, r, q_step, r_step, den):
    """The crossing one row up: add dx/dy and carry the remainder into the integer part."""
    q += q_step
    r += r_step
    if r >= den:
        r -= den
        q += 1
    return q, r


@njit(cache=True, inline="always")
def float_crossing(edge, scale, row, cast):
    """(x, slope) at `row` in dtype `cast`, with the operations of `FloatCrossing`."""
    x0, y0, x1, y1 = edge
    x_low, y_low = cast(x0 / scale), cast(y0 / scale)
    dy = cast(y1 / scale) - y_low
    slope = (cast(x1 / scale) - x_low) / dy if dy != 0 else cast(0)
    if not math.isfinite(slope):  # the textbook dx/dy breaks down: x stays at the lower end
        slope = cast(0)
    return x_low + slope * (cast(row) - y_low), slope


@njit(cache=True, inline="always")
def float_ceil(x):
    """ceil(x) as `FloatCrossing.ceil` takes it: clamped to +-FLOAT_X_LIMIT, off every raster."""
    return math.ceil(min(max(float(x), -FLOAT_X_LIMIT), FLOAT_X_LIMIT))


# --- the edge table ------------------------------------------------------------------------


@njit(cache=True, inline="always")
def put_edge(table, column, units, i, j, lower, upper, row_start, row_end):
    """Column `column` of an edge table: the edge from vertex i to j, `lower` its lower end."""
    # Downward edges enter a counter-clockwise polygon from the left: winding +1.
    table[WINDING, column] = 1 if units[j, 1] < units[i, 1] else -1
    table[ROW_START, column], table[ROW_END, column] = row_start, row_end
    table[X0, column], table[Y0, column] = units[lower, 0], units[lower, 1]
    table[X1, column], table[Y1, column] = units[upper, 0], units[upper, 1]
    table[LOWER, column], table[UPPER, column] = lower, upper


@njit(cache=True, inline="always")
def edge_table(units, offsets, scale, height, table):
    """edge_table_built: the edges of one polygon that cross a sample row, sorted by first row.

    `offsets` are its contours' starts in `units` plus the end. Writes `table`
    (9, >= edges) int64, column e edge e's WINDING, ROW_START, ROW_END, ends
    X0, Y0 (lower), X1, Y1, and the indices in `units` of those ends, LOWER
    and UPPER; ties keep vertex order. Returns (count, edges, kept_for_topology).
    Up to `SORTED_IN_PLACE` edges, each is inserted in place (nothing allocated).
    """
    edges = offsets[-1] - offsets[0]
    count = kept_for_topology = 0
    for c in range(offsets.shape[0] - 1):
        for i in range(offsets[c], offsets[c + 1]):
            j = i + 1 if i + 1 < offsets[c + 1] else offsets[c]
            lower, upper = (i, j) if units[i, 1] <= units[j, 1] else (j, i)
            bucket = ceil_div(units[lower, 1], scale)
            row_end = ceil_div(units[upper, 1], scale)
            kept_for_topology += bucket >= row_end
            row_start = max(bucket, 0)  # rows below the raster are never scanned
            if row_start < min(row_end, height):
                k = count
                while edges <= SORTED_IN_PLACE and k > 0 and table[ROW_START, k - 1] > row_start:
                    for field in range(TABLE_FIELDS):
                        table[field, k] = table[field, k - 1]
                    k -= 1
                put_edge(table, k, units, i, j, lower, upper, row_start, row_end)
                count += 1
    if edges > SORTED_IN_PLACE:
        order = np.argsort(table[ROW_START, :count], kind="mergesort")
        table[:, :count] = table[:, order]
    return count, edges, kept_for_topology


# --- the active edge table -----------------------------------------------------------------


@njit(cache=True, inline="always")
def activate(table, e, aet, xs, i, row, scale, exact, cast):
    """edges_activated: AET entry i for edge e, its crossing computed directly at `row`."""
    aet[WINDING, i], aet[ROW_END, i] = table[WINDING, e], table[ROW_END, e]
    edge = (table[X0, e], table[Y0, e], table[X1, e], table[Y1, e])
    if exact:
        q, r, aet[Q_STEP, i], aet[R_STEP, i], aet[DEN, i] = exact_crossing(edge, scale, row)
        aet[Q, i], aet[R, i], aet[CEIL, i] = q, r, q + (r > 0)
    else:
        xs[X, i], xs[SLOPE, i] = float_crossing(edge, scale, row, cast)
        aet[CEIL, i] = float_ceil(xs[X, i])


@njit(cache=True, inline="always")
def advance(aet, xs, i, exact):
    """Step AET entry i one row: x += dx/dy, exactly or in the float dtype; update ceil(x)."""
    if exact:
        q, r = exact_step(aet[Q, i], aet[R, i], aet[Q_STEP, i], aet[R_STEP, i], aet[DEN, i])
        aet[Q, i], aet[R, i], aet[CEIL, i] = q, r, q + (r > 0)
    else:
        xs[X, i] = xs[X, i] + xs[SLOPE, i]
        aet[CEIL, i] = float_ceil(xs[X, i])


@njit(cache=True, inline="always")
def move(aet, xs, edge_of, source, target):
    """Copy AET entry `source` (crossing and edge column) to column `target`."""
    for field in range(AET_FIELDS):  # a constant trip count: unrolled
        aet[field, target] = aet[field, source]
    xs[X, target], xs[SLOPE, target] = xs[X, source], xs[SLOPE, source]
    edge_of[target] = edge_of[source]


@njit(cache=True, inline="always")
def before(aet, i, j, by_x):
    """Whether AET entry i belongs left of entry j: by exact x (`ExactCrossing.before`) or by ceil(x)."""
    if not by_x:
        return aet[CEIL, i] < aet[CEIL, j]
    if aet[Q, i] != aet[Q, j]:
        return aet[Q, i] < aet[Q, j]
    left_high, left_low = wide_product(aet[R, i], aet[DEN, j])
    right_high, right_low = wide_product(aet[R, j], aet[DEN, i])
    return left_high < right_high or (left_high == right_high and left_low < right_low)


@njit(cache=True)
def merge_sort_active(aet, xs, edge_of, count, by_x):
    """Stable merge sort of the first `count` AET entries: the insertion sort's order, in O(n log n).

    Sorts a permutation (bottom-up, comparing the entries in place), then
    gathers the columns through a copy.
    """
    order, spare = np.arange(count), np.empty(count, np.int64)
    width = 1
    while width < count:
        for low in range(0, count, 2 * width):
            middle, high = min(low + width, count), min(low + 2 * width, count)
            i, j = low, middle
            for k in range(low, high):
                # take from the right run only when strictly before: ties keep their order
                if j < high and (i >= middle or before(aet, order[j], order[i], by_x)):
                    spare[k] = order[j]
                    j += 1
                else:
                    spare[k] = order[i]
                    i += 1
        order, spare = spare, order
        width *= 2
    old_aet, old_xs, old_edge_of = (
        aet[:, :count].copy(),
        xs[:, :count].copy(),
        edge_of[:count].copy(),
    )
    for k in range(count):
        aet[:, k], xs[:, k], edge_of[k] = (
            old_aet[:, order[k]],
            old_xs[:, order[k]],
            old_edge_of[order[k]],
        )


@njit(cache=True, inline="always")
def sort_active(aet, xs, edge_of, count, by_x):
    """aet_sorted: stable insertion sort (nearly sorted already); column `count` holds.

    An AET whose order is scrambled from row to row (edges that cross, as in a
    star of many spikes) would cost the insertion sort O(n^2) moves: past
    `SORT_MOVES_PER_EDGE` moves an edge it stops and `merge_sort_active`
    finishes. Both are stable and the insertion sort only ever moves an entry
    past strictly greater ones, so the order is the same either way.
    """
    budget = SORT_MOVES_PER_EDGE * count + SORT_MOVES_PER_EDGE
    for i in range(1, count):
        if before(aet, i, i - 1, by_x):
            move(aet, xs, edge_of, i, count)
            j = i
            while j > 0 and before(aet, count, j - 1, by_x):
                move(aet, xs, edge_of, j - 1, j)
                j -= 1
            move(aet, xs, edge_of, count, j)
            budget -= i - j
            if budget < 0:
                merge_sort_active(aet, xs, edge_of, count, by_x)
                return


@njit(cache=True, inline="always")
def step_row(table, count, entering, aet, xs, edge_of, n_active, y, scale, exact, cast, by_x):
    """The AET of the next row to scan, from row y on: returns (row, n_active, entering).

    Empty rows are skipped; then edges_retired (ymax passed; the others step
    x one row), edges_activated (the ET's edges entering, from column
    `entering` of the `count`), aet_sorted (by exact x if `by_x`, else by
    ceil(x)). edge_of[i] is entry i's column in `table`: per-edge values live
    there (the caller steps them for entries still active on the row, and
    starts them for the columns entered).
    """
    if n_active == 0 and table[ROW_START, entering] > y:
        y = table[ROW_START, entering]  # skip empty rows
    kept = 0
    for i in range(n_active):
        if aet[ROW_END, i] > y:
            if kept != i:
                move(aet, xs, edge_of, i, kept)
            advance(aet, xs, kept, exact)
            kept += 1
    while entering < count and table[ROW_START, entering] == y:
        activate(table, entering, aet, xs, kept, y, scale, exact, cast)
        edge_of[kept] = entering
        kept += 1
        entering += 1
    sort_active(aet, xs, edge_of, kept, by_x)
    return y, kept, entering


@njit(cache=True, inline="always")
def scratch_aet(edges, cast):
    """(aet, xs, edge_of) for up to `edges` active edges, plus a spare column for sorting."""
    return (
        np.empty((AET_FIELDS, edges + 1), np.int64),
        np.empty((2, edges + 1), cast),  # float crossings: unused with exact ones
        np.empty(edges + 1, np.int64),
    )


# --- the same walk, for a triangle ---------------------------------------------------------

NO_CROSSING = (0, 0, 0, 0, 1)  # a triangle with no row: nothing is walked


@njit(cache=True, inline="always")
def triangle_walk(x0, y0, x1, y1, x2, y2, scale, height):
    """(first, stop, walk): a grid triangle's rows [first, stop) and its two active edges there.

    The rows [ceil(y_low), ceil(y_high)) of a triangle have two active edges:
    the long edge low-high, and low-mid below ceil(y_mid), mid-high from there
    up. The winding between them is +-1, so both fill rules give the span
    [min ceil, max ceil) (`triangle_span`); zero-area triangles give only
    empty spans.
    """
    if y1 < y0:  # order the vertices by y: 0 low, 1 mid, 2 high
        x0, y0, x1, y1 = x1, y1, x0, y0
    if y2 < y1:
        x1, y1, x2, y2 = x2, y2, x1, y1
    if y1 < y0:
        x0, y0, x1, y1 = x1, y1, x0, y0
    first, middle = max(ceil_div(y0, scale), 0), ceil_div(y1, scale)
    stop = min(ceil_div(y2, scale), height)
    upper = (x1, y1, x2, y2)
    long_edge = short = NO_CROSSING
    if first < stop:  # else an edge could have dy = 0
        long_edge = exact_crossing((x0, y0, x2, y2), scale, first)
        short = exact_crossing((x0, y0, x1, y1) if first < middle else upper, scale, first)
    return first, stop, (long_edge, short, middle, upper)


@njit(cache=True, inline="always")
def triangle_span(walk, y, scale, width):
    """(start, end, walk): row y's span of a triangle, clipped to [0, width), and the next row's walk."""
    long_edge, short, middle, upper = walk
    if y == middle:  # the short side turns at the middle vertex
        short = exact_crossing(upper, scale, y)
    ceil_a, ceil_b = long_edge[0] + (long_edge[1] > 0), short[0] + (short[1] > 0)
    start, end = max(min(ceil_a, ceil_b), 0), min(max(ceil_a, ceil_b), width)
    qa, ra, qa_step, ra_step, den_a = long_edge
    qb, rb, qb_step, rb_step, den_b = short
    qa, ra = exact_step(qa, ra, qa_step, ra_step, den_a)
    qb, rb = exact_step(qb, rb, qb_step, rb_step, den_b)
    long_edge, short = (qa, ra, qa_step, ra_step, den_a), (qb, rb, qb_step, rb_step, den_b)
    return start, end, (long_edge, short, middle, upper)

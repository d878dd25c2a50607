"""Compiled twins of the raster algorithms (numba): the reference's spans, fast.

`scan_polygon` is `scanline.scan_reference` without the tracing: the same edge
table, the same exact DDA (x = q + r/den pixels) or textbook float update with
the same operations in the same dtype, the same spans. It differs in two ways
that cannot change a span:

* The active edge table is sorted by ceil(x), not by x. A span runs between the
  ceilings of two consecutive crossings; crossings with equal ceilings bound
  only empty spans among themselves, and the winding after the last of them is
  their sum, whatever their order. So every order by ceiling emits the same
  spans. (Hence sort swaps are not counted here.)
* An edge entering at row y starts at x = (xl + dx*(y*scale - yl)/dy) / scale.
  On the finest grid (2**17 units a pixel, +-2**20 pixels) dx and y*scale - yl
  reach 2**38, their product 2**76, beyond int64: `mul_divmod` divides it
  exactly all the same.

The span buffer grows with the output (a row adds fewer than min(active
edges, width + 1) spans), never past the `max_spans` its caller allows.

Coverage counts (`fill_polygons`, `rasterize_triangles`) are accumulated as
+1/-1 marks where spans start and end, then one prefix sum per row: the cost is
O(spans + pixels), not O(covered area). `rasterize_triangles` walks a triangle
as two trapezoids, the long edge against each short edge: exactly the two
active edges the ET/AET has on each row of a triangle.

`fill_polygons` needs no AET for a simple polygon. Counting crossings left of
a sample (x + eps, y + eps**2) gives its winding number, the AET's running sum
in any order; a simple polygon's is its orientation inside and 0 outside. So
each edge can add orientation * winding at every ceil(x) it crosses, walked on
its own, and the row sums are the coverage. `star_orientation` (O(n)) or
`simple_orientation` (O(n**2)) proves a polygon simple (exactly, in int64)
before it is marked so; the rest take the AET.
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


@njit(cache=True, inline="always")
def put_edge(table, column, units, i, j, lower, upper, row_start, row_end):
    """Column `column` of an edge table: the edge from vertex i to j, `lower` its lower end."""
    # Downward edges enter a counter-clockwise polygon from the left: winding +1.
    table[WINDING, column] = 1 if units[j, 1] < units[i, 1] else -1
    table[ROW_START, column], table[ROW_END, column] = row_start, row_end
    table[X0, column], table[Y0, column] = units[lower, 0], units[lower, 1]
    table[X1, column], table[Y1, column] = units[upper, 0], units[upper, 1]
    table[LOWER, column], table[UPPER, column] = lower, upper


@njit(cache=True)
def edge_table(units, offsets, scale, height):
    """The edges of one polygon that cross a sample row of the raster, sorted by first row.

    `offsets` are its contours' starts in `units` plus the end. Returns
    (table, edges, kept_for_topology), table a (9, k) int64 array whose column
    e holds edge e's WINDING, ROW_START, ROW_END, ends X0, Y0 (lower), X1, Y1,
    and the indices in `units` of those ends, LOWER and UPPER.
    """
    table = np.empty((9, offsets[-1] - offsets[0]), np.int64)
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
                put_edge(table, count, units, i, j, lower, upper, row_start, row_end)
                count += 1
    order = np.argsort(table[ROW_START, :count], kind="mergesort")
    return np.ascontiguousarray(table[:, order]), offsets[-1] - offsets[0], kept_for_topology


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
def move(aet, xs, source, target):
    """Copy AET entry `source` to column `target`."""
    for field in range(8):  # a constant trip count: unrolled
        aet[field, target] = aet[field, source]
    xs[X, target], xs[SLOPE, target] = xs[X, source], xs[SLOPE, source]


@njit(cache=True, inline="always")
def sort_by_ceil(aet, xs, count):
    """aet_sorted: insertion sort by ceil(x), nearly sorted already; column `count` holds."""
    for i in range(1, count):
        if aet[CEIL, i - 1] > aet[CEIL, i]:
            move(aet, xs, i, count)
            j = i
            while j > 0 and aet[CEIL, j - 1] > aet[CEIL, count]:
                move(aet, xs, j - 1, j)
                j -= 1
            move(aet, xs, count, j)


@njit(cache=True, inline="always")
def reserve(spans, needed, most):
    """`spans`, or a copy with room for `needed` <= `most` rows (doubled, capped at `most`)."""
    if needed <= spans.shape[0]:
        return spans
    grown = np.empty((min(max(needed, 2 * spans.shape[0]), most), 3), np.int64)
    grown[: spans.shape[0]] = spans
    return grown


@njit(cache=True, inline="always")
def store_spans(aet, count, y, width, parity, spans, span_count):
    """span: store the clipped, nonempty inside runs between consecutive crossings."""
    winding = 0
    for i in range(count - 1):
        winding += aet[WINDING, i]
        start, end = max(aet[CEIL, i], 0), min(aet[CEIL, i + 1], width)
        spans[span_count, 0], spans[span_count, 1], spans[span_count, 2] = y, start, end
        span_count += ((winding & parity) != 0) & (start < end)  # keep it, or overwrite it
    return span_count


@njit(cache=True, inline="always")
def mark_crossings(aet, count, y, parity, image):
    """Add this row's spans to `image` as marks: +1 where inside starts, -1 where it ends.

    Summed left to right, the marks give 1 between clamp(ceil(x_i)) and
    clamp(ceil(x_i+1)) exactly when the winding after crossing i is inside: the
    row's spans, with empty ones cancelling. Marks at x = width are dropped.
    """
    width = image.shape[1]
    inside = 0
    winding = 0
    for i in range(count):
        winding += aet[WINDING, i]
        now = np.int32((winding & parity) != 0)
        x = min(max(aet[CEIL, i], 0), width)
        if x < width:
            image[y, x] += now - inside
        inside = now


@njit(cache=True)
def scan_polygon(units, offsets, scale, width, height, evenodd, exact, cast, image, max_spans):
    """ET/AET scan conversion of one polygon (contours `offsets` of `units`).

    `cast` is np.float32 or np.float64 for the float arithmetic (unused when
    `exact`). The spans are added to the (height, width) int32 `image` as
    `mark_crossings` marks, or, if `image` is empty, returned, in a buffer
    of at most `max_spans` rows. Returns (spans, (edges, kept_for_topology,
    rows_scanned, max_active), refused): `refused` is 0, or the buffer rows
    the scan needed beyond `max_spans` (it stopped there).
    """
    table, edges, kept_for_topology = edge_table(units, offsets, scale, height)
    count = table.shape[1]
    spans = np.empty((0 if image.size else min(count, 1024), 3), np.int64)
    refused = 0
    aet = np.empty((8, count + 1), np.int64)
    xs = np.empty((2, count + 1), cast)
    parity = 1 if evenodd else -1  # winding & parity: odd for even-odd, nonzero for nonzero
    n_active = entering = span_count = rows_scanned = max_active = 0
    y = table[ROW_START, 0] if count else height
    while y < height and (n_active > 0 or entering < count):
        if n_active == 0 and table[ROW_START, entering] > y:
            y = table[ROW_START, entering]  # skip empty rows
        kept = 0  # edges_retired: drop edges whose ymax is passed, step the others
        for i in range(n_active):
            if aet[ROW_END, i] > y:
                if kept != i:
                    move(aet, xs, i, kept)
                advance(aet, xs, kept, exact)
                kept += 1
        n_active = kept
        while entering < count and table[ROW_START, entering] == y:
            activate(table, entering, aet, xs, n_active, y, scale, exact, cast)
            n_active += 1
            entering += 1
        sort_by_ceil(aet, xs, n_active)
        rows_scanned += 1
        max_active = max(max_active, n_active)
        if image.size:
            mark_crossings(aet, n_active, y, parity, image)
        else:
            # A row's spans are nonempty, disjoint and clipped: fewer than n_active, at most width.
            needed = span_count + min(n_active, width + 1)
            if needed > max_spans:
                refused = needed
                break
            spans = reserve(spans, needed, max_spans)
            span_count = store_spans(aet, n_active, y, width, parity, spans, span_count)
        y += 1
    return spans[:span_count], (edges, kept_for_topology, rows_scanned, max_active), refused


@njit(cache=True)
def scan_spans(units, offsets, scale, width, height, evenodd, exact, cast, max_spans):
    """Spans (K, 3) int64 of one polygon, its (edges, kept, rows_scanned, max_active), refused.

    `refused` is nonzero when the spans would need a buffer of more than
    `max_spans` rows (then the spans returned are only those found so far).
    """
    no_image = np.empty((0, 0), np.int32)
    spans, stats, refused = scan_polygon(
        units, offsets, scale, width, height, evenodd, exact, cast, no_image, max_spans
    )
    return spans.copy(), stats, refused  # not a view of the grown buffer


@njit(cache=True)
def paint_mask(spans, width, height):
    """The (height, width) bool mask of (K, 3) spans."""
    mask = np.zeros((height, width), np.bool_)
    for k in range(spans.shape[0]):
        mask[spans[k, 0], spans[k, 1] : spans[k, 2]] = True
    return mask


@njit(cache=True, inline="always")
def mark_span(image, y, start, end):
    """Count span [start, end) of row y as a +1 at its start and a -1 just after it."""
    image[y, start] += 1
    if end < image.shape[1]:
        image[y, end] -= 1


@njit(cache=True)
def prefix_sum_rows(image, first, stop):
    """Turn the marks of rows [first, stop) into coverage counts, in place."""
    for y in range(first, stop):
        total = 0
        for x in range(image.shape[1]):
            total += image[y, x]
            image[y, x] = total


@njit(cache=True)
def sum_marks(marks, marked, image, accumulate):
    """Write (or, if `accumulate`, add) the row prefix sums of `marks` into `image`: counts.

    Row y's marks lie in columns [marked[0, y], marked[1, y]). Left of them the
    sum is 0; right of them it stays at the row's total, nonzero when a span
    reaches the right edge (its -1 at x = width was dropped).
    """
    for y in range(image.shape[0]):
        low, high = marked[0, y], max(marked[1, y], marked[0, y])
        row, counts = marks[y, low:high], image[y, low:high]  # views: no index checks
        total = 0
        if accumulate:
            for x in range(row.shape[0]):
                total += row[x]
                counts[x] += total
            image[y, high:] += total
        else:
            image[y, :low] = 0
            for x in range(row.shape[0]):
                total += row[x]
                counts[x] = total
            image[y, high:] = total


@njit(cache=True)
def count_spans(spans, width, height):
    """(height, width) int32 count of the (K, 3) spans covering each sample."""
    image = np.zeros((height, width), np.int32)
    for k in range(spans.shape[0]):
        mark_span(image, spans[k, 0], spans[k, 1], spans[k, 2])
    prefix_sum_rows(image, 0, height)
    return image


@njit(cache=True)
def has_three_distinct(xy):
    """Whether (N, 2) vertices hold at least 3 distinct points (`geometry.Polygon`'s rule)."""
    second = 0  # the first vertex unlike vertex 0, once found
    for i in range(1, len(xy)):
        x, y = xy[i, 0], xy[i, 1]
        if x == xy[0, 0] and y == xy[0, 1]:
            continue
        if second == 0:
            second = i
        elif x != xy[second, 0] or y != xy[second, 1]:
            return True
    return False


@njit(cache=True)
def three_distinct(batch):
    """(T,) bool: which items of a (T, N, 2) float64 batch have at least 3 distinct vertices."""
    found = np.zeros(batch.shape[0], np.bool_)
    for t in range(batch.shape[0]):
        found[t] = has_three_distinct(batch[t])
    return found


SIMPLE_LIMIT = 2**30  # |units| below it keep every turn (products of differences) in int64


@njit(cache=True, inline="always")
def turn(ax, ay, bx, by, cx, cy):
    """Sign of the turn a -> b -> c: +1 left (counter-clockwise), -1 right, 0 straight."""
    cross = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return (cross > 0) - (cross < 0)


@njit(cache=True)
def simple_orientation(units, first, stop, boxes):
    """The orientation (+1 counter-clockwise, -1 clockwise) of contour units[first:stop] if it
    is simple, or 0.

    The test is conservative: 0 also when two edges that do not follow each other
    touch, two that do are straight on (or one has no length), or a coordinate
    reaches `SIMPLE_LIMIT` units. A simple contour turns like its lowest vertex.
    `boxes` (4, >= edges) int64 is work space: the edges' bounding boxes.
    """
    n = stop - first
    lowest = first
    for i in range(n):  # consecutive edges meet only at their vertex
        a, b, c = first + i, first + (i + 1) % n, first + (i + 2) % n
        ax, ay, bx, by = units[a, 0], units[a, 1], units[b, 0], units[b, 1]
        if abs(ax) >= SIMPLE_LIMIT or abs(ay) >= SIMPLE_LIMIT:
            return 0
        if (ay, ax) < (units[lowest, 1], units[lowest, 0]):
            lowest = a
        if turn(ax, ay, bx, by, units[c, 0], units[c, 1]) == 0:
            return 0
        boxes[0, i], boxes[1, i] = min(ax, bx), max(ax, bx)
        boxes[2, i], boxes[3, i] = min(ay, by), max(ay, by)
    for i in range(n - 2):  # the others not at all
        x_low, x_high, y_low, y_high = boxes[0, i], boxes[1, i], boxes[2, i], boxes[3, i]
        for j in range(i + 2, n - (i == 0)):
            if x_high < boxes[0, j] or boxes[1, j] < x_low:
                continue  # the bounding boxes are apart: most pairs
            if y_high < boxes[2, j] or boxes[3, j] < y_low:
                continue
            a, b, c, d = first + i, first + i + 1, first + j, first + (j + 1) % n
            ax, ay, bx, by = units[a, 0], units[a, 1], units[b, 0], units[b, 1]
            cx, cy, dx, dy = units[c, 0], units[c, 1], units[d, 0], units[d, 1]
            if turn(cx, cy, dx, dy, ax, ay) * turn(cx, cy, dx, dy, bx, by) > 0:
                continue  # a and b strictly on one side of cd
            if turn(ax, ay, bx, by, cx, cy) * turn(ax, ay, bx, by, dx, dy) > 0:
                continue
            return 0
    before, after = first + (lowest - first - 1) % n, first + (lowest - first + 1) % n
    return turn(
        units[before, 0],
        units[before, 1],
        units[lowest, 0],
        units[lowest, 1],
        units[after, 0],
        units[after, 1],
    )


STAR_TRIES = 8  # centres tried by `star_orientation`


@njit(cache=True)
def star_orientation(units, first, stop):
    """The orientation (+1 counter-clockwise, -1 clockwise) of contour units[first:stop] if it
    is proved star-shaped, or 0.

    Seen from a point c, the vertices of a star-shaped contour turn strictly one
    way at every edge (c is on no edge's line) and go round c once: then every
    ray from c meets the contour once, so it is simple. Strict turns make the
    angle of the vertex from c change by less than a half turn per edge, so the
    edges running up across the horizontal line through c (y_i < c_y <= y_i+1)
    are where it passes angle 0 counter-clockwise, or, running down across it,
    clockwise. Each test is exact, in int64; the grid points c tried are only a
    guess: the centre of the bounding box, then up to `STAR_TRIES` - 1 steps
    that move c just across the line of the edge it is furthest on the wrong
    side of. A sufficient test in O(n) a try: 0 says only that it did not prove
    the contour simple (or that a coordinate reaches `SIMPLE_LIMIT` units).
    """
    x_low, x_high = units[first:stop, 0].min(), units[first:stop, 0].max()
    y_low, y_high = units[first:stop, 1].min(), units[first:stop, 1].max()
    if max(-x_low, x_high, -y_low, y_high) >= SIMPLE_LIMIT:
        return 0
    n = stop - first
    centre_x, centre_y = (x_low + x_high) / 2, (y_low + y_high) / 2
    turning = 0  # the orientation to prove, once guessed
    for _ in range(STAR_TRIES):
        # A grid point in the box: a simple contour's kernel lies in it, and turns stay in int64.
        cx = min(max(np.int64(round(centre_x)), x_low), x_high)
        cy = min(max(np.int64(round(centre_y)), y_low), y_high)
        left = right = up = down = 0
        worst, worst_edge = 0.0, -1
        for i in range(first, stop):
            j = i + 1 if i + 1 < stop else first
            ax, ay, bx, by = units[i, 0] - cx, units[i, 1] - cy, units[j, 0] - cx, units[j, 1] - cy
            cross = ax * by - ay * bx  # |edge| times how far c is left of it
            left += cross > 0
            right += cross < 0
            up += (ay < 0) & (by >= 0)
            down += (ay >= 0) & (by < 0)
            if turning and cross * turning <= 0:
                length = math.hypot(bx - ax, by - ay)
                if length == 0:
                    return 0  # a repeated vertex: c is on that edge, wherever it is
                wrong = -cross * turning / length
                if wrong >= worst:
                    worst, worst_edge = wrong, i
        if left == n:
            return 1 if up == 1 else 0  # round c more than once: not simple
        if right == n:
            return -1 if down == 1 else 0
        if not turning:
            turning = 1 if left >= right else -1
            continue  # the same c again, now finding the edge to step across
        if worst_edge < 0:
            return 0
        j = worst_edge + 1 if worst_edge + 1 < stop else first
        edge_x = units[j, 0] - units[worst_edge, 0]
        edge_y = units[j, 1] - units[worst_edge, 1]
        step = turning * (worst + 1) / math.hypot(edge_x, edge_y)  # one unit past the line
        centre_x, centre_y = cx - edge_y * step, cy + edge_x * step
    return 0


@njit(cache=True)
def row_crossings(units, first, stop, scale, height):
    """How many (edge, sample row) crossings contour units[first:stop] has on the raster."""
    crossings = 0
    for i in range(first, stop):
        j = i + 1 if i + 1 < stop else first
        low, high = min(units[i, 1], units[j, 1]), max(units[i, 1], units[j, 1])
        crossings += max(min(ceil_div(high, scale), height) - max(ceil_div(low, scale), 0), 0)
    return crossings


@njit(cache=True)
def mark_simple(units, first, stop, scale, orientation, marks):
    """Add a simple contour's crossings to `marks` (height, width) edge by edge, without an AET.

    A simple contour's winding number is `orientation` inside and 0 outside, so
    with orientation * winding added at each clamped ceil(x) (dropped at x =
    width), the row's prefix sums are its coverage, as `mark_crossings` marks it.
    """
    height, width = marks.shape
    for i in range(first, stop):
        j = i + 1 if i + 1 < stop else first
        lower, upper = (i, j) if units[i, 1] <= units[j, 1] else (j, i)
        row_start = max(ceil_div(units[lower, 1], scale), 0)
        row_stop = min(ceil_div(units[upper, 1], scale), height)
        if row_start >= row_stop:
            continue
        edge = (units[lower, 0], units[lower, 1], units[upper, 0], units[upper, 1])
        q, r, q_step, r_step, den = exact_crossing(edge, scale, row_start)
        # Downward edges have winding +1 (`edge_table`).
        mark = np.int32(orientation if units[j, 1] < units[i, 1] else -orientation)
        for y in range(row_start, row_stop):
            x = min(max(q + (r > 0), 0), width)
            if x < width:
                marks[y, x] += mark
            q, r = exact_step(q, r, q_step, r_step, den)


MARK_BATCH = 2**15 - 1  # polygons marked at once: summed, their marks fit int16
BYTE_BATCH = 2**7 - 1  # so few polygons mark int8: half the memory again


@njit(cache=True)
def fill_polygons(units, contour_offsets, polygon_contours, scales, width, height, evenodd):
    """(height, width) int32 count of the polygons covering each sample (exact arithmetic).

    Polygon p has the contours contour_offsets[polygon_contours[p] : polygon_contours[p+1] + 1]
    of the packed (M, 2) int64 `units`, on a grid of scales[p] units per pixel.
    A simple one-contour polygon is marked edge by edge (`mark_simple`) when
    it is proved simple: star-shaped (`star_orientation`), or, when that
    proof costs no more than its crossings, by `simple_orientation`;
    the others go through the AET (`scan_polygon`). Summed, a polygon's marks
    at a sample are -1, 0 or 1, so those of `MARK_BATCH` polygons fit int16
    (wrapping meanwhile or not): half the memory of int32 to mark and to sum;
    up to `BYTE_BATCH` polygons fit int8.
    """
    image = np.empty((height, width), np.int32)
    if image.size == 0:
        return image
    polygons = scales.shape[0]
    bounds = np.empty((polygons, 4), np.int64)  # rows [first, stop), columns [low, high)
    for p in range(polygons):
        part = units[
            contour_offsets[polygon_contours[p]] : contour_offsets[polygon_contours[p + 1]]
        ]
        bounds[p, 0] = max(ceil_div(part[:, 1].min(), scales[p]), 0)
        bounds[p, 1] = min(ceil_div(part[:, 1].max(), scales[p]), height)
        bounds[p, 2] = max(ceil_div(part[:, 0].min(), scales[p]), 0)
        bounds[p, 3] = min(ceil_div(part[:, 0].max(), scales[p]), width - 1) + 1
    order = np.argsort(bounds[:, 0])  # bottom to top: nearby rows follow each other (cache)
    packed = units, contour_offsets, polygon_contours, scales, evenodd, order, bounds
    if polygons <= BYTE_BATCH:
        count_batches(*packed, np.zeros((height, width), np.int8), BYTE_BATCH, image)
    else:
        count_batches(*packed, np.zeros((height, width), np.int16), MARK_BATCH, image)
    return image


@njit(cache=True)
def count_batches(
    units, contour_offsets, polygon_contours, scales, evenodd, order, bounds, marks, size, image
):
    """`fill_polygons`: mark the polygons `order`, `size` at a time, in `marks`; sum into `image`."""
    height, width = marks.shape
    for start in range(0, max(order.shape[0], 1), size):
        if start:
            marks[:] = 0
        batch = order[start : start + size]
        mark_polygons(
            units, contour_offsets, polygon_contours, scales, evenodd, batch, bounds, marks
        )
        marked = np.empty((2, height), np.int64)  # row y's marks lie in columns [marked[:, y])
        marked[0], marked[1] = width, 0
        for p in batch:
            for y in range(bounds[p, 0], bounds[p, 1]):
                marked[0, y] = min(marked[0, y], bounds[p, 2])
                marked[1, y] = max(marked[1, y], bounds[p, 3])
        sum_marks(marks, marked, image, start > 0)


@njit(cache=True)
def mark_polygons(units, contour_offsets, polygon_contours, scales, evenodd, batch, bounds, marks):
    """`fill_polygons`: the crossings of polygons `batch`, in that order, as `marks`."""
    height, width = marks.shape
    sizes = contour_offsets[polygon_contours[1:]] - contour_offsets[polygon_contours[:-1]]
    boxes = np.empty((4, sizes.max() if sizes.shape[0] else 0), np.int64)
    for p in batch:
        offsets = contour_offsets[polygon_contours[p] : polygon_contours[p + 1] + 1]
        first, stop, scale = offsets[0], offsets[-1], scales[p]
        orientation = 0
        if offsets.shape[0] == 2:
            orientation = star_orientation(units, first, stop)
            pairs = (stop - first) * (stop - first - 1) // 2
            if not orientation and pairs <= row_crossings(units, first, stop, scale, height):
                orientation = simple_orientation(units, first, stop, boxes)
        if orientation:
            mark_simple(units, first, stop, scale, orientation, marks)
        else:
            scan_polygon(units, offsets, scale, width, height, evenodd, True, np.float64, marks, 0)


@njit(cache=True, inline="always")
def fill_trapezoid(image, edge_a, edge_b, first, stop, scale):
    """Mark the spans between edges (x0, y0, x1, y1), lower end first, on rows [first, stop)."""
    if first >= stop:  # also keeps a horizontal edge (dy = 0) from being divided by
        return
    width = image.shape[1]
    qa, ra, qa_step, ra_step, den_a = exact_crossing(edge_a, scale, first)
    qb, rb, qb_step, rb_step, den_b = exact_crossing(edge_b, scale, first)
    for y in range(first, stop):
        ceil_a, ceil_b = qa + (ra > 0), qb + (rb > 0)
        start, end = max(min(ceil_a, ceil_b), 0), min(max(ceil_a, ceil_b), width)
        if start < end:
            mark_span(image, y, start, end)
        qa, ra = exact_step(qa, ra, qa_step, ra_step, den_a)
        qb, rb = exact_step(qb, rb, qb_step, rb_step, den_b)


@njit(cache=True)
def rasterize_triangles(units, scale, width, height):
    """(height, width) int32 count of the (T, 3, 2) int64 grid triangles covering each sample.

    A triangle's rows [ceil(y_low), ceil(y_high)) have two active edges: the
    long edge low-high, and low-mid below ceil(y_mid), mid-high from there up.
    The winding between them is +-1, so both fill rules give the span
    [min ceil, max ceil). Zero-area triangles give only empty spans.
    """
    image = np.zeros((height, width), np.int32)
    first_row, stop_row = height, 0
    for t in range(units.shape[0]):
        x0, y0, x1, y1, x2, y2 = (
            units[t, 0, 0],
            units[t, 0, 1],
            units[t, 1, 0],
            units[t, 1, 1],
            units[t, 2, 0],
            units[t, 2, 1],
        )
        if y1 < y0:  # order the vertices by y: 0 low, 1 mid, 2 high
            x0, y0, x1, y1 = x1, y1, x0, y0
        if y2 < y1:
            x1, y1, x2, y2 = x2, y2, x1, y1
        if y1 < y0:
            x0, y0, x1, y1 = x1, y1, x0, y0
        if ceil_div(max(x0, x1, x2), scale) <= 0 or ceil_div(min(x0, x1, x2), scale) >= width:
            continue  # every span would be clipped away
        first = max(ceil_div(y0, scale), 0)
        middle = ceil_div(y1, scale)
        stop = min(ceil_div(y2, scale), height)
        if first < stop:
            long_edge = (x0, y0, x2, y2)
            fill_trapezoid(image, long_edge, (x0, y0, x1, y1), first, min(middle, stop), scale)
            fill_trapezoid(image, long_edge, (x1, y1, x2, y2), max(middle, first), stop, scale)
            first_row, stop_row = min(first_row, first), max(stop_row, stop)
    prefix_sum_rows(image, first_row, stop_row)
    return image

"""Fill a simple polygon without an AET: the proofs of simplicity it needs (numba).

An optimisation of `fill_batched.fill_polygons` for benchmark-like scenes of
many small simple polygons (stars): it skips the edge table and the AET.
Counting crossings left of a sample (x + eps, y + eps**2) gives its winding
number, the AET's running sum in any order; a simple polygon's is its
orientation inside and 0 outside. So each edge can add orientation * winding
at every ceil(x) it crosses, walked on its own (`mark_simple`), and the row
sums are the coverage. `star_orientation` (O(n)) or `simple_orientation`
(O(n**2)) proves a polygon simple (exactly, in int64) before it is marked so;
the rest take the AET. docs/performance.md says what it measured.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .walk_compiled import ceil_div, exact_crossing, exact_step

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

"""Exact area coverage: the area of (polygon ∩ pixel square) for every pixel it touches.

This is the "exact area" a-buffer fragments carry next to their pixel masks,
and the reference every anti-aliasing method is measured against.

Vertices are snapped as the scan converter snaps them (``rint(v * 2**bits) /
2**bits``), so coverage and sample masks describe the same polygon.

Algorithm (one compiled sweep per pixel row, bottom row to top):

1. The row's edges, clipped to it, are kept in x order as the sweep rises
   from its bottom. Events change that order: where two edges adjacent in it
   cross, they swap (Bentley-Ottmann: each adjacent pair's crossing waits in
   a heap); at a height where edges start or end (the row's bottom first)
   they are dropped, and merged in by x there, ties by slope. A pair swaps
   iff its order where the first of the two ends says so, a fixed test: each
   pair swaps at most once per row, and rounding can move a swap by an ulp
   of its height but not lose it.
2. Each edge keeps its side: the fill rule (nonzero or evenodd) applied to
   the winding on its left and on its right says whether it is a left
   boundary of the inside, a right one, or neither. A swap changes the
   winding between the two edges only, so only their sides can change; a
   height with vertices recomputes them all (a horizontal edge there changes
   the winding of every edge that passes it).
3. A boundary edge adds its piece (from where it got its side to where it
   loses it) to the row: with ``F_E(c) = ∫ clamp(x_E(t) - c, 0, 1) dt`` over
   the piece, a pixel's area is the sum of ``F_R(c) - F_L(c)`` over its right
   and left boundary pieces. The columns a piece crosses get F in closed
   form (the time it spends in the column times its mean offset there, plus
   the time it spends right of it); the columns left of it get the full
   height, as one step in a per-row accumulation buffer that a prefix sum
   over the row spreads (as font rasterizers do). Those heights are summed
   in integers of 2**-60 pixel, where the sides right of a column telescope
   to the fill rule there: a column no boundary crosses gets exactly 0 where
   the shape misses it and exactly 1 where it covers the whole row.

Work is, per row, its edges, one step per swap, the present edges at each
height where edges start or end (the merge: an array, so this term is the
row's vertex heights times its edges, not output-sized), and every column a
boundary piece crosses. A random polygon of n = 4,000 vertices on 16 x 16
takes n**2 / 3 steps: a third swaps, most of the rest merges. Past MAX_WORK
steps a polygon is refused: at once when a lower bound (each row's edges and
the pairs of row-spanning edges whose x order at its bottom and top differ,
counted by a merge sort) already exceeds it, else when the sweep gets there.

Rounding: coordinates are float64, so the per-pixel error is a few ulps of
the coordinate magnitude (about 1e-13 for a 256-pixel raster); full-height
parts are rounded to 2**-61 a piece. The tests hold it to 1e-12 against
exact rational areas and shapely.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..conventions import RULES, check_choice, check_raster_size, check_subpixel_bits
from ..geometry import Polygon
from ..limits import check_memory
from ..raster.sorting import inversions

EDGE_BYTES = 36 * 8  # per edge: its 5 arrays, its 18-word sweep table entry, lists, sorting
MAX_WORK = 2**26  # sweep steps (edges, swaps, merges, crossed columns) before a refusal
FIXED_BITS = 60  # full-height coverage is summed in integers of 2**-FIXED_BITS pixel


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
    keep = y0 != y1  # horizontal edges cover no area
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


@njit(cache=True, inline="always")
def _inside(wind, evenodd):
    return (wind % 2 != 0) if evenodd else (wind != 0)


@njit(cache=True, inline="always")
def _side(wind_left, winding, evenodd):
    """+1 for a right boundary of the inside, -1 for a left one, 0 if the fill rule does not change."""
    return int(_inside(wind_left, evenodd)) - int(_inside(wind_left + winding, evenodd))


@njit(cache=True, inline="always")
def _fixed(offset):
    """A height offset in [0, 1] within its row, in integers of 2**-FIXED_BITS."""
    return np.int64(np.rint(offset * 2.0**FIXED_BITS))


@njit(cache=True)
def _add_piece(row, cover, xa, xb, t0, t1, y, sign, width, col0):
    """Add sign * F_E(c) of an edge piece from (xa, t0) to (xb, t1) in row y; returns the columns visited.

    The columns the piece crosses get F in closed form in `row`; the columns
    left of its first column (clamped to 0..width) get the full height, as a
    fixed-point step at that column in `cover`. `row` and `cover` start at
    column `col0` (the columns left of it are not kept; the work counts them).
    """
    h = t1 - t0
    lo, hi = min(xa, xb), max(xa, xb)
    first = min(max(int(np.floor(lo)), 0), width)
    kept = max(first, col0)  # a step left of col0 reaches every kept column: put it at col0
    cover[kept - col0] -= sign * (_fixed(t1 - y) - _fixed(t0 - y))  # from `first` on
    last = min(int(np.floor(hi)), width - 1)
    span = hi - lo
    for c in range(kept, last + 1):
        if span == 0.0:
            row[c - col0] += sign * h * (lo - c)
            continue
        u0, u1 = max(lo, float(c)), min(hi, c + 1.0)
        inside_time = h * (u1 - u0) / span
        right_time = h * (hi - u1) / span
        row[c - col0] += sign * (inside_time * (0.5 * (u0 + u1) - c) + right_time)
    return max(last - first + 1, 0) + 1


@njit(cache=True, inline="always")
def _x(edge, t):
    """x of an edge record at height t, exact at its ends."""
    return _x_at(edge.ax, edge.ay, edge.bx, edge.by, t)


@njit(cache=True, inline="always")
def _slope(edge):
    return (edge.bx - edge.ax) / (edge.by - edge.ay)


# The sweep's table: entry e holds edge e (lower end (ax, ay), upper end (bx, by), winding) and
# its state in the row being swept, and entry i of each of the row's lists. The steps pass
# records, not arrays: a record costs no reference count, and numba counts (atomically) every
# array a step is given. Measured on a swap-bound 2,000-edge polygon: the steps given five
# arrays each ran 1.2 times slower than closures over the arrays in one 140-line function;
# given this table, 1.07 times.
SWEEP_TABLE = np.dtype(
    [
        ("ax", np.float64), ("ay", np.float64), ("bx", np.float64), ("by", np.float64),
        ("winding", np.int64),
        ("position", np.int64),  # its index in the row's x order (-1: not present)
        ("side", np.int64),  # +1 a right boundary of the inside, -1 a left one, 0 neither
        ("since", np.float64),  # the height where it got that side
        ("right_of", np.int64),  # its right neighbour when last scheduled (-1 none, -2 not yet)
        ("slot", np.int64),  # its slot in the swap heap (-1: not queued)
        ("height", np.float64),  # the heap's key: the height where it swaps with right_of,
        ("serial", np.int64),  # then the order of scheduling
        # The lists: the present edges left to right and the winding left of each, the swap
        # heap (of left edges), the edges entering and leaving inside the row, and scratch.
        ("order", np.int64), ("wind_left", np.int64), ("heap", np.int64),
        ("entering", np.int64), ("leaving", np.int64), ("merged", np.int64),
    ],
    align=True,
)  # fmt: skip
# The sweep's own record: the heap's size, the next serial, the row, its first kept column
# and the fill rule.
SWEEP = np.dtype(
    [("heap_size", np.int64), ("next_serial", np.int64), ("y", np.int64), ("col0", np.int64),
     ("evenodd", np.bool_)],
    align=True,
)  # fmt: skip


@njit(cache=True)
def _sweep_table(ax, ay, bx, by, winding):
    """The sweep's table of the edges, with no side and not queued."""
    table = np.empty(len(ay), SWEEP_TABLE)
    for e in range(len(ay)):
        edge = table[e]
        edge.ax, edge.ay, edge.bx, edge.by, edge.winding = ax[e], ay[e], bx[e], by[e], winding[e]
        edge.side, edge.slot = 0, -1
    return table


@njit(cache=True)
def _sorted_at(table, edges, t):
    """`edges` sorted by x at height t, ties by slope (their order just above t): with the keys."""
    xs, slopes = np.empty(len(edges)), np.empty(len(edges))
    for i, e in enumerate(edges):
        xs[i], slopes[i] = _x(table[e], t), _slope(table[e])
    by_slope = np.argsort(slopes, kind="mergesort")
    order = by_slope[np.argsort(xs[by_slope], kind="mergesort")]
    return edges[order], xs[order], slopes[order]


@njit(cache=True)
def _swap_height(left, right, now, y):
    """Where edge `right` must pass edge `left` (at or above `now`), or +inf if their order holds.

    The pair must swap iff `left` lies right of `right` where the first of
    them ends (in row y): a fixed test, so a pair swaps at most once per row
    whatever rounding did to the order. It swaps where they cross, found from
    their x at the ends of their common span, or at once if they are already
    out of order there.
    """
    lo = max(max(left.ay, right.ay), float(y))
    top = min(min(left.by, right.by), y + 1.0)
    d_top = _x(left, top) - _x(right, top)
    if not d_top > 0.0:
        return np.inf
    d_lo = _x(left, lo) - _x(right, lo)
    crossing = min(lo + (top - lo) * (d_lo / (d_lo - d_top)), top) if d_lo < 0.0 else lo
    return max(crossing, now)


@njit(cache=True)
def _row_events(table, edges, y):
    """List the row's edges in order of entry (those present at y first) and of exit: (n_in, n_out)."""
    n_in = n_out = 0
    for starts_above in (False, True):
        for e in edges:
            if (table[e].ay > y) == starts_above:  # above y in order of ay: the AET
                table[n_in].entering = e
                n_in += 1
    leaving, ends = np.empty(len(edges), np.int64), np.empty(len(edges))
    for e in edges:
        if table[e].by < y + 1.0:
            leaving[n_out], ends[n_out] = e, table[e].by
            n_out += 1
    for k, i in enumerate(np.argsort(ends[:n_out], kind="mergesort")):
        table[k].leaving = leaving[i]
    return n_in, n_out


@njit(cache=True, inline="always")
def _spread_cover(row, cover):
    """Prefix-sum the fixed-point full-height steps of `cover` into `row`, clearing `cover`."""
    covered = 0
    for c in range(len(row)):
        covered += cover[c]
        cover[c] = 0
        if covered != 0:
            row[c] += covered * 2.0**-FIXED_BITS
    cover[len(row)] = 0


# The steps of a row's sweep. They take, in this order, what they use of: the `table`, the
# `sweep` record, the row's areas `row` (columns col0 on) and its full-height steps `cover`.


@njit(cache=True, inline="always")
def _set_side(edge, new, t, sweep, row, cover):
    """Give `edge` side `new` from height t on, adding its finished piece: columns visited."""
    work = 0
    if edge.side != 0 and t > edge.since:
        xa, xb, col0 = _x(edge, edge.since), _x(edge, t), sweep.col0
        work = _add_piece(
            row, cover, xa, xb, edge.since, t, sweep.y, edge.side, col0 + len(row), col0
        )
    edge.side, edge.since = new, t
    return work


@njit(cache=True, inline="always")
def _earlier(a, b):
    """Whether record a's swap comes first: the lower height, then the earlier scheduled."""
    return a.height < b.height or (a.height == b.height and a.serial < b.serial)


@njit(cache=True, inline="always")
def _schedule(table, sweep, left, right, now):
    """(Re)schedule the swap of `left` with its new right neighbour `right` (-1: none)."""
    edge = table[left]
    edge.right_of = right
    swap_at = _swap_height(edge, table[right], now, sweep.y) if right >= 0 else np.inf
    slot = edge.slot
    if swap_at < np.inf:
        edge.height, edge.serial = swap_at, sweep.next_serial
        sweep.next_serial += 1
        if slot < 0:
            slot = sweep.heap_size
            table[slot].heap = left
            sweep.heap_size += 1
    else:  # no swap: take `left` out of the heap, if it is there
        if slot < 0:
            return
        edge.slot = -1
        sweep.heap_size -= 1
        last = table[sweep.heap_size].heap
        if last == left:
            return
        table[slot].heap = last
    # Sift the edge in heap slot `slot` up or down to where its key belongs.
    e, i, size = table[slot].heap, slot, sweep.heap_size
    while i > 0 and _earlier(table[e], table[table[(i - 1) // 2].heap]):
        table[i].heap = table[(i - 1) // 2].heap
        table[table[i].heap].slot = i
        i = (i - 1) // 2
    while 2 * i + 1 < size:
        child = 2 * i + 1
        if child + 1 < size and _earlier(table[table[child + 1].heap], table[table[child].heap]):
            child += 1
        if not _earlier(table[table[child].heap], table[e]):
            break
        table[i].heap = table[child].heap
        table[table[i].heap].slot = i
        i = child
    table[i].heap = e
    table[e].slot = i


@njit(cache=True, inline="always")
def _refresh(table, sweep, row, cover, n, t):
    """After the order of n edges changed at height t: positions, windings, sides and swaps."""
    work, wind = n, 0
    for i in range(n):
        e = table[i].order
        edge = table[e]
        edge.position, table[i].wind_left = i, wind
        side = _side(wind, edge.winding, sweep.evenodd)
        if side != edge.side:
            work += _set_side(edge, side, t, sweep, row, cover)
        wind += edge.winding
        right = table[i + 1].order if i + 1 < n else -1
        if edge.right_of != right:
            _schedule(table, sweep, e, right, t)
    return work


@njit(cache=True)
def _vertex_height(table, sweep, row, cover, n, t, leaving_now, entering_now):
    """At height t drop the edges of list slots `leaving_now`, merge in `entering_now`: (n, work)."""
    work = 0
    for k in leaving_now:
        e = table[k].leaving
        if table[e].side != 0:
            work += _set_side(table[e], 0, t, sweep, row, cover)
        _schedule(table, sweep, e, -1, t)
        table[e].position = -1
    new = np.empty(len(entering_now), np.int64)
    for j, k in enumerate(entering_now):
        new[j] = table[k].entering
    new, new_x, new_slope = _sorted_at(table, new, t)
    count, j = 0, 0
    for i in range(n):
        edge = table[table[i].order]
        if edge.position < 0:
            continue
        x, slope = _x(edge, t), _slope(edge)
        while j < len(new) and (new_x[j] < x or (new_x[j] == x and new_slope[j] < slope)):
            table[count].merged = new[j]
            count, j = count + 1, j + 1
        table[count].merged = table[i].order
        count += 1
    for e in new[j:]:
        table[count].merged = e
        count += 1
    for e in new:
        table[e].right_of = -2
    for i in range(count):
        table[i].order = table[i].merged
    return count, work + _refresh(table, sweep, row, cover, count, t)


@njit(cache=True)
def _sweep_row(table, sweep, row, cover, edges, max_work):
    """Add the coverage of row sweep.y by its `edges` to `row`; returns the work.

    The sweep stops past `max_work`.
    """
    y = sweep.y
    top = y + 1.0
    n_in, n_out = _row_events(table, edges, y)
    n, work, i_in, i_out = 0, len(edges), 0, 0
    while work <= max_work:
        t = min(
            max(table[table[i_in].entering].ay, float(y)) if i_in < n_in else top,
            table[table[i_out].leaving].by if i_out < n_out else top,
        )
        if sweep.heap_size and table[table[0].heap].height <= t:  # the first queued pair swaps
            left = table[0].heap
            right, t, i = table[left].right_of, table[left].height, table[left].position
            table[i].order, table[i + 1].order = right, left
            table[right].position, table[left].position = i, i + 1
            table[i + 1].wind_left = table[i].wind_left + table[right].winding  # the only change
            work += 1
            for k in (i, i + 1):
                edge = table[table[k].order]
                side = _side(table[k].wind_left, edge.winding, sweep.evenodd)
                if side != edge.side:
                    work += _set_side(edge, side, t, sweep, row, cover)
            for k in (i - 1, i, i + 1):  # the three pairs that changed
                if k >= 0:
                    right = table[k + 1].order if k + 1 < n else -1
                    _schedule(table, sweep, table[k].order, right, t)
            continue
        if t == top:
            break
        j_in, j_out = i_in, i_out
        while j_in < n_in and max(table[table[j_in].entering].ay, float(y)) == t:
            j_in += 1
        while j_out < n_out and table[table[j_out].leaving].by == t:
            j_out += 1
        n, more = _vertex_height(
            table, sweep, row, cover, n, t, range(i_out, j_out), range(i_in, j_in)
        )
        work += more
        i_in, i_out = j_in, j_out
    for i in range(n):
        edge = table[table[i].order]
        if edge.side != 0:
            work += _set_side(edge, 0, top, sweep, row, cover)
    _spread_cover(row, cover)
    return work


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
def _coverage_kernel(
    ax, ay, bx, by, winding, width, height, evenodd, row0, row1, max_work, col0=0
):  # fmt: skip
    """Exact coverage of rows [row0, row1): ((row1 - row0, width - col0) float64 array, work).

    Each row is swept on its own, from the edges that reach it (in the order
    of the edge arrays), so a row's areas do not depend on the other rows.
    Memory is linear in the edges. Past `max_work` steps the kernel stops and
    returns the work reached (the caller refuses the polygon). Columns from
    `col0` on are kept, their areas and the work the same as with col0 = 0:
    a window's left end, so that small polygons cost their size.
    """
    count = len(ay)
    image = np.zeros((max(row1 - row0, 0), width - col0))
    cover = np.zeros(width - col0 + 1, np.int64)
    active = np.empty(count, np.int64)
    table = _sweep_table(ax, ay, bx, by, winding)
    sweep = np.zeros(1, SWEEP)  # its record is sweep[0] (a record alone would not keep it alive)
    sweep[0].col0, sweep[0].evenodd = col0, evenodd
    work = 0
    next_edge = n_active = 0
    for y in range(row0, row1):
        n_active, next_edge = _update_active(ay, by, active, n_active, next_edge, y)
        if n_active:
            sweep[0].y = y
            edges = active[:n_active]
            work += _sweep_row(table, sweep[0], image[y - row0], cover, edges, max_work - work)
            if work > max_work:
                return image, work
    return image, work


@njit(cache=True)
def _least_work(ax, ay, bx, by, row0, row1, max_work):
    """A lower bound on the kernel's work in rows [row0, row1); stops past `max_work`.

    Per row, the sweep sorts its edges and swaps each pair of row-spanning
    edges whose x order at the bottom (the sweep's starting order) and at the
    top differ once: O(n log n) a row.
    """
    count = len(ay)
    active = np.empty(count, np.int64)
    tops, scratch = np.empty(count), np.empty(count)
    table = _sweep_table(ax, ay, bx, by, np.zeros(count, np.int64))
    work = 0.0
    next_edge = n_active = 0
    for y in range(row0, row1):
        n_active, next_edge = _update_active(ay, by, active, n_active, next_edge, y)
        edges = active[:n_active]
        spanning = edges[(ay[edges] <= y) & (by[edges] >= y + 1.0)]
        spanning = _sorted_at(table, spanning, float(y))[0]
        for i, e in enumerate(spanning):
            tops[i] = _x(table[e], y + 1.0)
        m = len(spanning)
        work += n_active + float(inversions(tops[:m], scratch[:m]))
        if work > max_work:
            return work
    return work


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
        extra_bytes + 8 * (row1 - row0) * width + 16 * width + EDGE_BYTES * len(edges[0]),
        f"{what}: {row1 - row0} rows of {width} float64 areas",
    )
    # Refuse at once what surely needs too much work; the kernel stops at the rest.
    least = _least_work(*edges[:4], row0, row1, MAX_WORK)
    if least > MAX_WORK:
        raise _too_much_work(what, len(edges[0]), f"at least {least:.3g}")
    rows, work = _coverage_kernel(*edges, width, height, rule == "evenodd", row0, row1, MAX_WORK)
    if work > MAX_WORK:
        raise _too_much_work(what, len(edges[0]), f"over {work}")
    return row0, np.clip(rows, 0.0, 1.0, out=rows)


def _too_much_work(what: str, edges: int, steps: str) -> ValueError:
    return ValueError(
        f"{what}: the polygon's {edges} edges need too many sweep steps "
        f"({steps}, limit {MAX_WORK}): every crossing of two edges inside a pixel row is "
        "a step, and every height where edges start or end costs a step per edge of its row; "
        "use fewer edge crossings or vertices per pixel row"
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
        option is unknown or out of range; or if the sweep needs over 2**26
        steps (about one per crossing of two edges inside a pixel row, per
        edge of a row at each height where edges start or end, and per
        boundary pixel: see the module docs), refused at once when a lower
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

"""Compiled scanline visibility (numba), and the depth certificates both paths share.

`scanline_ids` is `scanline.scanline_reference` without the tracing: one edge
table of all drawn polygons (the shared `edge_table` per polygon, merged by
first row), one active edge table of exact crossings sorted by ceil(x) (the
shared row step, `scanviz.raster.walk_compiled.step_row`), so each
polygon covers on each row exactly the samples the z-buffer's scan conversion
gives it (`scanviz.raster.scan_compiled` explains why any order by ceiling gives the
same runs). The row's spans run between consecutive distinct crossing ceilings.

A span's visible surface is the one of least (z, index) at each sample, z from
the polygons' planes (`plane_depth`). The reference compares at every sample;
here a *certificate* proves one surface nearest over a whole span at once:

* z_p(x) in float64 differs from the plane's exact value by at most
  `depth_error` (a bound on the rounding of `plane_depth`, times four so that
  it also covers the rounding of the bound's own arithmetic);
* the exact depth difference d(x) = z_s(x) - z_w(x) of two planes is linear
  in x, so a lower bound at both ends of a span bounds it everywhere between;
* hence `pair_slack` > 0 for every other surface s proves that w wins at
  every sample with a strict float comparison (no tie is ever certified).

A span whose certificate fails is cut at the estimated crossing of the first
surface to overtake w (or in half) and each part is decided the same way,
down to single samples, which are compared directly: the result is the
reference's, sample for sample.

Coherence: d(x, y) is linear in y too, so a slack certified on row y0 shrinks
by at most `pair_rate` per row; a span with the same ends and the same
surfaces on the next rows keeps its decision while `still_certain` holds.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..raster.walk_compiled import (
    CEIL,
    ROW_END,
    ROW_START,
    TABLE_FIELDS,
    WINDING,
    edge_table,
    scratch_aet,
    step_row,
)
from .zbuffer_compiled import plane_depth

ROUNDING = 16 * 2.0**-53  # 4 unit roundings for plane_depth's 4 operations, times a margin of 4
SAFETY = 2.0**-50  # relative margin for the two roundings of `still_certain`

# Fields of the counts `scanline_ids` returns (and `ScanlineStats` holds).
ROWS, SPANS, BACKGROUND, DECIDED, REUSED, SPLIT, MAX_ACTIVE = range(7)
COUNT_FIELDS = 7


# --- the certificates, plain Python shared with the compiled kernel -------------------------


def depth_error(x_first, y_first, z_first, dzdx, dzdy, x, y):
    """A bound on |plane_depth(...) - the plane's exact depth| at (x, y).

    >>> depth_error(0.0, 0.0, 1.0, 0.0, 0.0, 5.0, 5.0) == 16 * 2.0**-53
    True
    """
    return ROUNDING * (abs(z_first) + abs(dzdx * (x - x_first)) + abs(dzdy * (y - y_first)))


def pair_slack(near_first, near_last, far_first, far_last, error_first, error_last):
    """How surely the `near` surface is strictly nearer than `far` on all of a span (> 0: sure).

    The arguments are both surfaces' depths at the span's first and last
    samples, and the sum of their `depth_error` there. The exact difference
    d = z_far - z_near is at least ``floor`` at both ends, hence everywhere
    between (it is linear); the float depths differ from the exact ones by
    less than the larger error, so the float difference is positive wherever
    ``floor - max(error)`` is.

    >>> pair_slack(0.1, 0.2, 0.5, 0.5, 1e-15, 1e-15) > 0, pair_slack(0.1, 0.6, 0.5, 0.5, 0.0, 0.0) > 0
    (True, False)
    """
    floor = min(far_first - near_first - error_first, far_last - near_last - error_last)
    return floor - max(error_first, error_last)


def pair_rate(dzdy_near, dzdy_far):
    """The most `pair_slack` can shrink per row: the change of d and of the error bound.

    >>> pair_rate(0.5, 0.25) > 0.25
    True
    """
    return abs(dzdy_far - dzdy_near) + ROUNDING * (abs(dzdy_far) + abs(dzdy_near))


def still_certain(slack, rate, rows):
    """Whether a certificate with `slack` and `rate` still holds `rows` rows later.

    >>> still_certain(1.0, 0.25, 3), still_certain(1.0, 0.25, 4)
    (True, False)
    """
    return slack * (1.0 - SAFETY) > rows * rate * (1.0 + SAFETY)


depth_error_compiled = njit(cache=True, inline="always")(depth_error)
pair_slack_compiled = njit(cache=True, inline="always")(pair_slack)
pair_rate_compiled = njit(cache=True, inline="always")(pair_rate)
still_certain_compiled = njit(cache=True, inline="always")(still_certain)


# --- the compiled algorithm -----------------------------------------------------------------


@njit(cache=True, inline="always")
def evaluate(members, k, planes, x, y, depth, error):
    """Depth and `depth_error` of members[:k] at sample (x, y); return the index of the nearest.

    The nearest is the least (depth, polygon): ties go to the lower index.
    """
    best = 0
    for i in range(k):
        p = members[i]
        plane = planes[p]
        depth[i] = plane_depth(plane[0], plane[1], plane[2], plane[3], plane[4], x, y)
        error[i] = depth_error_compiled(plane[0], plane[1], plane[2], plane[3], plane[4], x, y)
        if depth[i] < depth[best] or (depth[i] == depth[best] and p < members[best]):
            best = i
    return best


@njit(cache=True)
def certify(members, k, planes, best, first, last, y, scratch):
    """(slack, rate, cut) of members[best] nearest on samples [first, last] of row y.

    slack > 0 proves it; otherwise `cut` is the first sample past the
    earliest estimated crossing of a surface overtaking it (-1 if none
    crosses). scratch[0:2] hold depths and errors at `first` (`evaluate`);
    scratch[2:4] receive them at `last`.
    """
    first_depth, first_error = scratch[0], scratch[1]
    last_depth, last_error = scratch[2], scratch[3]
    if last == first:
        last_depth, last_error = first_depth, first_error
    else:
        evaluate(members, k, planes, last, y, last_depth, last_error)
    w = members[best]
    slack, rate, cut = np.inf, 0.0, -1
    for i in range(k):
        if i == best:
            continue
        pair = pair_slack_compiled(
            first_depth[best], last_depth[best], first_depth[i], last_depth[i],
            first_error[best] + first_error[i], last_error[best] + last_error[i],
        )  # fmt: skip
        slack = min(slack, pair)
        rate = max(rate, pair_rate_compiled(planes[w, 4], planes[members[i], 4]))
        gap_first, gap_last = first_depth[i] - first_depth[best], last_depth[i] - last_depth[best]
        if pair <= 0.0 and gap_last < 0.0 <= gap_first:  # it overtakes w inside: where?
            at = first + int(np.floor(gap_first / (gap_first - gap_last) * (last - first))) + 1
            cut = at if cut < 0 else min(cut, at)
    return slack, rate, cut


@njit(cache=True)
def decide_span(members, k, planes, first, end, y, ids, stack, scratch):
    """Write the visible surface of samples [first, end) of row y; return the pieces (runs).

    Parts are decided left to right from a stack: a certified part is filled,
    a single sample is compared directly, any other part is cut and pushed.
    """
    pieces, previous = 0, -1
    stack[0, 0], stack[0, 1], top = first, end, 1
    while top > 0:
        top -= 1
        low, high = stack[top, 0], stack[top, 1]
        best = evaluate(members, k, planes, low, y, scratch[0], scratch[1])
        if high - low > 1:
            slack, _, cut = certify(members, k, planes, best, low, high - 1, y, scratch)
            if slack <= 0.0:
                middle = cut if low < cut < high else (low + high) // 2
                stack[top, 0], stack[top, 1] = middle, high
                stack[top + 1, 0], stack[top + 1, 1] = low, middle
                top += 2
                continue
        w = members[best]
        ids[y, low:high] = w
        pieces += w != previous
        previous = w
    return pieces


@njit(cache=True)
def merged_edge_table(units, offsets, drawn, scale, height):
    """The edge tables of the drawn polygons, one (9, E) table sorted by first row, and each edge's polygon.

    Also each polygon's rows [y_start, y_end) (0, 0 when not drawn).
    """
    count = offsets.shape[0] - 1
    tables = []
    total = 0
    y_start, y_end = np.zeros(count, np.int64), np.zeros(count, np.int64)
    for p in range(count):
        if not drawn[p]:
            tables.append(np.empty((TABLE_FIELDS, 0), np.int64))
            continue
        table = np.empty((TABLE_FIELDS, offsets[p + 1] - offsets[p]), np.int64)
        edges, _, _ = edge_table(units, offsets[p : p + 2], scale, height, table)
        table = table[:, :edges].copy()  # contiguous, as the list's other tables
        tables.append(table)
        total += table.shape[1]
        if table.shape[1]:
            y_start[p] = table[ROW_START].min()
            y_end[p] = min(table[ROW_END].max(), height)
    merged, polygon_of = np.empty((TABLE_FIELDS, total), np.int64), np.empty(total, np.int64)
    column = 0
    for p in range(count):
        n = tables[p].shape[1]
        merged[:, column : column + n] = tables[p]
        polygon_of[column : column + n] = p
        column += n
    order = np.argsort(merged[ROW_START], kind="mergesort")
    return np.ascontiguousarray(merged[:, order]), polygon_of[order], y_start, y_end


@njit(cache=True)
def same_surfaces(members, k, snapshot, stamp):
    """Whether members[:k] holds exactly the surfaces of `snapshot` (both without repeats).

    stamp[0] is a fresh token; stamp[1 + p] == token marks p as in the snapshot.
    """
    if snapshot.shape[0] != k:
        return False
    for p in snapshot:
        stamp[1 + p] = stamp[0]
    for i in range(k):
        if stamp[1 + members[i]] != stamp[0]:
            return False
    return True


@njit(cache=True)
def reusable(previous, certificates, snapshots, match, start, end, members, k, slot, stamp, y):
    """Whether span `match` of the row below has ends [start, end), the same surfaces, and a
    certificate that still holds on row y (coherence)."""
    record = previous[match]
    w = record[2]
    if record[0] != start or record[1] != end or slot[w] < 0:
        return False
    if not still_certain_compiled(certificates[match, 0], certificates[match, 1], y - record[3]):
        return False
    stamp[0] += 1  # a fresh token: stamp[1 + p] == token marks p as in the snapshot
    return same_surfaces(members, k, snapshots[record[4] : record[4] + record[5]], stamp)


@njit(cache=True, inline="always")
def cross(aet, edge_of, polygon_of, i, n_active, at, width, winding, members, slot, k):
    """Take the crossings at ceiling `at` (clipped), from AET entry i: surfaces enter or leave.

    members[:k] are the surfaces over the span, slot[p] p's place there (-1:
    absent). Returns (i, k) after the crossings.
    """
    while i < n_active and min(max(aet[CEIL, i], 0), width) == at:
        p = polygon_of[edge_of[i]]
        inside = winding[p] != 0
        winding[p] += aet[WINDING, i]
        if inside and winding[p] == 0:  # p's run ends: swap-remove it
            k -= 1
            last = members[k]
            members[slot[p]], slot[last], slot[p] = last, slot[p], -1
        elif not inside and winding[p] != 0:
            members[k], slot[p] = p, k
            k += 1
        i += 1
    return i, k


@njit(cache=True)
def decide(members, k, planes, start, end, y, ids, stack, scratch, counts, coherence):
    """Span [start, end) of row y over members[:k] (k >= 2) decided by depth; fill its ids.

    Returns (visible at start, slack, rate): the certificate of the whole span
    (not computed for a single sample without coherence: the comparison decides it).
    """
    counts[DECIDED] += 1
    best = evaluate(members, k, planes, start, y, scratch[0], scratch[1])
    if end - start == 1 and not coherence:
        ids[y, start] = members[best]
        return members[best], 0.0, 0.0
    slack, rate, _ = certify(members, k, planes, best, start, end - 1, y, scratch)
    if slack > 0.0:
        ids[y, start:end] = members[best]
    elif decide_span(members, k, planes, start, end, y, ids, stack, scratch) > 1:
        counts[SPLIT] += 1
    return members[best], slack, rate


@njit(cache=True)
def keep(kept, certificates, snapshots, n, used, record, certificate, members, k):
    """Append a span for the row above: its `record` (start, end, visible, row), certificate, surfaces.

    Returns (snapshots, n, used): the surfaces' buffer (grown if needed) and the new counts.
    """
    if used + k > snapshots.shape[0]:
        grown = np.empty(2 * (used + k), np.int64)
        grown[:used] = snapshots[:used]
        snapshots = grown
    snapshots[used : used + k] = members[:k]
    kept[n, 0], kept[n, 1], kept[n, 2], kept[n, 3] = record
    kept[n, 4], kept[n, 5] = used, k
    certificates[n, 0], certificates[n, 1] = certificate
    return snapshots, n + 1, used + k


@njit(cache=True)
def scanline_ids(units, offsets, drawn, planes, scale, width, height, coherence):
    """The visible polygon per sample, (height, width) int64 (-1: background), and the counts.

    `units` (M, 2) int64 are the snapped vertices, polygon p the rows
    offsets[p]:offsets[p+1]; `planes` (P, 5) the depth planes; only `drawn`
    polygons take part. Returns (ids, counts, y_start, y_end): counts by the
    fields ROWS ... MAX_ACTIVE; each polygon's rows [y_start, y_end).
    """
    count = offsets.shape[0] - 1
    ids = np.full((height, width), -1, np.int64)
    counts = np.zeros(COUNT_FIELDS, np.int64)
    table, polygon_of, y_start, y_end = merged_edge_table(units, offsets, drawn, scale, height)
    edges = table.shape[1]
    aet, xs, edge_of = scratch_aet(edges, np.float64)
    winding, slot = np.zeros(count, np.int64), np.full(count, -1, np.int64)
    members, stamp = np.empty(count, np.int64), np.zeros(count + 1, np.int64)
    stack = np.empty((2 * width + 2, 2), np.int64)
    scratch = np.empty((4, count))  # depths and errors of the members at two samples
    changes = np.zeros(height + 1, np.int64)  # AST size change per row: +1 entering, -1 exhausted
    for p in range(count):
        if y_start[p] < y_end[p]:
            changes[y_start[p]] += 1
            changes[y_end[p]] -= 1
    # The row below's spans that coherence may reuse: (start, end, visible, row decided,
    # first surface in `snapshots`, surface count), and their certificates (slack, rate).
    below, certificates = np.empty((width + 1, 6), np.int64), np.empty((width + 1, 2))
    snapshots = np.empty(0, np.int64)
    below_count, below_row = 0, -2
    ast = n_active = entering = next_change = 0
    y = table[ROW_START, 0] if edges else height
    while y < height and (n_active > 0 or entering < edges):
        y, n_active, entering = step_row(
            table, edges, entering, aet, xs, edge_of, n_active, y, scale, True, np.float64, False
        )
        while next_change <= y:
            ast += changes[next_change]
            next_change += 1
        if n_active == 0:
            continue  # the last polygons were exhausted: on to the next entering one, if any
        counts[ROWS] += 1
        counts[MAX_ACTIVE] = max(counts[MAX_ACTIVE], ast)
        kept, kept_certificates = np.empty((width + 1, 6), np.int64), np.empty((width + 1, 2))
        kept_snapshots = np.empty(1024, np.int64)
        kept_count = used = match = k = start = i = 0
        while start < width:
            end = width if i == n_active else min(max(aet[CEIL, i], 0), width)
            if end > start:  # span [start, end) over members[:k]
                counts[SPANS] += 1
                counts[BACKGROUND] += k == 0
                if k == 1:
                    ids[y, start:end] = members[0]
                elif k > 1:
                    while match < below_count and below[match, 0] < start:
                        match += 1
                    if (
                        coherence and below_row == y - 1 and match < below_count
                        and reusable(below, certificates, snapshots, match, start, end, members, k, slot, stamp, y)
                    ):  # fmt: skip
                        counts[REUSED] += 1
                        w, origin = below[match, 2], below[match, 3]
                        slack, rate = certificates[match, 0], certificates[match, 1]
                        ids[y, start:end] = w
                    else:
                        w, slack, rate = decide(members, k, planes, start, end, y, ids, stack, scratch, counts, coherence)  # fmt: skip
                        origin = y
                    if coherence and still_certain_compiled(slack, rate, y + 1 - origin):
                        kept_snapshots, kept_count, used = keep(
                            kept, kept_certificates, kept_snapshots, kept_count, used,
                            (start, end, w, origin), (slack, rate), members, k,
                        )  # fmt: skip
                start = end
            i, k = cross(
                aet, edge_of, polygon_of, i, n_active, end, width, winding, members, slot, k
            )
        # Every polygon's windings sum to zero along a row: no surface is left over.
        below, certificates, below_count = kept, kept_certificates, kept_count
        snapshots, below_row = kept_snapshots[:used], y
        y += 1
    return ids, counts, y_start, y_end

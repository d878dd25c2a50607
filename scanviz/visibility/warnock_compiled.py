"""Warnock's area subdivision: the rule that classifies an area, and the compiled quadtree walk.

`area_case` is the one definition of the classification; the traced
reference (`scanviz.visibility.warnock`) runs it as Python, `subdivide`
runs its compiled twin. Coverage comes from the z-buffer's own spans of each
polygon (`scanviz.raster.api.scan_snapped`), indexed by row: polygon p's
spans on row y are rows ``row_spans[row_base[p] + y - row_first[p]]`` up to
the next entry of `spans`, for ``row_first[p] <= y < row_stop[p]``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..raster.interpolate import plane_depth as _plane_depth
from ..raster.scan_compiled import scan_spans

# Cases of an area, in the order of the tests (`CASES` names them).
EMPTY, SURROUNDING, SINGLE, SUBDIVIDE, PIXEL = range(5)
# Columns of a quadtree row: one visited area.
LEVEL, X_START, X_END, Y_START, Y_END, CASE, VISIBLE, PARENT, MEETING = range(9)
AREA_FIELDS = 9

plane_depth = njit(cache=True, inline="always")(_plane_depth)


def area_case(covered, samples, corners, tolerance):
    """Classify an area from its candidates' coverage and depths: (case, index, kept).

    Parameters
    ----------
    covered : (n,) ndarray of int64
        Samples of the area each candidate covers (0: disjoint; `samples`: surrounding).
    samples : int
        Samples in the area.
    corners : (n, 4) ndarray of float64
        Each candidate's plane depth at the area's four extreme samples, the
        lower-left one first.
    tolerance : float
        Margin in depth by which a polygon must be nearer at every corner to
        be in front over the whole area.

    Returns
    -------
    case : int
        EMPTY, PIXEL (one sample, several polygons), SURROUNDING, SINGLE or SUBDIVIDE.
    index : int
        The candidate shown (-1 for EMPTY and SUBDIVIDE).
    kept : (n,) ndarray of bool
        Candidates that meet the area and are not hidden behind its nearest
        surrounding polygon: those the sub-areas need.

    Examples
    --------
    >>> covered = np.array([4, 2])  # a 2x2 area: candidate 0 surrounds it, 1 meets it
    >>> corners = np.array([[1.0, 1.0, 1.0, 1.0], [2.0, 2.0, 2.0, 2.0]])
    >>> area_case(covered, 4, corners, 1e-9)[:2]  # 0 is in front of 1 everywhere
    (1, 0)
    >>> area_case(covered, 4, corners[::-1].copy(), 1e-9)  # 1 is in front of 0 somewhere
    (3, -1, array([ True,  True]))
    """
    kept = covered > 0
    meeting, nearest, last = 0, -1, -1
    for i in range(covered.shape[0]):
        if kept[i]:
            meeting, last = meeting + 1, i
            # The nearest surrounding polygon at the first corner; ties keep the earlier one.
            if covered[i] == samples and (nearest < 0 or corners[i, 0] < corners[nearest, 0]):
                nearest = i
    if meeting == 0:
        return EMPTY, -1, kept
    if samples == 1 and meeting > 1:  # all cover the sample: the first nearest is shown
        return PIXEL, nearest, kept
    if nearest >= 0:
        in_front = True
        for i in range(covered.shape[0]):
            if kept[i] and i != nearest:
                # Depths are linear: behind by more than the margin at the corners is behind everywhere.
                hidden = True
                for c in range(4):
                    hidden = hidden and corners[i, c] - corners[nearest, c] > tolerance
                kept[i] = not hidden
                in_front = in_front and hidden
        if in_front:
            return SURROUNDING, nearest, kept
    if meeting == 1:
        return SINGLE, last, kept
    return SUBDIVIDE, -1, kept


area_case_compiled = njit(cache=True)(area_case)


@njit(cache=True)
def polygon_spans(units, offsets, drawn, scale, width, height, max_spans):
    """(spans, span_start, refused): every drawn polygon's spans, as `scan_snapped` gives them.

    Polygon p's (nonzero rule, exact arithmetic) are rows
    span_start[p]:span_start[p + 1] of the (K, 3) spans; `refused` is
    nonzero when they would need more than `max_spans` rows.
    """
    count = offsets.shape[0] - 1
    spans = np.empty((1024, 3), np.int64)
    span_start = np.zeros(count + 1, np.int64)
    for p in range(count):
        total = span_start[p]
        if drawn[p]:
            contour = offsets[p : p + 2].copy()
            found, _, refused = scan_spans(
                units, contour, scale, width, height, False, True, np.float64, max_spans - total
            )
            if refused:
                return spans[:total], span_start, total + refused
            if total + found.shape[0] > spans.shape[0]:
                grown = np.empty((max(2 * spans.shape[0], total + found.shape[0]), 3), np.int64)
                grown[:total] = spans[:total]
                spans = grown
            spans[total : total + found.shape[0]] = found
            total += found.shape[0]
        span_start[p + 1] = total
    return spans[:total], span_start, 0


@njit(cache=True)
def row_index(spans, span_start, height):
    """(row_spans, row_base, row_first, row_stop, x_low, x_high) for the spans of each polygon.

    Polygon p's spans are rows span_start[p]:span_start[p + 1] of (K, 3)
    `spans` (y, x_start, x_end), in scan order (y, then x); x_low and x_high
    bound their samples (x_low >= x_high: none).
    """
    count = span_start.shape[0] - 1
    row_first, row_stop = np.zeros(count, np.int64), np.zeros(count, np.int64)
    x_low, x_high = np.zeros(count, np.int64), np.zeros(count, np.int64)
    row_base = np.zeros(count + 1, np.int64)
    for p in range(count):
        first, stop = span_start[p], span_start[p + 1]
        if stop > first:
            row_first[p], row_stop[p] = spans[first, 0], spans[stop - 1, 0] + 1
            x_low[p], x_high[p] = spans[first:stop, 1].min(), spans[first:stop, 2].max()
        row_base[p + 1] = row_base[p] + row_stop[p] - row_first[p] + 1
    row_spans = np.empty(row_base[count], np.int64)
    for p in range(count):
        k = span_start[p]
        for r in range(row_stop[p] - row_first[p] + 1):
            while k < span_start[p + 1] and spans[k, 0] < row_first[p] + r:
                k += 1
            row_spans[row_base[p] + r] = k
    return row_spans, row_base, row_first, row_stop, x_low, x_high


@njit(cache=True, inline="always")
def covered_samples(p, x0, x1, y0, y1, spans, rows):
    """How many samples of [x0, x1) x [y0, y1) polygon p's spans cover."""
    row_spans, row_base, row_first, row_stop, x_low, x_high = rows
    low, high = max(y0, row_first[p]), min(y1, row_stop[p])
    if low >= high or x_low[p] >= x1 or x_high[p] <= x0:
        return 0
    total = 0
    for y in range(low, high):
        r = row_base[p] + y - row_first[p]
        for k in range(row_spans[r], row_spans[r + 1]):
            start, end = max(spans[k, 1], x0), min(spans[k, 2], x1)
            total += max(end - start, 0)
    return total


@njit(cache=True, inline="always")
def fill_covered(target, p, x0, x1, y0, y1, spans, rows):
    """Write p into `target` at the samples of [x0, x1) x [y0, y1) its spans cover."""
    row_spans, row_base, row_first = rows[0], rows[1], rows[2]
    for y in range(max(y0, row_first[p]), min(y1, rows[3][p])):
        r = row_base[p] + y - row_first[p]
        for k in range(row_spans[r], row_spans[r + 1]):
            for x in range(max(spans[k, 1], x0), min(spans[k, 2], x1)):
                target[y, x] = p


@njit(cache=True, inline="always")
def corner_depths(planes, listed, x0, x1, y0, y1):
    """(n, 4) depth of each listed polygon's plane at the area's extreme samples."""
    corners = np.empty((listed.shape[0], 4))
    xs, ys = (x0, x1 - 1, x0, x1 - 1), (y0, y0, y1 - 1, y1 - 1)
    for i in range(listed.shape[0]):
        plane = planes[listed[i]]
        for c in range(4):
            corners[i, c] = plane_depth(
                plane[0], plane[1], plane[2], plane[3], plane[4], xs[c], ys[c]
            )
    return corners


@njit(cache=True, inline="always")
def halves(start, end):
    """(start, middle, end): [start, middle) and [middle, end) halve the range; middle = start if one wide."""
    return start, start + (end - start) // 2, end


@njit(cache=True, inline="always")
def put(table, i, values):
    """Row i of an int64 table from a tuple."""
    for k in range(len(values)):
        table[i, k] = values[k]


@njit(cache=True)
def subdivide(spans, rows, planes, candidates, width, height, tolerance, prune):
    """Warnock's subdivision of the width x height raster: (target, areas, tests).

    `candidates` (ascending) are the polygons drawn; `rows` is `row_index`'s
    result; `planes` (P, 5) as `Surfaces.planes`. Returns the (H, W) int64
    visible polygon per sample (-1: background), the (n, AREA_FIELDS) rows of
    the areas visited (depth first: lower left, lower right, upper left,
    upper right) and how many polygon-area classifications were made. With
    `prune`, sub-areas get only the polygons `area_case` keeps; without, all
    that meet the area.
    """
    target = np.full((height, width), -1, np.int64)
    areas = np.zeros((64, AREA_FIELDS), np.int64)
    levels = 2
    while (1 << (levels - 2)) < max(width, height):
        levels += 1
    # Candidate lists on a stack: an area's list lies above its ancestors' (depth first).
    pool = np.empty(levels * candidates.shape[0] + 1, np.int64)
    pool[: candidates.shape[0]] = candidates
    stack = np.empty(
        (4 * levels + 4, 8), np.int64
    )  # level, parent, x0, x1, y0, y1, list start, size
    depth, count, tests = 0, 0, 0
    if width * height > 0:
        put(stack, 0, (0, -1, 0, width, 0, height, 0, candidates.shape[0]))
        depth = 1
    while depth > 0:
        depth -= 1
        level, parent, x0, x1, y0, y1, start, size = stack[depth]
        listed = pool[start : start + size]
        samples = (x1 - x0) * (y1 - y0)
        covered = np.empty(size, np.int64)
        for i in range(size):
            covered[i] = covered_samples(listed[i], x0, x1, y0, y1, spans, rows)
        tests += size
        corners = corner_depths(planes, listed, x0, x1, y0, y1)
        case, index, kept = area_case_compiled(covered, samples, corners, tolerance)
        visible = listed[index] if index >= 0 else -1
        if count == areas.shape[0]:
            grown = np.zeros((2 * count, AREA_FIELDS), np.int64)
            grown[:count] = areas
            areas = grown
        put(areas, count, (level, x0, x1, y0, y1, case, visible, parent, (covered > 0).sum()))
        if case == SURROUNDING or case == PIXEL:
            target[y0:y1, x0:x1] = visible
        elif case == SINGLE:
            fill_covered(target, visible, x0, x1, y0, y1, spans, rows)
        elif case == SUBDIVIDE:
            passed = kept if prune else covered > 0
            top = start + size  # this area's list is done with once its children have theirs
            children = listed[passed]
            pool[top : top + children.shape[0]] = children
            xs, ys = halves(x0, x1), halves(y0, y1)
            for j in range(1, -1, -1):  # upper right pushed first: lower left is popped first
                for i in range(1, -1, -1):
                    if xs[i] < xs[i + 1] and ys[j] < ys[j + 1]:
                        child = (
                            level + 1,
                            count,
                            xs[i],
                            xs[i + 1],
                            ys[j],
                            ys[j + 1],
                            top,
                            len(children),
                        )
                        put(stack, depth, child)
                        depth += 1
        count += 1
    return target, areas[:count], tests

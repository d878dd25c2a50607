"""Compiled twins of the raster algorithms (numba): the reference's spans, fast.

`scan_polygon` is `scanline.scan_reference` without the tracing: the same edge
table, the same exact DDA (x = q + r/den pixels) or textbook float update with
the same operations in the same dtype, the same spans. Its rows are the shared
edge walker's (`scanviz.raster.walk_compiled.step_row`), the AET sorted by
ceil(x), not by x: every order by ceiling emits the same spans, as that module
explains (hence sort swaps are not counted here).

The span buffer grows with the output (a row adds fewer than min(active
edges, width + 1) spans), never past the `max_spans` its caller allows.

Coverage counts (`rasterize_triangles`, and `fill_batched.fill_polygons`) are
accumulated as +1/-1 marks where spans start and end, then one prefix sum per
row: the cost is O(spans + pixels), not O(covered area). `rasterize_triangles`
walks a triangle's two active edges (`walk_compiled.triangle_walk`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .walk_compiled import (
    CEIL,
    ROW_START,
    WINDING,
    ceil_div,
    edge_table,
    scratch_aet,
    step_row,
    triangle_span,
    triangle_walk,
)


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
    table = np.empty((9, offsets[-1] - offsets[0]), np.int64)
    count, edges, kept_for_topology = edge_table(units, offsets, scale, height, table)
    spans = np.empty((0 if image.size else min(count, 1024), 3), np.int64)
    refused = 0
    aet, xs, edge_of = scratch_aet(count, cast)
    parity = 1 if evenodd else -1  # winding & parity: odd for even-odd, nonzero for nonzero
    n_active = entering = span_count = rows_scanned = max_active = 0
    y = table[ROW_START, 0] if count else height
    while y < height and (n_active > 0 or entering < count):
        y, n_active, entering = step_row(
            table, count, entering, aet, xs, edge_of, n_active, y, scale, exact, cast, False
        )
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


@njit(cache=True)
def rasterize_triangles(units, scale, width, height):
    """(height, width) int32 count of the (T, 3, 2) int64 grid triangles covering each sample.

    Each triangle is walked on its two active edges (`triangle_walk`), its
    spans marked, then the rows are summed.
    """
    image = np.zeros((height, width), np.int32)
    first_row, stop_row = height, 0
    for t in range(units.shape[0]):
        x0, y0, x1, y1, x2, y2 = (
            units[t, 0, 0], units[t, 0, 1], units[t, 1, 0],
            units[t, 1, 1], units[t, 2, 0], units[t, 2, 1],
        )  # fmt: skip
        if ceil_div(max(x0, x1, x2), scale) <= 0 or ceil_div(min(x0, x1, x2), scale) >= width:
            continue  # every span would be clipped away
        first, stop, walk = triangle_walk(x0, y0, x1, y1, x2, y2, scale, height)
        for y in range(first, stop):
            start, end, walk = triangle_span(walk, y, scale, width)
            if start < end:
                mark_span(image, y, start, end)
        if first < stop:
            first_row, stop_row = min(first_row, first), max(stop_row, stop)
    prefix_sum_rows(image, first_row, stop_row)
    return image

"""`fill_polygons`: the coverage count of many polygons at once, in narrow batches (numba).

An optimisation for the fill benchmarks' many-polygon scenes: polygons are
marked (+1/-1 where spans start and end, `scan_compiled.mark_crossings`) in
batches whose summed marks fit int8 or int16, half or a quarter of the memory
of int32 to mark and to sum, then each batch's rows are prefix-summed into the
int32 counts. Polygons proved simple are marked without an AET
(`simple_fill`). docs/performance.md says what it measured.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .scan_compiled import scan_polygon
from .simple_fill import mark_simple, row_crossings, simple_orientation, star_orientation
from .walk_compiled import ceil_div

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

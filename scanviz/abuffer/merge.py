"""Carpenter's per-object merge: one fragment per surface piece of an object in a pixel.

Where polygons of one mesh meet inside a pixel, each leaves its own fragment:
partial masks that together cover what the surface covers, and (Phong or
Gouraud shaded) colors that differ a little. The a-buffer's combining step
(`pixelstruct.same_surface`) joins only fragments of equal color whose masks
fill the pixel, so on a smooth mesh the lists grow with the triangles per
pixel. Carpenter (1984) instead merges fragments of one object whose depth
ranges overlap: they are pieces of one surface.

`merge_by_object` does that before insertion, in both resolve paths: in each
pixel, the fragments of one object and one opacity, taken by zmin, form a
cluster while the next one's zmin is at most the cluster's zmax (overlapping
or abutting ranges). A cluster becomes one fragment: masks or-ed, areas
summed (at most 1), the depth range the union, the color weighted by area
(the first fragment's color if every area is 0), in the drawing position and
polygon of its first fragment. A merged fragment with a full mask and an area
within `COMPLETE_TOLERANCE` of 1 is complete (area 1): the areas of the
pieces are computed apart, and their sum misses 1 by a few ulps.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numba import njit

COMPLETE_TOLERANCE = 1e-9  # a merged area this close to 1 under a full mask is 1
MERGES = ("none", "object")


@njit(cache=True, inline="always")
def _sorts_before(i, j, objects, opacity, zmin):
    """Order within a pixel: by object, opacity, zmin, then drawing order."""
    if objects[i] != objects[j]:
        return objects[i] < objects[j]
    if opacity[i] != opacity[j]:
        return opacity[i] < opacity[j]
    if zmin[i] != zmin[j]:
        return zmin[i] < zmin[j]
    return i < j


@njit(cache=True)
def _sort_group(rows, objects, opacity, zmin):
    """Sort `rows` (one pixel's fragment rows) in place by `_sorts_before`."""
    if len(rows) > 32:  # three stable passes, last key first
        for key in (zmin, opacity):
            rows[:] = rows[np.argsort(key[rows], kind="mergesort")]
        rows[:] = rows[np.argsort(objects[rows], kind="mergesort")]
        return
    for k in range(1, len(rows)):
        row, j = rows[k], k
        while j > 0 and _sorts_before(row, rows[j - 1], objects, opacity, zmin):
            rows[j] = rows[j - 1]
            j -= 1
        rows[j] = row


@njit(cache=True)
def merge_kernel(pixels, pixel_count, objects, opacity, zmin, zmax, area, mask, color, full):
    """Merge clusters in place (into each cluster's first row); returns the rows kept (bool)."""
    n = len(pixels)
    starts = np.zeros(pixel_count + 1, np.int64)
    for p in pixels:
        starts[p + 1] += 1
    for p in range(pixel_count):
        starts[p + 1] += starts[p]
    grouped = np.empty(n, np.int64)
    fill = starts[:-1].copy()
    for i in range(n):  # rows by pixel, in drawing order within each
        grouped[fill[pixels[i]]] = i
        fill[pixels[i]] += 1
    keep = np.ones(n, np.bool_)
    for p in range(pixel_count):
        rows = grouped[starts[p] : starts[p + 1]]
        if len(rows) < 2:
            continue
        _sort_group(rows, objects, opacity, zmin)
        k = 0
        while k < len(rows):
            first = k
            top = zmax[rows[k]]
            k += 1
            while (
                k < len(rows)
                and objects[rows[k]] == objects[rows[first]]
                and opacity[rows[k]] == opacity[rows[first]]
                and zmin[rows[k]] <= top
            ):
                top = max(top, zmax[rows[k]])
                k += 1
            if k - first > 1:
                _merge_cluster(rows[first:k], zmin, zmax, area, mask, color, full, keep)
    return keep


@njit(cache=True)
def _merge_cluster(rows, zmin, zmax, area, mask, color, full, keep):
    """Write the merged fragment of `rows` (sorted by zmin) into its earliest row."""
    target = rows.min()
    total = 0.0
    weighted = np.zeros(3)
    low, high, bits = np.inf, -np.inf, np.uint64(0)
    for row in rows:
        total += area[row]
        for c in range(3):
            weighted[c] += area[row] * color[row, c]
        low, high = min(low, zmin[row]), max(high, zmax[row])
        bits |= mask[row]
        keep[row] = row == target
    if total > 0.0:
        for c in range(3):
            color[target, c] = weighted[c] / total
    else:
        color[target] = color[rows[0]]
    if bits == full and abs(total - 1.0) <= COMPLETE_TOLERANCE:
        total = 1.0
    zmin[target], zmax[target], area[target], mask[target] = low, high, min(total, 1.0), bits


def merge_by_object(fragments, width, height, full):
    """(`Fragments` with each pixel's per-object clusters merged, the number of fragments merged away)."""
    pixels = fragments.y * width + fragments.x
    fields = {f.name: np.array(getattr(fragments, f.name)) for f in dataclasses.fields(fragments)}
    keep = merge_kernel(
        pixels, width * height, fields["object"], fields["opacity"], fields["zmin"],
        fields["zmax"], fields["area"], fields["mask"], fields["color"], np.uint64(full),
    )  # fmt: skip
    merged = type(fragments)(**{name: value[keep] for name, value in fields.items()})
    return merged, fragments.count - merged.count

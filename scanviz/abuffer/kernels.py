"""Compiled twin of `scanviz.abuffer.pixelstruct` (numba): the same lists, stats and image.

Fragments are inserted in drawing order, as the reference does, so that
combining and discarding (which depend on order) agree. Pixelstructs are
linked lists in flat arrays: ``head[pixel]`` is the nearest fragment's slot,
``after[slot]`` the next one (-1 ends). Slot i starts as fragment i; a
combined fragment takes over the stored partner's slot. The packer walks the
reference's recursion with an explicit stack of regions (level, mask, weight,
and the product of the transparencies in front), summing each level's
contribution: the same terms, in another order (equal to ~1e-15).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .pixelstruct import SAME_SURFACE_TOLERANCE, ABufferStats, FragmentTable, Resolved

# Fields of the stats array returned by `insert_fragments`.
MERGED, DISCARDED, LONGEST = range(3)
AREA_WEIGHTS, MASK_WEIGHTS = 0, 1


@njit(cache=True, inline="always")
def popcount(mask):
    """The number of set bits of a uint64."""
    count = 0
    while mask:
        mask &= mask - np.uint64(1)
        count += 1
    return count


@njit(cache=True, inline="always")
def complete(mask, area, full):
    """`pixelstruct.is_complete`: every sub-sample inside and the exact area 1."""
    return mask == full and area == 1.0


@njit(cache=True, inline="always")
def same_surface(table, slot, incoming, full):
    """`pixelstruct.same_surface` for stored `slot` and fragment row `incoming`."""
    zmin, zmax, area, mask, color, opacity, objects = table
    if objects[slot] != objects[incoming]:
        return False
    if complete(mask[slot], area[slot], full) or complete(mask[incoming], area[incoming], full):
        return False
    if (mask[slot] | mask[incoming]) != full:
        return False
    if abs(opacity[slot] - opacity[incoming]) > SAME_SURFACE_TOLERANCE:
        return False
    for c in range(3):
        if abs(color[slot, c] - color[incoming, c]) > SAME_SURFACE_TOLERANCE:
            return False
    return True


@njit(cache=True, inline="always")
def combine(table, slot, incoming):
    """`pixelstruct.combine` of stored `slot` and row `incoming`, written into `slot`."""
    zmin, zmax, area, mask, color, opacity, objects = table
    total = area[slot] + area[incoming]
    if total > 0.0:
        for c in range(3):
            color[slot, c] = (
                area[slot] * color[slot, c] + area[incoming] * color[incoming, c]
            ) / total
    zmin[slot] = min(zmin[slot], zmin[incoming])
    zmax[slot] = max(zmax[slot], zmax[incoming])
    area[slot] = min(total, 1.0)
    mask[slot] = mask[slot] | mask[incoming]


@njit(cache=True)
def insert_fragments(pixels, zmin, zmax, area, mask, color, opacity, objects, pixel_count, full):
    """Insert fragments in drawing order; edits the field arrays (slots) in place.

    Returns (head, after, stats): list heads per pixel, links per slot, and
    the MERGED, DISCARDED, LONGEST counts.
    """
    table = (zmin, zmax, area, mask, color, opacity, objects)
    head = np.full(pixel_count, -1, np.int64)
    after = np.full(len(pixels), -1, np.int64)
    stats = np.zeros(3, np.int64)
    for incoming in range(len(pixels)):
        p, slot = pixels[incoming], incoming
        previous, partner = -1, head[p]
        while partner >= 0 and not same_surface(table, partner, incoming, full):
            previous, partner = partner, after[partner]
        if partner >= 0:  # combine: unlink the partner, reinsert it as the merged fragment
            if previous < 0:
                head[p] = after[partner]
            else:
                after[previous] = after[partner]
            combine(table, partner, incoming)
            slot = partner
            stats[MERGED] += 1
        previous, current = -1, head[p]
        while current >= 0 and zmin[current] <= zmin[slot]:  # sorted by zmin, ties keep order
            previous, current = current, after[current]
        after[slot] = current
        if previous < 0:
            head[p] = slot
        else:
            after[previous] = slot
        length, current = 1, head[p]
        while (
            not (complete(mask[current], area[current], full) and opacity[current] == 1.0)
            and after[current] >= 0
        ):
            current = after[current]
            length += 1
        dropped = after[current]  # behind a complete opaque fragment: discarded
        after[current] = -1
        while dropped >= 0:
            stats[DISCARDED] += 1
            dropped = after[dropped]
        stats[LONGEST] = max(stats[LONGEST], length)
    return head, after, stats


@njit(cache=True, inline="always")
def covered_weight(region, weight, fragment_mask, fragment_area, full, samples, weights):
    """`pixelstruct.covered_weight`: A_i of one fragment in one region."""
    covered = region & fragment_mask
    if weights == MASK_WEIGHTS:
        return popcount(covered) / samples
    if complete(fragment_mask, fragment_area, full):
        return weight
    if covered == fragment_mask:  # all its sub-samples visible; an empty mask counts as visible
        return min(fragment_area, weight)
    visible = popcount(region)
    return weight * popcount(covered) / visible if visible else 0.0


@njit(cache=True)
def pack_lists(
    head,
    after,
    area,
    mask,
    color,
    opacity,
    full,
    samples,
    weights,
    background,
    image,
    alpha,
    longest,
):
    """Pack every list pixelstruct into `image` and `alpha` (flat per pixel); returns (simple, list) counts."""
    order = np.empty(longest, np.int64)
    levels = np.empty(longest + 2, np.int64)
    regions = np.empty(longest + 2, np.uint64)
    weights_left = np.empty(longest + 2)
    factors = np.empty(longest + 2)
    simple = lists = 0
    for p in range(len(head)):
        first = head[p]
        if first < 0:
            continue
        if complete(mask[first], area[first], full) and opacity[first] == 1.0:  # simple: no packing
            simple += 1
            image[p] = color[first]
            alpha[p] = 1.0
            continue
        lists += 1
        count, slot = 0, first
        while slot >= 0:
            order[count] = slot
            count += 1
            slot = after[slot]
        r = g = b = share = 0.0
        levels[0], regions[0], weights_left[0], factors[0], top = 0, full, 1.0, 1.0, 1
        while top > 0:
            top -= 1
            level, region, weight, factor = (
                levels[top],
                regions[top],
                weights_left[top],
                factors[top],
            )
            if level == count or weight == 0.0:  # the background fills what is left
                r += factor * (background[0] * weight)
                g += factor * (background[1] * weight)
                b += factor * (background[2] * weight)
                share += factor * weight
                continue
            f = order[level]
            a = covered_weight(region, weight, mask[f], area[f], full, samples, weights)
            uncovered = region & ~mask[f] & full
            q = popcount(uncovered) / samples if weights == MASK_WEIGHTS else weight - a
            levels[top], regions[top], weights_left[top], factors[top] = (
                level + 1,
                uncovered,
                q,
                factor,
            )
            top += 1
            covered_share = a * opacity[f]
            if opacity[f] != 1.0:  # eq. 6.5: what is behind shows through the covered region
                levels[top], regions[top], weights_left[top] = level + 1, region & mask[f], a
                factors[top] = factor * (1.0 - opacity[f])
                top += 1
            r += factor * (color[f, 0] * covered_share)
            g += factor * (color[f, 1] * covered_share)
            b += factor * (color[f, 2] * covered_share)
        image[p, 0], image[p, 1], image[p, 2] = r, g, b
        alpha[p] = 1.0 - share
    return simple, lists


@njit(cache=True)
def flawed_blend(pixels, zmin, area, color, pixel_count, background, image, alpha):
    """Thesis §6.3's flawed z-buffer into flat `image`/`alpha`; returns (discarded, empty)."""
    depth = np.full(pixel_count, np.inf)
    discarded = 0
    for i in range(len(pixels)):
        p = pixels[i]
        if not zmin[i] < depth[p]:
            discarded += 1
            continue
        depth[p] = zmin[i]
        coverage = area[i]
        for c in range(3):
            image[p, c] = color[i, c] * coverage + image[p, c] * (1.0 - coverage)
        alpha[p] = coverage + alpha[p] * (1.0 - coverage)
    return discarded, int(np.isinf(depth).sum())


def resolve_compiled(fragments, width, height, full, samples, weights, background, mode):
    """`resolve` after validation, through the kernels above."""
    pixel_count = width * height
    pixels = fragments.y * width + fragments.x
    image = np.empty((pixel_count, 3))
    image[:] = background
    alpha = np.zeros(pixel_count)
    stats = ABufferStats(fragments_inserted=fragments.count, path="compiled")
    table = [
        np.array(fragments.zmin), np.array(fragments.zmax), np.array(fragments.area),
        np.array(fragments.mask), np.array(fragments.color), np.array(fragments.opacity),
        np.array(fragments.object),
    ]  # fmt: skip
    full = np.uint64(full)
    if mode == "flawed":
        stats.fragments_discarded, stats.pixels_empty = flawed_blend(
            pixels, table[0], table[2], table[4], pixel_count, background, image, alpha
        )
        head, after = np.full(pixel_count, -1, np.int64), np.zeros(0, np.int64)
        table = [t[:0] for t in table]
    else:
        head, after, counts = insert_fragments(pixels, *table, pixel_count, full)
        stats.fragments_merged = int(counts[MERGED])
        stats.fragments_discarded = int(counts[DISCARDED])
        stats.longest_list = int(counts[LONGEST])
        flag = MASK_WEIGHTS if weights == "mask" else AREA_WEIGHTS
        _, area, mask, color, opacity = table[1:6]
        simple, lists = pack_lists(
            head, after, area, mask, color, opacity, full, samples, flag,
            background, image, alpha, stats.longest_list,
        )  # fmt: skip
        stats.pixels_simple, stats.pixels_list = int(simple), int(lists)
        stats.pixels_empty = pixel_count - stats.pixels_simple - stats.pixels_list
    zmin, zmax, area, mask, color, opacity, objects = table
    return Resolved(
        image.reshape(height, width, 3),
        alpha.reshape(height, width),
        stats,
        FragmentTable(
            head.reshape(height, width), after, zmin, zmax, area, mask, color, opacity, objects
        ),
    )

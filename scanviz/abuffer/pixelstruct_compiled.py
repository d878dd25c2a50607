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

import numba
import numpy as np
from numba import njit, prange

from ..threads import use_threads
from .pixelstruct import SAME_SURFACE_TOLERANCE, ABufferStats, FragmentTable, Resolved

# Fields of the stats array returned by `insert_fragments`.
MERGED, DISCARDED, LONGEST = range(3)
AREA_WEIGHTS, MASK_WEIGHTS = 0, 1
OBJECT_KEY_LIMIT = 2**45  # object * 128 + popcount is an exact float64 key within this


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


@njit(cache=True, inline="always")
def _before(key_a, seq_a, key_b, seq_b):
    """Whether (key_a, seq_a) sorts before (key_b, seq_b)."""
    return key_a < key_b or (key_a == key_b and seq_a < seq_b)


@njit(cache=True)
def _split(root, key, seq, keys, seqs, left, right, hook):
    """Split a treap into (its nodes sorting before (key, seq), the others).

    Iterative: the two halves grow from two spare slots `hook`, `hook` + 1
    of `left`/`right` (one pair per thread), down the search path. O(depth).
    """
    low_hook, high_hook = hook, hook + 1
    low_tail, high_tail, node = low_hook, high_hook, root
    while node >= 0:
        if _before(keys[node], seqs[node], key, seq):
            right[low_tail], low_tail, node = node, node, right[node]
        else:
            left[high_tail], high_tail, node = node, node, left[node]
    right[low_tail] = left[high_tail] = -1
    return right[low_hook], left[high_hook]


@njit(cache=True)
def _merge(low, high, priority, left, right):
    """Join treaps `low` and `high` (every node of `low` sorting first); returns the root. O(depth)."""
    if low < 0 or high < 0:
        return low if high < 0 else high
    root = low if priority[low] > priority[high] else high
    parent, on_right = -1, False
    while low >= 0 and high >= 0:
        top = low if priority[low] > priority[high] else high
        if parent >= 0:
            if on_right:
                right[parent] = top
            else:
                left[parent] = top
        parent = top
        if top == low:
            on_right, low = True, right[low]
        else:
            on_right, high = False, left[high]
    if on_right:
        right[parent] = low if low >= 0 else high
    else:
        left[parent] = low if low >= 0 else high
    return root


@njit(cache=True, inline="always")
def _insert(root, node, keys, seqs, priority, left, right, hook):
    low, high = _split(root, keys[node], seqs[node], keys, seqs, left, right, hook)
    left[node] = right[node] = -1
    return _merge(_merge(low, node, priority, left, right), high, priority, left, right)


@njit(cache=True, inline="always")
def _remove(root, node, keys, seqs, priority, left, right, hook):
    low, rest = _split(root, keys[node], seqs[node], keys, seqs, left, right, hook)
    _, high = _split(rest, keys[node], seqs[node] + 1, keys, seqs, left, right, hook)
    return _merge(low, high, priority, left, right)


@njit(cache=True)
def _in_order(root, left, right, stack, out):
    """The nodes of a treap in key order into `out`; returns their number."""
    top = count = 0
    node = root
    while node >= 0 or top > 0:
        while node >= 0:
            stack[top] = node
            top += 1
            node = left[node]
        top -= 1
        node = stack[top]
        out[count] = node
        count += 1
        node = right[node]
    return count


@njit(cache=True)
def _priorities(count):
    """Deterministic pseudo-random treap priorities (splitmix64 of the slot)."""
    priority = np.empty(count, np.uint64)
    for i in range(count):
        h = np.uint64(i) + np.uint64(0x9E3779B97F4A7C15)
        h = (h ^ (h >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        h = (h ^ (h >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        priority[i] = h ^ (h >> np.uint64(31))
    return priority


PARALLEL_FRAGMENTS = 2**16  # fewer fragments are inserted on the calling thread


def insert_fragments(pixels, zmin, zmax, area, mask, color, opacity, objects, pixel_count, full):
    """Insert fragments in drawing order; edits the field arrays (slots) in place.

    Returns (head, after, stats): list heads per pixel, links per slot, and
    the MERGED, DISCARDED, LONGEST counts. Each pixel's list is a treap keyed
    by (zmin, time of insertion): `insert_sorted`'s order, found in O(log n).
    Only its last fragment can hide what is behind (everything behind the
    first one that hides is discarded), so `hider[p]` answers the discard
    test in O(1). Stored partial fragments sit also in a second treap keyed by
    object, then their mask's bit count: masks that together fill the pixel
    have at least `samples` bits between them, so the same-surface search
    visits only the stored fragments of the incoming object with at least
    `samples` - popcount(incoming) bits, and takes the first of those that
    match in list order. `objects` must be within +-OBJECT_KEY_LIMIT (exact keys).

    `pixels` must be sorted (`pixel_order`). Pixels are independent: many
    fragments (`PARALLEL_FRAGMENTS`) are cut into runs of whole pixels, one
    per numba thread, each with its own two hook slots; the lists and counts
    are those of one run.
    """
    n = len(pixels)
    shared = use_threads(n, PARALLEL_FRAGMENTS)
    runs = numba.get_num_threads() if shared else 1
    cuts = np.full(runs + 1, n, np.int64)
    if n:
        cuts[:runs] = np.searchsorted(pixels, pixels[np.arange(runs) * n // runs], side="left")
    slots = n + 2 * runs  # the fragments, then each run's two hook slots
    lists = (
        np.full(pixel_count, -1, np.int64),  # root
        np.full(pixel_count, -1, np.int64),  # partial_root
        np.full(pixel_count, -1, np.int64),  # hider
        np.zeros(pixel_count, np.int64),  # length
        np.arange(slots),  # seq: time of (re)insertion
        _partial_keys(objects, mask, slots),  # bits: the key of the partial treap
        np.full(slots, -1, np.int64), np.full(slots, -1, np.int64),  # left, right
        np.full(slots, -1, np.int64), np.full(slots, -1, np.int64),  # partial_left, _right
        np.concatenate((zmin, np.zeros(2 * runs))),  # zkey
        _priorities(slots),
    )  # fmt: skip
    stats = np.zeros((runs, 3), np.int64)
    head, after = np.full(pixel_count, -1, np.int64), np.full(n, -1, np.int64)
    insert = _insert_shared if shared else _insert_here
    table = (zmin, zmax, area, mask, color, opacity, objects)
    insert(cuts, pixels, table, lists, full, stats, head, after)
    totals = np.array([stats[:, MERGED].sum(), stats[:, DISCARDED].sum(), stats[:, LONGEST].max()])
    return head, after, totals


@njit(cache=True)
def _partial_keys(objects, mask, slots):
    """The partial treap's keys: object * 128 + the mask's popcount (hook slots left as they are)."""
    bits = np.empty(slots)
    for i in range(len(objects)):
        bits[i] = objects[i] * 128.0 + popcount(mask[i])
    return bits


@njit(cache=True, parallel=True)
def _insert_shared(cuts, pixels, table, lists, full, stats, head, after):
    for run in prange(len(cuts) - 1):
        _insert_run(cuts[run], cuts[run + 1], len(pixels) + 2 * run, pixels, table, lists, full,
                    stats[run], head, after)  # fmt: skip


@njit(cache=True)
def _insert_here(cuts, pixels, table, lists, full, stats, head, after):
    for run in range(len(cuts) - 1):
        _insert_run(cuts[run], cuts[run + 1], len(pixels) + 2 * run, pixels, table, lists, full,
                    stats[run], head, after)  # fmt: skip


@njit(cache=True)
def _insert_run(first, stop, hook, pixels, table, lists, full, stats, head, after):
    """Insert fragments first..stop - 1 (whole pixels), splitting treaps at slots hook, hook + 1.

    Then links each of their pixels' treaps in key order into `head`/`after`.
    """
    zmin, zmax, area, mask, color, opacity, objects = table
    root, partial_root, hider, length, seq, bits, left, right = lists[:8]
    partial_left, partial_right, zkey, priority = lists[8:]
    n = len(pixels)
    samples = popcount(full)
    stack, dropped = np.empty(stop - first + 1, np.int64), np.empty(stop - first + 1, np.int64)
    for incoming in range(first, stop):
        p, slot = pixels[incoming], incoming
        if root[p] < 0:  # an empty pixelstruct: no search, no split
            root[p], length[p] = slot, 1
            if not complete(mask[slot], area[slot], full):
                partial_root[p] = slot
            elif opacity[slot] == 1.0:
                hider[p] = slot
            stats[LONGEST] = max(stats[LONGEST], 1)
            continue
        if partial_root[p] >= 0 and not complete(mask[incoming], area[incoming], full):
            first_key = objects[incoming] * 128.0 + (samples - popcount(mask[incoming]))
            below, rest = _split(
                partial_root[p], first_key, -1, bits, seq, partial_left, partial_right, hook
            )
            near, above = _split(
                rest, objects[incoming] * 128.0 + samples, n + 2, bits, seq, partial_left,
                partial_right, hook,
            )  # fmt: skip
            partner = -1
            for k in range(_in_order(near, partial_left, partial_right, stack, dropped)):
                candidate = dropped[k]
                if same_surface(table, candidate, incoming, full) and (
                    partner < 0
                    or _before(zkey[candidate], seq[candidate], zkey[partner], seq[partner])
                ):
                    partner = candidate
            partial_root[p] = _merge(
                _merge(below, near, priority, partial_left, partial_right), above, priority,
                partial_left, partial_right,
            )  # fmt: skip
            if partner >= 0:  # combine: unlink the partner, reinsert it as the merged fragment
                slot = _combine_into(p, partner, incoming, table, lists, hook)
                stats[MERGED] += 1
        last = hider[p]
        if last >= 0 and zmin[slot] >= zkey[last]:  # lands behind a complete opaque fragment
            stats[DISCARDED] += 1
            stats[LONGEST] = max(stats[LONGEST], length[p])
            continue
        low, high = _split(root[p], zkey[slot], seq[slot], zkey, seq, left, right, hook)
        left[slot] = right[slot] = -1
        root[p] = _merge(low, slot, priority, left, right)
        length[p] += 1
        if complete(mask[slot], area[slot], full) and opacity[slot] == 1.0:
            hider[p] = slot
            for k in range(_in_order(high, left, right, stack, dropped)):  # discarded
                gone = dropped[k]
                if not complete(mask[gone], area[gone], full):
                    partial_root[p] = _remove(
                        partial_root[p], gone, bits, seq, priority, partial_left, partial_right,
                        hook,
                    )  # fmt: skip
                length[p] -= 1
                stats[DISCARDED] += 1
        else:
            root[p] = _merge(root[p], high, priority, left, right)
            if not complete(mask[slot], area[slot], full):
                partial_root[p] = _insert(
                    partial_root[p], slot, bits, seq, priority, partial_left, partial_right, hook
                )
        stats[LONGEST] = max(stats[LONGEST], length[p])
    _link_lists(first, stop, pixels, lists, stack, dropped, head, after)


@njit(cache=True, inline="always")
def _combine_into(p, partner, incoming, table, lists, hook):
    """Unlink `partner` from pixel p's treaps and combine `incoming` into it: the slot to insert."""
    zmin, mask, objects = table[0], table[3], table[6]
    root, partial_root, _, length, seq, bits, left, right = lists[:8]
    partial_left, partial_right, zkey, priority = lists[8:]
    root[p] = _remove(root[p], partner, zkey, seq, priority, left, right, hook)
    partial_root[p] = _remove(
        partial_root[p], partner, bits, seq, priority, partial_left, partial_right, hook
    )
    length[p] -= 1
    combine(table, partner, incoming)
    seq[partner], zkey[partner] = incoming, zmin[partner]
    bits[partner] = objects[partner] * 128.0 + popcount(mask[partner])
    return partner


@njit(cache=True)
def _link_lists(first, stop, pixels, lists, stack, dropped, head, after):
    """Link each pixel's treap of fragments first..stop - 1 in key order into `head`/`after`."""
    root, left, right = lists[0], lists[6], lists[7]
    for i in range(first, stop):  # each pixel once, at its first fragment
        if i > first and pixels[i] == pixels[i - 1]:
            continue
        count = _in_order(root[pixels[i]], left, right, stack, dropped)
        if count:
            head[pixels[i]] = dropped[0]
            for k in range(count - 1):
                after[dropped[k]] = dropped[k + 1]


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


@njit(cache=True)
def nearest_fragments(pixels, zmin, polygon, pixel_count):
    """Per pixel the least zmin and its fragment's polygon (ties: the later fragment); inf, -1."""
    depth = np.full(pixel_count, np.inf)
    nearest = np.full(pixel_count, -1, np.int64)
    for i in range(len(pixels)):
        if zmin[i] <= depth[pixels[i]]:
            depth[pixels[i]], nearest[pixels[i]] = zmin[i], polygon[i]
    return depth, nearest


@njit(cache=True)
def pixel_order(pixels, pixel_count):
    """A stable counting sort of fragment rows by pixel: (order, sorted pixels). O(F + pixels).

    Pixels are independent, so inserting pixel by pixel (each in drawing
    order) gives the same lists; and a pixel's slots are then contiguous.
    """
    starts = np.zeros(pixel_count + 1, np.int64)
    for p in pixels:
        starts[p + 1] += 1
    for p in range(pixel_count):
        starts[p + 1] += starts[p]
    order = np.empty(len(pixels), np.int64)
    for i in range(len(pixels)):
        order[starts[pixels[i]]] = i
        starts[pixels[i]] += 1
    return order, pixels[order]


def resolve_compiled(fragments, width, height, full, samples, weights, background, mode):
    """`resolve` after validation, through the kernels above."""
    pixel_count = width * height
    pixels = fragments.y * width + fragments.x
    order = None
    if mode != "flawed":  # slots of one pixel side by side: the lists stay in cache
        order, pixels = pixel_order(pixels, pixel_count)
    image = np.empty((pixel_count, 3))
    image[:] = background
    alpha = np.zeros(pixel_count)
    stats = ABufferStats(fragments_inserted=fragments.count, path="compiled")
    fields = (fragments.zmin, fragments.zmax, fragments.area, fragments.mask, fragments.color,
              fragments.opacity, fragments.object)  # fmt: skip
    table = [np.array(f) if order is None else f[order] for f in fields]
    full = np.uint64(full)
    if mode == "flawed":
        stats.fragments_discarded, stats.pixels_empty = flawed_blend(
            pixels, table[0], table[2], table[4], pixel_count, background, image, alpha
        )
        head, after = np.full(pixel_count, -1, np.int64), np.zeros(0, np.int64)
        table = [t[:0] for t in table]
    else:
        objects = table[6]
        if len(objects) and np.abs(objects).max() > OBJECT_KEY_LIMIT:  # keys stay exact: ranks
            objects = np.unique(objects, return_inverse=True)[1].astype(np.int64)
        head, after, counts = insert_fragments(pixels, *table[:6], objects, pixel_count, full)
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

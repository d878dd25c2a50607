"""Pixelstructs, fragment insertion and the fragment packer: the traced reference.

A pixelstruct is a fragment list, nearest first (thesis Figs. 6.4-6.6). It is
*empty*, *simple* (one complete opaque fragment: the thesis' z, r, g, b,
coverage 1) or a *list*. Inserting a fragment (§6.3.4-6.3.5):

1. combine it with the first stored fragment of the same surface (same object,
   color and opacity; neither complete; masks together full),
2. insert it sorted by zmin (after stored fragments of equal zmin),
3. discard every fragment behind the first complete opaque one; if that one
   heads the list, the pixelstruct is simple again.

`pack_pixel` collapses a list into a color and a coverage (§6.3.6, eqs.
6.4-6.6), recursing on regions of the pixel (a mask M_Q and its weight Q).
Both are replaceable steps (`scanviz.steps`): the loop `resolve_reference`
calls them through the step table and traces what they return.
`scanviz.abuffer.pixelstruct_compiled` is the compiled twin of this module.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .. import steps
from ..trace.display import RichDisplay
from ..trace.events import (
    CoverageBlended,
    FragmentInserted,
    FragmentRecord,
    FragmentsDiscarded,
    FragmentsMerged,
    PackStep,
    PixelPacked,
)
from ..trace.schema import shown

SAME_SURFACE_TOLERANCE = 1e-12  # colors and opacities this close belong to one surface
EMPTY, SIMPLE, LIST = "empty", "simple", "list"


@dataclass
class ABufferStats(RichDisplay):
    """What one resolve did.

    ``pixels_*`` count the pixelstructs at the end by kind. Every fragment
    given is ``fragments_inserted``; ``fragments_merged`` counts combinations
    (two fragments became one); ``fragments_discarded`` the fragments thrown
    away behind a complete opaque one (incoming or stored) -- in flawed mode,
    those failing the depth test. ``longest_list`` is the longest fragment
    list at any time. ``fragments_object_merged`` counts the fragments that
    ``merge="object"`` merged away before insertion (`scanviz.abuffer.merge`).
    """

    pixels: int = 0
    pixels_empty: int = 0
    pixels_simple: int = 0
    pixels_list: int = 0
    fragments_inserted: int = 0
    fragments_merged: int = 0
    fragments_discarded: int = 0
    longest_list: int = 0
    fragments_object_merged: int = 0
    mode: str = "abuffer"
    weights: str = "area"
    path: str = "reference"


@dataclass(frozen=True)
class FragmentTable:
    """Every pixel's fragment list as linked rows: ``head[y, x]``, then ``next`` (-1 ends)."""

    head: np.ndarray
    next: np.ndarray
    zmin: np.ndarray
    zmax: np.ndarray
    area: np.ndarray
    mask: np.ndarray
    color: np.ndarray
    opacity: np.ndarray
    object: np.ndarray

    def pixel(self, x: int, y: int) -> tuple[FragmentRecord, ...]:
        """Pixel (x, y)'s fragment list, nearest first."""
        records, slot = [], int(self.head[y, x])
        while slot >= 0:
            color = tuple(float(c) for c in self.color[slot])
            records.append(
                FragmentRecord(
                    float(self.zmin[slot]),
                    float(self.zmax[slot]),
                    float(self.area[slot]),
                    int(self.mask[slot]),
                    color,
                    float(self.opacity[slot]),
                    int(self.object[slot]),
                )  # fmt: skip
            )
            slot = int(self.next[slot])
        return tuple(records)

    @classmethod
    def from_lists(cls, lists: dict[tuple[int, int], list[FragmentRecord]], width, height):
        """Link the reference's lists ({(x, y): records}) into a table."""
        records = [r for key in sorted(lists) for r in lists[key]]
        head = np.full((height, width), -1, np.int64)
        after = np.full(len(records), -1, np.int64)
        slot = 0
        for x, y in sorted(lists):
            head[y, x] = slot
            after[slot : slot + len(lists[x, y]) - 1] = np.arange(slot + 1, slot + len(lists[x, y]))
            slot += len(lists[x, y])
        column = lambda name, dtype: np.array([getattr(r, name) for r in records], dtype)  # noqa: E731
        return cls(
            head, after, column("z", np.float64), column("zmax", np.float64),
            column("area", np.float64), column("mask", np.uint64),
            np.array([r.color for r in records], np.float64).reshape(-1, 3),
            column("opacity", np.float64), column("object", np.int64),
        )  # fmt: skip


@dataclass(frozen=True)
class Resolved:
    """What `resolve_reference` and its compiled twin hand back to `resolve`."""

    image: np.ndarray
    alpha: np.ndarray
    stats: ABufferStats
    table: FragmentTable


def is_complete(fragment: FragmentRecord, full: int) -> bool:
    """Completely covered: every sub-sample inside and the exact area 1.

    A full mask alone is not enough: an edge can pass between the pixel's
    border and its outermost sub-samples, and that sliver of the pixel must
    still show what lies behind.
    """
    return fragment.mask == full and fragment.area == 1.0


def hides_behind(fragment: FragmentRecord, full: int) -> bool:
    """Complete and opaque: nothing behind it can be seen."""
    return is_complete(fragment, full) and fragment.opacity == 1.0


def pixelstruct_kind(fragments: list[FragmentRecord], full: int) -> str:
    """ "empty", "simple" (one complete opaque fragment) or "list"."""
    if not fragments:
        return EMPTY
    return SIMPLE if hides_behind(fragments[0], full) else LIST


def same_surface(stored: FragmentRecord, incoming: FragmentRecord, full: int) -> bool:
    """Whether two fragments combine: one surface, two partial masks that together fill the pixel."""
    return (
        stored.object == incoming.object
        and all(
            abs(a - b) <= SAME_SURFACE_TOLERANCE
            for a, b in zip(stored.color, incoming.color, strict=True)
        )
        and abs(stored.opacity - incoming.opacity) <= SAME_SURFACE_TOLERANCE
        and not is_complete(stored, full)
        and not is_complete(incoming, full)
        and stored.mask | incoming.mask == full
    )


def combine(stored: FragmentRecord, incoming: FragmentRecord) -> FragmentRecord:
    """One fragment of both: masks or-ed, areas summed (at most 1), z ranges unioned, colors area-weighted."""
    total = stored.area + incoming.area
    color = stored.color
    if total > 0.0:
        color = tuple(
            (stored.area * s + incoming.area * i) / total
            for s, i in zip(stored.color, incoming.color, strict=True)
        )
    return replace(
        stored,
        z=min(stored.z, incoming.z),
        zmax=max(stored.zmax, incoming.zmax),
        area=min(total, 1.0),
        mask=stored.mask | incoming.mask,
        color=color,
    )


def insert_sorted(fragments: list[FragmentRecord], fragment: FragmentRecord) -> None:
    """Insert by zmin, after every stored fragment with zmin <= its zmin (ties keep the earlier)."""
    position = 0
    while position < len(fragments) and fragments[position].z <= fragment.z:
        position += 1
    fragments.insert(position, fragment)


@steps.step(
    "insert_fragment",
    takes="a pixel's fragment list (FragmentRecords, nearest first), the incoming fragment, "
    "the full mask",
    returns="(the new list, (stored, combined) if it merged else None, the fragments discarded)",
)
def insert_fragment(fragments, incoming, full):
    """Carpenter's insertion of `incoming` into one pixel's list: combine, sort, discard.

    Returns ``(fragments, merged, discarded)``: the new list, nearest first;
    ``(stored, combined)`` if `incoming` was combined with a stored fragment
    of its surface, else None; the fragments thrown away behind the first
    complete opaque one, nearest first.

    Examples
    --------
    >>> full = 0b1111
    >>> left = FragmentRecord(0.5, 0.5, 0.5, 0b0101, (1.0, 1.0, 1.0), 1.0, 7)
    >>> pixel, merged, discarded = insert_fragment([left], replace(left, mask=0b1010), full)
    >>> pixelstruct_kind(pixel, full), pixel[0].mask, pixel[0].area, merged[0] == left, discarded
    ('simple', 15, 1.0, True, ())
    """
    fragments = list(fragments)
    merged, placed = None, incoming
    partner = next((f for f in fragments if same_surface(f, incoming, full)), None)
    if partner is not None:
        fragments.remove(partner)
        placed = combine(partner, incoming)
        merged = (partner, placed)
    insert_sorted(fragments, placed)
    front = next((i for i, f in enumerate(fragments) if hides_behind(f, full)), len(fragments))
    return fragments[: front + 1], merged, tuple(fragments[front + 1 :])


def insert_into(pixel, incoming, full, stats, trace=None, *, x=0, y=0, polygon=0, index=0):
    """Insert `incoming` into pixel (x, y)'s list `pixel` (in place) by step ``insert_fragment``.

    The stats and the events (``fragment_inserted``, ``fragments_merged``,
    ``fragments_discarded``) are what the step returned: a replaced step's
    decisions show in the trace.
    """
    before = tuple(pixel)
    before_kind = pixelstruct_kind(before, full)
    after, merged, discarded = returned(
        "insert_fragment", steps.get("insert_fragment")(list(before), incoming, full), 3
    )
    pixel[:] = after
    events = []
    if merged is not None:
        stored, combined = merged
        stats.fragments_merged += 1
        events.append(FragmentsMerged(x, y, polygon, stored, incoming, combined))
    if discarded:  # the fragment they hide behind is the last one kept
        if not pixel:
            raise ValueError(
                f"step 'insert_fragment' discarded {len(discarded)} fragments of pixel "
                f"({x}, {y}) and kept none in front of them"
            )
        stats.fragments_discarded += len(discarded)
        events.append(FragmentsDiscarded(x, y, polygon, pixel[-1], tuple(discarded)))
    stats.fragments_inserted += 1
    stats.longest_list = max(stats.longest_list, len(pixel))
    if trace is None:
        return
    case = ("complete_" if is_complete(incoming, full) else "partial_") + before_kind
    events.insert(
        0,
        FragmentInserted(
            x,
            y,
            polygon,
            index,
            incoming,
            case,
            before_kind,
            before,
            pixelstruct_kind(pixel, full),
            tuple(pixel),
        ),  # fmt: skip
    )
    for event in events:
        if trace.wants(event.kind, polygon=polygon, y=y):
            trace.emit(event)


def covered_weight(fragment, region, weight, full, samples, weights) -> float:
    """A_i: the weight of the part of `region` (mask M_Q, weight Q) the fragment covers.

    "mask": popcount(M_Q AND M_i) / n. "area": Q for a complete fragment;
    min(area, Q) if unobscured (its mask within M_Q; an empty mask, a sliver
    between sub-samples, is taken to lie in the visible region, which is right
    where polygons meet and over-counts at most its own area where a partial
    fragment in front hides it); else Q's share by sub-sample count,
    Q * popcount(M_A) / popcount(M_Q).
    """
    covered = region & fragment.mask
    if weights == "mask":
        return covered.bit_count() / samples
    if is_complete(fragment, full):
        return weight
    if covered == fragment.mask:  # all its sub-samples visible; an empty mask counts as visible
        return min(fragment.area, weight)
    visible = region.bit_count()
    return weight * covered.bit_count() / visible if visible else 0.0


@steps.step(
    "pack_pixel",
    takes="a pixel's fragment list (nearest first), the full mask, the number of sub-samples, "
    'the weights ("mask" or "area"), the background color',
    returns="(color, alpha, the PackSteps in the order the recursion finishes them)",
)
def pack_pixel(fragments, full, samples, weights, background):
    """Collapse a fragment list into (color, alpha, steps): eqs. 6.4-6.6 on regions of the pixel.

    `steps` holds a `PackStep` per level and region, deepest first.

    Examples
    --------
    >>> red = FragmentRecord(0.0, 0.0, 0.25, 0b0011, (1.0, 0.0, 0.0), 1.0, 0)
    >>> color, alpha, steps = pack_pixel([red], 0b1111, 4, "mask", (0.0, 0.0, 1.0))
    >>> color, alpha, [(s.region, s.mask_a, s.a, s.mask_q, s.q) for s in steps]
    ((0.5, 0.0, 0.5), 0.5, [(15, 3, 0.5, 12, 0.5)])
    """
    records = []

    def region_color(level, region, weight, branch):
        """The region's color times its weight, and the background's share of it."""
        if level == len(fragments) or weight == 0.0:
            return tuple(b * weight for b in background), weight
        fragment = fragments[level]
        covered, uncovered = region & fragment.mask, region & ~fragment.mask & full
        a = covered_weight(fragment, region, weight, full, samples, weights)
        q = uncovered.bit_count() / samples if weights == "mask" else weight - a
        transparent = fragment.opacity != 1.0
        behind, share = region_color(level + 1, uncovered, q, branch + "u" * transparent)
        if not transparent:  # eq. 6.4: C = P A + T Q
            color = tuple(p * a + t for p, t in zip(fragment.color, behind, strict=True))
        else:  # eq. 6.5: the covered region shows P (1 - t) + (what is behind) t
            through = 1.0 - fragment.opacity
            seen, seen_share = region_color(level + 1, covered, a, branch + "c")
            color = tuple(
                p * (fragment.opacity * a) + s * through + t
                for p, s, t in zip(fragment.color, seen, behind, strict=True)
            )
            share += seen_share * through
        records.append(
            PackStep(level, branch, fragment, region, weight, covered, a, uncovered, q, color)
        )
        return color, share

    color, share = region_color(0, full, 1.0, "")
    return color, 1.0 - share, tuple(records)


def resolve_reference(fragments, width, height, full, samples, weights, background, mode, trace):
    """The traced resolve (`resolve` after validation): insert in drawing order, then pack."""
    background = tuple(float(b) for b in background)
    if mode == "flawed":
        return flawed_reference(fragments, width, height, background, trace)
    stats = ABufferStats()
    lists: dict[tuple[int, int], list[FragmentRecord]] = {}
    for i in range(fragments.count):
        x, y, polygon = int(fragments.x[i]), int(fragments.y[i]), int(fragments.polygon[i])
        insert_into(
            lists.setdefault((x, y), []), record(fragments, i), full, stats, trace,
            x=x, y=y, polygon=polygon, index=i,
        )  # fmt: skip
    image = np.empty((height, width, 3))
    image[:] = background
    alpha = np.zeros((height, width))
    for (x, y), pixel_list in lists.items():
        kind = pixelstruct_kind(pixel_list, full)
        if kind == SIMPLE:  # simple pixelstructs need no packing
            stats.pixels_simple += 1
            image[y, x], alpha[y, x] = pixel_list[0].color, 1.0
            continue
        stats.pixels_list += 1
        color, alpha[y, x], packed = returned(
            "pack_pixel",
            steps.get("pack_pixel")(list(pixel_list), full, samples, weights, background),
            3,
        )
        image[y, x] = color
        if trace is not None and trace.wants("pixel_packed", y=y):
            color = tuple(float(c) for c in color)
            trace.emit(PixelPacked(x, y, weights, tuple(packed), color, float(alpha[y, x])))
    stats.pixels_empty = width * height - stats.pixels_simple - stats.pixels_list
    return Resolved(image, alpha, stats, FragmentTable.from_lists(lists, width, height))


def returned(step: str, value: object, count: int) -> tuple:
    """What step `step` returned, checked to be `count` values (a replaced step may not be)."""
    if not isinstance(value, tuple) or len(value) != count:
        table = {s.name: s.returns for s in steps.table()}
        raise TypeError(f"step {step!r} must return {table[step]}; got {shown(value)}")
    return value


def record(fragments, i: int) -> FragmentRecord:
    """Row i of `Fragments` as a `FragmentRecord`."""
    return FragmentRecord(
        float(fragments.zmin[i]), float(fragments.zmax[i]), float(fragments.area[i]),
        int(fragments.mask[i]), tuple(float(c) for c in fragments.color[i]),
        float(fragments.opacity[i]), int(fragments.object[i]),
    )  # fmt: skip


def flawed_reference(fragments, width, height, background, trace):
    """Thesis §6.3's flawed z-buffer: blend each nearer fragment over the pixel by its area."""
    stats = ABufferStats()
    depth = np.full((height, width), np.inf)
    image = np.empty((height, width, 3))
    image[:] = background
    alpha = np.zeros((height, width))
    for i in range(fragments.count):
        x, y, z = int(fragments.x[i]), int(fragments.y[i]), float(fragments.zmin[i])
        coverage, old = float(fragments.area[i]), tuple(float(c) for c in image[y, x])
        stored, passed = float(depth[y, x]), bool(z < depth[y, x])
        stats.fragments_inserted += 1
        if passed:
            depth[y, x] = z
            image[y, x] = fragments.color[i] * coverage + image[y, x] * (1.0 - coverage)
            alpha[y, x] = coverage + alpha[y, x] * (1.0 - coverage)
        else:
            stats.fragments_discarded += 1
        polygon = int(fragments.polygon[i])
        if trace is not None and trace.wants("coverage_blended", polygon=polygon, y=y):
            trace.emit(
                CoverageBlended(
                    x,
                    y,
                    polygon,
                    z,
                    None if stored == np.inf else stored,
                    passed,
                    coverage,
                    tuple(float(c) for c in fragments.color[i]),
                    old,
                    tuple(float(c) for c in image[y, x]),
                )  # fmt: skip
            )
    stats.pixels_empty = int(np.isinf(depth).sum())
    empty = FragmentTable.from_lists({}, width, height)
    return Resolved(image, alpha, stats, empty)

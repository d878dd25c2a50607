"""Exercises on the a-buffer (scanviz.abuffer.pixelstruct): fragment insertion and the packer.

Both are step exercises on `resolve`: the student's ``insert_fragment`` or
``pack_pixel`` runs inside the reference loop, which traces what it returns.
Cases are fragment rows on a 4x4 sub-sample mask (bit ``j * 4 + i`` is
sub-sample (i, j), row 0 at the bottom), a few pixels each.
"""

from __future__ import annotations

import functools
import itertools
import math
import random

from ..abuffer import Fragments, resolve
from ..abuffer.pixelstruct import insert_fragment, pack_pixel
from .cases import call_with_step, place_by_event
from .catalog import register
from .core import Case, Exercise, Variant, edited_variant, feature_tests

LAYOUT = "4x4"
FULL = 0xFFFF
LEFT, RIGHT, BOTTOM, TOP = 0x3333, 0xCCCC, 0x00FF, 0xFF00  # halves of the 4x4 mask
RED, GREEN, BLUE, YELLOW, GREY = (
    (1.0, 0.0, 0.0),
    (0.0, 1.0, 0.0),
    (0.0, 0.0, 1.0),
    (1.0, 1.0, 0.0),
    (0.5, 0.5, 0.5),
)
PALETTE = (RED, GREEN, BLUE, YELLOW, GREY, (0.25, 0.75, 1.0), (1.0, 0.5, 0.0))
BACKGROUNDS = ((0.0, 0.0, 0.25), (1.0, 1.0, 1.0), (0.25, 0.5, 0.75))
# The combined colors and the packer's sums are float arithmetic whose last bit depends on the
# order of the operations: compare them to 1e-9 (every mistake the variants make is far larger).
RTOL = 1e-9


def case_resolve(inputs: dict, trace=None):
    """The a-buffer resolve of a case's fragments (`scanviz.abuffer.resolve`'s result)."""
    return resolve(
        Fragments.from_rows(inputs["fragments"]),
        inputs["width"],
        inputs["height"],
        layout=inputs["layout"],
        weights=inputs["weights"],
        background=inputs["background"],
        trace=trace,
    )


def _packed(result) -> dict:
    return {"image": result.image.tolist(), "alpha": result.alpha.tolist()}


def fragment(x, y, mask, z, color, surface, *, area=None, zmax=None, opacity=1.0) -> dict:
    """One fragment row (plain values); the area defaults to the mask's share of the pixel."""
    return {
        "x": x,
        "y": y,
        "mask": mask,
        "area": mask.bit_count() / 16 if area is None else area,
        "zmin": z,
        "zmax": z if zmax is None else zmax,
        "color": list(color),
        "opacity": opacity,
        "object": surface,
    }


def case_inputs(rows, width, height, background=(0.0, 0.0, 0.25)) -> dict:
    """The inputs of a case: fragments in drawing order on a 4x4 mask, bit-count weights."""
    return {
        "fragments": rows,
        "width": width,
        "height": height,
        "layout": LAYOUT,
        "weights": "mask",
        "background": list(background),
    }


# --- hidden cases -------------------------------------------------------------------------


def _half_plane_mask(rng: random.Random) -> int:
    """The sub-samples on one side of a random line through the pixel: never empty or full."""
    while True:
        angle, offset = rng.uniform(0, 2 * math.pi), rng.uniform(-1.5, 1.5)
        mask = sum(
            1 << (j * 4 + i)
            for j in range(4)
            for i in range(4)
            if math.cos(angle) * (i - 1.5) + math.sin(angle) * (j - 1.5) < offset
        )
        if 0 < mask < FULL:
            return mask


HAIR = 2.0**-30  # "near-equal depths": fragments this far apart, far nearer than a depth step


def _depth(rng: random.Random, feature: str) -> tuple[float, float]:
    """(zmin, zmax) on a grid of 1/8 (ties happen); only two depths for the "depth ties" cases,
    and two a hair apart for the "near-equal depths" ones."""
    if feature == "near-equal depths":
        z = rng.choice((0.5, 0.5 - HAIR))
    else:
        z = rng.choice((0.25, 0.5)) if feature == "depth ties" else rng.randint(0, 7) / 8
    return z, z + rng.randint(0, 3) / 8


def _pixel_rows(
    rng: random.Random, x: int, y: int, feature: str, surfaces, gap: bool = False
) -> list[dict]:
    """1-4 fragments of pixel (x, y) in drawing order, weighted towards `feature`.

    Each fragment is a new surface (object id from the iterator `surfaces`); some get
    their surface's other part, the rest of the pixel, a fragment to combine with.
    With `gap`, a "one surface split" case leaves a sample of the rest uncovered, so
    the two parts stay two fragments of one surface (they combine only when they
    fill the pixel) and reach the packer as such.
    """
    rows = []
    for _ in range(rng.randint(1, 4)):
        surface, color = next(surfaces), rng.choice(PALETTE)
        z, zmax = _depth(rng, feature)
        transparent = rng.random() < (0.6 if feature == "transparency" else 0.1)
        opacity = rng.choice((0.25, 0.5, 0.75)) if transparent else 1.0
        if rng.random() < 0.3:
            mask, area = FULL, 1.0
            if rng.random() < (0.6 if feature == "slivers" else 0.1):  # an edge misses the samples
                area = 1.0 - rng.randint(1, 7) / 64
        else:
            mask, area = _half_plane_mask(rng), None
        rows.append(fragment(x, y, mask, z, color, surface, area=area, zmax=zmax, opacity=opacity))
        if mask != FULL and (feature == "one surface split" or rng.random() < 0.15):
            other = (FULL ^ mask) | (mask & rng.getrandbits(16) if rng.random() < 0.3 else 0)
            if gap and feature == "one surface split" and (FULL ^ mask).bit_count() > 1:
                other &= ~(1 << rng.choice([b for b in range(16) if (FULL ^ mask) >> b & 1]))
            z, zmax = _depth(rng, feature)
            rows.append(fragment(x, y, other, z, color, surface, zmax=zmax, opacity=opacity))
    return rows


def _interleaved(rng: random.Random, pixels: list[list[dict]]) -> list[dict]:
    """All rows, each pixel's in its own order, the pixels interleaved at random."""
    queues, rows = [list(p) for p in pixels if p], []
    while queues:
        queue = rng.choice(queues)
        rows.append(queue.pop(0))
        if not queue:
            queues.remove(queue)
    return rows


def _generator(features: tuple[str, ...], gap: bool = False):
    """Cases of 2-3 by 1-3 pixels for `features` (`gap`: see `_pixel_rows`)."""

    def generate(rng: random.Random, feature: str | None = None) -> Case:
        feature = feature or rng.choice(features)
        width, height = rng.randint(2, 3), rng.randint(1, 3)
        surfaces = itertools.count()
        pixels = [
            _pixel_rows(rng, x, y, feature, surfaces, gap)
            for y in range(height)
            for x in range(width)
        ]
        background = rng.choice(BACKGROUNDS)
        return Case(
            feature, case_inputs(_interleaved(rng, pixels), width, height, background), feature
        )

    return generate


def _calls(reference) -> list[tuple]:
    """The arguments of every call of the step in the reference's run."""
    return [args for args, _ in reference.arguments]


def _some_call(check):
    return lambda case, reference: any(check(*args) for args in _calls(reference))


def _some_output(check):
    return lambda case, reference: any(check(output) for output in reference.calls)


def _nearer_by(fragments, incoming, low: float, high: float) -> bool:
    """Whether `incoming` is nearer than a stored fragment by low..high (0..0: a tie)."""
    return any(low <= f.z - incoming.z <= high for f in fragments)


INSERT_FEATURES = {
    "layers": _some_call(lambda fragments, incoming, full: len(fragments) >= 2),
    "one surface split": _some_output(lambda output: output[1] is not None),
    "slivers": _some_call(
        lambda fragments, incoming, full: incoming.mask == full > 0 and incoming.area < 1
    ),
    "transparency": _some_call(lambda fragments, incoming, full: incoming.opacity < 1),
    "depth ties": _some_call(lambda f, incoming, full: _nearer_by(f, incoming, 0, 0)),
    "near-equal depths": _some_call(
        lambda f, incoming, full: _nearer_by(f, incoming, 2**-60, 1e-6)
    ),
    "discards behind": _some_output(lambda output: len(output[2]) > 0),
}
"""Tests of the insertion's features: each branch (a list, a surface's other part to combine, a
full mask that is not complete, a transparent fragment, what a complete one hides), depths that
tie and depths a hair apart (which a tolerance takes for a tie)."""


def _fragments(reference) -> list[list]:
    return [args[0] for args in _calls(reference)]


PACK_FEATURES = {
    "layers": lambda case, reference: any(len(f) >= 2 for f in _fragments(reference)),
    "one surface split": lambda case, reference: any(
        len({x.object for x in f}) < len(f) for f in _fragments(reference)
    ),
    "transparency": lambda case, reference: any(
        x.opacity < 1 for f in _fragments(reference) for x in f
    ),
    "background shows": lambda case, reference: any(
        args[1] & ~_union(args[0]) for args in _calls(reference)
    ),
    "depth ties": lambda case, reference: any(
        len({x.z for x in f}) < len(f) for f in _fragments(reference)
    ),
}
"""Tests of the packer's features: several fragments, one surface in two parts, a transparent
fragment (the packer's second branch), samples no fragment covers, and fragments at one depth."""


def _union(fragments) -> int:
    mask = 0
    for f in fragments:
        mask |= f.mask
    return mask


def _variant(solution: str, name: str, hint: str, old: str, new: str) -> Variant:
    return edited_variant(solution, name, hint, (old, new))


# --- exercise 14: a-buffer insertion ------------------------------------------------------

INSERT_SOLUTION = """\
from dataclasses import replace

TOLERANCE = 1e-12


def complete(f, full):
    return f.mask == full and f.area == 1.0


def same_surface(stored, incoming, full):
    return (
        stored.object == incoming.object
        and all(abs(a - b) <= TOLERANCE for a, b in zip(stored.color, incoming.color))
        and abs(stored.opacity - incoming.opacity) <= TOLERANCE
        and not complete(stored, full)
        and not complete(incoming, full)
        and stored.mask | incoming.mask == full
    )


def combine(stored, incoming):
    total = stored.area + incoming.area
    color = stored.color
    if total > 0:
        color = tuple(
            (stored.area * s + incoming.area * i) / total
            for s, i in zip(stored.color, incoming.color)
        )
    return replace(
        stored,
        z=min(stored.z, incoming.z),
        zmax=max(stored.zmax, incoming.zmax),
        area=min(total, 1.0),
        mask=stored.mask | incoming.mask,
        color=color,
    )


def insert_fragment(fragments, incoming, full):
    fragments = list(fragments)
    merged = None
    partner = next((f for f in fragments if same_surface(f, incoming, full)), None)
    if partner is not None:
        fragments.remove(partner)
        incoming = combine(partner, incoming)
        merged = (partner, incoming)
    position = 0
    while position < len(fragments) and fragments[position].z <= incoming.z:
        position += 1
    fragments.insert(position, incoming)
    for i, f in enumerate(fragments):
        if complete(f, full) and f.opacity == 1.0:
            return fragments[: i + 1], merged, fragments[i + 1 :]
    return fragments, merged, []
"""

DISCARD_LOOP = """\
    for i, f in enumerate(fragments):
        if complete(f, full) and f.opacity == 1.0:
            return fragments[: i + 1], merged, fragments[i + 1 :]
"""

SAME_SURFACE_TESTS = """\
        stored.object == incoming.object
        and all(abs(a - b) <= TOLERANCE for a, b in zip(stored.color, incoming.color))
        and abs(stored.opacity - incoming.opacity) <= TOLERANCE
        and not complete(stored, full)
"""


_insert_variant = functools.partial(_variant, INSERT_SOLUTION)


INSERT_CASES = (
    Case(
        "hidden, hiding, in between",
        case_inputs(
            [
                fragment(0, 0, FULL, 0.2, RED, 0),  # complete_empty
                fragment(0, 0, LEFT, 0.6, GREEN, 1),  # partial_simple: hidden, discarded
                fragment(1, 0, LEFT, 0.5, GREEN, 2),  # partial_empty
                fragment(1, 0, FULL, 0.1, BLUE, 3),  # complete_list: discards the green
                fragment(2, 0, LEFT, 0.1, RED, 4),
                fragment(2, 0, BOTTOM, 0.5, GREEN, 5),  # partial_list: behind a partial one
                fragment(2, 0, FULL, 0.3, BLUE, 6),  # complete_list: between them
                fragment(0, 1, FULL, 0.3, RED, 7),
                fragment(0, 1, FULL, 0.2, GREEN, 8),  # complete_simple, in front
            ],
            3,
            2,
        ),
    ),
    Case(
        "one surface split by an edge",
        case_inputs(
            [
                fragment(0, 0, FULL, 0.8, GREEN, 2),
                fragment(0, 0, LEFT, 0.4, RED, 1, zmax=0.5),
                fragment(0, 0, RIGHT, 0.3, RED, 1, zmax=0.6),  # merges: complete, hides green
                fragment(1, 0, LEFT, 0.2, BLUE, 3),
                fragment(1, 0, RIGHT, 0.25, YELLOW, 4),  # two surfaces: no merge
                fragment(2, 0, LEFT, 0.4, RED, 1),
                fragment(2, 0, BOTTOM, 0.45, RED, 1),  # masks not full together: no merge
            ],
            3,
            1,
        ),
    ),
    Case(
        "what hides and what does not",
        case_inputs(
            [
                fragment(0, 0, FULL, 0.2, RED, 0, area=0.9375),  # full mask, not complete
                fragment(0, 0, LEFT, 0.6, GREEN, 1),
                fragment(1, 0, FULL, 0.2, BLUE, 2, opacity=0.5),  # complete, transparent
                fragment(1, 0, FULL, 0.7, GREEN, 3),
                fragment(2, 0, TOP, 0.1, RED, 4),  # opaque, partial
                fragment(2, 0, FULL, 0.5, YELLOW, 5),
            ],
            3,
            1,
        ),
    ),
    Case(
        "a fragment a hair (2^-30) nearer than the stored one",
        case_inputs(
            [
                fragment(0, 0, LEFT, 0.5, RED, 0),
                fragment(0, 0, BOTTOM, 0.5 - 2**-30, GREEN, 1),  # nearer: first in the list
                fragment(1, 0, TOP, 0.25, BLUE, 2),
                fragment(1, 0, RIGHT, 0.25 + 2**-30, YELLOW, 3),  # farther: after it
            ],
            2,
            1,
        ),
    ),
    Case(
        "near depth, far depth, ties",
        case_inputs(
            [
                fragment(0, 0, LEFT, 0.2, RED, 0, zmax=0.9),
                fragment(0, 0, BOTTOM, 0.4, GREEN, 1, zmax=0.5),  # behind by zmin, in front by zmax
                fragment(1, 0, LEFT, 0.5, BLUE, 2),
                fragment(1, 0, TOP, 0.5, YELLOW, 3),  # a tie: after the stored one
            ],
            2,
            1,
        ),
    ),
)

register(
    Exercise(
        id="abuffer_insert",
        number=14,
        title="Inserting a fragment into an a-buffer pixel",
        stage="a-buffer",
        kind="step",
        points=5,
        answer="insert_fragment",
        idea=(
            "Carpenter's a-buffer keeps, per pixel, a list of **fragments** sorted nearest first: "
            "each has a depth range `z` (near) .. `zmax` (far), the exact `area` of the pixel it "
            "covers, a coverage **mask** (here 4x4 sub-samples, bit `j * 4 + i` is sub-sample "
            "(i, j), row 0 at the bottom), a color, an opacity and the object it belongs to. "
            "Smaller z is nearer.\n\n"
            "Inserting a fragment: (1) if it is the other part of a **surface** already stored "
            "(same object, color and opacity, neither complete, masks together full: an edge of "
            "one mesh crossing the pixel), combine the two; (2) insert the result in depth "
            "order; (3) a **complete** (mask full *and* area 1) **opaque** fragment hides "
            "everything behind it: throw those away. A full mask with area < 1 is not complete "
            "(the polygon misses a sliver between the border and the sub-samples), and a "
            "transparent fragment hides nothing."
        ),
        stub='''\
def insert_fragment(fragments, incoming, full):
    """Insert `incoming` into one pixel's fragment list (Carpenter's a-buffer).

    fragments: list of FragmentRecord(z, zmax, area, mask, color, opacity, object),
               nearest first; incoming: one FragmentRecord; full: the all-samples mask.
    Complete: mask == full and area == 1.0. Hides what is behind: complete and opacity 1.
    1. The first stored fragment of incoming's surface (same object, color and opacity
       within 1e-12, neither complete, stored.mask | incoming.mask == full) is removed
       and combined with it: dataclasses.replace(stored, z=min of z, zmax=max of zmax,
       area=min(sum of areas, 1.0), mask=the masks or-ed, color=area-weighted mean of
       the colors (stored.color if both areas are 0)); the combination is inserted.
    2. Insert after every stored fragment whose z <= its z.
    3. Remove every fragment behind the first one that hides.
    Return (new_list, merged, discarded): merged is None or (stored, combined);
    discarded lists the fragments removed in step 3, nearest first.
    """
    raise NotImplementedError
''',
        solution=INSERT_SOLUTION,
        call=call_with_step("insert_fragment", case_resolve),
        reference=insert_fragment,
        public=INSERT_CASES,
        generate=_generator(
            ("layers", "one surface split", "slivers", "transparency", "depth ties")
        ),
        **feature_tests(INSERT_FEATURES),
        variants=(
            _insert_variant(
                "depth_tolerance",
                "a tolerance in the depth order: a fragment nearer by a hair is nearer; insert "
                "after exactly the stored fragments whose z <= its z",
                "fragments[position].z <= incoming.z",
                "fragments[position].z <= incoming.z + 1e-6",
            ),
            _insert_variant(
                "sort_by_zmax",
                "sorted by the far depth zmax: the list is kept sorted by the near depth z (zmin)",
                "fragments[position].z <= incoming.z",
                "fragments[position].zmax <= incoming.zmax",
            ),
            _insert_variant(
                "ties_first",
                "inserted before a stored fragment of equal z: it goes after every z <= its z",
                "fragments[position].z <= incoming.z",
                "fragments[position].z < incoming.z",
            ),
            _insert_variant(
                "and_for_or",
                "the combined mask is the AND of the masks: a combined fragment covers the "
                "samples of both, stored.mask | incoming.mask",
                "mask=stored.mask | incoming.mask,",
                "mask=stored.mask & incoming.mask,",
            ),
            _insert_variant(
                "keep_partner",
                "the stored fragment stays in the list next to the combination: remove it first",
                "        fragments.remove(partner)\n",
                "",
            ),
            _insert_variant(
                "merge_any_surface",
                "fragments of different objects, colors or opacities combined: only the two parts "
                "of one surface (same object, color and opacity) combine",
                SAME_SURFACE_TESTS,
                "        not complete(stored, full)\n",
            ),
            _insert_variant(
                "never_discard",
                "nothing is thrown away: every fragment behind a complete opaque one is hidden "
                "and must be removed",
                DISCARD_LOOP,
                "",
            ),
            _insert_variant(
                "discard_behind_partial",
                "fragments discarded behind a partial one: only a complete (mask full and area 1) "
                "opaque fragment hides what is behind it",
                "if complete(f, full) and f.opacity == 1.0:",
                "if f.opacity == 1.0:",
            ),
            _insert_variant(
                "full_mask_is_complete",
                "a full mask taken as complete: a fragment is complete only if its area is 1 too "
                "(an edge can pass between the border and the outer sub-samples)",
                "return f.mask == full and f.area == 1.0",
                "return f.mask == full",
            ),
            _insert_variant(
                "discard_behind_transparent",
                "fragments discarded behind a transparent one: a complete fragment hides what is "
                "behind only if its opacity is 1",
                "if complete(f, full) and f.opacity == 1.0:",
                "if complete(f, full):",
            ),
        ),
        kinds=("fragment_inserted", "fragments_merged", "fragments_discarded"),
        step="insert_fragment",
        place=place_by_event(
            "fragment_inserted",
            lambda event: f"fragment {event.index} at pixel ({event.x}, {event.y})",
        ),
        result=_packed,
        rtol=RTOL,
        stepper=(
            "from scanviz.exercises.abuffer import case_resolve\n"
            "from scanviz.widgets import FragmentInsertionView, Stepper\n"
            "result = case_resolve(CASE, trace=True)\n"
            "inserted = result.trace.of_kind('fragment_inserted')\n"
            "Stepper(inserted, [FragmentInsertionView(inserted, CASE['layout'])]).widget"
        ),
    )
)


# --- exercise 15: the packer --------------------------------------------------------------

PACK_SOLUTION = """\
from scanviz.trace.events import PackStep


def pack_pixel(fragments, full, samples, weights, background):
    steps = []

    def region_color(level, region, weight, branch):
        if level == len(fragments) or weight == 0.0:
            return tuple(b * weight for b in background), weight
        fragment = fragments[level]
        mask_a = region & fragment.mask
        mask_q = region & ~fragment.mask & full
        a = bin(mask_a).count("1") / samples
        q = bin(mask_q).count("1") / samples
        if fragment.opacity == 1.0:
            behind, share = region_color(level + 1, mask_q, q, branch)
            color = tuple(p * a + t for p, t in zip(fragment.color, behind))
        else:
            behind, share = region_color(level + 1, mask_q, q, branch + "u")
            seen, seen_share = region_color(level + 1, mask_a, a, branch + "c")
            through = 1.0 - fragment.opacity
            color = tuple(
                p * fragment.opacity * a + s * through + t
                for p, s, t in zip(fragment.color, seen, behind)
            )
            share = share + seen_share * through
        steps.append(PackStep(level, branch, fragment, region, weight, mask_a, a, mask_q, q, color))
        return color, share

    color, share = region_color(0, full, 1.0, "")
    return color, 1.0 - share, steps
"""


_pack_variant = functools.partial(_variant, PACK_SOLUTION)


PACK_CASES = (
    Case(
        "thesis Fig. 6.7",
        case_inputs(
            [
                fragment(0, 0, LEFT, 0.1, RED, 0),  # front: the left half
                fragment(0, 0, BOTTOM, 0.2, GREEN, 1),  # behind: the bottom half
                fragment(1, 0, BOTTOM, 0.2, GREEN, 2),  # alone: the background shows above
            ],
            2,
            1,
            background=BLUE,
        ),
    ),
    Case(
        "three layers",
        case_inputs(
            [
                fragment(0, 0, FULL, 0.9, GREY, 0, zmax=1.0),
                fragment(0, 0, TOP, 0.5, GREEN, 1),
                fragment(0, 0, RIGHT, 0.2, RED, 2),
                fragment(1, 0, 0x0FF0, 0.3, YELLOW, 3),
                fragment(1, 0, LEFT, 0.6, BLUE, 4),
            ],
            2,
            1,
            background=(0.25, 0.5, 0.75),
        ),
    ),
    Case(
        "glass in front",
        case_inputs(
            [
                fragment(0, 0, BOTTOM, 0.6, RED, 0),
                fragment(0, 0, FULL, 0.2, BLUE, 1, opacity=0.75),  # complete, transparent
                fragment(1, 0, RIGHT, 0.7, GREEN, 2),
                fragment(1, 0, TOP, 0.3, YELLOW, 3, opacity=0.25),  # partial, transparent
            ],
            2,
            1,
            background=(1.0, 1.0, 1.0),
        ),
    ),
)

register(
    Exercise(
        id="pixel_pack",
        number=15,
        title="The fragment packer",
        stage="a-buffer",
        kind="step",
        points=5,
        answer="pack_pixel",
        idea=(
            "After the last fragment, the a-buffer **packs** each pixel's fragment list into one "
            "color, **front to back**, on regions of the pixel: a region is a mask M_Q of "
            "sub-samples still visible and its weight Q = popcount(M_Q) / n (here n = 16). "
            "Start with every sub-sample, weight 1. Fragment i covers M_A = M_Q AND M_i "
            "(weight A) and leaves M_Q AND NOT M_i (weight Q_i) to the fragments behind it.\n\n"
            "An opaque fragment of color P shows P on its part: C = P A + T, where T is the "
            "color times weight of the region it leaves open, packed the same way with the next "
            "fragments (thesis eq. 6.4). A transparent one (opacity o) lets 1 - o of its part "
            "through: C = P o A + S (1 - o) + T, where S packs the *covered* region with the "
            "fragments behind (eq. 6.5). Behind the last fragment a region shows the background; "
            "the pixel's coverage alpha is 1 - the background's share."
        ),
        stub='''\
from scanviz.trace.events import PackStep


def pack_pixel(fragments, full, samples, weights, background):
    """Pack one pixel's fragment list into (color, alpha, steps), front to back.

    fragments: list of FragmentRecord(z, zmax, area, mask, color, opacity, object), nearest
    first; full: the all-samples mask; samples: its bit count n; weights: always "mask"
    here (a region's weight is popcount of its mask / n); background: (r, g, b).
    Pack region (M, W) at level i = 0, 1, ...: past the last fragment, or if W == 0, it
    shows the background (color background * W, background share W). Else, with
    F = fragments[i], append after packing the regions behind (opaque: mask_q only;
    transparent: first mask_q with branch + "u", then mask_a with branch + "c")
    PackStep(level=i, branch, fragment=F, region=M, weight=W, mask_a=M & F.mask, a,
             mask_q=M & ~F.mask & full, q, color): a, q the weights of mask_a, mask_q,
    color the tuple (r, g, b) of the region's color times W (eqs. 6.4, 6.5). Start at
    (full, 1.0), branch "".
    Return (color, alpha, steps): the pixel's color (r, g, b), alpha = 1 - the
    background's share, the PackSteps in the order appended.
    """
    raise NotImplementedError
''',
        solution=PACK_SOLUTION,
        call=call_with_step("pack_pixel", case_resolve),
        reference=pack_pixel,
        public=PACK_CASES,
        generate=_generator(
            ("layers", "one surface split", "transparency", "depth ties"), gap=True
        ),
        **feature_tests(PACK_FEATURES),
        variants=(
            _pack_variant(
                "back_to_front",
                "packed from the farthest fragment: level 0 is the nearest fragment, the one "
                "everything behind is seen around",
                "fragment = fragments[level]",
                "fragment = fragments[len(fragments) - 1 - level]",
            ),
            _pack_variant(
                "double_count",
                "the covered samples are passed on to the fragments behind: the region behind "
                "is M_Q AND NOT M_i, not M_Q",
                "mask_q = region & ~fragment.mask & full",
                "mask_q = region",
            ),
            _pack_variant(
                "own_mask_weight",
                "A counts the fragment's whole mask: it is the part still visible, "
                "popcount(M_Q AND M_i) / n",
                'a = bin(mask_a).count("1") / samples',
                'a = bin(fragment.mask).count("1") / samples',
            ),
            _pack_variant(
                "ignore_opacity",
                "every fragment packed as opaque: a transparent one lets 1 - opacity of its "
                "part through to the fragments behind (eq. 6.5)",
                "if fragment.opacity == 1.0:",
                "if True:",
            ),
            _pack_variant(
                "opacity_as_transparency",
                "opacity used as transparency: the fragment's own color counts opacity times, "
                "what is behind it 1 - opacity",
                "p * fragment.opacity * a + s * through + t",
                "p * through * a + s * fragment.opacity + t",
            ),
            _pack_variant(
                "no_background",
                "uncovered samples left black: past the last fragment a region shows the "
                "background, background * weight",
                "return tuple(b * weight for b in background), weight",
                "return (0.0, 0.0, 0.0), weight",
            ),
        ),
        kinds=("pixel_packed",),
        step="pack_pixel",
        place=place_by_event("pixel_packed", lambda event: f"pixel ({event.x}, {event.y})"),
        result=_packed,
        rtol=RTOL,
        stepper=(
            "from scanviz.exercises.abuffer import case_resolve\n"
            "from scanviz.widgets import PackerView, Stepper\n"
            "result = case_resolve(CASE, trace=True)\n"
            "packed = result.trace.of_kind('pixel_packed')\n"
            "Stepper(packed, [PackerView(packed)], title='the packer, pixel by pixel').widget"
        ),
    )
)

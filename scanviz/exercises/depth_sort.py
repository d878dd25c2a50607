"""Exercise on the ambiguity tests of depth sort (scanviz.visibility.depth_sort), through `solve`.

The student writes the step ``depth_order_test``: for S, the piece at the
far end of the list, and an S' that overlaps it in depth, the first of the
slides' tests that shows S may be painted before S' (bounding rectangles in
x, in y, S behind the plane of S', S' in front of the plane of S, the
projections apart), or None. The real depth sort runs with it: its pairs,
swaps and splits are graded, then the image. Cases are screen polygons (x,
y in pixels, the sample frame of corner sampling; depth z, smaller nearer),
the slides' examples among them (`scanviz.visibility.examples`).
"""

from __future__ import annotations

import functools
import math
import random

from ..visibility import ScreenPolygons, examples, solve
from ..visibility.depth_sort import DepthSort, depth_order_test
from .cases import call_with_step, case_polygons, grid_value, plane_polygon, polygon_lists
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

KINDS = ("pair_tested", "pieces_swapped", "polygon_split")
REVERSED_TESTS = ("other_behind_plane", "s_in_front")


def _solve(inputs: dict, tracer):
    return solve(
        DepthSort(), case_polygons(inputs), inputs["width"], inputs["height"], trace=tracer
    )


def _pair_of_call(index: int, trace: list) -> str:
    """Which pair call `index` tested: each pair past minimax calls once, twice if reversed."""
    calls = []
    for e in trace:
        if e.kind == "pair_tested" and not e.tests[0].passed:
            calls.append(f"pair S = {e.piece}, S' = {e.other}")
            if any(t.name in REVERSED_TESTS for t in e.tests):
                calls.append(f"pair S = {e.piece}, S' = {e.other} (reversed: S' as S)")
    return calls[index] if index < len(calls) else f"call {index + 1}"


def _inputs(polygons: ScreenPolygons, width: int, height: int) -> dict:
    return {"polygons": polygon_lists(polygons), "width": width, "height": height}


def _touching_rectangles(rng: random.Random, width: int, height: int) -> list:
    """Two rectangles sharing a border at an integer x (or y), crossing each other's planes."""
    cut = rng.randint(3, min(width, height) - 3)
    low, high = rng.randint(0, 2), rng.randint(min(width, height) - 2, min(width, height))
    near, far = round(rng.uniform(0.2, 0.4), 3), round(rng.uniform(0.6, 0.8), 3)
    first = [[low, low, near], [cut, low, near], [cut, high, far], [low, high, far]]
    second = [[cut, low + 1, far], [high, low + 1, far], [high, high - 1, near]]
    second.append([cut, high - 1, near])
    if rng.random() < 0.5:  # share a horizontal border instead
        first, second = ([[y, x, z] for x, y, z in p][::-1] for p in (first, second))
    return [first, second]


def _rotated_bars(rng: random.Random, size: int) -> list:
    """Three bars in a cycle (the slides' cyclic overlap), turned by a random angle."""
    bars = _inputs(examples.cyclic_overlap(size), size, size)["polygons"]
    turn, centre = rng.uniform(0, 2 * math.pi), size / 2
    c, s = math.cos(turn), math.sin(turn)
    return [
        [
            [
                round(centre + c * (x - centre) - s * (y - centre), 3),
                round(centre + s * (x - centre) + c * (y - centre), 3),
                z,
            ]
            for x, y, z in bar
        ]
        for bar in bars
    ]


CATEGORIES = ("sloped polygons", "touching rectangles", "cyclic bars", "mixed")
NEAR = "near-equal depths"
BEYOND = "depths just beyond the tolerance"
GAPS = {  # how far a vertex is in front of a plane; the tolerance is 1e-9 x max(1, max |z|)
    NEAR: 2.0**-32,  # 2.3e-10: on the plane, within the tolerance
    BEYOND: 2.0**-28,  # 3.7e-9: in front of it, beyond the tolerance (and far below 1e-6)
}


def _depth_plane(rng: random.Random, x0: float, y0: float, tilt: bool):
    """A depth plane rising to the right (and up or down if `tilt`) by dyadic steps, so that its
    depth at quarter pixels is exact in floating point (and so is a vertex `GAPS` off it)."""
    dzdx, dzdy = rng.choice((1, 2)) / 128, rng.choice((-1, 0, 1)) / 256 if tilt else 0.0
    return lambda x, y: 0.75 + dzdx * (x - x0) + dzdy * (y - y0)


def _corners(rng: random.Random, x0, y0, x1, y1, depth) -> list:
    """The rectangle [x0, x1] x [y0, y1], or a triangle of three of its corners, on `depth`."""
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    if rng.random() < 0.5:
        corners.pop(rng.randrange(4))
    return [[x, y, depth(x, y)] for x, y in corners]


def _near_pair(rng: random.Random, size: int, gap: float) -> list:
    """Two polygons, S and S' of the step's first call, where the vertex of S nearest in front
    of the plane of S' is `gap` in front of it, their extents overlap (so the plane tests
    decide) and some test passes whatever the gap.

    Either S lies wholly `gap` in front of the plane of S' and reaches past it where that plane
    is deepest (so S is farther), or S' is flat at the depth of S's nearest vertices plus `gap`
    (their depth extents overlap by `gap`), where S's plane is deeper. Built on quarter pixels
    in a canonical frame, then turned by a random symmetry of the size x size raster.
    """
    on_plane = rng.random() < 0.5
    x0, y0 = grid_value(rng, 0.5, 3), grid_value(rng, 0.5, 3)
    x1, y1 = x0 + grid_value(rng, 3, 5), y0 + grid_value(rng, 3, size - 4 - y0)
    depth = _depth_plane(rng, x0, y0, tilt=on_plane)
    plane = _corners(rng, x0, y0, x1, y1, depth)
    if on_plane:  # S on the plane of S', from inside it to past its deepest side
        left, right = grid_value(rng, x0 + 1, x1 - 1), grid_value(rng, x1 + 1, size - 1)
        low, high = grid_value(rng, 0, y0), grid_value(rng, y1, size)  # S's rows hold those of S'
        corners = [(left, low), (right, low), (right, high), (left, high)]
        pair = [plane, [[x, y, depth(x, y) - gap] for x, y in corners]]
    else:  # S' flat, a quarter pixel and more right of S's nearest vertices (at x0)
        left, right = x0 + 0.25, x0 + grid_value(rng, 1, 3)
        low, high = grid_value(rng, 0, y0 + 1), grid_value(rng, y1 - 1, size)
        corners = [(left, low), (right, low), (right, high), (left, high)]
        pair = [[[x, y, depth(x0, y0) + gap] for x, y in corners], plane]
    flip_x, flip_y, swap = (rng.random() < 0.5 for _ in range(3))
    turned = []
    for polygon in pair:
        points = []
        for x, y, z in polygon:
            x, y = size - x if flip_x else x, size - y if flip_y else y
            points.append([y, x, z] if swap else [x, y, z])
        turned.append(points)
    return turned


def _depth_sort_case(rng: random.Random, feature: str | None = None) -> Case:
    """Screen polygons; a `feature` of `DEPTH_SORT_FEATURES` picks the kind that can have it:
    the near-equal depths build their pair, with up to two polygons nearer than it."""
    width, height = rng.randint(10, 16), rng.randint(10, 16)
    category = feature if feature in CATEGORIES else rng.choice(CATEGORIES)
    if feature == "extents touch":
        category = "touching rectangles"
    if feature in GAPS:
        width = height = rng.randint(12, 16)
        polygons = _near_pair(rng, width, GAPS[feature])
        # nearer than the pair (depths below 0.37 and 0.68 up): tested only after it is painted
        polygons += [
            plane_polygon(rng, width, height, depth=(0.15, 0.3), slope=0.005)
            for _ in range(rng.randint(0, 2))
        ]
    elif category == "cyclic bars":
        width = height = 24
        polygons = _rotated_bars(rng, 24)
    elif category == "touching rectangles":
        polygons = _touching_rectangles(rng, width, height)
    else:
        polygons = [
            plane_polygon(rng, width, height, depth=(0.3, 0.7), slope=0.06)
            for _ in range(rng.randint(2, 5))
        ]
        if category == "mixed":
            polygons += _touching_rectangles(rng, width, height)
    label = feature or category
    return Case(
        f"{label}: {len(polygons)} polygons",
        {"polygons": polygons, "width": width, "height": height},
        label,
    )


def _plane_at(plane, x, y):
    x0, y0, z0, dzdx, dzdy = plane
    return z0 + dzdx * (x - x0) + dzdy * (y - y0)


def _extents(polygon, axis: int) -> tuple[float, float]:
    return min(v[axis] for v in polygon), max(v[axis] for v in polygon)


def _touch(s, other) -> bool:
    """Whether the extents of S and S' only touch on some axis."""
    for axis in (0, 1):
        (s_low, s_high), (low, high) = _extents(s, axis), _extents(other, axis)
        if s_high == low or high == s_low:
            return True
    return False


def _extents_overlap(s, other) -> bool:
    """Whether the x extents of S and S' overlap, and so do their y extents (more than touch)."""
    return all(
        _extents(s, axis)[1] > _extents(other, axis)[0]
        and _extents(other, axis)[1] > _extents(s, axis)[0]
        for axis in (0, 1)
    )


def _in_front(feature: str):
    """Whether, in some call whose extents overlap, the vertex of S nearest in front of the
    plane of S' is in front of it within the tolerance (NEAR) or beyond it, by at most 16 times
    the tolerance (BEYOND)."""

    def test(case, reference) -> bool:
        for (s, other, _, other_plane, tolerance), _ in reference.arguments:
            front = max(_plane_at(other_plane, x, y) - z for x, y, z in s)
            low, high = (0, tolerance) if feature == NEAR else (tolerance, 16 * tolerance)
            if _extents_overlap(s, other) and low < front <= high:
                return True
        return False

    return test


def _result(name):
    return lambda case, reference: name in reference.calls


DEPTH_SORT_FEATURES = {
    **{
        name: _result(name)
        for name in ("x_extent", "y_extent", "s_behind_plane", "other_in_front", "no_overlap")
    },
    "no test passes": _result(None),
    "extents touch": lambda case, reference: any(
        _touch(args[0], args[1]) for args, _ in reference.arguments
    ),
    NEAR: _in_front(NEAR),
    BEYOND: _in_front(BEYOND),
}
"""Tests of the ambiguity tests' features: each result the step returns (each test passing
first, and none), extents that only touch (apart, by ownership), and S in front of the plane of
S' by a hair, within the tolerance (on it, by the rule) and just beyond it (in front)."""


DEPTH_ORDER_SOLUTION = """\
from fractions import Fraction


def depth_order_test(s, other, s_plane, other_plane, tolerance):
    def apart(axis):
        s_low, s_high = min(v[axis] for v in s), max(v[axis] for v in s)
        low, high = min(v[axis] for v in other), max(v[axis] for v in other)
        return s_high <= low or high <= s_low

    def plane(p, x, y):
        x0, y0, z0, dzdx, dzdy = p
        return z0 + dzdx * (x - x0) + dzdy * (y - y0)

    if apart(0):
        return "x_extent"
    if apart(1):
        return "y_extent"
    if all(z - plane(other_plane, x, y) >= -tolerance for x, y, z in s):
        return "s_behind_plane"
    if all(z - plane(s_plane, x, y) <= tolerance for x, y, z in other):
        return "other_in_front"
    if not (separated(s, other) or separated(other, s)):
        return None
    return "no_overlap"


def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def separated(polygon, other):
    # Convex polygons do not overlap iff some edge has the other wholly on its outer side.
    points = [(Fraction(x), Fraction(y)) for x, y, _ in polygon]
    others = [(Fraction(x), Fraction(y)) for x, y, _ in other]
    area = sum(cross(points[0], p, q) for p, q in zip(points[1:], points[2:]))
    if area == 0:
        return True  # no area: it overlaps nothing
    turn = 1 if area > 0 else -1
    for p, q in zip(points, points[1:] + points[:1]):
        if p != q and all(turn * cross(p, q, r) <= 0 for r in others):
            return True
    return False
"""


def _on_slope(corners: list, gap: float) -> list:
    """Vertices `gap` in front of the plane z = 0.5 + x / 64 (exact at integer x)."""
    return [[x, y, 0.5 + x / 64 - gap] for x, y in corners]


_variant = functools.partial(edited_variant, DEPTH_ORDER_SOLUTION)


EXTENT_TESTS = """\
    if apart(0):
        return "x_extent"
    if apart(1):
        return "y_extent"
"""
BEHIND_TEST = """\
    if all(z - plane(other_plane, x, y) >= -tolerance for x, y, z in s):
        return "s_behind_plane"
"""


register(
    Exercise(
        id="depth_sort_tests",
        number=16,
        title="The ambiguity tests of depth sort",
        stage="visibility",
        kind="step",
        points=4,
        answer="depth_order_test",
        idea=(
            "Depth sort (Newell, Newell and Sancha) sorts the polygons on their farthest "
            "depth (**smaller z is nearer**: the largest zmax first) and paints from the far "
            "end of the list. Before S, the far end, is painted, each S' that overlaps it in "
            "depth (S'.zmax > S.zmin: the minimax test) is checked with the slides' tests, "
            "cheapest first; the **first** that passes shows S may go before S':\n\n"
            "1. `x_extent`: the x extents do not overlap; 2. `y_extent`: the y extents do not "
            "overlap (extents that only touch are apart: a polygon owns no sample on its right "
            "or top border);\n3. `s_behind_plane`: every vertex of S is behind S''s plane or on "
            "it (depth at least the plane's, within `tolerance`);\n4. `other_in_front`: every "
            "vertex of S' is in front of S's plane or on it;\n5. `no_overlap`: the projections "
            "onto the screen do not overlap (touching does not count; decide exactly).\n\n"
            "If none passes, depth sort calls your test again with S and S' exchanged: if "
            "then S' may go before S, S' moves to the far end, else a piece is split."
        ),
        stub=(
            "def depth_order_test(s, other, s_plane, other_plane, tolerance):\n"
            '    """s, other: the vertices of S and S\', tuples of (x, y, z) (x, y in pixels,\n'
            "    z the depth, smaller is nearer). s_plane, other_plane: their depth planes\n"
            "    (x0, y0, z0, dzdx, dzdy): depth z0 + dzdx * (x - x0) + dzdy * (y - y0).\n"
            "    tolerance: how far from a plane (in depth) a vertex still counts as on it.\n"
            '    Return the name of the first test that passes, in order: "x_extent",\n'
            '    "y_extent", "s_behind_plane", "other_in_front", "no_overlap"; None if none\n'
            "    does. For no_overlap the polygons are convex; decide exactly (Fraction(x)\n"
            '    holds a float exactly)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=DEPTH_ORDER_SOLUTION,
        call=call_with_step("depth_order_test", _solve),
        reference=depth_order_test,
        public=(
            Case(
                "the UMBC slide: a sloped triangle piercing two flat polygons, a square beside",
                {
                    "polygons": [
                        *_inputs(examples.slides_zbuffer(), 10, 9)["polygons"],
                        [[11, 1, 4], [13, 1, 4], [13, 3, 6], [11, 3, 6]],
                    ],
                    "width": 14,
                    "height": 9,
                },
            ),
            Case(
                "three bars in a cycle (the slides' cyclic overlap)",
                _inputs(examples.cyclic_overlap(), 24, 24),
            ),
            Case(
                "two rectangles passing through each other",
                _inputs(examples.interpenetrating(), 16, 12),
            ),
            Case(
                "a long polygon behind a short one",
                _inputs(examples.long_behind_short(), 16, 12),
            ),
            Case(
                "two rectangles sharing the border x = 6, each crossing the other's plane",
                {
                    "polygons": [
                        [[1, 1, 0.2], [6, 1, 0.2], [6, 9, 0.8], [1, 9, 0.8]],
                        [[6, 2, 0.8], [11, 2, 0.8], [11, 8, 0.3], [6, 8, 0.3]],
                    ],
                    "width": 12,
                    "height": 10,
                },
            ),
            Case(
                "two squares on the plane of a sloped one (z = 0.5 + x / 64), in front of it by "
                "2^-32 (within the tolerance 1e-9: on it) and by 2^-28 = 3.7e-9 (beyond it)",
                {
                    "polygons": [
                        _on_slope([(1, 1), (7, 1), (7, 9), (1, 9)], 0.0),
                        _on_slope([(4, 0), (10, 0), (10, 4), (4, 4)], GAPS[NEAR]),
                        _on_slope([(4, 6), (10, 6), (10, 10), (4, 10)], GAPS[BEYOND]),
                    ],
                    "width": 12,
                    "height": 11,
                },
            ),
        ),
        generate=_depth_sort_case,
        **feature_tests(DEPTH_SORT_FEATURES),
        variants=(
            _variant(
                "extents_touching_overlap",
                "a polygon owns no sample on its right or top border, so extents that only "
                "touch are apart: s_high <= low, not s_high < low",
                ("return s_high <= low or high <= s_low", "return s_high < low or high < s_low"),
            ),
            _variant(
                "plane_sign_reversed",
                "smaller z is nearer: S is behind the plane of S' where its depth is at least "
                "the plane's (z - plane >= -tolerance), not at most",
                (
                    "z - plane(other_plane, x, y) >= -tolerance",
                    "z - plane(other_plane, x, y) <= tolerance",
                ),
            ),
            _variant(
                "no_tolerance",
                "a vertex within `tolerance` of the plane counts as on it (its depth was "
                "rounded): S is behind when z - plane >= -tolerance, not >= 0",
                (
                    "z - plane(other_plane, x, y) >= -tolerance",
                    "z - plane(other_plane, x, y) >= 0",
                ),
            ),
            _variant(
                "fixed_epsilon",
                "only the `tolerance` given counts as on a plane (1e-9, scaled with the "
                "scene's depths): a vertex 3.7e-9 in front of the plane of S' is in front of "
                "it, so S is not behind it; an epsilon of your own, such as 1e-6, takes it for "
                "on the plane",
                ("-tolerance for x, y, z in s", "-1e-6 for x, y, z in s"),
                ("<= tolerance for x, y, z in other", "<= 1e-6 for x, y, z in other"),
            ),
            _variant(
                "plane_tests_first",
                "the tests run cheapest first, as on the slides: the x and y extents before "
                "the plane tests",
                (EXTENT_TESTS + BEHIND_TEST, BEHIND_TEST + EXTENT_TESTS),
            ),
        ),
        kinds=KINDS,
        step="depth_order_test",
        place=_pair_of_call,
        result=lambda result: result.polygon.tolist(),
        stepper=(
            "from scanviz.exercises.depth_sort import case_polygons\n"
            "from scanviz.widgets.depth_sort import depth_sort_stepper\n"
            "depth_sort_stepper(case_polygons(CASE), CASE['width'], CASE['height'])"
        ),
    )
)

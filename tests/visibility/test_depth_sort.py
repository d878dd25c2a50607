"""Depth sort (Newell, Newell and Sancha) against the z-buffer, the slides and hostile input."""

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import scanviz.visibility.depth_sort  # noqa: F401 - registers "depth_sort"
from scanviz import steps
from scanviz.trace import Recorder
from scanviz.visibility import ScreenPolygons, examples, solve, zbuffer
from scanviz.visibility.depth_sort import (
    DepthSort,
    convex_hull,
    depth_order_test,
    projections_overlap,
)
from tests.visibility.support import assert_agrees, interpenetrate, random_scene

SIZE = 24
seeds = st.integers(0, 2**32 - 1)


def flat(z):
    return (0.0, 0.0, float(z), 0.0, 0.0)


def labels(result):
    return [piece.label for piece in result.order]


@settings(max_examples=10)
@given(seed=seeds, n=st.integers(1, 7))
def test_agrees_with_the_zbuffer_without_interpenetration(seed, n):
    assert_agrees("depth_sort", random_scene(np.random.default_rng(seed), n, SIZE), SIZE, SIZE)


@settings(max_examples=10)
@given(seed=seeds, n=st.integers(2, 6))
def test_agrees_with_the_zbuffer_with_interpenetration(seed, n):
    polygons = random_scene(np.random.default_rng(seed), n, SIZE, interpenetrating=True)
    assert_agrees("depth_sort", polygons, SIZE, SIZE)


def test_cyclic_overlap_painter_differs_depth_sort_splits_and_agrees():
    polygons = examples.cyclic_overlap()
    reference = zbuffer(polygons, 24, 24)
    assert (solve("painter", polygons, 24, 24).polygon != reference.polygon).any()
    result, _, _ = assert_agrees("depth_sort", polygons, 24, 24)
    assert result.algorithm.splits >= 1 and result.algorithm.unresolved == 0
    assert np.array_equal(result.polygon, reference.polygon)  # no ties in this scene


# Three bars in a true cycle that do not pass through one another (support.interpenetrate is
# False for every pair): each is nearer than the next where they cross.
CYCLE_VERTICES = [
    [(3.0, 14.0, 0.5272), (21.0, 14.0, 0.5303), (21.0, 18.0, 0.3691), (3.0, 18.0, 0.3659)],
    [(14.768, 3.206, 0.7436), (5.768, 18.794, 0.2453), (2.304, 16.794, 0.1053)]
    + [(11.304, 1.206, 0.6036)],
    [(18.232, 18.794, 0.7505), (9.232, 3.206, 0.2996), (12.696, 1.206, 0.229)]
    + [(21.696, 16.794, 0.6799)],
]
CYCLE = ScreenPolygons.from_polygons(CYCLE_VERTICES)


def test_a_cycle_without_interpenetration_is_broken_by_a_cycle_split():
    assert not any(
        interpenetrate(CYCLE_VERTICES[i], CYCLE_VERTICES[j]) for i in range(3) for j in range(i)
    )
    reference = zbuffer(CYCLE, 24, 24)
    assert (solve("painter", CYCLE, 24, 24).polygon != reference.polygon).any()
    result = solve("depth_sort", CYCLE, 24, 24, trace=True)
    events = [e.kind for e in result.trace]
    split = next(e for e in result.trace if e.kind == "polygon_split")
    assert split.why == "cycle" and events.index("pieces_swapped") < events.index("polygon_split")
    assert np.array_equal(result.polygon, reference.polygon)
    fast = solve("depth_sort", CYCLE, 24, 24)
    assert labels(fast) == labels(result) and fast.algorithm == result.algorithm


def test_interpenetrating_is_split_by_the_other_plane():
    polygons = examples.interpenetrating()
    result = solve("depth_sort", polygons, 16, 12, trace=Recorder(kinds=["polygon_split"]))
    assert [(e.piece, e.by, e.why) for e in result.trace] == [("0", 1, "interpenetration")]
    assert sorted(labels(result)) == ["0a", "0b", "1"]
    assert np.array_equal(result.polygon, zbuffer(polygons, 16, 12).polygon)


def test_the_slides_painter_example_paints_in_the_slides_order():
    result = solve("depth_sort", examples.slides_painter(), 16, 12)
    assert labels(result) == ["0", "1", "2"]  # z = 10, 8, 5: farthest first
    assert result.algorithm.swaps == result.algorithm.splits == 0
    assert result.algorithm.settled == {"minimax": 2}


def test_long_behind_short_is_right_without_a_split():
    polygons = examples.long_behind_short()
    result = solve("depth_sort", polygons, 16, 12)
    assert np.array_equal(result.polygon, zbuffer(polygons, 16, 12).polygon)
    assert result.algorithm.splits == 0


def test_a_swap_moves_the_nearer_piece_behind_and_retests():
    # S (zmax 0.9) slopes from 0.9 to 0.1 and lies in front of flat S' at 0.5 over their
    # overlap: S' must be painted first. Their x and y extents overlap, S straddles S''s plane,
    # S' is not in front of S's, the projections overlap; reversed, S' is behind S's plane.
    polygons = ScreenPolygons.from_polygons(
        [
            [(0, 0, 0.9), (8, 0, 0.1), (8, 8, 0.1), (0, 8, 0.9)],
            [(6, 2, 0.5), (12, 2, 0.5), (12, 6, 0.5), (6, 6, 0.5)],
        ]
    )
    result = solve("depth_sort", polygons, 12, 8, trace=True)
    swapped = [e for e in result.trace if e.kind == "pieces_swapped"]
    assert [(e.piece, e.moved, e.order) for e in swapped] == [("0", "1", ("1", "0"))]
    first = next(e for e in result.trace if e.kind == "pair_tested")
    assert (first.piece, first.other, first.settled_by, first.outcome) == (
        "0",
        "1",
        "other_behind_plane",
        "swap",
    )
    assert [t.name for t in first.tests] == [
        "minimax",
        "x_extent",
        "y_extent",
        "s_behind_plane",
        "other_in_front",
        "no_overlap",
        "other_behind_plane",
    ]
    assert labels(result) == ["1", "0"]
    assert np.array_equal(result.polygon, zbuffer(polygons, 12, 8).polygon)


@pytest.mark.parametrize(
    "scene, size",
    [
        (examples.cyclic_overlap(), (24, 24)),
        (examples.interpenetrating(), (16, 12)),
        (examples.slides_painter(), (16, 12)),
    ],
)
def test_traced_equals_untraced(scene, size):
    fast = solve("depth_sort", scene, *size)
    traced = solve("depth_sort", scene, *size, trace=True)
    assert labels(fast) == labels(traced)
    assert fast.algorithm == traced.algorithm
    for name in ("polygon", "depth", "values"):
        assert np.array_equal(getattr(fast, name), getattr(traced, name)), name
    pairs = [e for e in traced.trace if e.kind == "pair_tested"]
    assert len(pairs) == traced.algorithm.pairs_tested
    assert sum(e.kind == "polygon_split" for e in traced.trace) == traced.algorithm.splits


@settings(max_examples=8)
@given(seed=seeds, n=st.integers(2, 12), interpenetrating=st.booleans())
def test_traced_equals_untraced_on_random_scenes(seed, n, interpenetrating):
    polygons = random_scene(np.random.default_rng(seed), n, SIZE, interpenetrating)
    fast = solve("depth_sort", polygons, SIZE, SIZE)
    traced = solve("depth_sort", polygons, SIZE, SIZE, trace=True)
    assert labels(fast) == labels(traced) and fast.algorithm == traced.algorithm
    assert np.array_equal(fast.polygon, traced.polygon)
    with steps.using(depth_order_test=depth_order_test):  # the step table's path, untraced
        plugged = solve("depth_sort", polygons, SIZE, SIZE)
    assert labels(plugged) == labels(fast) and plugged.algorithm == fast.algorithm


def test_degenerate_input_renders_without_raising():
    empty = ScreenPolygons.from_polygons([])
    assert (solve("depth_sort", empty, 8, 8).polygon == -1).all()
    one = ScreenPolygons.from_polygons([[(1, 1, 0.5), (6, 1, 0.5), (1, 6, 0.5)]])
    assert labels(solve("depth_sort", one, 8, 8)) == ["0"]
    coplanar = ScreenPolygons.from_polygons(
        [
            [(0, 0, 0.5), (6, 0, 0.5), (6, 6, 0.5), (0, 6, 0.5)],
            [(2, 2, 0.5), (8, 2, 0.5), (8, 8, 0.5), (2, 8, 0.5)],
            [(1, 1, 0.5), (7, 1, 0.5), (1, 7, 0.5)],
        ]
    )
    result = solve("depth_sort", coplanar, 8, 8)
    assert result.algorithm.splits == 0 and (result.polygon >= 0).sum() > 0
    edge_on = ScreenPolygons.from_polygons(
        [[(1, 1, 0.2), (6, 6, 0.8), (3.5, 3.5, 0.5)], [(0, 0, 0.5), (7, 0, 0.5), (0, 7, 0.5)]]
    )
    result = solve("depth_sort", edge_on, 8, 8)
    assert result.algorithm.left_out == 1 and labels(result) == ["1"]


def slivers(n: int) -> ScreenPolygons:
    """n thin bars through the centre at even angles, alternately tilted: every pair crosses."""
    polygons = []
    for k in range(n):
        c, d = np.cos(np.pi * k / n), np.sin(np.pi * k / n)
        u, v = np.array([-30.0, 30, 30, -30]), np.array([-0.6, -0.6, 0.6, 0.6])
        z = 0.5 + (0.4 if k % 2 else -0.4) * u / 30 + 0.001 * k
        polygons.append(list(zip(32 + u * c - v * d, 32 + u * d + v * c, z, strict=True)))
    return ScreenPolygons.from_polygons(polygons)


def test_hostile_mutually_cyclic_slivers_terminate_within_the_split_budget():
    result = solve(DepthSort(max_splits=60), slivers(12), 64, 64)
    assert result.algorithm.splits <= 60
    assert result.algorithm.unresolved > 0  # the budget ran out: the rest is accepted as it is
    default = solve("depth_sort", slivers(8), 64, 64)
    assert default.algorithm.splits > 0


def test_max_splits_zero_falls_back_to_the_list_order():
    result = solve(DepthSort(max_splits=0), examples.cyclic_overlap(), 24, 24)
    assert result.algorithm.splits == 0 and result.algorithm.unresolved > 0
    assert sorted(labels(result)) == ["0", "1", "2"]


def test_bad_max_splits_is_refused():
    with pytest.raises(ValueError, match="'max_splits'"):
        DepthSort(max_splits=-1)


def test_the_step_runs_the_tests_in_the_slides_order():
    far = ((0, 0, 9), (4, 0, 9), (0, 4, 9))
    assert depth_order_test(far, ((4, 0, 1), (9, 0, 1), (4, 4, 1)), flat(9), flat(1), 1e-9) == (
        "x_extent"  # touching extents are apart: no sample is owned by both
    )
    assert depth_order_test(far, ((0, 4, 1), (4, 4, 1), (0, 9, 1)), flat(9), flat(1), 1e-9) == (
        "y_extent"
    )
    near = ((1, 1, 1), (5, 1, 1), (1, 5, 1))
    assert depth_order_test(far, near, flat(9), flat(1), 1e-9) == "s_behind_plane"
    # S sloped through S''s depth, S' at 5 wholly in front of S's plane (z = 9 - x) there
    sloped, sloped_plane = ((0, 0, 9), (8, 0, 1), (0, 8, 9)), (0.0, 0.0, 9.0, -1.0, 0.0)
    small = ((1, 1, 5), (3, 1, 5), (1, 3, 5))
    assert depth_order_test(sloped, small, sloped_plane, flat(5), 1e-9) == "other_in_front"
    # crossing in depth, the projections apart across the diagonal (bounding boxes overlap)
    lower = ((0, 0, 9), (8, 0, 1), (0, 8, 9))
    upper = ((8.5, 8.5, 2), (8.5, 1, 6), (1, 8.5, 6))
    plane = (8.5, 8.5, 2.0, -4 / 7.5, -4 / 7.5)
    assert depth_order_test(lower, upper, sloped_plane, plane, 1e-9) == "no_overlap"
    crossing, crossing_plane = ((2, 2, 9), (6, 2, 1), (2, 6, 1)), (2.0, 2.0, 9.0, -2.0, -2.0)
    assert depth_order_test(sloped, crossing, sloped_plane, crossing_plane, 1e-9) is None


def test_plane_tests_use_the_tolerance():
    far = ((0, 0, 1.0), (4, 0, 1.0), (0, 4, 1.0))
    near = ((0, 0, 1.0 - 1e-12), (4, 0, 1.0), (0, 4, 1.0))
    assert depth_order_test(near, far, flat(1.0), flat(1.0), 1e-9) == "s_behind_plane"  # "on"
    assert depth_order_test(near, far, flat(1.0), flat(1.0), 0.0) == "other_in_front"


def random_convex(rng, n):
    center, radius = rng.uniform(0, 8, 2), rng.uniform(0.5, 4)
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    return [tuple(center + radius * np.array([np.cos(a), np.sin(a)])) for a in angles]


@settings(max_examples=40)
@given(seed=seeds)
def test_projections_overlap_agrees_with_shapely(seed):
    rng = np.random.default_rng(seed)
    a, b = random_convex(rng, rng.integers(3, 6)), random_convex(rng, rng.integers(3, 6))
    area = shapely.Polygon(a).intersection(shapely.Polygon(b)).area
    if 1e-9 < area or area == 0.0:
        assert projections_overlap(a, b) == (area > 0)


def test_projections_overlap_is_exact_on_touching_and_nested_polygons():
    square = [(0, 0), (2, 0), (2, 2), (0, 2)]
    assert not projections_overlap(square, [(2, 0), (4, 0), (4, 2), (2, 2)])  # a shared edge
    assert not projections_overlap(square, [(2, 2), (3, 2), (3, 3)])  # a shared corner
    assert projections_overlap(square, [(0.5, 0.5), (1, 0.5), (1, 1)])  # nested
    assert projections_overlap(square, [(0, 0), (2, 0), (0, 2)])  # half of it
    tiny = float(Fraction(1, 2**40))
    assert projections_overlap(square, [(2 - tiny, 0), (4, 0), (4, 2)])  # overlap of 2^-40
    assert not projections_overlap(square, [(1, 1), (1, 1), (1, 1)])  # no area


def test_convex_hull_drops_reflex_and_collinear_points():
    arrow = [(0, 0), (4, 2), (0, 4), (1, 2)]
    assert convex_hull(arrow) == [(0, 0), (4, 2), (0, 4)]

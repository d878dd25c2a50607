"""The Floating Horizon Algorithm: hand-derived cases, horizon invariants, traced == untraced."""

from __future__ import annotations

from collections import defaultdict

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.surfaces import GridSurface, View, gaussian, polynomial, rogers
from scanviz.surfaces.horizon import (
    FLAG_PAIRS,
    crossing,
    flag,
    floating_horizon,
    monotone_pieces,
    visible_parts,
)
from scanviz.trace import Recorder, Trace

# Looking along +y, horizontal, parallel: screen = (x, z) exactly when x and z both span [0, 4]
# and the raster is 5 x 5 (scale 1, no offset).
SIDE_VIEW = View((0.0, -10.0, 0.0), (0.0, 1.0, 0.0), "parallel")
COLUMNS = [0.0, 1.0, 2.0, 3.0, 4.0]


def side_surface(*curves):
    """The curves y = 0, 1, 2, ... (nearest the side view first) with the given heights."""
    return GridSurface(COLUMNS, np.arange(len(curves), dtype=float), curves)


def traced(surface, view, width, height, **options):
    recorder = Recorder()
    result = floating_horizon(surface, view, width, height, trace=recorder, **options)
    return result, recorder.trace()


# --- hand-derived cases ---------------------------------------------------------------------


def test_screen_is_x_and_z_in_the_side_view():
    screen, _ = SIDE_VIEW.screen_from_world([[0, 0, 0], [4, 0, 4], [1, 2, 3]], 5, 5)
    assert screen.tolist() == [[0.0, 0.0], [4.0, 4.0], [1.0, 3.0]]


def test_flat_tilted_plane_every_curve_fully_visible():
    plane = GridSurface.from_function(lambda x, y: 0.5 * y, (-1, 1), (-1, 1), 6, 6)
    result, trace = traced(plane, View((0, -6, 4), (0, 6, -4)), 64, 64)
    columns = [e for e in trace if e.kind == "horizon_column"]
    assert {e.flag for e in columns} == {1}
    assert sum(result.stats.intersections.values()) == 0
    assert result.stats.segments == result.stats.columns - result.stats.pieces
    assert result.order == (0, 1, 2, 3, 4, 5)


def test_far_curve_hidden_where_the_nearer_ones_enclose_it():
    # up = 2 (curve 0), low = 0.5 (curve 1); curve 2 = 4, 3, 2.5, 1.5, 0 is visible above 2,
    # hidden between, visible below 0.5. It meets up = 2 at x = 2 + 0.5 / 1 = 2.5 and
    # low = 0.5 at x = 3 + (1.5 - 0.5) / 1.5 = 3 + 2/3.
    surface = side_surface([2.0] * 5, [0.5] * 5, [4.0, 3.0, 2.5, 1.5, 0.0])
    result, trace = traced(surface, SIDE_VIEW, 5, 5)
    third = [e for e in trace if e.kind == "horizon_column" and e.curve == 2]
    assert [e.flag for e in third] == [1, 1, 1, 0, -1]
    assert np.allclose(
        [p for e in third for p in e.drawn],
        [(0, 4, 1, 3), (1, 3, 2, 2.5), (2, 2.5, 2.5, 2.0), (3 + 2 / 3, 0.5, 4, 0)],
    )
    assert result.stats.intersections == {
        pair: int(pair in ((1, 0), (0, -1))) for pair in FLAG_PAIRS
    }
    assert result.up.tolist() == [4.0, 3.0, 2.5, 2.0, 2.0]
    assert result.low.tolist() == [0.5, 0.5, 0.5, 0.5, 0.0]
    assert result.lines[::-1].astype(int).tolist() == [
        [1, 0, 0, 0, 0],
        [0, 1, 0, 0, 0],
        [1, 1, 1, 1, 1],  # curve 0, and curve 2 meeting it at (2.5, 2) -> pixel (2, 2)
        [0, 0, 0, 0, 0],
        [1, 1, 1, 1, 1],  # curve 1 at 0.5 rounds to row 0 (ties to even), curve 2 ends at (4, 0)
    ]


def test_a_jump_from_above_to_below_needs_both_intersections():
    # Between columns 2 and 3 curve 2 falls from 4 to 0: it meets up = 2 at t = 2 / 4
    # and low = 0.5 at t = 3.5 / 4.
    surface = side_surface([2.0] * 5, [0.5] * 5, [4.0, 4.0, 4.0, 0.0, 0.0])
    result, trace = traced(surface, SIDE_VIEW, 5, 5)
    jump = next(e for e in trace if e.kind == "horizon_column" and e.curve == 2 and e.x == 3)
    assert (jump.previous_flag, jump.flag, jump.up, jump.low) == (1, -1, 2.0, 0.5)
    assert np.allclose(jump.drawn, [(2, 4, 2.5, 2), (2.875, 0.5, 3, 0)])
    assert result.stats.intersections[1, -1] == 2


def test_near_curve_higher_hides_the_far_one_from_the_crossing_on():
    # Looking down at 45 degrees (parallel), screen y is proportional to y + z. Curve 0 (y = 0)
    # rises from z = 0 to 3, curve 1 (y = 1, z = -2) sets the lower horizon far below, and the
    # flat curve 2 (y = 2, z = 0) is hidden exactly where curve 0 is above it: y + z = 3x > 2,
    # from x = 2/3 on.
    surface = GridSurface([0.0, 1.0], [0.0, 1.0, 2.0], [[0.0, 3.0], [-2.0, -2.0], [0.0, 0.0]])
    view = View((0.5, -100.0, 100.0), (0.0, 1.0, -1.0), "parallel")
    result, trace = traced(surface, view, 41, 41)
    fit = [[0, 0, 0], [1, 0, 3], [0, 1, -2], [1, 1, -2], [0, 2, 0], [1, 2, 0]]
    screen, _ = view.screen_from_world(fit, 41, 41)
    (x0, a), (x1, b), _, _, (_, c), _ = screen.tolist()
    crossing_x = x0 + (x1 - x0) * (c - a) / (b - a)  # where curve 0 reaches curve 2's height
    assert crossing_x == pytest.approx(x0 + (x1 - x0) * 2 / 3)
    far = [e for e in trace if e.kind == "horizon_column" and e.curve == 2]
    assert [e.flag for e in far] == [1 if e.x <= crossing_x else 0 for e in far]
    assert {e.flag for e in far} == {0, 1}
    cut = next(e for e in far if e.previous_flag == 1 and e.flag == 0)
    assert cut.drawn[0][2:] == pytest.approx((crossing_x, c))
    assert result.stats.intersections == {pair: int(pair == (1, 0)) for pair in FLAG_PAIRS}


def test_two_curves_the_far_one_below_the_near_one_is_seen_from_below():
    # With two curves up == low == the near curve, so a far curve below it is under the lower
    # horizon: visible (flag -1), as Rogers' rule says; the flags change at the crossing.
    surface = GridSurface([0.0, 1.0], [0.0, 1.0], [[0.0, 3.0], [0.0, 0.0]])
    view = View((0.5, -100.0, 100.0), (0.0, 1.0, -1.0), "parallel")
    result, trace = traced(surface, view, 41, 41)
    screen, _ = view.screen_from_world(
        [[0, 0, 0], [1, 0, 3], [0, 1, 0]], 41, 41, fit=[[0, 0, 0], [1, 0, 3], [0, 1, 0], [1, 1, 0]]
    )
    (x0, a), (x1, b), (_, c) = screen.tolist()
    crossing_x = x0 + (x1 - x0) * (c - a) / (b - a)
    far = [e for e in trace if e.kind == "horizon_column" and e.curve == 1]
    assert [e.flag for e in far] == [1 if e.x <= crossing_x else -1 for e in far]
    jump = next(e for e in far if e.previous_flag == 1 and e.flag == -1)
    assert np.allclose(jump.drawn, [(jump.x - 1, c, crossing_x, c), (crossing_x, c, jump.x, c)])
    assert result.stats.intersections[1, -1] == 2


def test_crossing_and_visible_parts_by_hand():
    # On a horizon counts as visible (step 3): up first, then low.
    assert (flag(2.0, 2.0, 0.5), flag(0.5, 2.0, 0.5), flag(1.0, 2.0, 0.5)) == (1, -1, 0)
    assert flag(0.0, 0.0, 0.0) == 1
    assert crossing((0.0, 0.0), (1.0, 2.0), (1.0, 1.0)) == (0.5, 1.0)
    assert crossing((0.0, 5.0), (1.0, 0.0), (-np.inf, 1.0)) == (0.0, 5.0)  # no horizon yet
    assert visible_parts((0.0, 0.0), (1.0, 1.0), 0, 0, (2.0, 2.0), (-1.0, -1.0)) == ([], 0)
    assert visible_parts((0.0, 3.0), (1.0, 4.0), 1, 1, (2.0, 2.0), (-1.0, -1.0)) == (
        [(0.0, 3.0, 1.0, 4.0)],
        0,
    )
    assert visible_parts((0.0, 0.0), (1.0, 4.0), 0, 1, (2.0, 2.0), (-1.0, -1.0)) == (
        [(0.5, 2.0, 1.0, 4.0)],
        1,
    )


def test_monotone_pieces_split_where_x_reverses():
    assert monotone_pieces(np.array([0.0, 1.0, 2.0])) == [(0, 2)]
    assert monotone_pieces(np.array([2.0, 1.0, 1.0, 0.0])) == [(0, 3)]
    assert monotone_pieces(np.array([0.0, 2.0, 2.0, 1.0, 3.0])) == [(0, 2), (2, 3), (3, 4)]


def test_reversing_curves_are_split_and_still_obey_the_horizons():
    # Looking along +x and down, a tall spike comes much nearer than its neighbours: x reverses.
    z = np.zeros((3, 5))
    z[1, 2] = 6.0
    surface = GridSurface(np.arange(5.0), np.arange(3.0), z)
    view = View((-4.0, 1.3, 1.0), (1.0, 0.0, -1.0))
    for family in ("x", "y"):
        result, trace = check_traced_equals_untraced(surface, view, 64, 64, family)
        assert result.stats.pieces > result.stats.curves or family == "y"
        check_invariants(result, trace)


# --- invariants -----------------------------------------------------------------------------


def check_invariants(result, trace):
    columns = [e for e in trace if e.kind == "horizon_column"]
    curves = [e for e in trace if e.kind == "horizon_curve"]
    assert [e.curve for e in curves] == list(result.order)
    first = result.order[0]
    assert all(e.flag == 1 for e in columns if e.curve == first)  # nothing before it
    ups, lows, heights = defaultdict(list), defaultdict(list), defaultdict(list)
    for e in columns:
        assert e.flag == (1 if e.y >= e.up else -1 if e.y <= e.low else 0)
        for x0, _, x1, _ in e.drawn:  # a drawn part never starts or ends at a hidden column
            assert (x0 != e.x - 1 or e.previous_flag != 0) and (x1 != e.x or e.flag != 0)
            assert e.x - 1 <= x0 <= x1 <= e.x
        ups[e.x].append(e.up)
        lows[e.x].append(e.low)
        heights[e.x].append(e.y)
    for x in heights:
        assert ups[x] == sorted(ups[x]) and lows[x] == sorted(lows[x], reverse=True)
        assert result.up[x] == max(heights[x]) and result.low[x] == min(heights[x])
    untouched = np.setdiff1d(np.arange(len(result.up)), list(heights))
    assert np.all(result.up[untouched] == -np.inf) and np.all(result.low[untouched] == np.inf)
    assert result.stats.columns == len(columns)
    assert result.stats.segments == sum(len(e.drawn) for e in columns) == len(result.segments)


def check_traced_equals_untraced(surface, view, width, height, family):
    result, trace = traced(surface, view, width, height, family=family)
    plain = floating_horizon(surface, view, width, height, family=family)
    assert np.array_equal(plain.lines, result.lines)
    assert np.array_equal(plain.segments, result.segments)
    assert np.array_equal(plain.up, result.up) and np.array_equal(plain.low, result.low)
    assert plain.stats == result.stats and plain.order == result.order
    return result, trace


VIEWS = [
    View((6, 8, 3), (-6, -8, -3)),
    View((0.0, -6, 3), (0, 6, -3)),
    View((-7, 0.5, 2), (7, -0.5, -2)),
    View((3, -9, 5), (-3, 9, -5), "parallel"),
]


@pytest.mark.parametrize("view", VIEWS, ids=range(len(VIEWS)))
@pytest.mark.parametrize("family", ["x", "y"])
def test_invariants_on_the_builtin_surfaces(view, family):
    for surface in (gaussian(12), polynomial(10)):
        result, trace = check_traced_equals_untraced(surface, view, 48, 40, family)
        check_invariants(result, trace)
        assert result.lines.sum() > 48


@settings(max_examples=25)
@given(
    nx=st.integers(2, 7),
    ny=st.integers(2, 7),
    seed=st.integers(0, 2**16),
    view=st.sampled_from(VIEWS),
    family=st.sampled_from(["x", "y"]),
    size=st.tuples(st.integers(1, 40), st.integers(1, 40)),
)
def test_invariants_on_random_surfaces(nx, ny, seed, view, family, size):
    surface = GridSurface.random(nx, ny, seed)
    result, trace = check_traced_equals_untraced(surface, view, *size, family)
    check_invariants(result, trace)
    assert result.lines.shape == size[::-1] and result.image.shape == (*size[::-1], 3)


def test_family_y_is_family_x_of_the_mirrored_grid():
    # Swapping world x and y mirrors the screen: screen x -> width - 1 - screen x.
    surface = rogers(15)
    mirrored = GridSurface(surface.y, surface.x, surface.z.T)
    view = View((9, -3, 4), (-6, 6, -4))
    swapped = View((-3, 9, 4), (6, -6, -4))
    by_y = floating_horizon(surface, view, 60, 50, family="y")
    by_x = floating_horizon(mirrored, swapped, 60, 50, family="x")
    assert by_y.order == by_x.order
    assert by_y.up == pytest.approx(by_x.up[::-1]) and by_y.low == pytest.approx(by_x.low[::-1])


def test_image_is_black_lines_on_white():
    result = floating_horizon(gaussian(8), VIEWS[0], 30, 20)
    assert np.array_equal(result.image[result.lines], np.zeros((result.lines.sum(), 3)))
    assert np.array_equal(result.image[~result.lines], np.ones(((~result.lines).sum(), 3)))


def test_trace_round_trips_through_json():
    _, trace = traced(gaussian(5), VIEWS[1], 16, 16)
    assert Trace.from_json(trace.to_json()) == trace


def test_trace_filters_by_kind():
    recorder = Recorder(kinds=["horizon_curve"])
    floating_horizon(gaussian(5), VIEWS[1], 16, 16, trace=recorder)
    assert [e.kind for e in recorder.trace()] == ["horizon_curve"] * 5


# --- errors ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("arguments", "options", "error", "message"),
    [
        (("grid", VIEWS[0], 8, 8), {}, TypeError, "'surface' must be a GridSurface"),
        ((gaussian(3), (6, 8, 3), 8, 8), {}, TypeError, "'view' must be a View"),
        ((gaussian(3), VIEWS[0], 0, 8), {}, ValueError, "'width' and 'height' must be at least 1"),
        ((gaussian(3), VIEWS[0], 8, 2.0), {}, TypeError, "'height' must be an int"),
        ((gaussian(3), VIEWS[0], 8, 8), {"family": "z"}, ValueError, "'family' must be 'x' or 'y'"),
        ((gaussian(3), VIEWS[0], 8, 8), {"trace": 1}, TypeError, "'trace' must be None, True"),
        ((gaussian(3), View((5, 0, 0), (1, 0, 0)), 8, 8), {}, ValueError, "in front of"),
        ((gaussian(3), View((0, 0, 1), (0, 0, 1)), 8, 8), {}, ValueError, "in front of"),
    ],
)
def test_bad_input_is_a_clear_error(arguments, options, error, message):
    with pytest.raises(error, match=message):
        floating_horizon(*arguments, **options)

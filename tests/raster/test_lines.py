"""Midpoint lines: golden pixels in every octant, nearest-pixel and symmetry invariants, trace."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Recorder, Trace, midpoint_line
from scanviz.conventions import COORD_LIMIT
from scanviz.raster.lines import octant, paint_lines


def pixels(*endpoints, trace=None) -> list[tuple[int, int]]:
    xs, ys = midpoint_line(*endpoints, trace=trace)
    assert xs.dtype == ys.dtype == np.int64
    return list(zip(xs.tolist(), ys.tolist(), strict=True))


# Worked by hand with the slides' loop in the first octant, then mapped by symmetry.
# (0,0)-(5,2): d = 1, -3, 3, -1, 5, 1 -> E, NE, E, NE, E: y = 0, 0, 1, 1, 2, 2 (no ties).
NO_TIES = {
    0: ((0, 0, 5, 2), [(0, 0), (1, 0), (2, 1), (3, 1), (4, 2), (5, 2)]),
    1: ((0, 0, 2, 5), [(0, 0), (0, 1), (1, 2), (1, 3), (2, 4), (2, 5)]),
    2: ((0, 0, -2, 5), [(0, 0), (0, 1), (-1, 2), (-1, 3), (-2, 4), (-2, 5)]),
    3: ((0, 0, -5, 2), [(0, 0), (-1, 0), (-2, 1), (-3, 1), (-4, 2), (-5, 2)]),
    4: ((0, 0, -5, -2), [(0, 0), (-1, 0), (-2, -1), (-3, -1), (-4, -2), (-5, -2)]),
    5: ((0, 0, -2, -5), [(0, 0), (0, -1), (-1, -2), (-1, -3), (-2, -4), (-2, -5)]),
    6: ((0, 0, 2, -5), [(0, 0), (0, -1), (1, -2), (1, -3), (2, -4), (2, -5)]),
    7: ((0, 0, 5, -2), [(0, 0), (1, 0), (2, -1), (3, -1), (4, -2), (5, -2)]),
}
# (0,0)-(4,2): d = 0, -4, 0, -4, 0. The line passes through the midpoints at x = 1 and 3; the
# slides' tie (d == 0 -> E) keeps the smaller y, and every octant keeps the smaller minor value.
TIES = {
    0: ((0, 0, 4, 2), [(0, 0), (1, 0), (2, 1), (3, 1), (4, 2)]),
    1: ((0, 0, 2, 4), [(0, 0), (0, 1), (1, 2), (1, 3), (2, 4)]),
    2: ((0, 0, -2, 4), [(0, 0), (-1, 1), (-1, 2), (-2, 3), (-2, 4)]),
    3: ((0, 0, -4, 2), [(0, 0), (-1, 0), (-2, 1), (-3, 1), (-4, 2)]),
    4: ((0, 0, -4, -2), [(0, 0), (-1, -1), (-2, -1), (-3, -2), (-4, -2)]),
    5: ((0, 0, -2, -4), [(0, 0), (-1, -1), (-1, -2), (-2, -3), (-2, -4)]),
    6: ((0, 0, 2, -4), [(0, 0), (0, -1), (1, -2), (1, -3), (2, -4)]),
    7: ((0, 0, 4, -2), [(0, 0), (1, -1), (2, -1), (3, -2), (4, -2)]),
}


@pytest.mark.parametrize("golden", [NO_TIES, TIES], ids=["no_ties", "ties"])
@pytest.mark.parametrize("octant_index", range(8))
def test_golden_pixels_in_every_octant(golden, octant_index):
    endpoints, expected = golden[octant_index]
    assert octant(endpoints[2] - endpoints[0], endpoints[3] - endpoints[1]) == octant_index
    assert pixels(*endpoints) == expected
    x0, y0, x1, y1 = endpoints
    moved = pixels(x0 + 7, y0 - 3, x1 + 7, y1 - 3)
    assert moved == [(x + 7, y - 3) for x, y in expected]  # translation invariant


def test_slide_trace_in_the_first_octant():
    recorder = Recorder()
    assert pixels(0, 0, 5, 2, trace=recorder) == NO_TIES[0][1]
    setup, *steps = recorder.trace()
    assert (setup.octant, setup.major, setup.step_x, setup.step_y) == (0, "x", 1, 1)
    # doubled: d = 2 f(x0 + 1, y0 + 1/2) = 2 (-2 + 5/2) = 1; E adds 2 (y0 - y1), NE 2 (dx - dy)
    assert (setup.d_start, setup.d_axial, setup.d_diagonal, setup.tie_steps) == (1, -4, 6, False)
    assert [(s.x, s.y, s.d, s.choice) for s in steps] == [
        (0, 0, 1, "axial"),
        (1, 0, -3, "diagonal"),
        (2, 1, 3, "axial"),
        (3, 1, -1, "diagonal"),
        (4, 2, 5, "axial"),
        (5, 2, 1, "last"),
    ]


def test_tie_takes_the_diagonal_only_when_the_minor_axis_steps_down():
    recorder = Recorder(kinds=["line_step"])
    pixels(4, -2, 0, 0, trace=recorder)  # octant 3 walked from the other end
    assert [(s.d, s.choice) for s in recorder.trace()][:2] == [(0, "axial"), (-4, "diagonal")]
    recorder = Recorder(kinds=["line_step"])
    pixels(0, 0, 4, -2, trace=recorder)
    assert [(s.d, s.choice) for s in recorder.trace()][:2] == [(0, "diagonal"), (4, "axial")]


@pytest.mark.parametrize(
    ("endpoints", "expected"),
    [
        ((3, 3, 3, 3), [(3, 3)]),
        ((0, 0, 3, 0), [(0, 0), (1, 0), (2, 0), (3, 0)]),
        ((0, 0, -3, 0), [(0, 0), (-1, 0), (-2, 0), (-3, 0)]),
        ((0, 0, 0, 3), [(0, 0), (0, 1), (0, 2), (0, 3)]),
        ((0, 0, 0, -2), [(0, 0), (0, -1), (0, -2)]),
        ((0, 0, 3, 3), [(0, 0), (1, 1), (2, 2), (3, 3)]),
        ((0, 0, -3, 3), [(0, 0), (-1, 1), (-2, 2), (-3, 3)]),
        ((2, 1, -1, -2), [(2, 1), (1, 0), (0, -1), (-1, -2)]),
    ],
)
def test_points_axes_and_diagonals(endpoints, expected):
    assert pixels(*endpoints) == expected


def test_octant_boundaries():
    assert [octant(*d) for d in [(1, 0), (1, 1), (0, 1), (-1, 1)]] == [0, 1, 2, 3]
    assert [octant(*d) for d in [(-1, 0), (-1, -1), (0, -1), (1, -1)]] == [4, 5, 6, 7]
    assert octant(0, 0) == 0


coordinates = st.one_of(st.integers(-40, 40), st.integers(-COORD_LIMIT, COORD_LIMIT))


@st.composite
def lines(draw):
    """Endpoints anywhere in the coordinate range, at most 60 pixels apart per axis."""
    x0, y0 = draw(coordinates), draw(coordinates)
    x1 = min(max(x0 + draw(st.integers(-60, 60)), -COORD_LIMIT), COORD_LIMIT)
    y1 = min(max(y0 + draw(st.integers(-60, 60)), -COORD_LIMIT), COORD_LIMIT)
    return x0, y0, x1, y1


@settings(max_examples=10 * settings.default.max_examples)
@given(lines())
def test_one_nearest_pixel_per_major_step_connected_and_reversible(endpoints):
    x0, y0, x1, y1 = endpoints
    drawn = pixels(*endpoints)
    assert drawn[0] == (x0, y0) and drawn[-1] == (x1, y1)
    steep = abs(y1 - y0) > abs(x1 - x0)
    major = [p[1] if steep else p[0] for p in drawn]
    step = 1 if (y1 >= y0 if steep else x1 >= x0) else -1
    start, end = (y0, y1) if steep else (x0, x1)
    assert major == list(range(start, end + step, step))  # one pixel per major-axis step
    for (xa, ya), (xb, yb) in zip(drawn, drawn[1:], strict=False):
        assert max(abs(xb - xa), abs(yb - ya)) == 1  # 8-connected, no repeats
    for x, y in drawn:  # nearest along the minor axis, ties to the smaller coordinate
        if steep:
            exact, minor = x0 + Fraction(x1 - x0, y1 - y0) * (y - y0), x
        else:
            exact = y0 + (Fraction(y1 - y0, x1 - x0) * (x - x0) if x1 != x0 else 0)
            minor = y
        assert abs(minor - exact) <= Fraction(1, 2)
        assert minor - exact != Fraction(1, 2)
    assert pixels(x1, y1, x0, y0) == drawn[::-1]  # reversing gives the same pixels


@settings(max_examples=2 * settings.default.max_examples)
@given(lines())
def test_trace_replays_the_pixels_and_round_trips_through_json(endpoints):
    recorder = Recorder()
    drawn = pixels(*endpoints, trace=recorder)
    trace = recorder.trace()
    setup, *steps = trace
    assert setup.kind == "line_setup" and (setup.x0, setup.y0, setup.x1, setup.y1) == endpoints
    assert [(s.x, s.y) for s in steps] == drawn
    assert [s.choice for s in steps][-1] == "last"
    for here, after in zip(steps, steps[1:], strict=False):  # d follows the increments
        diagonal = here.choice == "diagonal"
        assert after.d == here.d + (setup.d_diagonal if diagonal else setup.d_axial)
        assert diagonal == (here.d < 0 or (here.d == 0 and setup.tie_steps))
    assert Trace.from_json(trace.to_json()) == trace


def test_trace_filters_by_row():
    recorder = Recorder(kinds=["line_step"], rows=(1, 2))
    pixels(0, 0, 5, 2, trace=recorder)
    assert [(s.x, s.y) for s in recorder.trace()] == [(2, 1), (3, 1)]


def test_numpy_integers_and_the_coordinate_limit_are_accepted():
    assert pixels(np.int32(1), np.int64(2), np.int16(3), 2) == [(1, 2), (2, 2), (3, 2)]
    assert len(pixels(-COORD_LIMIT, 0, -COORD_LIMIT + 3, 0)) == 4


@pytest.mark.parametrize(
    ("endpoints", "error", "message"),
    [
        ((0.5, 0, 1, 1), TypeError, "'x0' must be an int; got 0.5"),
        ((0, True, 1, 1), TypeError, "'y0' must be an int; got True"),
        ((0, 0, "1", 1), TypeError, "'x1' must be an int"),
        ((0, 0, 1, COORD_LIMIT + 1), ValueError, "'y1' must be within"),
        ((-COORD_LIMIT - 1, 0, 1, 1), ValueError, "'x0' must be within"),
    ],
)
def test_bad_endpoints_are_named(endpoints, error, message):
    with pytest.raises(error, match=message):
        midpoint_line(*endpoints)


def test_trace_must_be_a_tracer():
    with pytest.raises(TypeError, match="'trace' must be None or a Tracer"):
        midpoint_line(0, 0, 1, 1, trace=True)


@pytest.mark.parametrize(
    ("value", "error", "message"),
    [
        (
            10**400,
            ValueError,
            r"'x1' must be within \+-2\*\*20 = 1048576; got <an int of 1329 bits>",
        ),
        (2**20 + 1, ValueError, r"'x1' must be within"),
        (float("nan"), TypeError, r"'x1' must be an int; got nan"),
        (True, TypeError, r"'x1' must be an int; got True"),
        ("4", TypeError, r"'x1' must be an int; got '4'"),
        (4.0, TypeError, r"'x1' must be an int; got 4.0"),
    ],
)
def test_issue8_d9_endpoints_must_be_ints_within_the_limit(value, error, message):
    with pytest.raises(error, match=message):
        midpoint_line(0, 0, value, 0)


# --- the replaceable step midpoint_step -----------------------------------------------------


def doubled_f(dx: int, dy: int, x: Fraction, y: Fraction) -> Fraction:
    """2 f(x, y) of the slides for the line from (0, 0) to (dx, dy)."""
    return 2 * (-dy * x + dx * y)


@settings(derandomize=True, max_examples=60, deadline=None)
@given(st.integers(1, 40).flatmap(lambda dx: st.tuples(st.just(dx), st.integers(0, dx))))
def test_midpoint_step_is_the_slides_update_of_2f_at_the_midpoint(extents):
    # Exact oracle: d is 2 f at the midpoint (x + 1, y + 1/2) of each pixel of the
    # first-octant line; the step picks NE iff d < 0 and returns 2 f at the next midpoint.
    from scanviz.raster.lines import midpoint_step

    dx, dy = extents
    x, y = 0, 0
    d = doubled_f(dx, dy, Fraction(1), Fraction(1, 2))
    for _ in range(dx):
        diagonal, d_next = midpoint_step(int(d), dx, dy)
        assert diagonal == (d < 0)
        x, y = x + 1, y + diagonal
        assert d_next == doubled_f(dx, dy, Fraction(x + 1), y + Fraction(1, 2))
        d = d_next


def test_midpoint_line_takes_its_decisions_from_the_step_table():
    from scanviz import steps

    calls = []

    def always_diagonal(d, dx, dy):
        calls.append((d, dx, dy))
        return True, d

    with steps.using(midpoint_step=always_diagonal):
        assert pixels(0, 0, 6, -2) == [(k, -k) for k in range(7)]
        assert pixels(3, 1, 1, 5) == [(3, 1), (2, 2), (1, 3), (0, 4), (-1, 5)]
    assert calls[:2] == [(2, 6, 2), (2, 6, 2)]  # d = 6 - 2 * 2, in the first-octant frame
    assert len(calls) == 6 + 4  # one decision per pixel but the last


@settings(max_examples=50)
@given(
    st.lists(st.tuples(*[st.integers(-12, 40)] * 4), min_size=0, max_size=12),
    st.integers(0, 30),
    st.integers(0, 30),
)
def test_paint_lines_draws_the_pixels_of_midpoint_line(ends, width, height):
    want = np.zeros((height, width), bool)
    for x0, y0, x1, y1 in ends:
        xs, ys = midpoint_line(x0, y0, x1, y1)
        inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
        want[ys[inside], xs[inside]] = True
    np.testing.assert_array_equal(
        paint_lines(np.array(ends, np.int64).reshape(-1, 4), width, height), want
    )


def test_paint_lines_rejects_bad_ends_and_sizes():
    with pytest.raises(ValueError, match="'ends' must be a \\(K, 4\\) array of ints"):
        paint_lines([[0.5, 0, 1, 1]], 4, 4)
    with pytest.raises(ValueError, match="within"):
        paint_lines([[0, 0, COORD_LIMIT + 1, 0]], 4, 4)
    with pytest.raises(ValueError, match="'height' must be an int >= 0"):
        paint_lines([[0, 0, 1, 1]], 4, -1)

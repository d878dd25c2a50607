"""The colour ring of Wang (1989) §3.4 (spec §2.9): ring, phase -> entry, triangle rule, marker."""

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from scanviz.shading.colour_ring import (
    MAX_RING_STEPS,
    colour_ring,
    marked_triangles,
    replace_entry,
    ring_index,
    triangle_ring_index,
)

PI = math.pi
GREEN, RED, BLUE = (0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


# --- the ring ---------------------------------------------------------------------------------


def test_ring_of_two_steps_is_the_six_primaries_and_midpoints():
    expected = [GREEN, (0.5, 0.5, 0), RED, (0.5, 0, 0.5), BLUE, (0, 0.5, 0.5)]
    np.testing.assert_array_equal(colour_ring(2), expected)


def test_ring_of_one_step_is_the_three_primaries():
    np.testing.assert_array_equal(colour_ring(1), [GREEN, RED, BLUE])


@pytest.mark.parametrize("steps, size", [(32, 96), (64, 192), (1, 3), (MAX_RING_STEPS, 12288)])
def test_ring_sizes(steps, size):
    ring = colour_ring(steps)
    assert ring.shape == (size, 3) and ring.dtype == np.float64


def test_default_ring_is_the_192_colours_of_fig_3_8():
    np.testing.assert_array_equal(colour_ring(), colour_ring(64))


@pytest.mark.parametrize("steps", [1, 2, 3, 7, 32, 64])
def test_ring_is_closed_and_continuous(steps):
    ring = colour_ring(steps)
    closed = np.vstack([ring, ring[:1]])  # entry 3S wraps to entry 0
    step = np.abs(np.diff(closed, axis=0))
    assert step.max() <= 1 / steps + 1e-15
    # Each step moves exactly two channels by 1/S: one primary fades, the next grows.
    np.testing.assert_allclose(
        np.sort(step, axis=1), np.tile([0, 1 / steps, 1 / steps], (len(ring), 1)), atol=1e-15
    )


@pytest.mark.parametrize("steps", [1, 4, 64])
def test_two_primaries_mixed_except_at_segment_starts(steps):
    ring = colour_ring(steps)
    lit = (ring > 0).sum(axis=1)
    starts = np.arange(len(ring)) % steps == 0
    assert (lit[starts] == 1).all() and (lit[~starts] == 2).all()
    np.testing.assert_array_equal(ring[[0, steps, 2 * steps]], [GREEN, RED, BLUE])
    np.testing.assert_allclose(ring.sum(axis=1), 1.0, atol=1e-15)  # binary colours
    assert ring.min() >= 0 and ring.max() <= 1


def test_segments_blend_green_red_then_red_blue_then_blue_green():
    ring = colour_ring(64)
    np.testing.assert_array_equal(
        ring[[32, 96, 160]], [(0.5, 0.5, 0), (0.5, 0, 0.5), (0, 0.5, 0.5)]
    )
    assert ring[1].tolist() == [1 / 64, 63 / 64, 0.0]  # just past 0°: a touch of red on green
    assert ring[191].tolist() == [0.0, 63 / 64, 1 / 64]  # just before 360°: almost green again


def test_ring_scales_to_bytes():
    levels = np.rint(255 * colour_ring(64)).astype(np.uint8)
    assert levels[0].tolist() == [0, 255, 0] and levels[32].tolist() == [128, 128, 0]


@pytest.mark.parametrize("steps", [0, -1, MAX_RING_STEPS + 1])
def test_bad_steps_value(steps):
    with pytest.raises(ValueError, match="'steps' must be in 1..4096"):
        colour_ring(steps)


@pytest.mark.parametrize("steps", [2.0, True, "3", None])
def test_bad_steps_type(steps):
    with pytest.raises(TypeError, match="'steps' must be an int"):
        colour_ring(steps)


# --- phase -> entry ---------------------------------------------------------------------------


def test_ring_index_hand_values():
    # int(p 191 / 2pi) with p moved into [0, 2pi): pi/2 -> 47.75, pi -> 95.5, 3pi/2 -> 143.25.
    phases = [0.0, 1e-9, PI / 2, PI, -PI, -PI / 2, -1e-9]
    assert ring_index(phases, 192).tolist() == [0, 0, 47, 95, 95, 143, 190]


def test_ring_index_reaches_the_last_entry_only_at_two_pi():
    assert ring_index(-1e-300, 192) == 191  # -1e-300 + 2 pi rounds to 2 pi
    dense = np.linspace(-PI, PI, 100_001)
    moved = np.where(dense < 0, dense + 2 * PI, dense)
    assert ring_index(dense[moved < 2 * PI], 192).max() == 190


def test_ring_index_of_the_96_colour_ring_uses_95():
    assert ring_index([PI, -PI / 2], 96).tolist() == [47, 71]  # 47.5, 71.25


def test_ring_index_keeps_the_shape():
    assert ring_index(np.zeros((2, 3)), 192).shape == (2, 3)
    assert ring_index(0.5, 1).tolist() == 0


@settings(max_examples=200)
@given(st.floats(-PI, PI), st.integers(2, 400))
def test_ring_index_lies_in_its_phase_interval(phase, size):
    moved = phase + 2 * PI if phase < 0 else phase
    position = moved * (size - 1) / (2 * PI)
    assume(abs(position - round(position)) > 1e-9)  # away from the breakpoints
    entry = int(ring_index(phase, size))
    assert 2 * PI * entry / (size - 1) <= moved < 2 * PI * (entry + 1) / (size - 1)


@pytest.mark.parametrize("phase", [3.2, -3.2, math.nan, math.inf])
def test_ring_index_refuses_phases_outside_minus_pi_pi(phase):
    with pytest.raises(ValueError, match=r"'phase' must be phases in \[-pi, pi\]"):
        ring_index([0.0, phase], 192)


def test_ring_index_bad_size():
    with pytest.raises(ValueError, match="'size' must be >= 1"):
        ring_index(0.0, 0)
    with pytest.raises(TypeError, match="'size' must be an int"):
        ring_index(0.0, 192.0)
    with pytest.raises(TypeError, match="'phase' must be an array of numbers"):
        ring_index("north", 192)


# --- the triangle rule ------------------------------------------------------------------------


@pytest.mark.parametrize(
    "phases, entry",
    [
        # Straddling ±pi: -3pi/4 -> 5pi/4, mean pi, 95.5 (the naive mean pi/3 would give 31).
        ((3 * PI / 4, -3 * PI / 4, PI), 95),
        # pi - 0.1, pi + 0.1, pi - 0.2: mean pi - 0.2/3, 95.5 - 2.026 = 93.47.
        ((PI - 0.1, -PI + 0.1, PI - 0.2), 93),
        # No straddle: mean 0.2/3 = 0.0667, 2.03.
        ((-0.1, 0.1, 0.2), 2),
        # All negative: mean -1.5 -> 2pi - 1.5, 191 - 45.60 = 145.40.
        ((-1.0, -1.5, -2.0), 145),
        # Sequential: -2 -> 2pi - 2; then -0.5 is compared with 2pi - 2 and moves too:
        # mean (4pi - 0.5)/3, 127.33 - 5.07 = 122.27 (comparing with the original -2: 58).
        ((-2.0, -0.5, 2.0), 122),
        # The same vertices in another order: -0.5 stays, -2 moves: mean 1.928, 58.6.
        ((2.0, -0.5, -2.0), 58),
        # A difference of exactly pi does not count: mean 0.
        ((-PI / 2, PI / 2, 0.0), 0),
        # -pi moves to pi when another vertex is above 0: mean (pi + 0.6)/3 = 1.2472, 37.91.
        ((-PI, 0.3, 0.3), 37),
    ],
)
def test_triangle_rule_hand_cases(phases, entry):
    assert triangle_ring_index([phases], 192).tolist() == [entry]


def test_triangle_rule_on_the_96_colour_ring():
    assert triangle_ring_index([(3 * PI / 4, -3 * PI / 4, PI)], 96).tolist() == [47]  # 47.5


def test_triangle_rule_is_vectorized_over_triangles():
    phases = [(3 * PI / 4, -3 * PI / 4, PI), (-0.1, 0.1, 0.2), (-1.0, -1.5, -2.0)]
    assert triangle_ring_index(phases, 192).tolist() == [95, 2, 145]
    assert triangle_ring_index(np.zeros((0, 3)), 192).shape == (0,)


def _unwrapped_mean(phases):
    """Oracle: the mean of the phases unwrapped around the first (valid for a spread < pi)."""
    p0 = phases[0]
    unwrapped = [p0 + math.remainder(p - p0, 2 * PI) for p in phases]
    return sum(unwrapped) / 3 % (2 * PI)


@settings(max_examples=200)
@given(
    st.floats(-PI, PI),
    st.lists(st.floats(-1.4, 1.4), min_size=2, max_size=2),
    st.sampled_from([96, 192]),
)
def test_triangle_rule_is_the_mean_of_nearby_phases_on_the_circle(centre, offsets, size):
    phases = [centre, *(math.remainder(centre + d, 2 * PI) for d in offsets)]
    assume(all(abs(p) < PI for p in phases))
    mean = _unwrapped_mean(phases)
    position = mean * (size - 1) / (2 * PI)
    assume(abs(position - round(position)) > 1e-9 and mean < 2 * PI - 1e-9)
    assert triangle_ring_index([phases], size).tolist() == [int(position)]


def test_triangle_rule_leaves_its_input_alone():
    phases = np.array([[3 * PI / 4, -3 * PI / 4, PI]])
    triangle_ring_index(phases, 192)
    assert phases[0, 1] == -3 * PI / 4


@pytest.mark.parametrize("shape", [(3,), (2, 2), (1, 3, 1)])
def test_triangle_rule_bad_shape(shape):
    with pytest.raises(ValueError, match=r"'phases' must be a \(T, 3\) array"):
        triangle_ring_index(np.zeros(shape), 192)


def test_triangle_rule_bad_phase():
    with pytest.raises(ValueError, match=r"phases\[1, 2\] is nan"):
        triangle_ring_index([(0, 0, 0), (0, 0, math.nan)], 192)


# --- the marker -------------------------------------------------------------------------------


def test_replace_entry_swaps_one_entry_for_white():
    ring = colour_ring(64)
    before = ring.copy()
    marked = replace_entry(ring, 100)
    assert marked[100].tolist() == [1.0, 1.0, 1.0]
    changed = np.flatnonzero((marked != ring).any(axis=1))
    assert changed.tolist() == [100]
    np.testing.assert_array_equal(ring, before)  # a new ring; the old one is unchanged


def test_replace_entry_with_another_marker():
    marked = replace_entry(colour_ring(2), 5, marker=(0, 0, 0))
    assert marked[5].tolist() == [0.0, 0.0, 0.0] and marked[4].tolist() == list(BLUE)


@pytest.mark.parametrize("entry", [6, -1])
def test_replace_entry_out_of_range(entry):
    with pytest.raises(ValueError, match=r"'entry' must be >= 0 and < 6"):
        replace_entry(colour_ring(2), entry)


@pytest.mark.parametrize(
    "ring, entry, marker, error, message",
    [
        (colour_ring(2), True, (1, 1, 1), TypeError, "'entry' must be an int"),
        (colour_ring(2), 1.0, (1, 1, 1), TypeError, "'entry' must be an int"),
        (colour_ring(2), 1, (1, 1), ValueError, "'marker' must be 3 numbers in"),
        (colour_ring(2), 1, (1, 1, 2), ValueError, "'marker' must be 3 numbers in"),
        (colour_ring(2), 1, "red", ValueError, "'marker' must be 3 numbers in"),
        (np.zeros((4, 2)), 1, (1, 1, 1), ValueError, r"'ring' must be an \(N, 3\) array"),
        (np.zeros((0, 3)), 0, (1, 1, 1), ValueError, r"'ring' must be an \(N, 3\) array"),
        (np.full((2, 3), 1.5), 0, (1, 1, 1), ValueError, r"'ring' colours must be in \[0, 1\]"),
        ([["a", "b", "c"]], 0, (1, 1, 1), TypeError, "'ring' must be an"),
    ],
)
def test_replace_entry_bad_input(ring, entry, marker, error, message):
    with pytest.raises(error, match=message):
        replace_entry(ring, entry, marker)


def test_marked_triangles():
    entries = triangle_ring_index([(0.1, 0.1, 0.1), (PI, PI, PI), (0.12, 0.1, 0.08)], 192)
    assert marked_triangles(entries, 3).tolist() == [0, 2]  # 0.1 * 191 / 2pi = 3.04
    assert marked_triangles(entries, 95).tolist() == [1]
    assert marked_triangles(entries, 7).tolist() == []


def test_marked_triangles_bad_input():
    with pytest.raises(ValueError, match="'entries' must be a 1-D array of ints"):
        marked_triangles([[1, 2]], 1)
    with pytest.raises(ValueError, match="'entries' must be a 1-D array of ints"):
        marked_triangles([1.5], 1)
    with pytest.raises(ValueError, match="'entry' must be >= 0"):
        marked_triangles([1, 2], -1)

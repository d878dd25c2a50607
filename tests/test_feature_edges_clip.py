"""Feature edges clipped before they are walked: the same pixels, `along` and depths as the full walk.

`midpoint_line_window` against `midpoint_line` (the reference walk, then
clipped) in every octant, on lines that miss, graze or cross the raster; at
+-2**20 against the compiled full walk `paint_lines`; and `feature_edge_runs`
against its reference path (a replaced step table walks every whole line).
"""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.conventions import COORD_LIMIT
from scanviz.pipeline.feature_lines import feature_edge_runs
from scanviz.raster.lines import midpoint_line, midpoint_line_window, midpoint_step, paint_lines
from scanviz.scene.builtin import builtin_scene

MANY = settings(max_examples=5 * settings.default.max_examples)


def walked_then_clipped(x0, y0, x1, y1, width, height):
    xs, ys = midpoint_line(x0, y0, x1, y1)
    inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
    return xs[inside], ys[inside], np.flatnonzero(inside)


def assert_same_window(line, width, height):
    window = midpoint_line_window(*line, width, height)
    for got, expected in zip(window, walked_then_clipped(*line, width, height), strict=True):
        assert got.dtype == np.int64
        np.testing.assert_array_equal(got, expected)


@MANY
@given(
    line=st.lists(st.integers(-24, 40), min_size=4, max_size=4),
    width=st.integers(0, 12),
    height=st.integers(0, 12),
)
def test_window_equals_the_full_walk_clipped(line, width, height):
    assert_same_window(line, width, height)


@pytest.mark.parametrize(
    "line",
    [
        (3, 3, 3, 3),  # one pixel, on the raster
        (-1, 3, -1, 3),  # one pixel, off it
        (-5, 2, 20, 2),  # horizontal through
        (4, -9, 4, 30),  # vertical through
        (20, 6, -5, 6),  # horizontal, right to left
        (4, 30, 4, -9),  # vertical, downwards
        (-3, 10, 10, -3),  # crosses the corner (0, 7) to (7, 0)
        (-1, 9, 9, -1),  # x + y = 8: (1, 7) to (7, 1)
        (8, 0, 12, 4),  # starts just right of the raster
        (-4, -2, 12, 6),  # a tie at each midpoint: 2:1 slope
        (12, 6, -4, -2),  # the same line reversed
        (-2, 12, 2, -12),  # steep, the minor axis pointing right
        (2, -12, -2, 12),
    ],
)
def test_window_explicit_cases(line):
    for width, height in [(8, 8), (1, 1), (0, 5), (5, 0)]:
        assert_same_window(line, width, height)


def assert_same_as_paint_lines(line, width, height):
    """At +-2**20 the reference walk is too slow: check against the compiled full walk."""
    xs, ys, index = midpoint_line_window(*line, width, height)
    painted = paint_lines([line], width, height)
    assert len(xs) == painted.sum()
    assert painted[ys, xs].all()
    x0, y0, x1, y1 = line
    steep = abs(y1 - y0) > abs(x1 - x0)
    major, start, end = (ys, y0, y1) if steep else (xs, x0, x1)
    np.testing.assert_array_equal(major, start + np.sign(end - start) * index)
    assert (np.diff(index) == 1).all()  # consecutive steps, in drawing order


LIMIT = COORD_LIMIT


@settings(max_examples=settings.default.max_examples)
@given(
    far=st.tuples(st.sampled_from([-LIMIT, LIMIT, 0]), st.integers(-LIMIT, LIMIT)),
    near=st.tuples(st.integers(-6, 14), st.integers(-6, 14)),
    flip=st.booleans(),
    reverse=st.booleans(),
)
def test_window_of_lines_reaching_the_coordinate_limit(far, near, flip, reverse):
    far = far[::-1] if flip else far
    line = (*near, *far) if reverse else (*far, *near)
    assert_same_as_paint_lines(line, 8, 8)


@pytest.mark.parametrize(
    "line",
    [
        (-LIMIT, -LIMIT, LIMIT, LIMIT),  # the diagonal through the raster
        (-LIMIT, 3, LIMIT, 4),  # almost horizontal through it
        (LIMIT, -LIMIT, -LIMIT, LIMIT),  # the other diagonal: misses 8 x 8 but for no pixel
        (-LIMIT, LIMIT, -LIMIT + 1, -LIMIT),  # far off the raster, no pixel
        (5, -LIMIT, 6, LIMIT),  # almost vertical
    ],
)
def test_window_of_the_longest_lines(line):
    assert_same_as_paint_lines(line, 8, 8)
    assert_same_as_paint_lines(line, 3, 11)


def test_window_against_the_full_walk_of_a_long_line():
    line = (-40000, -15001, 30001, 9000)  # 70,001 pixels, 11 or so on the raster
    assert_same_window(line, 16, 9)
    assert_same_window(line[2:] + line[:2], 16, 9)


def test_window_rejects_bad_arguments():
    with pytest.raises(ValueError, match="'x1' must be within"):
        midpoint_line_window(0, 0, 2**21, 0, 4, 4)
    with pytest.raises(TypeError, match="'y0' must be an int"):
        midpoint_line_window(0, 0.5, 1, 0, 4, 4)
    with pytest.raises(ValueError, match="'height' must be an int >= 0"):
        midpoint_line_window(0, 0, 1, 0, 4, -1)


# -- feature_edge_runs: the clipped walk against the reference (the whole line walked) ------


def zoomed_terrain(factor: float, n: int = 24):
    """builtin:terrain with the eye moved `factor` of the way from look_at: edges run far off screen."""
    scene = builtin_scene("terrain", n=n)
    camera = scene.camera
    eye = np.array(camera.look_at) + factor * (np.array(camera.eye) - np.array(camera.look_at))
    return dataclasses.replace(scene, camera=dataclasses.replace(camera, eye=tuple(eye)))


def assert_runs_equal(scene, width, height):
    from scanviz import render

    depth = render(scene, width, height).depth
    fast = list(feature_edge_runs(scene, depth, width, height))
    with steps.using(midpoint_step=midpoint_step):  # a replaced table: the reference walk
        reference = list(feature_edge_runs(scene, depth, width, height))
    assert len(fast) == len(reference)
    for got, expected in zip(fast, reference, strict=True):
        for field in ("ends", "xs", "ys", "along", "shown"):
            a, b = getattr(got, field), getattr(expected, field)
            assert a.dtype == b.dtype and a.shape == b.shape
            np.testing.assert_array_equal(a, b)  # bit for bit, `along` included
    return fast


@pytest.mark.parametrize("factor", [1.0, 0.3, 0.2225])
def test_feature_edge_runs_equal_the_full_walk(factor):
    for width, height in [(8, 8), (40, 24)]:
        runs = assert_runs_equal(zoomed_terrain(factor), width, height)
        assert runs and any(len(run.xs) for run in runs)


def test_along_is_linspace_over_the_whole_line():
    from scanviz import render

    scene = zoomed_terrain(0.2225)
    depth = render(scene, 8, 8).depth
    for run in feature_edge_runs(scene, depth, 8, 8):
        if not len(run.xs):
            continue
        (x0, y0), (x1, y1) = np.floor(run.ends).astype(int)
        xs, ys, index = midpoint_line_window(x0, y0, x1, y1, 8, 8)
        full = np.linspace(0.0, 1.0, max(abs(x1 - x0), abs(y1 - y0)) + 1)
        np.testing.assert_array_equal(run.along, full[index])

"""The View: validation, look-at axes and the fit to a y-up raster (spec §1.6.1 [EXT])."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.surfaces.view import View
from scanviz.transform.viewing import vertex_tables

SQUARE = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"point": (0, 0, np.nan)}, ValueError, "'point' must be finite"),
        ({"point": (0, 0, 1e100)}, ValueError, "'point' components must be within"),
        ({"point": (0, 0)}, ValueError, "'point' must have 3 components"),
        ({"direction": (0, 0, 0)}, ValueError, "'direction' must be nonzero"),
        ({"direction": (0, np.inf, 0)}, ValueError, "'direction' must be finite"),
        ({"direction": "abc"}, TypeError, "'direction' must be 3 numbers"),
        ({"projection": "orthographic"}, ValueError, "'projection' must be 'perspective' or"),
    ],
)
def test_bad_views_are_named(kwargs, error, message):
    arguments = {"point": (0, 0, 5), "direction": (0, 0, -1)} | kwargs
    with pytest.raises(error, match=message):
        View(**arguments)


def test_view_is_frozen_and_stores_floats():
    view = View((1, 2, 3), (0, 1, 0))
    assert view.point == (1.0, 2.0, 3.0) and view.projection == "perspective"
    with pytest.raises(dataclasses.FrozenInstanceError):
        view.point = (0, 0, 0)


@settings(max_examples=50)
@given(st.tuples(*[st.floats(-1e3, 1e3)] * 3).filter(lambda d: max(map(abs, d)) > 1e-6))
def test_axes_are_orthonormal_with_up_towards_world_z(direction):
    right, up, forward = View((0, 0, 0), direction).axes()
    axes = np.array([right, up, forward])
    np.testing.assert_allclose(axes @ axes.T, np.eye(3), atol=1e-12)
    np.testing.assert_allclose(forward, np.array(direction) / np.linalg.norm(direction))
    assert np.linalg.det(axes) == pytest.approx(-1.0)  # right, up, *forward*: into the screen
    if direction[:2] != (0.0, 0.0):
        assert right[2] == pytest.approx(0.0, abs=1e-12)  # the horizon stays level
        assert up[2] >= 0.0


def test_vertical_views_use_world_y_as_up():
    right, up, _ = View((0, 0, 5), (0, 0, 1)).axes()
    np.testing.assert_array_equal(up, [0, 1, 0])
    np.testing.assert_array_equal(right, [-1, 0, 0])  # looking up: +x is on the left


def test_perspective_projection_by_hand():
    # Eye at y = -4 looking +y: right = +x, up = +z, depth = y + 4.
    plane, depth = View((0, -4, 0), (0, 2, 0)).project([[2, 4, -1], [0, 0, 3]])
    np.testing.assert_allclose(plane, [[0.25, -0.125], [0.0, 0.75]])
    np.testing.assert_allclose(depth, [8, 4])


def test_parallel_projection_ignores_distance_and_allows_points_behind():
    plane, depth = View((0, 0, 0), (0, 1, 0), "parallel").project([[2, 5, 1], [2, -5, 1]])
    np.testing.assert_allclose(plane, [[2, 1], [2, 1]])
    np.testing.assert_allclose(depth, [5, -5])


@pytest.mark.parametrize("y", [-4.0, -6.0])
def test_points_at_or_behind_a_perspective_viewpoint_are_an_error(y):
    with pytest.raises(ValueError, match=r"in front of the viewpoint .*'points' row 1"):
        View((0, -4, 0), (0, 1, 0)).project([[0, 0, 0], [1, y, 0]])


def test_fit_points_behind_are_named_fit():
    view = View((0, -4, 0), (0, 1, 0))
    with pytest.raises(ValueError, match="'fit' row 0"):
        view.screen_from_world([[0, 0, 0]], 10, 10, fit=[[0, -9, 0]])


def test_square_from_above_by_hand():
    screen, depth = View((0.5, 0.5, 2), (0, 0, -1)).screen_from_world(SQUARE, 5, 3)
    np.testing.assert_allclose(screen, [[1, 0], [3, 0], [3, 2], [1, 2]])
    np.testing.assert_allclose(depth, [2, 2, 2, 2])


def test_screen_is_y_up():
    view = View((0, -10, 1), (0, 1, 0))
    screen, _ = view.screen_from_world([[0, 0, 0], [0, 0, 2], [1, 0, 1]], 11, 11)
    assert screen[1, 1] > screen[0, 1]  # higher in the world is higher on screen
    assert screen[2, 0] > screen[0, 0]  # +x is to the right, looking along +y


def test_fit_uses_the_given_points_and_a_single_point_goes_to_the_centre():
    view = View((0.5, 0.5, 2), (0, 0, -1))
    screen, _ = view.screen_from_world([[0.5, 0.5, 0]], 5, 3, fit=SQUARE)
    np.testing.assert_allclose(screen, [[2, 1]])
    lone, _ = view.screen_from_world([[7, 7, 0]], 5, 3)
    np.testing.assert_allclose(lone, [[2, 1]])


@settings(max_examples=40)
@given(
    st.lists(st.tuples(*[st.floats(-5, 5)] * 3), min_size=2, max_size=12),
    st.integers(1, 300),
    st.integers(1, 300),
    st.sampled_from(["perspective", "parallel"]),
)
def test_fitted_points_fill_the_raster_on_one_axis_and_are_centred_on_the_other(
    points, width, height, projection
):
    view = View((20.0, 15.0, 12.0), (-1.0, -0.75, -0.6), projection)
    screen, _ = view.screen_from_world(points, width, height)
    room = np.array([width - 1, height - 1], dtype=float)
    low, high = screen.min(axis=0), screen.max(axis=0)
    assert (low >= -1e-9).all() and (high <= room + 1e-9).all()
    np.testing.assert_allclose((low + high) / 2, room / 2, atol=1e-9)
    if np.ptp(screen, axis=0).max() > 1e-9:
        assert np.isclose(high - low, room, atol=1e-9).any()


@settings(max_examples=30)
@given(st.tuples(*[st.floats(-50, 50)] * 3), st.floats(0.1, 10))
def test_moving_or_scaling_the_scene_with_the_viewpoint_keeps_the_picture(shift, scale):
    view = View((4.0, -6.0, 3.0), (-0.4, 0.6, -0.3))
    points = np.array(SQUARE, dtype=float) + [[0, 0, 0], [0, 0, 0.3], [0, 0, 0.1], [0, 0, 0.5]]
    screen, depth = view.screen_from_world(points, 64, 48)
    moved = View(tuple(np.add(view.point, shift) * scale), view.direction)
    again, moved_depth = moved.screen_from_world((points + shift) * scale, 64, 48)
    np.testing.assert_allclose(again, screen, atol=1e-9)
    np.testing.assert_allclose(moved_depth, depth * scale, rtol=1e-9)


@pytest.mark.parametrize(
    ("width", "height", "error"),
    [(0, 5, ValueError), (5, 0, ValueError), (True, 5, TypeError), (5.0, 5, TypeError)],
)
def test_bad_raster_sizes_are_named(width, height, error):
    with pytest.raises(error, match="'width'|'height'"):
        View((0.5, 0.5, 2), (0, 0, -1)).screen_from_world(SQUARE, width, height)


def test_bad_points_are_named():
    view = View((0.5, 0.5, 2), (0, 0, -1))
    with pytest.raises(ValueError, match=r"'points' must be an \(N, 3\) array"):
        view.screen_from_world([[0, 0]], 5, 5)
    with pytest.raises(ValueError, match="'points' row 1 is not finite"):
        view.project([[0, 0, 0], [0, np.nan, 0]])
    with pytest.raises(ValueError, match="'fit' must have at least 1 rows"):
        view.screen_from_world(SQUARE, 5, 5, fit=np.empty((0, 3)))


@settings(max_examples=30)
@given(
    st.lists(st.tuples(*[st.floats(-5, 5)] * 3), min_size=1, max_size=12),
    st.integers(2, 300),
    st.integers(2, 300),
    st.sampled_from(
        [((20, 15, 12), (-1, -0.75, -0.6)), ((1, 2, 20), (0, 0, -1)), ((0, -20, 9), (0, 1, -0.2))]
    ),
    st.sampled_from(["perspective", "parallel"]),
)
def test_the_camera_puts_points_half_a_pixel_past_screen_from_world(
    points, width, height, point_and_direction, projection
):
    view = View(*point_and_direction, projection=projection)
    camera = view.camera(width, height, points)
    display = vertex_tables(camera, points, width, height, subpixel_bits=None)["display"]
    screen, _ = view.screen_from_world(points, width, height)
    np.testing.assert_allclose(display[:, :2], screen + 0.5, atol=1e-7 * max(width, height))
    assert ((display[:, 2] > 0) & (display[:, 2] < 1)).all()  # between near and far
    inside = (display[:, :2] >= 0.5 - 1e-7 * max(width, height)) & (
        display[:, :2] <= np.array([width, height]) - 0.5 + 1e-7 * max(width, height)
    )
    assert inside.all()  # half a pixel from the window's edges: nothing fitted is clipped


def test_camera_needs_two_pixels_per_axis():
    with pytest.raises(ValueError, match="'width' and 'height' must be at least 2"):
        View((0.5, 0.5, 2), (0, 0, -1)).camera(1, 5, SQUARE)

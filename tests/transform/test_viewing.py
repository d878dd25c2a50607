"""Viewing transforms: rigid look-at, projection depth range, viewport, snapping, traces."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.raster.fixed import snap_units
from scanviz.scene import Camera
from scanviz.trace import Recorder, Trace
from scanviz.transform import (
    STAGES,
    clip_from_eye,
    display_from_ndc,
    eye_from_world,
    image_from_display,
    ndc_from_clip,
    transform_points,
    transform_vertices,
    vertex_tables,
)

from .strategies import cameras

BASE = settings.default.max_examples
unit = st.floats(0, 1)


def ndc_of_eye_points(camera, eye_points):
    return ndc_from_clip(transform_points(clip_from_eye(camera), eye_points))


# --- world -> eye -------------------------------------------------------------------------


@given(cameras())
def test_eye_from_world_is_a_rigid_motion_onto_the_minus_z_axis(camera):
    matrix = eye_from_world(camera)
    rotation = matrix[:3, :3]
    assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(rotation) == pytest.approx(1.0, abs=1e-12)
    assert np.array_equal(matrix[3], [0, 0, 0, 1])
    scale = 1 + np.abs(camera.eye).max()
    eye, look_at = transform_points(matrix, [camera.eye, camera.look_at])[:, :3]
    assert np.allclose(eye, 0, atol=1e-12 * scale)
    distance = np.linalg.norm(np.subtract(camera.look_at, camera.eye))
    assert np.allclose(look_at, [0, 0, -distance], atol=1e-12 * scale)
    up = rotation @ camera.up  # the up vector lands in the y-z plane, pointing up
    assert abs(up[0]) <= 1e-12 * np.linalg.norm(up) and up[1] > 0


@given(cameras())
def test_eye_from_world_inverse_is_the_transposed_rotation_then_the_eye(camera):
    matrix = eye_from_world(camera)
    world_from_eye = np.eye(4)
    world_from_eye[:3, :3] = matrix[:3, :3].T
    world_from_eye[:3, 3] = camera.eye
    assert np.allclose(world_from_eye @ matrix, np.eye(4), atol=1e-12)
    assert np.allclose(matrix @ world_from_eye, np.eye(4), atol=1e-12)
    assert np.allclose(np.linalg.inv(matrix), world_from_eye, atol=1e-12)


def test_eye_space_is_right_handed_looking_down_minus_z():
    # From (0, 0, 5) looking at the origin with y up, eye space is world space moved by -5 in z.
    matrix = eye_from_world(Camera(eye=(0, 0, 5), look_at=(0, 0, 0), up=(0, 1, 0)))
    assert np.allclose(matrix, [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -5], [0, 0, 0, 1]])
    # up needs only to be off the view direction: a tilted up gives the same matrix.
    tilted = eye_from_world(Camera(eye=(0, 0, 5), look_at=(0, 0, 0), up=(0, 3, 2)))
    assert np.allclose(tilted, matrix)


# --- eye -> clip -> NDC -------------------------------------------------------------------


@given(cameras(), st.lists(st.tuples(unit, unit), min_size=1, max_size=5))
def test_near_plane_maps_to_depth_0_and_far_plane_to_1(camera, samples):
    left, right, bottom, top = camera.window
    near, far = camera.near, camera.far
    for depth, expected in ((near, 0.0), (far, 1.0)):
        spread = depth / near if camera.projection == "perspective" else 1.0
        points = [
            (spread * (left + u * (right - left)), spread * (bottom + v * (top - bottom)), -depth)
            for u, v in samples
        ]
        ndc = ndc_of_eye_points(camera, points)
        assert np.allclose(ndc[:, 2], expected, atol=1e-12)
        assert (np.abs(ndc[:, :2]) <= 1 + 1e-12).all()


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_window_corners_map_to_ndc_corners(projection):
    camera = Camera(window=(-0.5, 1.5, 0.25, 1.0), near=2.0, far=8.0, projection=projection)
    spread = 4.0 if projection == "perspective" else 1.0  # far / near
    corners = [(-0.5, 0.25), (1.5, 0.25), (1.5, 1.0), (-0.5, 1.0)]
    signs = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    near_ndc = ndc_of_eye_points(camera, [(x, y, -2.0) for x, y in corners])
    far_ndc = ndc_of_eye_points(camera, [(spread * x, spread * y, -8.0) for x, y in corners])
    assert np.allclose(near_ndc, [(sx, sy, 0) for sx, sy in signs], atol=1e-15)
    assert np.allclose(far_ndc, [(sx, sy, 1) for sx, sy in signs], atol=1e-15)


@given(cameras())
def test_depth_grows_with_distance_and_starts_at_the_near_plane(camera):
    depths = np.linspace(camera.near, camera.far, 7)
    z = ndc_of_eye_points(camera, [(0.0, 0.0, -d) for d in depths])[:, 2]
    assert (np.diff(z) > 0).all()  # smaller z is nearer
    between_eye_and_near = transform_points(clip_from_eye(camera), [(0, 0, -camera.near / 2)])
    assert between_eye_and_near[0, 2] < 0  # outside the near plane z >= 0


def test_golden_perspective_matrix_like_glfrustum_with_0_to_1_depth():
    camera = Camera(window=(-1.0, 3.0, -2.0, 2.0), near=2.0, far=6.0)
    expected = [[1, 0, 0.5, 0], [0, 1, 0, 0], [0, 0, -1.5, -3], [0, 0, -1, 0]]
    assert np.array_equal(clip_from_eye(camera), expected)


def test_infinite_far_plane_is_the_limit_matrix():
    camera = Camera(near=0.5, far=float("inf"))
    z = ndc_of_eye_points(camera, [(0, 0, -0.5), (0, 0, -1.0), (0, 0, -1e12)])[:, 2]
    assert z[0] == 0 and z[1] == 0.5 and 1 - 1e-12 < z[2] < 1
    with pytest.raises(ValueError, match="'far' must be finite"):
        Camera(near=0.5, far=float("inf"), projection="orthographic")


def test_divide_leaves_points_at_or_behind_the_eye_undefined():
    ndc = ndc_from_clip([[1, 2, 3, 4], [1, 2, 3, 0], [1, 2, 3, -4], [1, 2, 3, 1e-310]])
    assert np.array_equal(ndc[0], [0.25, 0.5, 0.75])
    assert np.isnan(ndc[1:]).all()


# --- NDC -> display -> image --------------------------------------------------------------


@given(st.integers(0, 4096), st.integers(0, 4096))
def test_viewport_maps_ndc_corners_to_raster_corners_y_up(width, height):
    ndc = [(-1, -1, 0.25), (1, -1, 0.5), (1, 1, 0.75), (-1, 1, 1.0), (0, 0, 0)]
    display = transform_points(display_from_ndc(width, height), ndc)
    expected = [(0, 0), (width, 0), (width, height), (0, height), (width / 2, height / 2)]
    assert np.array_equal(display[:, :2], expected)  # row 0 at the bottom: no flip
    assert np.array_equal(display[:, 2], [0.25, 0.5, 0.75, 1.0, 0])


@given(
    st.lists(st.floats(-1e4, 1e4), min_size=2, max_size=20).filter(lambda v: len(v) % 2 == 0),
    st.integers(0, 16),
)
def test_image_snaps_exactly_as_the_rasterizer_does(values, bits):
    display = np.column_stack([np.reshape(values, (-1, 2)), np.arange(len(values) // 2)])
    image = image_from_display(display, bits)
    units = snap_units(display[:, :2], "corner", bits)
    assert np.array_equal(image[:, :2], units / 2.0 ** (bits + 1))
    assert np.array_equal(image[:, 2], display[:, 2])


def test_image_rounds_half_to_even_and_none_keeps_values():
    display = [[0.5 / 256, 1.5 / 256], [2.5, 3.25]]
    assert np.array_equal(image_from_display(display, 8), [[0, 2 / 256], [2.5, 3.25]])
    assert np.array_equal(image_from_display(display, 0), [[0, 0], [2, 3]])
    assert np.array_equal(image_from_display(display, None), display)


# --- the stage tables and their trace -----------------------------------------------------


@given(cameras(), st.lists(st.tuples(*[st.floats(-20, 20)] * 3), min_size=1, max_size=8))
@settings(max_examples=BASE // 2)
def test_vertex_tables_compose_the_stage_matrices(camera, points):
    tables = vertex_tables(camera, points, 64, 48, subpixel_bits=4)
    assert tuple(tables) == STAGES
    clip_from_world = clip_from_eye(camera) @ eye_from_world(camera)
    clip = transform_points(clip_from_world, points)
    scale = 1 + np.abs(clip).max()
    assert np.allclose(tables["clip"], clip, rtol=0, atol=1e-12 * scale)
    assert np.array_equal(tables["eye"], transform_points(eye_from_world(camera), points)[:, :3])
    ahead = ~np.isnan(tables["ndc"]).any(axis=1)
    assert not (ahead & (tables["clip"][:, 3] <= 0)).any()
    assert np.isnan(tables["display"][~ahead]).all() and np.isnan(tables["image"][~ahead]).all()
    display = transform_points(display_from_ndc(64, 48), tables["ndc"][ahead])[:, :3]
    assert np.array_equal(tables["display"][ahead], display)
    assert np.array_equal(tables["image"][ahead], image_from_display(display, 4))
    assert [t.shape[1] for t in tables.values()] == [3, 3, 4, 3, 3, 3]


def test_golden_table_for_the_default_camera():
    tables = vertex_tables(Camera(), [[0, 0, 0], [1, -1, 3]], 100, 100, subpixel_bits=2)
    assert np.allclose(tables["eye"], [[0, 0, -5], [1, -1, -2]])
    assert np.allclose(tables["clip"], [[0, 0, 400 / 99, 5], [1, -1, 100 / 99, 2]])
    assert np.allclose(tables["ndc"], [[0, 0, 80 / 99], [0.5, -0.5, 50 / 99]])
    assert np.allclose(tables["display"], [[50, 50, 80 / 99], [75, 25, 50 / 99]])


def test_transform_vertices_emits_one_event_per_stage():
    camera = Camera()
    points = [[0, 0, 0], [0, 0, 5], [1, 2, -3]]  # the second is the eye itself: w = 0
    recorder = Recorder()
    tables = transform_vertices(camera, points, 32, 16, trace=recorder, object=7)
    trace = recorder.trace()
    assert [e.stage for e in trace] == list(STAGES)
    assert {e.kind for e in trace} == {"vertices_transformed"} and {e.object for e in trace} == {7}
    matrices = [None, eye_from_world(camera), clip_from_eye(camera), None]
    matrices += [display_from_ndc(32, 16), None]
    for event, matrix in zip(trace, matrices, strict=True):
        assert event.matrix == (None if matrix is None else tuple(matrix.ravel()))
        rows = tables[event.stage]
        for row, expected in zip(event.vertices, rows, strict=True):
            assert (row is None and np.isnan(expected).all()) or row == tuple(expected)
    assert trace[3].vertices[1] is None and trace[2].vertices[1] is not None
    assert Trace.from_json(trace.to_json()) == trace
    assert transform_vertices(camera, points, 32, 16, trace=Recorder(kinds=["span"])).keys() == (
        tables.keys()
    )


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: transform_points(np.eye(3), [[0, 0, 0]]), ValueError, "'matrix' must be an"),
        (lambda: transform_points(np.eye(4)[:3], [[0, 0, 0]]), ValueError, "'matrix' must be 4x4"),
        (lambda: transform_points(np.eye(4), [[0, 0]]), ValueError, r"\(N, 3\) or \(N, 4\)"),
        (lambda: transform_points(np.eye(4), [[0, np.inf, 0]]), ValueError, "row 0 is not finite"),
        (lambda: transform_points(np.eye(4), "abc"), TypeError, "'points' must be an array"),
        (lambda: ndc_from_clip([[1, 2, 3]]), ValueError, r"'points' must be an \(N, 4\)"),
        (lambda: image_from_display([[1.0]], 8), ValueError, "x and y columns"),
        (lambda: image_from_display([[1.0, 2.0]], 17), ValueError, "subpixel_bits"),
        (lambda: display_from_ndc(-1, 4), ValueError, "'width'"),
        (lambda: eye_from_world("camera"), TypeError, "'camera' must be a scanviz.scene.Camera"),
        (lambda: vertex_tables(Camera(), [[0, 0, 0, 1]], 4, 4), ValueError, "'world_points'"),
        (lambda: transform_vertices(Camera(), [[0, 0, 0]], 4, 4, trace=1), TypeError, "'trace'"),
    ],
)
def test_bad_arguments_raise_naming_the_argument(call, error, message):
    with pytest.raises(error, match=message):
        call()


@pytest.mark.parametrize(
    "camera",
    [
        Camera(eye=(0, 0, 1e99), look_at=(0, 0, 0), up=(0, 1e-300, 0)),
        Camera(eye=(0, 0, 1e-95), look_at=(0, 0, 0), up=(0, 1e300, 0), near=1e-98, far=1e-96,
               window=(-1e-98, 1e-98, -1e-98, 1e-98)),
        Camera(eye=(1e99, 0, 0), look_at=(-1e99, 0, 0), up=(0, 1e-300, 0)),
    ],
)  # fmt: skip
def test_issue8_d5_eye_from_world_survives_huge_and_tiny_lengths(camera):
    matrix = eye_from_world(camera)
    rotation = matrix[:3, :3]
    assert np.isfinite(matrix).all()
    assert np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-15)
    view = np.subtract(camera.look_at, camera.eye)
    assert np.allclose(rotation @ (view / np.abs(view).max()), [0, 0, -1], atol=1e-15)
    assert np.allclose(rotation[1], [0, 1, 0], atol=1e-15)  # up stays up

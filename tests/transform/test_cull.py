"""Back-face culling: the sign test on a cube, Newell normals, and a screen-space oracle."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from scanviz.scene import Camera
from scanviz.trace import Recorder, Trace
from scanviz.transform import (
    back_facing,
    clip_from_eye,
    cull_faces,
    eye_from_world,
    face_normals,
    transform_points,
)

from .strategies import cameras

BASE = settings.default.max_examples
CUBE = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
# Counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
CUBE_FACES = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
OUTWARD = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]])


def test_cube_faces_are_counter_clockwise_from_outside():
    normals = face_normals(CUBE, CUBE_FACES)
    assert np.array_equal(normals, 8 * OUTWARD)  # twice the area, 2 x 2


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
@pytest.mark.parametrize("eye", [(3, 4, 5), (-3, 4, -5), (2, -7, 1.5), (-4, -3, -6)])
def test_a_cube_seen_from_outside_shows_three_faces(eye, projection):
    camera = Camera(eye=eye, look_at=(0.1, -0.2, 0.3), projection=projection)
    culled, dots = cull_faces(camera, CUBE, CUBE_FACES)
    if projection == "perspective":
        facing = OUTWARD @ eye > 1  # the eye is outside the slab of that face's plane
    else:
        facing = OUTWARD @ np.subtract(camera.eye, camera.look_at) > 0
    assert np.array_equal(culled, ~facing) and culled.sum() == 3
    assert np.array_equal(culled, dots >= 0)


def test_head_on_view_culls_edge_on_faces():
    # Perspective from (0, 0, 5): only +z faces the eye. Orthographic along -z: the four
    # side faces are exactly edge-on (dot = 0) and culled too.
    for projection in ("perspective", "orthographic"):
        culled, dots = cull_faces(Camera(eye=(0, 0, 5), projection=projection), CUBE, CUBE_FACES)
        assert culled.tolist() == [True, True, True, True, True, False]
    assert dots[:4].tolist() == [0, 0, 0, 0]


def test_degenerate_faces_are_never_culled():
    points = [[0, 0, 0], [1, 1, 1], [2, 2, 2], [5, 5, 5]]
    faces = [[0, 1, 2], [3, 3, 3], [0, 1, 2, 1]]  # collinear, one point, a folded path
    culled, dots = cull_faces(Camera(), points, faces)
    assert culled.tolist() == [False] * 3 and dots.tolist() == [0, 0, 0]
    assert not back_facing(Camera(projection="orthographic"), [[0, 0, 0]] * 3)


@st.composite
def triangles(draw):
    """A triangle of world points in [-5, 5]^3."""
    corner = st.tuples(*[st.floats(-5, 5)] * 3)
    return np.array(draw(st.lists(corner, min_size=3, max_size=3)))


@given(cameras(), triangles())
@settings(max_examples=BASE * 2)
def test_back_facing_matches_the_screen_space_orientation(camera, triangle):
    # Projected with y up, a front face is counter-clockwise on screen (positive area).
    clip = transform_points(clip_from_eye(camera) @ eye_from_world(camera), triangle)
    assume((clip[:, 3] > 1e-6).all())  # all in front of the eye: the projection keeps order
    x, y = (clip[:, :2] / clip[:, 3:]).T
    area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])
    assume(abs(area) > 1e-6 * (1 + np.abs(x).max() + np.abs(y).max()) ** 2)
    assert back_facing(camera, triangle) == (area < 0)


@given(cameras(), triangles())
def test_reversing_a_face_flips_the_verdict(camera, triangle):
    # Nearly edge-on faces are decided by rounding either way; they cover (almost) no area.
    _, (dot,) = cull_faces(camera, triangle, [[0, 1, 2]])
    (normal,) = face_normals(triangle, [[0, 1, 2]])
    perspective = camera.projection == "perspective"
    view = (
        triangle.mean(axis=0) - camera.eye
        if perspective
        else np.subtract(camera.look_at, camera.eye)
    )
    assume(abs(dot) > 1e-9 * np.linalg.norm(normal) * (1 + np.linalg.norm(view)))
    assert back_facing(camera, triangle) != back_facing(camera, triangle[::-1])


@given(st.integers(0, 2**32 - 1), st.integers(3, 9), st.floats(0, 1e6))
def test_newell_normal_of_a_planar_polygon_is_twice_its_area_along_the_normal(seed, count, far):
    rng = np.random.default_rng(seed)
    angles = np.sort(rng.uniform(0, 2 * np.pi, count))
    radii = rng.uniform(0.5, 2, count)
    flat = np.column_stack([radii * np.cos(angles), radii * np.sin(angles), np.zeros(count)])
    x, y = flat[:, 0], flat[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)  # shoelace, counter-clockwise
    rotation, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    rotation *= np.linalg.det(rotation)  # a proper rotation keeps counter-clockwise
    placed = flat @ rotation.T + far * rng.normal(size=3)
    (normal,) = face_normals(placed, [np.arange(count)])
    assert np.allclose(normal, 2 * area * rotation[:, 2], rtol=0, atol=1e-9 * (1 + far))


@given(st.integers(0, 2**32 - 1))
def test_newell_normal_of_any_quad_is_the_cross_product_of_its_diagonals(seed):
    quad = np.random.default_rng(seed).uniform(-3, 3, (4, 3))  # generally not planar
    (normal,) = face_normals(quad, [[0, 1, 2, 3]])
    assert np.allclose(normal, np.cross(quad[2] - quad[0], quad[3] - quad[1]), atol=1e-12)


def test_cull_faces_agrees_with_back_facing_and_takes_ragged_or_square_faces():
    camera = Camera(eye=(3, 4, 5))
    ragged = [np.array(f) for f in CUBE_FACES] + [np.array([0, 4, 6, 2, 0, 2])[:3]]
    culled, _ = cull_faces(camera, CUBE, ragged)
    assert culled.tolist() == [back_facing(camera, CUBE[f]) for f in ragged]
    assert np.array_equal(cull_faces(camera, CUBE, np.array(CUBE_FACES))[0], culled[:6])
    assert cull_faces(camera, CUBE, [])[0].shape == (0,)


def test_face_culled_events_carry_the_test():
    camera = Camera(eye=(3, 4, 5))
    recorder = Recorder(polygons=[1, 4])
    culled, dots = cull_faces(camera, CUBE, CUBE_FACES, trace=recorder)
    trace = recorder.trace()
    assert [(e.kind, e.polygon, e.culled) for e in trace] == [
        ("face_culled", 1, False),
        ("face_culled", 4, True),
    ]
    plus_x = trace[0]
    assert plus_x.normal == (8.0, 0.0, 0.0) and plus_x.view == (1 - 3, 0 - 4, 0 - 5)
    assert plus_x.dot == dots[1] == -16.0
    assert Trace.from_json(trace.to_json()) == trace


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: cull_faces(Camera(), CUBE, [[0, 1, 8]]), ValueError, r"'faces\[0\]' indexes"),
        (lambda: cull_faces(Camera(), CUBE, [[0, 1]]), ValueError, "has 2 vertices"),
        (lambda: cull_faces(Camera(), CUBE[:, :2], [[0, 1, 2]]), ValueError, "'world_positions'"),
        (lambda: cull_faces(None, CUBE, [[0, 1, 2]]), TypeError, "'camera'"),
        (lambda: cull_faces(Camera(), CUBE, [[0, 1, 2]], trace=3), TypeError, "'trace'"),
        (lambda: back_facing(Camera(), [[0, 0, 0], [1, 0, 0]]), ValueError, "at least 3 rows"),
        (lambda: face_normals(CUBE, [[0, 1, 2.5]]), TypeError, "int indices"),
    ],
)
def test_bad_arguments_raise_naming_the_argument(call, error, message):
    with pytest.raises(error, match=message):
        call()

"""The transform stage's replaceable steps: viewing_matrix, back_face_test, clip_against_plane."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.scene import Camera
from scanviz.trace import Recorder
from scanviz.transform import clip_polygon, cull_faces, eye_from_world, transform_vertices
from scanviz.transform.clip import clip_against_plane
from scanviz.transform.cull import back_face_test

from .strategies import cameras

CUBE = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
CUBE_FACES = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
RIGHT = (-1, 0, 0, 1)  # distance w - x (integers: Fractions stay exact)
F = Fraction


def test_a_replaced_viewing_matrix_is_what_eye_from_world_returns():
    shifted = np.eye(4)
    shifted[0, 3] = 2.0
    with steps.using(viewing_matrix=lambda eye, look_at, up: shifted.tolist()):
        assert np.array_equal(eye_from_world(Camera()), shifted)
        eye = transform_vertices(Camera(), [[1, 2, 3]], 8, 8)["eye"]
    assert eye.tolist() == [[3.0, 2.0, 3.0]]
    assert eye_from_world(Camera())[2, 3] == -5.0  # the reference again


def test_the_viewing_matrix_step_gets_the_camera_as_plain_tuples():
    seen = []

    def spy(eye, look_at, up):
        seen.append((eye, look_at, up))
        return np.eye(4)

    with steps.using(viewing_matrix=spy):
        eye_from_world(Camera(eye=(1, 2, 3), look_at=(0, 0, 0), up=(0, 0, 2)))
    assert seen == [((1.0, 2.0, 3.0), (0.0, 0.0, 0.0), (0.0, 0.0, 2.0))]


def test_a_viewing_matrix_step_that_returns_no_4x4_matrix_is_named():
    with steps.using(viewing_matrix=lambda eye, look_at, up: [[1, 0], [0, 1]]):
        with pytest.raises(ValueError, match=r"'viewing_matrix' step must return a 4x4 matrix"):
            eye_from_world(Camera())


def test_a_replaced_back_face_test_runs_without_a_tracer():
    with steps.using(back_face_test=lambda normal, view: normal[2] > 0):
        culled, _ = cull_faces(Camera(eye=(3, 4, 5)), CUBE, CUBE_FACES)
    assert culled.tolist() == [False, False, False, False, False, True]  # only +z


def test_back_face_test_on_the_rules_edges():
    assert back_face_test((0.0, 0.0, 4.0), (0.0, 0.0, -5.0)) is False  # facing the eye
    assert back_face_test((4.0, 0.0, 0.0), (0.0, 0.0, -5.0)) is True  # edge-on: culled
    assert back_face_test((0.0, 0.0, -4.0), (0.0, 0.0, -5.0)) is True  # turned away
    assert back_face_test((0.0, -0.0, 0.0), (1.0, 2.0, 3.0)) is False  # no area, no back


@settings(derandomize=True, max_examples=25, deadline=None)
@given(
    cameras(),
    st.lists(st.tuples(*[st.floats(-5, 5)] * 3), min_size=4, max_size=8),
    st.integers(0, 2**32 - 1),
)
def test_the_vectorized_test_is_the_step_bit_for_bit(camera, positions, seed):
    # Untraced, all faces are tested at once; traced, each goes through back_face_test.
    rng = np.random.default_rng(seed)
    faces = [rng.choice(len(positions), 3, replace=False) for _ in range(6)]
    fast, fast_dots = cull_faces(camera, positions, faces)
    traced, traced_dots = cull_faces(camera, positions, faces, trace=Recorder())
    assert np.array_equal(fast, traced) and np.array_equal(fast_dots, traced_dots)


def _distance(vertex, plane):
    return sum(c * v for c, v in zip(plane, vertex[:4], strict=True))


@settings(derandomize=True, max_examples=30, deadline=None)
@given(
    st.lists(
        st.tuples(
            *[st.fractions(-3, 3, max_denominator=8)] * 3,
            st.fractions(F(1, 4), 3, max_denominator=8),
        ),
        min_size=3,
        max_size=7,
    ),
    st.sampled_from([(0, 0, 1, 0), (0, 0, -1, 1), (1, 0, 0, 1), (-1, 0, 0, 1), (0, 1, 0, 1)]),
)
def test_one_stage_is_exact_on_fractions(polygon, plane):
    # Plain arithmetic, so Fractions go through exactly: the crossings lie on the plane, the
    # inside vertices survive in order, and nothing outside is left.
    vertices = [(*v, v[0] + v[3]) for v in polygon]  # an attribute: x + w
    clipped = clip_against_plane(vertices, plane)
    assert all(_distance(v, plane) >= 0 for v in clipped)
    assert all(v[4] == v[0] + v[3] for v in clipped)  # linear attributes stay exact
    inside = [v for v in vertices if _distance(v, plane) >= 0]
    assert [v for v in clipped if v in vertices] == inside
    assert all(_distance(v, plane) == 0 for v in clipped if v not in vertices)


def test_one_stage_cuts_the_tip_off_a_triangle():
    # Distances w - x: 1, -2, 1. The edge 0 -> 1 leaves at t = 1/3, the edge 1 -> 2 enters at
    # 1/3 from vertex 2 (the inside end): both crossings have x = 1 and attribute 1.
    triangle = [tuple(map(F, v)) for v in [(0, 0, 0, 1, 0), (3, 0, 0, 1, 3), (0, 1, 0, 1, 0)]]
    assert clip_against_plane(triangle, RIGHT) == [
        (0, 0, 0, 1, 0),
        (1, 0, 0, 1, 1),
        (1, F(2, 3), 0, 1, 1),
        (0, 1, 0, 1, 0),
    ]


def test_a_replaced_clip_stage_runs_and_its_counts_are_traced():
    points = [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]
    recorder = Recorder()
    with steps.using(clip_against_plane=lambda vertices, plane: vertices[:2]):
        clipped, _ = clip_polygon(points, trace=recorder)
    (event,) = recorder.trace()
    assert len(clipped) == 0 and event.counts == (3, 3, 3, 2, 2, 2) and event.verdict == "rejected"


@pytest.mark.parametrize("returned", [[(1, 2, 3)] * 3, [(1, 2, 3, 4), (1, 2)], [("a",) * 4] * 3])
def test_a_clip_stage_that_returns_malformed_vertices_is_named(returned):
    points = [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]
    with steps.using(clip_against_plane=lambda vertices, plane: returned):
        with pytest.raises(ValueError, match=r"'clip_against_plane' step must return vertices"):
            clip_polygon(points)


def test_a_clip_stage_that_returns_no_list_is_named():
    points = [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]
    with steps.using(clip_against_plane=lambda vertices, plane: None):
        with pytest.raises(TypeError, match=r"'clip_against_plane' step must return a list"):
            clip_polygon(points)

"""Feature edges: a cube's creases and silhouette, open boundaries, and silhouette loops."""

import numpy as np
import pytest

from scanviz.raster.lines import midpoint_line
from scanviz.shading import feature_edges
from tests.shading import CUBE_FACES, CUBE_POSITIONS, uv_sphere

CENTER = np.array([0.5, 0.5, 0.5])
SQUARE = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def pairs(edges: np.ndarray) -> set[tuple[int, int]]:
    return {tuple(e) for e in edges.tolist()}


@pytest.mark.parametrize(("threshold", "creases"), [(30, 12), (89.9, 12), (90, 0), (100, 0)])
def test_a_cube_has_twelve_right_angle_creases(threshold, creases):
    edges = feature_edges(CUBE_POSITIONS, CUBE_FACES, (3, 4, 5), threshold)
    assert len(edges["crease"]) == creases
    assert len(edges["boundary"]) == 0


@pytest.mark.parametrize(
    "viewer",
    [{"eye": (3, 4, 5)}, {"eye": (-2, 0.3, -4)}, {"eye": None, "view_dir": (1, -2, 3)}],
)
def test_a_cube_seen_in_general_position_has_a_hexagonal_silhouette(viewer):
    silhouette = feature_edges(CUBE_POSITIONS, CUBE_FACES, **viewer)["silhouette"]
    assert len(silhouette) == 6
    assert np.all(np.bincount(silhouette.ravel(), minlength=8) % 2 == 0)  # a closed loop


def test_a_cube_seen_face_on_outlines_its_front_face():
    silhouette = feature_edges(CUBE_POSITIONS, CUBE_FACES, (0.5, 0.5, 5))["silhouette"]
    assert pairs(silhouette) == {(1, 3), (1, 5), (3, 7), (5, 7)}  # the z = 1 square


@pytest.mark.parametrize(
    "faces", [[[0, 1, 2, 3]], [[0, 1, 2], [0, 2, 3]]], ids=["quad", "triangles"]
)
def test_an_open_square_has_four_boundary_edges(faces):
    edges = feature_edges(SQUARE, faces, (0.3, 0.2, 2))
    assert pairs(edges["boundary"]) == {(0, 1), (1, 2), (2, 3), (0, 3)}
    assert len(edges["silhouette"]) == len(edges["crease"]) == 0


def test_the_silhouette_of_a_sphere_is_closed_loops_around_the_visible_cap():
    positions, faces = uv_sphere()
    eye = np.array([2.0, 1.0, 3.0])
    silhouette = feature_edges(positions, faces, eye)["silhouette"]
    assert len(silhouette) > 0
    assert np.all(np.bincount(silhouette.ravel()) % 2 == 0)
    # Every silhouette vertex lies near the horizon seen from the eye: p . (eye - p) ~ 0.
    points = positions[np.unique(silhouette)]
    horizon = np.sum(points * (eye - points), axis=1) / np.linalg.norm(eye - points, axis=1)
    assert np.abs(horizon).max() < 0.3


def test_edges_come_once_each_as_sorted_int64_pairs():
    edges = feature_edges(CUBE_POSITIONS, CUBE_FACES, (3, 4, 5))
    for name in ("silhouette", "boundary", "crease"):
        array = edges[name]
        assert array.dtype == np.int64 and array.ndim == 2 and array.shape[1] == 2
        assert np.all(array[:, 0] < array[:, 1])
        assert len(pairs(array)) == len(array)
        assert array.tolist() == sorted(array.tolist())


def test_degenerate_faces_take_no_part_in_silhouettes_and_creases():
    positions = np.vstack([SQUARE, [(2, 0, 0)]])
    edges = feature_edges(positions, [[0, 1, 2, 3], [0, 4, 1]], (0.5, 0.5, 3))
    assert len(edges["silhouette"]) == len(edges["crease"]) == 0
    assert pairs(edges["boundary"]) >= {(1, 2), (2, 3), (0, 3)}


def test_silhouette_edges_project_to_lines_the_rasterizer_draws():
    silhouette = feature_edges(CUBE_POSITIONS, CUBE_FACES, None, view_dir=(0, 0, 1))["silhouette"]
    pixels = np.rint(CUBE_POSITIONS[:, :2] * 10).astype(np.int64)  # orthographic along z
    drawn = {
        (int(x), int(y))
        for a, b in silhouette
        for x, y in zip(*midpoint_line(*pixels[a], *pixels[b]), strict=True)
    }
    assert len(drawn) == 40  # the outline of a 10 x 10 pixel square


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"crease_degrees": 200}, ValueError, r"'crease_degrees' must be in \[0, 180\]"),
        ({"crease_degrees": "30"}, TypeError, "'crease_degrees' must be a number"),
        ({"eye": None}, ValueError, "exactly one of 'eye'"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    with pytest.raises(error, match=message):
        feature_edges(CUBE_POSITIONS, CUBE_FACES, **({"eye": (3, 4, 5)} | arguments))

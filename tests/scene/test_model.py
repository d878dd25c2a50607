"""The scene model: every class validates at construction and names the rule broken."""

import math

import numpy as np
import pytest

from scanviz.scene import Camera, Light, Material, Mesh, Scene, SceneObject

TRIANGLE = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]


def test_material_defaults_and_coercion():
    material = Material(color=[1, 0, 0], diffuse=1)
    assert material.color == (1.0, 0.0, 0.0) and material.diffuse == 1.0
    assert material.opaque and not Material(transparency=0.5).opaque


@pytest.mark.parametrize(
    "kwargs, error, rule",
    [
        ({"diffuse": 1.5}, ValueError, r"'diffuse' must be in \[0.0, 1.0\]; got 1.5"),
        ({"transparency": -0.1}, ValueError, "'transparency' must be in"),
        ({"exponent": -1}, ValueError, "'exponent' must be in"),
        ({"ambient": math.nan}, ValueError, "'ambient' must be finite"),
        ({"specular": True}, TypeError, "'specular' must be a number"),
        ({"color": (1, 2, 0)}, ValueError, r"'color' components must be in \[0, 1\]"),
        ({"color": (1, 0)}, ValueError, "'color' must have 3 components"),
        ({"color": (1, 0, math.inf)}, ValueError, "'color' must be finite"),
    ],
)
def test_material_rejects(kwargs, error, rule):
    with pytest.raises(error, match=rule):
        Material(**kwargs)


def test_mesh_arrays_are_read_only_and_typed():
    mesh = Mesh(TRIANGLE, [[0, 1, 2]], face_materials=[0], materials=(Material(),))
    assert mesh.positions.dtype == np.float64 and mesh.faces[0].dtype == np.int64
    assert not mesh.positions.flags.writeable and not mesh.faces[0].flags.writeable
    assert mesh.face_count == 1 and mesh.triangle_count() == 1
    assert Mesh(np.zeros((5, 3)), [[0, 1, 2, 3, 4]]).triangle_count() == 3


@pytest.mark.parametrize(
    "kwargs, error, rule",
    [
        ({"positions": [[0, 0]] * 3}, ValueError, r"'positions' must be an \(N, 3\) array"),
        ({"positions": [[0, 0, 0], [1, 0, 0], [0, math.nan, 0]]}, ValueError, "'positions' row 2"),
        ({"faces": [[0, 1]]}, ValueError, r"'faces\[0\]' has 2 vertices; a face needs >= 3"),
        ({"faces": [[0, 1, 3]]}, ValueError, r"'faces\[0\]' indexes outside 0..2"),
        ({"faces": [[0, 1, -1]]}, ValueError, r"'faces\[0\]' indexes outside 0..2"),
        (
            {"faces": [[0, 1, 1.7]]},
            TypeError,
            r"'faces\[0\]' must be a 1-D sequence of int indices",
        ),
        ({"normals": [[0, 0, 1]]}, ValueError, "'normals' must have one row per position"),
        ({"face_materials": [0]}, ValueError, "'face_materials' must index 'materials'"),
        ({"vertex_materials": [-1, -1]}, ValueError, "'vertex_materials' must have 3 entries"),
        ({"vertex_materials": [-1, -1, 0.5]}, TypeError, "'vertex_materials' must hold integers"),
    ],
)
def test_mesh_rejects(kwargs, error, rule):
    arguments = {"positions": TRIANGLE, "faces": [[0, 1, 2]]} | kwargs
    with pytest.raises(error, match=rule):
        Mesh(**arguments)


def test_scene_object_needs_a_4x4_matrix():
    mesh = Mesh(TRIANGLE, [[0, 1, 2]])
    assert (SceneObject(mesh).world_from_model == np.eye(4)).all()
    with pytest.raises(ValueError, match="'world_from_model' must be"):
        SceneObject(mesh, world_from_model=np.eye(3))


@pytest.mark.parametrize(
    "kwargs, rule",
    [
        ({"up": (0, 0, 1)}, "'up' .* must not be parallel to the view direction"),
        ({"up": (0, 0, 0)}, "'up' .* must not be parallel"),
        ({"look_at": (0, 0, 5)}, "'look_at' must differ from 'eye'"),
        ({"near": 5.0, "far": 5.0}, "'near' must be < 'far'"),
        ({"near": 0.0}, "'near' must be > 0 for a perspective camera"),
        ({"window": (1, -1, -1, 1)}, "'window' must have left < right and bottom < top"),
        ({"window": (-1, 1, 1, 1)}, "'window' must have left < right and bottom < top"),
        ({"projection": "fisheye"}, "'projection' must be 'perspective' or 'orthographic'"),
    ],
)
def test_camera_rejects(kwargs, rule):
    with pytest.raises(ValueError, match=rule):
        Camera(**kwargs)


def test_orthographic_camera_allows_near_at_or_behind_the_eye():
    assert Camera(projection="orthographic", near=-2.0, far=3.0).near == -2.0


def test_lights():
    point = Light("point", position=(1, 2, 3))
    assert point.direction is None and point.position == (1.0, 2.0, 3.0)
    assert Light().position is None
    with pytest.raises(ValueError, match="'kind' must be 'point' or 'directional'"):
        Light("spot")
    with pytest.raises(ValueError, match="a point light needs a 'position'"):
        Light("point")
    with pytest.raises(ValueError, match="'direction' must not be the zero vector"):
        Light(direction=(0, 0, 0))
    with pytest.raises(ValueError, match="'color' components must be >= 0"):
        Light(color=(-1, 0, 0))


def test_scene_counts_triangles_and_checks_colors():
    mesh = Mesh(np.zeros((4, 3)), [[0, 1, 2, 3]])
    scene = Scene([SceneObject(mesh), SceneObject(mesh)])
    assert scene.triangle_count() == 4 and isinstance(scene.objects, tuple)
    with pytest.raises(ValueError, match=r"'background' components must be in \[0, 1\]"):
        Scene((), background=(0, 0, 2))

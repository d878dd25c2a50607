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


# --- issue 8 -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "build, rule",
    [
        (lambda: Material(exponent=1e308), r"'exponent' must be in \[0.0, 10000.0\]; got 1e\+308"),
        (lambda: Material(fudge=1e200), r"'fudge' must be in \[0.0, 1e\+99\]"),
        (lambda: Light("point", position=(0, 0, 1e308)), r"'position' components must be within"),
        (lambda: Light(color=(1e7, 0, 0)), r"'color' components must be >= 0 and <= 1e\+06"),
        (lambda: Camera(eye=(0, 0, 1e300)), r"'eye' components must be within \+-1e\+99"),
        (lambda: Camera(window=(0, 5e-324, 0, 5e-324)), r"'window' width must be at least 1e-12"),
        (
            lambda: Camera(window=(1e20, 1e20 + 1e7, -1, 1)),
            r"'window' width must be at least 1e\+08",
        ),
        (lambda: Camera(near=1e-200), r"'near' must be > 0 for a perspective camera \(at least"),
        (lambda: Camera(near=1.0, far=1.0 + 1e-15), r"'far' - 'near' must be at least"),
        (
            lambda: SceneObject(
                Mesh(TRIANGLE, [[0, 1, 2]]), world_from_model=np.diag([1e150] * 3 + [1])
            ),
            r"'world_from_model' 3x3 entries must be within \+-1e\+100",
        ),
        (
            lambda: SceneObject(
                Mesh(TRIANGLE, [[0, 1, 2]]), world_from_model=np.diag([1e-150] * 3 + [1])
            ),
            r"'world_from_model' 3x3 block must be invertible with inverse entries within",
        ),
        (
            lambda: SceneObject(
                Mesh([[0, 0, 0], [1e200, 0, 0], [0, 1, 0]], [[0, 1, 2]]), name="far"
            ),
            r"mesh position 1 of object 'far' \[1e\+200, 0.0, 0.0\] lands at world .* limit \+-1e\+99",
        ),
        (
            lambda: SceneObject(Mesh(TRIANGLE, [[0, 1, 2]]), world_from_model=[[1, 0, 0, 0]] * 4),
            r"'world_from_model' must be affine, bottom row \(0, 0, 0, 1\)",
        ),
        (
            lambda: Scene([SceneObject(Mesh([[0, 0, 0], [1e14, 0, 0], [0, 1, 0]], [[0, 1, 2]]))]),
            r"'objects\[0\]' mesh position 1 is 1e\+14 from the eye, more than 1e\+12 times 1",
        ),
    ],
)
def test_issue8_d3_finite_values_beyond_the_limits_name_the_field_and_rule(build, rule):
    with pytest.raises(ValueError, match=rule):
        build()


def test_issue8_d3_scenes_at_the_limits_render_without_nan():
    from scanviz.pipeline import render

    limit = 1e99
    mesh = Mesh(
        [[-limit, -limit, -limit], [limit, -limit, -limit], [0, limit, -limit]], [[0, 1, 2]]
    )
    lights = (
        Light("point", position=(limit, limit, limit), color=(1e6, 1e6, 1e6)),
        Light(direction=(1e-300, 0, -1e-300)),
    )
    cameras = (
        Camera(eye=(0, 0, limit), window=(-1e88, 1e88, -1e88, 1e88), near=1e88, far=np.inf),
        Camera(eye=(0, 0, limit), near=-limit, far=limit, window=(-limit, limit, -limit, limit),
               projection="orthographic"),
    )  # fmt: skip
    for camera in cameras:
        scene = Scene(
            [SceneObject(replace_closed(mesh), Material(exponent=1e4, fudge=1e99))], camera, lights
        )
        for shading in ("flat", "gouraud", "phong", "gooch"):
            for visibility in ("zbuffer", "abuffer"):
                image = render(scene, 8, 8, shading=shading, visibility=visibility).image
                assert np.isfinite(image).all(), (camera.projection, shading, visibility)


def replace_closed(mesh):
    return Mesh(mesh.positions, mesh.faces, closed=False)


def test_issue8_d5_camera_lengths_neither_overflow_nor_underflow():
    Camera(eye=(0, 0, 1e99), look_at=(0, 0, 0))  # |view| = 1e99: not "parallel"
    Camera(up=(0, 1e-300, 0))
    Camera(eye=(1e99, 0, 0), look_at=(-1e99, 0, 0))
    with pytest.raises(ValueError, match="must not be parallel"):
        Camera(up=(0, 0, 1e-300))


def test_issue8_d11_an_empty_mesh_is_valid_and_renders_as_nothing():
    from scanviz.pipeline import render

    mesh = Mesh([], [])
    assert mesh.positions.shape == (0, 3) and mesh.faces == ()
    image = render(Scene([SceneObject(mesh)], background=(0.25, 0.5, 1)), 4, 4).image
    assert (image == np.array([0.25, 0.5, 1])).all()
    with pytest.raises(ValueError, match=r"'positions' must be an \(N, 3\) array"):
        Mesh([[]], [])

"""Built-in scenes and mesh generators: counts, geometry, orientation and framing."""

import numpy as np
import pytest

from scanviz.io import load_scene
from scanviz.scene import (
    BUILTIN_MESHES,
    BUILTIN_SCENES,
    Scene,
    box,
    builtin_scene,
    function_surface_mesh,
    icosphere,
    terrain,
    torus,
    uv_sphere,
)
from scanviz.transform import clip_from_eye, display_from_ndc, eye_from_world

TRIANGLES = {
    "umbc_zbuffer": 4,
    "painter": 5,
    "sphere": 1280,
    "function_surface": 3200,
    "transparent_cube": 1292,
    "terrain": 51200,
}


@pytest.fixture(scope="module")
def scenes():
    return {name: builtin_scene(name) for name in BUILTIN_SCENES}


def newell_normals(mesh):
    """Area vector of every face (twice its area, along its counter-clockwise normal)."""
    normals = []
    for face in mesh.faces:
        corners = mesh.positions[face]
        normals.append(np.cross(corners, np.roll(corners, -1, axis=0)).sum(axis=0))
    return np.array(normals)


def face_centroids(mesh):
    return np.array([mesh.positions[face].mean(axis=0) for face in mesh.faces])


def test_every_builtin_loads_with_its_triangle_count(scenes):
    assert list(BUILTIN_SCENES) == list(TRIANGLES)
    for name, scene in scenes.items():
        assert isinstance(scene, Scene) and scene.name == name
        assert scene.triangle_count() == TRIANGLES[name], name
        assert BUILTIN_SCENES[name].name == name
    assert 10**4 <= scenes["terrain"].triangle_count() <= 10**5


@pytest.mark.parametrize("name", ["umbc_zbuffer", "painter", "sphere"])
def test_load_scene_builtin_prefix(name):
    scene = load_scene(f"builtin:{name}")
    assert scene.name == name and scene.triangle_count() == TRIANGLES[name]


def test_unknown_scene_and_parameter():
    with pytest.raises(ValueError, match="unknown built-in scene 'cube'; known: umbc_zbuffer"):
        builtin_scene("cube")
    with pytest.raises(ValueError, match=r"takes parameters \(n, seed\); got size"):
        builtin_scene("terrain", size=10)
    with pytest.raises(ValueError, match=r"takes parameters \(\); got n"):
        builtin_scene("painter", n=3)
    with pytest.raises(ValueError, match="unknown built-in scene"):
        load_scene("builtin:nope")


def project(scene, width, height):
    """Display coordinates (x, y, z_ndc) of every vertex of every object."""
    camera = scene.camera
    display_from_world = (
        display_from_ndc(width, height) @ clip_from_eye(camera) @ eye_from_world(camera)
    )
    points = []
    for obj in scene.objects:
        homogeneous = np.c_[obj.mesh.positions, np.ones(len(obj.mesh.positions))]
        clip = homogeneous @ (display_from_world @ obj.world_from_model).T
        points.append(clip[:, :3] / clip[:, 3:])
    return np.concatenate(points)


@pytest.mark.parametrize("name", ["umbc_zbuffer", "painter"])
def test_slide_coordinates_map_one_to_one(scenes, name):
    """Rendered at the listed raster, display (x, y) is the slides' (x, y) and depth z / 16."""
    scene, info = scenes[name], BUILTIN_SCENES[name]
    slide = np.concatenate([obj.mesh.positions for obj in scene.objects])
    display = project(scene, info.width, info.height)
    assert np.array_equal(display, slide * [1, 1, 1 / 16])


def test_slide_polygons_are_the_slides_in_red_green_blue(scenes):
    zbuffer = [o.mesh.positions.tolist() for o in scenes["umbc_zbuffer"].objects]
    assert zbuffer == [
        [[1, 1, 5], [7, 7, 5], [1, 7, 5]],
        [[3, 5, 9], [10, 5, 9], [10, 9, 9], [3, 9, 9]],
        [[2, 6, 3], [2, 3, 8], [7, 3, 3]],
    ]
    painter = [o.mesh.positions.tolist() for o in scenes["painter"].objects]
    assert painter == [
        [[6, 3, 10], [11, 5, 10], [2, 2, 10]],
        [[1, 2, 8], [12, 2, 8], [12, 6, 8], [1, 6, 8]],
        [[6, 5, 5], [14, 5, 5], [14, 10, 5], [6, 10, 5]],
    ]
    for name in ("umbc_zbuffer", "painter"):
        scene = scenes[name]
        colors = [o.material.color for o in scene.objects]
        assert colors == [(1, 0, 0), (0, 1, 0), (0, 0, 1)]
        for obj in scene.objects:
            assert not obj.mesh.closed
            assert (obj.material.ambient, obj.material.diffuse, obj.material.specular) == (1, 0, 0)
        assert scene.lights == () and scene.ambient == (1, 1, 1)


@pytest.mark.parametrize("name", ["sphere", "function_surface", "transparent_cube", "terrain"])
def test_camera_frames_the_scene(scenes, name):
    """Everything is in view and in depth range, and fills most of the raster's width."""
    info = BUILTIN_SCENES[name]
    assert (info.width, info.height) == (256, 256)
    display = project(scenes[name], info.width, info.height)
    low, high = display.min(axis=0), display.max(axis=0)
    assert (low >= [0, 0, 0]).all() and (high <= [256, 256, 1]).all()
    assert max(high[:2] - low[:2]) >= 0.7 * 256
    assert abs((low[0] + high[0]) / 2 - 128) < 20 and abs((low[1] + high[1]) / 2 - 128) < 20


def test_transparent_cube_hides_part_of_an_opaque_object(scenes):
    scene = scenes["transparent_cube"]
    sphere, cube = scene.objects
    assert sphere.material.transparency == 0 and cube.material.transparency == 0.5
    assert not cube.mesh.closed
    info = BUILTIN_SCENES["transparent_cube"]
    eye = np.array(scene.camera.eye)
    sphere_centre = sphere.world_from_model[:3, 3]
    assert np.linalg.norm(sphere_centre - eye) > np.linalg.norm(eye) + 1  # behind the cube
    cube_box = project(Scene((cube,), scene.camera), info.width, info.height)
    sphere_box = project(Scene((sphere,), scene.camera), info.width, info.height)
    overlap = np.minimum(cube_box.max(0), sphere_box.max(0)) - np.maximum(
        cube_box.min(0), sphere_box.min(0)
    )
    assert (overlap[:2] > 50).all()


@pytest.mark.parametrize(
    "mesh",
    [uv_sphere(), uv_sphere(2, 3), icosphere(0), icosphere(3)],
    ids=["uv", "uv-2-3", "ico0", "ico3"],
)
def test_spheres_have_unit_outward_normals_and_faces(mesh):
    assert np.allclose(np.linalg.norm(mesh.positions, axis=1), 1, atol=1e-12)
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1, atol=1e-12)
    assert (np.einsum("ij,ij->i", mesh.normals, mesh.positions) > 0.999).all()
    assert (np.einsum("ij,ij->i", newell_normals(mesh), face_centroids(mesh)) > 0).all()
    assert mesh.smooth and mesh.closed


def test_sphere_scene_normals(scenes):
    mesh = scenes["sphere"].objects[0].mesh
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1, atol=1e-12)
    assert (np.einsum("ij,ij->i", mesh.normals, mesh.positions) > 0).all()


def test_sphere_counts():
    assert [icosphere(level).triangle_count() for level in range(5)] == [
        20 * 4**level for level in range(5)
    ]
    assert len(icosphere(2).positions) == 162  # 10 * 4**level + 2: shared midpoints
    assert uv_sphere(16, 32).triangle_count() == 2 * 32 * 15
    quads = [f for f in uv_sphere(5, 7).faces if len(f) == 4]
    assert len(quads) == 7 * 3


def test_uv_sphere_quads_are_planar():
    mesh = uv_sphere(9, 13)
    for face in mesh.faces:
        corners = mesh.positions[face]
        if len(face) == 4:
            normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
            assert abs(np.dot(corners[3] - corners[0], normal)) < 1e-12


def test_torus_normals_and_orientation():
    mesh = torus(2.0, 0.5, 12, 8)
    assert mesh.triangle_count() == 2 * 12 * 8 and len(mesh.positions) == 96
    radial = mesh.positions * [1, 0, 1]
    ring = (
        2.0 * radial / np.linalg.norm(radial, axis=1)[:, None]
    )  # nearest point of the centre circle
    assert np.allclose(np.linalg.norm(mesh.positions - ring, axis=1), 0.5)
    assert np.allclose(mesh.normals, (mesh.positions - ring) / 0.5)
    mean_normals = np.array([mesh.normals[f].mean(axis=0) for f in mesh.faces])
    assert (np.einsum("ij,ij->i", newell_normals(mesh), mean_normals) > 0).all()


def test_box_faces_outward():
    mesh = box((2, 4, 6))
    assert np.array_equal(np.abs(mesh.positions), np.tile([1.0, 2.0, 3.0], (8, 1)))
    assert (np.einsum("ij,ij->i", newell_normals(mesh), face_centroids(mesh)) > 0).all()
    assert not mesh.smooth and mesh.closed and mesh.triangle_count() == 12


def test_function_surface_heights_are_exact(scenes):
    mesh = scenes["function_surface"].objects[0].mesh
    x, y, z = mesh.positions.T
    assert np.array_equal(z, np.exp(-(x**2) - y**2))
    assert len(mesh.positions) == 41 * 41 and x.min() == y.min() == -2 and x.max() == y.max() == 2
    assert not mesh.closed
    assert (newell_normals(mesh)[:, 2] > 0).all()  # counter-clockwise seen from above
    camera = scenes["function_surface"].camera
    assert (camera.eye, camera.look_at, camera.up) == ((6, 8, 3), (0, 0, 0), (0, 0, 1))


def test_function_surface_mesh_layout_and_errors():
    mesh = function_surface_mesh(lambda x, y: x + 10 * y, (0, 2), (0, 1), n=2)
    assert mesh.positions[2 * 3 + 1].tolist() == [1.0, 1.0, 11.0]  # row 2 (y), column 1 (x)
    with pytest.raises(ValueError, match="'xrange' must be finite with low < high"):
        function_surface_mesh(np.hypot, (1, 1))
    with pytest.raises(ValueError, match="'func' must return an array of shape"):
        function_surface_mesh(lambda x, y: 0.0)
    with pytest.raises(ValueError, match="non-finite heights"):
        function_surface_mesh(lambda x, y: np.where(x > 1, np.nan, x))
    with pytest.raises(TypeError, match="'n' must be an int"):
        function_surface_mesh(np.hypot, n=4.0)


def test_terrain_is_deterministic_and_sized():
    small = terrain(20, seed=3)
    assert small.triangle_count() == 2 * 20**2 and len(small.positions) == 21**2
    assert np.array_equal(small.positions, terrain(20, seed=3).positions)
    assert not np.array_equal(small.positions, terrain(20, seed=4).positions)
    z = small.positions[:, 2]
    assert z.min() == 0 and z.max() == 0.5
    assert set(np.unique(small.vertex_materials)) <= set(range(len(small.materials)))
    assert (small.vertex_materials[z == 0] == 0).all()  # the lake is water
    assert (newell_normals(small)[:, 2] > 0).all()
    assert builtin_scene("terrain", n=50, seed=1).triangle_count() == 5000


@pytest.mark.parametrize(
    "call, error, rule",
    [
        (lambda: icosphere(9), ValueError, r"'level' must be in 0..8; got 9"),
        (lambda: icosphere(True), TypeError, "'level' must be an int"),
        (lambda: uv_sphere(1, 8), ValueError, "'n_lat' must be in 2..4096"),
        (lambda: uv_sphere(4, 2), ValueError, "'n_lon' must be in 3..4096"),
        (lambda: box(0), ValueError, "'size' must be > 0 and <= 2e\\+99"),
        (lambda: box((1, 2)), ValueError, "'size' must be a number or 3 numbers"),
        (lambda: torus(minor_radius=-1), ValueError, "'minor_radius' must be > 0 and <= 5e\\+98"),
        (lambda: terrain(0), ValueError, "'n' must be in 1..2048"),
        (lambda: terrain(4, roughness=2), ValueError, r"'roughness' must be in \(0, 1\]"),
    ],
)
def test_generator_arguments_are_checked(call, error, rule):
    with pytest.raises(error, match=rule):
        call()


def test_builtin_meshes_registry():
    assert sorted(BUILTIN_MESHES) == ["box", "icosphere", "terrain", "torus", "uv_sphere"]
    assert BUILTIN_MESHES["icosphere"] is icosphere


@pytest.mark.parametrize(
    "generator, kwargs",
    [
        (torus, {"n_major": 4096, "n_minor": 4096}),
        (uv_sphere, {"n_lat": 4096, "n_lon": 4096}),
        (terrain, {"n": 2048}),
        (icosphere, {"level": 8}),
    ],
)
def test_issue8_d7_generators_refuse_over_the_memory_limit_before_allocating(generator, kwargs):
    import tracemalloc

    from scanviz.limits import ResourceLimitError, memory_limit

    tracemalloc.start()
    try:
        with memory_limit("64M"), pytest.raises(ResourceLimitError, match="over the memory limit"):
            generator(**kwargs)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 2**20  # refused from the parameters alone


def test_issue8_d7_the_estimate_covers_the_measured_peak():
    import tracemalloc

    from scanviz.limits import memory_limit

    for build in (lambda: torus(n_major=200, n_minor=100), lambda: terrain(128)):
        tracemalloc.start()
        build()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        with memory_limit(int(peak * 0.8)), pytest.raises(ValueError, match="over the memory"):
            build()  # a limit below the real peak is refused

"""The compiled fast Phong pass of render equals the loop over fast_phong_triangle, bit for bit."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import render
from scanviz.pipeline import fast_shade
from scanviz.scene import Camera, Light, Material, Mesh, Scene, SceneObject
from scanviz.scene.builtin import builtin_scene


def both(scene, width, height, monkeypatch, **options):
    """(compiled, reference) renders: the reference forced by refusing the int64 snap."""
    compiled = render(scene, width, height, shading="fast_phong", **options)
    with monkeypatch.context() as patch:
        patch.setattr(fast_shade, "_snap_batch", lambda *args: None)
        reference = render(scene, width, height, shading="fast_phong", **options)
    return compiled, reference


def assert_same(compiled, reference):
    assert np.array_equal(compiled.polygon, reference.polygon)
    assert compiled.stats.shaded_pixels == reference.stats.shaded_pixels
    assert np.array_equal(compiled.image, reference.image)  # bit for bit, background included


@pytest.mark.parametrize(
    ("name", "options"),
    [
        ("sphere", {}),
        ("sphere", {"sample": "center"}),
        ("function_surface", {}),
        ("umbc_zbuffer", {"subpixel_bits": 2}),
        ("painter", {"visibility": "painter"}),
    ],
)
def test_builtin_scenes_compiled_equal_the_reference(name, options, monkeypatch):
    compiled, reference = both(builtin_scene(name), 64, 48, monkeypatch, **options)
    assert compiled.stats.shaded_pixels > 200
    assert_same(compiled, reference)


def coloured_lights(scene: Scene) -> Scene:
    """Perspective, a coloured point light close by and a directional one: L and V per triangle."""
    lights = (
        Light(kind="point", position=(1.5, 1.0, 2.0), color=(1.0, 0.6, 0.3)),
        Light(direction=(0.4, -0.3, -1.0), color=(0.2, 0.3, 0.9)),
    )
    return dataclasses.replace(scene, lights=lights)


def test_point_lights_perspective_and_coloured_lights_are_summed_alike(monkeypatch):
    scene = coloured_lights(builtin_scene("sphere"))
    assert scene.camera.projection == "perspective"
    compiled, reference = both(scene, 56, 56, monkeypatch)
    assert_same(compiled, reference)
    # both lights reach the picture: it differs from each light alone
    alone = render(
        dataclasses.replace(scene, lights=scene.lights[:1]), 56, 56, shading="fast_phong"
    )
    assert not np.array_equal(alone.image, compiled.image)


def test_a_scene_larger_than_the_raster_is_clipped_alike(monkeypatch):
    scene = builtin_scene("sphere")
    window = (-0.1, 0.1, -0.08, 0.08)  # a third of the default window: the sphere fills it
    zoomed = dataclasses.replace(scene, camera=dataclasses.replace(scene.camera, window=window))
    compiled, reference = both(zoomed, 40, 30, monkeypatch)
    assert (compiled.polygon >= 0).all()  # every pixel is covered: triangles leave the raster
    assert_same(compiled, reference)


def test_the_centroid_expansion_is_the_same_in_both(monkeypatch):
    scene = builtin_scene("function_surface")
    compiled = fast_shade_image(scene, "centroid", compiled=True)
    reference = fast_shade_image(scene, "centroid", compiled=False)
    vertex = fast_shade_image(scene, "vertex", compiled=True)
    assert np.array_equal(compiled[0], reference[0]) and compiled[1] == reference[1] > 200
    assert not np.array_equal(compiled[0], vertex[0])  # the expansion point matters


def fast_shade_image(scene, expansion, *, compiled):
    """fast_phong_image on render's own prepared polygons and visibility."""
    from scanviz.pipeline.prepare import prepare

    width = height = 48
    result = render(scene, width, height, shading="fast_phong")
    prepared = prepare(scene, width, height, shading="fast_phong", cull=None)
    return fast_shade.fast_phong_image(
        scene, prepared.polygons, result, width, height, "corner", 8, expansion,
        compiled=compiled,
    )  # fmt: skip


def quad_scene(points, normals_tilt, exponent):
    """A random quadrilateral fan (two triangles) with per-vertex normals, seen orthographically."""
    positions = np.column_stack([points, np.zeros(4)])
    tilt = np.array(normals_tilt).reshape(4, 2)
    normals = np.column_stack([tilt, np.ones(4)])
    mesh = Mesh(positions, [[0, 1, 2, 3]], normals=normals, smooth=True, closed=False)
    camera = Camera(eye=(0.0, 0.0, 5.0), look_at=(0.0, 0.0, 0.0), projection="orthographic",
                    window=(-1.2, 1.2, -1.2, 1.2))  # fmt: skip
    material = Material(color=(0.9, 0.7, 0.5), specular=0.8, exponent=exponent)
    light = Light(direction=(-0.3, -0.2, -1.0))
    return Scene([SceneObject(mesh, material)], camera=camera, lights=(light,))


@settings(max_examples=25, deadline=None, derandomize=True)
@given(
    st.lists(st.floats(-1.0, 1.0), min_size=8, max_size=8),
    st.lists(st.floats(-0.6, 0.6), min_size=8, max_size=8),
    st.sampled_from([1.0, 10.0, 60.0]),
    st.sampled_from(["corner", "center"]),
)
def test_random_quadrilaterals_compiled_equal_the_reference(points, tilt, exponent, sample):
    scene = quad_scene(np.reshape(points, (4, 2)), tilt, exponent)
    compiled = render(scene, 33, 29, shading="fast_phong", sample=sample)
    reference_snap = fast_shade._snap_batch
    try:
        fast_shade._snap_batch = lambda *args: None
        reference = render(scene, 33, 29, shading="fast_phong", sample=sample)
    finally:
        fast_shade._snap_batch = reference_snap
    assert_same(compiled, reference)

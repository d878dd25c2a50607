"""RenderResult.relight: the image function again over the kept record equals a fresh render."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.pipeline import render
from scanviz.pipeline.result import RenderResult
from scanviz.scene import Camera, Light, Material, Scene, SceneObject, box, uv_sphere

SIZE = 40


def _translate(x, y, z, turn=0.0):
    matrix = np.eye(4)
    c, s = np.cos(turn), np.sin(turn)
    matrix[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    matrix[:3, 3] = x, y, z
    return matrix


def _painted_box():
    """A box whose faces and two corners have their own materials (blended across polygons)."""
    mesh = box(1.4)
    materials = (Material(color=(0.1, 0.7, 0.2), exponent=5.0), Material(color=(0.9, 0.9, 0.1)))
    vertex = np.full(len(mesh.positions), -1)
    vertex[:2] = 1
    return dataclasses.replace(
        mesh,
        materials=materials,
        face_materials=np.arange(len(mesh.faces)) % 2,
        vertex_materials=vertex,
    )


def _scene(projection="perspective"):
    """A sphere and a painted box; the box pokes out of the window, so some polygons are clipped."""
    sphere = SceneObject(uv_sphere(6, 10), Material(color=(0.8, 0.3, 0.2)), _translate(-0.4, 0, 0))
    painted = SceneObject(_painted_box(), Material(), _translate(1.1, 0.3, -0.5, turn=0.6))
    camera = Camera(eye=(0.0, 0.5, 4.0), window=(-1.2, 1.2, -1.2, 1.2), projection=projection)
    if projection == "perspective":
        camera = dataclasses.replace(camera, window=(-0.3, 0.3, -0.3, 0.3))
    lights = (Light(kind="point", position=(3.0, 4.0, 5.0)), Light(direction=(1.0, 0.2, -1.0)))
    return Scene((sphere, painted), camera, lights, ambient=(0.5, 0.5, 0.6), background=(0, 0, 0.2))


def _made_of(scene, materials):
    """The scene with object i wholly of materials[i]: relight's meaning of `materials`, built here."""
    objects = list(scene.objects)
    for i, material in materials.items():
        mesh = dataclasses.replace(
            objects[i].mesh, materials=(), face_materials=None, vertex_materials=None
        )
        objects[i] = dataclasses.replace(objects[i], material=material, mesh=mesh)
    return dataclasses.replace(scene, objects=tuple(objects))


def _direction(azimuth, elevation):
    a, e = np.radians(azimuth), np.radians(elevation)
    return (-np.cos(e) * np.sin(a), -np.sin(e), -np.cos(e) * np.cos(a))


colors = st.tuples(*[st.floats(0, 1)] * 3)
materials = st.builds(
    Material,
    color=colors,
    ambient=st.floats(0, 1),
    diffuse=st.floats(0, 1),
    specular=st.floats(0, 1),
    exponent=st.floats(0.5, 200),
)
directions = st.builds(_direction, st.floats(-180, 180), st.floats(-89, 89))


@settings(max_examples=12, deadline=None)
@given(
    direction=directions,
    color=colors,
    material=materials,
    which=st.sampled_from([{0}, {1}, {0, 1}]),
    shading=st.sampled_from(["phong", "gooch"]),
    first=st.sampled_from(["phong", "gooch"]),
    visibility=st.sampled_from(["zbuffer", "bsp", "depth_sort"]),
)
def test_relight_equals_a_fresh_render(
    direction, color, material, which, shading, first, visibility
):
    scene = _scene()
    lights = (Light(direction=direction, color=color),)
    chosen = {i: material for i in which}
    result = render(scene, SIZE, SIZE, shading=first, visibility=visibility)
    relit = result.relight(lights=lights, materials=chosen, shading=shading)
    fresh = render(
        dataclasses.replace(_made_of(scene, chosen), lights=lights),
        SIZE,
        SIZE,
        shading=shading,
        visibility=visibility,
    )
    np.testing.assert_array_equal(relit.image, fresh.image)
    np.testing.assert_array_equal(relit.polygon, fresh.polygon)
    assert str(relit.plan) == str(fresh.plan)


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
@pytest.mark.parametrize("visibility", ["zbuffer", "painter", "scanline", "warnock"])
def test_relight_with_point_lights_ambient_and_edges_equals_a_fresh_render(projection, visibility):
    scene = _scene(projection)
    lights = (Light(kind="point", position=(-2.0, 1.0, 3.0), color=(0.3, 0.9, 0.4)),)
    options = {"visibility": visibility, "edges": True}
    relit = render(scene, SIZE, SIZE, **options).relight(lights=lights, ambient=(0.1, 0.0, 0.3))
    fresh = render(
        dataclasses.replace(scene, lights=lights, ambient=(0.1, 0.0, 0.3)), SIZE, SIZE, **options
    )
    np.testing.assert_array_equal(relit.image, fresh.image)
    assert relit.stats.edge_pixels > 0


@pytest.mark.parametrize("shading", ["phong", "gooch"])
@pytest.mark.parametrize("visibility", ["zbuffer", "bsp", "scanline"])
def test_relight_without_arguments_is_the_original_image(shading, visibility):
    result = render(_scene(), SIZE, SIZE, shading=shading, visibility=visibility, edges=True)
    again = result.relight()
    np.testing.assert_array_equal(again.image, result.image)
    assert str(again.plan) == str(result.plan)
    assert again.image is not result.image


def test_relights_compose_and_the_sequence_form_equals_the_mapping_form():
    scene = _scene()
    shiny = Material(color=(0.2, 0.4, 1.0), specular=0.9, exponent=80.0)
    dull = Material(color=(1.0, 1.0, 1.0), specular=0.0)
    lights = (Light(direction=(0.0, -1.0, -0.2)),)
    result = render(scene, SIZE, SIZE)
    twice = result.relight(materials=[None, shiny]).relight(lights=lights, materials={0: dull})
    once = result.relight(lights=lights, materials={0: dull, 1: shiny})
    fresh = render(dataclasses.replace(_made_of(scene, {0: dull, 1: shiny}), lights=lights), 40, 40)
    np.testing.assert_array_equal(twice.image, fresh.image)
    np.testing.assert_array_equal(once.image, fresh.image)


def test_relight_with_no_lights_leaves_ambient_light_only():
    scene = _scene()
    relit = render(scene, SIZE, SIZE).relight(lights=())
    fresh = render(dataclasses.replace(scene, lights=()), SIZE, SIZE)
    np.testing.assert_array_equal(relit.image, fresh.image)
    sphere = relit.image[SIZE // 2, SIZE // 4]  # Od ka Ia on the sphere's middle
    np.testing.assert_allclose(sphere, np.array([0.8, 0.3, 0.2]) * 0.15 * np.array([0.5, 0.5, 0.6]))


def test_a_material_constant_over_a_polygon_reaches_the_shader_exactly():
    """Regression: interpolating a constant left it 1e-16 off, differently per pixel."""
    result = render(_scene(), SIZE, SIZE)
    sphere = result.record.polygon_object[result.polygon] == 0
    rows = result.visibility.values[sphere & (result.polygon >= 0)][:, 6:15]
    expected = [0.8, 0.3, 0.2, 0.15, 0.7, 0.3, 32.0, 0.0, 0.0]
    assert len(rows) > 100
    assert (rows == expected).all()


def test_a_traced_render_relights_to_the_untraced_image_without_a_trace():
    scene = _scene()
    lights = (Light(direction=(0.5, 0.5, -1.0)),)
    relit = render(scene, 16, 16, trace=True).relight(lights=lights)
    fresh = render(dataclasses.replace(scene, lights=lights), 16, 16)
    np.testing.assert_array_equal(relit.image, fresh.image)
    assert relit.trace is None


def test_a_transparent_material_changes_the_plan_as_a_fresh_render_says():
    glass = Material(transparency=0.5)
    relit = render(_scene(), 16, 16).relight(materials={0: glass})
    assert "transparency ignored by the z-buffer" in str(relit.plan)
    assert str(relit.plan) == str(render(_made_of(_scene(), {0: glass}), 16, 16).plan)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (
            {"shading": "flat"},
            "shading='flat' render fixes its colors per polygon before visibility",
        ),
        ({"shading": "gouraud"}, "shading='gouraud' render fixes its colors per vertex before"),
        ({"visibility": "abuffer"}, "visibility='abuffer' render packs every fragment"),
        ({"visibility": "flawed"}, "visibility='flawed' render packs every fragment"),
    ],
)
def test_renders_whose_colors_are_not_kept_refuse_to_relight(options, message):
    result = render(_scene(), 12, 12, **options)
    with pytest.raises(ValueError, match=message):
        result.relight(lights=())
    with pytest.raises(ValueError, match="re-render with scanviz.render"):
        result.relight()


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"shading": "flat"}, ValueError, r"'shading' must be one of \('phong', 'gooch'\)"),
        ({"shading": "toon"}, ValueError, "shading"),
        ({"lights": Light()}, TypeError, r"'lights' must be a tuple of Light \(one light"),
        ({"lights": (Light(), "sun")}, TypeError, r"'lights\[1\]' must be a Light"),
        ({"ambient": (2, 0, 0)}, ValueError, r"'ambient' components must be in \[0, 1\]"),
        (
            {"materials": {2: Material()}},
            ValueError,
            r"'materials' keys must be object indices 0..1",
        ),
        ({"materials": {True: Material()}}, ValueError, "'materials' keys must be object indices"),
        ({"materials": {0: "red"}}, TypeError, r"'materials\[0\]' must be a Material; got str"),
        ({"materials": [Material()]}, ValueError, r"one entry per scene object \(2\); got 1"),
        ({"materials": Material()}, TypeError, "'materials' must be a mapping"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    result = render(_scene(), 12, 12)
    with pytest.raises(error, match=message):
        result.relight(**arguments)


def test_a_result_not_made_by_render_cannot_be_relit():
    result = render(_scene(), 8, 8)
    bare = RenderResult(result.image, result.depth, result.polygon, result.stats, result.plan)
    with pytest.raises(ValueError, match="made by scanviz.render"):
        bare.relight()


def test_relight_is_bounded_by_the_memory_limit():
    result = render(_scene(), 64, 64)
    with memory_limit("64K"), pytest.raises(ResourceLimitError, match="relighting a 64x64"):
        result.relight(lights=())

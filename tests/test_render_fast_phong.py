"""render(shading="fast_phong"): every visible pixel shaded, exact Phong on flat facets up to the table."""

import dataclasses

import numpy as np
import pytest

from scanviz import render
from scanviz.scene import Camera, Light, Material, Mesh, Scene, SceneObject
from scanviz.scene.builtin import builtin_scene


def flat_plate(light: Light, material: Material) -> Scene:
    # Two triangles of one plane with equal normals: cos θ and cos φ are constant over each.
    positions = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [-1.0, 1.0, 0.0]])
    mesh = Mesh(positions, [[0, 1, 2], [0, 2, 3]], smooth=False, closed=False)
    camera = Camera(eye=(0.3, -0.2, 5.0), look_at=(0.0, 0.0, 0.0), projection="orthographic",
                    window=(-1.5, 1.5, -1.5, 1.5))  # fmt: skip
    return Scene(
        [SceneObject(mesh, material)], camera=camera, lights=(light,), ambient=(0.3, 0.3, 0.3)
    )


@pytest.mark.parametrize("exponent", [1.0, 8.0, 40.0])
def test_on_a_flat_facet_fast_phong_is_phong_but_for_the_tables_floor(exponent):
    material = Material(
        color=(0.8, 0.6, 0.4), ambient=0.2, diffuse=0.6, specular=0.5, exponent=exponent
    )
    scene = flat_plate(Light(direction=(-0.1, 0.2, -1.0)), material)
    fast = render(scene, 40, 40, shading="fast_phong")
    exact = render(scene, 40, 40, shading="phong")
    visible = fast.polygon >= 0
    assert visible.sum() > 500 and np.array_equal(fast.polygon, exact.polygon)
    gap = (exact.image - fast.image)[visible]
    # Exact: Isr c^n with Isr = 255 ks; fast: floor(N c^n) with N = floor(Isr) (the table's size),
    # so the highlight falls short by at most (Isr - N) c^n + 1 levels and never exceeds.
    isr = 255 * material.specular
    assert (gap >= -1e-12).all() and (gap <= (isr - np.floor(isr) + 1) / 255 + 1e-12).all()


def test_every_visible_pixel_is_shaded_and_the_plan_says_how():
    result = render(builtin_scene("sphere"), 48, 48, shading="fast_phong")
    visible = result.polygon >= 0
    assert result.stats.shaded_pixels == visible.sum() > 1000
    assert np.isfinite(result.image).all() and ((result.image >= 0) & (result.image <= 1)).all()
    background = np.array(builtin_scene("sphere").background)
    assert (result.image[visible] != background).any(axis=1).all()
    (stage,) = [s for s in result.plan.stages if s.name == "shade pixels"]
    assert stage.runs and "Taylor quadratics" in stage.why


def test_fast_phong_needs_an_opaque_visibility_and_cannot_be_relit():
    sphere = builtin_scene("sphere")
    with pytest.raises(ValueError, match="shading='fast_phong' shades the visible triangles"):
        render(sphere, 16, 16, shading="fast_phong", visibility="abuffer")
    painted = render(sphere, 24, 24, shading="fast_phong", visibility="painter")
    assert painted.stats.shaded_pixels == (painted.polygon >= 0).sum()
    with pytest.raises(ValueError, match="relight"):
        painted.relight(lights=(Light(),))


def test_a_scene_without_lights_is_its_ambient_colour():
    material = Material(color=(0.5, 0.5, 1.0), ambient=0.4, diffuse=0.6, specular=0.5)
    scene = dataclasses.replace(flat_plate(Light(), material), lights=())
    fast, exact = (
        render(scene, 24, 24, shading="fast_phong"),
        render(scene, 24, 24, shading="phong"),
    )
    visible = fast.polygon >= 0
    np.testing.assert_allclose(fast.image[visible], exact.image[visible], atol=1e-12)


def test_the_expansion_point_is_a_render_option_checked_by_name():
    sphere = builtin_scene("sphere", level=1)
    vertex = render(sphere, 64, 64, shading="fast_phong")
    centroid = render(sphere, 64, 64, shading="fast_phong", expansion="centroid")
    exact = render(sphere, 64, 64, shading="phong")
    shown = exact.polygon >= 0
    assert np.array_equal(vertex.polygon, centroid.polygon)

    def rms(result):
        return float(np.sqrt(((255 * (result.image - exact.image)[shown]) ** 2).mean()))

    # large triangles (about 12 px a side here): the centroid keeps the quadratic near every sample
    assert rms(centroid) < 0.6 * rms(vertex)
    assert np.array_equal(render(sphere, 64, 64, expansion="centroid").image, exact.image)
    with pytest.raises(ValueError, match="'expansion'"):
        render(sphere, 8, 8, shading="fast_phong", expansion="middle")


def test_a_replaced_step_reaches_render_through_the_reference_loop():
    from scanviz import steps

    sphere = builtin_scene("sphere", level=2)
    plain = render(sphere, 32, 32, shading="fast_phong")
    calls = []

    def counted(value, difference, t5):
        calls.append(1)
        return value + difference, difference + 2 * t5

    with steps.using(forward_difference=counted):
        same = render(sphere, 32, 32, shading="fast_phong")
    with steps.using(forward_difference=lambda value, difference, t5: (value, difference)):
        frozen = render(sphere, 32, 32, shading="fast_phong")
    assert calls and np.array_equal(same.image, plain.image)  # the loop equals the kernel
    assert not np.array_equal(frozen.image, plain.image)

"""The whole pipeline: render() against independent expectations, traced == compiled, plan, CLI."""

import dataclasses
import os

import matplotlib.image
import numpy as np
import pytest

from scanviz.cli import main
from scanviz.pipeline import render
from scanviz.scene import Light, Material, Scene
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder

RED, GREEN, BLUE = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)


def point_in_triangle(p, a, b, c):
    """Exact corner-sample test for small integer triangles via the ownership rule (p + (e, e^2))."""

    def side(u, v):
        e = (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0])
        return e if e else (-(v[1] - u[1]) or (v[0] - u[0]))  # first nonzero of (E, dE/dx, dE/dy)

    signs = [np.sign(side(a, b)), np.sign(side(b, c)), np.sign(side(c, a))]
    return all(s > 0 for s in signs) or all(s < 0 for s in signs)


def test_umbc_zbuffer_example_visible_polygon_per_pixel():
    # Slide polygons in screen space; smaller z is nearer. The green quad (z = 9) is behind
    # everything; the red triangle (z = 5) is in front of it; the blue triangle's depth
    # varies from 3 to 8, so red and blue cross.
    result = render(builtin_scene("umbc_zbuffer"), 12, 12, shading="flat")
    red = [(1, 1), (7, 7), (1, 7)]
    blue = [(2, 6, 3), (2, 3, 8), (7, 3, 3)]
    for y in range(12):
        for x in range(12):
            candidates = []
            if point_in_triangle((x, y), *red):
                candidates.append((5.0, 0, RED))
            if point_in_triangle((x, y), *[v[:2] for v in blue]):
                # plane through the blue vertices: z = 3 + 5 * (6 - y) / 3 ... solved exactly:
                (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = blue
                n = np.cross(np.subtract(blue[1], blue[0]), np.subtract(blue[2], blue[0]))
                z = z0 - (n[0] * (x - x0) + n[1] * (y - y0)) / n[2]
                candidates.append((z, 2, BLUE))
            if 3 <= x < 10 and 5 <= y < 9:
                candidates.append((9.0, 1, GREEN))
            expected = min(candidates)[2] if candidates else (0.0, 0.0, 0.0)
            assert tuple(result.image[y, x]) == pytest.approx(expected), (x, y)


@pytest.mark.parametrize("shading", ["flat", "gouraud", "phong", "gooch"])
@pytest.mark.parametrize("name", ["sphere", "function_surface"])
def test_traced_path_gives_the_compiled_image(name, shading):
    scene = builtin_scene(name)
    compiled = render(scene, 40, 40, shading=shading)
    traced = render(
        scene, 40, 40, shading=shading, trace=Recorder(kinds=["depth_test"], region=(0, 0, 4, 4))
    )
    assert compiled.stats.path == "compiled" and traced.stats.path == "reference"
    np.testing.assert_allclose(traced.image, compiled.image, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(traced.polygon, compiled.polygon)
    np.testing.assert_allclose(traced.depth, compiled.depth, rtol=0, atol=1e-12)
    assert dataclasses.replace(traced.stats, path="x") == dataclasses.replace(
        compiled.stats, path="x"
    )


def test_gouraud_of_a_constant_color_is_constant():
    sphere = builtin_scene("sphere")
    flat_white = Material(color=(0.6, 0.5, 0.4), ambient=1.0, diffuse=0.0, specular=0.0)
    obj = dataclasses.replace(sphere.objects[0], material=flat_white)
    scene = dataclasses.replace(sphere, objects=(obj,), lights=())
    affine = render(scene, 64, 64, shading="gouraud", perspective_correct=False)
    covered = affine.polygon >= 0
    assert covered.sum() > 1000
    np.testing.assert_array_equal(np.unique(affine.image[covered], axis=0), [[0.6, 0.5, 0.4]])
    # Perspective-correct: (c / w) interpolated over (1 / w) interpolated is c up to rounding.
    correct = render(scene, 64, 64, shading="gouraud")
    np.testing.assert_allclose(
        correct.image[covered],
        np.broadcast_to([0.6, 0.5, 0.4], (covered.sum(), 3)),
        rtol=0,
        atol=1e-15,
    )


def test_phong_highlight_lies_where_the_reflection_puts_it():
    sphere = builtin_scene("sphere")
    shiny = Material(color=(1, 1, 1), ambient=0.0, diffuse=0.0, specular=1.0, exponent=200.0)
    light = Light(kind="directional", direction=(-1.0, -1.0, -2.0))
    scene = dataclasses.replace(
        sphere, objects=(dataclasses.replace(sphere.objects[0], material=shiny),), lights=(light,)
    )
    size = 200
    result = render(scene, size, size, shading="phong")
    y, x = np.unravel_index(np.argmax(result.image[..., 0]), (size, size))
    # Analytic: on the unit sphere the highlight is where the normal bisects the directions to
    # the light and to the eye; find it on a fine grid of sphere points, then project it.
    theta, phi = np.meshgrid(np.linspace(0, np.pi, 1500), np.linspace(0, 2 * np.pi, 3000))
    points = np.stack(
        [np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], -1
    ).reshape(-1, 3)
    to_light = -np.array(light.direction) / np.linalg.norm(light.direction)
    to_eye = np.array(scene.camera.eye) - points
    to_eye /= np.linalg.norm(to_eye, axis=1, keepdims=True)
    halfway = to_light + to_eye
    halfway /= np.linalg.norm(halfway, axis=1, keepdims=True)
    best = points[np.argmax(np.einsum("ij,ij->i", points, halfway))]
    eye_z = scene.camera.eye[2] - best[2]  # camera looks down -z from (0, 0, 4)
    left, right, bottom, top = scene.camera.window
    near = scene.camera.near
    px = (best[0] * near / eye_z - left) / (right - left) * size
    py = (best[1] * near / eye_z - bottom) / (top - bottom) * size
    assert abs(x - px) <= 2 and abs(y - py) <= 2, ((x, y), (px, py))


def test_draw_order_of_objects_does_not_matter_for_distinct_depths():
    scene = builtin_scene("transparent_cube")
    reversed_scene = dataclasses.replace(scene, objects=scene.objects[::-1])
    a = render(scene, 64, 64, shading="phong")
    b = render(reversed_scene, 64, 64, shading="phong")
    np.testing.assert_array_equal(a.image, b.image)


def test_plan_and_stats_say_what_ran():
    sphere = render(builtin_scene("sphere"), 64, 64)
    assert (
        sphere.plan.runs("cull")
        and sphere.plan.runs("z-buffer")
        and not sphere.plan.runs("a-buffer")
    )
    assert "opaque scene without anti-aliasing" in str(sphere.plan)
    s = sphere.stats
    # From distance 4 a unit sphere shows a cap of (1 - 1/4) / 2 = 37.5% of its area: ~800 of
    # its 1280 faces face away.
    assert s.polygons_in == 1280 and 760 < s.culled < 850
    assert s.polygons_drawn == s.polygons_in - s.culled - s.off_screen
    assert (
        s.depth_passed + s.depth_failed == s.fragments
        and s.shaded_pixels == (sphere.polygon >= 0).sum()
    )
    surface = render(builtin_scene("function_surface"), 64, 64, shading="gouraud")
    assert not surface.plan.runs("cull") and surface.stats.culled == 0
    assert surface.stats.shaded_vertices > 0 and surface.stats.shaded_pixels == 0
    cube = render(builtin_scene("transparent_cube"), 32, 32)
    assert "transparency ignored by the z-buffer" in str(cube.plan)


def test_clipping_runs_only_when_the_view_cuts_polygons():
    sphere = builtin_scene("sphere")
    close = dataclasses.replace(
        sphere, camera=dataclasses.replace(sphere.camera, window=(-0.1, 0.1, -0.1, 0.1))
    )
    result = render(close, 48, 48)
    assert result.plan.runs("clip") and result.stats.clipped > 0
    assert (result.polygon >= 0).all()  # the sphere fills the narrowed view


def test_bad_arguments_name_the_rule():
    scene = builtin_scene("sphere")
    with pytest.raises(ValueError, match="'shading' must be one of"):
        render(scene, 8, 8, shading="toon")
    with pytest.raises(ValueError, match="'visibility' must be one of"):
        render(scene, 8, 8, visibility="sorted")
    with pytest.raises(TypeError, match="'scene' must be a scanviz.scene.Scene"):
        render("builtin:sphere", 8, 8)


def test_empty_scene_renders_the_background():
    scene = Scene(objects=(), background=(0.2, 0.3, 0.4))
    result = render(scene, 5, 4)
    assert result.image.shape == (4, 5, 3) and (result.image == [0.2, 0.3, 0.4]).all()
    assert np.isinf(result.depth).all() and (result.polygon == -1).all()


def test_cli_render_writes_the_image_and_plan(tmp_path, capsys):
    out = tmp_path / "sphere.png"
    assert (
        main(
            [
                "render",
                "builtin:sphere",
                "-o",
                str(out),
                "--width",
                "48",
                "--height",
                "40",
                "--plan",
            ]
        )
        == 0
    )
    printed = capsys.readouterr().out
    assert "run   z-buffer" in printed and "culled" in printed
    image = matplotlib.image.imread(out)
    assert image.shape[:2] == (40, 48)
    assert main(["render", "builtin:nonesuch", "-o", str(out)]) == 2


# --- issue 8 -----------------------------------------------------------------------------------

MODES = [
    (shading, visibility, perspective)
    for shading in ("flat", "gouraud", "phong", "gooch")
    for visibility in ("zbuffer", "abuffer", "flawed")
    for perspective in (True, False)
]


def assert_clean(result):
    """No NaN anywhere; image and alpha in [0, 1]; depth finite or +inf (background)."""
    assert (
        np.isfinite(result.image).all() and (0 <= result.image).all() and (result.image <= 1).all()
    )
    assert not np.isnan(result.depth).any() and not (result.depth == -np.inf).any()
    if result.alpha is not None:
        assert np.isfinite(result.alpha).all()
        assert (0 <= result.alpha).all() and (result.alpha <= 1).all()


def scene_at(scale, eye_distance, near, far, window, material=None, light=None):
    """The sphere scaled by `scale` and seen from `eye_distance` on +z."""
    from scanviz.scene import Camera, SceneObject

    sphere = builtin_scene("sphere", level=1)
    objects = [
        SceneObject(o.mesh, material or o.material, np.diag([scale, scale, scale, 1.0]))
        for o in sphere.objects
    ]
    camera = Camera(eye=(0, 0, eye_distance), near=near, far=far, window=window)
    return Scene(objects, camera=camera, lights=(light,) if light else sphere.lights)


@pytest.mark.parametrize("shading, visibility, perspective", MODES)
def test_issue8_d3_scenes_at_the_scene_limits_render(shading, visibility, perspective):
    huge_light = Light("point", color=(1e6, 1e6, 1e6), position=(0, 0, 1e99))
    scenes = [
        scene_at(1e98, 5e98, 1e97, 1e99, (-1e97, 1e97, -1e97, 1e97), light=huge_light),
        scene_at(1e-90, 5e-90, 1e-91, 1e-88, (-1e-91, 1e-91, -1e-91, 1e-91)),
        scene_at(
            1,
            5,
            1e-11,
            np.inf,
            (-1e-11, 1e-11, -1e-11, 1e-11),
            material=Material(exponent=1e4, fudge=1e99),
            light=huge_light,
        ),
    ]
    for scene in scenes:
        result = render(
            scene, 6, 5, shading=shading, visibility=visibility, perspective_correct=perspective
        )
        assert_clean(result)
        assert result.stats.polygons_drawn > 0


def test_issue8_d3_an_internal_bound_names_the_object_and_the_rule():
    from scanviz.pipeline.prepare import _screen_polygons

    xyzw = np.array([[0.0, 0, 0.5, 1], [0.5, 0, 0.5, 1], [0, 0.5, 0.5, 1]] * 2)
    values = np.zeros((6, 15))
    values[4, 12] = 1e200  # an exponent no scene allows, on a vertex of object 7
    with pytest.raises(ValueError, match=r"'objects\[7\]': its materials .* within \+-1e\+100"):
        _screen_polygons(
            xyzw, values, np.array([3, 3]), np.array([0, 0, 0, 7, 7, 7]), 4, 4, "phong"
        )


@pytest.mark.parametrize("visibility", ["zbuffer", "abuffer"])
def test_issue8_d4_render_never_returns_nan(visibility):
    sphere = builtin_scene("sphere", level=1)
    light = Light("point", position=(0, 0, 1))
    object.__setattr__(
        light, "position", (0.0, 0.0, 1e308)
    )  # past the scene limit, as in the issue
    scene = dataclasses.replace(sphere, lights=(light,))
    for shading in ("flat", "gouraud", "phong", "gooch"):
        assert_clean(render(scene, 16, 16, shading=shading, visibility=visibility))


def test_issue8_d7_a_render_too_large_is_refused_before_allocating():
    from scanviz.limits import ResourceLimitError, memory_limit

    with pytest.raises(ResourceLimitError, match="a 65536x65536 zbuffer render with phong"):
        render(builtin_scene("sphere", level=1), 65536, 65536)
    with memory_limit("16M"):
        with pytest.raises(ResourceLimitError, match="fragments of a 200x200 abuffer render"):
            render(builtin_scene("sphere", level=1), 200, 200, visibility="abuffer")
        render(builtin_scene("sphere", level=1), 60, 60, visibility="abuffer")  # fits


def test_issue8_d12_plan_estimates_the_work_and_large_renders_show_progress(monkeypatch, capsys):
    import scanviz.pipeline

    scene = builtin_scene("sphere", level=1)
    result = render(scene, 20, 20, visibility="abuffer")
    bound = result.stats.fragments_estimated
    assert result.stats.fragments <= bound <= 20 * 20 * result.stats.polygons_drawn
    assert f"at most {bound} fragments" in str(result.plan)
    monkeypatch.setattr(scanviz.pipeline.antialiased, "PROGRESS_POLYGONS", 10)
    render(scene, 20, 20, visibility="abuffer")
    assert "abuffer polygons" in capsys.readouterr().err


TINY_SIZES = [(1, 1), (3, 2), (17, 9), (0, 0), (4, 0)]
VARIANTS = [(None, False), (True, True), (False, False)]  # (cull, edges), cycled through the modes
# Built-ins with their parameters made small, so every mode runs in seconds; the a-buffer costs
# milliseconds per polygon. SCANVIZ_FULL_RENDER_MODES=1 runs them at their full size instead.
SMALL = {"sphere": {"level": 1}, "function_surface": {"n": 3}, "terrain": {"n": 2}}
FULL = os.environ.get("SCANVIZ_FULL_RENDER_MODES") == "1"


@pytest.mark.parametrize(
    "name", ["umbc_zbuffer", "painter", "sphere", "function_surface", "transparent_cube", "terrain"]
)
def test_every_builtin_scene_renders_in_every_mode_at_tiny_sizes(name):
    scene = builtin_scene(name, **({} if FULL else SMALL.get(name, {})))
    # transparent_cube has 567 polygons: its a-buffer runs in 4 of the 16 modes, at 1x1 only.
    slow = name == "transparent_cube" and not FULL
    for index, (shading, visibility, perspective) in enumerate(MODES):
        if slow and visibility != "zbuffer" and index % 4:
            continue
        sizes = [(1, 1)] if slow and visibility != "zbuffer" else TINY_SIZES
        for size_index, (width, height) in enumerate(sizes):
            cull, edges = VARIANTS[(index + size_index) % len(VARIANTS)]
            result = render(
                scene,
                width,
                height,
                shading=shading,
                visibility=visibility,
                perspective_correct=perspective,
                cull=cull,
                edges=edges,
            )
            assert result.image.shape == (height, width, 3)
            assert_clean(result)


def test_every_builtin_scene_is_covered_by_the_tiny_size_test():
    from scanviz.scene import BUILTIN_SCENES

    assert set(BUILTIN_SCENES) == {
        "umbc_zbuffer",
        "painter",
        "sphere",
        "function_surface",
        "transparent_cube",
        "terrain",
    }


def test_hostile_but_valid_geometry_renders_in_every_mode():
    from scanviz.scene import Camera, Mesh, SceneObject

    positions = [
        (0, 0, 0),
        (1, 1, 0),
        (2, 2, 0),  # collinear
        (0.5, 0.5, 0),
        (0.5, 0.5, 0),
        (0.7, 0.1, 0),  # a repeated vertex: two distinct corners
        (-1, -1, 4),
        (1, -1, 4),
        (0, 1, 4),  # exactly on the near plane (z = 4 is distance 1)
        (-1, -1, 6),
        (1, -1, 6),
        (0, 1, 3),  # through the eye plane z = 5
        (0.1, 0.1, -1),
        (0.1 + 1e-9, 0.1, -1),
        (0.1, 0.1 + 1e-9, -1),  # far below a sub-sample
    ]
    faces = [[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11], [12, 13, 14]]
    mesh = Mesh(positions, faces, closed=False, smooth=True)
    scene = Scene([SceneObject(mesh)], camera=Camera(near=1.0, far=50.0))
    for (shading, visibility, perspective), (width, height) in zip(
        MODES, [(5, 4), (1, 1), (3, 2)] * len(MODES), strict=False
    ):
        result = render(
            scene,
            width,
            height,
            shading=shading,
            visibility=visibility,
            perspective_correct=perspective,
            edges=True,
        )
        assert_clean(result)

"""`render(visibility=NAME)` with every opaque algorithm of `ALGORITHMS`, against the z-buffer.

On the built-in meshes every sample's nearest surface is unique by far more
than the tolerance: triangles meet only at shared edges, which cover each
sample once, and the layers a view crosses (front and back of the sphere,
the fold of the function surface, the cube's faces and the sphere inside)
are apart in depth. So an exact algorithm must give the z-buffer's image
bit for bit there; the test also checks that nearly every sample is
decided, so it cannot pass vacuously. The painter's algorithm is not exact:
its differing fraction is only bounded (it is 0 on these meshes, whose
nearest-vertex order happens to be a visibility order, at the time of
writing).
"""

import numpy as np
import pytest

import scanviz
from scanviz.bench.visibility import unique_nearest
from scanviz.pipeline import SHADINGS, VISIBILITIES, prepare
from scanviz.scene.builtin import builtin_scene
from scanviz.visibility import ALGORITHMS

SIZE = 40
SCENES = {  # name: (builtin, its parameters, cull); small meshes: the traced tests draw them too
    "sphere": ("sphere", {"level": 2}, None),
    "sphere, no culling": ("sphere", {"level": 2}, False),
    "function surface": ("function_surface", {"n": 14}, None),  # open: never culled
    "transparent cube": ("transparent_cube", {}, None),
}
PAINTER_BOUND = 0.02  # at most this fraction of the pixels differs from the z-buffer's


def scene_of(label):
    name, params, cull = SCENES[label]
    return builtin_scene(name, **params), cull


_references = {}


def reference(label, shading, **options):
    """The z-buffer's render and where the nearest is unique (cached per scene and shading)."""
    key = (label, shading, tuple(sorted(options.items())))
    if key not in _references:
        scene, cull = scene_of(label)
        zbuffer = scanviz.render(scene, SIZE, SIZE, shading=shading, cull=cull, **options)
        polygons = prepare(scene, SIZE, SIZE, shading=shading, cull=cull).polygons
        _references[key] = (zbuffer, unique_nearest(polygons, SIZE, SIZE))
    return _references[key]


def differing(result, zbuffer, unique) -> tuple[float, int]:
    """(fraction of pixels whose color differs, how many of them have a unique nearest)."""
    wrong = (result.image != zbuffer.image).any(axis=2)
    return float(wrong.mean()), int((wrong & unique).sum())


@pytest.mark.parametrize("name", list(ALGORITHMS))
@pytest.mark.parametrize("shading", SHADINGS)
@pytest.mark.parametrize("label", list(SCENES))
def test_every_algorithm_gives_the_zbuffers_image_where_the_nearest_is_unique(name, shading, label):
    scene, cull = scene_of(label)
    zbuffer, unique = reference(label, shading)
    result = scanviz.render(scene, SIZE, SIZE, shading=shading, cull=cull, visibility=name)
    assert unique.mean() > 0.99  # nearly every sample is decided: the check is not vacuous
    fraction, wrong_where_decided = differing(result, zbuffer, unique)
    if name == "painter":
        assert fraction <= PAINTER_BOUND
    else:
        assert wrong_where_decided == 0
        assert np.array_equal(result.polygon[unique], zbuffer.polygon[unique])
        assert np.array_equal(result.depth[unique], zbuffer.depth[unique])
    assert result.visibility.name == name


@pytest.mark.parametrize("name", list(ALGORITHMS))
def test_the_plan_names_the_algorithm(name):
    scene, cull = scene_of("sphere")
    plan = scanviz.render(scene, 8, 8, cull=cull, visibility=name).plan
    if name == "zbuffer":
        assert plan.runs("z-buffer") and not plan.runs("list priority / image space")
    else:
        assert plan.runs("list priority / image space") and not plan.runs("z-buffer")
        assert f"{name}: decides what is visible" in str(plan)


def test_an_unknown_visibility_is_refused_with_the_names():
    scene, _ = scene_of("sphere")
    with pytest.raises(ValueError, match="'visibility'") as error:
        scanviz.render(scene, 8, 8, visibility="nonsense")
    assert all(repr(name) in str(error.value) for name in VISIBILITIES)
    assert set(ALGORITHMS) <= set(VISIBILITIES)


@pytest.mark.parametrize("name", list(ALGORITHMS))
def test_an_instance_is_accepted_and_gives_the_names_image(name):
    scene, cull = scene_of("sphere, no culling")
    by_name = scanviz.render(scene, 24, 24, cull=cull, visibility=name)
    by_instance = scanviz.render(scene, 24, 24, cull=cull, visibility=ALGORITHMS[name]())
    assert np.array_equal(by_instance.image, by_name.image)
    assert by_instance.visibility.name == name


def test_an_instance_with_options_is_used():
    painter = ALGORITHMS["painter"]
    scene, cull = scene_of("function surface")
    result = scanviz.render(scene, 24, 24, cull=cull, visibility=painter(key="zmax"))
    assert result.visibility.algorithm.polygons > 0
    with pytest.raises(ValueError, match="'key'"):
        painter(key="nonsense")


@pytest.mark.parametrize("name", list(ALGORITHMS))
@pytest.mark.parametrize("label", ["sphere, no culling", "function surface"])
def test_edges_work_with_every_algorithm(name, label):
    scene, cull = scene_of(label)
    zbuffer, unique = reference(label, "phong", edges=True)
    result = scanviz.render(scene, SIZE, SIZE, cull=cull, visibility=name, edges=True)
    assert result.stats.edge_pixels > 0
    fraction, wrong_where_decided = differing(result, zbuffer, unique)
    if name == "painter":
        assert fraction <= PAINTER_BOUND
    else:
        assert wrong_where_decided == 0 and result.stats.edge_pixels == zbuffer.stats.edge_pixels


@pytest.mark.parametrize("name", list(ALGORITHMS))
@pytest.mark.parametrize("shading", ["flat", "phong"])
def test_a_traced_render_gives_the_untraced_image(name, shading):
    scene = builtin_scene("sphere", level=1)
    untraced = scanviz.render(scene, 16, 16, shading=shading, cull=False, visibility=name)
    traced = scanviz.render(scene, 16, 16, shading=shading, cull=False, visibility=name, trace=True)
    assert np.array_equal(traced.image, untraced.image)
    kinds = {event.kind for event in traced.trace}
    assert ("depth_test" if name == "zbuffer" else "pixel_painted") in kinds
    assert untraced.trace is None


@pytest.mark.parametrize("name", list(ALGORITHMS))
def test_cli_render_takes_every_algorithm(name, capsys):
    from scanviz.cli import main

    argv = ["render", "builtin:painter", "--width", "16", "--height", "12", "--plan"]
    assert main([*argv, "--visibility", name]) == 0
    out = capsys.readouterr().out
    assert ("run   z-buffer" if name == "zbuffer" else f"{name}: decides what is visible") in out


def test_cli_render_lists_every_visibility_of_the_pipeline():
    from scanviz.cli import VISIBILITY_NAMES

    assert set(VISIBILITIES) <= set(VISIBILITY_NAMES)

"""render(visibility="abuffer" | "flawed"): anti-aliasing through the whole pipeline."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import area_coverage, render
from scanviz.scene import Camera, Material, Mesh, Scene, SceneObject
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder

WHITE = Material(color=(1.0, 1.0, 1.0), ambient=1.0, diffuse=0.0, specular=0.0)
SIZE = 12


def screen_scene(*polygons, material=WHITE):
    """Polygons given in display pixels: an orthographic camera maps (x, y) 1:1 onto the raster."""
    objects = []
    for points in polygons:
        positions = [(x, y, -1.0) for x, y in points]
        objects.append(
            SceneObject(Mesh(positions, [list(range(len(points)))], closed=False), material)
        )
    camera = Camera(
        eye=(0, 0, 0),
        look_at=(0, 0, -1),
        window=(0, SIZE, 0, SIZE),
        near=0.5,
        far=2.0,
        projection="orthographic",
    )
    return Scene(objects, camera=camera, lights=(), background=(0.0, 0.0, 0.0))


TRIANGLE = [(1.3, 0.7), (10.2, 3.15), (4.6, 9.9)]


def test_single_polygon_coverage_is_its_exact_area():
    result = render(screen_scene(TRIANGLE), SIZE, SIZE, shading="flat", visibility="abuffer")
    exact = area_coverage(TRIANGLE, SIZE, SIZE)
    np.testing.assert_allclose(result.alpha, exact, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.image[..., 0], exact, rtol=0, atol=1e-12)  # white on black


def test_mask_weights_stay_within_the_sub_sample_bound():
    result = render(
        screen_scene(TRIANGLE),
        SIZE,
        SIZE,
        shading="flat",
        visibility="abuffer",
        mask="8x8",
        weights="mask",
    )
    error = np.abs(result.alpha - area_coverage(TRIANGLE, SIZE, SIZE))
    # A straight edge misplaces at most one sub-sample column per sub-row: 1/8 of a pixel per
    # edge crossing it; a pixel holds at most two edges of this triangle.
    assert error.max() <= 2 / 8 and 0 < error.max()


def test_adjacent_polygons_leave_no_seam_but_coverage_blending_does():
    quad = [(1.2, 1.1), (10.7, 2.3), (9.9, 10.6), (2.1, 9.4)]
    halves = screen_scene(quad[:3], [quad[0], quad[2], quad[3]])
    whole = area_coverage(quad, SIZE, SIZE)
    abuffer = render(halves, SIZE, SIZE, shading="flat", visibility="abuffer")
    np.testing.assert_allclose(abuffer.alpha, whole, rtol=0, atol=1e-9)
    inside = whole == 1.0
    assert inside.sum() > 40 and (np.abs(abuffer.image[inside] - 1) <= 1e-9).all()
    flawed = render(halves, SIZE, SIZE, shading="flat", visibility="flawed")
    assert flawed.image[inside].min() < 0.9  # the grey seam of the thesis' §6.3


def test_one_pixel_can_be_traced_through_insertion_and_packing():
    quad = [(1.2, 1.1), (10.7, 2.3), (9.9, 10.6), (2.1, 9.4)]
    scene = screen_scene(quad[:3], [quad[0], quad[2], quad[3]])
    recorder = Recorder(region=(5, 5, 6, 6))
    traced = render(scene, SIZE, SIZE, shading="flat", visibility="abuffer", trace=recorder)
    kinds = {event.kind for event in traced.trace if getattr(event, "x", 5) == 5}
    assert {"fragment_inserted", "pixel_packed"} <= kinds or "fragment_inserted" in kinds
    assert len(traced.fragments_at(5, 5)) >= 1
    compiled = render(scene, SIZE, SIZE, shading="flat", visibility="abuffer")
    np.testing.assert_allclose(traced.image, compiled.image, rtol=0, atol=1e-12)
    assert traced.fragments_at(5, 5) == compiled.fragments_at(5, 5)


@pytest.mark.parametrize("shading", ["flat", "gouraud", "phong"])
def test_traced_and_compiled_a_buffer_agree_on_a_3d_scene(shading):
    scene = builtin_scene("transparent_cube")
    compiled = render(scene, 24, 24, shading=shading, visibility="abuffer")
    traced = render(
        scene,
        24,
        24,
        shading=shading,
        visibility="abuffer",
        trace=Recorder(kinds=["pixel_packed"], region=(10, 10, 12, 12)),
    )
    np.testing.assert_allclose(traced.image, compiled.image, rtol=0, atol=1e-12)
    np.testing.assert_allclose(traced.alpha, compiled.alpha, rtol=0, atol=1e-12)


def test_transparent_objects_keep_their_back_faces_in_the_a_buffer():
    scene = builtin_scene("transparent_cube")
    sphere, cube = scene.objects
    closed_cube = dataclasses.replace(cube, mesh=dataclasses.replace(cube.mesh, closed=True))
    scene = dataclasses.replace(scene, objects=(sphere, closed_cube))
    opaque_view = render(scene, 32, 32, visibility="zbuffer")
    glass_view = render(scene, 32, 32, visibility="abuffer")
    assert glass_view.plan.runs("a-buffer") and not opaque_view.plan.runs("a-buffer")
    # A cube seen from a generic direction turns 3 of its 6 faces away: the a-buffer keeps them.
    assert glass_view.stats.culled == opaque_view.stats.culled - 3
    assert glass_view.abuffer.stats.pixels_list > 0


def test_fragments_at_needs_an_a_buffer_render():
    with pytest.raises(ValueError, match="visibility='abuffer'"):
        render(builtin_scene("sphere"), 8, 8).fragments_at(0, 0)


# --- issue 8 -----------------------------------------------------------------------------------


def issue8_d1_scene():
    """The issue's example: vertex 0 has exponent 0, vertices 1 and 2 exponent 1, on a 4x4 raster."""
    mesh = Mesh(
        [[0.75, 0.75, 0], [3.5, 0.75, 0], [0.75, 3.5, 0]],
        [[0, 1, 2]],
        closed=False,
        vertex_materials=[0, 1, 1],
        materials=(Material(exponent=0), Material(exponent=1)),
    )
    camera = Camera(
        eye=(0, 0, 5),
        look_at=(0, 0, 0),
        window=(0, 4, 0, 4),
        near=0.1,
        far=10,
        projection="orthographic",
    )
    return Scene([SceneObject(mesh)], camera=camera)


@pytest.mark.parametrize("visibility", ["abuffer", "flawed"])
@pytest.mark.parametrize("shading", ["phong", "gooch", "gouraud"])
def test_issue8_d1_fragments_are_shaded_inside_the_polygon(shading, visibility):
    result = render(issue8_d1_scene(), 4, 4, shading=shading, visibility=visibility)
    assert np.isfinite(result.image).all() and result.stats.fragments > 0
    # Pixel (3, 0)'s center (3.5, 0.5) is outside the triangle; its fragment is not.
    assert result.fragments_at(3, 0) or visibility == "flawed"


def test_issue8_d1_fragment_values_are_the_barycentric_values_at_the_covered_centroid():
    from fractions import Fraction

    from scanviz.abuffer import mask_to_grid
    from scanviz.abuffer.fragments import polygon_fragments

    triangle = [
        (Fraction(3, 4), Fraction(3, 4)),
        (Fraction(7, 2), Fraction(3, 4)),
        (Fraction(3, 4), Fraction(7, 2)),
    ]
    values = [[0.0], [1.0], [1.0]]  # the exponents of the issue's example
    found = polygon_fragments(
        np.array(triangle, float),
        np.zeros(3),
        np.ones(3),
        np.array(values),
        4,
        4,
        mask="8x8",
        perspective=False,
    )
    (ax, ay), (bx, by), (cx, cy) = triangle
    area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
    checked = 0
    for x, y, mask, value in zip(found.xs, found.ys, found.masks, found.values[:, 0], strict=True):
        assert 0.0 <= value <= 1.0
        rows, cols = np.nonzero(mask_to_grid(int(mask), "8x8"))
        if not len(rows):
            continue
        px = x + sum(Fraction(2 * int(i) + 1, 16) for i in cols) / len(cols)
        py = y + sum(Fraction(2 * int(j) + 1, 16) for j in rows) / len(rows)
        u = ((px - ax) * (cy - ay) - (cx - ax) * (py - ay)) / area  # weight of vertex b
        v = ((bx - ax) * (py - ay) - (px - ax) * (by - ay)) / area  # weight of vertex c
        assert value == pytest.approx(float(u + v), abs=1e-12)
        checked += 1
    assert checked >= 5


@settings(derandomize=True, max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(-2, 9), st.floats(-2, 9)), min_size=3, max_size=3),
    st.lists(st.floats(0.4, 0.6), min_size=9, max_size=9),
    st.lists(st.floats(0.01, 100), min_size=3, max_size=3),
    st.booleans(),
    st.sampled_from(["4x4", "8x8"]),
)
def test_issue8_d1_fragment_colors_stay_within_the_vertex_colors(xy, colors, w, perspective, mask):
    from scanviz.abuffer.fragments import polygon_fragments

    colors = np.array(colors).reshape(3, 3)
    found = polygon_fragments(
        np.array(xy), np.zeros(3), 1 / np.array(w), colors, 7, 7, mask=mask, perspective=perspective
    )
    if found is None:
        return
    assert found.values.shape == (len(found.xs), 3)
    assert (found.values >= colors.min(axis=0) - 1e-12).all()
    assert (found.values <= colors.max(axis=0) + 1e-12).all()


@pytest.mark.parametrize("name", ["umbc_zbuffer", "painter", "sphere", "transparent_cube"])
@pytest.mark.parametrize("visibility", ["abuffer", "flawed"])
def test_issue8_d2_flat_affine_a_buffer_renders(name, visibility):
    scene = builtin_scene(name)
    result = render(scene, 4, 4, shading="flat", visibility=visibility, perspective_correct=False)
    correct = render(scene, 4, 4, shading="flat", visibility=visibility)
    np.testing.assert_array_equal(result.image, correct.image)  # flat colors need no interpolation


@pytest.mark.parametrize("visibility", ["abuffer", "flawed"])
@pytest.mark.parametrize("shading", ["phong", "gooch"])
def test_issue8_d1_terrain_renders_through_the_a_buffer(shading, visibility):
    # The terrain's vertex materials differ in exponent: pixel-center planes made them negative.
    result = render(builtin_scene("terrain", n=4), 8, 8, shading=shading, visibility=visibility)
    assert np.isfinite(result.image).all() and result.stats.fragments > 0


def test_issue14_d2_an_interrupt_stops_the_compiled_fragments_between_chunks(monkeypatch):
    import scanviz.abuffer.fragments_compiled as fragment_kernels

    monkeypatch.setattr(fragment_kernels, "CHUNK_POLYGONS", 10)
    firsts, compiled = [], fragment_kernels.chunk_fragments

    def interrupted(*args):
        firsts.append(args[6])  # the chunk's first polygon
        if len(firsts) == 3:
            raise KeyboardInterrupt
        return compiled(*args)

    monkeypatch.setattr(fragment_kernels, "chunk_fragments", interrupted)
    with pytest.raises(KeyboardInterrupt):
        render(builtin_scene("sphere", level=1), 8, 8, visibility="abuffer")
    assert firsts == [0, 10, 20]


def test_issue14_d2_traced_fragments_stop_between_polygons(monkeypatch):
    import scanviz.abuffer.fragments

    drawn = []

    def interrupted(*args, polygon_index, **kwargs):
        drawn.append(polygon_index)
        if polygon_index == 3:
            raise KeyboardInterrupt
        return None

    monkeypatch.setattr(scanviz.abuffer.fragments, "polygon_fragments", interrupted)
    with pytest.raises(KeyboardInterrupt):
        render(builtin_scene("sphere", level=1), 8, 8, visibility="abuffer", trace=True)
    assert drawn == [0, 1, 2, 3]


@pytest.mark.parametrize("name", ["sphere", "terrain"])
def test_issue14_d2_object_merge_keeps_lists_short_and_the_sphere_unchanged(name):
    scene = builtin_scene(name, **({"level": 2} if name == "sphere" else {"n": 12}))
    plain = render(scene, 24, 24, visibility="abuffer")
    merged = render(scene, 24, 24, visibility="abuffer", merge="object")
    assert merged.abuffer.stats.fragments_object_merged > 0
    assert merged.abuffer.stats.longest_list <= plain.abuffer.stats.longest_list
    assert merged.abuffer.stats.pixels_simple >= plain.abuffer.stats.pixels_simple
    if name == "sphere":  # a convex surface: the merge changes the image by rounding only
        np.testing.assert_allclose(merged.image, plain.image, rtol=0, atol=1e-12)

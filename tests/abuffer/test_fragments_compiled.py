"""The compiled fragment pass, the treap insertion and the per-object merge against their references."""

import itertools
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.abuffer import Fragments, fragments_compiled, pixelstruct, resolve
from scanviz.abuffer.fragments import polygon_fragments
from scanviz.abuffer.fragments_compiled import FlatFragments, fragment_chunks
from scanviz.abuffer.merge import merge_by_object
from scanviz.pipeline import render
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder

WIDTH, HEIGHT = 9, 7
FULL = (1 << 64) - 1


def screen_polygons(polygons, value_count, rng):
    """A ScreenPolygons-like table of (N, 2) vertex arrays, with random depths and values."""
    xy = np.concatenate(polygons)
    count = len(xy)
    return SimpleNamespace(
        xy=xy,
        z=rng.uniform(-1, 1, count),
        inv_w=rng.uniform(0.25, 4, count),
        values=rng.uniform(-2, 2, (count, value_count)),
        offsets=np.r_[0, np.cumsum([len(p) for p in polygons])].astype(np.int64),
        count=len(polygons),
        value_count=value_count,
    )


def reference(table, width, height, **options):
    """Every polygon's `polygon_fragments`, joined in drawing order."""
    parts = []
    for p in range(table.count):
        rows = slice(table.offsets[p], table.offsets[p + 1])
        found = polygon_fragments(
            table.xy[rows], table.z[rows], table.inv_w[rows], table.values[rows],
            width, height, polygon_index=p, **options,
        )  # fmt: skip
        if found is not None:
            parts.append(FlatFragments.of_polygon(found, p))
    return FlatFragments.join(parts, table.value_count)


def compiled(table, width, height, **options):
    chunks = fragment_chunks(table, width, height, **options)
    return FlatFragments.join([found for _, found in chunks], table.value_count)


def assert_identical(got, expected):
    for name in FlatFragments.__dataclass_fields__:
        a, b = getattr(got, name), getattr(expected, name)
        assert a.dtype == b.dtype and a.shape == b.shape, name
        assert np.array_equal(a, b), name  # bit for bit (no tolerance)


@st.composite
def polygon(draw):
    """Convex, concave or self-intersecting; slivers, off-raster parts, dyadic or raw floats."""
    n = draw(st.integers(3, 10))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    shape = draw(st.sampled_from(["convex", "star", "random", "sliver", "degenerate"]))
    centre = rng.uniform(-3, [WIDTH + 3, HEIGHT + 3])
    radius = draw(st.sampled_from([0.05, 0.7, 3.0, 9.0]))
    if shape == "sliver":  # a thin needle: long and a hundredth of a pixel wide
        along = rng.uniform(-1, 1, 2) * radius
        xy = centre + np.outer(np.linspace(-1, 1, n), along)
        xy[1::2] += 0.01 * np.array([-along[1], along[0]]) / max(np.hypot(*along), 1e-9)
    elif shape == "degenerate":  # two distinct vertices at most, or collinear
        xy = np.repeat(centre[None], n, axis=0)
        xy[n // 2 :] += rng.uniform(-1, 1) * draw(st.sampled_from([0, 1]))
    else:
        angles = np.sort(rng.uniform(0, 2 * np.pi, n)) if shape != "random" else None
        radii = radius * (rng.uniform(0.2, 1, n) if shape == "star" else np.ones(n))
        if angles is None:
            xy = centre + rng.uniform(-radius, radius, (n, 2))
        else:
            xy = centre + radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])
    if draw(st.booleans()):  # on a 1/64 grid: compilable without snapping
        xy = np.round(xy * 64) / 64
    return xy


@settings(max_examples=50, derandomize=True, deadline=None)
@given(
    st.lists(polygon(), min_size=1, max_size=8),
    st.sampled_from([0, 15]),
    st.sampled_from(["4x4", "8x4", "8x8"]),
    st.sampled_from([8, None]),
    st.booleans(),
    st.integers(0, 2**32 - 1),
)
def test_compiled_pass_equals_polygon_fragments(
    polygons, value_count, mask, bits, perspective, seed
):
    table = screen_polygons(polygons, value_count, np.random.default_rng(seed))
    options = {"mask": mask, "subpixel_bits": bits, "perspective": perspective}
    assert_identical(
        compiled(table, WIDTH, HEIGHT, **options), reference(table, WIDTH, HEIGHT, **options)
    )


def test_chunks_and_reference_polygons_splice_in_drawing_order(monkeypatch):
    """Chunks of 2 polygons, unsnapped raw floats (made by the reference) between compiled ones."""
    rng = np.random.default_rng(3)
    polygons = [rng.uniform(-2, 10, (rng.integers(3, 7), 2)) for _ in range(11)]
    polygons[::2] = [np.round(p * 16) / 16 for p in polygons[::2]]
    table = screen_polygons(polygons, 4, rng)
    monkeypatch.setattr(fragments_compiled, "CHUNK_POLYGONS", 2)
    options = {"mask": "8x8", "subpixel_bits": None, "perspective": True}
    done = [count for count, _ in fragment_chunks(table, WIDTH, HEIGHT, **options)]
    assert done == [2, 2, 2, 2, 2, 1]
    assert_identical(
        compiled(table, WIDTH, HEIGHT, **options), reference(table, WIDTH, HEIGHT, **options)
    )


@pytest.mark.parametrize(
    "xy",
    [
        [(1, 1), (1, 1), (1, 1)],  # one distinct vertex
        [(1, 1), (4, 2), (1, 1), (4, 2)],  # two
        [(0, 0), (2, 2), (4, 4)],  # collinear: no area
        [(2.1, 2.1), (2.1004, 2.1), (2.1, 2.1004)],  # inside one pixel, between sub-samples
        [(-5, -5), (-1, -5), (-1, -1)],  # off the raster
        [(1, 1), (8, 1.001), (1, 1.002)],  # a sliver across pixels
    ],
)
def test_degenerate_polygons_as_the_reference(xy):
    table = screen_polygons([np.array(xy, dtype=float)], 3, np.random.default_rng(0))
    for bits in (8, None):
        options = {"mask": "8x8", "subpixel_bits": bits, "perspective": True}
        got = compiled(table, WIDTH, HEIGHT, **options)
        assert_identical(got, reference(table, WIDTH, HEIGHT, **options))


def test_terrain_polygons_equal_the_reference():
    """Real mesh polygons (a sample of the terrain's 51,200 at 32x32)."""
    from scanviz.pipeline.prepare import prepare

    scene = builtin_scene("terrain")
    polygons = prepare(scene, 32, 32, shading="phong", cull=None, tracer=None).polygons
    picked = range(0, polygons.count, 97)
    rows = [np.arange(polygons.offsets[p], polygons.offsets[p + 1]) for p in picked]
    index = np.concatenate(rows)
    table = SimpleNamespace(
        xy=polygons.xy[index], z=polygons.z[index], inv_w=polygons.inv_w[index],
        values=polygons.values[index], count=len(rows), value_count=polygons.values.shape[1],
        offsets=np.r_[0, np.cumsum([len(r) for r in rows])].astype(np.int64),
    )  # fmt: skip
    options = {"mask": "8x8", "subpixel_bits": 8, "perspective": True}
    assert_identical(compiled(table, 32, 32, **options), reference(table, 32, 32, **options))


# --- whole renders: compiled == traced ------------------------------------------------------


def assert_same_result(traced, fast):
    np.testing.assert_allclose(traced.image, fast.image, rtol=0, atol=1e-12)
    np.testing.assert_allclose(traced.alpha, fast.alpha, rtol=0, atol=1e-12)
    assert np.array_equal(traced.depth, fast.depth)
    assert np.array_equal(traced.polygon, fast.polygon)
    assert traced.stats.fragments == fast.stats.fragments
    a, b = traced.abuffer, fast.abuffer
    assert {**vars(a.stats), "path": ""} == {**vars(b.stats), "path": ""}
    height, width = traced.alpha.shape
    for y, x in itertools.product(range(height), range(width)):
        assert a.pixel(x, y) == b.pixel(x, y)


@pytest.mark.parametrize(
    ("scene", "shading", "merge"),
    [
        (("sphere", {"level": 2}), "phong", "none"),
        (("terrain", {"n": 10}), "gouraud", "none"),
        (("terrain", {"n": 10}), "phong", "object"),
    ],
)
def test_render_compiled_equals_traced(scene, shading, merge):
    scene = builtin_scene(scene[0], **scene[1])
    options = {"visibility": "abuffer", "shading": shading, "mask": "8x8", "merge": merge}
    fast = render(scene, 20, 20, **options)
    assert fast.abuffer.stats.path == "compiled"
    assert_same_result(render(scene, 20, 20, trace=Recorder(), **options), fast)
    with steps.using(insert_fragment=pixelstruct.insert_fragment):  # the reference, untraced
        assert_same_result(render(scene, 20, 20, **options), fast)


# --- insertion: treaps against the reference ---------------------------------------------


@st.composite
def stacks(draw):
    """Deep stacks in 2 pixels: few objects, colors and masks, so that fragments combine."""
    count = draw(st.integers(1, 60))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    halves = [0x0F0F0F0F0F0F0F0F, 0xF0F0F0F0F0F0F0F0, 2**32 - 1, FULL ^ (2**32 - 1)]
    masks = np.array(
        [FULL if r < 0.15 else halves[k] if r < 0.8 else int(b) for r, k, b in
         zip(rng.random(count), rng.integers(0, 4, count), rng.integers(0, 2**63, count), strict=True)],
        dtype=np.uint64,
    )  # fmt: skip
    area = np.where(masks == FULL, np.where(rng.random(count) < 0.8, 1.0, 0.9), 0.5)
    zmin = rng.integers(0, 8, count) / 8.0  # many ties
    palette = np.array([(1.0, 0, 0), (0, 1.0, 0), (0.5, 0.5, 0.5)])
    return Fragments(
        x=rng.integers(0, 2, count), y=np.zeros(count, np.int64), polygon=np.arange(count),
        object=rng.integers(0, 2, count), mask=masks, area=area, zmin=zmin,
        zmax=zmin + rng.integers(0, 3, count) / 8.0, color=palette[rng.integers(0, 3, count)],
        opacity=rng.choice([1.0, 1.0, 0.5], count),
    )  # fmt: skip


@settings(max_examples=60, derandomize=True, deadline=None)
@given(stacks(), st.sampled_from(["none", "object"]))
def test_insertion_equals_the_reference_on_deep_stacks(fragments, merge):
    traced = resolve(fragments, 2, 1, trace=Recorder(), merge=merge)
    fast = resolve(fragments, 2, 1, merge=merge)
    np.testing.assert_allclose(traced.image, fast.image, rtol=0, atol=1e-12)
    assert {**vars(traced.stats), "path": ""} == {**vars(fast.stats), "path": ""}
    for x in range(2):
        assert traced.pixel(x, 0) == fast.pixel(x, 0)


def test_long_transparent_list_keeps_every_fragment_sorted():
    """1,000 transparent fragments in one pixel, drawn in random depth order."""
    rng = np.random.default_rng(5)
    count = 1000
    zmin = rng.permutation(count) / count
    fragments = Fragments(
        x=np.zeros(count, np.int64), y=np.zeros(count, np.int64), polygon=np.arange(count),
        object=np.arange(count), mask=np.full(count, FULL, np.uint64), area=np.ones(count),
        zmin=zmin, zmax=zmin, color=rng.random((count, 3)), opacity=np.full(count, 0.5),
    )  # fmt: skip
    result = resolve(fragments, 1, 1)
    assert result.stats.longest_list == count and result.stats.fragments_discarded == 0
    assert [r.z for r in result.pixel(0, 0)] == sorted(zmin.tolist())


# --- the per-object merge ---------------------------------------------------------------


def test_object_merge_joins_overlapping_ranges_of_one_object():
    left, right = 0x0F0F0F0F0F0F0F0F, 0xF0F0F0F0F0F0F0F0
    rows = [
        dict(x=0, y=0, mask=left, area=0.5, zmin=0.1, zmax=0.3, color=(1, 0, 0), object=1),
        dict(x=0, y=0, mask=right, area=0.25, zmin=0.3, zmax=0.4, color=(0, 1, 0), object=1),
        dict(x=0, y=0, mask=right, area=0.5, zmin=0.35, zmax=0.5, color=(0, 0, 1), object=2),
        dict(x=0, y=0, mask=left, area=0.5, zmin=0.6, zmax=0.7, color=(1, 1, 1), object=1),
    ]
    merged, count = merge_by_object(Fragments.from_rows(rows), 1, 1, FULL)
    assert count == 1
    assert merged.polygon.tolist() == [0, 2, 3]  # drawing order of each cluster's first
    assert merged.mask[0] == FULL and merged.area[0] == 0.75
    assert (merged.zmin[0], merged.zmax[0]) == (0.1, 0.4)
    assert merged.color[0].tolist() == [2 / 3, 1 / 3, 0.0]


def test_object_merge_makes_a_complete_fragment_of_two_halves():
    """Two Phong-shaded halves of one surface: different colors, areas summing to 1 - ulp."""
    left, right = 0x0F0F0F0F0F0F0F0F, 0xF0F0F0F0F0F0F0F0
    rows = [
        dict(x=0, y=0, mask=left, area=0.3, z=0.5, color=(1, 0, 0)),
        dict(x=0, y=0, mask=right, area=0.7 - 1e-16, z=0.5, color=(0.9, 0, 0)),
        dict(x=0, y=0, mask=FULL, area=1.0, z=0.8, color=(0, 0, 1), object=5),
    ]
    plain = resolve(Fragments.from_rows(rows), 1, 1)
    merged = resolve(Fragments.from_rows(rows), 1, 1, merge="object")
    assert plain.stats.pixels_list == 1 and len(plain.pixel(0, 0)) == 3
    assert merged.stats.pixels_simple == 1 and merged.stats.fragments_object_merged == 1
    assert len(merged.pixel(0, 0)) == 1 and merged.pixel(0, 0)[0].area == 1.0


def test_bad_merge_is_named():
    with pytest.raises(ValueError, match="merge"):
        resolve(Fragments.from_rows([]), 1, 1, merge="surface")

"""Warnock's area subdivision against the z-buffer and against exact per-sample oracles.

The oracles never use the quadtree: coverage is each polygon drawn alone by
the z-buffer (`support.polygon_depths`), and "nearest" is the first polygon
with the least plane depth at the sample (`Surfaces.depth`), as the
algorithm's documentation promises sample by sample.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import scanviz.visibility.warnock  # noqa: F401  (registers "warnock")
from scanviz import render
from scanviz.io import load_scene
from scanviz.pipeline import SHADINGS
from scanviz.trace import Recorder
from scanviz.visibility import ScreenPolygons, Surfaces, examples, solve, zbuffer
from scanviz.visibility.warnock import CASES, Quadtree, Warnock, WarnockStats, quadrants
from tests.visibility.support import assert_agrees, polygon_depths, random_scene

EXAMPLES = max(settings.default.max_examples // 5, 1)
seeds = st.integers(0, 2**32 - 1)
rasters = st.sampled_from([(16, 16), (23, 17), (7, 31), (32, 5), (13, 13)])
modes = st.sampled_from(["corner", "center"])


def scene(seed, n, size, interpenetrating):
    return random_scene(np.random.default_rng(seed), n, size, interpenetrating)


def covers(polygons, width, height, **options) -> np.ndarray:
    """(P, H, W) bool: the samples each polygon covers, drawn alone by the z-buffer."""
    return np.isfinite(polygon_depths(polygons, width, height, **options))


def first_nearest(polygons, width, height, **options) -> np.ndarray:
    """(H, W) the first covering polygon of least plane depth at each sample (-1: none)."""
    if not polygons.count:
        return np.full((height, width), -1)
    surfaces = Surfaces.of(polygons, width, height, **options)
    ys, xs = np.mgrid[0:height, 0:width].astype(float)
    planes = np.array([surfaces.depth(p, xs, ys) for p in range(polygons.count)])
    planes = np.where(covers(polygons, width, height, **options), planes, np.inf)
    return np.where(np.isfinite(planes.min(axis=0)), np.argmin(planes, axis=0), -1)


def area_events(trace):
    return [e for e in trace if e.kind == "area_classified"]


# --- agreement ---------------------------------------------------------------------------


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 8), raster=rasters, sample=modes)
def test_agrees_with_the_zbuffer_without_interpenetration(seed, n, raster, sample):
    assert_agrees("warnock", scene(seed, n, max(raster), False), *raster, sample=sample)


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(2, 8), raster=rasters, sample=modes)
def test_agrees_with_the_zbuffer_with_interpenetration(seed, n, raster, sample):
    assert_agrees("warnock", scene(seed, n, max(raster), True), *raster, sample=sample)


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 8), raster=rasters, sample=modes, prune=st.booleans())
def test_every_sample_shows_the_first_nearest_covering_polygon(seed, n, raster, sample, prune):
    polygons = scene(seed, n, max(raster), True)
    result = solve(Warnock(prune=prune), polygons, *raster, sample=sample)
    assert np.array_equal(result.polygon, first_nearest(polygons, *raster, sample=sample))


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 8), raster=rasters, sample=modes)
def test_coverage_is_the_zbuffer_s_union(seed, n, raster, sample):
    polygons = scene(seed, n, max(raster), True)
    result = solve("warnock", polygons, *raster, sample=sample)
    reference = zbuffer(polygons, *raster, sample=sample)
    assert np.array_equal(result.polygon >= 0, reference.polygon >= 0)
    assert np.array_equal(np.isinf(result.depth), np.isinf(reference.depth))


SLIDES = [
    (examples.slides_painter, (16, 12)),
    (examples.slides_zbuffer, (10, 9)),
    (examples.cyclic_overlap, (24, 24)),
    (examples.interpenetrating, (16, 12)),
    (examples.long_behind_short, (16, 12)),
]


@pytest.mark.parametrize("example, size", SLIDES)
@pytest.mark.parametrize("sample", ["corner", "center"])
def test_the_slides_examples_are_the_zbuffer_s(example, size, sample):
    _, _, where = assert_agrees("warnock", example(), *size, sample=sample)
    assert where.all() or sample == "center"  # no ties at the corner samples: all are checked


def test_the_slides_zbuffer_example_gives_the_slides_map():
    # The literal map of the UMBC slides (as in the z-buffer's docstring), top row first.
    expected = np.array(
        [
            [0, 0, 0, 2, 2, 2, 2, 2, 2, 2],
            [0, 0, 0, 2, 2, 2, 2, 2, 2, 2],
            [0, 1, 1, 1, 1, 1, 2, 2, 2, 2],
            [0, 1, 3, 3, 1, 2, 2, 2, 2, 2],
            [0, 1, 1, 1, 3, 3, 0, 0, 0, 0],
            [0, 1, 1, 3, 3, 3, 3, 0, 0, 0],
            [0, 1, 0, 0, 0, 0, 0, 0, 0, 0],
            [0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
            [0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        ]
    )
    result = solve("warnock", examples.slides_zbuffer(), 10, 9)
    assert np.array_equal(result.polygon[::-1] + 1, expected)
    assert result.algorithm.pixel > 0  # the sloped triangle pierces the first: decided per sample


# --- the classification ------------------------------------------------------------------


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 6), raster=rasters, sample=modes)
def test_each_area_is_classified_as_its_samples_say(seed, n, raster, sample):
    """Without pruning every area lists exactly the polygons covering one of its samples."""
    polygons = scene(seed, n, max(raster), True)
    covered = covers(polygons, *raster, sample=sample)
    nearest = first_nearest(polygons, *raster, sample=sample)
    result = solve(Warnock(prune=False), polygons, *raster, sample=sample, trace=True)
    for e in area_events(result.trace):
        inside = covered[:, e.y_start : e.y_end, e.x_start : e.x_end]
        meeting = tuple(np.flatnonzero(inside.any(axis=(1, 2))).tolist())
        assert e.polygons == meeting, e
        shown = nearest[e.y_start : e.y_end, e.x_start : e.x_end]
        if e.case == "empty":
            assert not meeting
        elif e.case == "surrounding":
            assert inside[e.visible].all() and (shown == e.visible).all(), e
        elif e.case == "single":
            assert meeting == (e.visible,) and not inside[e.visible].all(), e
        elif e.case == "pixel":
            assert shown.shape == (1, 1) and shown[0, 0] == e.visible and len(meeting) > 1, e
        else:
            assert e.case == "subdivide" and e.visible == -1 and len(meeting) > 1, e


def test_a_polygon_over_an_area_s_pixels_but_none_of_its_samples_is_disjoint():
    # Center sampling: the near square reaches x = y = 4.4, into the pixels of column and
    # row 4, but not to their samples at 4.5: the other quadrants see only the far polygon.
    polygons = ScreenPolygons.from_polygons(
        [
            [(0, 0, 0.9), (8, 0, 0.9), (8, 8, 0.9), (0, 8, 0.9)],
            [(0, 0, 0.1), (4.4, 0, 0.1), (4.4, 4.4, 0.1), (0, 4.4, 0.1)],
        ]
    )
    trace = Recorder(kinds=["area_classified"])
    result = solve("warnock", polygons, 8, 8, sample="center", trace=trace)
    shown = [((e.x_start, e.y_start), e.case, e.visible, e.polygons) for e in result.trace]
    assert shown[:5] == [
        ((0, 0), "subdivide", -1, (0, 1)),
        ((0, 0), "surrounding", 1, (0, 1)),
        ((4, 0), "surrounding", 0, (0,)),
        ((0, 4), "surrounding", 0, (0,)),
        ((4, 4), "surrounding", 0, (0,)),
    ]
    assert (
        result.algorithm.areas
        == solve("warnock", polygons, 8, 8, sample="center").algorithm.areas
        == 5
    )


def test_in_front_is_decided_at_the_extreme_samples_not_the_pixel_corners():
    # On a 2 x 2 raster the near polygon's plane rises above the far one's at x = 1.5: beyond
    # the last sample column (x = 1) but inside its pixels. At the samples it is in front.
    polygons = ScreenPolygons.from_polygons(
        [
            [(-1, -1, 0.5), (4, -1, 0.5), (4, 4, 0.5), (-1, 4, 0.5)],
            [(-1, -1, 0.25), (4, -1, 0.75), (4, 4, 0.75), (-1, 4, 0.25)],  # z = 0.35 + 0.1 x
        ]
    )
    result = solve("warnock", polygons, 2, 2, trace=Recorder(kinds=["area_classified"]))
    (event,) = result.trace
    assert (event.case, event.visible, event.polygons) == ("surrounding", 1, (0, 1))
    assert (result.polygon == 1).all()
    assert solve("warnock", polygons, 2, 2).algorithm.areas == 1  # the compiled walk too


def test_a_near_tie_is_left_to_the_samples():
    # Two polygons in one plane: neither is in front by the tolerance, so the raster is cut
    # down to its samples, each shown with the lower index, as the z-buffer keeps the earlier.
    square = [(0, 0, 0.5), (4, 0, 0.5), (4, 4, 0.5), (0, 4, 0.5)]
    polygons = ScreenPolygons.from_polygons([square, square])
    result = solve("warnock", polygons, 4, 4)
    stats = result.algorithm
    assert (result.polygon == 0).all() and stats.pixel == 16 and stats.depth == 2
    assert np.array_equal(result.polygon, zbuffer(polygons, 4, 4).polygon)


def test_pruning_changes_the_work_not_the_image():
    polygons = scene(7, 30, 48, True)
    pruned, textbook = (solve(Warnock(prune=p), polygons, 48, 40) for p in (True, False))
    assert np.array_equal(pruned.polygon, textbook.polygon)
    assert pruned.algorithm.tests < textbook.algorithm.tests


# --- the quadtree and the trace ----------------------------------------------------------


def check_tiles(boxes, x0, x1, y0, y1):
    """The boxes (x0, x1, y0, y1) cover the rectangle each sample once."""
    count = np.zeros((y1 - y0, x1 - x0), int)
    for a, b, c, d in boxes:
        assert x0 <= a < b <= x1 and y0 <= c < d <= y1
        count[c - y0 : d - y0, a - x0 : b - x0] += 1
    assert (count == 1).all()


def boxes(tree: Quadtree, which) -> list[tuple[int, int, int, int]]:
    return [
        (int(tree.x_start[i]), int(tree.x_end[i]), int(tree.y_start[i]), int(tree.y_end[i]))
        for i in which
    ]


@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(0, 8), raster=rasters, sample=modes)
def test_children_tile_their_parent_and_leaves_tile_the_raster(seed, n, raster, sample):
    polygons = scene(seed, n, max(raster), True)
    result = solve("warnock", polygons, *raster, sample=sample)
    tree = result.detail
    assert isinstance(tree, Quadtree) and tree.parent[0] == -1 and tree.level[0] == 0
    check_tiles(boxes(tree, np.flatnonzero(tree.leaves())), 0, raster[0], 0, raster[1])
    for area in range(len(tree)):
        children = tree.children(area)
        if tree.leaves()[area]:
            assert len(children) == 0
            continue
        assert len(children) in (2, 4) and (tree.level[children] == tree.level[area] + 1).all()
        check_tiles(boxes(tree, children), *boxes(tree, [area])[0])
        assert (children > area).all()  # depth first: children after their parent
    one_sample = (tree.x_end - tree.x_start) * (tree.y_end - tree.y_start) == 1
    assert one_sample[tree.case == CASES.index("pixel")].all()
    stats = result.algorithm
    counts = [stats.empty, stats.surrounding, stats.single, stats.subdivide, stats.pixel]
    assert counts == np.bincount(tree.case, minlength=5).tolist() and sum(counts) == stats.areas
    assert stats.depth == tree.level.max()


@settings(max_examples=EXAMPLES)
@given(
    seed=seeds,
    n=st.integers(0, 8),
    raster=rasters,
    sample=modes,
    bits=st.sampled_from([8, 2, None]),
    prune=st.booleans(),
)
def test_traced_equals_untraced(seed, n, raster, sample, bits, prune):
    polygons = scene(seed, n, max(raster), True)
    options = {"sample": sample, "subpixel_bits": bits}
    untraced = solve(Warnock(prune=prune), polygons, *raster, **options)
    traced = solve(Warnock(prune=prune), polygons, *raster, **options, trace=True)
    for buffer in ("polygon", "depth", "values"):
        assert np.array_equal(getattr(traced, buffer), getattr(untraced, buffer)), buffer
    for name in Quadtree.__dataclass_fields__:
        assert np.array_equal(getattr(traced.detail, name), getattr(untraced.detail, name)), name
    assert untraced.algorithm.path == "compiled"
    expected = {**vars(untraced.algorithm), "path": "traced reference"}
    assert traced.algorithm == WarnockStats(**expected)
    events = area_events(traced.trace)
    tree = traced.detail
    assert [(e.level, e.x_start, e.x_end, e.y_start, e.y_end) for e in events] == list(
        zip(*(tree.level, tree.x_start, tree.x_end, tree.y_start, tree.y_end), strict=True)
    )
    assert [e.case for e in events] == tree.cases()
    assert [e.visible for e in events] == tree.visible.tolist()
    assert [len(e.polygons) for e in events] == tree.meeting.tolist()


# --- degenerate input and the pipeline ---------------------------------------------------


def _polygons(*polygons) -> ScreenPolygons:
    return ScreenPolygons.from_polygons(list(polygons))


DEGENERATE = {
    "coplanar": (
        _polygons(
            [(0, 0, 0.5), (6, 0, 0.5), (6, 6, 0.5), (0, 6, 0.5)],
            [(3, 2, 0.5), (9, 2, 0.5), (9, 9, 0.5), (3, 9, 0.5)],
        ),
        (9, 9),
    ),
    "edge-on": (
        _polygons(
            [(0, 0, 0.5), (8, 0, 0.5), (8, 8, 0.5), (0, 8, 0.5)],
            [(1, 1, 0.1), (4, 4, 0.5), (7, 7, 0.9)],
        ),
        (8, 8),
    ),
    "empty": (ScreenPolygons.from_polygons([]), (5, 3)),
    "1x1 raster": (
        _polygons(
            [(-1, -1, 0.5), (3, -1, 0.5), (-1, 3, 0.5)], [(0, 0, 0.2), (2, 0, 0.9), (0, 2, 0.9)]
        ),
        (1, 1),
    ),
    "off the raster": (
        _polygons(
            [(20, 20, 0.5), (30, 20, 0.5), (20, 30, 0.5)],
            [(-9, 1, 0.2), (-1, 1, 0.2), (-1, 6, 0.2)],
        ),
        (8, 8),
    ),
    "no samples": (_polygons([(0.2, 0.2, 0.5), (0.8, 0.2, 0.5), (0.8, 0.8, 0.5)]), (4, 4)),
    "empty raster": (_polygons([(0, 0, 0.5), (4, 0, 0.5), (0, 4, 0.5)]), (0, 3)),
}


@pytest.mark.parametrize("case", list(DEGENERATE))
@pytest.mark.parametrize("trace", [None, True])
def test_degenerate_input_renders_as_the_zbuffer(case, trace):
    polygons, (width, height) = DEGENERATE[case]
    result = solve("warnock", polygons, width, height, trace=trace)
    assert np.array_equal(result.polygon, zbuffer(polygons, width, height).polygon)
    assert (len(result.detail) == 0) == (width * height == 0)


def test_the_options_are_checked():
    with pytest.raises(TypeError, match="'prune' must be a bool"):
        Warnock(prune="yes")


def test_quadrants_halve_each_side():
    assert quadrants(0, 4, 0, 4) == [(0, 2, 0, 2), (2, 4, 0, 2), (0, 2, 2, 4), (2, 4, 2, 4)]
    assert quadrants(3, 4, 0, 3) == [(3, 4, 0, 1), (3, 4, 1, 3)]


@pytest.mark.parametrize("shading", SHADINGS)
def test_render_with_every_shading_is_the_zbuffer_s_image(shading):
    sphere = load_scene("builtin:sphere")
    result = render(sphere, 48, 40, shading=shading, visibility="warnock")
    reference = render(sphere, 48, 40, shading=shading)
    assert result.visibility.name == "warnock"
    assert np.array_equal(result.image, reference.image)

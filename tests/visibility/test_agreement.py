"""Every visibility algorithm against the z-buffer, the oracle (issue 10, deliverable 8).

Parametrized over `ALGORITHMS` as registered: an algorithm that is not
registered is not in the parameters (and `test_the_issue_algorithms_are_registered`
says which). Where the nearest surface is unique by more than
`support.TOLERANCE`, an exact algorithm shows the z-buffer's polygon, depth
and values (`support.assert_agrees`): on random scenes without
interpenetration for every algorithm but the painter's, with
interpenetration for the algorithms that split. The painter's algorithm
differs on the slides' cyclic overlap (where no order of whole polygons is
right: checked over every order), the splitting ones do not. Traced and
untraced runs give the same buffers bit for bit; degenerate input renders.
"""

from itertools import permutations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.bench.visibility import random_triangles
from scanviz.conventions import SAMPLE_MODES
from scanviz.visibility import (
    ALGORITHMS,
    Painter,
    ScreenPolygons,
    Surfaces,
    examples,
    solve,
    zbuffer,
)
from scanviz.visibility.draw_decisions import paint
from tests.visibility.support import assert_agrees, random_scene, unique_nearest

EXAMPLES = max(settings.default.max_examples // 5, 1)  # SCANVIZ_MAX_EXAMPLES scales these too
ISSUE_ALGORITHMS = ("zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock")
SPLITTING = ("depth_sort", "bsp", "scanline", "warnock")
NAMES = [name for name in ALGORITHMS if name != "zbuffer"]
EXACT = [name for name in NAMES if name != "painter"]  # right wherever nothing interpenetrates
SPLITS = [name for name in NAMES if name in SPLITTING]  # right with interpenetration too
SIZE = 24
seeds = st.integers(0, 2**32 - 1)


def scene(seed: int, n: int, interpenetrating: bool) -> ScreenPolygons:
    return random_scene(np.random.default_rng(seed), n, SIZE, interpenetrating)


def test_the_issue_algorithms_are_registered():
    missing = [name for name in ISSUE_ALGORITHMS if name not in ALGORITHMS]
    assert not missing, f"not in scanviz.visibility.ALGORITHMS (not imported?): {missing}"


@pytest.mark.parametrize("name", EXACT)
@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 10), sample=st.sampled_from(SAMPLE_MODES))
def test_agrees_with_the_zbuffer_without_interpenetration(name, seed, n, sample):
    assert_agrees(name, scene(seed, n, False), SIZE, SIZE, sample=sample)


@pytest.mark.parametrize("name", SPLITS)
@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(2, 10), sample=st.sampled_from(SAMPLE_MODES))
def test_agrees_with_the_zbuffer_with_interpenetration(name, seed, n, sample):
    assert_agrees(name, scene(seed, n, True), SIZE, SIZE, sample=sample)


@pytest.mark.parametrize("name", SPLITS)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_agrees_on_the_benchmarks_crowded_scenes(name, seed):
    polygons = random_triangles(150, 40, 32, seed)  # depth complexity 4, some interpenetrating
    _, _, where = assert_agrees(name, polygons, 40, 32)
    assert where.mean() > 0.99


@pytest.mark.parametrize("name", EXACT)
@pytest.mark.parametrize(
    "example, size",
    [(examples.slides_painter, (16, 12)), (examples.long_behind_short, (16, 12))],
)
def test_agrees_on_the_slides_scenes_without_interpenetration(name, example, size):
    assert_agrees(name, example(), *size)


@pytest.mark.parametrize("name", SPLITS)
@pytest.mark.parametrize(
    "example, size",
    [
        (examples.cyclic_overlap, (24, 24)),
        (examples.interpenetrating, (16, 12)),
        (examples.slides_zbuffer, (10, 9)),
    ],
)
def test_agrees_on_the_slides_cycles_and_interpenetration(name, example, size):
    _, _, where = assert_agrees(name, example(), *size)
    assert where.all()  # these scenes have no ties: every sample is decided


def wrong_samples(polygon: np.ndarray, polygons: ScreenPolygons, width: int, height: int) -> int:
    """Samples where `polygon` is not the z-buffer's polygon although the nearest is unique."""
    where = unique_nearest(polygons, width, height)
    return int((where & (polygon != zbuffer(polygons, width, height).polygon)).sum())


def test_no_order_of_whole_polygons_paints_the_cyclic_overlap_right():
    polygons = examples.cyclic_overlap()
    surfaces = Surfaces.of(polygons, 24, 24)
    for order in permutations(surfaces.pieces()):
        painted = paint(surfaces, list(order), "over")
        assert wrong_samples(painted.polygon, polygons, 24, 24) > 0, [p.label for p in order]


@pytest.mark.parametrize("key", ["zmin", "zmax", "centroid"])
def test_the_painters_algorithm_differs_on_the_cyclic_overlap(key):
    result = solve(Painter(key=key), examples.cyclic_overlap(), 24, 24)
    assert wrong_samples(result.polygon, examples.cyclic_overlap(), 24, 24) > 0


def test_the_painters_algorithm_differs_on_interpenetration_and_a_long_polygon():
    for example in (examples.interpenetrating, examples.long_behind_short):
        polygons = example()
        assert wrong_samples(solve("painter", polygons, 16, 12).polygon, polygons, 16, 12) > 0


@pytest.mark.parametrize("name", list(ALGORITHMS))
@settings(max_examples=max(EXAMPLES // 2, 1))
@given(
    seed=seeds,
    n=st.integers(1, 5),
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from([8, None]),
)
def test_traced_equals_untraced(name, seed, n, sample, bits):
    polygons = scene(seed, n, True)
    options = {"sample": sample, "subpixel_bits": bits}
    untraced = solve(name, polygons, 16, 16, **options)
    traced = solve(name, polygons, 16, 16, **options, trace=True)
    assert traced.trace is not None and untraced.trace is None
    for buffer in ("polygon", "depth", "values"):
        a, b = getattr(traced, buffer), getattr(untraced, buffer)
        assert a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes(), buffer


def _polygons(*polygons) -> ScreenPolygons:
    values = [np.column_stack([np.full(len(p), i), [v[2] for v in p]]) for i, p in enumerate(polygons)]  # fmt: skip
    return ScreenPolygons.from_polygons(list(polygons), values)


DEGENERATE = {
    "empty": (
        ScreenPolygons(
            xy=np.zeros((0, 2)),
            z=np.zeros(0),
            inv_w=np.zeros(0),
            values=np.zeros((0, 2)),
            offsets=np.array([0]),
        ),
        (8, 8),
    ),
    "one polygon": (_polygons([(1, 1, 0.5), (7, 2, 0.6), (2, 7, 0.4)]), (8, 8)),
    "coplanar overlapping": (
        _polygons(
            [(0, 0, 0.5), (6, 0, 0.5), (6, 6, 0.5), (0, 6, 0.5)],
            [(3, 2, 0.5), (8, 2, 0.5), (8, 8, 0.5), (3, 8, 0.5)],
            [
                (1, 1, 0.2),
                (7, 1, 0.26),
                (1, 7, 0.2),
            ],  # a sloped pair in one plane z = 0.19 + 0.01 x
            [(2, 2, 0.21), (7, 2, 0.26), (7, 7, 0.26)],
        ),
        (8, 8),
    ),
    "edge-on": (
        _polygons(
            [(0, 0, 0.5), (8, 0, 0.5), (8, 8, 0.5), (0, 8, 0.5)],
            [(1, 1, 0.2), (4, 4, 0.5), (7, 7, 0.8)],  # collinear on the screen
            [(2, 5, 0.1), (2, 5, 0.1), (6, 1, 0.3)],  # two vertices in one
        ),
        (8, 8),
    ),
    "off the raster": (
        _polygons(
            [(20, 20, 0.5), (30, 20, 0.5), (20, 30, 0.5)],
            [(-9, 1, 0.2), (-1, 1, 0.2), (-1, 6, 0.2)],
            [(1, -9, 0.3), (6, -9, 0.9), (3, -2, 0.1)],
            [(2, 2, 0.7), (6, 2, 0.7), (2, 6, 0.7)],
        ),
        (8, 8),
    ),
    "1x1 raster": (
        _polygons(
            [(-1, -1, 0.5), (3, -1, 0.5), (-1, 3, 0.5)],
            [(0, 0, 0.2), (1, 0, 0.9), (0, 1, 0.9)],
            [(-5, -5, 0.1), (0.5, -5, 0.8), (0.5, 0.5, 0.1)],
        ),
        (1, 1),
    ),
    "empty raster": (_polygons([(0, 0, 0.5), (4, 0, 0.5), (0, 4, 0.5)]), (0, 3)),
}


@pytest.mark.parametrize("name", list(ALGORITHMS))
@pytest.mark.parametrize("case", list(DEGENERATE))
@pytest.mark.parametrize("sample", SAMPLE_MODES)
@pytest.mark.parametrize("bits", [8, None])
def test_degenerate_input_renders(name, case, sample, bits):
    polygons, (width, height) = DEGENERATE[case]
    options = {"sample": sample, "subpixel_bits": bits}
    results = [solve(name, polygons, width, height, **options, trace=t) for t in (None, True)]
    for result in results:
        assert result.polygon.shape == result.depth.shape == (height, width)
        assert result.values.shape == (height, width, polygons.value_count)
    assert np.array_equal(results[0].polygon, results[1].polygon)
    assert np.array_equal(results[0].values, results[1].values)
    if width and height:  # no depth order is at stake here: even the painter's must agree
        assert_agrees(name, polygons, width, height, **options)

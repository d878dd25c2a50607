"""The z-buffer: the UMBC slide example, exact oracles, invariants, and traced == compiled.

Golden values: the UMBC CMSC 435 z-buffer example against an independent
per-pixel oracle (exact winding number and exact plane depth in Fractions),
also written out as a literal map checked by hand. Invariants: draw-order
independence, coplanar triangles covering each sample once, constant and
linear attributes, perspective-correct recovery. Cross-implementation: the
traced reference and the compiled kernel agree bit for bit, and coverage is
`scan_convert`'s.
"""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Recorder, scan_convert
from scanviz.conventions import SAMPLE_MODES
from scanviz.trace import Trace
from scanviz.visibility import ScreenPolygons, zbuffer
from tests.oracle import snapped_contours, winding_number

BASE = settings.default.max_examples  # SCANVIZ_MAX_EXAMPLES scales every property test
PATHS = {"reference": True, "compiled": None}  # the `trace` argument that selects each path
F = Fraction


def exact_plane(vertices):
    """Newell's plane of exact (x, y, z) vertices through their centroid: a function z(x, y)."""
    n = len(vertices)
    a = b = c = F(0)
    for (x0, y0, z0), (x1, y1, z1) in zip(vertices, vertices[1:] + vertices[:1], strict=True):
        a += (y0 - y1) * (z0 + z1)
        b += (z0 - z1) * (x0 + x1)
        c += (x0 - x1) * (y0 + y1)
    cx, cy, cz = (sum(v[k] for v in vertices) / n for k in range(3))
    return lambda x, y: cz - (a * (x - cx) + b * (y - cy)) / c


def exact_vertices(polygon, bits):
    """A polygon's (x, y, z) rows as Fractions, x and y snapped as scanviz snaps them."""
    xy = snapped_contours([[(x, y) for x, y, _ in polygon]], bits)[0]
    return [(x, y, F(float(z))) for (x, y), (_, _, z) in zip(xy, polygon, strict=True)]


def covered(mask) -> list[tuple[int, int]]:
    """(y, x) of the True samples of `mask`, as Python ints (exact with Fractions)."""
    return [(int(y), int(x)) for y, x in np.argwhere(mask)]


def oracle(polygons, width, height, sample="corner", bits=8):
    """Visible polygon per sample (-1 for none) and its exact depth, independently of scanviz."""
    offset = F(1, 2) if sample == "center" else F(0)
    exact = [exact_vertices(p, bits) for p in polygons]
    planes = [exact_plane(v) for v in exact]
    ids = np.full((height, width), -1)
    depth = np.full((height, width), None, dtype=object)
    for y in range(height):
        for x in range(width):
            sx, sy = x + offset, y + offset
            for p, vertices in enumerate(exact):
                if winding_number([[(vx, vy) for vx, vy, _ in vertices]], sx, sy):
                    z = planes[p](sx, sy)
                    if depth[y, x] is None or z < depth[y, x]:  # ties keep the earlier polygon
                        ids[y, x], depth[y, x] = p, z
    return ids, depth


# --- the UMBC example ---------------------------------------------------------------------

UMBC = [
    [(1, 1, 5), (7, 7, 5), (1, 7, 5)],
    [(3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)],
    [(2, 6, 3), (2, 3, 8), (7, 3, 3)],
]
# Visible polygon + 1 (0 = none), top row (y = 11) first. Polygon 2 has the plane
# z = 15 - x - 5y/3 (through (2,6,3), (2,3,8), (7,3,3)). By hand:
#   (2, 3): polygon 0 (y >= x) at 5 vs polygon 2 at its owned corner, z = 8: polygon 0.
#   (2, 5): polygon 0 at 5 vs polygon 2 on its owned left edge x = 2, z = 14/3: polygon 2.
#   (4, 4): on polygon 0's right edge y = x, not owned (the sample is read as
#           (4 + e, 4 + e^2), below the line); polygon 2, z = 13/3.
#   (3, 6): polygon 0 at 5, the square at 9; polygon 2 needs y <= 6 - 3/5 (x - 2): polygon 0.
#   (6, 6): on polygon 0's right edge again: the square, at 9.
#   (1, 7), (2, 9): on top edges (not owned): nothing.
UMBC_VISIBLE = np.array(
    [
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 2, 2, 2, 2, 2, 2, 2, 0, 0],
        [0, 0, 0, 2, 2, 2, 2, 2, 2, 2, 0, 0],
        [0, 1, 1, 1, 1, 1, 2, 2, 2, 2, 0, 0],
        [0, 1, 3, 3, 1, 2, 2, 2, 2, 2, 0, 0],
        [0, 1, 1, 1, 3, 3, 0, 0, 0, 0, 0, 0],
        [0, 1, 1, 3, 3, 3, 3, 0, 0, 0, 0, 0],
        [0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
    ]
)[::-1]


def test_umbc_oracle_gives_the_literal_map():
    ids, _ = oracle(UMBC, 12, 12)
    np.testing.assert_array_equal(ids + 1, UMBC_VISIBLE)


@pytest.mark.parametrize("path", PATHS)
def test_umbc_example(path):
    result = zbuffer(ScreenPolygons.from_polygons(UMBC), 12, 12, trace=PATHS[path])
    np.testing.assert_array_equal(result.polygon + 1, UMBC_VISIBLE)
    _, exact = oracle(UMBC, 12, 12)
    drawn = result.polygon >= 0
    np.testing.assert_allclose(result.depth[drawn], exact[drawn].astype(float), rtol=0, atol=1e-14)
    assert (result.depth[~drawn] == np.inf).all()
    assert result.depth[5, 2] == pytest.approx(14 / 3, abs=1e-15)
    stats = result.stats
    assert (stats.polygons, stats.polygons_drawn, stats.fragments) == (3, 3, 54)
    assert stats.depth_passed + stats.depth_failed == stats.fragments
    assert stats.path == path


# --- random scenes -----------------------------------------------------------------------

WIDTH, HEIGHT = 16, 14


@st.composite
def scenes(draw, max_polygons=5, layered=False, values=2, far=False):
    """Overlapping triangles and quads (quads may self-intersect) with depths and attributes.

    `layered` puts polygon i's depths in [layer_i, layer_i + 0.5) for distinct
    integer layers, so no two polygons tie at any sample. `far` spreads the
    vertices over the whole coordinate range, +-2**20 px.
    """
    count = draw(st.integers(1, max_polygons))
    layers = draw(st.permutations(range(count)))
    coordinate = (
        st.floats(-(2.0**20), 2.0**20)
        if far
        else st.integers(-3 * 16, (WIDTH + 3) * 16).map(lambda v: v / 16)
    )
    unit = st.floats(0, 1, allow_nan=False)
    polygons, attributes, inv_w = [], [], []
    for p in range(count):
        n = draw(st.sampled_from([3, 4]))
        xy = draw(st.lists(st.tuples(coordinate, coordinate), min_size=n, max_size=n))
        z = [layers[p] + 0.5 * draw(unit) if layered else draw(unit) for _ in range(n)]
        polygons.append([(x, y, depth) for (x, y), depth in zip(xy, z, strict=True)])
        attributes.append(draw(st.lists(st.lists(unit, min_size=values, max_size=values), min_size=n, max_size=n)))  # fmt: skip
        inv_w.append([0.25 + draw(unit) for _ in range(n)])
    return polygons, attributes, inv_w


def pack(scene) -> ScreenPolygons:
    return ScreenPolygons.from_polygons(*scene)


@settings(max_examples=2 * BASE)
@given(
    scene=st.one_of(scenes(), scenes(max_polygons=3, far=True)),
    sample=st.sampled_from(SAMPLE_MODES),
    perspective=st.booleans(),
    bits=st.sampled_from([0, 4, 8, 16]),
)
def test_compiled_equals_reference(scene, sample, perspective, bits):
    """Also at +-2**20 px with 16 bits: crossings x = q + r/den with den up to 2**55."""
    polygons = pack(scene)
    options = dict(sample=sample, perspective=perspective, subpixel_bits=bits)
    compiled = zbuffer(polygons, WIDTH, HEIGHT, **options)
    reference = zbuffer(polygons, WIDTH, HEIGHT, trace=True, **options)
    assert (compiled.stats.path, reference.stats.path) == ("compiled", "reference")
    np.testing.assert_array_equal(compiled.polygon, reference.polygon)
    np.testing.assert_array_equal(compiled.depth, reference.depth)
    # One definition of every formula, one order of operations: the same bits (brief: 1e-12).
    np.testing.assert_array_equal(compiled.values, reference.values)
    assert {**vars(compiled.stats), "path": ""} == {**vars(reference.stats), "path": ""}


@settings(max_examples=BASE)
@given(scene=scenes(max_polygons=4), sample=st.sampled_from(SAMPLE_MODES))
def test_coverage_is_scan_convert(scene, sample):
    polygons = pack(scene)
    expected = np.zeros((HEIGHT, WIDTH), bool)
    for vertices in scene[0]:
        xy = [(x, y) for x, y, _ in vertices]
        single = zbuffer(ScreenPolygons.from_polygons([vertices]), WIDTH, HEIGHT, sample=sample)
        if single.stats.polygons_skipped:  # seen edge-on: zero signed area, draws nothing
            assert (single.polygon == -1).all()
            continue
        mask = scan_convert(xy, WIDTH, HEIGHT, sample=sample, rule="nonzero").mask
        np.testing.assert_array_equal(single.polygon == 0, mask)
        assert single.stats.fragments == mask.sum() == single.stats.depth_passed
        expected |= mask
    np.testing.assert_array_equal(
        zbuffer(polygons, WIDTH, HEIGHT, sample=sample).polygon >= 0, expected
    )


@settings(max_examples=BASE)
@given(
    scene=scenes(layered=True), seed=st.integers(0, 2**32 - 1), path=st.sampled_from(list(PATHS))
)
def test_draw_order_does_not_matter_when_depths_are_distinct(scene, seed, path):
    permutation = np.random.default_rng(seed).permutation(len(scene[0]))
    shuffled = tuple([part[i] for i in permutation] for part in scene)
    first = zbuffer(pack(scene), WIDTH, HEIGHT, trace=PATHS[path])
    second = zbuffer(pack(shuffled), WIDTH, HEIGHT, trace=PATHS[path])
    drawn = second.polygon >= 0
    relabeled = np.where(drawn, permutation[np.maximum(second.polygon, 0)], -1)
    np.testing.assert_array_equal(relabeled, first.polygon)
    np.testing.assert_array_equal(second.depth, first.depth)
    np.testing.assert_array_equal(second.values, first.values)


def test_ties_keep_the_earlier_polygon():
    square = [(0, 0, 0.5), (4, 0, 0.5), (4, 4, 0.5), (0, 4, 0.5)]
    shifted = [(x + 2, y, z) for x, y, z in square]
    for path in PATHS.values():
        result = zbuffer(ScreenPolygons.from_polygons([square, shifted]), 6, 4, trace=path)
        np.testing.assert_array_equal(result.polygon[0], [0, 0, 0, 0, 1, 1])
        assert result.stats.depth_failed == 8  # columns 2, 3 of polygon 1: equal depth fails


# --- coplanar pieces, attributes, perspective -------------------------------------------


@st.composite
def convex_quads(draw):
    """A convex quad (on a circle, counter-clockwise, 1/256 grid) and a plane z = c + a x + b y."""
    center = draw(st.tuples(st.floats(4, WIDTH - 4), st.floats(4, HEIGHT - 4)))
    radius = draw(st.floats(2, 7))
    gaps = draw(st.lists(st.floats(0.4, 1.0), min_size=4, max_size=4))
    angles = np.cumsum(gaps) / sum(gaps) * 2 * np.pi  # gaps of 0.4 : 1 keep corners away from 180
    xy = [
        (round((center[0] + radius * np.cos(t)) * 256) / 256, round((center[1] + radius * np.sin(t)) * 256) / 256)
        for t in angles + draw(st.floats(0, np.pi))
    ]  # fmt: skip
    a, b, c = draw(st.tuples(st.floats(-0.1, 0.1), st.floats(-0.1, 0.1), st.floats(0.2, 0.8)))
    return [(x, y, c + a * x + b * y) for x, y in xy]


@settings(max_examples=BASE)
@given(quad=convex_quads(), sample=st.sampled_from(SAMPLE_MODES))
def test_coplanar_triangles_sharing_an_edge_cover_the_quad_once(quad, sample):
    whole = zbuffer(ScreenPolygons.from_polygons([quad]), WIDTH, HEIGHT, sample=sample)
    halves = [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    split = zbuffer(ScreenPolygons.from_polygons(halves), WIDTH, HEIGHT, sample=sample)
    mask = scan_convert([(x, y) for x, y, _ in quad], WIDTH, HEIGHT, sample=sample).mask
    np.testing.assert_array_equal(split.polygon >= 0, mask)
    assert split.stats.fragments == mask.sum() == split.stats.depth_passed  # each sample once
    plane = exact_plane(exact_vertices(quad, 8))
    offset = 0.5 if sample == "center" else 0.0
    for y, x in covered(mask):
        exact = float(plane(F(x + offset), F(y + offset)))
        assert abs(split.depth[y, x] - exact) <= 1e-12
        assert abs(whole.depth[y, x] - exact) <= 1e-12


def barycentric_value(triangle, values, x, y):
    """The affine interpolant of per-vertex `values` over exact `triangle` at (x, y)."""
    (x0, y0), (x1, y1), (x2, y2) = triangle
    det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    l1 = ((x - x0) * (y2 - y0) - (x2 - x0) * (y - y0)) / det
    l2 = ((x1 - x0) * (y - y0) - (x - x0) * (y1 - y0)) / det
    return values[0] * (1 - l1 - l2) + values[1] * l1 + values[2] * l2


@settings(max_examples=BASE)
@given(scene=scenes(max_polygons=1, values=3), path=st.sampled_from(list(PATHS)))
def test_constant_and_linear_attributes(scene, path):
    (triangle, *_), (attributes, *_), _ = scene
    triangle = triangle[:3]
    attributes = [[0.625, a[1], a[2]] for a in attributes[:3]]  # 0: constant, 1 and 2: linear
    result = zbuffer(
        ScreenPolygons.from_polygons([triangle], [attributes]), WIDTH, HEIGHT, trace=PATHS[path]
    )
    drawn = result.polygon == 0
    assert (result.values[drawn, 0] == 0.625).all()  # Gouraud: a constant stays exactly constant
    assert (result.values[~drawn] == 0).all()
    exact = exact_vertices(triangle, 8)
    for y, x in covered(drawn):
        for k in (1, 2):
            expected = barycentric_value(
                [v[:2] for v in exact], [F(a[k]) for a in attributes], F(x), F(y)
            )
            assert abs(result.values[y, x, k] - float(expected)) <= 1e-9


def test_constant_attribute_with_perspective_is_constant_to_rounding():
    triangle = [(0.5, 0.25, 0.1), (30.0, 3.0, 0.5), (4.0, 28.0, 0.9)]
    scene = ScreenPolygons.from_polygons([triangle], [[(0.3,)] * 3], [[1.0, 0.1, 0.02]])
    result = zbuffer(scene, 32, 32, perspective=True)
    assert np.abs(result.values[result.polygon == 0] - 0.3).max() < 1e-14


def test_perspective_correct_recovers_eye_space_linear_attributes():
    """A triangle seen in perspective carries a(P) = 2X - Y + Z/2 + 3, linear in eye space.

    Its vertices are placed so that they project onto the sub-pixel grid (no
    snapping error); each sample's eye point is found exactly (Fractions) by
    intersecting its viewing ray with the triangle's plane.
    """
    focal, center = F(40), F(16)
    screen = [(F(5, 4), F(2), F(3, 2)), (F(59, 2), F(6), F(12)), (F(8), F(61, 2), F(4))]  # x, y, w
    eye = [((x - center) * w / focal, (y - center) * w / focal, -w) for x, y, w in screen]
    attribute = lambda p: 2 * p[0] - p[1] + p[2] / 2 + 3  # noqa: E731
    scene = ScreenPolygons.from_polygons(
        [[(float(x), float(y), float(1 - 1 / w)) for x, y, w in screen]],  # NDC-like depth
        [[(float(attribute(p)),) for p in eye]],
        [[float(1 / w) for _, _, w in screen]],
    )
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = eye
    normal = (
        (y1 - y0) * (z2 - z0) - (z1 - z0) * (y2 - y0),
        (z1 - z0) * (x2 - x0) - (x1 - x0) * (z2 - z0),
        (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0),
    )
    offset = sum(n * e for n, e in zip(normal, eye[0], strict=True))
    for path in PATHS.values():
        errors = {}
        for perspective in (True, False):
            result = zbuffer(scene, 32, 32, perspective=perspective, trace=path)
            worst = 0.0
            for y, x in covered(result.polygon == 0):
                ray = ((x - center) / focal, (y - center) / focal, F(-1))
                t = offset / sum(n * r for n, r in zip(normal, ray, strict=True))
                expected = attribute([t * r for r in ray])
                worst = max(worst, abs(result.values[y, x, 0] - float(expected)))
            errors[perspective] = worst
        assert errors[True] <= 1e-9 and errors[False] > 0.5


# --- accuracy on long thin polygons ----------------------------------------------------------


def long_polygons():
    """Polygons spanning 1000+ rows that stress stepped depths (name, (x, y, z) rows).

    Thin triangles and parallelograms; a sliver whose depth changes by 1 over
    0.02 px across it, far from x = 0 (z_row, the plane at x = 0, is ~2e4
    there); a wide triangle with NDC-like depths spanning 1e-6 near 1 (each
    step rounds at 1, a millionth of the range). Without compensated steps the
    last two drift by more than 1e-9 of their depth range.
    """
    rng = np.random.default_rng(7)
    for k in range(4):
        x0, x1 = rng.uniform(20, 1000, 2)
        width, t = rng.uniform(0.5, 6), rng.uniform(0.1, 0.9)
        if k % 2:
            xy = [(x0, -10.0), (x0 + width, -10.0), (x1 + width, 1210.0), (x1, 1210.0)]
        else:
            xy = [(x0, -10.0), (x1, 1210.0), (x0 + t * (x1 - x0) + width, -10 + t * 1220)]
        a, b, c = rng.uniform(-1e-3, 1e-3), rng.uniform(-1e-3, 1e-3), rng.uniform(0, 1)
        yield "thin", [(x, y, c + a * x + b * y) for x, y in xy]
    yield "steep sliver", [(300.0, -10.0, 0.0), (400.0, 1210.0, 0.0), (350.015625, 600.0, 1.0)]
    ndc = [(5.5, -3.25, 0.999999), (1090.0, 40.0, 0.9999995), (300.0, 1195.5, 0.999999875)]
    yield "NDC depths", ndc


@pytest.mark.parametrize("sample", SAMPLE_MODES)
def test_depth_and_values_are_exact_to_1e9_on_long_polygons(sample):
    offset = F(1, 2) if sample == "center" else F(0)
    for name, polygon in long_polygons():
        n = len(polygon)
        attributes = [[v, 1 - v] for v in np.linspace(0, 1, n)]
        scene = ScreenPolygons.from_polygons([polygon], [attributes])
        result = zbuffer(scene, 1100, 1200, sample=sample, subpixel_bits=8)
        samples = covered(result.polygon == 0)
        assert max(samples)[0] - min(samples)[0] >= 1000, name
        exact = exact_vertices(polygon, 8)
        plane = exact_plane(exact)
        depths = [v[2] for v in exact]
        depth_range = float(max(depths) - min(depths))
        for y, x in samples[:: max(1, len(samples) // 3000)]:
            sx, sy = x + offset, y + offset
            error = abs(result.depth[y, x] - float(plane(sx, sy)))
            assert error <= 1e-9 * depth_range, (name, y, x, error / depth_range)
            if n == 3:
                expected = barycentric_value(
                    [v[:2] for v in exact], [F(a[0]) for a in attributes], sx, sy
                )
                assert abs(result.values[y, x, 0] - float(expected)) <= 1e-9, (name, y, x)


# --- degenerate input, options, validation ------------------------------------------------


@pytest.mark.parametrize("path", PATHS)
def test_edge_on_off_raster_and_empty_polygons_draw_nothing(path):
    collinear = [(0, 0, 0.1), (4, 4, 0.2), (8, 8, 0.3)]
    off_raster = [(-9, 0, 0.1), (-5, 0, 0.1), (-5, 4, 0.1)]
    collapsed = [(1.001, 1, 0.1), (1.002, 1, 0.2), (1.001, 1.001, 0.3)]  # one point once snapped
    between_rows = [(0, 0.2, 0.1), (5, 0.2, 0.1), (5, 0.8, 0.1)]
    scene = ScreenPolygons.from_polygons([collinear, off_raster, collapsed, between_rows])
    result = zbuffer(scene, 10, 10, trace=PATHS[path])
    assert (result.polygon == -1).all() and (result.depth == np.inf).all()
    stats = result.stats
    assert (stats.polygons_skipped, stats.polygons_drawn, stats.fragments) == (3, 0, 0)
    empty = zbuffer(ScreenPolygons.from_polygons([]), 3, 2, trace=PATHS[path])
    assert empty.values.shape == (2, 3, 0) and (empty.polygon == -1).all()


def test_unsnapped_input_too_fine_for_int64_runs_the_reference():
    polygon = [(0.1, 0.2, 0.5), (7.3, 1.1, 0.25), (2.2, 6.7, 0.75)]
    scene = ScreenPolygons.from_polygons([polygon], [[(1.0,), (2.0,), (3.0,)]])
    untraced = zbuffer(scene, 8, 8, subpixel_bits=None)
    traced = zbuffer(scene, 8, 8, subpixel_bits=None, trace=True)
    assert untraced.stats.path == traced.stats.path == "reference"
    np.testing.assert_array_equal(untraced.values, traced.values)
    mask = scan_convert([p[:2] for p in polygon], 8, 8, subpixel_bits=None).mask
    np.testing.assert_array_equal(untraced.polygon == 0, mask)


def valid():
    return dict(
        xy=np.zeros((3, 2)) + [[0, 0], [1, 0], [0, 1]],
        z=np.zeros(3),
        inv_w=np.ones(3),
        values=np.zeros((3, 1)),
        offsets=[0, 3],
    )


@pytest.mark.parametrize(
    "change, error, message",
    [
        (dict(xy=np.zeros((3, 3))), ValueError, r"'xy' must be an \(M, 2\) array"),
        (dict(z=np.zeros(2)), ValueError, r"'z' must have one row per vertex of 'xy' \(3\)"),
        (dict(values=np.zeros(3)), ValueError, r"'values' must be an \(M, K\) array"),
        (dict(z=[0, np.nan, 0]), ValueError, r"'z'\[1\] = nan is not finite"),
        (dict(xy=[[0, 0], [2**21, 0], [0, 1]]), ValueError, r"'xy'\[1\] .* beyond"),
        (dict(inv_w=[1, 1, -1]), ValueError, r"'inv_w'\[2\] = -1.0 is not in"),
        (dict(values=[[1e200], [0], [0]]), ValueError, r"'values'\[0\] = \[1e\+200\] is beyond"),
        (
            dict(offsets=[0, 2]),
            ValueError,
            r"'offsets' must start at 0 and end at the vertex count 3",
        ),
        (dict(offsets=[0, 1, 3]), ValueError, r"'offsets': polygon 0 has 1 vertices"),
        (dict(offsets=[0.0, 3.0]), TypeError, r"'offsets' must hold integers"),
        (dict(z=["a", "b", "c"]), TypeError, r"'z' must be an array of numbers"),
    ],
)
def test_screen_polygons_validation(change, error, message):
    with pytest.raises(error, match=message):
        ScreenPolygons(**{**valid(), **change})


def test_screen_polygons_are_read_only_copies():
    arrays = valid()
    polygons = ScreenPolygons(**arrays)
    arrays["z"][0] = 7.0
    assert polygons.z[0] == 0.0 and not polygons.z.flags.writeable


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda p: zbuffer(p.xy, 4, 4), TypeError, "'polygons' must be a ScreenPolygons"),
        (lambda p: zbuffer(p, 4, 4, sample="middle"), ValueError, "'sample' must be one of"),
        (lambda p: zbuffer(p, 4, 4, perspective=1), TypeError, "'perspective' must be a bool"),
        (lambda p: zbuffer(p, 4, 4, subpixel_bits=17), ValueError, "'subpixel_bits' must be in"),
        (lambda p: zbuffer(p, -1, 4), ValueError, "'width' must be in"),
        (
            lambda p: zbuffer(p, 4, 4, trace="yes"),
            TypeError,
            "'trace' must be None, True or a Tracer",
        ),
    ],
)
def test_zbuffer_validation(call, error, message):
    with pytest.raises(error, match=message):
        call(ScreenPolygons(**valid()))


# --- the trace -------------------------------------------------------------------------------


def umbc_with_values():
    values = [[(1, 0), (0, 1), (0, 0)], [(1, 1)] * 4, [(0, 0), (1, 0), (0, 1)]]
    return ScreenPolygons.from_polygons(UMBC, values)


def test_trace_is_filterable_by_polygon_row_and_pixel():
    scene = umbc_with_values()
    rows = zbuffer(scene, 12, 12, trace=Recorder(polygons=[2], rows=(4, 5))).trace
    assert [e.kind for e in rows] == [
        "polygon_setup", "edge_table_built", "aet_sorted", "span", "edge_values", "span_values",
        "depth_test", "depth_test", "depth_test", "depth_test",
    ]  # fmt: skip
    tests = rows.of_kind("depth_test")
    assert [(e.x, e.y, e.passed, e.stored) for e in tests] == [
        (2, 4, False, 5.0), (3, 4, False, 5.0), (4, 4, True, None), (5, 4, True, None)
    ]  # fmt: skip
    assert tests[2].z == pytest.approx(13 / 3, abs=1e-14)  # 15 - 4 - 5*4/3
    pixel = zbuffer(scene, 12, 12, trace=Recorder(["depth_test"], region=(5, 6, 6, 7))).trace
    assert [(e.polygon, e.passed) for e in pixel] == [(0, True), (1, False)]  # (5, 6): 5 < 9


def test_depth_tests_are_not_built_when_not_wanted():
    class NoDepthTests:
        built = 0

        def wants(self, kind, *, polygon=None, y=None):
            return kind != "depth_test"

        def emit(self, event):
            self.built += 1
            assert event.kind != "depth_test"

    tracer = NoDepthTests()
    result = zbuffer(umbc_with_values(), 12, 12, trace=tracer)
    assert tracer.built > 0 and result.trace is None


def test_trace_events_tell_the_interpolation_story():
    trace = zbuffer(umbc_with_values(), 12, 12, trace=True).trace
    setup = trace.filter(["polygon_setup"], polygons=[2])[0]
    a, b, c, d = setup.plane
    assert (setup.dzdx, setup.dzdy) == (-a / c, -b / c) == (-1.0, pytest.approx(-5 / 3))
    for x, y, z in setup.vertices:  # A x + B y + C z + D = 0 at every vertex
        assert a * x + b * y + c * z + d == pytest.approx(0, abs=1e-12)
    rows = trace.filter(["edge_values"], polygons=[2])
    for below, above in zip(rows, rows[1:], strict=False):  # between rows: z_row += dz/dy
        assert above.z_row - below.z_row == pytest.approx(setup.dzdy, abs=1e-14)
    first = rows[0]  # row 3: values computed from each edge's lower end, (2, 3)
    assert [e.values for e in first.entries] == [(1.0, 0.0), (0.0, 1.0)]
    for span in trace.filter(["span_values"], polygons=[2]):  # z starts at z_row + dz/dx x_start
        row = next(r for r in rows if r.y == span.y)
        assert span.z == row.z_row + span.dzdx * span.x_start
    assert Trace.from_json(trace.to_json()) == trace
    assert len(trace.of_kind("depth_test")) == 54  # one per fragment

"""The compiled kernels against the traced reference: same spans, same coverage, any input.

Oracle tests (compiled == reference) over random polygons and triangles in
every mode, the int64 overflow cases at +-2**20 pixels, and the validation of
the batch entry points.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Polygon, fill_polygons, rasterize_triangles, scan_convert
from scanviz.catalog import SHAPES
from scanviz.conventions import ARITHMETICS, COORD_LIMIT, RULES, SAMPLE_MODES
from scanviz.raster import scan_compiled
from scanviz.raster.api import scan_snapped
from scanviz.raster.fixed import snap
from scanviz.raster.scanline import scan_reference
from scanviz.raster.walk_compiled import mul_divmod

MANY = settings(max_examples=10 * settings.default.max_examples)
WIDTH, HEIGHT = 24, 20
LIMIT = float(COORD_LIMIT)


def counted(stats) -> tuple:
    """The ScanStats fields both paths count (the compiled path leaves `swaps` at 0)."""
    return stats.edges, stats.kept_for_topology, stats.rows_scanned, stats.spans, stats.max_active


def assert_same_scan(snapped, width, height, rule, arithmetic):
    """Compiled and reference scans of `snapped` agree: spans and the stats both count."""
    expected, expected_stats = scan_reference(
        snapped, width, height, rule=rule, arithmetic=arithmetic
    )
    spans, stats = scan_snapped(snapped, width, height, rule=rule, arithmetic=arithmetic)
    assert stats.path == ("compiled" if snapped.compilable else "reference")
    np.testing.assert_array_equal(spans, expected)
    assert spans.dtype == np.int64 and spans.shape[1] == 3
    assert counted(stats) == counted(expected_stats)


def coordinates(kind: str, low: float, high: float) -> st.SearchStrategy:
    """Pixel coordinates: whole pixels, a 1/256 grid, or any float in [low, high]."""
    if kind == "integer":
        return st.integers(int(low), int(high)).map(float)
    if kind == "grid":
        return st.integers(int(low * 256), int(high * 256)).map(lambda v: v / 256)
    return st.floats(low, high, allow_nan=False)


@st.composite
def contours(draw, kind: str, low: float = -6, high: float = WIDTH + 6) -> list:
    """1 to 3 random contours of 3 to 8 vertices (self-intersecting as they come)."""
    point = st.tuples(coordinates(kind, low, high), coordinates(kind, low, high))
    return draw(st.lists(st.lists(point, min_size=3, max_size=8), min_size=1, max_size=3))


def polygon_or_none(parts) -> Polygon | None:
    try:
        return Polygon(parts)
    except ValueError:  # fewer than 3 distinct vertices in a contour
        return None


@MANY
@given(
    kind=st.sampled_from(["integer", "grid", "float"]),
    data=st.data(),
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from([0, 4, 8, 16, None]),
)
def test_compiled_spans_equal_reference_on_random_polygons(kind, data, sample, bits):
    polygon = polygon_or_none(data.draw(contours(kind)))
    if polygon is None:
        return
    snapped = snap(polygon, sample, bits)
    for rule in RULES:
        for arithmetic in ARITHMETICS:
            assert_same_scan(snapped, WIDTH, HEIGHT, rule, arithmetic)


@pytest.mark.parametrize("name", list(SHAPES))
def test_compiled_spans_equal_reference_on_catalog(name):
    shape = SHAPES[name]
    for sample in SAMPLE_MODES:
        for bits in (0, 8, 16, None):
            snapped = snap(shape.polygon, sample, bits)
            for rule in RULES:
                for arithmetic in ARITHMETICS:
                    assert_same_scan(snapped, shape.width, shape.height, rule, arithmetic)


def test_scan_convert_runs_the_kernel_unless_traced():
    square = [(0.5, 0.5), (6.25, 1), (5, 7.75), (1, 6)]
    fast, traced = scan_convert(square, 8, 8), scan_convert(square, 8, 8, trace=True)
    assert (fast.stats.path, traced.stats.path) == ("compiled", "reference")
    assert fast.trace is None and traced.trace is not None
    np.testing.assert_array_equal(fast.spans, traced.spans)
    np.testing.assert_array_equal(fast.mask, traced.mask)
    assert fast.stats.swaps == 0
    unsnapped = scan_convert([(0.1, 0.2), (7.3, 0.9), (3.3, 7.7)], 8, 8, subpixel_bits=None)
    assert unsnapped.stats.path == "reference"  # 0.1 needs more than 16 bits


# -- int64 overflow: grid values reach 2**37 and dx * (y * scale - yl) 2**77 ---------------


@pytest.mark.parametrize(
    "a, b, d",
    [
        (2**38 + 12345, 2**38 - 1, 2**38 + 7),
        (-(2**38) - 131071, 2**38 - 3, 2**38),
        (2**39 - 1, 2**38 + 5, 3 * 2**37 + 1),
        (-(2**52), 2**20 + 1, 2**22 + 3),
        (0, 2**40, 5),
        (7, 3, 1),
    ],
)
def test_mul_divmod_is_exact_beyond_int64(a, b, d):
    assert mul_divmod(a, b, d) == divmod(a * b, d)


@settings(max_examples=5 * settings.default.max_examples)
@given(
    a=st.integers(-(2**39), 2**39),
    t=st.integers(0, 2**39),
    d=st.integers(1, 2**39),
)
def test_mul_divmod_matches_python_ints(a, t, d):
    b = t % d  # as in `exact_crossing`: 0 <= b < d, so |a * b / d| < |a|
    assert mul_divmod(a, b, d) == divmod(a * b, d)


@settings(max_examples=3 * settings.default.max_examples)
@given(
    far=st.lists(
        st.tuples(st.floats(-LIMIT, LIMIT), st.floats(-LIMIT, LIMIT)), min_size=2, max_size=5
    ),
    near=st.tuples(st.floats(-4, 40), st.floats(-4, 40)),
    on_grid=st.booleans(),
    sample=st.sampled_from(SAMPLE_MODES),
)
def test_extreme_coordinates_match_reference(far, near, on_grid, sample):
    vertices = np.array([near, *far])
    if on_grid:
        vertices = np.rint(vertices * 2**16) / 2**16
    polygon = polygon_or_none(vertices)
    if polygon is None:
        return
    snapped = snap(polygon, sample, 16)
    for arithmetic in ARITHMETICS:
        assert_same_scan(snapped, 40, 40, "nonzero", arithmetic)


def test_edges_across_the_whole_coordinate_range():
    # dx ~ 2**38 units times y*scale - yl ~ 2**37 at row 0: a 2**75 product.
    big = COORD_LIMIT
    polygon = Polygon([(-big, -big), (big, -big + 0.5), (big - 3.25, big), (-big + 1, big - 2)])
    for sample in SAMPLE_MODES:
        snapped = snap(polygon, sample, 16)
        for arithmetic in ARITHMETICS:
            assert_same_scan(snapped, 64, 64, "nonzero", arithmetic)


@pytest.mark.parametrize("arithmetic", ARITHMETICS)
def test_edges_stepped_through_65536_rows(arithmetic):
    big = COORD_LIMIT
    sliver = Polygon([(-big, -big), (3.0001, big), (5.00003, big), (big, -big + 1)])
    snapped = snap(sliver, "center", 16)
    spans, stats = scan_snapped(snapped, 8, 2**16, arithmetic=arithmetic)
    assert stats.rows_scanned == 2**16
    expected, _ = scan_reference(snapped, 8, 2**16, arithmetic=arithmetic)
    np.testing.assert_array_equal(spans, expected)


def test_float32_dy_rounding_to_zero_keeps_x_like_the_reference():
    # At y = 300 float32 values are 2**-15 apart: both ends of these edges round to 300.0,
    # so the textbook dx/dy is inf or NaN; both paths keep x at the lower end instead.
    eps = 2.0**-16
    polygon = Polygon([(0, 300 - eps), (10, 300 + eps), (5, 300 + eps), (7, 300 - eps)])
    snapped = snap(polygon, "corner", 16)
    for arithmetic in ARITHMETICS:
        assert_same_scan(snapped, 16, 302, "nonzero", arithmetic)
    spans, _ = scan_snapped(snapped, 16, 302, arithmetic="float32")
    assert spans.tolist() == [[300, 0, 7]]


# -- batches: fill_polygons and rasterize_triangles == sums of scan_convert masks -----------


def mask_sum(polygons, width, height, **options) -> np.ndarray:
    total = np.zeros((height, width), np.int32)
    for polygon in polygons:
        total += scan_convert(polygon, width, height, **options).mask
    return total


@st.composite
def triangles(draw, kind: str) -> np.ndarray:
    """Random triangles, some of them degenerate: repeated or collinear vertices."""
    count = draw(st.integers(0, 12))
    coordinate = coordinates(kind, -6, WIDTH + 6)
    array = np.array(draw(st.lists(coordinate, min_size=6 * count, max_size=6 * count)))
    array = array.reshape(count, 3, 2)
    for index in draw(st.lists(st.integers(0, max(count - 1, 0)), max_size=3)) if count else []:
        if draw(st.booleans()):
            array[index, 2] = array[index, draw(st.integers(0, 1))]  # repeated vertex
        else:
            array[index, 2] = 2 * array[index, 1] - array[index, 0]  # collinear
    return array


@MANY
@given(
    kind=st.sampled_from(["integer", "grid", "float"]),
    data=st.data(),
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from([0, 4, 8, 16, None]),
)
def test_rasterize_triangles_equals_sum_of_masks(kind, data, sample, bits):
    batch = data.draw(triangles(kind))
    image = rasterize_triangles(batch, WIDTH, HEIGHT, sample=sample, subpixel_bits=bits)
    assert image.dtype == np.int32 and image.shape == (HEIGHT, WIDTH)
    valid = [t for t in batch if polygon_or_none(t) is not None]  # the rest have no area
    expected = mask_sum(valid, WIDTH, HEIGHT, sample=sample, subpixel_bits=bits)
    np.testing.assert_array_equal(image, expected)


@settings(max_examples=2 * settings.default.max_examples)
@given(
    vertices=st.lists(
        st.tuples(st.floats(-LIMIT, LIMIT), st.floats(-LIMIT, LIMIT)), min_size=15, max_size=15
    ),
    sample=st.sampled_from(SAMPLE_MODES),
)
def test_rasterize_extreme_triangles_equals_sum_of_masks(vertices, sample):
    batch = np.array(vertices).reshape(5, 3, 2)
    batch[:, 0] = np.clip(batch[:, 0] / 2**16, -4, 40)  # one vertex near the raster
    image = rasterize_triangles(batch, 32, 32, sample=sample, subpixel_bits=16)
    valid = [t for t in batch if polygon_or_none(t) is not None]
    np.testing.assert_array_equal(image, mask_sum(valid, 32, 32, sample=sample, subpixel_bits=16))


@MANY
@given(
    kind=st.sampled_from(["integer", "grid", "float"]),
    data=st.data(),
    sample=st.sampled_from(SAMPLE_MODES),
    rule=st.sampled_from(RULES),
    bits=st.sampled_from([0, 8, 16, None]),
)
def test_fill_polygons_equals_sum_of_masks(kind, data, sample, rule, bits):
    drawn = data.draw(st.lists(contours(kind), max_size=4))
    polygons = [p for p in map(polygon_or_none, drawn) if p is not None]
    options = dict(sample=sample, rule=rule, subpixel_bits=bits)
    expected = mask_sum(polygons, WIDTH, HEIGHT, **options)
    np.testing.assert_array_equal(fill_polygons(polygons, WIDTH, HEIGHT, **options), expected)
    corners = [p.contours[0][:3] for p in polygons]  # as a (P, 3, 2) array: the batch path
    singles = np.array([c for c in corners if polygon_or_none(c)]).reshape(-1, 3, 2)
    expected = mask_sum(list(singles), WIDTH, HEIGHT, **options)
    np.testing.assert_array_equal(fill_polygons(singles, WIDTH, HEIGHT, **options), expected)


def test_stars_as_an_array_and_as_polygons_agree():
    rng = np.random.default_rng(7)
    angles = np.sort(rng.uniform(0, 2 * np.pi, (6, 50)), axis=1)
    radii = np.where(np.arange(50) % 2 == 0, 30.0, 8.0) * rng.uniform(0.5, 1, (6, 1))
    centers = rng.uniform(0, 64, (6, 1, 2))
    stars = centers + np.stack([radii * np.cos(angles), radii * np.sin(angles)], axis=2)
    for rule in RULES:
        image = fill_polygons(stars, 64, 64, rule=rule, sample="center")
        np.testing.assert_array_equal(
            image, fill_polygons([Polygon(s) for s in stars], 64, 64, rule=rule, sample="center")
        )
        np.testing.assert_array_equal(image, mask_sum(stars, 64, 64, rule=rule, sample="center"))


# -- empty input, degenerate input, bad input ---------------------------------------------


@pytest.mark.parametrize("empty", [[], np.zeros((0, 3, 2))])
def test_no_triangles_no_polygons_give_zeros(empty):
    for image in (rasterize_triangles(empty, 5, 4), fill_polygons(empty, 5, 4)):
        np.testing.assert_array_equal(image, np.zeros((4, 5), np.int32))
    assert rasterize_triangles([[(0, 0), (4, 0), (0, 4)]], 0, 3).shape == (3, 0)
    assert fill_polygons([[(0, 0), (4, 0), (0, 4)]], 3, 0).shape == (0, 3)


def test_degenerate_triangles_cover_nothing_and_never_raise():
    degenerate = [
        [(1, 1), (1, 1), (1, 1)],
        [(0, 0), (3, 3), (0, 0)],
        [(0, 0), (2, 2), (4, 4)],
        [(0.5, 1), (2.5, 1), (4.5, 1)],
        [(0.1, 0.1), (0.1 + 1e-9, 0.1), (0.1, 0.1 + 1e-9)],
    ]
    for bits in (0, 8, None):
        assert not rasterize_triangles(degenerate, 6, 6, subpixel_bits=bits).any()


def test_shared_edges_are_covered_once():
    corners = np.array([(0.3, 0.7), (9.6, 0.2), (9.1, 8.8), (0.4, 9.5), (5.25, 4.5)])
    fan = [[corners[i], corners[(i + 1) % 4], corners[4]] for i in range(4)]
    image = rasterize_triangles(fan, 10, 10, sample="center")
    np.testing.assert_array_equal(image, scan_convert(corners[:4], 10, 10, sample="center").mask)


@pytest.mark.parametrize(
    "triangles, error, message",
    [
        ([(0, 0), (1, 0), (0, 1)], ValueError, r"'triangles' must be a \(T, 3, 2\) array"),
        (np.zeros((2, 4, 2)), ValueError, r"got shape \(2, 4, 2\)"),
        ([[(0, 0), (1, "x"), (0, 1)]], TypeError, "'triangles' must be"),
        ([[(0, 0), (1, 0), (0, 1)], [(0, 0), (np.nan, 0), (0, 1)]], ValueError, r"\[1\] vertex 1"),
        ([[(0, 0), (1, 0), (0, 2**21)]], ValueError, r"'triangles'\[0\] vertex 2 .* limit"),
    ],
)
def test_rasterize_triangles_rejects_bad_input(triangles, error, message):
    with pytest.raises(error, match=message):
        rasterize_triangles(triangles, 4, 4)


def test_fill_polygons_rejects_bad_input():
    line = [(0, 0), (2, 2), (0, 0)]
    with pytest.raises(ValueError, match=r"'polygons'\[1\]: contour 0 has 2 distinct"):
        fill_polygons(np.array([[(0, 0), (1, 0), (0, 1)], line]), 4, 4)
    with pytest.raises(ValueError, match=r"'polygons'\[1\]: contour 0 has 2 distinct"):
        fill_polygons([Polygon([(0, 0), (1, 0), (0, 1)]), line], 4, 4)
    with pytest.raises(ValueError, match=r"'polygons'\[0\] vertex 1 .* not finite"):
        fill_polygons([[(0, 0), (np.inf, 0), (0, 1)]], 4, 4)
    with pytest.raises(TypeError, match="'polygons' must be an iterable"):
        fill_polygons(3, 4, 4)
    with pytest.raises(ValueError, match="'rule'"):
        fill_polygons([], 4, 4, rule="winding")


def test_fill_polygons_prefix_sums_only_marked_columns_and_fills_to_the_right_edge():
    # Rows are summed only across the polygons' column ranges: spans clipped at the right
    # edge (no -1 mark) must still fill to it, spans left of x = 0 must start at 0, and
    # polygons given top first (scanned bottom first) must count the same.
    polygons = [
        [(5.5, 9.0), (30.0, 10.5), (29.0, 17.0), (6.0, 16.0)],  # beyond the right edge
        [(-8.0, 0.5), (3.25, 1.0), (2.0, 7.5)],  # beyond the left edge
        [(10.0, -3.0), (19.5, 2.0), (12.0, 12.0), (15.0, 4.0)],
        [(30.0, 3.0), (40.0, 3.0), (35.0, 8.0)],  # off the raster entirely
    ]
    for rule in RULES:
        expected = mask_sum([Polygon(p) for p in polygons], WIDTH, HEIGHT, rule=rule)
        np.testing.assert_array_equal(fill_polygons(polygons, WIDTH, HEIGHT, rule=rule), expected)
    assert fill_polygons(polygons, WIDTH, HEIGHT)[12, WIDTH - 1] == 1


def test_issue8_d7_fill_and_triangles_refuse_rasters_over_the_memory_limit():
    from scanviz.limits import ResourceLimitError, memory_limit

    triangle = [(0, 0), (4, 0), (0, 4)]
    with pytest.raises(ResourceLimitError, match="fill_polygons: a 65536x65536 int32"):
        fill_polygons([triangle], 65536, 65536)
    with pytest.raises(ResourceLimitError, match="rasterize_triangles: a 65536x65536 int32"):
        rasterize_triangles([triangle], 65536, 65536)
    with memory_limit("64K"):
        with pytest.raises(ResourceLimitError, match="fill_polygons: a 256x256"):
            fill_polygons([triangle], 256, 256)  # 256 KiB of counts
        assert fill_polygons([triangle], 64, 64).sum() == 10  # 16 KiB fits


@pytest.mark.parametrize("huge", [10**400, 2**1024])
def test_issue8_d8_huge_ints_are_a_value_error_naming_the_item(huge):
    triangle = [(0, 0), (4, 0), (0, 4)]
    with pytest.raises(ValueError, match=r"'triangles'\[1\] vertex 0 = .* \+-2\*\*20"):
        rasterize_triangles([triangle, [(huge, 0), (1, 0), (0, 1)]], 8, 8)
    with pytest.raises(ValueError, match=r"'polygons'\[1\] vertex 0 = .* \+-2\*\*20"):
        fill_polygons([triangle, [(huge, 0), (1, 0), (0, 1)]], 8, 8)
    with pytest.raises(ValueError, match=r"'polygons'\[1\]: contour 0 vertex 0 = .* \+-2\*\*20"):
        fill_polygons([triangle, [(huge, 0), (1, 0), (0, 1), (1, 1)]], 8, 8)


@pytest.mark.parametrize("bad", [7j, "0", True, None], ids=["complex", "str", "bool", "None"])
def test_issue8_d9_non_real_coordinates_are_a_type_error(bad):
    triangle = [(0, 0), (4, 0), (0, 4)]
    with pytest.raises(TypeError, match=r"'triangles'\[1\] vertex 2 holds"):
        rasterize_triangles([triangle, [(0, 0), (4, 0), (0, bad)]], 8, 8)
    with pytest.raises(TypeError, match=r"'polygons'\[1\] vertex 2 holds"):
        fill_polygons([triangle, [(0, 0), (4, 0), (0, bad)]], 8, 8)


def test_issue8_d9_shapes_and_items_are_checked():
    triangle = [(0, 0), (4, 0), (0, 4)]
    with pytest.raises(ValueError, match=r"'triangles'\[1\] has 2 items; want 3"):
        rasterize_triangles([triangle, [(0, 0), (1, 0)]], 8, 8)
    with pytest.raises(ValueError, match=r"'triangles'\[0\] vertex 1 has 3 coordinates"):
        rasterize_triangles([[(0, 0), (1, 0, 2), (0, 1)]], 8, 8)
    with pytest.raises(TypeError, match=r"got dtype complex128"):
        rasterize_triangles(np.zeros((1, 3, 2), complex), 8, 8)
    assert rasterize_triangles([], 8, 8).sum() == 0
    assert fill_polygons([], 8, 8).sum() == 0
    with pytest.raises(TypeError, match=r"'polygons'\[0\]: 'contours' must be"):
        fill_polygons([1, 2, 3], 8, 8)
    with pytest.raises(TypeError, match=r"'polygons'\[0\]: 'contours' must be"):
        fill_polygons([None], 8, 8)


@settings(max_examples=settings.default.max_examples)
@given(
    values=st.lists(st.sampled_from([0.0, -0.0, 1.0, 2.5]), min_size=2 * 4 * 5, max_size=2 * 4 * 5),
    size=st.integers(3, 5),
)
def test_three_distinct_counts_as_unique(values, size):
    batch = np.array(values).reshape(4, 5, 2)[:, :size].copy()
    expected = [len(np.unique(item, axis=0)) >= 3 for item in batch]
    assert scan_compiled.three_distinct(batch).tolist() == expected

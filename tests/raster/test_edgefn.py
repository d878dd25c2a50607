"""Edge-function triangles: golden arrays, the fill-convention probe, and scan_convert as oracle."""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Polygon, Recorder, Trace, scan_convert, triangle_samples
from scanviz.catalog import get
from scanviz.conventions import COORD_LIMIT, SAMPLE_MODES
from scanviz.raster.fixed import snap

BITS = (0, 2, 8, 16, None)


def paint(cover, width: int, height: int) -> np.ndarray:
    """Coverage counts of a `triangle_samples` result: (height, width) ndarray of int64."""
    image = np.zeros((height, width), dtype=np.int64)
    np.add.at(image, (cover.ys, cover.xs), 1)
    return image


def reference_mask(triangle, width, height, sample, bits) -> np.ndarray:
    """The ET/AET reference: any tracer forces the traced reference path.

    Recording spans only keeps it fast (and skips the float dx/dy of the
    edge records, which overflows for subnormal inputs, a known xfail).
    """
    recorder = Recorder(kinds=["span"])
    options = dict(sample=sample, subpixel_bits=bits, trace=recorder)
    return scan_convert(triangle, width, height, **options).mask


def check_against_reference(triangle, width, height, sample, bits) -> None:
    cover = triangle_samples(triangle, width, height, sample=sample, subpixel_bits=bits)
    assert cover.ys.dtype == cover.xs.dtype == np.int64
    assert cover.barycentric.shape == (len(cover.ys), 3)
    assert np.all(np.diff(cover.ys * (width + 1) + cover.xs) > 0)  # sorted by y then x, unique
    if len(np.unique(np.asarray(triangle, dtype=float), axis=0)) < 3:
        assert len(cover.ys) == 0  # a point or a segment (scan_convert rejects these)
        return
    assert np.array_equal(
        paint(cover, width, height) == 1, reference_mask(triangle, width, height, sample, bits)
    )
    vertices = snap(Polygon(triangle), sample, bits).pixel_vertices()
    offset = 0.5 if sample == "center" else 0.0
    points = np.stack([cover.xs, cover.ys], axis=1) + offset
    tolerance = 1e-9 * max(1.0, np.abs(vertices).max())
    assert np.all(cover.barycentric >= 0)
    np.testing.assert_allclose(cover.barycentric.sum(axis=1), 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(cover.barycentric @ vertices, points, rtol=0, atol=tolerance)


def test_right_triangle_golden_both_windings():
    expected = np.array(
        [
            [0, 0, 0, 0, 0],
            [1, 1, 0, 0, 0],
            [1, 1, 1, 0, 0],
            [1, 1, 1, 1, 0],
        ]
    )[::-1]
    for triangle in ([(0, 0), (4, 0), (0, 3)], [(0, 0), (0, 3), (4, 0)]):
        assert np.array_equal(paint(triangle_samples(triangle, 5, 4), 5, 4), expected)


def test_center_sampling_golden():
    cover = triangle_samples([(0, 0), (4, 0), (0, 4)], 4, 4, sample="center")
    # centres (x + .5, y + .5) with x + y + 1 < 4; on the hypotenuse (x + y + 1 == 4) out
    assert sorted(zip(cover.ys.tolist(), cover.xs.tolist(), strict=True)) == [
        (0, 0), (0, 1), (0, 2), (1, 0), (1, 1), (2, 0),
    ]  # fmt: skip


def test_barycentric_of_vertices_and_edge_midpoints():
    cover = triangle_samples([(0, 0), (4, 0), (0, 4)], 5, 5)
    weights = {
        (x, y): tuple(b)
        for x, y, b in zip(cover.xs, cover.ys, cover.barycentric.tolist(), strict=True)
    }
    assert weights[(0, 0)] == (1.0, 0.0, 0.0)
    assert weights[(2, 0)] == (0.5, 0.5, 0.0)
    assert weights[(0, 2)] == (0.5, 0.0, 0.5)
    assert weights[(1, 1)] == (0.5, 0.25, 0.25)


@pytest.mark.parametrize("sample", SAMPLE_MODES)
@pytest.mark.parametrize("bits", [0, 8, None])
@pytest.mark.parametrize("reverse", [False, True])
def test_fan_of_eight_triangles_covers_the_hub_sample_once(sample, bits, reverse):
    hub = (5.5, 5.5) if sample == "center" else (5, 5)
    directions = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1)]
    ring = [(hub[0] + 2 * dx, hub[1] + 2 * dy) for dx, dy in directions]
    fan = [[hub, ring[i], ring[(i + 1) % 8]] for i in range(8)]
    if reverse:
        fan = [triangle[::-1] for triangle in fan]
    covers = [triangle_samples(t, 12, 12, sample=sample, subpixel_bits=bits) for t in fan]
    images = [paint(c, 12, 12) for c in covers]
    hub_hits = [i for i, image in enumerate(images) if image[5, 5]]
    assert len(hub_hits) == 1
    if sample == "corner":  # (5 + eps, 5 + eps**2) lies just above the +x ray: the first sector
        assert hub_hits == [0]
    square = [ring[7], ring[1], ring[3], ring[5]]  # the fan's outline
    outline = scan_convert(square, 12, 12, sample=sample, subpixel_bits=bits).mask
    assert np.array_equal(sum(images), outline.astype(np.int64))  # no gaps, no double hits


@pytest.mark.parametrize("name", ["convex", "vertices_on_samples"])
@pytest.mark.parametrize("sample", SAMPLE_MODES)
@pytest.mark.parametrize("bits", BITS)
def test_fan_triangulation_of_a_convex_catalog_shape_is_watertight(name, sample, bits):
    shape = get(name)
    v = shape.polygon.vertices.tolist()
    options = dict(sample=sample, subpixel_bits=bits)
    counts = sum(
        paint(
            triangle_samples([v[0], v[i], v[i + 1]], shape.width, shape.height, **options),
            shape.width,
            shape.height,
        )
        for i in range(1, len(v) - 1)
    )
    expected = scan_convert(shape.polygon, shape.width, shape.height, **options).mask
    assert np.array_equal(counts, expected.astype(np.int64))


@pytest.mark.parametrize("name", ["subpixel", "huge", "tiny"])
@pytest.mark.parametrize("sample", SAMPLE_MODES)
@pytest.mark.parametrize("bits", BITS)
def test_catalog_triangles_match_scan_convert(name, sample, bits):
    shape = get(name)
    check_against_reference(
        shape.polygon.vertices.tolist(), shape.width, shape.height, sample, bits
    )


small_int = st.integers(-4, 22)
small_float = st.floats(-4, 22, allow_nan=False, allow_infinity=False)
on_grid = st.integers(-32, 176).map(lambda k: k / 8)
huge = st.floats(-COORD_LIMIT, COORD_LIMIT, allow_nan=False, allow_infinity=False)
fine = st.sampled_from([0.0, 1.0, 2.0**-30, 2.0**-70, 2.0**-1000, 5e-324, 1 + 2.0**-52])


def _random_triangle(seed: int) -> list[tuple[float, float]]:
    """Well-spread vertices: integer, on a 1/8 grid, float, or anywhere in the coordinate range."""
    rng = np.random.default_rng(seed)
    kind = rng.integers(4)
    if kind == 0:
        return rng.integers(-4, 23, (3, 2)).tolist()
    if kind == 1:
        return (rng.integers(-32, 177, (3, 2)) / 8).tolist()
    if kind == 2:
        return rng.uniform(-4, 22, (3, 2)).tolist()
    return rng.uniform(-COORD_LIMIT, COORD_LIMIT, (3, 2)).tolist()


@st.composite
def chosen_triangles(draw):
    """Hypothesis-chosen vertices (edge cases: shared values, 0, extremes), often degenerate."""
    coordinate = draw(st.sampled_from([small_int, small_float, on_grid, huge, fine]))
    a, b, c = (draw(st.tuples(coordinate, coordinate)) for _ in range(3))
    shape = draw(st.sampled_from(["any", "collinear", "repeated"]))
    if shape == "collinear":  # c on the line through a and b (exactly, for integer steps)
        k = draw(st.sampled_from([-1, 2, 0.5, 3]))
        c = tuple(
            float(np.clip(p + k * (q - p), -COORD_LIMIT, COORD_LIMIT))
            for p, q in zip(a, b, strict=True)
        )
    elif shape == "repeated":
        c = draw(st.sampled_from([a, b]))
    return [a, b, c]


sizes = st.tuples(st.sampled_from(range(1, 21)), st.sampled_from(range(1, 21)))


@settings(max_examples=30 * settings.default.max_examples)
@given(
    seed=st.integers(0, 2**32 - 1),
    size=sizes,
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from(BITS),
)
def test_random_triangles_cover_exactly_what_scan_convert_covers(seed, size, sample, bits):
    check_against_reference(_random_triangle(seed), *size, sample, bits)


@settings(max_examples=10 * settings.default.max_examples)
@given(
    triangle=chosen_triangles(),
    size=sizes,
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from(BITS),
)
def test_chosen_and_degenerate_triangles_match_scan_convert(triangle, size, sample, bits):
    check_against_reference(triangle, *size, sample, bits)


@settings(max_examples=5 * settings.default.max_examples)
@given(seed=st.integers(0, 2**32 - 1), size=sizes, sample=st.sampled_from(SAMPLE_MODES))
def test_trace_rows_replay_the_result(seed, size, sample):
    triangle = _random_triangle(seed)
    plain = triangle_samples(triangle, *size, sample=sample)
    traced = triangle_samples(triangle, *size, sample=sample, trace=True)
    assert np.array_equal(plain.xs, traced.xs) and np.array_equal(plain.ys, traced.ys)
    setup, *rows = traced.trace
    x_start, y_start, x_end, y_end = setup.bbox
    assert [r.y for r in rows] == list(range(y_start, y_end))
    replayed = []
    for r in rows:
        assert (r.x_start, r.x_end) == (x_start, x_end)
        px, py = r.x_start * setup.scale, r.y * setup.scale
        assert r.values == tuple(e.a * px + e.b * py + e.c for e in setup.edges)
        replayed += [(r.y, x) for x in range(r.covered_start, r.covered_end)]
    assert replayed == list(zip(traced.ys.tolist(), traced.xs.tolist(), strict=True))


def test_huge_triangle_beyond_int64_matches_scan_convert():
    # Edge functions reach ~2**75 grid units on this raster: the exact (object) path decides.
    triangle = [(-COORD_LIMIT, -COORD_LIMIT + 0.3), (COORD_LIMIT, 3.7), (2.5, COORD_LIMIT)]
    for sample in SAMPLE_MODES:
        for bits in (16, None):
            check_against_reference(triangle, 9, 7, sample, bits)


def test_regression_tiny_unsnapped_triangle_does_not_overflow_int64():
    # Grid of 2**1001 units per pixel but small coordinates: the steps, not E, overflowed.
    for sample in SAMPLE_MODES:
        check_against_reference([(0, 0), (2.0**-1000, 0), (0, 2.0**-1000)], 3, 3, sample, None)


def test_degenerate_triangles_cover_nothing_and_never_raise():
    for triangle in ([(1, 1), (1, 1), (1, 1)], [(0, 0), (3, 3), (0, 0)], [(0, 0), (2, 2), (4, 4)]):
        cover = triangle_samples(triangle, 8, 8, trace=True)
        assert cover.ys.shape == cover.xs.shape == (0,) and cover.barycentric.shape == (0, 3)
        assert all(e.kind == "triangle_setup" and e.area2 == 0 for e in cover.trace)
    # snapping collapses a thin triangle to zero area
    assert len(triangle_samples([(0, 0), (8, 0.01), (4, 0.002)], 8, 8, subpixel_bits=2).ys) == 0


def test_trace_setup_rows_and_json_round_trip():
    cover = triangle_samples([(0, 0), (4, 0), (0, 3)], 5, 4, subpixel_bits=0, trace=True)
    setup, *rows = cover.trace
    assert setup.kind == "triangle_setup" and setup.scale == 2
    assert setup.units == ((0, 0), (8, 0), (0, 6)) and setup.vertices == ((0, 0), (4, 0), (0, 3))
    assert setup.area2 == 48 and setup.orientation == 1 and setup.bbox == (0, 0, 4, 3)
    assert [(e.a, e.b, e.c, e.owns_boundary) for e in setup.edges] == [
        (0, 8, 0, True),  # bottom edge, left to right: owns its samples
        (-6, -8, 48, False),  # hypotenuse: right-facing
        (6, 0, 0, True),  # left edge, downward
    ]
    assert [(r.y, r.x_start, r.x_end, r.covered_start, r.covered_end) for r in rows] == [
        (0, 0, 4, 0, 4),
        (1, 0, 4, 0, 3),
        (2, 0, 4, 0, 2),
    ]
    assert rows[1].values == (16, 32, 0)  # E_i at sample (0, 1), grid point (0, 2)
    assert Trace.from_json(cover.trace.to_json()) == cover.trace


def test_trace_respects_filters_and_none_records_nothing():
    recorder = Recorder(kinds=["edge_function_row"], rows=(1, 2))
    result = triangle_samples([(0, 0), (4, 0), (0, 3)], 5, 4, trace=recorder)
    assert [e.y for e in result.trace] == [1]
    assert triangle_samples([(0, 0), (4, 0), (0, 3)], 5, 4).trace is None


def test_clipping_to_the_raster():
    cover = triangle_samples([(-10, -10), (30, -10), (-10, 30)], 4, 3, trace=True)
    assert cover.trace[0].bbox == (0, 0, 4, 3)
    assert len(cover.ys) == 12
    for width, height in [(0, 3), (4, 0)]:
        assert len(triangle_samples([(0, 0), (4, 0), (0, 4)], width, height).ys) == 0


@pytest.mark.parametrize(
    ("triangle", "error", "message"),
    [
        ([(0, 0), (1, 0)], ValueError, r"'triangle' must be a \(3, 2\) array; got shape \(2, 2\)"),
        ([(0, 0), (1, 0), (0, "a")], TypeError, "'triangle' must be a"),
        ([(0, 0), (1, np.nan), (0, 1)], ValueError, "'triangle' vertex 1 is not finite"),
        ([(0, 0), (1, 0), (0, 2.0**21)], ValueError, "'triangle' vertex 2 .* beyond"),
    ],
)
def test_bad_triangles_are_named(triangle, error, message):
    with pytest.raises(error, match=message):
        triangle_samples(triangle, 4, 4)


def test_bad_options_are_named():
    triangle = [(0, 0), (1, 0), (0, 1)]
    with pytest.raises(ValueError, match="'sample'"):
        triangle_samples(triangle, 4, 4, sample="middle")
    with pytest.raises(ValueError, match="'subpixel_bits'"):
        triangle_samples(triangle, 4, 4, subpixel_bits=17)
    with pytest.raises(TypeError, match="'width'"):
        triangle_samples(triangle, 4.0, 4)
    with pytest.raises(TypeError, match="'trace'"):
        triangle_samples(triangle, 4, 4, trace="yes")


def test_issue8_d7_covered_samples_over_the_memory_limit_are_refused():
    from scanviz.limits import ResourceLimitError, memory_limit

    with pytest.raises(ResourceLimitError, match="triangle_samples: the samples of a triangle"):
        triangle_samples([(0, 0), (65536, 0), (0, 65536)], 65536, 65536)
    with memory_limit("1M"):  # about 13,000 samples of 80 bytes
        assert len(triangle_samples([(0, 0), (100, 0), (0, 100)], 128, 128).xs) == 5050
        with pytest.raises(ResourceLimitError, match="over the memory limit of 1.0 MiB"):
            triangle_samples([(0, 0), (200, 0), (0, 200)], 256, 256)


@pytest.mark.parametrize("huge", [10**400, 2**1024])
def test_issue8_d8_huge_ints_are_a_value_error_naming_the_vertex(huge):
    with pytest.raises(ValueError, match=r"'triangle' vertex 1 = .* \+-2\*\*20"):
        triangle_samples([(0, 0), (huge, 0), (0, 1)], 8, 8)


def test_issue8_d9_types_of_coordinates_and_options_are_checked():
    triangle = [(0, 0), (4, 0), (0, 4)]
    for bad in (7j, "4", True):
        with pytest.raises(TypeError, match=r"'triangle' .* numbers .* vertex 1 holds"):
            triangle_samples([(0, 0), (bad, 0), (0, 4)], 8, 8)
    with pytest.raises(TypeError, match=r"'polygon' must be an int >= 0; got 'not an int'"):
        triangle_samples(triangle, 8, 8, polygon="not an int")
    with pytest.raises(TypeError, match=r"'polygon' must be an int"):
        triangle_samples(triangle, 8, 8, polygon=True)
    with pytest.raises(ValueError, match=r"'polygon' must be an int >= 0; got -1"):
        triangle_samples(triangle, 8, 8, polygon=-1)
    with pytest.raises(
        ValueError, match=r"'triangle' must be a \(3, 2\) array; got shape \(4, 2\)"
    ):
        triangle_samples([*triangle, (1, 1)], 8, 8)


@st.composite
def thin_and_ordinary_triangles(draw):
    """Three vertices on a 1/64 grid around a 40 x 30 raster; often a sliver along a long edge."""
    coordinate = st.integers(-8 * 64, 48 * 64).map(lambda k: k / 64)
    a, b, c = (draw(st.tuples(coordinate, coordinate)) for _ in range(3))
    if draw(st.booleans()):  # c a few grid steps off a point of the segment ab
        t = draw(st.sampled_from([0.0, 0.25, 0.5, 1.0]))
        dx, dy = (draw(st.integers(-3, 3)) / 64 for _ in range(2))
        c = (a[0] + t * (b[0] - a[0]) + dx, a[1] + t * (b[1] - a[1]) + dy)
    return [a, b, c]


@settings(derandomize=True, max_examples=100, deadline=None)
@given(
    triangle=st.one_of(thin_and_ordinary_triangles(), chosen_triangles()),
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from(BITS),
)
def test_row_range_path_gives_the_bounding_box_paths_samples_bit_for_bit(triangle, sample, bits):
    options = dict(sample=sample, subpixel_bits=bits)
    ranged = triangle_samples(triangle, 40, 30, **options)  # untraced: each row's exact x-range
    boxed = triangle_samples(triangle, 40, 30, trace=Recorder(kinds=["span"]), **options)
    assert np.array_equal(ranged.ys, boxed.ys) and np.array_equal(ranged.xs, boxed.xs)
    assert np.array_equal(ranged.barycentric, boxed.barycentric)  # the same floats, bit for bit


def _exact_row(vertices, y: int) -> tuple[list[int], list[tuple[Fraction, ...]]]:
    """Columns of row y covered under DESIGN §2's rule, and their barycentric weights, by Fraction.

    A sample p is inside when p + (eps, eps**2) is strictly on the inner side of
    every edge: the sign of E(p) + eps * (Y0 - Y1) + eps**2 * (X1 - X0).
    """
    v = [(Fraction(x), Fraction(yv)) for x, yv in vertices]
    area2 = (v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[1][1] - v[0][1]) * (v[2][0] - v[0][0])
    sign = 1 if area2 > 0 else -1

    def edge(i, px, py):
        (x0, y0), (x1, y1) = v[i], v[(i + 1) % 3]
        return (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0), y0 - y1, x1 - x0

    # The row's chord of the triangle, from the edges crossing height y.
    crossings = [
        v[i][0] + (y - v[i][1]) * (v[j][0] - v[i][0]) / (v[j][1] - v[i][1])
        for i, j in ((0, 1), (1, 2), (2, 0))
        if v[i][1] != v[j][1] and min(v[i][1], v[j][1]) <= y <= max(v[i][1], v[j][1])
    ]
    columns, weights = [], []
    for x in range(math.floor(min(crossings)) - 1, math.ceil(max(crossings)) + 2):
        terms = [edge(i, Fraction(x), Fraction(y)) for i in range(3)]
        if all(sign * next(t for t in term if t) > 0 for term in terms):
            columns.append(x)
            weights.append((terms[1][0] / area2, terms[2][0] / area2, terms[0][0] / area2))
    return columns, weights


def test_issue8_d7_thin_triangle_in_a_huge_box_is_fast_enough():
    # A sliver across a 65536² box: testing every sample of its box took minutes.
    triangle = [(0, 0), (65535, 65535.5), (1, 0)]  # exact on the 1/256 grid: snapping keeps it
    cover = triangle_samples(triangle, 65536, 65536)
    assert np.all(np.diff(cover.ys * 65536 + cover.xs) > 0)
    for y in (0, 1, 2, 777, 30000, 43689, 43690, 43691, 65534, 65535):
        columns, weights = _exact_row(triangle, y)
        on_row = cover.ys == y
        assert cover.xs[on_row].tolist() == columns, y
        expected = np.array([[float(w) for w in ws] for ws in weights]).reshape(-1, 3)
        assert np.array_equal(cover.barycentric[on_row], expected), y
    assert len(_exact_row(triangle, 30000)[0]) == 1  # the oracle sees the sliver's one sample


# --- the replaceable steps edge_function and owns_boundary ------------------------------------


@settings(derandomize=True, max_examples=80, deadline=None)
@given(st.lists(st.integers(-50, 50), min_size=4, max_size=4))
def test_edge_function_is_zero_on_its_edge_and_positive_on_its_left(coordinates):
    from scanviz.raster.edgefn import edge_function

    x0, y0, x1, y1 = coordinates
    a, b, c = edge_function((x0, y0), (x1, y1))
    assert a * x0 + b * y0 + c == 0
    assert a * x1 + b * y1 + c == 0
    left = (x0 - (y1 - y0), y0 + (x1 - x0))  # the start moved by the direction turned +90 deg
    assert a * left[0] + b * left[1] + c == (x1 - x0) ** 2 + (y1 - y0) ** 2


def test_owns_boundary_decides_the_sample_moved_by_eps_and_eps_squared():
    # Exact oracle: E(p + (eps, eps**2)) = a eps + b eps**2 for E(p) = 0; with |a|, |b| <= 9
    # and eps = 1/100 the sign is that of the infinitesimal limit.
    from scanviz.raster.edgefn import owns_boundary

    eps = Fraction(1, 100)
    for a in range(-9, 10):
        for b in range(-9, 10):
            if a == b == 0:
                continue
            for orientation in (1, -1):
                moved = orientation * (a * eps + b * eps**2)
                assert owns_boundary(a, b, orientation) == (moved > 0), (a, b, orientation)


def test_untraced_triangle_samples_honours_a_replaced_step():
    from scanviz import steps

    triangle = [(0, 0), (4, 0), (0, 4)]  # the hypothesis samples (1, 3), (2, 2), (3, 1)
    with steps.using(owns_boundary=lambda a, b, orientation: True):
        closed = triangle_samples(triangle, 5, 5)
        traced = triangle_samples(triangle, 5, 5, trace=True)
    default = triangle_samples(triangle, 5, 5)
    on_hypotenuse = {(1, 3), (2, 2), (3, 1)}
    as_set = lambda found: set(zip(found.xs.tolist(), found.ys.tolist(), strict=True))  # noqa: E731
    assert as_set(closed) == as_set(traced) == as_set(default) | on_hypotenuse
    assert not as_set(default) & on_hypotenuse

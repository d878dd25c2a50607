"""ET/AET scan conversion: the slide example by hand, an exact oracle, and invariants.

Three kinds of test (STYLE.md): golden values derived by hand from the UMBC
CMSC 435 slides; cross-implementation checks against the independent oracle
of `tests.oracle`, for the traced reference (``trace=True``) and the fast path
(``trace=None``); and invariants — watertightness, translation, no drift.
"""

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from scanviz import Polygon, scan_convert
from scanviz.catalog import SHAPES, get
from scanviz.conventions import ARITHMETICS, COORD_LIMIT, RULES, SAMPLE_MODES
from tests.oracle import oracle_mask, point_oracle_mask, snapped_contours

BASE = settings.default.max_examples  # SCANVIZ_MAX_EXAMPLES scales every property test
BITS = (0, 3, 8, 16, None)
PATHS = {"reference": True, "fast": None}  # the `trace` argument that selects each path


# --- the UMBC slide example, by hand -----------------------------------------------------

# Edges of (4,1), (1,11), (9,5), (12,8), (12,1), contour order:
#   e0 (4,1)-(1,11):  x = 4 - 3/10 (y - 1),  rows 1..10
#   e1 (1,11)-(9,5):  x = 9 - 4/3 (y - 5),   rows 5..10
#   e2 (9,5)-(12,8):  x = 9 + (y - 5),       rows 5..7
#   e3 (12,8)-(12,1): x = 12,                rows 1..7
#   e4 (12,1)-(4,1):  horizontal, kept only for topology
# The slides print row 2 as "3 1/10, 12": a typo, since x = 4 - 3/10 = 3 7/10 there.
F = Fraction
UMBC_AET = {
    1: [4, 12],
    2: [F(37, 10), 12],
    3: [F(17, 5), 12],
    4: [F(31, 10), 12],
    5: [F(14, 5), 9, 9, 12],
    6: [F(5, 2), F(23, 3), 10, 12],
    7: [F(11, 5), F(19, 3), 11, 12],
    8: [F(19, 10), 5],
    9: [F(8, 5), F(11, 3)],
    10: [F(13, 10), F(7, 3)],
}
# Spans [ceil(x_in), ceil(x_out)): row 5 is split at the local minimum (9, 5).
UMBC_SPANS = {
    1: [(4, 12)],
    2: [(4, 12)],
    3: [(4, 12)],
    4: [(4, 12)],
    5: [(3, 9), (9, 12)],
    6: [(3, 8), (10, 12)],
    7: [(3, 7), (11, 12)],
    8: [(2, 5)],
    9: [(2, 4)],
    10: [(2, 3)],
}


@pytest.fixture(scope="module")
def umbc_trace():
    shape = get("umbc_example")
    return scan_convert(shape.polygon, shape.width, shape.height, trace=True).trace


def test_umbc_edge_table(umbc_trace):
    (table,) = umbc_trace.of_kind("edge_table_built")
    rows = [
        (e.bucket, e.ymax, e.x_exact, e.dxdy_exact, e.horizontal, e.kept_for_topology)
        for e in table.edges
    ]
    assert rows == [
        (1, 11, 4, F(-3, 10), False, False),
        (5, 11, 9, F(-4, 3), False, False),
        (5, 8, 9, 1, False, False),
        (1, 8, 12, 0, False, False),
        (1, 1, 4, None, True, True),
    ]
    horizontal = table.edges[4]
    assert {(horizontal.x0, horizontal.y0), (horizontal.x1, horizontal.y1)} == {(12, 1), (4, 1)}


def test_umbc_active_edge_table_row_by_row(umbc_trace):
    aet = {e.y: [entry.x_exact for entry in e.entries] for e in umbc_trace.of_kind("aet_sorted")}
    assert aet == UMBC_AET
    for event in umbc_trace.of_kind("aet_sorted"):
        assert [entry.x for entry in event.entries] == [float(x) for x in UMBC_AET[event.y]]


def test_umbc_spans_row_by_row(umbc_trace):
    spans = {}
    for e in umbc_trace.of_kind("span"):
        spans.setdefault(e.y, []).append((e.x_start, e.x_end))
    assert spans == UMBC_SPANS


def test_umbc_edges_enter_and_leave_at_their_buckets(umbc_trace):
    steps = [
        (e.kind, e.y, sorted(e.edges))
        for e in umbc_trace.of_kind("edges_activated", "edges_retired")
    ]
    assert steps == [
        ("edges_activated", 1, [0, 3]),
        ("edges_activated", 5, [1, 2]),
        ("edges_retired", 8, [2, 3]),
        ("edges_retired", 11, [0, 1]),
    ]


def test_umbc_mask_golden():
    shape = get("umbc_example")
    mask = scan_convert(shape.polygon, 13, 12).mask
    assert ["".join(".#"[v] for v in row) for row in mask.astype(int)[::-1]] == [
        ".............",  # y = 11: the top vertex (1, 11) is not owned
        "..#..........",
        "..##.........",
        "..###........",
        "...####....#.",
        "...#####..##.",
        "...#########.",  # y = 5: the spans [3, 9) and [9, 12) meet at the minimum (9, 5)
        "....########.",
        "....########.",
        "....########.",
        "....########.",  # y = 1: the lower horizontal edge is owned, x = 12 is not
        ".............",
    ]


# --- strategies ---------------------------------------------------------------------------


def coordinates(kind: str, low: float, high: float):
    """Integers, values on the 1/256 grid, or arbitrary floats in [low, high]."""
    if kind == "int":
        return st.integers(int(low), int(high)).map(float)
    if kind == "grid":
        return st.integers(int(low * 256), int(high * 256)).map(lambda v: v / 256)
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


@st.composite
def polygons(draw, width: int, height: int, margin: float = 2, max_contours: int = 3):
    """1..max_contours contours of 3..12 distinct vertices, slightly beyond the raster too."""
    kind = draw(st.sampled_from(["int", "grid", "float"]))
    point = st.tuples(
        coordinates(kind, -margin, width + margin), coordinates(kind, -margin, height + margin)
    )
    contour = st.lists(point, min_size=3, max_size=12, unique=True)
    return Polygon(draw(st.lists(contour, min_size=1, max_size=max_contours)))


@st.composite
def scenes(draw, max_size: int = 24):
    width, height = draw(st.integers(0, max_size)), draw(st.integers(0, max_size))
    polygon = draw(polygons(max(width, 1), max(height, 1)))
    options = {
        "sample": draw(st.sampled_from(SAMPLE_MODES)),
        "rule": draw(st.sampled_from(RULES)),
        "subpixel_bits": draw(st.sampled_from(BITS)),
    }
    return polygon, width, height, options


def expected_mask(polygon, width, height, sample="corner", rule="nonzero", subpixel_bits=8):
    return oracle_mask(polygon, width, height, sample, rule, subpixel_bits)


# --- the oracle itself ------------------------------------------------------------------


@settings(max_examples=BASE)
@given(scenes(max_size=7))
def test_oracle_row_formula_matches_its_point_definition(scene):
    polygon, width, height, options = scene
    np.testing.assert_array_equal(
        expected_mask(polygon, width, height, **options),
        point_oracle_mask(polygon, width, height, **options),
    )


def spread_angles(draw, count: int) -> list[float]:
    """`count` increasing angles in [0, 2 pi), at least half a degree apart."""
    steps = draw(st.lists(st.integers(0, 719), min_size=count, max_size=count, unique=True))
    return [step * np.pi / 360 for step in sorted(steps)]


@st.composite
def star_shaped(draw):
    """A simple polygon: float points sorted by angle around an interior centre."""
    count = draw(st.integers(3, 12))
    angles = spread_angles(draw, count)
    radii = draw(st.lists(st.floats(1, 11), min_size=count, max_size=count))
    cx, cy = draw(st.floats(8, 16)), draw(st.floats(8, 16))
    points = [(cx + r * np.cos(a), cy + r * np.sin(a)) for a, r in zip(angles, radii, strict=True)]
    assume(shapely.Polygon(points).is_valid and shapely.Polygon(points).area > 0)
    return points


@settings(max_examples=BASE)
@given(star_shaped(), st.sampled_from(SAMPLE_MODES))
def test_oracle_agrees_with_shapely_away_from_the_boundary(points, sample):
    offset = 0.5 if sample == "center" else 0.0
    xs, ys = np.meshgrid(np.arange(24) + offset, np.arange(24) + offset)
    region = shapely.Polygon(points)
    inside = shapely.contains_xy(region, xs, ys)
    on_boundary = shapely.intersects_xy(region.boundary, xs, ys)
    mask = expected_mask(Polygon(points), 24, 24, sample, "evenodd", None)
    np.testing.assert_array_equal(mask[~on_boundary], inside[~on_boundary])


# --- reference and fast path against the oracle -----------------------------------------


def check_spans(spans: np.ndarray, mask: np.ndarray) -> None:
    """Spans are sorted, non-empty, inside the raster, disjoint, and paint exactly `mask`."""
    height, width = mask.shape
    assert spans.dtype == np.int64 and spans.shape[1:] == (3,)
    assert [tuple(s) for s in spans.tolist()] == sorted(tuple(s) for s in spans.tolist())
    painted = np.zeros((height, width), dtype=np.int64)
    for y, start, end in spans.tolist():
        assert 0 <= y < height and 0 <= start < end <= width
        painted[y, start:end] += 1
    np.testing.assert_array_equal(painted, mask.astype(np.int64))


@settings(max_examples=15 * BASE)
@given(scenes())
def test_reference_and_fast_path_match_the_exact_oracle(scene):
    polygon, width, height, options = scene
    expected = expected_mask(polygon, width, height, **options)
    traced = scan_convert(polygon, width, height, trace=True, **options)
    fast = scan_convert(polygon, width, height, trace=None, **options)
    for result in (traced, fast):
        assert result.mask.shape == (height, width) and result.mask.dtype == bool
        np.testing.assert_array_equal(result.mask, expected)
        check_spans(result.spans, result.mask)
    np.testing.assert_array_equal(traced.spans, fast.spans)
    span_events = [(e.y, e.x_start, e.x_end) for e in traced.trace.of_kind("span")]
    assert span_events == [tuple(s) for s in traced.spans.tolist()]


@st.composite
def far_reaching(draw):
    """Contours mixing vertices near a 16 x 16 raster with vertices up to 2**20 away."""
    near = st.tuples(st.floats(-2, 18), st.floats(-2, 18))
    far = st.tuples(st.floats(-COORD_LIMIT, COORD_LIMIT), st.floats(-COORD_LIMIT, COORD_LIMIT))
    contour = st.lists(st.one_of(near, far), min_size=3, max_size=8, unique=True)
    return Polygon(draw(st.lists(contour, min_size=1, max_size=2)))


@settings(max_examples=3 * BASE)
@given(
    far_reaching(),
    st.sampled_from(SAMPLE_MODES),
    st.sampled_from(RULES),
    st.sampled_from(BITS),
    st.sampled_from(list(PATHS)),
)
def test_edges_from_far_away_match_the_exact_oracle(polygon, sample, rule, bits, path):
    options = {"sample": sample, "rule": rule, "subpixel_bits": bits}
    result = scan_convert(polygon, 16, 16, trace=PATHS[path], **options)
    np.testing.assert_array_equal(result.mask, expected_mask(polygon, 16, 16, **options))


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # float dy == 0: the known bug below
@settings(max_examples=3 * BASE)
@given(scenes(), st.sampled_from(["float32", "float64"]))
def test_float_arithmetic_fast_path_matches_reference(scene, arithmetic):
    polygon, width, height, options = scene

    def spans(trace):
        try:
            return scan_convert(
                polygon, width, height, arithmetic=arithmetic, trace=trace, **options
            ).spans.tolist()
        except ValueError:  # both paths, for now: see test_float_arithmetic_never_raises_...
            return "ValueError"

    assert spans(None) == spans(True)


# --- watertightness ------------------------------------------------------------------------


def signed_area(points, bits) -> Fraction:
    """Twice the signed area of a contour after the oracle's snapping."""
    (snapped,) = snapped_contours([points], bits)
    return sum(
        (
            x0 * y1 - x1 * y0
            for (x0, y0), (x1, y1) in zip(snapped, snapped[1:] + snapped[:1], strict=True)
        ),
        Fraction(0),
    )


def coverage_count(pieces, width, height, path, **options) -> np.ndarray:
    """How many pieces cover each sample: (height, width) ndarray of int64."""
    count = np.zeros((height, width), dtype=np.int64)
    for piece in pieces:
        count += scan_convert(piece, width, height, trace=PATHS[path], **options).mask
    return count


def assert_watertight(pieces, outline, width, height, path, sample, bits):
    """Every sample inside `outline` is covered exactly once by the pieces, others never."""
    assume(all(len(set(piece)) == len(piece) for piece in pieces))  # Polygon needs 3 distinct
    # Snapping can flip a thin piece; a flipped piece would wind -1 and break the count.
    assume(all(signed_area(piece, bits) >= 0 for piece in pieces))
    assume(signed_area(outline, bits) > 0)
    count = coverage_count(pieces, width, height, path, sample=sample, subpixel_bits=bits)
    inside = expected_mask(Polygon(outline), width, height, sample, "nonzero", bits)
    np.testing.assert_array_equal(count, inside.astype(np.int64))


WATERTIGHT_BITS = st.sampled_from((3, 8, 16, None))
WEIGHT = st.floats(0.05, 1.0)  # barycentric weights, kept away from 0


@st.composite
def subdivided_quads(draw):
    """A convex quad cut in two, then random interior points each splitting a triangle in 3."""
    low, high = st.floats(-2, 10), st.floats(22, 34)
    outline = [
        (draw(low), draw(low)),
        (draw(high), draw(low)),
        (draw(high), draw(high)),
        (draw(low), draw(high)),
    ]
    a, b, c, d = outline
    triangles = [(a, b, c), (a, c, d)]
    for _ in range(draw(st.integers(0, 24))):
        p, q, r = triangles.pop(draw(st.integers(0, len(triangles) - 1)))
        wp, wq, wr = draw(WEIGHT), draw(WEIGHT), draw(WEIGHT)
        total = wp + wq + wr
        m = tuple((wp * u + wq * v + wr * w) / total for u, v, w in zip(p, q, r, strict=True))
        triangles += [(p, q, m), (q, r, m), (r, p, m)]
    return [list(t) for t in triangles], outline


@st.composite
def fans(draw):
    """A convex polygon (points on a circle) fanned around a random interior point."""
    count = draw(st.integers(3, 16))
    angles = spread_angles(draw, count)
    radius, cx, cy = draw(st.floats(2, 15)), draw(st.floats(12, 20)), draw(st.floats(12, 20))
    outline = [(cx + radius * np.cos(t), cy + radius * np.sin(t)) for t in angles]
    weights = [draw(WEIGHT) for _ in outline]
    centre = tuple(
        sum(w * p[i] for w, p in zip(weights, outline, strict=True)) / sum(weights) for i in (0, 1)
    )
    pieces = [[centre, outline[i], outline[(i + 1) % count]] for i in range(count)]
    return pieces, outline


@st.composite
def jittered_meshes(draw):
    """A grid of quads whose shared vertices are jittered: 4 pieces meet at inner vertices."""
    columns, rows = draw(st.integers(1, 5)), draw(st.integers(1, 5))
    cell = 30 / max(columns, rows)
    jitter = st.floats(-cell / 4, cell / 4)
    grid = [
        [(1 + i * cell + draw(jitter), 1 + j * cell + draw(jitter)) for i in range(columns + 1)]
        for j in range(rows + 1)
    ]
    pieces = [
        [grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i]]
        for j in range(rows)
        for i in range(columns)
    ]
    outline = (
        grid[0]
        + [grid[j][columns] for j in range(1, rows + 1)]
        + grid[rows][::-1][1:]
        + [grid[j][0] for j in range(rows - 1, 0, -1)]
    )
    return pieces, outline


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("mesh", [subdivided_quads, fans, jittered_meshes])
def test_shared_edges_cover_every_sample_exactly_once(mesh, path):
    @settings(max_examples=BASE)
    @given(mesh(), st.sampled_from(SAMPLE_MODES), WATERTIGHT_BITS)
    def check(pieces_and_outline, sample, bits):
        pieces, outline = pieces_and_outline
        assert_watertight(pieces, outline, 32, 32, path, sample, bits)

    check()


@settings(max_examples=2 * BASE)
@given(
    st.tuples(st.floats(-40, -0.01), st.floats(-40, -0.01)),
    st.tuples(st.floats(32.01, 70), st.floats(-40, -0.01)),
    st.tuples(st.floats(32.01, 70), st.floats(32.01, 70)),
    st.tuples(st.floats(-40, -0.01), st.floats(32.01, 70)),
    st.sampled_from(SAMPLE_MODES),
    st.sampled_from(list(PATHS)),
)
def test_two_triangles_covering_the_raster_cover_each_sample_once(a, b, c, d, sample, path):
    # One corner beyond each side of the raster: the quad is simple and holds the raster,
    # and at least one of its diagonals lies inside it.
    for pieces in ([[a, b, c], [a, c, d]], [[a, b, d], [b, c, d]]):
        if all(signed_area(p, 8) > 0 for p in pieces):
            break
    else:
        pytest.fail("neither diagonal of the quad lies inside it")
    count = coverage_count(pieces, 32, 32, path, sample=sample)
    np.testing.assert_array_equal(count, np.ones((32, 32), dtype=np.int64))


# --- translation invariance --------------------------------------------------------------


@settings(max_examples=3 * BASE)
@given(
    st.sampled_from(["int", "grid", "float"]).flatmap(
        lambda kind: st.lists(
            st.lists(
                st.tuples(coordinates(kind, 12, 28), coordinates(kind, 12, 28)),
                min_size=3,
                max_size=10,
                unique=True,
            ),
            min_size=1,
            max_size=2,
        )
    ),
    st.integers(-12, 20),
    st.integers(-12, 20),
    st.sampled_from(SAMPLE_MODES),
    st.sampled_from(RULES),
    st.sampled_from(BITS),
)
def test_integer_translation_shifts_the_mask(contours, dx, dy, sample, rule, bits):
    shifted = [[(x + dx, y + dy) for x, y in c] for c in contours]
    # Float addition may round; test only shifts that are exact after snapping.
    moved = [[(x + dx, y + dy) for x, y in c] for c in snapped_contours(contours, bits)]
    assume(snapped_contours(shifted, bits) == moved)
    options = {"sample": sample, "rule": rule, "subpixel_bits": bits}
    before = scan_convert(Polygon(contours), 48, 48, **options).mask
    after = scan_convert(Polygon(shifted), 48, 48, **options).mask
    np.testing.assert_array_equal(after, np.roll(before, (dy, dx), axis=(0, 1)))
    assert after.sum() == before.sum()


# --- long edges: exact has no drift, float32 does ---------------------------------------


@pytest.fixture(scope="module")
def long_quad():
    """A quad about 1.2 pixels wide whose steep edges span all 65,536 rows of an 8-wide raster."""
    height = 65536
    polygon = Polygon([(0.1234567, 0), (1.3141592, 0), (7.9876543, height), (6.7654321, height)])
    return polygon, 8, height, expected_mask(polygon, 8, height, subpixel_bits=16)


@pytest.mark.parametrize("path", PATHS)
def test_exact_arithmetic_has_no_drift_over_65536_rows(long_quad, path):
    polygon, width, height, expected = long_quad
    result = scan_convert(polygon, width, height, subpixel_bits=16, trace=PATHS[path])
    assert np.count_nonzero(result.mask != expected) == 0


def test_float32_increments_drift_and_float64_far_less(long_quad):
    polygon, width, height, expected = long_quad
    deviations = {}
    for arithmetic in ("float32", "float64"):
        result = scan_convert(polygon, width, height, subpixel_bits=16, arithmetic=arithmetic)
        deviations[arithmetic] = int(np.count_nonzero(result.mask != expected))
    print(f"samples deviating from the exact fill over {height} rows: {deviations}")
    assert deviations["float32"] > 0
    assert deviations["float64"] * 10 < deviations["float32"]


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize(
    ("arithmetic", "polygon", "bits", "height"),
    [
        # On the bits=16 grid at y = 300, where float32 values are 2**-15 apart, both ends
        # of an edge 2**-15 tall round to 300.0, yet the edge crosses row 300.
        ("float32", [(1, 300 - 2**-16), (3, 300 + 2**-16), (5, 310), (0.5, 310)], 16, 305),
        # Unsnapped, dy = 5e-324: dx/dy = -inf and inf * 0 = NaN at row 0.
        ("float64", [(0, 0), (0, 5e-324), (1, 0)], None, 4),
    ],
    ids=["float32-dy-rounds-to-0", "float64-subnormal-dy"],
)
def test_float_arithmetic_never_raises_on_valid_input(arithmetic, polygon, bits, height, path):
    # Regression: an edge whose float dy is 0 or subnormal made x += dx/dy NaN and raised.
    result = scan_convert(
        polygon, 8, height, subpixel_bits=bits, arithmetic=arithmetic, trace=PATHS[path]
    )
    assert result.mask.shape == (height, 8)
    reference = scan_convert(
        polygon, 8, height, subpixel_bits=bits, arithmetic=arithmetic, trace=True
    )
    np.testing.assert_array_equal(result.spans, reference.spans)


@pytest.mark.parametrize("sample", ["corner", "center"])
def test_trace_survives_a_slope_beyond_float_range(sample):
    # Regression: float(dx/dy) raised OverflowError in the trace, and for center sampling
    # so did the x of an edge crossing no row, extrapolated to row ceil(ymin) (~2**1073). Unsnapped, dy = 5e-324
    # (the smallest subnormal) and dx = 1: dx/dy = 2**1074, shown as inf next to the exact value.
    polygon = Polygon([(0, 0), (0, 5e-324), (1, 0)])
    result = scan_convert(polygon, 4, 4, sample=sample, subpixel_bits=None, trace=True)
    expected = expected_mask(polygon, 4, 4, sample=sample, subpixel_bits=None)
    np.testing.assert_array_equal(result.mask, expected)
    (table,) = result.trace.of_kind("edge_table_built")
    assert table.edges[1].dxdy == -np.inf and table.edges[1].dxdy_exact == -(2**1074)


def test_corner_sample_owns_the_lower_left_corner_of_a_subnormal_triangle():
    # (eps, eps**2) lies inside the triangle even though its height is 5e-324.
    polygon = [(0, 0), (0, 5e-324), (1, 0)]
    for trace in PATHS.values():
        mask = scan_convert(polygon, 4, 4, subpixel_bits=None, trace=trace).mask
        assert np.argwhere(mask).tolist() == [[0, 0]]


# --- degenerate input renders nothing and never raises ---------------------------------

DEGENERATE = {name: (s.polygon, s.width, s.height) for name, s in SHAPES.items() if s.degenerate}
DEGENERATE |= {
    "left_of_raster": (Polygon([(-30, 2), (-5, 4), (-9, 20)]), 16, 16),
    "right_of_raster": (Polygon([(16, 2), (40, 4), (30, 20)]), 16, 16),
    "below_raster": (Polygon([(2, -30), (14, -20), (8, -0.5)]), 16, 16),
    "above_raster": (Polygon([(2, 16), (14, 20), (8, 40)]), 16, 16),
    "zero_by_zero_raster": (get("convex").polygon, 0, 0),
    "zero_width_raster": (get("convex").polygon, 0, 32),
    "zero_height_raster": (get("convex").polygon, 32, 0),
}


@pytest.mark.parametrize("name", DEGENERATE)
@pytest.mark.parametrize("arithmetic", ARITHMETICS)
def test_degenerate_input_renders_nothing(name, arithmetic):
    polygon, width, height = DEGENERATE[name]
    for sample in SAMPLE_MODES:
        for rule in RULES:
            for bits in BITS:
                for trace in PATHS.values():
                    result = scan_convert(
                        polygon,
                        width,
                        height,
                        sample=sample,
                        rule=rule,
                        subpixel_bits=bits,
                        arithmetic=arithmetic,
                        trace=trace,
                    )
                    assert result.mask.shape == (height, width)
                    assert not result.mask.any() and result.spans.shape == (0, 3)


# --- bad input raises a clear error naming the argument ---------------------------------

TRIANGLE = [(0, 0), (4, 0), (4, 3)]


@pytest.mark.parametrize(
    ("polygon", "options", "error", "message"),
    [
        (
            [TRIANGLE, [(0, 0), (np.nan, 1), (2, 2)]],
            {},
            ValueError,
            r"contour 1 vertex 1 is not finite",
        ),
        ([(0, 0), (1, 0), (0, np.inf)], {}, ValueError, r"contour 0 vertex 2 is not finite"),
        ([(0, 0, 1), (1, 0, 1), (0, 1, 1)], {}, ValueError, r"contour 0 must be an \(N, 2\) array"),
        ([(0, 0), (1, 1)], {}, ValueError, r"contour 0 has 2 distinct vertices"),
        ([(0, 0), (2 * COORD_LIMIT, 0), (0, 1)], {}, ValueError, r"contour 0 vertex 1 .*limit"),
        (TRIANGLE, {"sample": "middle"}, ValueError, r"'sample' must be one of 'corner', 'center'"),
        (TRIANGLE, {"rule": "winding"}, ValueError, r"'rule' must be one of 'nonzero', 'evenodd'"),
        (TRIANGLE, {"arithmetic": "float16"}, ValueError, r"'arithmetic' must be one of"),
        (TRIANGLE, {"subpixel_bits": 17}, ValueError, r"'subpixel_bits' must be in 0\.\.16"),
        (TRIANGLE, {"subpixel_bits": -1}, ValueError, r"'subpixel_bits' must be in 0\.\.16"),
        (TRIANGLE, {"subpixel_bits": 2.5}, TypeError, r"'subpixel_bits' must be an int or None"),
        (TRIANGLE, {"subpixel_bits": True}, TypeError, r"'subpixel_bits' must be an int or None"),
        (TRIANGLE, {"width": -1}, ValueError, r"'width' must be in 0\.\.65536"),
        (TRIANGLE, {"width": "10"}, TypeError, r"'width' must be an int"),
        (TRIANGLE, {"height": 65537}, ValueError, r"'height' must be in 0\.\.65536"),
        (TRIANGLE, {"trace": object()}, TypeError, r"'trace' must be None, True or a Tracer"),
    ],
    ids=[
        "nan",
        "inf",
        "N-by-3",
        "two-points",
        "beyond-limit",
        "sample",
        "rule",
        "arithmetic",
        "bits-17",
        "bits-negative",
        "bits-float",
        "bits-bool",
        "width-negative",
        "width-str",
        "height-too-big",
        "trace-object",
    ],
)
def test_bad_input_raises_a_clear_error(polygon, options, error, message):
    arguments = {"width": 8, "height": 8, **options}
    with pytest.raises(error, match=message):
        scan_convert(polygon, **arguments)


def test_issue8_d7_span_buffer_is_sized_by_the_output_not_the_edges():
    # 4001 edges over 4096 rows: sum(rows per edge) * 24 bytes is ~390 MiB, the output ~100 KiB.
    from scanviz.limits import memory_limit

    zigzag = [(0, 0), (1, 4096)] * 2000 + [(2, 0)]  # the pairs cancel: a triangle remains
    with memory_limit("32M"):
        result = scan_convert(zigzag, 4, 4096)
    triangle = scan_convert([(0, 0), (1, 4096), (2, 0)], 4, 4096)
    np.testing.assert_array_equal(result.mask, triangle.mask)
    np.testing.assert_array_equal(result.spans, triangle.spans)
    assert result.mask[0].tolist() == [True, True, False, False]


def test_issue8_d7_rasters_over_the_memory_limit_are_refused_before_allocating():
    from scanviz.limits import ResourceLimitError, memory_limit

    with pytest.raises(ResourceLimitError, match=r"scan_convert: a 65536x65536 bool mask"):
        scan_convert([(0, 0), (9, 0), (0, 9)], 65536, 65536)
    comb = [(0, 0), (256, 0)] + [(255 - i, 64 + 64 * (i % 2)) for i in range(256)]
    with memory_limit("256K"), pytest.raises(ResourceLimitError, match=r"at least \d+ spans"):
        scan_convert(comb, 256, 128)  # 8256 spans, 72 bytes each while the buffer grows
    assert len(scan_convert(comb, 256, 128).spans) > 256 * 1024 // 72


@pytest.mark.parametrize("huge", [10**400, 2**1024, -(2**1024)])
def test_issue8_d8_huge_ints_are_a_value_error_naming_the_vertex(huge):
    with pytest.raises(ValueError, match=r"contour 0 vertex 2 = .* limit of \+-2\*\*20"):
        scan_convert([(0, 0), (4, 0), (0, huge)], 8, 8)
    with pytest.raises(ValueError, match=r"contour 1 vertex 0 = "):
        scan_convert([[(0, 0), (4, 0), (0, 4)], [(huge, huge), (1, 1), (2, 1)]], 8, 8)


@pytest.mark.parametrize("bad", [7j, "4", True, None], ids=["complex", "str", "bool", "None"])
def test_issue8_d9_non_real_coordinates_are_a_type_error(bad):
    with pytest.raises(TypeError, match=r"contour 0 .* numbers .* vertex 1 holds"):
        scan_convert([(0, 0), (4, bad), (0, 4)], 8, 8)


def test_issue8_d9_ragged_polygon_names_the_vertex():
    with pytest.raises(ValueError, match=r"contour 0 vertex 1 has 3 coordinates"):
        scan_convert([(0, 0), (1, 0, 5), (0, 1)], 8, 8)

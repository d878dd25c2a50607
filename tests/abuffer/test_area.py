"""Exact area coverage against a shapely oracle, plus invariants and golden cases."""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.ops import polygonize, unary_union

from scanviz import Polygon, catalog
from scanviz.abuffer import area
from scanviz.abuffer.area import area_coverage, pixel_areas
from scanviz.conformance.exact import snap_contours

TOLERANCE = 1e-12


def _winding(contours: list[np.ndarray], x: float, y: float) -> int:
    """Winding number of (x, y) around the contours; (x, y) must not lie on an edge."""
    total = 0
    for contour in contours:
        x0, y0 = contour[:, 0], contour[:, 1]
        x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
        crosses = (y0 <= y) != (y1 <= y)
        with np.errstate(divide="ignore", invalid="ignore"):
            x_cross = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        right = crosses & (x_cross > x)
        total += int(np.sum(np.where(y1 > y0, 1, -1)[right]))
    return total


def oracle_region(polygon: Polygon, rule: str, bits: int | None):
    """The inside region by shapely: faces of the edge arrangement whose winding passes `rule`."""
    scale = 1.0 if bits is None else 2.0**bits
    contours = [c if bits is None else np.rint(c * scale) / scale for c in polygon.contours]
    segments = [
        shapely.LineString([c[i], c[(i + 1) % len(c)]])
        for c in contours
        for i in range(len(c))
        if not np.array_equal(c[i], c[(i + 1) % len(c)])
    ]
    inside = []
    for face in polygonize(unary_union(segments)):
        point = face.representative_point()
        w = _winding(contours, point.x, point.y)
        if (w % 2 != 0) if rule == "evenodd" else (w != 0):
            inside.append(face)
    return unary_union(inside) if inside else shapely.Polygon()


def oracle_coverage(polygon: Polygon, width: int, height: int, rule: str, bits: int | None):
    """(height, width) areas of the oracle region ∩ each pixel square."""
    region = oracle_region(polygon, rule, bits)
    ys, xs = np.mgrid[0:height, 0:width]
    boxes = shapely.box(xs, ys, xs + 1, ys + 1)
    return shapely.area(shapely.intersection(region, boxes))


def _check_against_oracle(polygon, width, height, rule, bits=8):
    ours = area_coverage(polygon, width, height, rule=rule, subpixel_bits=bits)
    expected = oracle_coverage(Polygon(polygon), width, height, rule, bits)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=TOLERANCE)
    # Sparse form: exactly the pixels of positive area, sorted by y then x.
    ys, xs, areas = pixel_areas(polygon, width, height, rule=rule, subpixel_bits=bits)
    assert ys.dtype == xs.dtype == np.int64 and areas.dtype == np.float64
    assert np.all(np.diff(ys * width + xs) > 0)
    assert np.all((areas > 0) & (areas <= 1))
    np.testing.assert_array_equal(np.argwhere(ours > 0), np.column_stack([ys, xs]))


@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
@pytest.mark.parametrize("name", [name for name in catalog.SHAPES if name not in ("huge", "tiny")])
def test_catalog_matches_shapely(name, rule):
    shape = catalog.get(name)
    _check_against_oracle(shape.polygon, shape.width, shape.height, rule)


@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
def test_huge_triangle_matches_shapely(rule):
    # Edges 2**21 pixels long: x is interpolated from vertices far outside the raster.
    shape = catalog.get("huge")
    ours = area_coverage(shape.polygon, shape.width, shape.height, rule=rule)
    expected = oracle_coverage(shape.polygon, shape.width, shape.height, rule, 8)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=TOLERANCE)


def test_tiny_triangle_unsnapped_has_its_exact_area():
    shape = catalog.get("tiny")
    ys, xs, areas = pixel_areas(shape.polygon, shape.width, shape.height, subpixel_bits=None)
    expected = oracle_coverage(shape.polygon, shape.width, shape.height, "nonzero", None)
    assert areas.sum() == pytest.approx(shapely.Polygon(shape.polygon.contours[0]).area, rel=1e-9)
    np.testing.assert_allclose(
        area_coverage(shape.polygon, 16, 16, subpixel_bits=None), expected, atol=1e-15
    )
    assert len(areas) == 4  # around the sample point (8, 8): one piece in each of four pixels


def _contour(draw, size: float) -> list[tuple[float, float]]:
    count = draw(st.integers(3, 9))
    grid = st.integers(int(-2 * 64), int((size + 2) * 64)).map(lambda v: v / 64)
    return [(draw(grid), draw(grid)) for _ in range(count)]


@st.composite
def random_polygons(draw):
    """1-2 random (often self-intersecting) contours on a 1/64 grid, partly off a 12 x 10 raster."""
    contours = [_contour(draw, 12) for _ in range(draw(st.integers(1, 2)))]
    for contour in contours:
        if len(set(contour)) < 3:
            contour.extend([(0.0, 0.0), (5.0, 0.0), (0.0, 5.0)])
    return Polygon(contours)


@settings(max_examples=settings.default.max_examples)
@given(random_polygons(), st.sampled_from(["nonzero", "evenodd"]))
def test_random_polygons_match_shapely(polygon, rule):
    _check_against_oracle(polygon, 12, 10, rule)


@given(random_polygons(), st.sampled_from(["nonzero", "evenodd"]))
def test_unsnapped_random_float_polygons_match_shapely(polygon, rule):
    jittered = Polygon([c + np.float64(1 / 3) for c in polygon.contours])
    _check_against_oracle(jittered, 12, 10, rule, bits=None)


def _crossing_height(e, f):
    """Where two edges ((x0, y0), (x1, y1)) of Fractions have equal x, if they are not parallel."""
    (ex0, ey0), (ex1, ey1) = e
    (fx0, fy0), (fx1, fy1) = f
    e_slope, f_slope = (ex1 - ex0) / (ey1 - ey0), (fx1 - fx0) / (fy1 - fy0)
    if e_slope == f_slope:
        return None
    return ((fx0 - fy0 * f_slope) - (ex0 - ey0 * e_slope)) / (e_slope - f_slope)


def _x_on(edge, t: Fraction) -> Fraction:
    (x0, y0), (x1, y1) = edge
    return x0 + (t - y0) * (x1 - x0) / (y1 - y0)


def _column_integral(edge, a: Fraction, b: Fraction, c: int) -> Fraction:
    """∫ clamp(x(t) - c, 0, 1) dt over [a, b]: exact by the trapezoid rule where the clamp is linear."""
    cuts = {a, b}
    for level in (c, c + 1):
        (x0, y0), (x1, y1) = edge
        if x0 != x1:
            t = y0 + (level - x0) * (y1 - y0) / (x1 - x0)
            if a < t < b:
                cuts.add(t)
    points = sorted(cuts)
    value = [min(max(_x_on(edge, t) - c, Fraction(0)), Fraction(1)) for t in points]
    return sum(
        (
            (value[i] + value[i + 1]) / 2 * (points[i + 1] - points[i])
            for i in range(len(points) - 1)
        ),
        Fraction(0),
    )


def exact_rule_coverage(polygon: Polygon, width: int, height: int, rule: str, bits: int | None):
    """Per pixel, the exact area where the winding passes `rule`: (height, width) of Fraction.

    Written apart from the sweep: every vertex height and every height where
    two edges cross (found for all pairs) cuts the rows into slabs in which
    no two edges cross; in a slab the inside is bounded by the edges where the
    fill rule switches, walking them by x at mid-height, and a pixel gets
    ``∫ clamp(x_R - c, 0, 1) - clamp(x_L - c, 0, 1)`` over each such pair.
    """
    edges = []
    for contour in snap_contours(polygon.contours, bits):
        for p, q in zip(contour, contour[1:] + contour[:1], strict=True):
            if p[1] != q[1]:
                edges.append(((p, q) if p[1] < q[1] else (q, p), 1 if q[1] > p[1] else -1))
    cuts = {v for (p, q), _ in edges for v in (p[1], q[1])}
    for (e, _), (f, _) in itertools.combinations(edges, 2):
        t = _crossing_height(e, f)
        if t is not None:
            cuts.add(t)

    def passes(wind: int) -> bool:
        return wind % 2 != 0 if rule == "evenodd" else wind != 0

    image = np.full((height, width), Fraction(0), dtype=object)
    for y in range(height):
        heights = sorted({Fraction(y), Fraction(y + 1)} | {t for t in cuts if y < t < y + 1})
        for a, b in itertools.pairwise(heights):
            mid = (a + b) / 2
            spanning = sorted(
                (_x_on(e, mid), w, e) for e, w in edges if e[0][1] <= a and b <= e[1][1]
            )
            wind = 0
            for _, w, e in spanning:
                side = int(passes(wind)) - int(passes(wind + w))  # +1: right boundary, -1: left
                wind += w
                if side:
                    for c in range(width):
                        image[y, c] += side * _column_integral(e, a, b, c)
    return image


def _check_against_fractions(polygon, width, height, rule, bits):
    ours = area_coverage(polygon, width, height, rule=rule, subpixel_bits=bits)
    expected = exact_rule_coverage(Polygon(polygon), width, height, rule, bits).astype(float)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=TOLERANCE)


@st.composite
def many_vertex_polygons(draw, width: int, height: int, fewest: int = 6, most: int = 16):
    """One contour of many vertices (heavily self-intersecting), on a 1/8 grid or off it."""
    count = draw(st.integers(fewest, most))
    grid = st.integers(-8, 8 * width + 8).map(lambda v: v / 8)
    rows = st.integers(-8, 8 * height + 8).map(lambda v: v / 8)
    points = [(draw(grid), draw(rows)) for _ in range(count)]
    if draw(st.booleans()):  # off the grid: crossings, vertex heights and pixel lines all differ
        points = [(x + 0.013 * i, y + 0.007 * (i % 5)) for i, (x, y) in enumerate(points)]
    if len(set(points)) < 3:
        points += [(0.5, 0.5), (3.0, 0.5), (0.5, 3.0)]
    return Polygon(points)


@settings(max_examples=settings.default.max_examples // 4)
@given(
    many_vertex_polygons(6, 5), st.sampled_from(["nonzero", "evenodd"]), st.sampled_from([8, None])
)
def test_issue14_d3_many_vertex_self_intersecting_polygons_match_exact_fractions(
    polygon, rule, bits
):
    _check_against_fractions(polygon, 6, 5, rule, bits)


@settings(max_examples=settings.default.max_examples // 10)
@given(
    many_vertex_polygons(16, 16, fewest=50, most=300),
    st.sampled_from(["nonzero", "evenodd"]),
    st.sampled_from([8, None]),
)
def test_issue14_d3_hundreds_of_vertices_match_shapely(polygon, rule, bits):
    _check_against_oracle(polygon, 16, 16, rule, bits)


@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
@pytest.mark.parametrize(
    "contours",
    [
        # Eight edges through one point (a pinwheel of triangles): one crossing of many pairs.
        [[(3, 2.5), (5.5, 3.25), (5.5, 1.75)], [(3, 2.5), (0.5, 1.75), (0.5, 3.25)],
         [(3, 2.5), (3.75, 5), (2.25, 5)], [(3, 2.5), (2.25, 0), (3.75, 0)]],
        # A horizontal edge crossed by other edges: the winding changes along it.
        [[(0.5, 0.5), (5.5, 0.5), (5.5, 2.5), (0.5, 2.5)], [(2, 1.5), (4, 1.5), (4, 4.5), (2, 4.5)],
         [(1, 1.5), (5, 3.5), (1, 3.5)]],
        # Crossings exactly at vertex heights, on pixel lines and at pixel corners.
        [[(0, 0), (4, 4), (4, 0), (0, 4)], [(1, 1), (5, 1), (3, 3)], [(2, 0), (2, 4), (6, 2)]],
        # Overlapping collinear edges, a retraced spike and a contour run twice.
        [[(0.5, 0.5), (4.5, 0.5), (4.5, 4.5), (2.5, 2.5), (5.75, 4.75), (2.5, 2.5), (0.5, 4.5)],
         [(1, 1), (4, 4), (1, 4)], [(1, 1), (4, 4), (1, 4)]],
        # Nested and crossing contours of both orientations.
        [[(0.25, 0.25), (5.75, 0.25), (5.75, 4.75), (0.25, 4.75)],
         [(1, 1), (1, 4), (5, 4), (5, 1)], [(2, 0.5), (4, 0.5), (4, 4.5), (2, 4.5)]],
    ],
)  # fmt: skip
def test_issue14_d3_degenerate_sweeps_match_exact_fractions(contours, rule):
    _check_against_fractions(contours, 6, 5, rule, 8)
    _check_against_fractions([np.array(c) + (0.01, 0.003) for c in contours], 6, 5, rule, None)


@settings(max_examples=settings.default.max_examples // 4)
@given(many_vertex_polygons(8, 6), st.integers(0, 5))
def test_a_rows_areas_depend_only_on_the_edges_reaching_it(polygon, y):
    # `antialias.edge_algorithm` runs the kernel on one pixel's row with just those edges.
    edges = area._edge_arrays(area.snapped_vertices(polygon, 8), polygon.offsets)
    rows, _ = area._coverage_kernel(*edges, 8, 6, False, 0, 6, 2**62)
    reach = (edges[1] < y + 1) & (edges[3] > y)
    alone, _ = area._coverage_kernel(*(a[reach] for a in edges), 8, 6, False, y, y + 1, 2**62)
    np.testing.assert_array_equal(rows[y], alone[0])


@pytest.mark.parametrize("name", ["convex", "concave", "umbc_example", "comb", "sliver"])
def test_sum_of_areas_is_the_polygon_area(name):
    shape = catalog.get(name)
    snapped = np.rint(shape.polygon.contours[0] * 256) / 256
    _, _, areas = pixel_areas(shape.polygon, shape.width, shape.height)
    assert areas.sum() == pytest.approx(shapely.Polygon(snapped).area, rel=1e-14)


def test_polygons_sharing_an_edge_sum_to_their_union():
    left = [(1.3, 0.7), (6.1, 2.2), (4.9, 9.4), (0.6, 7.7)]
    right = [(6.1, 2.2), (11.2, 1.1), (10.4, 8.8), (4.9, 9.4)]
    union = [(1.3, 0.7), (6.1, 2.2), (11.2, 1.1), (10.4, 8.8), (4.9, 9.4), (0.6, 7.7)]
    total = area_coverage(left, 12, 10) + area_coverage(right, 12, 10)
    np.testing.assert_allclose(total, area_coverage(union, 12, 10), rtol=0, atol=1e-12)
    assert total.max() <= 1 + 1e-12


@pytest.mark.parametrize("shift", [(3, 2), (-2, 5), (7, -1)])
def test_integer_translation_shifts_the_coverage(shift):
    shape = catalog.get("pentagram")
    dx, dy = shift
    base = area_coverage(shape.polygon, 64, 64)
    moved = area_coverage([c + shift for c in shape.polygon.contours], 64, 64)
    expected = np.roll(base, (dy, dx), axis=(0, 1))
    kept = np.s_[max(dy, 0) :, max(dx, 0) :]  # rows and columns that np.roll did not wrap
    np.testing.assert_allclose(
        moved[kept], expected[kept], rtol=0, atol=TOLERANCE
    )  # float rounding
    assert np.array_equal(moved[kept] > 0, expected[kept] > 0)


@pytest.mark.parametrize(
    "name",
    [
        name
        for name, shape in catalog.SHAPES.items()
        if shape.degenerate and name != "sliver_between_rows"
    ],
)
def test_zero_area_shapes_cover_nothing(name):
    shape = catalog.get(name)
    for rule in ("nonzero", "evenodd"):
        ys, xs, areas = pixel_areas(shape.polygon, shape.width, shape.height, rule=rule)
        assert len(ys) == len(xs) == len(areas) == 0
        assert not area_coverage(shape.polygon, shape.width, shape.height, rule=rule).any()


def test_sliver_between_rows_has_area_though_it_covers_no_sample():
    shape = catalog.get("sliver_between_rows")
    _, _, areas = pixel_areas(shape.polygon, shape.width, shape.height)
    assert areas.sum() == pytest.approx(shapely.Polygon(shape.polygon.contours[0]).area, rel=1e-14)


def test_subpixel_triangle_has_its_exact_area_in_its_pixel():
    ys, xs, areas = pixel_areas(catalog.get("subpixel").polygon, 8, 8)
    assert (ys.tolist(), xs.tolist()) == ([5], [5])
    # Shoelace of (5.25, 5.25), (5.875, 5.375), (5.5, 5.875): exactly representable.
    assert areas[0] == pytest.approx(0.5 * abs(0.625 * 0.625 - 0.125 * 0.25), abs=TOLERANCE)


def test_square_with_hole_golden():
    square_with_hole = [
        [(0, 0), (3, 0), (3, 3), (0, 3)],
        [(0.5, 0.5), (0.5, 2.5), (2.5, 2.5), (2.5, 0.5)],
    ]
    expected = [[0.75, 0.5, 0.75], [0.5, 0.0, 0.5], [0.75, 0.5, 0.75]]
    np.testing.assert_array_equal(area_coverage(square_with_hole, 3, 3), expected)


def test_only_pixels_inside_the_raster_are_reported():
    ys, xs, areas = pixel_areas([(-5, -5), (40, -5), (40, 40), (-5, 40)], 4, 3)
    assert len(areas) == 12 and np.all(areas == 1.0)
    assert area_coverage([(0, 0), (2, 0), (0, 2)], 0, 0).shape == (0, 0)
    assert area_coverage([(10, 10), (12, 10), (10, 12)], 4, 4).sum() == 0


def test_bad_input_raises_like_scan_convert():
    triangle = [(0, 0), (2, 0), (0, 2)]
    with pytest.raises(ValueError, match="'rule' must be one of"):
        pixel_areas(triangle, 4, 4, rule="winding")
    with pytest.raises(ValueError, match="not finite"):
        area_coverage([(0, 0), (np.nan, 0), (0, 2)], 4, 4)
    with pytest.raises(ValueError, match="'subpixel_bits' must be in"):
        area_coverage(triangle, 4, 4, subpixel_bits=17)
    with pytest.raises(TypeError, match="'width' must be an int"):
        area_coverage(triangle, 4.0, 4)
    with pytest.raises(ValueError, match="distinct vertices"):
        pixel_areas([(0, 0), (1, 1), (0, 0)], 4, 4)


def test_coverage_benchmark_quick_prints_every_method(tmp_path, capsys):
    from scanviz.bench.coverage import methods
    from scanviz.cli import main

    plot = tmp_path / "coverage.png"
    assert main(["bench", "coverage", "--quick", "--plot", str(plot)]) == 0
    lines = capsys.readouterr().out.splitlines()
    for name, _ in methods():
        assert any(line.startswith(name) for line in lines), name
    exact = next(line for line in lines if line.startswith("exact area")).split()
    assert exact[-3:-1] == ["0.00e+00", "0.00e+00"]  # RMS and max error of the reference itself
    assert plot.stat().st_size > 0


def test_issue8_d7_memory_is_linear_in_the_edges_and_stays_exact():
    # The old kernel sized a break buffer n(n-1)/2 for n edges active in one row.
    from scanviz.limits import ResourceLimitError, memory_limit

    n = 100_000
    x = 64 * np.arange(n) / n
    top = np.stack([x[::-1], np.where(np.arange(n) % 2, 1.0, 0.5)], axis=1)  # a zigzag roof
    roof = Polygon(np.concatenate([[(0, 0), (64, 0)], top]))
    with memory_limit("64M"):
        ours = area_coverage(roof, 64, 1, subpixel_bits=None)
    expected = oracle_coverage(roof, 64, 1, "nonzero", None)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=1e-9)
    # A zigzag whose closing edge crosses all of its 2,000 edges in one row.
    zigzag = Polygon(np.stack([8 * np.arange(2000) / 2000, np.arange(2000) % 2], axis=1))
    with memory_limit("8M"):  # the old buffer alone: 16 MB
        ours = area_coverage(zigzag, 8, 1, subpixel_bits=None)
    expected = oracle_coverage(zigzag, 8, 1, "nonzero", None)
    np.testing.assert_allclose(ours, expected, rtol=0, atol=1e-9)
    with pytest.raises(ResourceLimitError, match="area_coverage: a 65536x65536 float64 raster"):
        area_coverage([(0, 0), (9, 0), (0, 9)], 65536, 65536)


@pytest.mark.parametrize("huge", [10**400, 2**1024])
def test_issue8_d8_huge_ints_are_a_value_error_naming_the_vertex(huge):
    with pytest.raises(ValueError, match=r"contour 0 vertex 1 = .* \+-2\*\*20"):
        area_coverage([(0, 0), (huge, 0), (0, 1)], 8, 8)


def test_issue8_d9_non_real_coordinates_are_a_type_error():
    for bad in (7j, "4", True):
        with pytest.raises(TypeError, match=r"contour 0 .* numbers .* vertex 1 holds"):
            area_coverage([(0, 0), (bad, 0), (0, 4)], 8, 8)


def test_issue14_d3_one_row_crossed_by_all_its_edges_now_renders():
    # Refused before issue 14 (1e10 edge visits): 100,000 edges in one pixel row, nearly all
    # crossed by the closing edge. The sweep swaps each crossing pair once: ~1e5 steps.
    n = 100_000
    zigzag = np.stack([64 * np.arange(n) / n, np.arange(n) % 2], axis=1)
    ours = area_coverage(zigzag, 64, 1, subpixel_bits=None)
    # The same polygon from another start vertex: the same edges, so the same areas.
    rotated = area_coverage(np.roll(zigzag, 12_345, axis=0), 64, 1, subpixel_bits=None)
    np.testing.assert_allclose(ours, rotated, rtol=0, atol=1e-12)
    # Its total is 64 (n - 1) / (3 n), as for the 2,000-edge zigzag checked against shapely above.
    assert ours.sum() == pytest.approx(64 * (n - 1) / (3 * n), abs=1e-9)
    assert ours.min() >= 0 and ours.max() <= 1


def _crossing_fan(n: int) -> np.ndarray:
    """A zigzag whose 2n edges all run between the bottom and top of row 0 and nearly all cross."""
    bottom = 64 * np.arange(n) / n
    top = 64 - bottom - 32 / n
    return np.stack([np.stack([bottom, top], 1).ravel(), np.tile([0.0, 1.0], n)], axis=1)


def test_issue8_d7_a_polygon_needing_too_much_work_is_refused_before_the_sweep(monkeypatch):
    # 40,000 edges spanning one pixel row, about 8e8 pairs crossing inside it.
    def must_not_run(*args):
        raise AssertionError("the sweep ran before the refusal")

    monkeypatch.setattr(area, "_coverage_kernel", must_not_run)
    fan = _crossing_fan(20_000)
    message = (
        r"area_coverage: a 64x1 float64 raster: the polygon's 40000 edges need too many sweep "
        r"steps \(at least 8e\+08, limit 67108864\): every crossing of two edges inside a "
        r"pixel row is a step"
    )
    with pytest.raises(ValueError, match=message):
        area_coverage(fan, 64, 1, subpixel_bits=None)
    with pytest.raises(ValueError, match=r"pixel_areas: .*\(at least 8e\+08, limit"):
        pixel_areas(fan, 64, 1, subpixel_bits=None)


def test_the_sweep_stops_at_the_work_limit_when_the_lower_bound_passes(monkeypatch):
    fan = _crossing_fan(200)  # about 80,000 crossings
    monkeypatch.setattr(area, "_least_work", lambda *args: 0.0)
    monkeypatch.setattr(area, "MAX_WORK", 10_000)
    with pytest.raises(ValueError, match=r"too many sweep steps \(over 10\d\d\d, limit 10000\)"):
        area_coverage(fan, 64, 1, subpixel_bits=None)
    monkeypatch.setattr(area, "MAX_WORK", 10**6)
    assert area_coverage(fan, 64, 1, subpixel_bits=None).shape == (1, 64)


@settings(derandomize=True, max_examples=100, deadline=None)
@given(st.one_of(random_polygons(), many_vertex_polygons(12, 10)), st.booleans())
def test_the_early_refusal_counts_no_more_work_than_the_sweep_does(polygon, evenodd):
    # A lower bound: the early refusal never refuses a polygon the sweep would render.
    edges = area._edge_arrays(area.snapped_vertices(polygon, 8), polygon.offsets)
    row0, row1 = area._row_range(edges[1], edges[3], 10)
    least = area._least_work(*edges[:4], row0, row1, 2**62)
    _, work = area._coverage_kernel(*edges, 12, 10, evenodd, row0, row1, 2**62)
    assert least <= work


@pytest.mark.parametrize(
    ("width", "height", "error"),
    [(4.0, 10**400, TypeError), (True, None, TypeError), (4, 10**400, ValueError)],
)
def test_issue8_fuzz_raster_size_is_checked_before_the_memory_estimate(width, height, error):
    # Found by the fuzz campaign: the estimate multiplied width * height before they were checked.
    with pytest.raises(error, match="'width'|'height'"):
        area_coverage([(0, 0), (4, 0), (0, 3)], width, height)

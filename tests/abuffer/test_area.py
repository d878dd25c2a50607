"""Exact area coverage against a shapely oracle, plus invariants and golden cases."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.ops import polygonize, unary_union

from scanviz import Polygon, catalog
from scanviz.abuffer.area import area_coverage, pixel_areas

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


def test_issue8_d7_a_polygon_needing_too_many_strips_is_refused_before_the_sweep(monkeypatch):
    # 100,000 edges in one pixel row, nearly all crossed by the closing edge: ~1e10 edge visits.
    from scanviz.abuffer import area

    def must_not_run(*args):
        raise AssertionError("the sweep ran before the refusal")

    monkeypatch.setattr(area, "_coverage_kernel", must_not_run)
    n = 100_000
    zigzag = Polygon(np.stack([64 * np.arange(n) / n, np.arange(n) % 2], axis=1))
    message = (
        r"area_coverage: a 64x1 float64 raster: the polygon's 100000 edges cut its rows into "
        r"too many strips \(at least 1e\+10 edge visits, limit 67108864\): every vertex height "
        r"and every crossing of two edges inside a pixel row starts a strip"
    )
    with pytest.raises(ValueError, match=message):
        area_coverage(zigzag, 64, 1, subpixel_bits=None)
    with pytest.raises(ValueError, match=r"pixel_areas: .*\(at least 1e\+10 edge visits"):
        pixel_areas(zigzag, 64, 1, subpixel_bits=None)


@settings(derandomize=True, max_examples=100, deadline=None)
@given(random_polygons())
def test_the_early_refusal_counts_no_more_work_than_the_sweep_does(polygon):
    # A lower bound: the early refusal never refuses a polygon the sweep would render.
    from scanviz.abuffer import area

    edges = area._edge_arrays(area.snapped_vertices(polygon, 8), polygon.offsets)
    row0, row1 = area._row_range(edges[1], edges[3], 10)
    least = area._least_work(*edges[:4], row0, row1, 2**62)
    _, work = area._coverage_kernel(*edges, 12, 10, False, row0, row1, 2**62)
    assert least <= work


@pytest.mark.parametrize(
    ("width", "height", "error"),
    [(4.0, 10**400, TypeError), (True, None, TypeError), (4, 10**400, ValueError)],
)
def test_issue8_fuzz_raster_size_is_checked_before_the_memory_estimate(width, height, error):
    # Found by the fuzz campaign: the estimate multiplied width * height before they were checked.
    with pytest.raises(error, match="'width'|'height'"):
        area_coverage([(0, 0), (4, 0), (0, 3)], width, height)

"""DISLOP_E: Wang 1989 Fig 5-6 and Table 4-6, the formula against half-plane clipping, exact area."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.abuffer.area import area_coverage
from scanviz.antialias import dislop_edge
from scanviz.antialias.columns import edge_column

# Fig 5-6: the shared edge (100.3,150.2)-(108.6,155.8), pixel: (flag 0, flag 1); spec §4.1.
FIG_5_6 = {
    (101, 151): (0.807524, 0.192476), (101, 150): (0.020192, 0.979808),
    (102, 152): (0.974819, 0.025181), (102, 151): (0.178196, 0.821804),
    (103, 152): (0.478315, 0.521685),
    (104, 153): (0.788889, 0.211111), (104, 152): (0.014726, 0.985274),
    (105, 154): (0.967804, 0.032196), (105, 153): (0.161111, 0.838889),
    (106, 154): (0.454216, 0.545784),
    (107, 155): (0.769395, 0.230605), (107, 154): (0.010121, 0.989879),
    (108, 156): (0.959929, 0.040071), (108, 155): (0.144887, 0.855113),
}  # fmt: skip
M40 = math.tan(40 * 3.14156 / 180)
TABLE_4_6 = {  # j: (up, mid, low) for dxy = -1/2 + j/56, flag 1 (spec §3.7, golden check 17)
    0: (0.0, 0.1049, 0.8951),
    23: (0.0, 0.4108, 1.0),
    24: (0.0, 0.4286, 0.0),
    34: (0.0004, 0.6067, 0.0),
    56: (0.1049, 0.8951, 0.0),
}


def test_fig_5_6_shared_edge():
    """The edge as the top of a polygon below it (flag 1) and the bottom of one above (flag 0)."""
    a, b = (100.8, 150.7), (109.1, 156.3)  # shifted by 1/2 into scanviz's pixels
    below = dislop_edge([a, b, (109.1, 140), (100.8, 140)], 120, 170)
    above = dislop_edge([b, a, (100.8, 165), (109.1, 165)], 120, 170)
    for (x, y), (flag0, flag1) in FIG_5_6.items():
        assert above[y, x] == pytest.approx(flag0, abs=1e-5)
        assert below[y, x] == pytest.approx(flag1, abs=1e-5)
        assert above[y, x] + below[y, x] == pytest.approx(1.0, abs=1e-12)


def test_table_4_6():
    for j, areas in TABLE_4_6.items():
        assert edge_column(M40, -0.5 + j / 56, 1)[:3] == pytest.approx(areas, abs=1e-4)


@given(st.floats(0, 1), st.floats(-0.5, 0.5, exclude_min=True), st.sampled_from([0, 1]))
@settings(max_examples=settings.default.max_examples // 2)
def test_formula_is_exact_on_cut_pixels(m, dxy, flag):
    """Golden check 24: against shapely clipping of the half-plane, effective coverage."""
    far = 10.0
    line = [(-far, dxy - m * far), (far, dxy + m * far)]
    side = [(far, -3 * far if flag else 3 * far), (-far, -3 * far if flag else 3 * far)]
    half_plane = shapely.Polygon(line + side)
    up, mid, low, _, _, branch = edge_column(m, dxy, flag)
    for row, area in ((1, up), (0, mid), (-1, low)):
        exact = half_plane.intersection(shapely.box(-0.5, row - 0.5, 0.5, row + 0.5)).area
        if row == 0 or (branch == 1 and (row == 1) == (dxy > 0)):
            assert area == pytest.approx(exact, abs=1e-9)


def _polygon(data, holes):
    """A star around (cx, cy), with a hole of opposite orientation inside it if `holes`."""
    n = data.draw(st.integers(4 if holes else 3, 9))
    radii = data.draw(st.lists(st.floats(3.5 if holes else 1.5, 8), min_size=n, max_size=n))
    jitter = data.draw(st.lists(st.floats(0, 0.5), min_size=n, max_size=n))
    angles = (np.arange(n) + np.array(jitter)) * 2 * math.pi / n  # gaps < pi: the centre is inside
    cx, cy = data.draw(st.floats(8, 12)), data.draw(st.floats(8, 12))
    outer = np.c_[cx + np.cos(angles) * radii, cy + np.sin(angles) * radii]
    if data.draw(st.booleans()):
        outer = outer[::-1]
    if not holes:
        return outer
    hole = np.array([(cx - 0.7, cy - 0.6), (cx + 0.9, cy - 0.5), (cx + 0.1, cy + 0.8)])
    return [outer, hole[::-1] if _signed(outer) > 0 else hole]


def _signed(p):
    return 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])


@given(st.data(), st.booleans())
@settings(max_examples=settings.default.max_examples // 7)
def test_equals_exact_area_coverage(data, holes):
    polygon = _polygon(data, holes)
    expected = area_coverage(polygon, 21, 21, subpixel_bits=None)
    assert np.abs(dislop_edge(polygon, 21, 21) - expected).max() < 1e-9


@given(st.lists(st.tuples(st.floats(1, 20), st.floats(1, 20)), min_size=3, max_size=9))
@settings(max_examples=settings.default.max_examples // 4)
def test_self_intersecting_polygons_are_exact(points):
    """Crossing edges are split, so each piece has one inside side (nonzero winding)."""
    if len(set(points)) < 3:
        return
    expected = area_coverage(points, 21, 21, subpixel_bits=None)
    assert np.abs(dislop_edge(points, 21, 21) - expected).max() < 1e-9


def test_figure_eight_crossing_pixel():
    bow = [(2.2, 2.3), (8.6, 7.9), (8.4, 2.1), (2.1, 7.7)]  # winding +1 and -1 lobes
    image = dislop_edge(bow, 11, 11)
    assert np.abs(image - area_coverage(bow, 11, 11, subpixel_bits=None)).max() < 1e-12


def test_same_orientation_inner_contour_is_no_hole_under_nonzero():
    outer, inner = (
        [(1, 1), (9, 1), (9, 9), (1, 9)],
        [(3.2, 3.2), (6.7, 3.2), (6.7, 6.7), (3.2, 6.7)],
    )
    image = dislop_edge([outer, inner], 10, 10)
    assert np.abs(image - area_coverage([outer, inner], 10, 10, subpixel_bits=None)).max() < 1e-12
    assert image[4, 4] == 1.0


def test_degenerate_polygons():
    assert not dislop_edge([(0, 0), (5, 5), (10, 10)], 12, 12).any()  # collinear: zero area
    assert not dislop_edge([(-9, -9), (-5, -9), (-5, -5)], 8, 8).any()  # off the raster
    sliver = [(0.2, 1.1), (9.7, 1.2), (0.2, 1.15)]
    assert (
        np.abs(dislop_edge(sliver, 10, 3) - area_coverage(sliver, 10, 3, subpixel_bits=None)).max()
        < 1e-12
    )


@pytest.mark.parametrize(
    "polygon, size, error",
    [
        ([(0, 0), (1, math.inf), (1, 0)], (4, 4), ValueError),
        ([(0, 0), (1, 1)], (4, 4), ValueError),
        ([(0, 0), (1, 1), (1, 0)], (4, -4), ValueError),
        ([(0, 0), (1, "a"), (1, 0)], (4, 4), TypeError),
    ],
)
def test_bad_input(polygon, size, error):
    with pytest.raises(error):
        dislop_edge(polygon, *size)


# DISLOP_E slices (golden check 18): (m, dxy, flag, (up, mid, low)); skip |cv| < 1e-6.
EDGE_SLICES = [
    (0.84, -0.5, 1, (0.0, 0.1050, 0.8950)),  # Table 4-9, j = 0
    (0.84, -0.06, 1, (0.0, 0.4400, 0.0)),  # j = 22: one-pixel branch
    (0.84, 0.10, 1, (0.0002, 0.5998, 0.0)),  # j = 30
    (0.68, -0.5, 0, (0.0, 0.9150, 0.0850)),  # Table 5-3, j = 0
    (0.68, -0.5, 1, (0.0, 0.0850, 0.9150)),  # Table 5-4, j = 0
    (0.68, 0.5, 1, (0.0850, 0.9150, 0.0)),  # j = 50
]


@pytest.mark.parametrize("m, dxy, flag, areas", EDGE_SLICES)
def test_edge_slices(m, dxy, flag, areas):
    assert edge_column(m, dxy, flag)[:3] == pytest.approx(areas, abs=1e-4)


def test_traced_equals_untraced_and_events():
    a, b = (100.8, 150.7), (109.1, 156.3)
    polygon = [a, b, (109.1, 140), (100.8, 140)]
    image, trace = dislop_edge(polygon, 120, 170, trace=True)
    assert np.array_equal(image, dislop_edge(polygon, 120, 170))
    top = {e.x: e for e in trace if e.major == "x" and e.y > 145}
    assert sorted(top) == list(range(101, 109))  # the columns the edge spans fully
    assert top[103].branch == "one_pixel" and top[103].mid == pytest.approx(0.521685, abs=1e-5)
    assert top[101].branch == "two_pixel" and top[101].low == pytest.approx(0.979808, abs=1e-5)


def _traced_and_compiled(polygon, size):
    traced, _ = dislop_edge(polygon, size, size, trace=True)
    return traced, dislop_edge(polygon, size, size)


coordinate = st.floats(-6, 22, allow_nan=False)


@given(st.lists(st.tuples(coordinate, coordinate), min_size=3, max_size=12), st.booleans())
@settings(max_examples=settings.default.max_examples // 4)
def test_compiled_equals_traced(points, on_grid):
    """Random polygons, self-intersecting and partly off the 16x16 raster: the same bits."""
    points = np.array(points)
    if on_grid:  # shared vertices, collinear and axis-parallel edges
        points = np.rint(points * 4) / 4
    if len(np.unique(points, axis=0)) < 3:
        return
    traced, compiled = _traced_and_compiled(points, 16)
    assert np.array_equal(traced, compiled)


@given(st.data(), st.booleans())
@settings(max_examples=settings.default.max_examples // 10)
def test_compiled_equals_traced_with_holes(data, holes):
    traced, compiled = _traced_and_compiled(_polygon(data, holes), 21)
    assert np.array_equal(traced, compiled)


@pytest.mark.parametrize(
    "polygon",
    [
        [(0, 0), (5, 5), (10, 10)],  # collinear: zero area
        [(1.5, 1.5), (6.5, 1.5), (6.5, 1.5), (6.5, 1.5), (3, 7.25)],  # repeated vertices
        [(1, 1), (7, 1), (4, 1), (4, 6), (4, 3)],  # zero-area spikes, edges folding back
        [(2, 2), (8, 8), (2, 8), (8, 2), (2, 2), (5, 5)],  # bow tie through a repeated vertex
        [(-9, -9), (-5, -9), (-5, -5)],  # off the raster
        [[(1, 1), (9, 1), (9, 9), (1, 9)], [(1, 1), (9, 1), (9, 9), (1, 9)]],  # winding 2
        [[(1, 1), (9, 1), (9, 9), (1, 9)], [(1, 9), (9, 9), (9, 1), (1, 1)]],  # cancels: 0
        [(0, 0), (0, 1), (0, 2.5063623372388222e-104)],  # an edge that vanishes in x - 1/2
        [(3, 1e-300), (8, 0), (8, 6), (3, 0)],  # a side shorter than the rounding at y - 1/2
    ],
)
def test_degenerate_polygons_compiled_equals_traced(polygon):
    traced, compiled = _traced_and_compiled(polygon, 10)
    assert np.array_equal(traced, compiled)
    exact = area_coverage(polygon, 10, 10, subpixel_bits=None)
    assert np.abs(compiled - exact).max() < 1e-12

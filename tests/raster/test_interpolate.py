"""Interpolation along edges and spans (thesis §6.2): the formulas, exact oracles, the trace.

The plane of a triangle against Fractions; the interpolating ET/AET against
`scan_convert` (same spans) and against barycentric values; constants stay
exactly constant; compensated stepping against plain stepping; the
`edge_values` and `span_values` events against the formulas they show.
"""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Polygon, Recorder, scan_convert
from scanviz.conventions import SAMPLE_MODES
from scanviz.raster.fixed import snap
from scanviz.raster.interpolate import (
    EdgeInterpolant,
    Plane,
    compensated_step,
    depth_plane,
    edge_slope,
    edge_start,
    interpolate_rows,
    perspective_divide,
    polygon_plane,
    span_samples,
    span_slope,
    vertex_channels,
)

BASE = settings.default.max_examples
F = Fraction
WIDTH, HEIGHT = 20, 16
FLAT = Plane(0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # z = 0: spans do not depend on the plane

grid = st.integers(-4 * 64, (WIDTH + 4) * 64).map(lambda v: v / 64)
contour = st.lists(st.tuples(grid, grid), min_size=3, max_size=7)
triangle = st.lists(st.tuples(grid, grid), min_size=3, max_size=3, unique=True)


def one_contour(points) -> Polygon | None:
    try:
        return Polygon(points)
    except ValueError:  # fewer than 3 distinct vertices
        return None


def rows_of(snapped, channels, plane=FLAT, trace=None):
    return list(
        interpolate_rows(snapped, plane, np.asarray(channels, float), WIDTH, HEIGHT, trace=trace)
    )


def affine(points, values, x, y):
    """Barycentric interpolation of `values` over the exact triangle `points` at (x, y)."""
    (x0, y0), (x1, y1), (x2, y2) = points
    det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    l1 = ((x - x0) * (y2 - y0) - (x2 - x0) * (y - y0)) / det
    l2 = ((x1 - x0) * (y - y0) - (x - x0) * (y1 - y0)) / det
    return values[0] * (1 - l1 - l2) + values[1] * l1 + values[2] * l2


# --- the formulas --------------------------------------------------------------------------


@settings(max_examples=BASE)
@given(points=triangle, depths=st.lists(st.floats(-2, 2), min_size=3, max_size=3))
def test_depth_plane_of_a_triangle_is_exact_to_rounding(points, depths):
    xs, ys = [x for x, _ in points], [y for _, y in points]
    a, b, c, dzdx, dzdy, z_first = depth_plane(xs, ys, depths)
    exact = [(F(x), F(y), F(z)) for (x, y), z in zip(points, depths, strict=True)]
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = exact
    twice_area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    assert c == twice_area  # grid coordinates: exact in float64
    if twice_area == 0:
        assert (dzdx, dzdy, z_first) == (0.0, 0.0, depths[0])
        return
    exact_dzdx = -((y1 - y0) * (z2 - z0) - (z1 - z0) * (y2 - y0)) / twice_area
    exact_dzdy = -((z1 - z0) * (x2 - x0) - (x1 - x0) * (z2 - z0)) / twice_area
    scale = max(abs(exact_dzdx), abs(exact_dzdy), 1)
    assert abs(dzdx - exact_dzdx) <= 1e-12 * scale and abs(dzdy - exact_dzdy) <= 1e-12 * scale
    assert abs(z_first - depths[0]) <= 1e-12 * (1 + float(scale) * 100)


def test_span_slope_of_crossings_rounding_together_is_zero():
    assert span_slope(1.0, 5.0, 3.0, 3.0) == 0.0
    assert span_slope(1.0, 5.0, 3.0, 5.0) == 2.0


def test_perspective_divide_guards_a_vanishing_one_over_w():
    assert perspective_divide(3.0, 0.5) == 6.0
    assert perspective_divide(3.0, 0.0) == 0.0 and perspective_divide(3.0, -1e-300) == 0.0


def test_compensated_steps_do_not_drift():
    plain, total, carry = 1.0, 1.0, 0.0
    for _ in range(100_000):
        plain += 1e-6
        total, carry = compensated_step(total, carry, 1e-6)
    exact = 1 + F(1e-6) * 100_000
    assert abs(F(total) - exact) <= F(2.0**-52)  # within an ulp of 1.1
    assert abs(F(plain) - exact) > 100 * F(2.0**-52)  # the textbook z += dz drifts


def test_vertex_channels():
    values, inv_w = np.array([[2.0, 4.0], [1.0, 3.0]]), np.array([0.5, 0.25])
    np.testing.assert_array_equal(vertex_channels(values, inv_w, False), values)
    np.testing.assert_array_equal(
        vertex_channels(values, inv_w, True), [[1.0, 2.0, 0.5], [0.25, 0.75, 0.25]]
    )
    assert vertex_channels(np.zeros((2, 0)), inv_w, True).shape == (2, 1)


def test_edge_interpolant_starts_from_its_lower_end_and_steps():
    edge = EdgeInterpolant([1.0, 0.0], [4.0, 3.0], 0.5, 2.0, 1)
    assert edge.dvdy == [2.0, 2.0] and edge.values == [2.0, 1.0]
    edge.step()
    assert edge.values == [4.0, 3.0]


# --- interpolating scan conversion -----------------------------------------------------------


@settings(max_examples=2 * BASE)
@given(points=contour, sample=st.sampled_from(SAMPLE_MODES), bits=st.sampled_from([0, 4, 8, 16]))
def test_spans_are_scan_convert_spans(points, sample, bits):
    polygon = one_contour(points)
    if polygon is None:
        return
    snapped = snap(polygon, sample, bits)
    spans = [
        (y, s.x_start, s.x_end)
        for y, row in rows_of(snapped, np.zeros((len(points), 0)))
        for s in row
    ]
    expected = scan_convert(polygon, WIDTH, HEIGHT, sample=sample, subpixel_bits=bits, trace=True)
    assert spans == [tuple(s) for s in expected.spans.tolist()]


@settings(max_examples=BASE)
@given(points=contour, constant=st.floats(-1e6, 1e6), perspective_w=st.floats(0.1, 10))
def test_a_constant_stays_exactly_constant(points, constant, perspective_w):
    polygon = one_contour(points)
    if polygon is None:
        return
    channels = np.full((len(points), 2), constant)
    for _, row in rows_of(snap(polygon), channels):
        for span in row:
            assert span.dvdx == (0.0, 0.0)
            assert all(values == (constant, constant) for _, _, values in span_samples(span))


@settings(max_examples=BASE)
@given(
    points=triangle,
    values=st.lists(st.floats(-1, 1), min_size=3, max_size=3),
    sample=st.sampled_from(SAMPLE_MODES),
)
def test_triangle_depth_and_values_are_affine(points, values, sample):
    polygon = one_contour(points)
    if polygon is None:
        return
    snapped = snap(polygon, sample)
    depths = [0.25, -0.5, 0.75]
    plane = polygon_plane(snapped, depths)
    if plane.edge_on:
        return
    offset = F(1, 2) if sample == "center" else F(0)
    exact = [(F(x), F(y)) for x, y in points]  # on the 1/64 grid: snapping is exact
    for y, row in rows_of(snapped, np.array(values)[:, None], plane):
        for span in row:
            for x, z, (value,) in span_samples(span):
                sx, sy = x + offset, y + offset
                assert abs(z - float(affine(exact, [F(d) for d in depths], sx, sy))) <= 1e-12
                assert abs(value - float(affine(exact, [F(v) for v in values], sx, sy))) <= 1e-12


def test_events_show_the_formulas_they_ran():
    """Triangle (1,1)-(9,3)-(3,8) with values 0, 8, 4: each event recomputed from its inputs."""
    snapped = snap(Polygon([(1, 1), (9, 3), (3, 8)]))
    plane = polygon_plane(snapped, [0.5, 0.25, 0.75])
    recorder = Recorder()
    rows = rows_of(snapped, [[0.0], [8.0], [4.0]], plane, trace=recorder)
    trace = recorder.trace()
    edge_rows = trace.of_kind("edge_values")
    assert [e.y for e in edge_rows] == [y for y, _ in rows][: len(edge_rows)]
    first = edge_rows[0]  # row 1: both edges start at (1, 1), value 0, slopes from their ends
    assert first.y == 1 and [e.values for e in first.entries] == [(0.0,), (0.0,)]
    assert [e.edge for e in first.entries] == [0, 2]  # equal x: ties keep the AET order
    assert [e.dvdy for e in first.entries] == [
        (edge_slope(0.0, 8.0, 1.0, 3.0),),
        (edge_slope(0.0, 4.0, 1.0, 8.0),),
    ]
    assert first.z_row == plane.depth(0.0, 1)
    for below, above in zip(edge_rows, edge_rows[1:], strict=False):
        assert above.z_row == pytest.approx(below.z_row + plane.dzdy, abs=1e-15)
    row_3 = next(
        e for e in edge_rows if e.y == 3
    )  # the edge (9,3)-(3,8) enters: from its lower end
    entering = next(e for e in row_3.entries if e.edge == 1)
    assert entering.values == (edge_start(8.0, edge_slope(8.0, 4.0, 3.0, 8.0), 3.0, 3),)
    for event in trace.of_kind("span_values"):
        row = next(e for e in edge_rows if e.y == event.y)
        left, right = row.entries  # a triangle: two crossings bound each span
        assert (event.x_left, event.x_right) == (left.x, right.x)
        dvdx = span_slope(left.values[0], right.values[0], left.x, right.x)
        assert event.dvdx == (dvdx,)
        assert event.values == (left.values[0] + (event.x_start - left.x) * dvdx,)
        assert event.z == row.z_row + plane.dzdx * event.x_start
    assert trace[0].kind == "edge_table_built"
    assert [e.kind for e in trace if getattr(e, "y", None) == 3] == [
        "edges_retired", "edges_activated", "aet_sorted", "span", "edge_values", "span_values"
    ]  # fmt: skip


# --- the replaceable step span_step -----------------------------------------------------------


def test_span_step_compensates_the_depth_and_adds_the_values():
    from scanviz.raster.interpolate import span_step

    z, carry, values = 0.9, 0.0, (0.0, 1.0)
    plain = 0.9
    for _ in range(1000):
        z, carry, values = span_step(z, carry, values, 1e-4, (0.1, -0.001))
        plain += 1e-4
    exact = Fraction(0.9) + 1000 * Fraction(1e-4)
    assert abs(Fraction(z) - exact) <= abs(Fraction(plain) - exact)
    assert abs(Fraction(z) - exact) <= Fraction(2**-52)  # within an ulp of 1
    plain_values = (0.0, 1.0)
    for _ in range(1000):
        plain_values = (plain_values[0] + 0.1, plain_values[1] - 0.001)
    assert values == plain_values  # the values are plain sums, in order


def test_span_samples_take_their_step_from_the_step_table():
    from scanviz import steps
    from scanviz.trace import InterpolatedSpan

    span = InterpolatedSpan(0, 2, 6, 1.5, 6.5, 0.25, 0.5, (1.0,), (0.125,))
    assert [(x, z, v) for x, z, v in span_samples(span)][-1] == (
        5,
        1.75,
        (1.375,),
    )  # three steps from x = 2
    with steps.using(span_step=lambda z, carry, values, dzdx, dvdx: (z, carry, values)):
        assert [(x, z, v) for x, z, v in span_samples(span)] == [
            (x, 0.25, (1.0,)) for x in range(2, 6)
        ]

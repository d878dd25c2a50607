"""Pixel masks: exact per sub-sample, watertight, and the traced mask buffer agrees."""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from scanviz import Polygon
from scanviz.abuffer.masks import (
    MASK_LAYOUTS,
    full_mask,
    mask_buffer_rows,
    mask_to_grid,
    pixel_masks,
    popcount,
    subsample_positions,
)
from scanviz.trace import Filter, Recorder, Trace
from tests.oracle import snapped_contours, winding_number

LAYOUTS = sorted(MASK_LAYOUTS)
RULES = ["nonzero", "evenodd"]
EXAMPLES = settings.default.max_examples


def oracle_masks(polygon, width, height, layout, rule, bits) -> dict[tuple[int, int], int]:
    """{(y, x): mask} from the winding number of every sub-sample point, in Fractions."""
    cols, rows = MASK_LAYOUTS[layout]
    exact = snapped_contours([np.asarray(c).tolist() for c in polygon.contours], bits)
    xs = [x for contour in exact for x, _ in contour]
    ys = [y for contour in exact for _, y in contour]
    masks = {}
    for y in range(max(int(min(ys)) - 1, 0), min(int(max(ys)) + 1, height)):
        for x in range(max(int(min(xs)) - 1, 0), min(int(max(xs)) + 1, width)):
            mask = 0
            for j in range(rows):
                for i in range(cols):
                    point = (x + Fraction(2 * i + 1, 2 * cols), y + Fraction(2 * j + 1, 2 * rows))
                    winding = winding_number(exact, *point)
                    if (winding % 2 == 1) if rule == "evenodd" else winding != 0:
                        mask |= 1 << (j * cols + i)
            if mask:
                masks[(y, x)] = mask
    return masks


def as_dict(result) -> dict[tuple[int, int], int]:
    keys = list(zip(result.ys.tolist(), result.xs.tolist(), strict=True))
    assert keys == sorted(keys), "pixels must be sorted by y then x"
    assert result.masks.dtype == np.uint64 and (result.masks != 0).all()
    return dict(zip(keys, (int(m) for m in result.masks), strict=True))


# Coordinates on the 1/16 grid hit sub-sample centers and cell borders of every layout.
sixteenths = st.integers(-8, 4 * 16 + 8).map(lambda n: n / 16)
two_fifty_sixths = st.integers(-128, 4 * 256 + 128).map(lambda n: n / 256)
integers = st.integers(-1, 5).map(float)
coordinate = st.one_of(sixteenths, two_fifty_sixths, integers)


@st.composite
def polygons(draw, coordinates=coordinate):
    contours = []
    for _ in range(draw(st.integers(1, 2))):
        points = draw(st.lists(st.tuples(coordinates, coordinates), min_size=3, max_size=6))
        if len(set(points)) < 3:
            points = [(0.0, 0.0), (2.5, 0.25), (1.0, 3.0)]
        contours.append(points)
    return Polygon(contours)


# --- layout helpers ------------------------------------------------------------------------


@pytest.mark.parametrize("layout", LAYOUTS)
def test_bit_k_is_subsample_i_j_at_its_sub_cell_center(layout):
    cols, rows = MASK_LAYOUTS[layout]
    positions = subsample_positions(layout)
    assert positions.shape == (cols * rows, 2)
    for k in range(cols * rows):
        j, i = divmod(k, cols)
        assert positions[k].tolist() == [(i + 0.5) / cols, (j + 0.5) / rows]
        grid = mask_to_grid(1 << k, layout)
        assert grid.shape == (rows, cols) and grid.sum() == 1 and grid[j, i]
    assert popcount(full_mask(layout)) == cols * rows
    assert mask_to_grid(full_mask(layout), layout).all()


def test_popcount_is_vectorized():
    masks = np.array([[0, 2**63], [2**64 - 1, 0b111]], dtype=np.uint64)
    assert popcount(masks).tolist() == [[0, 1], [64, 3]]


def test_unknown_layout_is_named():
    with pytest.raises(ValueError, match="'mask' must be one of"):
        pixel_masks([(0, 0), (1, 0), (0, 1)], 2, 2, mask="3x3")


# --- exactness ------------------------------------------------------------------------------


@settings(max_examples=2 * EXAMPLES)
@given(polygons(), st.sampled_from(LAYOUTS), st.sampled_from(RULES))
@example(Polygon([(0.5625, 0.0625), (2.5625, 0.0625), (0.5625, 2.0625)]), "8x8", "nonzero")
@example(
    Polygon([(0.125, 0.375), (3.125, 0.375), (3.125, 1.875), (0.125, 1.875)]), "4x4", "evenodd"
)
@example(
    Polygon([[(0, 0), (4, 0), (4, 4), (0, 4)], [(1, 1), (3, 3), (1, 3), (3, 1)]]), "8x4", "evenodd"
)
def test_masks_equal_exact_winding_of_every_subsample(polygon, layout, rule):
    # vertices on sub-sample points; edges along sub-sample rows and columns; bow-tie hole
    expected = oracle_masks(polygon, 4, 4, layout, rule, 8)
    assert as_dict(pixel_masks(polygon, 4, 4, mask=layout, rule=rule)) == expected


@settings(max_examples=EXAMPLES // 2)
@given(
    polygons(st.floats(-0.7, 4.7, allow_nan=False)),
    st.sampled_from(LAYOUTS),
    st.sampled_from(RULES),
    st.sampled_from([None, 0, 2, 8]),
)
def test_masks_snap_as_the_scan_converter_does(polygon, layout, rule, bits):
    expected = oracle_masks(polygon, 4, 4, layout, rule, bits)
    result = pixel_masks(polygon, 4, 4, mask=layout, rule=rule, subpixel_bits=bits)
    assert as_dict(result) == expected


# --- invariants -----------------------------------------------------------------------------


@st.composite
def triangles_sharing_an_edge(draw):
    """(p, q, r) and (q, p, s) with r left of p->q and s right of it: both counter-clockwise."""
    point = st.tuples(sixteenths, sixteenths)
    p, q, r, s = (draw(point) for _ in range(4))

    def side(a):
        return (q[0] - p[0]) * (a[1] - p[1]) - (q[1] - p[1]) * (a[0] - p[0])

    if side(r) <= 0 or side(s) >= 0:
        p, q, r, s = (0.5, 0.5), (3.5, 2.75), (0.5, 3.0), (3.25, 0.0625)
    return [p, q, r], [q, p, s], [q, r, p, s]


@settings(max_examples=EXAMPLES)
@given(triangles_sharing_an_edge(), st.sampled_from(LAYOUTS), st.sampled_from(RULES))
def test_shared_edge_splits_subsamples_exactly(shapes, layout, rule):
    first, second, quad = (
        as_dict(pixel_masks(shape, 4, 4, mask=layout, rule=rule)) for shape in shapes
    )
    for pixel in first.keys() & second.keys():
        assert first[pixel] & second[pixel] == 0, pixel
    union = dict(first)
    for pixel, mask in second.items():
        union[pixel] = union.get(pixel, 0) | mask
    assert union == quad


@pytest.mark.parametrize("layout", LAYOUTS)
@pytest.mark.parametrize(
    "outline", [[(0, 0), (5, 0), (5, 3), (0, 3)], [(-1, -2), (12, -1), (0, 9)]]
)
def test_polygon_covering_the_raster_gives_full_masks(layout, outline):
    result = pixel_masks(outline, 5, 3, mask=layout)
    assert result.ys.tolist() == np.repeat(np.arange(3), 5).tolist()
    assert result.xs.tolist() == np.tile(np.arange(5), 3).tolist()
    assert (result.masks == full_mask(layout)).all()


def test_sub_pixel_triangle_gives_a_partial_mask_in_one_pixel():
    result = pixel_masks([(2.1, 1.1), (2.9, 1.1), (2.1, 1.9)], 4, 3, mask="4x4")
    assert (result.xs.tolist(), result.ys.tolist()) == ([2], [1])
    assert mask_to_grid(result.masks[0], "4x4")[::-1].astype(int).tolist() == [
        [0, 0, 0, 0],
        [1, 0, 0, 0],
        [1, 1, 0, 0],
        [1, 1, 1, 0],
    ]


@pytest.mark.parametrize("layout", LAYOUTS)
@pytest.mark.parametrize("thickness", [0.05, 1e-3, 1e-5])
def test_slivers_give_few_or_no_bits_and_never_raise(layout, thickness):
    sliver = [(0.3, 1.5), (3.7, 1.5 + thickness), (3.7, 1.5 + 2 * thickness)]
    result = pixel_masks(sliver, 4, 3, mask=layout)
    for mask in result.masks:  # thinner than a sub-row: at most one bit per sub-sample column
        assert mask_to_grid(mask, layout).sum(axis=0).max() <= 1
    assert as_dict(result) == oracle_masks(Polygon(sliver), 4, 3, layout, "nonzero", 8)
    traced = mask_buffer_rows(sliver, 4, 3, mask=layout)
    assert as_dict(traced) == as_dict(result)


def test_coverage_approaches_exact_area_as_layouts_get_finer():
    angles = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    disk = np.column_stack([5 + 3.3 * np.cos(angles), 4 + 3.3 * np.sin(angles)])
    snapped = np.rint(disk * 256) / 256
    x, y = snapped.T
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    perimeter = np.hypot(*(np.roll(snapped, -1, axis=0) - snapped).T).sum()
    errors = {}
    for layout in LAYOUTS:
        cols, rows = MASK_LAYOUTS[layout]
        covered = popcount(pixel_masks(disk, 10, 8, mask=layout).masks).sum() / (cols * rows)
        errors[layout] = abs(covered - area)
        assert errors[layout] <= perimeter * (1 / cols + 1 / rows) / 2
    assert errors["8x8"] < errors["4x4"]


def test_empty_raster_and_off_screen_polygon_give_no_pixels():
    for polygon, width, height in [
        ([(0, 0), (3, 0), (0, 3)], 0, 5),
        ([(9, 9), (12, 9), (9, 12)], 4, 4),
    ]:
        result = pixel_masks(polygon, width, height)
        assert len(result.ys) == len(result.xs) == len(result.masks) == 0


# --- the traced mask buffer -----------------------------------------------------------------


@settings(max_examples=EXAMPLES)
@given(polygons(), st.sampled_from(LAYOUTS), st.sampled_from(RULES))
def test_mask_buffer_equals_pixel_masks(polygon, layout, rule):
    fast = pixel_masks(polygon, 4, 4, mask=layout, rule=rule)
    traced = mask_buffer_rows(polygon, 4, 4, mask=layout, rule=rule)
    assert as_dict(traced) == as_dict(fast)
    rows = traced.trace.of_kind("mask_buffer_row")
    shown = {}
    for row in rows:  # the events alone rebuild the masks
        shown.update({(row.y, p.x): p.mask for p in row.pixels if p.mask})
        shown.update(
            {(row.y, x): run.mask for run in row.runs for x in range(run.x_start, run.x_end)}
        )
    assert shown == as_dict(fast)


def test_pixel_masks_with_a_tracer_runs_the_mask_buffer():
    triangle = [(0.5, 0.25), (3.5, 1.0), (1.0, 2.75)]
    traced = pixel_masks(triangle, 4, 3, trace=True)
    assert as_dict(traced) == as_dict(pixel_masks(triangle, 4, 3))
    assert {e.kind for e in traced.trace} == {"mask_buffer_row", "edge_mask"}
    assert pixel_masks(triangle, 4, 3).trace is None


def test_corner_inside_a_pixel_is_the_and_of_its_edge_masks():
    # Fig. 6.10: edges a and b meet at (0.75, 0.5) inside pixel (0, 0), the left edge c at x = 0.
    trace = mask_buffer_rows([(0, 0), (0.75, 0.5), (0, 1)], 1, 1, mask="4x4").trace
    (row,) = trace.of_kind("mask_buffer_row")
    (pixel,) = row.pixels
    assert pixel.carry == (0, 0, 0, 0)
    assert [(e.edge, e.winding) for e in pixel.edges] == [(0, -1), (1, -1), (2, 1)]
    a, b, c = (mask_to_grid(e.mask, "4x4") for e in pixel.edges)
    assert c.all()  # every sub-sample is right of the left edge
    assert (mask_to_grid(pixel.mask, "4x4") == (c & ~a & ~b)).all()  # inside = and of the sides
    (edge_a,) = [e for e in trace.of_kind("edge_mask") if e.edge == 0]
    assert edge_a.crossings == (Fraction(3, 16), Fraction(9, 16), None, None)


def test_pixels_under_a_horizontal_edge_get_partial_masks_from_the_carry():
    result = mask_buffer_rows([(0, 0), (4, 0), (4, 0.5), (0, 0.5)], 4, 1, mask="4x4")
    (row,) = result.trace.of_kind("mask_buffer_row")
    assert [p.x for p in row.pixels] == [0]  # only the left edge crosses a pixel
    assert [(r.x_start, r.x_end, r.mask) for r in row.runs] == [(1, 4, 0xFF)]
    assert result.masks.tolist() == [0xFF] * 4


def test_mask_buffer_trace_round_trips_through_json_and_filters():
    polygon = [[(0.2, 0.1), (3.8, 0.6), (2.0, 2.9)], [(1.5, 1.0), (2.5, 1.0), (2.0, 1.6)]]
    trace = mask_buffer_rows(polygon, 4, 3, rule="evenodd").trace
    assert len(trace.of_kind("mask_buffer_row")) == 3
    assert Trace.from_json(trace.to_json()) == trace
    only_row_1 = mask_buffer_rows(polygon, 4, 3, trace=Recorder(rows=(1, 2))).trace
    assert {e.y for e in only_row_1} == {1}
    region = Filter("edge_mask", region=(2, 0, 3, 3))
    assert all(e.x == 2 for e in trace if region.keeps(e))

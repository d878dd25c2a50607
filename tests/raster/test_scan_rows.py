"""One ET/AET walk: `scan_rows` drives scan conversion, the traced z-buffer, the mask buffer
and scanline visibility.

Regression for issue 24: the traced z-buffer, the mask buffer and scanline
visibility walked their own AETs, so a replaced ``aet_update`` or ``span_rule``
was silently not used there. Now a replaced step shows in the z-buffer's spans
and depth tests, the mask buffer's masks and scanline visibility's ids, as it
does in `scan_convert`'s.
"""

import dataclasses

import numpy as np
import pytest

from scanviz import Polygon, scan_convert, steps
from scanviz.abuffer.masks import mask_buffer_rows, pixel_masks
from scanviz.raster.fixed import snap
from scanviz.raster.interpolate import interpolate_rows, polygon_plane
from scanviz.raster.scanline import (
    aet_update,
    bucketed_edge_table,
    scan_reference,
    scan_rows,
    span_rule,
)
from scanviz.visibility import ScreenPolygons, solve, zbuffer

# The UMBC z-buffer slide: a triangle at depth 5, a square behind it at 9, a sloped triangle.
SLIDE = ScreenPolygons.from_polygons(
    [
        [(1, 1, 5), (7, 7, 5), (1, 7, 5)],
        [(3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)],
        [(2, 6, 3), (2, 3, 8), (7, 3, 3)],
    ],
    values=[[(0.0,)] * 3, [(1.0,)] * 4, [(2.0,)] * 3],
)
WIDTH, HEIGHT = 10, 9


def _traced(**replaced):
    with steps.using(**replaced):
        return zbuffer(SLIDE, WIDTH, HEIGHT, trace=True)


def _spans(trace):
    return [(e.polygon, e.y, e.x_start, e.x_end) for e in trace.of_kind("span")]


def _tested(trace):
    return sorted((e.polygon, e.y, e.x) for e in trace.of_kind("depth_test"))


def drop_last_pixel(crossings, rule):
    """A wrong span rule: every span one pixel short on the right."""
    return [(start, end - 1, winding) for start, end, winding in span_rule(crossings, rule)]


def test_the_walk_yields_the_rows_scan_reference_counts():
    snapped = snap(Polygon([(1, 1), (7, 7), (1, 7)]))
    rows = list(scan_rows(snapped, bucketed_edge_table(snapped, HEIGHT), WIDTH, HEIGHT))
    spans, stats = scan_reference(snapped, WIDTH, HEIGHT)
    assert [[r.y, s, e] for r in rows for s, e, _ in r.spans] == spans.tolist()
    assert len(rows) == stats.rows_scanned and sum(r.swaps for r in rows) == stats.swaps
    assert all([i.x for i in r.aet] == sorted(i.x for i in r.aet) for r in rows)


def test_a_replaced_span_rule_shortens_the_zbuffers_spans_and_depth_tests():
    default, short = _traced(), _traced(span_rule=drop_last_pixel)
    expected = [(p, y, s, e - 1) for p, y, s, e in _spans(default.trace) if e - 1 > s]
    assert _spans(short.trace) == expected
    assert _tested(short.trace) == sorted((p, y, x) for p, y, s, e in expected for x in range(s, e))
    values = [(e.polygon, e.y, e.x_start, e.x_end) for e in short.trace.of_kind("span_values")]
    assert values == expected
    assert short.stats.fragments < default.stats.fragments


def test_a_shortened_span_is_interpolated_between_the_same_two_edges():
    def values(trace):
        return {
            (e.polygon, e.y, e.x_start): (e.x_left, e.x_right, e.z, e.dzdx, e.values, e.dvdx)
            for e in trace.of_kind("span_values")
        }

    default, short = values(_traced().trace), values(_traced(span_rule=drop_last_pixel).trace)
    assert short and all(short[key] == default[key] for key in short)


def test_a_replaced_aet_update_is_called_by_the_zbuffer_once_per_row():
    calls = []

    def recording(active, y, entering):
        calls.append(y)
        return aet_update(active, y, entering)

    default, recorded = _traced(), _traced(aet_update=recording)
    assert len(calls) == default.stats.rows_scanned > 0
    assert recorded.trace == default.trace
    for name in ("depth", "polygon", "values"):
        assert np.array_equal(getattr(recorded, name), getattr(default, name)), name


def test_a_replaced_aet_updates_x_moves_the_zbuffers_spans_and_depth_tests():
    def shifted(active, y, entering):  # every edge enters one pixel right, and stays so
        return aet_update(active, y, [dataclasses.replace(e, x=e.x + 1) for e in entering])

    default, moved = _traced(), _traced(aet_update=shifted)
    clipped = [(p, y, s + 1, min(e + 1, WIDTH)) for p, y, s, e in _spans(default.trace)]
    expected = [(p, y, s, e) for p, y, s, e in clipped if s < e]
    assert _spans(moved.trace) == expected
    assert _tested(moved.trace) == sorted((p, y, x) for p, y, s, e in expected for x in range(s, e))


def test_a_span_no_two_crossings_bound_is_a_clear_error():
    square = snap(Polygon([(0, 0), (4, 0), (4, 4), (0, 4)]))
    plane = polygon_plane(square, [0.0, 0.0, 0.0, 0.0])
    channels = np.zeros((4, 1))

    def too_long(crossings, rule):
        return [(0, 6, 1)] if crossings else []

    with steps.using(span_rule=too_long), pytest.raises(ValueError, match="span_rule.*row 0"):
        list(interpolate_rows(square, plane, channels, 8, 8))


def test_scan_convert_and_the_zbuffer_see_the_same_replaced_span_rule():
    triangle = [(1, 1), (7, 7), (1, 7)]
    with steps.using(span_rule=drop_last_pixel):
        scanned = scan_convert(triangle, WIDTH, HEIGHT, trace=True).trace
    zbuffered = _traced(span_rule=drop_last_pixel).trace
    assert [(e.y, e.x_start, e.x_end) for e in scanned.of_kind("span")] == [
        (y, s, e) for p, y, s, e in _spans(zbuffered) if p == 0
    ]


def test_a_replaced_aet_update_moves_the_mask_buffers_edges():
    def shifted(active, y, entering):  # every edge enters one sub-sample column right
        return aet_update(active, y, [dataclasses.replace(e, x=e.x + 1) for e in entering])

    triangle = [(0.5, 0.5), (3.25, 1.0), (1.0, 2.75)]
    with steps.using(aet_update=shifted):
        moved = mask_buffer_rows(triangle, 5, 4, mask="4x4")
    expected = pixel_masks([(x + 0.25, y) for x, y in triangle], 5, 4, mask="4x4")
    assert (moved.ys.tolist(), moved.xs.tolist()) == (expected.ys.tolist(), expected.xs.tolist())
    assert moved.masks.tolist() == expected.masks.tolist()
    assert moved.masks.tolist() != mask_buffer_rows(triangle, 5, 4, mask="4x4").masks.tolist()


def test_the_mask_buffers_active_edges_cover_a_sub_row_of_their_row():
    # Edge 0, (-1, -2)-(3, -1), lies wholly below the raster: it is active on no row.
    trace = mask_buffer_rows([(-1, -2), (3, -1), (2, 2.5)], 4, 3, mask="4x4").trace
    first = trace.of_kind("mask_buffer_row")[0]
    assert (first.y, first.active) == (0, (1, 2))


def test_a_replaced_aet_update_moves_scanline_visibility_as_it_moves_the_zbuffer():
    def shifted(active, y, entering):  # every edge enters one pixel right, and stays so
        return aet_update(active, y, [dataclasses.replace(e, x=e.x + 1) for e in entering])

    def ids(name, **replaced):
        with steps.using(**replaced):
            return solve(name, SLIDE, WIDTH, HEIGHT, trace=True).polygon

    default, moved = ids("scanline"), ids("scanline", aet_update=shifted)
    assert np.array_equal(moved, ids("zbuffer", aet_update=shifted))
    assert np.array_equal(moved != -1, np.pad(default != -1, ((0, 0), (1, 0)))[:, :WIDTH])

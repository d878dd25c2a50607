"""The visibility, grid-surface, fast Phong and DISLOP steppers narrate each step, and fit.

Each narration is checked against a trace recorded here, independently of
the widget: the polygon, pixel, row or column of the event and the values
that matter must be in the sentence.
"""

import matplotlib
import numpy as np
import pytest
from matplotlib.text import Text

from scanviz.antialias import dislop_line
from scanviz.shading import ReflectionModel
from scanviz.surfaces import View, floating_horizon, floating_perimeter, gaussian
from scanviz.trace import Recorder
from scanviz.visibility import examples, solve
from scanviz.visibility.bsp import BSP
from scanviz.widgets._common import WIDEST
from scanviz.widgets.antialias import (
    dislop_stepper,
    plot_coverage_comparison,
    plot_period_table,
    plot_post_antialias,
    plot_ropiness,
)
from scanviz.widgets.bsp import bsp_stepper
from scanviz.widgets.depth_sort import depth_sort_stepper, painter_stepper
from scanviz.widgets.fast_phong import fast_phong_stepper
from scanviz.widgets.scanline_visibility import scanline_visibility_stepper
from scanviz.widgets.surfaces import (
    horizon_stepper,
    perimeter_stepper,
    plot_grid,
    plot_mismatch,
    plot_results,
)
from scanviz.widgets.visibility import compare_visibility
from scanviz.widgets.warnock import warnock_stepper

matplotlib.use("Agg")

CORNER = View((3, 4, 3), (-3, -4, -3))
SLIDES_NUMBERS = {  # the ambiguity tests as the slides number them
    "x_extent": "1",
    "y_extent": "2",
    "s_behind_plane": "3",
    "other_in_front": "4",
    "no_overlap": "5",
    "other_behind_plane": "3'",
    "s_in_front": "4'",
}
MODEL = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.75, 0.55, 0.3), ks=0.7, n=32, r_plus_r0=1.5)
TRIANGLE = ([(3.3, 3.2), (12.7, 5.1), (6.6, 12.4)], [(0, 0, 1), (0.3, 0, 1), (0, 0.3, 1)])


def sentences(stepper) -> list[str]:
    view = stepper.views[0]
    return [view.narrate(step) for step in range(len(stepper.model) + 1)]


def test_every_step_of_every_stepper_is_one_plain_sentence():
    steppers = [
        painter_stepper(examples.slides_painter(), 16, 12),
        depth_sort_stepper(examples.cyclic_overlap(), 24, 24),
        bsp_stepper(examples.slides_bsp(), 32, 24, sequence=examples.BSP_SEQUENCE),
        warnock_stepper(examples.slides_painter(), 16, 12),
        scanline_visibility_stepper(examples.interpenetrating(), 16, 12),
        perimeter_stepper(gaussian(4), CORNER, 32, 32),
        horizon_stepper(gaussian(4), CORNER, 32, 32),
        fast_phong_stepper(*TRIANGLE, (0.2, 0.2, 1), (0, 0, 1), MODEL, width=16, height=16),
        dislop_stepper((1.3, 1.6), (13.7, 12.1), 16, 14),
    ]
    for stepper in steppers:
        said = sentences(stepper)
        assert said[0].startswith("The start"), said[0]
        for step, sentence in enumerate(said):
            assert sentence and sentence[0].isupper() and sentence.endswith("."), (step, sentence)
            assert "(" not in sentence.split(" ")[0] and "Event" not in sentence  # no repr
            assert "\n" not in sentence
        stepper.slider.value = len(said) - 1
        assert said[-1] in stepper.narration.value.replace("&#x27;", "'").replace("&gt;", ">")


def test_the_painter_steps_one_polygon_painted_per_step_and_says_how_many_samples():
    polygons = examples.slides_painter()
    trace = solve("painter", polygons, 16, 12, trace=True).trace
    painted = [e for e in trace if e.kind == "pixel_painted"]
    pieces = list(dict.fromkeys(e.piece for e in painted))
    stepper = painter_stepper(polygons, 16, 12)
    assert stepper.slider.max == 1 + len(pieces)  # the sort, then one step per polygon
    said = sentences(stepper)
    order = [p.label for p in trace.of_kind("polygons_sorted")[0].pieces]
    assert said[1].index(f" {order[0]} (") < said[1].index(f" {order[-1]} (")  # farthest first
    for k, piece in enumerate(pieces, 2):
        mine = [e for e in painted if e.piece == piece]
        assert f"Polygon {mine[0].polygon}," in said[k]
        assert f"{sum(e.painted for e in mine)} samples" in said[k]
        assert f"number {k - 1} of {len(pieces)}" in said[k]


def test_painter_pixel_steps_name_the_sample_and_what_it_covers():
    polygons = examples.long_behind_short()
    trace = solve("painter", polygons, 16, 12, trace=True).trace
    painted = [e for e in trace if e.kind == "pixel_painted"]
    stepper = painter_stepper(polygons, 16, 12, steps="pixel")
    said = sentences(stepper)
    assert len(said) == 2 + len(painted)
    for event, sentence in zip(painted, said[2:], strict=True):
        assert f"sample ({event.x}, {event.y})" in sentence
        assert f"Polygon {event.polygon} " in sentence
        under = f"over polygon {event.previous}" if event.previous >= 0 else "background"
        assert under in sentence


def test_depth_sort_narrates_the_test_that_settled_each_pair_and_paints_piece_by_piece():
    polygons = examples.cyclic_overlap()
    trace = solve("depth_sort", polygons, 24, 24, trace=True).trace
    pairs = [e for e in trace if e.kind == "pair_tested"]
    order = trace.of_kind("paint_order")[0].pieces
    stepper = depth_sort_stepper(polygons, 24, 24)
    view, said = stepper.views[0], sentences(stepper)
    told = [s for e, s in zip(view.steps, said[1:], strict=True) if e.kind == "pair_tested"]
    assert len(told) == len(pairs)
    for pair, sentence in zip(pairs, told, strict=True):
        assert f"S = {pair.piece} (z " in sentence and f"S' = {pair.other} (z " in sentence
        if pair.settled_by in SLIDES_NUMBERS:
            assert f"test {SLIDES_NUMBERS[pair.settled_by]} (" in sentence
            assert "passes" in sentence
        if pair.outcome == "split":
            assert "split" in sentence
    painting = [s for s in said if " so it is painted: " in s]
    assert len(painting) == len(order)  # one step per piece painted
    for piece, sentence in zip(order, painting, strict=True):
        samples = [e for e in trace if e.kind == "pixel_painted" and e.piece == piece.label]
        assert sentence.startswith(f"Piece {piece.label} (polygon {piece.polygon})")
        assert f"{sum(e.painted for e in samples)} samples" in sentence
    splits = [e for e in trace if e.kind == "polygon_split"]
    told = [s for e, s in zip(view.steps, said[1:], strict=True) if e.kind == "polygon_split"]
    for split, sentence in zip(splits, told, strict=True):
        assert f"Piece {split.piece} is cut by the plane of polygon {split.by}" in sentence
        assert f"{split.front.label} lies in front" in sentence
        assert f"{split.behind.label} behind" in sentence


def test_depth_sort_pixel_steps_paint_one_sample_each():
    polygons = examples.interpenetrating()
    trace = solve("depth_sort", polygons, 16, 12, trace=True).trace
    samples = [e for e in trace if e.kind == "pixel_painted"]
    decisions = [e for e in trace if e.kind != "pixel_painted"]
    stepper = depth_sort_stepper(polygons, 16, 12, steps="pixel")
    assert stepper.slider.max == len(decisions) + len(samples)
    said = [s for s in sentences(stepper) if " sample (" in s]
    assert len(said) == len(samples)
    for event, sentence in zip(samples, said, strict=True):
        assert sentence.startswith(f"Piece {event.piece} ")
        assert f"sample ({event.x}, {event.y})" in sentence
    with pytest.raises(ValueError, match="'steps' must be one of"):
        depth_sort_stepper(polygons, 16, 12, steps="row")


def test_bsp_narrates_nodes_splits_and_visits():
    polygons, sequence = examples.slides_bsp(), examples.BSP_SEQUENCE
    kinds = ["bsp_node", "polygon_split", "bsp_visited"]
    trace = solve(BSP(sequence=sequence), polygons, 32, 24, trace=Recorder(kinds)).trace
    said = sentences(bsp_stepper(polygons, 32, 24, sequence=sequence))
    assert len(said) == 1 + len(trace)
    for event, sentence in zip(trace, said[1:], strict=True):
        if event.kind == "bsp_node":
            assert sentence.startswith(f"Node {event.node}, ")
            assert f"takes piece {event.piece}" in sentence
            for label in (*event.front, *event.back):
                assert label in sentence
        elif event.kind == "polygon_split":
            assert f"Piece {event.piece} straddles the plane of polygon {event.by}" in sentence
        else:
            assert f"ode {event.node}" in sentence and f"piece {event.piece}" in sentence
            if "leaf" not in sentence:
                side = "in front of" if event.viewer_in_front else "behind"
                assert f"the viewpoint is {side} its plane" in sentence
                assert f"the {event.first} subtree is displayed first" in sentence


def test_warnock_narrates_each_area_and_its_case():
    polygons = examples.slides_painter()
    trace = solve("warnock", polygons, 16, 12, trace=Recorder(kinds=["area_classified"])).trace
    said = sentences(warnock_stepper(polygons, 16, 12))
    for area, sentence in zip(trace, said[1:], strict=True):
        if area.case == "pixel":
            assert sentence.startswith(f"Pixel ({area.x_start}, {area.y_start}) ")
        else:
            last = area.x_end - 1
            xs = f"x {area.x_start}" + (f"..{last}" if last > area.x_start else "")
            assert sentence.startswith(f"Area {xs}, y {area.y_start}")
        assert f"(level {area.level})" in sentence
        expected = {
            "empty": "meets no polygon",
            "single": f"meets only polygon {area.visible}",
            "surrounding": f"polygon {area.visible} covers it all",
            "subdivide": "four quadrants",
            "pixel": f"polygon {area.visible} is nearest" if area.visible >= 0 else "background",
        }[area.case]
        assert expected in sentence


def test_scanline_narrates_rows_and_spans_with_their_depths():
    polygons = examples.interpenetrating()
    kinds = ["surface_table_built", "active_surfaces", "visible_span"]
    trace = solve("scanline", polygons, 16, 12, trace=Recorder(kinds=kinds)).trace
    said = sentences(scanline_visibility_stepper(polygons, 16, 12))
    for event, sentence in zip(trace, said[1:], strict=True):
        if event.kind == "active_surfaces":
            assert sentence.startswith(f"Row y = {event.y}: ")
        elif event.kind == "visible_span":
            assert sentence.startswith(f"Row {event.y}, x {event.x_start}")
            for depth in event.depths:
                assert f"z {float(f'{depth:.3g}'):g}" in sentence
            if event.visible < 0:
                assert "background" in sentence
            else:
                only = f"only surface {event.visible} "
                assert f"{event.visible} is the nearest" in sentence or only in sentence
            if event.split_at is not None:
                assert f"cross at x = {float(f'{event.split_at:.4g}'):g}" in sentence


def test_perimeter_narrates_facets_edges_and_the_numbers_that_hide_a_point():
    trace = floating_perimeter(gaussian(4), CORNER, 32, 32, trace=True).trace
    said = sentences(perimeter_stepper(gaussian(4), CORNER, 32, 32))
    top, bottom = np.zeros(32, int), np.full(32, 32)
    right, left = np.zeros(32, int), np.full(32, 32)
    hidden_told = 0
    for event, sentence in zip(trace, said[1:], strict=True):
        if event.kind == "perimeter_facet":
            assert sentence.startswith(f"Facet {event.number} (row {event.row}, column ")
        elif event.kind == "perimeter_update":
            for x, t, b in event.columns:
                top[x], bottom[x] = t, b
            for y, r, lf in event.rows:
                right[y], left[y] = r, lf
            assert f"{event.points} visible points" in sentence
        elif event.kind == "perimeter_edge":
            assert f"of facet {event.facet}: " in sentence
            if all(event.visible):
                assert f"all {len(event.points)} points" in sentence
                continue
            x, y = event.points[event.visible.index(False)]
            assert f"({x}, {y})" in sentence
            assert f"bottom[{x}] = {bottom[x]} < {y} < top[{x}] = {top[x]}" in sentence
            assert f"left[{y}] = {left[y]} < {x} < right[{y}] = {right[y]}" in sentence
            hidden_told += 1
    assert hidden_told > 0


def test_horizon_narrates_each_curve_and_its_flags():
    recorder = Recorder(kinds=["horizon_curve", "horizon_column"])
    floating_horizon(gaussian(4), CORNER, 32, 32, trace=recorder)
    events = list(recorder.trace())
    said = sentences(horizon_stepper(gaussian(4), CORNER, 32, 32))
    curves = [e for e in events if e.kind == "horizon_curve"]
    assert len(said) == 1 + len(curves)
    for curve, sentence in zip(curves, said[1:], strict=True):
        columns = [e for e in events if e.kind == "horizon_column" and e.curve == curve.curve]
        flags = [e.flag for e in columns]
        assert sentence.startswith(f"Curve {curve.curve} ")
        assert f"crosses {len(columns)} columns: {flags.count(1)} at or above" in sentence
        assert f"{flags.count(0)} hidden" in sentence


def test_fast_phong_narrates_each_sample_and_its_table_level():
    from scanviz.shading.fast_phong import fast_phong_triangle

    args = (*TRIANGLE, (0.2, 0.2, 1), (0, 0, 1), MODEL)
    shaded = fast_phong_triangle(*args, width=16, height=16, trace=True)
    pixels = [e for e in shaded.trace if e.kind == "fast_phong_pixel"]
    said = sentences(fast_phong_stepper(*args, width=16, height=16))
    for pixel, sentence in zip(pixels, said[1:], strict=True):
        assert sentence.startswith(f"Pixel ({pixel.x}, {pixel.y}): ")
        assert ("directly" in sentence) == pixel.direct
        if pixel.lit:
            assert f"table level {pixel.level} of" in sentence
        else:
            assert "unlit" in sentence


def test_dislop_narrates_each_column_its_branch_and_areas():
    p0, p1 = (1.3, 1.6), (13.7, 12.1)
    _, trace = dislop_line(p0, p1, 16, 14, trace=True)
    said = sentences(dislop_stepper(p0, p1, 16, 14))
    words = {"two": "two pixels", "three": "three pixels", "three_triangle": "a triangle"}
    for column, sentence in zip(trace, said[1:], strict=True):
        assert sentence.startswith(f"Column x = {column.x}: slope m = ")
        assert f"upper {column.up:.3f}, middle {column.mid:.3f}, lower {column.low:.3f}" in sentence
        assert words.get(column.branch, column.branch.replace("cap", "end column")) in sentence


def figures():
    """Every figure these widgets make, steppers stepped to the middle."""
    steppers = [
        painter_stepper(examples.slides_painter(), 16, 12),
        depth_sort_stepper(examples.cyclic_overlap(), 24, 24),
        bsp_stepper(examples.slides_bsp(), 32, 24, sequence=examples.BSP_SEQUENCE),
        warnock_stepper(examples.cyclic_overlap(), 24, 24),
        scanline_visibility_stepper(examples.interpenetrating(), 16, 12),
        perimeter_stepper(gaussian(6), CORNER, 64, 64),
        horizon_stepper(gaussian(6), CORNER, 64, 64),
        fast_phong_stepper(*TRIANGLE, (0.2, 0.2, 1), (0, 0, 1), MODEL, width=16, height=16),
        dislop_stepper((1.3, 1.6), (13.7, 12.1), 16, 14),
    ]
    made = {}
    for stepper in steppers:
        stepper.slider.value = stepper.slider.max // 2
        made[stepper.widget.children[0].value] = stepper.views[0].figure
    views = [
        View((0.3, -0.2, 4.0), (0.0, 0.05, -1.0)),
        View((0.2, -4.0, 2.0), (0, 1, -0.5)),
        CORNER,
    ]
    from scanviz.surfaces import compare_with_zbuffer, polynomial

    made["compare_visibility"] = compare_visibility(examples.cyclic_overlap(), 24, 24)
    made["plot_grid"] = plot_grid(gaussian(6), views)
    made["plot_results"] = plot_results(polynomial(9), CORNER, 48, 48)
    comparison = compare_with_zbuffer(gaussian(5), CORNER, 24, 24)
    made["plot_mismatch"] = plot_mismatch(comparison, region=(4, 4, 14, 14))
    made["plot_coverage_comparison"] = plot_coverage_comparison((1.4, 2.2), (22.6, 13.9), 24, 16)
    made["plot_ropiness"] = plot_ropiness(range(0, 91, 15), 20, 32, 32)
    made["plot_period_table"] = plot_period_table(0.0875, levels=64)
    before = np.eye(32)
    made["plot_post_antialias"] = plot_post_antialias(before, np.clip(before + 0.3, 0, 1))
    return made


def test_every_figure_fits_the_notebook_and_no_text_is_under_9_points():
    for name, figure in figures().items():
        assert figure.get_size_inches()[0] <= WIDEST + 1e-9, name
        figure.canvas.draw()  # lay out, so every text is final
        small = [
            (t.get_text(), t.get_fontsize())
            for t in figure.findobj(Text)
            if t.get_visible() and t.get_text().strip() and t.get_fontsize() < 9
        ]
        assert small == [], name


def test_fast_phong_coefficients_scroll_when_wide():
    stepper = fast_phong_stepper(*TRIANGLE, (0.2, 0.2, 1), (0, 0, 1), MODEL, width=16, height=16)
    table = stepper.views[0].coefficients.value
    assert "overflow-x:auto" in table and "scroll →" in table


def test_a_painting_step_is_labelled_by_what_it_paints():
    from scanviz.visibility import examples
    from scanviz.widgets import painter_stepper

    stepper = painter_stepper(examples.slides_painter(), 24, 24)
    stepper.slider.value = 1
    assert stepper.label.value.endswith(": polygons_sorted")
    stepper.slider.value = 2
    assert stepper.label.value.endswith(": polygon_painted")
    pixels = painter_stepper(examples.slides_painter(), 24, 24, steps="pixel")
    pixels.slider.value = 2
    assert pixels.label.value.endswith(": pixel_painted")

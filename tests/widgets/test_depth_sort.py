"""The depth sort and painter's views, headless: step, then check what the view shows."""

import re

import matplotlib
import numpy as np

from scanviz.visibility import examples, solve, zbuffer
from scanviz.widgets.depth_sort import (
    depth_sort_stepper,
    list_states,
    painter_stepper,
)
from scanviz.widgets.visibility import polygon_colors

matplotlib.use("Agg")


def text(html_value: str) -> str:
    return " ".join(re.sub("<[^>]+>", " ", html_value).split())


def test_depth_sort_stepper_shows_each_pair_and_what_settled_it():
    stepper = depth_sort_stepper(examples.interpenetrating(), 16, 12)
    view = stepper.views[0]
    kinds = [e.kind for e in view.steps]
    assert kinds[0] == "polygons_sorted" and "paint_order" in kinds
    assert kinds[-1] == "pixel_painted"  # the last piece painted, after the order is settled
    first_pair = kinds.index("pair_tested") + 1
    stepper.slider.value = first_pair
    pair = view.steps[first_pair - 1]
    assert text(view.settled.value) == (
        f"S = {pair.piece}, S' = {pair.other}: no test settles it &rarr; "
        "no order works: a piece is split"  # the two rectangles cross
    )
    assert text(view.tests_table.value).split()[2:] == [
        "0.", "minimax", "fail", "1.", "x_extent", "fail", "2.", "y_extent", "fail",
        "3.", "s_behind_plane", "fail", "4.", "other_in_front", "fail", "5.", "no_overlap", "fail",
        "3'.", "other_behind_plane", "fail", "4'.", "s_in_front", "fail",
    ]  # fmt: skip
    rows = text(view.list_table.value)
    assert "1 0 0 0.2 0.8 S" in rows and "2 1 1 0.3 0.7 S'" in rows
    assert view.s_outline.get_visible() and view.other_outline.get_visible()


def test_depth_sort_stepper_logs_splits_and_ends_with_the_final_image():
    stepper = depth_sort_stepper(examples.cyclic_overlap(), 24, 24)
    view = stepper.views[0]
    splits = sum(e.kind == "polygon_split" for e in view.steps)
    assert splits == view.result.algorithm.splits > 0
    stepper.slider.value = len(view.steps)
    assert text(view.log.value).startswith(f"swaps and splits ({splits + view.result.algorithm.swaps})")  # fmt: skip
    assert "cut by the plane of polygon" in text(view.log.value)
    last = view.result.order[-1].label  # the last step paints the last piece
    assert text(view.settled.value) == f"no pair under test: piece {last} is painted"
    # At the end everything is painted: the image is the result's, which is the z-buffer's.
    final = polygon_colors(zbuffer(examples.cyclic_overlap(), 24, 24).polygon)
    assert np.array_equal(view.painted_image.get_array(), final)
    assert "0 to paint" in text(view.list_table.value)


def test_the_list_loses_its_far_end_as_pieces_are_painted():
    result = solve("depth_sort", examples.cyclic_overlap(), 24, 24, trace=True)
    steps = [e for e in result.trace if e.kind != "pixel_painted"]
    states = list_states(steps)
    painted_orders = [painted for _, painted, _ in states]
    assert painted_orders[-1] == [p.label for p in result.order]
    for earlier, later in zip(painted_orders, painted_orders[1:], strict=False):
        assert later[: len(earlier)] == earlier  # painting only ever appends
    for event, (pending, painted, pair) in zip(steps, states[1:], strict=True):
        labels = [r.label for r in pending]
        assert not set(labels) & set(painted)
        if event.kind == "pair_tested":
            assert pair is event and labels[0] == pair.piece  # S is the far end of the list


def test_painter_stepper_paints_polygon_by_polygon_and_outlines_its_errors():
    stepper = painter_stepper(examples.long_behind_short(), 16, 12, key="zmin")
    view = stepper.views[0]
    wrong = (
        solve("painter", examples.long_behind_short(), 16, 12).polygon
        != zbuffer(examples.long_behind_short(), 16, 12).polygon
    )
    assert text(view.summary.value).startswith(f"{int(wrong.sum())} samples differ")
    painted = solve("painter", examples.long_behind_short(), 16, 12, trace=True).trace
    pieces = list(dict.fromkeys(e.piece for e in painted if e.kind == "pixel_painted"))
    assert stepper.slider.max == 1 + len(pieces)  # the sort, then one step per polygon
    stepper.slider.value = 2  # the first polygon (sorted on zmin, farthest first) painted whole
    first = [e for e in painted if e.kind == "pixel_painted" and e.piece == pieces[0]]
    assert f"1 {pieces[0]} {first[0].polygon} 0.5 0.5 0.5" in text(view.list_table.value)
    shown = (view.painted_image.get_array() != 1.0).any(axis=2)
    assert shown.sum() == len({(e.x, e.y) for e in first})
    stepper.slider.value = len(view.steps)
    assert np.array_equal(
        view.painted_image.get_array(),
        polygon_colors(solve("painter", examples.long_behind_short(), 16, 12).polygon),
    )
    zmax = painter_stepper(examples.long_behind_short(), 16, 12, key="zmax").views[0]
    assert text(zmax.summary.value).startswith("0 samples differ")


def test_painter_pixel_steps_paint_one_sample_each():
    stepper = painter_stepper(examples.long_behind_short(), 16, 12, steps="pixel")
    painted = solve("painter", examples.long_behind_short(), 16, 12, trace=True).trace
    samples = [e for e in painted if e.kind == "pixel_painted"]
    assert stepper.slider.max == 1 + len(samples)
    stepper.slider.value = 2
    view = stepper.views[0]
    assert (view.painted_image.get_array() != 1.0).any(axis=2).sum() == 1
    assert view.current_marker.get_xy() == (samples[0].x, samples[0].y)

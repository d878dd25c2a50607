"""The BSP view, headless: step it, check what the tree, the partition and the images show."""

import matplotlib
import numpy as np
import pytest

from scanviz.visibility import examples
from scanviz.widgets.bsp import BUILT, CURRENT, PAINTED, PENDING, bsp_stepper, tree_layout
from scanviz.widgets.visibility import polygon_colors

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def stepper():
    return bsp_stepper(examples.slides_bsp(), 32, 24, sequence=examples.BSP_SEQUENCE)


def box_colors(view):
    name = {n.node: n.pieces[0] for n in view.tree.nodes}
    return {
        name[k]: matplotlib.colors.to_hex(box.get_bbox_patch().get_facecolor())
        for k, box in view.node_boxes.items()
    }


def test_the_steps_are_the_build_then_the_display(stepper):
    # The slides' example: 1 split, 6 nodes, then 6 visits.
    kinds = [e.kind for e in stepper.views[0].steps]
    assert kinds == ["polygon_split"] + ["bsp_node"] * 6 + ["bsp_visited"] * 6
    assert stepper.slider.max == 13


def test_the_tree_is_drawn_front_left_back_right(stepper):
    view = stepper.views[0]
    places = tree_layout(view.tree)
    x = {n.pieces[0]: places[n.node][0] for n in view.tree.nodes}
    assert x["5a"] < x["2"] < x["1"] < x["3"] < x["4"] < x["5b"]
    assert {box.get_text() for box in view.node_boxes.values()} == {"3", "2", "4", "5a", "5b", "1"}


def test_the_build_marks_nodes_and_splits(stepper):
    view = stepper.views[0]
    stepper.slider.value = 0
    assert set(box_colors(view).values()) == {PENDING}
    assert not any(line.get_visible() for line in view.split_lines)
    stepper.slider.value = 1  # 5 split by the plane of 3
    assert view.split_lines[0].get_visible()
    assert "split</b> 5 by the plane of polygon 3" in view.event.value
    stepper.slider.value = 2  # node 0: root 3
    colors = box_colors(view)
    assert colors["3"] == CURRENT and colors["2"] == PENDING
    assert "front: 2, 5a, 1" in view.event.value and "back: 4, 5b" in view.event.value
    stepper.slider.value = 7
    assert box_colors(view)["5b"] == CURRENT
    assert set(box_colors(view).values()) == {BUILT, CURRENT}
    assert (view.so_far.get_array() == 1.0).all()  # nothing painted yet: white


def test_the_display_paints_in_order(stepper):
    view = stepper.views[0]
    # Step 11 reaches pgon 2 ("at 2: viewpoint on back -> display front first"): 4, 5b and 3
    # are painted, 5a, 2 and 1 are not.
    stepper.slider.value = 11
    assert "at 2</b> (node 1): viewpoint on back &rarr; display front first" in view.event.value
    colors = box_colors(view)
    assert colors["2"] == CURRENT
    assert [k for k, c in colors.items() if c == PAINTED] == ["3", "4", "5b"]
    image = view.so_far.get_array()
    for polygon, shown in ((4, True), (3, True), (1, False), (2, False)):
        color = polygon_colors(np.array([[polygon]]))[0, 0]
        assert np.all(image == color, axis=-1).any() == shown, polygon
    assert view.order.value.count("background:#ffe9a8") == 1  # the current node's piece
    stepper.slider.value = 13
    np.testing.assert_array_equal(view.so_far.get_array(), polygon_colors(view.result.polygon))
    assert set(box_colors(view).values()) == {PAINTED, CURRENT}


def test_the_final_images_are_the_bsp_and_the_zbuffer(stepper):
    view = stepper.views[0]
    _, _, final, zbuffered = view.axes[1:]
    np.testing.assert_array_equal(final.images[0].get_array(), polygon_colors(view.result.polygon))
    np.testing.assert_array_equal(final.images[0].get_array(), zbuffered.images[0].get_array())


def test_tree_boxes_and_regions_have_their_polygons_palette_color(stepper):
    from matplotlib.colors import to_rgb

    from scanviz.widgets.visibility import PALETTE

    view = stepper.views[0]
    for node in view.tree.nodes:
        edge = view.node_boxes[node.node].get_bbox_patch().get_edgecolor()
        assert np.allclose(edge[:3], to_rgb(PALETTE[node.polygon % len(PALETTE)])), node.node
    for (polygon, _), patch in view.regions.items():
        assert np.allclose(patch.get_facecolor()[:3], to_rgb(PALETTE[polygon % len(PALETTE)]))

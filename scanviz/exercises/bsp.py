"""Exercise on the BSP tree's display order (scanviz.visibility.bsp), through `solve`.

The student writes the step ``bsp_display_order``: at each node of the
tree, given whether the viewer is in front of the node's plane and the
display's direction, the order of the node's back subtree, its own
polygons and its front subtree. The real BSP builds the tree and displays
it with that step; the trace of the visits and the painting order is
graded. Cases are screen polygons (x, y in pixels, depth z, smaller =
nearer), the slides' example among them (`scanviz.visibility.examples.slides_bsp`).
"""

from __future__ import annotations

import functools
import random

from ..visibility import solve
from ..visibility.bsp import BSP, ORDERS, ROOTS, display_order
from ..visibility.examples import BSP_SEQUENCE, slides_bsp
from .cases import call_with_step, case_polygons, place_by_event, plane_polygon, polygon_lists
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests


def case_options(inputs: dict) -> BSP:
    """The BSP of a case: its root rule, display order and polygon list order."""
    return BSP(root=inputs["root"], order=inputs["order"], sequence=tuple(inputs["sequence"]))


def _solve(inputs: dict, tracer):
    return solve(
        case_options(inputs),
        case_polygons(inputs),
        inputs["width"],
        inputs["height"],
        trace=tracer,
    )


_node_of_call = place_by_event(
    "bsp_visited", lambda visit: f"node {visit.node} (piece {visit.piece})"
)


def _slides_case(order: str) -> dict:
    return {
        "polygons": polygon_lists(slides_bsp()),
        "width": 32,
        "height": 24,
        "root": "first",
        "order": order,
        "sequence": list(BSP_SEQUENCE),
    }


def _bsp_case(rng: random.Random, feature: str | None = None) -> Case:
    """Screen polygons and a BSP; a `feature` of `BSP_FEATURES` picks the display order."""
    width, height = rng.randint(8, 16), rng.randint(8, 16)
    count = rng.randint(2, 6)
    polygons = [
        plane_polygon(rng, width, height, depth=(0.2, 0.8), slope=0.05) for _ in range(count)
    ]
    order, root = rng.choice(ORDERS), rng.choice(ROOTS)
    if feature is not None:
        order = "front_to_back" if feature.endswith("front to back") else "back_to_front"
    sequence = rng.sample(range(count), rng.randint(0, count))
    return Case(
        f"{count} polygons, {order.replace('_', ' ')}, root {root}",
        {
            "polygons": polygons,
            "width": width,
            "height": height,
            "root": root,
            "order": order,
            "sequence": sequence,
        },
        order.replace("_", " "),
    )


def _visit(viewer_in_front: bool, front_to_back: bool):
    return lambda case, reference: (
        (viewer_in_front, front_to_back) in [tuple(args) for args, _ in reference.arguments]
    )


BSP_FEATURES = {
    f"viewer {'in front' if front else 'behind'}, {'front to back' if forward else 'back to front'}": (
        _visit(front, forward)
    )
    for front in (True, False)
    for forward in (True, False)
}
"""Tests of the display order's features: each of its four branches (the viewer on either side
of a node's plane, in either display direction)."""


DISPLAY_ORDER_SOLUTION = """\
def bsp_display_order(viewer_in_front, front_to_back):
    if viewer_in_front:
        far, near = "back", "front"
    else:
        far, near = "front", "back"
    if front_to_back:
        return (near, "self", far)
    return (far, "self", near)
"""


_order_variant = functools.partial(edited_variant, DISPLAY_ORDER_SOLUTION)


EXERCISE = register(
    Exercise(
        id="bsp_display_order",
        number=17,
        title="The BSP tree's display order",
        stage="visibility",
        kind="step",
        points=2,
        answer="bsp_display_order",
        idea=(
            "A BSP tree (Fuchs, Kedem and Naylor) holds at each node a polygon's plane, the "
            "polygons on its front side in the front subtree and those behind it in the back "
            "subtree (straddling ones are split). **DisplayBSP** paints the whole tree in a "
            "right order for any viewpoint: at each node, first the subtree on the side of the "
            "plane **away from the viewer**, then the node's own polygons, then the subtree on "
            "the viewer's side. So if the viewer is in front of the node's plane, the back "
            "subtree is drawn first (the slides: *viewpoint on front -> display back first*), "
            "else the front subtree.\n\n"
            "With a coverage mask the tree can also be displayed **front to back** (each "
            "sample is written only while still empty): then every node's order is reversed, "
            "the viewer's side first. Your step answers one node at a time."
        ),
        stub=(
            "def bsp_display_order(viewer_in_front, front_to_back):\n"
            '    """viewer_in_front: True if the viewer is on the front side of the node\'s\n'
            "    plane. front_to_back: True when the display goes front to back (with a\n"
            "    coverage mask), False for back to front.\n"
            '    Return the order to display the node\'s parts in: a tuple of "back" (its\n'
            '    back subtree), "self" (its own polygons) and "front" (its front subtree),\n'
            '    each once."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=DISPLAY_ORDER_SOLUTION,
        call=call_with_step("bsp_display_order", _solve),
        reference=display_order,
        public=(
            Case(
                "the slides' example from viewpoint C, back to front", _slides_case("back_to_front")
            ),
            Case(
                "the slides' example from viewpoint C, front to back", _slides_case("front_to_back")
            ),
            Case(
                "two triangles, the viewer behind the nearer one's plane, back to front",
                {
                    "polygons": [
                        [[1, 1, 0.3], [1, 9, 0.3], [9, 1, 0.3]],  # clockwise: seen from its back
                        [[3, 3, 0.6], [11, 3, 0.6], [3, 11, 0.6]],
                    ],
                    "width": 12,
                    "height": 12,
                    "root": "first",
                    "order": "back_to_front",
                    "sequence": [],
                },
            ),
        ),
        generate=_bsp_case,
        **feature_tests(BSP_FEATURES),
        variants=(
            _order_variant(
                "always_back_first",
                "which subtree is far depends on the viewer: behind the node's plane (viewer not "
                "in front), the front subtree is the far one and is drawn first",
                ('        far, near = "front", "back"\n', '        far, near = "back", "front"\n'),
            ),
            _order_variant(
                "sides_swapped",
                "back to front draws the side away from the viewer first: the back subtree when "
                "the viewer is in front of the plane (viewpoint on front -> display back first)",
                ('    return (far, "self", near)\n', '    return (near, "self", far)\n'),
            ),
            _order_variant(
                "ignores_front_to_back",
                "front to back reverses every node's order: the viewer's side first, then the "
                "node, then the far side",
                ("    if front_to_back:\n", "    if False:\n"),
            ),
            _order_variant(
                "self_first",
                "a node's own polygons go between its subtrees: after everything on the far "
                "side, before everything on the viewer's side",
                ('    return (far, "self", near)\n', '    return ("self", far, near)\n'),
            ),
        ),
        kinds=("bsp_visited", "paint_order"),
        step="bsp_display_order",
        place=_node_of_call,
        result=lambda result: result.polygon.tolist(),
        stepper=(
            "from scanviz.exercises.bsp import case_options, case_polygons\n"
            "from scanviz.widgets.bsp import bsp_stepper\n"
            "options = case_options(CASE)\n"
            "bsp_stepper(case_polygons(CASE), CASE['width'], CASE['height'], root=options.root,\n"
            "            order=options.order, sequence=options.sequence)"
        ),
    )
)

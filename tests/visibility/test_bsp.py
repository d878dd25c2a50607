"""BSP trees (issue 10, deliverable 3): the slides' tree, agreement with the z-buffer, invariants.

The oracles: the z-buffer (`support.assert_agrees`), each polygon drawn alone
(its samples and depths), `Surfaces.classify` piece by piece, and the
slides' example (`examples.slides_bsp`), whose tree, visits and painting
order are read off the slides, not the code.
"""

import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.pipeline import render
from scanviz.scene.builtin import BUILTIN_SCENES, builtin_scene
from scanviz.trace import Recorder
from scanviz.visibility import ScreenPolygons, Surfaces, examples, solve, zbuffer
from scanviz.visibility.bsp import BSP, ORDERS, ROOTS, BspTree, classify_all
from tests.visibility.support import assert_agrees, polygon_depths, random_scene

EXAMPLES = max(settings.default.max_examples // 5, 1)
SIZE = 24
seeds = st.integers(0, 2**32 - 1)
SLIDES = BSP(sequence=examples.BSP_SEQUENCE)


def slides(options=SLIDES, **kwargs):
    return solve(options, examples.slides_bsp(), 32, 24, **kwargs)


def labelled(tree: BspTree):
    """node root label -> (front root label, back root label), '' for none."""
    name = {n.node: n.pieces[0] for n in tree.nodes}
    return {n.pieces[0]: (name.get(n.front, ""), name.get(n.back, "")) for n in tree.nodes}


# --- the slides' example ------------------------------------------------------------------


def test_the_slides_tree_from_pgon_3():
    tree = slides().detail
    assert labelled(tree) == {
        "3": ("2", "4"),  # pgon 3 at the root, split on its plane
        "2": ("5a", "1"),  # the front subtree split at pgon 2
        "4": ("", "5b"),  # the back subtree at pgon 4
        "5a": ("", ""),
        "1": ("", ""),
        "5b": ("", ""),
    }
    assert tree.nodes[0].polygon == 3 and tree.height == 3


def test_the_slides_display_from_viewpoint_c():
    result = slides(trace=Recorder(["bsp_visited"]))
    # "at 3: viewpoint on front -> display back first; at 4: on back -> front first (none) ..."
    visits = [(e.piece, e.viewer_in_front, e.first) for e in result.trace]
    assert visits == [
        ("3", True, "back"),
        ("4", False, "front"),
        ("5b", False, "front"),
        ("2", False, "front"),
        ("5a", False, "front"),
        ("1", True, "back"),
    ]
    assert [p.label for p in result.order] == ["4", "5b", "3", "5a", "2", "1"]


def test_the_slides_split_of_5_by_the_plane_of_3():
    result = slides(trace=True)
    (split,) = [e for e in result.trace if e.kind == "polygon_split"]
    assert (split.piece, split.by, split.why) == ("5", 3, "straddles")
    assert (split.front.label, split.behind.label) == ("5a", "5b")
    root = next(e for e in result.trace if e.kind == "bsp_node")
    assert (root.front, root.back, root.coplanar) == (("2", "5a", "1"), ("4", "5b"), ())
    assert root.candidates[0].label == "3" and root.candidates[0].splits == 1


def test_the_slides_stats_and_image():
    result = slides()
    stats = result.algorithm
    assert (stats.nodes, stats.splits, stats.depth, stats.pieces, stats.left_out) == (6, 1, 3, 6, 1)
    _, _, where = assert_agrees(SLIDES, examples.slides_bsp(), 32, 24)
    assert where.all()
    assert set(np.unique(result.polygon)) == {-1, 1, 2, 3, 4, 5}  # every wall shows somewhere


def test_the_alternate_tree_of_the_slides():
    # "Alternate tree if splits are made at 5, 4, 3, 1": another tree, the same image.
    alternate = slides(BSP(sequence=(5, 4, 3, 1, 2)))
    assert alternate.detail.nodes[0].polygon == 5 and labelled(alternate.detail) != labelled(
        slides().detail
    )
    assert np.array_equal(alternate.polygon, slides().polygon)


# --- agreement with the z-buffer ----------------------------------------------------------


def scene(seed, n, interpenetrating):
    return random_scene(np.random.default_rng(seed), n, SIZE, interpenetrating)


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("root", ROOTS)
@settings(max_examples=EXAMPLES)
@given(seed=seeds, n=st.integers(1, 7), interpenetrating=st.booleans())
def test_agrees_with_the_zbuffer(root, order, seed, n, interpenetrating):
    assert_agrees(
        BSP(root=root, order=order, seed=seed % 7), scene(seed, n, interpenetrating), SIZE, SIZE
    )


@pytest.mark.parametrize("order", ORDERS)
@pytest.mark.parametrize("root", ROOTS)
def test_traced_equals_untraced(root, order):
    polygons = scene(11, 7, True)
    options = BSP(root=root, order=order)
    fast = solve(options, polygons, SIZE, SIZE)
    traced = solve(options, polygons, SIZE, SIZE, trace=True)
    assert fast.stats.path == "compiled" and traced.stats.path == "traced reference"
    for name in ("depth", "polygon", "values"):
        assert np.array_equal(getattr(fast, name), getattr(traced, name)), name
    assert fast.order == traced.order and fast.detail == traced.detail
    assert fast.algorithm == traced.algorithm


def test_front_to_back_writes_each_sample_once():
    polygons = scene(5, 7, True)
    back = solve(BSP(), polygons, SIZE, SIZE)
    front = solve(BSP(order="front_to_back"), polygons, SIZE, SIZE)
    assert [p.label for p in front.order] == [p.label for p in back.order][::-1]
    assert front.stats.depth_passed == int((front.polygon >= 0).sum())  # the coverage mask
    assert back.stats.depth_passed > front.stats.depth_passed  # back to front overpaints


# --- the tree's invariants ----------------------------------------------------------------


def subtree(tree, node):
    """The node numbers of the subtree rooted at `node`."""
    found, stack = [], [node] if node >= 0 else []
    while stack:
        n = tree.nodes[stack.pop()]
        found.append(n.node)
        stack.extend(k for k in (n.front, n.back) if k >= 0)
    return found


@pytest.mark.parametrize("root", ROOTS)
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_every_piece_lies_on_its_side_and_the_pieces_partition_each_polygon(root, seed):
    polygons = scene(seed, 7, True)
    surfaces = Surfaces.of(polygons, SIZE, SIZE)
    result = solve(BSP(root=root), polygons, SIZE, SIZE)
    tree, pieces = result.detail, {p.label + f"@{p.polygon}": p for p in result.order}
    depths = polygon_depths(polygons, SIZE, SIZE)
    ys, xs = np.mgrid[0:SIZE, 0:SIZE]

    def samples(piece):
        covered = np.isfinite(depths[piece.polygon])
        kept = [surfaces.keeps(piece, x, y) for x, y in zip(xs[covered], ys[covered], strict=True)]
        return xs[covered][kept], ys[covered][kept]

    def node_pieces(n):
        node = tree.nodes[n]
        return [pieces[f"{label}@{node.polygon}"] for label in node.pieces]

    # Each polygon's samples are painted exactly once over all its pieces.
    count = np.zeros((polygons.count, SIZE, SIZE), int)
    for piece in result.order:
        x, y = samples(piece)
        np.add.at(count[piece.polygon], (y, x), 1)
    assert np.array_equal(count, np.isfinite(depths).astype(int))
    # A piece in a node's front subtree is on the front side of the node's plane (the viewer's
    # side iff the node's polygon faces the viewer), in its back subtree on the back side.
    for node in tree.nodes:
        q, facing = node.polygon, surfaces.front_facing(node.polygon)
        for side, sign in (("front", -1), ("back", 1)):
            for k in subtree(tree, getattr(node, side)):
                for piece in node_pieces(k):
                    x, y = samples(piece)
                    behind = surfaces.depth(piece.polygon, x, y) - surfaces.depth(q, x, y)
                    assert (sign * (1 if facing else -1) * behind >= -2 * surfaces.tolerance).all()
    # The tree: parents and children agree, the depth is the longest path.
    for node in tree.nodes:
        for side in ("front", "back"):
            child = getattr(node, side)
            if child >= 0:
                assert (tree.nodes[child].parent, tree.nodes[child].side) == (node.node, side)
                assert tree.nodes[child].depth == node.depth + 1
    assert result.algorithm.depth == 1 + max(n.depth for n in tree.nodes)
    assert result.algorithm.pieces == len(result.order) == sum(len(n.pieces) for n in tree.nodes)
    drawn = int(surfaces.drawn.sum())
    assert result.algorithm.pieces == drawn + result.algorithm.splits  # a split adds one piece


def test_vectorised_classification_is_surfaces_classify():
    polygons = scene(8, 7, True)
    surfaces = Surfaces.of(polygons, SIZE, SIZE)
    pieces = list(solve(BSP(), polygons, SIZE, SIZE).order)  # split pieces among them
    assert any(p.cuts for p in pieces)
    for q in range(polygons.count):
        assert classify_all(surfaces, pieces, q).tolist() == [
            surfaces.classify(p, q) for p in pieces
        ]


def test_fewest_splits_takes_the_candidate_with_fewest_ties_to_the_earliest():
    polygons = scene(3, 7, True)
    surfaces = Surfaces.of(polygons, SIZE, SIZE)
    result = solve(BSP(root="fewest_splits", candidates=3), polygons, SIZE, SIZE, trace=True)
    root = next(e for e in result.trace if e.kind == "bsp_node")
    listed = surfaces.pieces()
    expected = [
        sum(surfaces.classify(p, c.polygon) == "straddles" for p in listed if p is not c)
        for c in listed[:3]
    ]
    assert [c.splits for c in root.candidates] == expected
    assert root.piece == listed[expected.index(min(expected))].label


def test_random_roots_follow_the_seed():
    polygons = scene(4, 7, True)
    trees = [solve(BSP(root="random", seed=s), polygons, SIZE, SIZE).detail for s in (1, 1, 2, 3)]
    assert trees[0] == trees[1]
    assert len({labelled(t).__repr__() for t in trees}) > 1


def test_the_trace_has_one_node_event_per_node_and_one_visit_per_node():
    result = solve(BSP(root="fewest_splits"), scene(9, 7, True), SIZE, SIZE, trace=True)
    kinds = [e.kind for e in result.trace]
    nodes = [e for e in result.trace if e.kind == "bsp_node"]
    assert [e.node for e in nodes] == list(range(result.algorithm.nodes))
    assert kinds.count("bsp_visited") == result.algorithm.nodes
    assert kinds.count("polygon_split") == result.algorithm.splits
    visited = [e.node for e in result.trace if e.kind == "bsp_visited"]
    assert tuple(visited) == result.detail.visits
    assert kinds.index("paint_order") > max(i for i, k in enumerate(kinds) if k == "bsp_visited")


# --- degenerate and hostile input ---------------------------------------------------------


def test_coplanar_polygons_share_a_node():
    polygons = ScreenPolygons.from_polygons(
        [
            [(1, 1, 0.5), (9, 1, 0.5), (1, 9, 0.5)],
            [(3, 3, 0.5), (11, 3, 0.5), (3, 11, 0.5)],  # the same plane
            [(0, 0, 0.9), (12, 0, 0.9), (12, 12, 0.9), (0, 12, 0.9)],
        ]
    )
    result = solve(BSP(), polygons, 12, 12)
    assert result.detail.nodes[0].pieces == ("0", "1")
    assert result.algorithm.nodes == 2
    assert_agrees(BSP(), polygons, 12, 12)


def test_edge_on_and_empty_scenes_render():
    edge_on = ScreenPolygons.from_polygons(
        [[(1, 1, 0.2), (9, 9, 0.5), (5, 5, 0.8)], [(0, 0, 0.5), (8, 0, 0.5), (0, 8, 0.5)]]
    )
    result = solve(BSP(), edge_on, 10, 10)
    assert result.algorithm.left_out == 1 and result.algorithm.nodes == 1
    empty = ScreenPolygons.from_polygons([])
    for order in ORDERS:
        nothing = solve(BSP(order=order), empty, 4, 4, trace=True)
        assert (nothing.polygon == -1).all() and nothing.detail == BspTree()
        assert nothing.algorithm.depth == 0


def test_a_deep_tree_needs_no_recursion():
    # Nested triangles, each behind the last: with root "first" the tree is a chain.
    n = sys.getrecursionlimit() + 200
    polygons = ScreenPolygons.from_polygons(
        [[(0, 0, k / n), (8, 0, k / n), (0, 8, k / n)] for k in range(n)]
    )
    result = solve(BSP(), polygons, 8, 8)
    assert result.algorithm.depth == n and (result.polygon[result.polygon >= 0] == 0).all()


def test_splitting_is_bounded_by_the_memory_limit():
    polygons = random_scene(np.random.default_rng(1), 200, 64, interpenetrating=True)
    with memory_limit("1M"), pytest.raises(ResourceLimitError, match="a BSP tree of"):
        solve(BSP(), polygons, 64, 64)


# --- options, the step, render ------------------------------------------------------------


@pytest.mark.parametrize(
    "options, error, message",
    [
        ({"root": "best"}, ValueError, "'root' must be one of"),
        ({"order": "front"}, ValueError, "'order' must be one of"),
        ({"candidates": 0}, ValueError, "'candidates' must be at least 1"),
        ({"candidates": 2.5}, TypeError, "'candidates' must be an int"),
        ({"seed": None}, TypeError, "'seed' must be an int"),
        ({"sequence": [3, 2]}, TypeError, "'sequence' must be a tuple"),
        ({"sequence": (3, 3)}, ValueError, "must not repeat"),
    ],
)
def test_bad_options_are_refused(options, error, message):
    with pytest.raises(error, match=message):
        BSP(**options)


def test_a_sequence_beyond_the_scene_is_refused():
    with pytest.raises(ValueError, match="'sequence' names polygon 9"):
        solve(BSP(sequence=(9,)), examples.slides_bsp(), 32, 24)


def test_the_display_order_step_drives_the_display():
    def swapped(in_front, front_to_back):  # the sides swapped: the viewer's side first
        return ("front", "self", "back") if in_front else ("back", "self", "front")

    with steps.using(bsp_display_order=swapped):
        wrong = slides()
    assert [p.label for p in wrong.order] == ["1", "2", "5a", "3", "5b", "4"]
    reference = zbuffer(examples.slides_bsp(), 32, 24)
    assert (wrong.polygon != reference.polygon).any()
    with steps.using(bsp_display_order=lambda *args: ("back", "front")):
        with pytest.raises(ValueError, match="must return an ordering of"):
            slides()


@pytest.mark.parametrize("shading", ["flat", "gouraud", "phong", "gooch"])
def test_render_with_bsp_in_every_shading_mode(shading):
    for name in ("umbc_zbuffer", "painter"):
        spec, chosen = BUILTIN_SCENES[name], builtin_scene(name)
        reference = render(chosen, spec.width, spec.height, shading=shading)
        for visibility in ("bsp", BSP(root="fewest_splits", order="front_to_back")):
            result = render(chosen, spec.width, spec.height, shading=shading, visibility=visibility)
            assert np.array_equal(result.polygon, reference.polygon), (name, visibility)
            assert np.array_equal(result.image, reference.image), (name, visibility)

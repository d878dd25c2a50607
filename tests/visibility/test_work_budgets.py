"""Issue 27: BSP and depth sort refuse, with the figure and the option, scenes whose work explodes."""

import numpy as np
import pytest

from scanviz.limits import ResourceLimitError
from scanviz.visibility import BSP, DepthSort, ScreenPolygons, examples, solve


def _covering_triangles(count: int, size: int = 64, seed: int = 0) -> ScreenPolygons:
    """Random triangles larger than the raster at random depths: every plane cuts every polygon."""
    rng = np.random.default_rng(seed)
    corners = rng.uniform(-size, 2 * size, (count, 3, 2))
    depths = rng.uniform(0.1, 0.9, (count, 3, 1))
    return ScreenPolygons.from_polygons(np.concatenate([corners, depths], axis=2).tolist())


def test_bsp_refuses_a_tree_past_its_piece_budget():
    with pytest.raises(
        ResourceLimitError, match=r"the BSP tree's pieces passed [\d,]+ \(max_pieces\)"
    ):
        solve("bsp", _covering_triangles(300), 64, 64)


def test_depth_sort_refuses_past_its_work_budgets():
    with pytest.raises(
        ResourceLimitError, match=r"depth sort's overlapping pairs passed [\d,]+ \(max_hard_pairs\)"
    ):
        solve("depth_sort", _covering_triangles(100), 64, 64)


def test_the_budgets_are_options():
    scene = examples.cyclic_overlap()
    pieces = solve(BSP(), scene, 24, 24).algorithm.pieces
    assert pieces > scene.count  # the cycle is split
    assert solve(BSP(max_pieces=pieces), scene, 24, 24).algorithm.pieces == pieces
    with pytest.raises(ResourceLimitError, match=f"pieces passed {pieces - 1} "):
        solve(BSP(max_pieces=pieces - 1), scene, 24, 24)
    with pytest.raises(ResourceLimitError, match=r"pairs passed 1 \(max_hard_pairs\)"):
        solve(DepthSort(max_hard_pairs=1), scene, 24, 24)
    with pytest.raises(ResourceLimitError, match=r"pair tests passed 1 \(max_pairs\)"):
        solve(DepthSort(max_pairs=1), scene, 24, 24)
    assert solve(DepthSort(), scene, 24, 24).algorithm.unresolved == 0


@pytest.mark.parametrize("bad", [0, -1, 2.5, True])
def test_bad_budgets_are_refused(bad):
    with pytest.raises(ValueError, match="'max_pieces' must be None or an int >= 1"):
        BSP(max_pieces=bad)
    with pytest.raises(ValueError, match="'max_hard_pairs' must be None or an int >= 1"):
        DepthSort(max_hard_pairs=bad)
    with pytest.raises(ValueError, match="'max_pairs' must be None or an int >= 1"):
        DepthSort(max_pairs=bad)


def test_ordinary_scenes_stay_far_below_the_budgets():
    for kind in examples.RANDOM_KINDS:
        scene = examples.random_scene(kind, 1)
        solve("bsp", scene, 32, 32)
        solve("depth_sort", scene, 32, 32)

"""Issue 27: DISLOP inputs beyond float64 and walks past their step budget are refused in one line."""

import re

import numpy as np
import pytest

from scanviz.antialias import dislop_circle, dislop_disk, dislop_edge, edge_algorithm
from scanviz.antialias.surfaces import _level


@pytest.mark.parametrize("draw", [dislop_disk, dislop_circle])
@pytest.mark.parametrize("radius", [10**400, -(10**400)])
def test_a_radius_past_float64_is_out_of_range(draw, radius):
    with pytest.raises(ValueError, match=r"^'radius' must be finite and in 0\.\.2\*\*20; got "):
        draw((5, 5), radius, 10, 10)


def test_a_level_past_float64_is_out_of_range():
    with pytest.raises(ValueError, match=r"^'background' must be in \[0, 1\]"):
        _level("background", 10**400)


def crossing_polygon(vertices: int) -> np.ndarray:
    return np.random.default_rng(0).uniform(0, 16, (vertices, 2))


def test_dislop_edge_refuses_a_polygon_past_its_step_budget(monkeypatch):
    # 100 random vertices: their edges cross about 1,200 times, each crossing splitting both
    # edges, so about 2,500 pieces, each testing its two sides against the 100 edges
    polygon = crossing_polygon(100)
    pieces = edge_algorithm._count_pieces(polygon, np.roll(polygon, -1, axis=0))
    assert 2000 < pieces < 3000
    steps = 100 * 100 + 100 * 16 + 2 * pieces * 100
    monkeypatch.setattr(edge_algorithm, "MAX_STEPS", steps - 1)
    message = f"100 edges need too many steps ({steps:.3g} for {pieces} pieces, limit {steps - 1})"
    with pytest.raises(ValueError, match=re.escape(message)):
        dislop_edge(polygon, 16, 16)
    monkeypatch.setattr(edge_algorithm, "MAX_STEPS", steps)
    assert dislop_edge(polygon, 16, 16).max() <= 1.0


def test_dislop_edge_refuses_at_once_what_its_pair_tests_alone_exceed():
    # 50,000 vertices: 2.5e9 pairs of edges to test, over the 2**31 budget; refused before any test
    angle = np.linspace(0, 2 * np.pi, 50_000, endpoint=False)
    circle = np.column_stack([8 + 6 * np.cos(angle), 8 + 6 * np.sin(angle)])
    with pytest.raises(ValueError, match=r"50000 edges need too many steps \(at least 2.5e\+09"):
        dislop_edge(circle, 16, 16)

"""Issue 27: the line images of the floating horizon and perimeter are estimated; traces kept."""

import numpy as np
import pytest

from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.surfaces import GridSurface, View, floating_horizon, floating_perimeter

PLANE = GridSurface([0.0, 1.0], [0.0, 1.0, 2.0], [[0, 0], [0, 0], [0, 0]])
FRONT = View((0.5, -4, 3), (0, 1, -1))


def test_floating_horizon_keeps_its_trace():
    result = floating_horizon(PLANE, FRONT, 5, 5, trace=True)
    kinds = [event.kind for event in result.trace]
    assert kinds.count("horizon_curve") == 3 and "horizon_column" in kinds
    assert floating_horizon(PLANE, FRONT, 5, 5).trace is None


def test_floating_horizon_traced_and_compiled_draw_the_same_lines():
    traced = floating_horizon(PLANE, FRONT, 9, 7, trace=True)
    assert np.array_equal(traced.lines, floating_horizon(PLANE, FRONT, 9, 7).lines)


def test_floating_horizon_refuses_its_image_before_allocating_it():
    # 33 bytes a pixel (lines, gray, RGB): 200 x 200 is 1.3 MB, over 1 MiB
    with memory_limit("1M"), pytest.raises(ResourceLimitError) as refused:
        floating_horizon(PLANE, FRONT, 200, 200)
    assert "floating_horizon: a 200x200 line image of a 2x3 grid" in str(refused.value)
    with memory_limit("1M"):
        assert floating_horizon(PLANE, FRONT, 150, 150).lines.any()  # 0.74 MB


def test_floating_perimeter_lines_refuse_their_image_before_allocating_it():
    with memory_limit("1M"), pytest.raises(ResourceLimitError, match="floating perimeter of a 2x3"):
        floating_perimeter(PLANE, FRONT, 200, 200, "lines")

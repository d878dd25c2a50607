"""The visibility interface: names and instances, errors, and `render` dispatching through it."""

import numpy as np
import pytest

from scanviz import render
from scanviz.io import load_scene
from scanviz.trace import Recorder
from scanviz.visibility import (
    ALGORITHMS,
    Painter,
    ScreenPolygons,
    Visibility,
    examples,
    solve,
    zbuffer,
)
from scanviz.visibility.interface import register
from scanviz.visibility.painter import PainterStats


def test_solve_checks_its_arguments():
    polygons = examples.slides_painter()
    with pytest.raises(ValueError, match="'visibility' must be one of .*'painter'"):
        solve("painters", polygons, 16, 12)
    with pytest.raises(TypeError, match="'visibility' must be a name"):
        solve(3, polygons, 16, 12)
    with pytest.raises(TypeError, match="'polygons' must be a ScreenPolygons"):
        solve("painter", [[(0, 0, 0)]], 16, 12)
    with pytest.raises(ValueError, match="'key' must be one of"):
        Painter(key="zfar")
    with pytest.raises(TypeError, match="empty or taken"):
        register(Painter)


def test_the_z_buffer_through_solve_is_the_z_buffer():
    polygons = examples.slides_zbuffer()
    a, b = solve("zbuffer", polygons, 10, 9), zbuffer(polygons, 10, 9)
    assert np.array_equal(a.polygon, b.polygon) and np.array_equal(a.depth, b.depth)
    assert a.name == "zbuffer" and not a.order


def test_the_slides_painter_example_paints_10_then_8_then_5():
    result = solve("painter", examples.slides_painter(), 16, 12, trace=Recorder())
    assert [p.label for p in result.order] == ["0", "1", "2"]
    assert isinstance(result.algorithm, PainterStats) and result.algorithm.polygons == 3
    kinds = [e.kind for e in result.trace]
    assert kinds[:2] == ["polygons_sorted", "paint_order"] and "pixel_painted" in kinds
    # where the square (z = 5) overlaps the rectangle (z = 8), the square wins: it is painted last
    assert result.polygon[5, 7] == 2 and result.polygon[3, 3] == 1


def test_render_takes_a_name_or_an_instance_and_says_which_ran():
    scene = load_scene("builtin:sphere")
    by_name = render(scene, 32, 32, visibility="painter")
    by_instance = render(scene, 32, 32, visibility=Painter(key="zmax"))
    reference = render(scene, 32, 32)
    # a closed convex mesh, culled: no two front faces overlap, so any order is right
    assert np.array_equal(by_name.image, reference.image)
    assert np.array_equal(by_instance.image, reference.image)
    assert by_name.plan.runs("list priority / image space") and not by_name.plan.runs("z-buffer")
    assert "painter: decides what is visible" in str(by_name.plan)
    assert by_name.visibility.name == "painter" and reference.visibility.name == "zbuffer"


def test_every_registered_algorithm_is_a_named_visibility():
    assert {"zbuffer", "painter"} <= set(ALGORITHMS)
    for name, cls in ALGORITHMS.items():
        assert cls.name == name and issubclass(cls, Visibility)
        empty = ScreenPolygons.from_polygons([])
        result = solve(name, empty, 4, 3)
        assert (result.polygon == -1).all() and np.isinf(result.depth).all()

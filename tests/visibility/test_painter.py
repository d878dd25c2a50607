"""The painter's algorithm: its sort keys, and its failures left visible (deliverable 1)."""

import numpy as np
import pytest

import scanviz
from scanviz.pipeline import SHADINGS
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder
from scanviz.visibility import ScreenPolygons, examples, solve, zbuffer
from scanviz.visibility.painter import KEYS, Painter

# Three triangles whose zmin, zmax and mean vertex depth give three orders:
# zmin 0.1, 0.45, 0.2; zmax 0.9, 0.47, 0.95; mean 0.5, 0.46, 0.483.
KEYED = ScreenPolygons.from_polygons(
    [
        [(0, 0, 0.1), (4, 0, 0.5), (0, 4, 0.9)],
        [(4, 4, 0.45), (8, 4, 0.46), (4, 8, 0.47)],
        [(0, 4, 0.2), (4, 4, 0.3), (0, 8, 0.95)],
    ]
)


@pytest.mark.parametrize(
    "key, order",
    [("zmin", ["1", "2", "0"]), ("zmax", ["2", "0", "1"]), ("centroid", ["0", "2", "1"])],
)
def test_each_key_sorts_farthest_first(key, order):
    result = solve(Painter(key=key), KEYED, 8, 8, trace=Recorder(kinds=["polygons_sorted"]))
    assert [piece.label for piece in result.order] == order
    (sorted_event,) = result.trace
    assert sorted_event.key == key and [p.label for p in sorted_event.pieces] == order


def test_the_slides_example_is_painted_10_8_5():
    result = solve("painter", examples.slides_painter(), 16, 12)
    assert [piece.label for piece in result.order] == ["0", "1", "2"]
    assert np.array_equal(result.polygon, zbuffer(examples.slides_painter(), 16, 12).polygon)


def wrong_samples(polygons, width, height, visibility="painter"):
    painted = solve(visibility, polygons, width, height).polygon
    return int((painted != zbuffer(polygons, width, height).polygon).sum())


@pytest.mark.parametrize("key", KEYS)
def test_a_cyclic_overlap_is_painted_wrongly_with_every_key(key):
    assert wrong_samples(examples.cyclic_overlap(), 24, 24, Painter(key=key)) > 0


@pytest.mark.parametrize("key", KEYS)
def test_interpenetrating_polygons_are_painted_wrongly_with_every_key(key):
    assert wrong_samples(examples.interpenetrating(), 16, 12, Painter(key=key)) > 0


def test_a_long_polygon_behind_a_short_one_is_wrong_on_zmin_right_on_zmax():
    polygons = examples.long_behind_short()
    assert wrong_samples(polygons, 16, 12, Painter(key="zmin")) > 0
    assert wrong_samples(polygons, 16, 12, Painter(key="zmax")) == 0


def test_the_wrong_samples_are_where_the_first_painted_polygon_is_nearer():
    polygons = examples.long_behind_short()
    painted = solve("painter", polygons, 16, 12)
    reference = zbuffer(polygons, 16, 12)
    wrong = painted.polygon != reference.polygon
    # Sorted on zmin the short polygon (1, zmin 0.5) goes first; the long one (0) covers it.
    assert (painted.polygon[wrong] == 0).all() and (reference.polygon[wrong] == 1).all()
    assert (painted.depth[wrong] > reference.depth[wrong]).all()  # a farther surface shown


@pytest.mark.parametrize("key", KEYS)
def test_traced_equals_untraced(key):
    polygons = examples.cyclic_overlap()
    fast = solve(Painter(key=key), polygons, 24, 24)
    traced = solve(Painter(key=key), polygons, 24, 24, trace=True)
    assert [p.label for p in fast.order] == [p.label for p in traced.order]
    for name in ("polygon", "depth", "values"):
        assert np.array_equal(getattr(fast, name), getattr(traced, name)), name
    painted = [e for e in traced.trace if e.kind == "pixel_painted" and e.painted]
    assert len(painted) == traced.stats.fragments


def test_a_bad_key_is_refused():
    with pytest.raises(ValueError, match="'key'"):
        Painter(key="zmean")


@pytest.mark.parametrize("shading", SHADINGS)
def test_render_with_the_painter_equals_the_zbuffer_on_a_culled_sphere(shading):
    # Culled, the sphere's front faces never overlap on the screen: any order is right.
    scene = builtin_scene("sphere", level=2)
    painted = scanviz.render(scene, 32, 32, shading=shading, visibility="painter")
    reference = scanviz.render(scene, 32, 32, shading=shading)
    assert (reference.polygon >= 0).sum() > 300
    assert np.array_equal(painted.polygon, reference.polygon)
    assert np.array_equal(painted.image, reference.image)

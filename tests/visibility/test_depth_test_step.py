"""The z-buffer's replaceable depth test: the rule, and the compiled path stepping aside."""

import numpy as np

from scanviz import steps
from scanviz.visibility import ScreenPolygons, zbuffer
from scanviz.visibility.zbuffer import depth_test

# The UMBC slide: a triangle at depth 5, a square behind it at 9, a sloped triangle piercing both.
SLIDE = ScreenPolygons.from_polygons(
    [
        [(1, 1, 5), (7, 7, 5), (1, 7, 5)],
        [(3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)],
        [(2, 6, 3), (2, 3, 8), (7, 3, 3)],
    ],
    values=[[(0.0,)] * 3, [(1.0,)] * 4, [(2.0,)] * 3],
)


def test_depth_test_smaller_is_nearer_ties_keep_the_stored_fragment():
    assert depth_test(0.75, None) is True  # an empty sample takes any fragment
    assert depth_test(0.0, 0.5) is True
    assert depth_test(0.5, 0.5) is False  # a tie: the earlier polygon stays
    assert depth_test(0.5, 0.0) is False


def test_while_a_step_is_replaced_zbuffer_runs_the_reference_untraced():
    compiled = zbuffer(SLIDE, 10, 9)
    with steps.using(depth_test=depth_test):
        plugged = zbuffer(SLIDE, 10, 9)
    assert (compiled.stats.path, plugged.stats.path) == ("compiled", "reference")
    for name in ("depth", "polygon", "values"):
        assert np.array_equal(getattr(plugged, name), getattr(compiled, name)), name


def test_a_replaced_depth_test_decides_every_sample():
    with steps.using(depth_test=lambda z, stored: True):  # no test: the last polygon drawn wins
        last = zbuffer(SLIDE, 10, 9)
    # At (3, 6) the square (drawn second) is behind the first triangle: the test keeps 0.
    assert zbuffer(SLIDE, 10, 9).polygon[6, 3] == 0 and last.polygon[6, 3] == 1
    assert last.stats.depth_failed == 0 and last.stats.depth_passed == last.stats.fragments

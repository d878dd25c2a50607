"""The fill-variant stepper, headless: built from real traces, stepped to the end."""

import matplotlib
import numpy as np
import pytest

from scanviz.raster import ColourWash, Pattern, Solid, VertexColours, fill_polygon
from scanviz.widgets.fill import UNFILLED, fill_stepper

matplotlib.use("Agg")

TRIANGLE = [(1.25, 1.5), (14.5, 3.0), (6.0, 12.75)]


@pytest.mark.parametrize(
    "fill",
    [Solid((0.1, 0.5, 0.9)), Pattern.checker(), ColourWash(), VertexColours(np.eye(3))],
    ids=lambda f: type(f).__name__,
)
def test_stepping_to_the_end_shows_the_fill_and_each_span(fill):
    stepper = fill_stepper(TRIANGLE, 16, 14, fill)
    view = stepper.views[0]
    result = fill_polygon(TRIANGLE, 16, 14, fill)
    view.show(len(view.trace))
    shown = view.picture.get_array()
    np.testing.assert_array_equal(shown[result.mask], result.image[result.mask])
    assert (shown[~result.mask] == UNFILLED).all()
    rows = np.flatnonzero(result.mask.any(axis=1))
    assert len(view.spans) == len(rows)  # one span per row of a triangle
    view.show(0)
    assert (view.picture.get_array() == UNFILLED).all() and not view.span_patch.get_visible()


def test_a_bad_fill_is_a_clear_error():
    with pytest.raises(TypeError, match="'fill' must be a Solid"):
        fill_stepper(TRIANGLE, 8, 8, "red")

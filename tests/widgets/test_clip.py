"""The clipping view draws the input and the clipped polygon from the front and from above."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from scanviz.trace import Recorder  # noqa: E402
from scanviz.transform import clip_polygon  # noqa: E402
from scanviz.widgets import plot_clip  # noqa: E402


def test_plot_clip_shows_both_polygons_in_both_views():
    triangle = [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]  # pokes out of x = w
    recorder = Recorder()
    clipped, _ = clip_polygon(triangle, None, trace=recorder)
    figure = plot_clip(triangle, recorder.trace()[0])
    front, above = figure.axes
    for ax in (front, above):  # the visible area, the input's outline, the clipped polygon
        assert [p.get_fill() for p in ax.patches] == [True, False, True]
    # the clipped polygon's vertices, x/w and y/w, are the points drawn in red on the front view
    red = [line for line in front.lines if line.get_color() == "tab:red"][0]
    expected = np.asarray(clipped)[:, :2] / np.asarray(clipped)[:, 3:4]
    np.testing.assert_allclose(np.column_stack(red.get_data()), expected)
    assert "right 4" in figure._suptitle.get_text()


def test_plot_clip_wants_a_clipping_event():
    with pytest.raises(TypeError, match="'event' must be a PolygonClipped event"):
        plot_clip([[0, 0, 0, 1]] * 3, "nope")

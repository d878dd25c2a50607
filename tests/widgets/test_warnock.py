"""The Warnock view, headless: move the slider, check what the figure and the text now hold."""

import io

import matplotlib
import numpy as np
import pytest
from matplotlib.colors import to_rgb, to_rgba

from scanviz.visibility import examples, zbuffer
from scanviz.widgets.stepper import Stepper
from scanviz.widgets.visibility import polygon_colors
from scanviz.widgets.warnock import CASE_COLORS, UNDECIDED, warnock_stepper

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def stepper():
    return warnock_stepper(examples.slides_zbuffer(), 10, 9)


def decided_by(events, height, width):
    """Samples inside an area classified without subdividing among `events`."""
    decided = np.zeros((height, width), bool)
    for e in events:
        if e.case != "subdivide":
            decided[e.y_start : e.y_end, e.x_start : e.x_end] = True
    return decided


def test_one_step_per_area(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    assert stepper.slider.max == len(trace) == view.result.algorithm.areas
    assert all(e.kind == "area_classified" for e in trace)


@pytest.mark.parametrize("step", [1, 7, 20, -1])
def test_the_current_area_is_highlighted_and_described(stepper, step):
    view, trace = stepper.views[0], stepper.model.trace
    step = step % (len(trace) + 1)
    stepper.slider.value = step
    event = trace[step - 1]
    assert view.current.get_visible()
    assert view.current.get_xy() == (event.x_start, event.y_start)
    assert view.current.get_width() == event.x_end - event.x_start
    assert view.current.get_height() == event.y_end - event.y_start
    assert view.current.get_edgecolor() == to_rgba(CASE_COLORS[event.case])
    assert f"<b>{event.case}</b>" in view.text.value
    assert (
        f"polygons meeting it: {', '.join(map(str, event.polygons)) or 'none'}" in view.text.value
    )
    assert f"level {event.level}: area x [{event.x_start}, {event.x_end})" in view.text.value


@pytest.mark.parametrize("step", [0, 1, 12, 30, -1])
def test_the_quadtree_shows_the_areas_visited_in_their_case_colours(stepper, step):
    view, trace = stepper.views[0], stepper.model.trace
    step = step % (len(trace) + 1)
    stepper.slider.value = step
    edges = view.areas.get_edgecolors()
    assert (edges[:step, 3] > 0).all() and (edges[step:, 3] == 0).all()
    for e, color in zip(trace[:step], edges[:step], strict=True):
        assert tuple(color) == to_rgba(CASE_COLORS[e.case])


@pytest.mark.parametrize("step", [0, 5, 25, -1])
def test_the_decided_image_shows_the_leaves_so_far(stepper, step):
    view, trace = stepper.views[0], stepper.model.trace
    step = step % (len(trace) + 1)
    stepper.slider.value = step
    shown = np.asarray(view.decided_image.get_array())
    decided = decided_by(trace[:step], 9, 10)
    final = polygon_colors(view.result.polygon)
    assert np.array_equal(shown[decided], final[decided])
    assert np.allclose(shown[~decided], to_rgb(UNDECIDED))
    if step == len(trace):
        assert decided.all()  # the leaves tile the raster


def test_step_zero_has_no_current_area(stepper):
    stepper.slider.value = 0
    view = stepper.views[0]
    assert not view.current.get_visible() and "no area classified yet" in view.text.value


def test_the_final_and_zbuffer_panels(stepper):
    view = stepper.views[0]
    final, reference = (np.asarray(ax.images[0].get_array()) for ax in view.axes[2:])
    assert np.array_equal(final, polygon_colors(view.result.polygon))
    assert np.array_equal(
        reference, polygon_colors(zbuffer(examples.slides_zbuffer(), 10, 9).polygon)
    )
    assert np.array_equal(final, reference)  # no ties in this scene: Warnock is the z-buffer


def test_a_long_trace_is_cut_and_said_so(monkeypatch):
    monkeypatch.setattr(Stepper, "MAX_STEPS", 10)
    stepper = warnock_stepper(examples.cyclic_overlap(), 24, 24, prune=False)
    assert stepper.slider.max == 10
    assert "showing the first 10" in stepper.views[0].note.value


def test_the_figure_renders_to_png(stepper):
    stepper.slider.value = 15
    buffer = io.BytesIO()
    stepper.views[0].figure.savefig(buffer, format="png")
    assert buffer.getvalue()[:4] == b"\x89PNG"

"""StepModel and Stepper, headless: drive the widgets by setting values and clicking."""

import re

import matplotlib
import pytest

from scanviz import scan_convert
from scanviz.trace import Span, Trace
from scanviz.widgets import LineView, StepModel, Stepper, View, line_stepper, redraw_time

matplotlib.use("Agg")


@pytest.fixture
def trace():
    return scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace


class RecordingView:
    """A view that remembers every step it was told to show."""

    def __init__(self):
        import ipywidgets

        self.widget = ipywidgets.HTML()
        self.shown = []

    def show(self, step):
        self.shown.append(step)


def test_model_steps_and_notifies(trace):
    model = StepModel(trace)
    seen = []
    model.observe(seen.append)
    model.set_step(len(trace))
    model.set_step(len(trace))
    model.set_step(0)
    assert (model.step, len(model), seen) == (0, len(trace), [len(trace), 0])


@pytest.mark.parametrize(
    ("step", "error"), [(-1, ValueError), (99, ValueError), (1.0, TypeError), (True, TypeError)]
)
def test_model_rejects_bad_steps(trace, step, error):
    with pytest.raises(error, match="'step'"):
        StepModel(trace).set_step(step)


def test_model_needs_a_trace():
    with pytest.raises(TypeError, match="'trace'"):
        StepModel([])


def test_slider_drives_every_view(trace):
    views = [RecordingView(), RecordingView()]
    stepper = Stepper(trace, views)
    stepper.slider.value = 3
    assert stepper.model.step == 3
    assert [v.shown for v in views] == [[0, 3], [0, 3]]
    assert stepper.label.value == f"step 3 / {len(trace)}: {trace[2].kind}"


def test_buttons_move_by_one_and_stop_at_the_ends(trace):
    stepper = Stepper(trace, [])
    assert stepper.prev_button.disabled and stepper.label.value.endswith(": start")
    stepper.next_button.click()
    stepper.next_button.click()
    stepper.prev_button.click()
    assert stepper.slider.value == stepper.model.step == 1
    stepper.slider.value = len(trace)
    assert stepper.next_button.disabled
    stepper.next_button.click()
    assert stepper.model.step == len(trace)


def test_moving_the_model_moves_the_slider(trace):
    view = RecordingView()
    stepper = Stepper(trace, [view])
    stepper.model.set_step(2)
    assert stepper.slider.value == 2 and view.shown == [0, 2]


def test_play_is_linked_to_the_slider(trace):
    stepper = Stepper(trace, [], interval=50)
    assert (stepper.play.min, stepper.play.max, stepper.play.interval) == (0, len(trace), 50)
    assert stepper.link.source == (stepper.play, "value")
    assert stepper.link.target == (stepper.slider, "value")


def test_layout_holds_controls_title_and_views(trace):
    view = RecordingView()
    stepper = Stepper(trace, [view], title="a <title>")
    assert "a &lt;title&gt;" in stepper.widget.children[0].value
    assert stepper.widget.children[-1] is view.widget
    assert stepper.play in stepper.widget.children[1].children


def test_views_must_follow_the_protocol(trace):
    assert isinstance(RecordingView(), View)
    with pytest.raises(TypeError, match=r"'views'\[0\]"):
        Stepper(trace, [object()])


def test_too_long_a_trace_is_refused_with_a_message():
    trace = Trace([Span(0, 0, 0, 1, 1)] * (Stepper.MAX_STEPS + 1))
    view = RecordingView()
    stepper = Stepper(trace, [view])
    message = stepper.widget.children[-1].value
    assert "20,001 events" in message and "Recorder(" in message
    assert stepper.slider is None and stepper.play is None and view.shown == []
    with pytest.raises(ValueError, match="refused"):
        redraw_time(stepper)


def test_redraw_time_plays_and_returns_to_the_start(trace):
    view = RecordingView()
    stepper = Stepper(trace, [view])
    stepper.slider.value = 2
    assert redraw_time(stepper, steps=len(trace) + 3) > 0
    assert stepper.slider.value == 2
    assert view.shown[2:5] == [3, 4, 5]


# --- the midpoint line view -------------------------------------------------------------


def table_rows(html):
    """(style, cells) of each body row of a view's HTML table."""
    body = html.split("<tbody>")[1]
    return [
        (style, re.findall(r">([^<]*)</td>", row))
        for style, row in re.findall(r"<tr style='([^']*)'>(.*?)</tr>", body)
    ]


def test_line_table_shows_d_of_each_step():
    stepper = line_stepper(0, 0, 5, 2)
    view = stepper.views[0]
    assert [e.d for e in view.steps] == [1, -3, 3, -1, 5, 1]  # the slides' d, doubled
    for drawn, event in enumerate(view.steps, 1):
        stepper.slider.value = drawn + 1
        rows = table_rows(view.table_html.value)
        assert [int(cells[2]) for _, cells in rows] == [e.d for e in view.steps[:drawn]]
        assert [bool(style) for style, _ in rows] == [False] * (drawn - 1) + [True]
        assert view.title.get_text().endswith(f"d = {event.d}: {event.choice}")


def test_line_image_midpoint_and_candidates_follow_the_step():
    view = LineView(2, 1, -1, 8)  # steep, going left: octant 2
    xs, ys = view._xs, view._ys
    view.show(3)
    image = view.image.get_array()
    assert image[ys[0], xs[0]] == 1 and image[ys[1], xs[1]] == 2 and image.sum() == 3
    second = view.steps[1]
    (mx,), (my,) = view.midpoint.get_data()
    assert (mx, my) == (second.x - 0.5, second.y + 1)
    assert view.candidates.get_data() == ([second.x, second.x - 1], [second.y + 1] * 2)
    view.show(len(view.trace))  # the last pixel decides nothing
    assert not view.midpoint.get_visible() and not view.candidates.get_visible()


def test_line_view_refuses_long_lines():
    with pytest.raises(ValueError, match="at most 512"):
        LineView(0, 0, 1000, 3)
    with pytest.raises(TypeError, match="'x1'"):
        LineView(0, 0, "3", 3)

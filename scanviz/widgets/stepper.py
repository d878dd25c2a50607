"""A stepper: Play, slider and Prev/Next over a `Trace`, driving views that show one step.

The controls only move a `StepModel`; every view's ``show(step)`` then
updates its artists and tables in place (created once, changed with
``set_data`` and friends). Views draw what the trace says; they never run
the algorithm.
"""

from __future__ import annotations

import html
import io
import os
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Protocol, runtime_checkable

import ipywidgets as widgets
import numpy as np

from ..conventions import sample_offset
from ..trace import Trace
from ._common import DisplaysWidget, pixel_image, say
from .export import MAX_FRAMES, gif_data_uri, save_steps
from .model import StepModel


@runtime_checkable
class View(Protocol):
    """What a stepper lays out and drives.

    Attributes
    ----------
    widget : ipywidgets.Widget
        Laid out below the controls.
    """

    widget: widgets.Widget

    def show(self, step: int) -> None:
        """Update in place to the state after the first `step` events."""


def _step_kind(view: View, step: int) -> str:
    """What `view` calls `step` when its steps are not the trace's events one for one (a
    painter's "polygon_painted" stands for the samples it paints), or ""."""
    step_kind = getattr(view, "step_kind", None)
    return step_kind(step) if callable(step_kind) else ""


def narration_of(view: View, step: int) -> str:
    """What `view` says of `step`: its ``narrate(step)`` sentence, or "" if it has none.

    A view may define ``narrate(step) -> str``: one plain sentence saying what
    event `step` did and why (step 0 is the start). The stepper shows the
    first view's sentence under its controls.
    """
    narrate = getattr(view, "narrate", None)
    return narrate(step) if callable(narrate) else ""


def figure_widget(figure):
    """The widget that shows a matplotlib figure.

    Under ipympl (``%matplotlib widget``) the figure's canvas is itself a
    widget and is returned. Otherwise the figure is shown as a PNG in an
    ``ipywidgets.Image`` (which works headless and in any frontend) and
    pyplot forgets the figure: the widget owns it. Call `refresh_figure`
    after changing artists.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> with plt.ioff():
    ...     figure = plt.figure(figsize=(1, 1))
    >>> widget = figure_widget(figure)  # an Image on a non-widget backend
    >>> refresh_figure(figure, widget)
    >>> widget.value[:4] == b"\\x89PNG" or widget is figure.canvas
    True
    """
    import matplotlib.pyplot as plt

    if isinstance(figure.canvas, widgets.DOMWidget):
        return figure.canvas
    plt.close(figure)
    return widgets.Image(format="png")


def refresh_figure(figure, widget) -> None:
    """Redraw `figure` into the `widget` that `figure_widget` made for it."""
    if widget is figure.canvas:
        figure.canvas.draw_idle()
        return
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", pil_kwargs={"compress_level": 1})  # speed over size
    widget.value = buffer.getvalue()


def draw_pixel_grid(axes, extent: tuple[int, int, int, int]) -> None:
    """Thin lines on the pixel borders of `extent` = (x_start, x_end, y_start, y_end).

    One `LineCollection`, so a redraw costs one artist, not a tick per line.
    """
    from matplotlib.collections import LineCollection

    x_start, x_end, y_start, y_end = extent
    lines = [[(x, y_start), (x, y_end)] for x in range(x_start, x_end + 1)]
    lines += [[(x_start, y), (x_end, y)] for y in range(y_start, y_end + 1)]
    axes.add_collection(LineCollection(lines, colors="0.85", linewidths=0.5, zorder=1.5))


DOTS_LIMIT = 64  # pixels a side: beyond it a sample dot would be a speck, so none is drawn


class SampleDots:
    """Each pixel's sample point as a dot over its square: inside filled dark, outside hollow grey.

    Pixel (x, y) is sampled at (x + offset, y + offset): its lower-left
    corner with ``sample="corner"``, its centre with ``sample="center"``. The
    dots make the offset of a fill visible as the consequence of where the
    pixels are sampled.

    Parameters
    ----------
    axes : matplotlib Axes
    shape : (int, int)
        (height, width) of the raster.
    sample : {"corner", "center"}
    origin : (int, int), optional
        The pixel at the raster's lower-left.

    Attributes
    ----------
    inside, outside : matplotlib Line2D
        The dots of the samples inside and outside, updated by `show`.
    offset : float
        Where a pixel's sample lies from its lower-left corner (0 or 0.5);
        set it to move the dots to another sample mode at the next `show`.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> with plt.ioff():
    ...     figure, axes = plt.subplots()
    >>> dots = SampleDots(axes, (2, 3), "center")
    >>> dots.show(np.array([[True, False, False], [False, False, True]]))
    >>> dots.inside.get_data()
    (array([0.5, 2.5]), array([0.5, 1.5]))
    """

    def __init__(self, axes, shape, sample: str = "corner", *, origin=(0, 0)) -> None:
        self.offset = sample_offset(sample)
        self.origin = origin
        size = _dot_size(axes, max(shape))
        (self.inside,) = axes.plot([], [], "o", ms=size, color="#08306b", ls="none", zorder=3)
        (self.outside,) = axes.plot(
            [], [], "o", ms=size, mfc="none", mec="0.45", mew=0.8, ls="none", zorder=3
        )

    def show(self, inside: np.ndarray) -> None:
        """Colour the dots by `inside`, a (height, width) array of bool."""
        inside = np.asarray(inside, bool)
        for dots, where in ((self.inside, inside), (self.outside, ~inside)):
            ys, xs = np.nonzero(where)
            x0, y0 = self.origin
            dots.set_data(xs + x0 + self.offset, ys + y0 + self.offset)

    @staticmethod
    def fit(shape) -> bool:
        """Whether a raster of `shape` is small enough to show its sample dots."""
        return max(shape) <= DOTS_LIMIT


def _dot_size(axes, pixels: int) -> float:
    """A marker size in points: about a fifth of a pixel square as the axes first lays it out."""
    box = axes.get_position()
    inches = min(box.width * axes.figure.get_figwidth(), box.height * axes.figure.get_figheight())
    return float(np.clip(0.22 * 72 * inches / max(pixels, 1), 2.5, 6.0))


def coverage_image(axes, covered: np.ndarray, *, alpha: float | None = None, sample=None):
    """Show a (height, width) coverage array as filled pixel squares on a pixel grid (y up).

    With `sample` ("corner" or "center") each pixel's sample point is drawn
    too, as `SampleDots` (when the raster is at most `DOTS_LIMIT` a side).

    Returns
    -------
    (AxesImage, SampleDots or None)
        Update them with ``image.set_data(covered)`` and ``dots.show(covered)``.
    """
    height, width = covered.shape
    image = pixel_image(axes, covered, cmap="Blues", vmin=0, vmax=1.6, alpha=alpha)
    draw_pixel_grid(axes, (0, width, 0, height))
    dots = None
    if sample is not None and SampleDots.fit(covered.shape):
        dots = SampleDots(axes, covered.shape, sample)
        dots.show(covered)
    return image, dots


SPEEDS = {"slow": 900, "normal": 300, "fast": 80}  # milliseconds between steps when playing


class Stepper(DisplaysWidget):
    """Step through a trace with Play, a slider and Prev/Next; every view shows the step.

    Parameters
    ----------
    trace : Trace
    views : iterable of View
        Each is shown below the controls and told every new step.
    title : str, optional
        A heading above the controls.
    interval : int, optional
        Milliseconds between steps when playing.

    Attributes
    ----------
    model : StepModel
    views : list of View
    play : ipywidgets.Play
        Linked in the frontend to `slider` by `link` (``jslink``), so playing is smooth.
    link : ipywidgets.Link
    slider : ipywidgets.IntSlider
        0..len(trace); moving it shows that step.
    prev_button, next_button : ipywidgets.Button
        One step back or on; disabled at the ends.
    label : ipywidgets.Label
        ``"step k / n: <kind of event k>"`` (``start`` at step 0).
    narration : ipywidgets.HTML
        The step in one plain sentence (the first view's ``narrate(step)``;
        the event's kind in words when no view narrates).
    speed : ipywidgets.Dropdown
        Play's pace: slow, normal or fast (milliseconds between steps).
    widget : ipywidgets.VBox
        Everything; displaying the stepper displays this.

    Notes
    -----
    A trace longer than `MAX_STEPS` is refused: `widget` is then a message
    saying how to record less (a `Recorder` filter) and the controls are
    None, so a huge trace never freezes the kernel.

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> trace = scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace
    >>> stepper = Stepper(trace, [])
    >>> stepper.next_button.click()
    >>> stepper.label.value
    'step 1 / 8: edge_table_built'
    >>> stepper.slider.value = 8
    >>> stepper.model.step, stepper.label.value
    (8, 'step 8 / 8: span')
    >>> stepper.speed.value = SPEEDS["fast"]
    >>> stepper.play.interval
    80
    >>> stepper  # doctest: +SKIP
    """

    MAX_STEPS = 20_000

    def __init__(
        self, trace: Trace, views: Iterable[View] = (), *, title: str = "", interval: int = 300
    ) -> None:
        self.model = StepModel(trace)
        self.views = list(views)
        for index, view in enumerate(self.views):
            if not isinstance(view, View):
                raise TypeError(
                    f"'views'[{index}] must have a widget and a show(step); got {view!r}"
                )
        heading = [widgets.HTML(f"<b>{html.escape(title)}</b>")] if title else []
        steps = len(trace)
        if steps > self.MAX_STEPS:
            self.play = self.slider = self.link = self.label = None
            self.prev_button = self.next_button = self.narration = self.speed = None
            self.widget = widgets.VBox([*heading, widgets.HTML(_too_long_message(steps))])
            return
        self.play = widgets.Play(min=0, max=steps, step=1, interval=interval, description="play")
        self.slider = widgets.IntSlider(min=0, max=steps, value=0, description="step")
        self.link = widgets.jslink((self.play, "value"), (self.slider, "value"))
        self.prev_button = widgets.Button(description="◀ prev", layout={"width": "auto"})
        self.next_button = widgets.Button(description="next ▶", layout={"width": "auto"})
        self.label = widgets.Label()
        self.narration = widgets.HTML(layout={"min_height": "1.6em"})
        self.speed = widgets.Dropdown(
            options=list(SPEEDS.items()),
            value=interval if interval in SPEEDS.values() else SPEEDS["normal"],
            description="speed",
            layout={"width": "11em"},
            style={"description_width": "3.5em"},
        )
        self.speed.observe(lambda change: setattr(self.play, "interval", change["new"]), "value")
        self.prev_button.on_click(lambda _: self._move(-1))
        self.next_button.on_click(lambda _: self._move(+1))
        self.slider.observe(lambda change: self.model.set_step(change["new"]), names="value")
        self.model.observe(self._show)
        controls = widgets.HBox(
            [self.play, self.prev_button, self.slider, self.next_button, self.speed],
            layout={"flex_flow": "row wrap"},
        )
        self.widget = widgets.VBox(
            [*heading, controls, self.label, self.narration, *(view.widget for view in self.views)]
        )
        self._show(0)

    def save(
        self,
        path: str | os.PathLike,
        *,
        steps: Iterable[int] | None = None,
        max_frames: int = MAX_FRAMES,
        milliseconds: int | None = None,
    ) -> list[Path]:
        """Save the steps as pictures: an animated GIF (``*.gif``) or PNG frames in a folder.

        Each frame is what the stepper shows at one step, from the same trace:
        the label, the narration and every view's figure. See
        `scanviz.widgets.export.save_steps` for the parameters.

        Examples
        --------
        >>> import tempfile
        >>> from scanviz import scan_convert
        >>> stepper = Stepper(scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace)
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     [p.name for p in stepper.save(folder, steps=[0, 8])]
        ['step_00000.png', 'step_00008.png']
        """
        return save_steps(self, path, steps=steps, max_frames=max_frames, milliseconds=milliseconds)

    def still(self) -> str:
        """A short looping GIF of the steps, in HTML: the still a page without a kernel shows."""
        if self.slider is None:  # the trace was refused: the message says why
            return super().still()
        return f"<img src='{gif_data_uri(self)}' alt='{html.escape(self.label.value)}'>"

    def _move(self, delta: int) -> None:
        self.slider.value = min(max(self.slider.value + delta, 0), len(self.model))

    def _show(self, step: int) -> None:
        self.slider.value = step  # when the model was moved directly
        kind = self.model.trace[step - 1].kind if step else "start"
        kind = next(filter(None, (_step_kind(view, step) for view in self.views)), kind)
        self.label.value = f"step {step} / {len(self.model)}: {kind}"
        sentence = next(filter(None, (narration_of(view, step) for view in self.views)), "")
        if not sentence:
            sentence = (
                "The start: nothing has happened yet." if not step else kind.replace("_", " ")
            )
        self.narration.value = f"<span style='font-size:13px'>{html.escape(sentence)}</span>"
        self.prev_button.disabled = step == 0
        self.next_button.disabled = step == len(self.model)
        for view in self.views:
            view.show(step)


def first_steps(steps, what: str = "events"):
    """(at most `Stepper.MAX_STEPS` of `steps`, a note saying what was cut or "").

    >>> first_steps(list(range(3)))
    ([0, 1, 2], '')
    >>> len(first_steps(list(range(Stepper.MAX_STEPS + 1)), "areas")[0])
    20000
    """
    if len(steps) <= Stepper.MAX_STEPS:
        return steps, ""
    note = f"{len(steps):,} {what}: showing the first {Stepper.MAX_STEPS:,}."
    return steps[: Stepper.MAX_STEPS], note


def stepper_of(view, title: str, what: str = "events") -> Stepper:
    """A `Stepper` over ``view.steps``, cut to `Stepper.MAX_STEPS` (``view.note`` then says so)."""
    view.steps, note = first_steps(view.steps, what)
    if note:
        say(view.note, note)
    return Stepper(view.steps, [view], title=title)


def _too_long_message(steps: int) -> str:
    return (
        f"<b>This trace has {steps:,} events; a stepper shows at most {Stepper.MAX_STEPS:,}.</b><br>"
        "Record only what you want to step through with a filter, e.g. "
        "<code>Recorder(rows=(10, 20))</code>, <code>Recorder(kinds=['aet_sorted', 'span'])</code> "
        "or <code>Recorder(region=(x0, y0, x1, y1))</code>, and pass it as "
        "<code>trace=</code>."
    )


def redraw_time(stepper: Stepper, steps: int = 50) -> float:
    """Mean seconds the kernel spends per step while playing forward `steps` steps.

    Each step sets the slider, as Play does, so it counts every view's
    ``show`` and the redraw of its figures: the PNG render on a non-widget
    backend; under ipympl, which draws later in the event loop, a draw of
    each view's ``figure`` is forced so that it counts too. The stepper ends
    on the step it started from.

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> stepper = Stepper(scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace)
    >>> redraw_time(stepper, steps=5) < 1.0
    True
    """
    if stepper.slider is None:
        raise ValueError("'stepper' refused its trace (too long); there is nothing to redraw")
    start, cycle = stepper.slider.value, len(stepper.model) + 1
    figures = [getattr(view, "figure", None) for view in stepper.views]
    deferred = [f for f in figures if f is not None and isinstance(f.canvas, widgets.DOMWidget)]
    began = time.perf_counter()
    for offset in range(1, steps + 1):
        stepper.slider.value = (start + offset) % cycle
        for figure in deferred:
            figure.canvas.draw()
    elapsed = time.perf_counter() - began
    stepper.slider.value = start
    return elapsed / max(steps, 1)

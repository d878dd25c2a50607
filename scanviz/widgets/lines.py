"""Step through the midpoint line algorithm: pixels so far, the true line, the midpoint, d."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..raster import midpoint_line
from ..trace import Recorder
from ._common import html_table, new_figure
from .stepper import SampleDots, Stepper, draw_pixel_grid, figure_widget, refresh_figure

TABLE_ROWS = 12  # the table shows the last steps up to the current one


class LineView:
    """The midpoint line from (x0, y0) to (x1, y1), one traced step at a time.

    The view runs `scanviz.midpoint_line` with a `Recorder` and shows the
    trace: the pixels drawn so far (pixel (x, y) is the square
    [x, x+1) x [y, y+1), its sample the dot at (x, y), filled once drawn),
    the true line through the samples, the midpoint tested at the current
    step between its two candidate samples, and a table of the decision
    variable d per step. ``narrate(step)`` says what the step decided and why.

    Parameters
    ----------
    x0, y0, x1, y1 : int
        Endpoints in pixels; the line may be at most `MAX_LENGTH` pixels long
        along its major axis.

    Attributes
    ----------
    trace : Trace
        ``line_setup`` then one ``line_step`` per pixel.
    widget : ipywidgets.HBox
    figure : matplotlib Figure
    image : AxesImage
        1 where a pixel is drawn, 2 at the current pixel.
    midpoint, candidates : Line2D
        The midpoint tested at this step and its two candidate samples
        (hidden when no decision is made).
    table_html : ipywidgets.HTML

    Examples
    --------
    >>> view = LineView(0, 0, 5, 2)
    >>> view.show(2)  # setup, then the first pixel
    >>> view.midpoint.get_data(), view.title.get_text()
    (([1.0], [0.5]), 'pixel (0, 0), d = 1: axial')
    >>> print(view.narrate(2))
    Pixel (0, 0) is drawn; d = 1 > 0: the line passes the midpoint (1, 0.5) on the side of the axial candidate, so the step is axial to (1, 0), and d changes by -4 to -3.
    >>> view.widget  # doctest: +SKIP
    """

    MAX_LENGTH = 512

    def __init__(self, x0: int, y0: int, x1: int, y1: int) -> None:
        try:
            length = max(abs(x1 - x0), abs(y1 - y0))
        except TypeError:
            length = 0  # midpoint_line names the argument
        if length > self.MAX_LENGTH:
            raise ValueError(
                f"the line is {length} pixels long along its major axis; "
                f"a LineView shows at most {self.MAX_LENGTH}"
            )
        recorder = Recorder()
        xs, ys = midpoint_line(x0, y0, x1, y1, trace=recorder)
        self.trace = recorder.trace()
        self.setup = self.trace[0]
        self.steps = self.trace[1:]
        self._origin = (min(x0, x1) - 1, min(y0, y1) - 1)
        self._xs, self._ys = xs - self._origin[0], ys - self._origin[1]
        width, height = abs(x1 - x0) + 3, abs(y1 - y0) + 3
        x_origin, y_origin = self._origin
        extent = (x_origin, x_origin + width, y_origin, y_origin + height)

        # Small enough that the table fits beside it in most notebooks (else it wraps below).
        scale = min(4.5 / width, 5.0 / height, 0.45)
        self.figure, (axes,) = new_figure(1, width=width * scale + 1, height=height * scale + 0.8)
        self.image = axes.imshow(
            np.zeros((height, width)),
            origin="lower",
            cmap="Blues",
            vmin=0,
            vmax=2.5,
            extent=extent,
            interpolation="nearest",
        )
        self.samples = None
        if SampleDots.fit((height, width)):
            self.samples = SampleDots(axes, (height, width), origin=self._origin)
            draw_pixel_grid(axes, extent)
        axes.plot([x0, x1], [y0, y1], color="crimson", linewidth=1.5, zorder=4)
        (self.candidates,) = axes.plot([], [], "o", mfc="none", mec="darkorange", ms=9, zorder=5)
        (self.midpoint,) = axes.plot([], [], "x", color="darkorange", ms=9, mew=2, zorder=6)
        axes.set(xlim=extent[:2], ylim=extent[2:], aspect="equal")
        self.title = axes.set_title("", fontsize=10)
        self.figure.subplots_adjust(left=0.12, right=0.97, bottom=0.08, top=0.92)

        self.table_html = widgets.HTML()
        self._canvas = figure_widget(self.figure)
        table = widgets.VBox(
            [self.table_html], layout={"margin": "0 0 0 12px", "min_width": "0", "flex": "1 1 22em"}
        )
        self.widget = widgets.HBox([self._canvas, table], layout={"flex_flow": "row wrap"})
        self.show(0)

    def narrate(self, step: int) -> str:
        """What event `step` did and why, in one sentence (step 0: the start)."""
        s = self.setup
        if step == 0:
            return f"The start: the line from ({s.x0}, {s.y0}) to ({s.x1}, {s.y1}) is set up next."
        if step == 1:
            (ax, ay), (mx, my) = self._directions()
            return (
                f"Setup: the line is in octant {s.octant}, so {s.major} is the major axis: each "
                f"step goes axially by {_move(ax, ay)} or diagonally by {_move(ax + mx, ay + my)}; "
                f"d = 2 f(midpoint) starts at {s.d_start} and changes by "
                f"{s.d_axial:+d} after an axial step, {s.d_diagonal:+d} after a diagonal one."
            )
        current = self.steps[step - 2]
        drawn = f"Pixel ({current.x}, {current.y}) is drawn"
        if current.choice == "last":
            return f"{drawn}: it is the end point, so no decision is left."
        (ax, ay), (mx, my) = self._directions()
        axial, diagonal = (
            (current.x + ax, current.y + ay),
            (current.x + ax + mx, current.y + ay + my),
        )
        middle = f"({axial[0] + mx / 2:g}, {axial[1] + my / 2:g})"
        if current.d == 0:
            why = (
                f"d = 0: the line passes exactly through the midpoint {middle}, a tie that "
                f"takes the {current.choice} step"
            )
        else:
            sign = "<" if current.d < 0 else ">"
            nearer = "diagonal" if current.d < 0 else "axial"
            why = (
                f"d = {current.d} {sign} 0: the line passes the midpoint {middle} on the side "
                f"of the {nearer} candidate, so the step is {current.choice}"
            )
        following = self.steps[step - 1]
        change = s.d_diagonal if current.choice == "diagonal" else s.d_axial
        to = diagonal if current.choice == "diagonal" else axial
        return (
            f"{drawn}; {why} to ({to[0]}, {to[1]}), and d changes by {change:+d} to {following.d}."
        )

    def show(self, step: int) -> None:
        """Show the state after the first `step` events (artists and table updated in place)."""
        drawn = max(step - 1, 0)  # event 0 is the setup; each later one draws a pixel
        image = np.zeros(self.image.get_array().shape)
        image[self._ys[:drawn], self._xs[:drawn]] = 1
        if drawn:
            image[self._ys[drawn - 1], self._xs[drawn - 1]] = 2
        self.image.set_data(image)
        if self.samples is not None:
            self.samples.show(image > 0)
        current = self.steps[drawn - 1] if drawn else None
        decides = current is not None and current.choice != "last"
        self.midpoint.set_visible(decides)
        self.candidates.set_visible(decides)
        if decides:
            (axial_x, axial_y), (minor_x, minor_y) = self._directions()
            ax, ay = current.x + axial_x, current.y + axial_y
            self.midpoint.set_data([ax + minor_x / 2], [ay + minor_y / 2])
            self.candidates.set_data([ax, ax + minor_x], [ay, ay + minor_y])
        if current is None:
            self.title.set_text("setup" if step else "start")
        else:
            self.title.set_text(
                f"pixel ({current.x}, {current.y}), d = {current.d}: {current.choice}"
            )
        self.table_html.value = self._table(step, drawn)
        refresh_figure(self.figure, self._canvas)

    def _directions(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """The axial step and the minor-axis step, from the setup's major axis and signs."""
        s = self.setup
        if s.major == "x":
            return (s.step_x, 0), (0, s.step_y)
        return (0, s.step_y), (s.step_x, 0)

    def _table(self, step: int, drawn: int) -> str:
        if step == 0:
            return "<b>midpoint line</b>: press next for the setup"
        s = self.setup
        tie = "diagonal" if s.tie_steps else "axial"
        intro = (
            f"<b>midpoint line</b> ({s.x0}, {s.y0}) to ({s.x1}, {s.y1}): octant {s.octant}, "
            f"major axis {s.major}<br>d starts at {s.d_start}; diagonal step if d &lt; 0 "
            f"(d = 0: {tie}); then d += {s.d_diagonal} after a diagonal step, "
            f"d += {s.d_axial} after an axial one<br>"
        )
        first = max(drawn - TABLE_ROWS, 0)
        rows = [
            (i, f"({e.x}, {e.y})", e.d, e.choice)
            for i, e in enumerate(self.steps[first:drawn], first)
        ]
        states = [""] * (len(rows) - 1) + ["current"] if rows else []
        return intro + html_table(("#", "pixel", "d", "choice"), rows, states=states)


def _move(dx: int, dy: int) -> str:
    """A pixel step as '(+1, 0)'."""
    return "(" + ", ".join(f"{v:+d}" if v else "0" for v in (dx, dy)) + ")"


def line_stepper(x0: int, y0: int, x1: int, y1: int) -> Stepper:
    """Step through the midpoint line from (x0, y0) to (x1, y1) in a `LineView`.

    Examples
    --------
    >>> stepper = line_stepper(0, 0, 5, 2)
    >>> len(stepper.model), stepper.slider.max
    (7, 7)
    >>> stepper  # doctest: +SKIP
    """
    view = LineView(x0, y0, x1, y1)
    return Stepper(view.trace, [view], title=f"Midpoint line from ({x0}, {y0}) to ({x1}, {y1})")

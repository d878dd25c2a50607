"""The floating horizon curve by curve (`horizon_stepper`): the visible parts drawn so far,
the current curve, and the upper and lower horizons replayed from the ``horizon_column`` events.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.collections import LineCollection

from ..surfaces import GridSurface, View, floating_horizon
from ..surfaces.horizon import FLAG_PAIRS, HorizonResult
from ..trace import Recorder, Trace
from ._common import WIDEST, html_table, new_figure, pixel_image
from .perimeter import VISIBLE
from .stepper import Stepper, figure_widget, refresh_figure
from .surface_grid import CURRENT, check_surface_view

# --- the floating horizon, curve by curve ---------------------------------------------------


def _horizon_line(values: np.ndarray) -> np.ndarray:
    """Horizon heights for a line plot: infinite (no curve reached the column) as gaps."""
    return np.where(np.isfinite(values), values, np.nan)


class HorizonView:
    """The floating horizon after each curve: parts drawn so far, the current curve, the horizons.

    Parameters
    ----------
    trace : Trace
        Of ``floating_horizon(..., trace=recorder)``: its ``horizon_curve`` and
        ``horizon_column`` events.
    result : HorizonResult
        The same run (its raster size).

    Attributes
    ----------
    widget : ipywidgets.VBox
    drawn : matplotlib LineCollection
        The visible parts of the curves so far.
    current_curve : matplotlib Line2D
        The current curve's whole screen polyline (dotted).
    current_drawn : matplotlib LineCollection
        Its visible parts.
    curves : dict of str to matplotlib Line2D
        "up", "low": the horizons after the curves so far; "up before", "low
        before": those the current curve was tested against.
    text : ipywidgets.HTML
        The current curve and its nine flag combinations.

    `show(step)` shows the state after `step` curves (the stepper steps over
    the ``horizon_curve`` events).
    """

    def __init__(self, trace: Trace, result: HorizonResult) -> None:
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        if not isinstance(result, HorizonResult):
            raise TypeError(f"'result' must be a HorizonResult; got {result!r}")
        self.result = result
        self.height, self.width = result.lines.shape
        self._read_events(trace)
        self.step = 0
        fig, (axes,) = new_figure(1, width=min(WIDEST, 6.4), height=5.0)
        pixel_image(axes, np.ones((self.height, self.width, 3)), offset=-0.5)
        self.drawn = LineCollection([], colors=VISIBLE, lw=1)
        self.current_drawn = LineCollection([], colors=CURRENT, lw=2.2, zorder=4)
        axes.add_collection(self.drawn)
        axes.add_collection(self.current_drawn)
        (self.current_curve,) = axes.plot([], [], color=CURRENT, lw=1, ls=":", zorder=3)
        styles = {
            "up": ("#1f77b4", "-"),
            "low": ("#2ca02c", "-"),
            "up before": ("#1f77b4", "--"),
            "low before": ("#2ca02c", "--"),
        }
        self.curves = {}
        for name, (color, dash) in styles.items():
            (self.curves[name],) = axes.plot(
                [], [], color=color, ls=dash, lw=1, alpha=0.8, label=name
            )
        axes.legend(fontsize=9, loc="upper right")
        axes.set_xlim(-0.5, self.width - 0.5)
        axes.set_ylim(-0.5, self.height - 0.5)
        axes.set_aspect("equal")
        axes.set_title("floating horizon: one curve per step", fontsize=10)
        fig.tight_layout()
        self.figure, self.axes = fig, axes
        self.text = widgets.HTML()
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox([self._canvas, self.text])
        self.show(0)

    def _read_events(self, trace: Trace) -> None:
        self.curve_events, self._columns = [], []
        for event in trace:
            if event.kind == "horizon_curve":
                self.curve_events.append(event)
                self._columns.append([])
            elif event.kind == "horizon_column" and self._columns:
                self._columns[-1].append(event)
        if not self.curve_events:
            raise ValueError(
                "'trace' holds no horizon_curve events: pass the trace of "
                "floating_horizon(..., trace=recorder)"
            )
        up, low = np.full(self.width, -np.inf), np.full(self.width, np.inf)
        self._up, self._low = [up.copy()], [low.copy()]
        for columns in self._columns:  # before a curve: its columns' recorded horizons
            for e in columns:
                up[e.x] = max(up[e.x], e.up, e.y)
                low[e.x] = min(low[e.x], e.low, e.y)
            self._up.append(up.copy())
            self._low.append(low.copy())
        self._segments = [[p for e in columns for p in e.drawn] for columns in self._columns]

    def horizons(self, step: int) -> tuple[np.ndarray, np.ndarray]:
        """(up, low), (W,) float64, after the first `step` curves (-inf / +inf: no curve yet)."""
        return self._up[step], self._low[step]

    def show(self, step: int) -> None:
        """Show the state after the first `step` curves."""
        self.step = int(step)
        segments = [s for parts in self._segments[: self.step] for s in parts]
        self.drawn.set_segments([[(x0, y0), (x1, y1)] for x0, y0, x1, y1 in segments])
        columns = np.arange(self.width)
        up, low = self.horizons(self.step)
        self.curves["up"].set_data(columns, _horizon_line(up))
        self.curves["low"].set_data(columns, _horizon_line(low))
        if self.step == 0:
            for name in ("up before", "low before"):
                self.curves[name].set_data([], [])
            self.current_curve.set_data([], [])
            self.current_drawn.set_segments([])
            self.text.value = "<i>start: up = -inf and low = +inf in every column</i>"
        else:
            before_up, before_low = self.horizons(self.step - 1)
            self.curves["up before"].set_data(columns, _horizon_line(before_up))
            self.curves["low before"].set_data(columns, _horizon_line(before_low))
            event = self.curve_events[self.step - 1]
            self.current_curve.set_data(*np.array(event.points).T)
            parts = self._segments[self.step - 1]
            self.current_drawn.set_segments([[(x0, y0), (x1, y1)] for x0, y0, x1, y1 in parts])
            self.text.value = self._describe(event, self._columns[self.step - 1])
        refresh_figure(self.figure, self._canvas)

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the curve, how many of its columns rise above the
        upper horizon, fall below the lower or are hidden, and the parts drawn."""
        if step == 0:
            return (
                "The start: no curve yet, so the upper horizon is -inf and the lower +inf in "
                "every column."
            )
        event, columns = self.curve_events[step - 1], self._columns[step - 1]
        flags = [e.flag for e in columns]
        plane = "y" if event.family == "x" else "x"
        return (
            f"Curve {event.curve} ({plane} = const, number {event.step + 1} from the front) "
            f"crosses {len(columns)} columns: {flags.count(1)} at or above the upper horizon, "
            f"{flags.count(-1)} at or below the lower and {flags.count(0)} hidden between "
            f"them, so {sum(len(e.drawn) for e in columns)} parts are drawn and the horizons "
            "grow to take it in."
        )

    @staticmethod
    def _describe(event, columns) -> str:
        plane = "y" if event.family == "x" else "x"
        pairs = [(e.previous_flag, e.flag) for e in columns if e.previous_flag is not None]
        counts = [pairs.count(pair) for pair in FLAG_PAIRS]
        names = [f"({p:+d}, {c:+d})".replace("+0", "0") for p, c in FLAG_PAIRS]
        table = html_table(("(Pflag, Cflag)", *names), [("columns", *counts)])
        return (
            f"<b>curve {event.curve}</b> ({plane} = const, number {event.step + 1} from the "
            f"front): {len(columns)} columns in {len(event.pieces)} x-monotone piece(s), "
            f"{sum(len(e.drawn) for e in columns)} visible parts. Where the flags of two "
            "columns differ, the segment between them is cut at the horizon." + table
        )


def horizon_stepper(
    surface: GridSurface, view: View, width: int, height: int, *, family: str = "x"
) -> Stepper:
    """Trace the floating horizon and step through it one curve at a time.

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
        Raster size.
    family : {"x", "y"}
        As `floating_horizon`: the curves y = const ("x") or x = const ("y").

    Returns
    -------
    Stepper
        Over the ``horizon_curve`` events; ``.views[0]`` is the `HorizonView`.

    Examples
    --------
    >>> from scanviz.surfaces import gaussian
    >>> stepper = horizon_stepper(gaussian(5), View((3, 4, 3), (-3, -4, -3)), 32, 32)
    >>> stepper.slider.max
    5
    """
    check_surface_view(surface, view)
    recorder = Recorder(kinds=["horizon_curve", "horizon_column"])
    result = floating_horizon(surface, view, width, height, family=family, trace=recorder)
    trace = recorder.trace()
    horizon_view = HorizonView(trace, result)
    return Stepper(
        trace.of_kind("horizon_curve"), [horizon_view], title="floating horizon: one curve per step"
    )

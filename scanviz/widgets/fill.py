"""The slides' fill variants span by span (`fill_stepper`): the image filled so far and the span's colours.

Drawn from the trace of `scanviz.raster.fill_polygon`: its ``span`` events
(solid and pattern fills) or ``span_values`` events (colour wash and vertex
colours, whose C and dC the AET carries). Each span is a step; the image
shows the samples of the spans emitted so far in the fill's final colours.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Rectangle

from ..geometry import Polygon
from ..raster.fill import ColourWash, Pattern, Solid, VertexColours, fill_polygon
from ..trace import Recorder, Trace
from ._common import draw_outline, fmt, new_figure, note_label, pixel_image
from .scan import ScanNarrator
from .stepper import Stepper, figure_widget, first_steps, refresh_figure
from .zbuffer import narrate_interpolation

UNFILLED = (0.85, 0.85, 0.85)  # samples no span has reached yet
INCREMENTAL_KINDS = ("polygon_setup", "edge_values", "span_values")


class FillView:
    """The filled image after each span, and what the span wrote.

    Parameters
    ----------
    polygon : Polygon or array_like
        The polygon filled (its outline is drawn).
    trace : Trace
        ``span`` or ``span_values`` events of ``fill_polygon(..., trace=True)``.
    image : (H, W, 3) ndarray
        The final image.
    fill : Solid, Pattern, ColourWash or VertexColours
    note : str, optional
    sample : {"corner", "center"}
        The sample mode the fill ran with (what the narration says of samples).

    Attributes
    ----------
    widget : ipywidgets.VBox
    picture : matplotlib AxesImage
        The image so far: the final colours on the spans emitted, `UNFILLED` elsewhere.
    span_patch : matplotlib Rectangle
        Around the current span.
    text : ipywidgets.HTML
        The span: its row and pixels, and for the incremental fills C at its
        start and dC per pixel.

    Examples
    --------
    >>> from scanviz.raster import Solid
    >>> stepper = fill_stepper([(1, 1), (6, 1), (1, 5)], 8, 6, Solid((1.0, 0.5, 0.0)))
    >>> view = stepper.views[0]
    >>> step = 1 + next(i for i, e in enumerate(view.trace) if e.kind == "span")
    >>> print(view.narrate(step))
    Row y = 1: pixels 1 ≤ x < 6 are filled: their samples x = 1 … 5 lie between the crossings 1 (e2) and 6 (e1), where the winding count is +1, so inside; each gets the colour (1, 0.5, 0).
    """

    def __init__(
        self, polygon, trace: Trace, image: np.ndarray, fill, *, note: str = "", sample="corner"
    ) -> None:
        self.trace, self.image, self.fill = trace, image, fill
        self.narrator = ScanNarrator(trace, sample)
        # The incremental fills' spans are their span_values; solid and pattern fills', span events.
        self.kind = "span_values" if isinstance(fill, ColourWash | VertexColours) else "span"
        self.spans = [e for e in trace if e.kind == self.kind]
        height, width = image.shape[:2]
        fig, (ax,) = new_figure(1, width=4.5, height=4.5)
        self.picture = pixel_image(ax, image)
        draw_outline(ax, Polygon(polygon).contours, linewidth=1.2, zorder=2)
        self.span_patch = Rectangle((0, 0), 0, 1, fill=False, ec="black", lw=2, visible=False)
        ax.add_patch(self.span_patch)
        ax.set_xlim(0, width)
        ax.set_ylim(0, height)
        ax.set_title(type(fill).__name__, fontsize=9)
        fig.tight_layout()
        self.figure, self.ax = fig, ax
        self.text, self.note = widgets.HTML(), note_label(note)
        self._canvas = figure_widget(fig)
        self.text.layout = {"min_width": "0", "flex": "1 1 20em", "margin": "0 0 0 12px"}
        row = widgets.HBox([self._canvas, self.text], layout={"flex_flow": "row wrap"})
        self.widget = widgets.VBox([self.note, row])
        self.show(0)

    def narrate(self, step: int) -> str:
        """What event `step` did and why, in one sentence (step 0: the start)."""
        if step == 0:
            return "The start: nothing is filled yet."
        event = self.trace[step - 1]
        if event.kind in INCREMENTAL_KINDS:
            return narrate_interpolation(event, "C")
        sentence = self.narrator.narrate(step)
        if event.kind != "span":
            return sentence
        if isinstance(self.fill, Pattern):
            h, w = self.fill.tile.shape[:2]
            return sentence[:-1] + f"; each takes tile pixel ((x − x0) mod {w}, (y − y0) mod {h})."
        return sentence[:-1] + f"; each gets the colour {fmt(tuple(self.fill.color), 3)}."

    def show(self, step: int) -> None:
        """Show the image after the spans among the first `step` events."""
        done = [e for e in self.trace[: int(step)] if e.kind == self.kind]
        filled = np.zeros(self.image.shape[:2], bool)
        for span in done:
            filled[span.y, span.x_start : span.x_end] = True
        self.picture.set_data(np.where(filled[..., None], self.image, UNFILLED))
        if done:
            span = done[-1]
            self.span_patch.set_bounds(span.x_start, span.y, span.x_end - span.x_start, 1)
            self.span_patch.set_visible(True)
            self.text.value = self._describe(span, len(done))
        else:
            self.span_patch.set_visible(False)
            self.text.value = "<i>no span yet: the edge table is being built</i>"
        refresh_figure(self.figure, self._canvas)

    def _describe(self, span, count: int) -> str:
        head = (
            f"<b>span {count} of {len(self.spans)}</b>: row {span.y}, pixels "
            f"{span.x_start} &le; x &lt; {span.x_end}<br>"
        )
        if span.kind == "span_values":
            start = ", ".join(f"{v:.4f}" for v in span.values)
            step = ", ".join(f"{v:+.4f}" for v in span.dvdx)
            return head + (
                f"crossings x = {span.x_left:.3f} … {span.x_right:.3f}<br>"
                f"C at x = {span.x_start}: ({html.escape(start)})<br>"
                f"dC per pixel: ({html.escape(step)})<br>"
                "<i>each pixel: C &larr; C + dC (one addition per channel)</i>"
            )
        if isinstance(self.fill, Pattern):
            h, w = self.fill.tile.shape[:2]
            return head + f"tile pixel ((x &minus; x0) mod {w}, (y &minus; y0) mod {h}) for each x"
        return head + f"colour {tuple(round(c, 3) for c in self.fill.color)} for each x"


def fill_stepper(polygon, width: int, height: int, fill=None, **options) -> Stepper:
    """Fill `polygon` with tracing and step through its spans.

    Parameters
    ----------
    polygon : Polygon or array_like
    width, height : int
    fill : Solid, Pattern, ColourWash or VertexColours (default Solid())
    **options
        Passed to `scanviz.raster.fill_polygon` (``sample``, ``rule``,
        ``subpixel_bits``, ``background``).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `FillView`.

    Examples
    --------
    >>> from scanviz.raster import ColourWash
    >>> stepper = fill_stepper([(1, 1), (14, 3), (6, 12)], 16, 14, ColourWash())
    >>> stepper.slider.value = stepper.slider.max
    >>> "dC per pixel" in stepper.views[0].text.value
    True
    """
    fill = Solid() if fill is None else fill
    if not isinstance(fill, Solid | Pattern | ColourWash | VertexColours):
        raise TypeError(
            f"'fill' must be a Solid, Pattern, ColourWash or VertexColours; got {type(fill).__name__}"
        )
    incremental = isinstance(fill, ColourWash | VertexColours)
    # The incremental fills step the AET's values row by row; their per-sample depth tests
    # (the z-buffer they run through) would only lengthen the stepping.
    recorder = Recorder(kinds=INCREMENTAL_KINDS) if incremental else Recorder()
    result = fill_polygon(polygon, width, height, fill, trace=recorder, **options)
    trace, note = first_steps(result.trace, "events")
    view = FillView(
        polygon, trace, result.image, fill, note=note, sample=options.get("sample", "corner")
    )
    return Stepper(trace, [view], title="fill variants: one span at a time")

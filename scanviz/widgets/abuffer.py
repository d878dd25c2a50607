"""Inspect the a-buffer at one pixel: its masks, fragment list, packer steps and insertions.

`ABufferInspector` takes a traced a-buffer render (``visibility="abuffer"``,
a `Recorder` filtered to a region) and shows what the core recorded for the
pixel you pick: each fragment's pixel mask as a grid, the fragment list, the
packer's levels (``pixel_packed``) and a `Stepper` over the pixel's
``fragment_inserted`` events with the pixelstruct before and after.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Rectangle

from ..abuffer.masks import DEFAULT_MASK, mask_to_grid, popcount
from ..pipeline import RenderResult
from ..trace import Trace
from ..trace.display import scroll_box
from ._common import WIDEST, fmt, html_table, new_figure, pixel_image, say, status_label, swatch
from .stepper import Stepper, figure_widget, refresh_figure

FRAGMENT_COLUMNS = ("#", "z", "zmax", "area", "bits", "color", "opacity", "object")
PACK_COLUMNS = ("level", "branch", "z", "region bits", "weight Q(i+1)")
PACK_COLUMNS += ("M_A bits", "A", "M_Q bits", "Q", "color x weight", "")
MAX_GRIDS = 6  # mask grids drawn per pixel; the table lists every fragment


def fragment_table(fragments, layout: str) -> str:
    """An HTML table of a fragment list (`FragmentRecord`s), nearest first."""
    return html_table(
        FRAGMENT_COLUMNS,
        [
            (k, f.z, f.zmax, f.area, int(popcount(f.mask)), swatch(f.color), f.opacity, f.object)
            for k, f in enumerate(fragments)
        ],
        raw=(5,),
    )


def _held(kind: str, fragments) -> str:
    """What a pixelstruct holds, in words."""
    if kind == "empty" or not fragments:
        return "nothing"
    if kind == "simple":
        return "one complete opaque fragment"
    return f"a list of {len(fragments)} fragment{'s' * (len(fragments) != 1)}"


class _EventPage:
    """A view showing one event at a time as HTML: ``_page(event)``, and `_START` at step 0."""

    _START = ""

    def __init__(self, trace: Trace) -> None:
        self.trace = trace
        self.widget = widgets.HTML()

    def show(self, step: int) -> None:
        """Show event `step` (at step 0, what stepping will show)."""
        self.widget.value = self._page(self.trace[step - 1]) if step else f"<i>{self._START}</i>"


class FragmentInsertionView(_EventPage):
    """One ``fragment_inserted`` event: the case, the incoming fragment, before and after.

    Attributes
    ----------
    widget : ipywidgets.HTML
        Everything as HTML tables (empty at step 0).

    Examples
    --------
    >>> from scanviz.trace import FragmentInserted, FragmentRecord, Trace
    >>> half = FragmentRecord(0.5, 0.5, 0.5, 0b0011, (1.0, 0.0, 0.0), 1.0, 0)
    >>> event = FragmentInserted(2, 3, 0, 0, half, "partial_empty", "empty", (), "list", (half,))
    >>> print(FragmentInsertionView(Trace([event]), "4x4").narrate(1))
    Fragment 0 of polygon 0 reaches pixel (2, 3) at z = 0.5, partial (2 of 16 sub-samples, area 0.5); the pixel held nothing and, sorted by z, now holds a list of 1 fragment.
    """

    _START = "step forward to insert this pixel's fragments one by one"

    def __init__(self, trace: Trace, layout: str) -> None:
        super().__init__(trace)
        self.layout = layout

    def narrate(self, step: int) -> str:
        """What insertion `step` did and why, in one sentence (step 0: the start)."""
        if step == 0:
            return "The start: the pixel's fragments are inserted one by one, nearest kept first."
        event = self.trace[step - 1]
        fragment = event.fragment
        cols, rows = (int(v) for v in self.layout.split("x"))
        if event.case.startswith("complete"):
            cover = f"complete (all {cols * rows} sub-samples, area 1)"
        else:
            cover = (
                f"partial ({int(popcount(fragment.mask))} of {cols * rows} sub-samples, "
                f"area {fmt(fragment.area, 3)})"
            )
        merged = any(f not in event.before and f != fragment for f in event.after)
        gone = sum(f not in event.after for f in event.before) - merged
        notes = ["merged with a stored fragment of its surface"] * merged
        if gone > 0:
            notes.append(f"{gone} hidden behind a complete opaque fragment discarded")
        done = f" ({'; '.join(notes)})" if notes else ""
        return (
            f"Fragment {event.index} of polygon {event.polygon} reaches pixel ({event.x}, "
            f"{event.y}) at z = {fmt(fragment.z, 4)}, {cover}; the pixel held "
            f"{_held(event.before_kind, event.before)} and, sorted by z, now holds "
            f"{_held(event.after_kind, event.after)}{done}."
        )

    def _page(self, event) -> str:
        """The case, the incoming fragment, and the pixel's list before and after."""
        return (
            f"<b>case {event.case}</b>: fragment {event.index} of polygon {event.polygon}"
            + fragment_table([event.fragment], self.layout)
            + f"<b>before</b> ({event.before_kind})"
            + fragment_table(event.before, self.layout)
            + f"<b>after</b> ({event.after_kind}, merged and discarded)"
            + fragment_table(event.after, self.layout)
        )


def packer_html(event) -> str:
    """The packer's steps of one ``pixel_packed`` event as an HTML table (None: a note)."""
    if event is None:
        return "<i>no pixel_packed event recorded here</i>"
    rows = [
        (
            s.level,
            s.branch or "\u2013",
            s.fragment.z,
            int(popcount(s.region)),
            s.weight,
            int(popcount(s.mask_a)),
            s.a,
            int(popcount(s.mask_q)),
            s.q,
            s.color,
            swatch(s.color),
        )
        for s in event.steps
    ]
    return (
        f"<b>packer</b> ({event.weights} weights): color {swatch(event.color)} "
        f"{', '.join(f'{c:.4g}' for c in event.color)}, alpha {event.alpha:.4g}"
        + scroll_box(html_table(PACK_COLUMNS, rows, raw=(10,)))
    )


class PackerView(_EventPage):
    """One ``pixel_packed`` event: the pixel, its color and alpha, and the packer's steps.

    Attributes
    ----------
    widget : ipywidgets.HTML
    """

    _START = "step forward to pack the pixels one by one"

    def narrate(self, step: int) -> str:
        """What packing `step` produced and how, in one sentence (step 0: the start)."""
        if step == 0:
            return "The start: each step packs one pixel's fragment list into a colour."
        event = self.trace[step - 1]
        levels = len({s.level for s in event.steps})
        return (
            f"Pixel ({event.x}, {event.y}) is packed over {levels} fragment level"
            f"{'s' * (levels != 1)} ({len(event.steps)} regions, {event.weights} weights): each "
            "fragment counts for the sub-samples it covers that nothing in front of it hides, "
            f"giving colour {fmt(tuple(event.color), 3)} and alpha {fmt(event.alpha, 3)}."
        )

    def _page(self, event) -> str:
        """The pixel and its packer's steps."""
        return f"<b>pixel ({event.x}, {event.y})</b> " + packer_html(event)


class ABufferInspector:
    """Pick a pixel of an a-buffer render and see its masks, fragments, packer and insertions.

    Parameters
    ----------
    result : RenderResult
        From ``render(..., visibility="abuffer", trace=Recorder(region=...))``.
    pixel : (int, int), optional
        The first pixel shown (default: the first one the packer recorded).
    mask : {"4x4", "8x4", "8x8"}, optional
        The mask layout of the render (default: read from the trace, else "8x8").

    Attributes
    ----------
    widget : ipywidgets.VBox
    x_box, y_box : ipywidgets.IntText
        The picked pixel; clicking the image sets them.
    fragments : ipywidgets.HTML
        The pixel's fragment list after insertion.
    packer : ipywidgets.HTML
        The packer's steps (``pixel_packed``), deepest level first, and the result.
    grids : list of matplotlib AxesImage
        Mask grids of the first `MAX_GRIDS` fragments (`mask_to_grid`).
    insertions : Stepper or None
        Over the pixel's ``fragment_inserted`` events (None when none were recorded).
    status : ipywidgets.HTML
        Errors and what was not recorded.

    Examples
    --------
    >>> from scanviz import Recorder, render
    >>> from scanviz.scene.builtin import builtin_scene
    >>> result = render(builtin_scene("transparent_cube"), 64, 64, shading="flat",
    ...                 visibility="abuffer", trace=Recorder(region=(30, 30, 33, 33)))
    >>> inspector = ABufferInspector(result, pixel=(31, 31))
    >>> len(result.fragments_at(31, 31)), inspector.insertions.slider.max
    (4, 4)
    """

    def __init__(
        self, result: RenderResult, *, pixel: tuple[int, int] | None = None, mask: str | None = None
    ) -> None:
        if result.abuffer is None or result.trace is None:
            raise ValueError(
                "'result' must come from render(..., visibility='abuffer', trace=Recorder(...))"
            )
        self.result, self.trace = result, result.trace
        self.layout = mask or next(
            (e.layout for e in self.trace if e.kind == "mask_buffer_row"), DEFAULT_MASK
        )
        height, width = result.depth.shape
        packed = self.trace.of_kind("pixel_packed")
        if pixel is None:
            pixel = (packed[0].x, packed[0].y) if len(packed) else (width // 2, height // 2)

        fig, (ax,) = new_figure(1, width=4.0, height=4.0)
        pixel_image(ax, result.image)
        ax.set_title("click a pixel", fontsize=10)
        self.marker = Rectangle((0, 0), 1, 1, fill=False, ec="red", lw=1.5)
        ax.add_patch(self.marker)
        fig.tight_layout()
        fig.canvas.mpl_connect("button_press_event", self._clicked)
        self.figure, self.ax = fig, ax

        cols, rows = (int(v) for v in self.layout.split("x"))
        grid_fig, grid_axes = new_figure(
            MAX_GRIDS, width=WIDEST, height=WIDEST / MAX_GRIDS + 0.4, per_row=MAX_GRIDS
        )
        self.grids = []
        for grid_ax in grid_axes:
            self.grids.append(
                pixel_image(grid_ax, np.zeros((rows, cols)), cmap="Greys", vmin=0, vmax=1)
            )
            grid_ax.set_xticks(range(cols + 1), labels=[])
            grid_ax.set_yticks(range(rows + 1), labels=[])
            grid_ax.tick_params(length=0)
            grid_ax.grid(color="0.6", lw=0.5)
            grid_ax.set_title("#0 z=0.0000", fontsize=9)  # room for the titles `_show_grids` sets
        grid_fig.tight_layout()
        self.grid_figure, self.grid_axes = grid_fig, grid_axes

        self.x_box = widgets.IntText(value=int(pixel[0]), description="x", layout={"width": "9em"})
        self.y_box = widgets.IntText(value=int(pixel[1]), description="y", layout={"width": "9em"})
        for box in (self.x_box, self.y_box):
            box.observe(lambda _: self._pixel_changed(), names="value")
        self.status = status_label()
        self.fragments, self.packer = widgets.HTML(), widgets.HTML()
        self.fragments.layout = {"min_width": "0", "flex": "1 1 30em", "margin": "0 0 0 12px"}
        self.insertions: Stepper | None = None
        self._insertions_box = widgets.VBox()
        self._canvas, self._grid_canvas = figure_widget(fig), figure_widget(grid_fig)
        self.widget = widgets.VBox(
            [
                widgets.HBox([self.x_box, self.y_box, self.status]),
                widgets.HBox([self._canvas, self.fragments], layout={"flex_flow": "row wrap"}),
                self.packer,
                widgets.HTML("<b>pixel masks</b> (sub-sample (i, j) is bit j * cols + i)"),
                self._grid_canvas,
                widgets.HTML("<b>insertions</b> into this pixel's pixelstruct"),
                self._insertions_box,
            ]
        )
        self.pixel = (-1, -1)
        self._pixel_changed()

    def pick(self, x: int, y: int) -> None:
        """Show pixel (x, y) (same as typing it in the boxes or clicking it)."""
        with self.x_box.hold_trait_notifications(), self.y_box.hold_trait_notifications():
            self.x_box.value, self.y_box.value = int(x), int(y)
        self._pixel_changed()

    def _clicked(self, event) -> None:
        if event.inaxes is self.ax and event.xdata is not None:
            self.pick(int(np.floor(event.xdata)), int(np.floor(event.ydata)))

    def _pixel_changed(self) -> None:
        x, y = self.x_box.value, self.y_box.value
        height, width = self.result.depth.shape
        if not (0 <= x < width and 0 <= y < height):
            say(self.status, f"pixel ({x}, {y}) is outside the {width}x{height} raster", error=True)
            return
        if (x, y) == self.pixel:
            return
        self.pixel = (x, y)
        fragments = self.result.fragments_at(x, y)
        inserted = Trace(
            e for e in self.trace if e.kind == "fragment_inserted" and (e.x, e.y) == (x, y)
        )
        packed = [e for e in self.trace if e.kind == "pixel_packed" and (e.x, e.y) == (x, y)]
        say(
            self.status,
            ""
            if inserted or packed or not fragments
            else f"no events recorded at ({x}, {y}): trace a region that holds it",
        )
        self.marker.set_xy((x, y))
        self.fragments.value = (
            f"<b>pixel ({x}, {y})</b>: {len(fragments)} fragments, nearest first"
            + fragment_table(fragments, self.layout)
        )
        self.packer.value = packer_html(packed[-1] if packed else None)
        self._show_grids(fragments)
        self.insertions = (
            Stepper(inserted, [FragmentInsertionView(inserted, self.layout)]) if inserted else None
        )
        self._insertions_box.children = (
            (self.insertions.widget,)
            if self.insertions
            else (widgets.HTML("<i>no fragment_inserted events recorded here</i>"),)
        )
        refresh_figure(self.figure, self._canvas)

    def _show_grids(self, fragments) -> None:
        for k, (image, grid_ax) in enumerate(zip(self.grids, self.grid_axes, strict=True)):
            grid_ax.set_visible(k < len(fragments))
            if k < len(fragments):
                image.set_data(mask_to_grid(fragments[k].mask, self.layout))
                grid_ax.set_title(f"#{k} z={fragments[k].z:.4g}", fontsize=9)
        refresh_figure(self.grid_figure, self._grid_canvas)

"""Small pieces the trace views share: HTML tables, figures, pixel pickers, swatches."""

from __future__ import annotations

import html
import os
from collections.abc import Sequence

import ipywidgets as widgets
import numpy as np

ROW_STYLES = {
    "": "",
    "done": "",
    "current": "background:#ffe9a8;font-weight:bold",
    "pending": "color:#999",
}


STILLS = "SCANVIZ_STILLS"
"""Set (to 1) where nobody will drive the widgets, as the docs build does: a display then also
carries a still of the widget (HTML), which a page shows in its place."""


class DisplaysWidget:
    """A mixin: displaying the object in a notebook displays its `widget`.

    With ``SCANVIZ_STILLS=1`` in the environment the display also carries
    `still()`, an HTML picture of the widget, for pages without a kernel; a
    live notebook shows the widget either way.
    """

    widget: widgets.Widget

    def _ipython_display_(self) -> None:
        from IPython.display import display

        if not os.environ.get(STILLS):
            display(self.widget)
            return
        bundle = self.widget._repr_mimebundle_()
        display({**bundle, "text/html": self.still()}, raw=True)

    def still(self) -> str:
        """An HTML still of the widget: its text, tables and pictures, without the controls."""
        from .export import static_html

        return static_html(self.widget)


def fmt(value: object, digits: int = 4) -> str:
    """A table cell: floats to `digits` significant digits, tuples joined, None as a dash."""
    if value is None:
        return "\u2013"
    if isinstance(value, bool | np.bool_):
        return "pass" if value else "fail"
    if isinstance(value, float | np.floating):
        return f"{float(value):.{digits}g}"
    if isinstance(value, tuple | list):
        return "(" + ", ".join(fmt(v, digits) for v in value) + ")"
    return str(value)


def html_table(
    columns: Sequence[str],
    rows: Sequence[Sequence[object]],
    *,
    states: Sequence[str] | None = None,
    raw: Sequence[int] = (),
) -> str:
    """An HTML table; `states[i]` styles row i ("current", "pending", "done" or "").

    Cells are formatted with `fmt` and escaped, except the columns in `raw`
    (already HTML, e.g. a color swatch).
    """
    head = "".join(f"<th style='padding:0 6px'>{html.escape(c)}</th>" for c in columns)
    body = []
    for i, row in enumerate(rows):
        style = ROW_STYLES[states[i]] if states is not None else ""
        cells = "".join(
            f"<td style='padding:0 6px;text-align:right'>"
            f"{cell if k in raw else html.escape(fmt(cell), quote=False)}"
            "</td>"
            for k, cell in enumerate(row)
        )
        body.append(f"<tr style='{style}'>{cells}</tr>")
    return (
        "<table style='font-family:monospace;font-size:12px;border-collapse:collapse'>"
        f"<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"
    )


def listed(items, empty: str = "") -> str:
    """Items in words: 'a', 'a and b', 'a, b and c' (`empty` for none).

    >>> listed([1, 2, 3]), listed(["x"]), listed([], "nothing")
    ('1, 2 and 3', 'x', 'nothing')
    """
    words = [str(item) for item in items]
    if len(words) < 2:
        return words[0] if words else empty
    return ", ".join(words[:-1]) + " and " + words[-1]


def swatch(color: Sequence[float]) -> str:
    """A small colored square for an RGB color in [0, 1] (HTML)."""
    r, g, b = (int(round(255 * min(max(float(c), 0.0), 1.0))) for c in color[:3])
    return (
        f"<span style='display:inline-block;width:14px;height:14px;"
        f"background:rgb({r},{g},{b});border:1px solid #444'></span>"
    )


# The widest figure a notebook shows whole: JupyterLab in a 1280 px window with the
# file browser open leaves an output area of about 880 px (figures are drawn at 100 dpi).
WIDEST = 8.4  # inches
PER_ROW = 3  # panels side by side; more wrap into rows


def new_figure(
    ncols: int, *, width: float = 8.0, height: float = 3.2, per_row: int = PER_ROW, **subplot_kw
):
    """(figure, axes) made without displaying it (pyplot, so ipympl gives its canvas widget).

    The figure is at most `WIDEST` wide; more than `per_row` panels wrap into
    rows of `height` each (unless ``gridspec_kw`` sets ``width_ratios``). `axes` is the list of the `ncols` panels in reading
    order. Under ipympl the canvas has no "Figure N" header, no toolbar over
    the labels and no resize handle.

    >>> fig, axes = new_figure(5, width=20, height=2)
    >>> len(axes), fig.get_size_inches().tolist()
    (5, [8.4, 4.0])
    """
    import math

    import matplotlib.pyplot as plt

    if "width_ratios" in subplot_kw.get("gridspec_kw", {}):
        per_row = ncols  # panels of set widths stay in one row
    per_row = max(1, per_row)
    rows, columns = math.ceil(ncols / per_row), min(ncols, per_row)
    with plt.ioff():
        fig, grid = plt.subplots(
            rows, columns, figsize=(min(width, WIDEST), height * rows), squeeze=False, **subplot_kw
        )
    axes = list(grid.ravel())
    for spare in axes[ncols:]:
        spare.remove()
    quiet_canvas(fig)
    return fig, axes[:ncols]


def pixel_image(axes, image, *, offset: float = 0.0, **style):
    """Show an (H, W) or (H, W, 3) `image` as pixel squares, row 0 at the bottom (an AxesImage).

    Pixel (x, y) is the unit square from (x + offset, y + offset): 0 lays it
    on the pixel grid, -0.5 centres it on its sample. `style` goes to ``imshow``.
    """
    height, width = np.shape(image)[:2]
    extent = (offset, width + offset, offset, height + offset)
    return axes.imshow(image, origin="lower", extent=extent, interpolation="nearest", **style)


def draw_outline(axes, contours, *, arrows: bool = False, **style) -> None:
    """Each contour, an (N, 2) array, as a closed crimson line; `arrows`: each edge's direction.

    `style` goes to ``plot`` (by default a 1.5 pt line at zorder 4).
    """
    style = {"color": "crimson", "linewidth": 1.5, "zorder": 4} | style
    for contour in contours:
        closed = np.vstack([contour, contour[:1]])
        axes.plot(closed[:, 0], closed[:, 1], **style)
        if not arrows:
            continue
        for start, end in zip(closed[:-1], closed[1:], strict=True):
            middle, half = (start + end) / 2, (end - start) * 0.04
            axes.annotate(
                "",
                xy=middle + half,
                xytext=middle - half,
                zorder=4,
                arrowprops={"arrowstyle": "-|>", "color": "crimson"},
            )


def quiet_canvas(figure) -> None:
    """No header, toolbar or resize handle on an ipympl canvas (nothing on other backends)."""
    canvas = figure.canvas
    if isinstance(canvas, widgets.DOMWidget):
        canvas.header_visible = False
        canvas.toolbar_visible = False
        canvas.footer_visible = False
        canvas.resizable = False


def parse_pixel(text: str) -> tuple[int, int]:
    """'x, y' (or 'x y', '(x, y)') as a pair of ints; ValueError naming the rule otherwise."""
    parts = text.replace("(", " ").replace(")", " ").replace(",", " ").split()
    try:
        x, y = (int(p) for p in parts)
    except ValueError:
        raise ValueError(f"pixel must be 'x, y' with two integers; got {text!r}") from None
    return x, y


def status_label() -> widgets.HTML:
    """An HTML line for messages and errors (empty until something is said)."""
    return widgets.HTML(value="")


def say(label: widgets.HTML, message: str, *, error: bool = False) -> None:
    """Show `message` in `label` (red when it is an error)."""
    color = "#b00020" if error else "#555"
    label.value = f"<span style='color:{color}'>{html.escape(message)}</span>" if message else ""


def note_label(note: str) -> widgets.HTML:
    """A status label saying `note` (e.g. how the trace was filtered; empty: nothing shown)."""
    label = status_label()
    say(label, note)
    return label


def pixel_region(points: np.ndarray, width: int, height: int, margin: int) -> tuple[int, ...]:
    """(x_start, x_end, y_start, y_end): the points' pixels and `margin` more each side, on the raster.

    `points` is an (N, 2) array of (x, y); a region off the raster is the whole raster.
    """
    low = np.floor(points.min(axis=0)).astype(int) - margin
    high = np.ceil(points.max(axis=0)).astype(int) + margin
    x_start, y_start = max(int(low[0]), 0), max(int(low[1]), 0)
    x_end, y_end = min(int(high[0]), width), min(int(high[1]), height)
    if x_end <= x_start or y_end <= y_start:  # off the raster: show all of it
        return 0, width, 0, height
    return x_start, x_end, y_start, y_end

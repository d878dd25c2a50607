"""Small pieces the trace views share: HTML tables, figures, pixel pickers, swatches."""

from __future__ import annotations

import html
from collections.abc import Sequence

import ipywidgets as widgets
import numpy as np

ROW_STYLES = {
    "": "",
    "done": "",
    "current": "background:#ffe9a8;font-weight:bold",
    "pending": "color:#999",
}


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


def swatch(color: Sequence[float]) -> str:
    """A small colored square for an RGB color in [0, 1] (HTML)."""
    r, g, b = (int(round(255 * min(max(float(c), 0.0), 1.0))) for c in color[:3])
    return (
        f"<span style='display:inline-block;width:14px;height:14px;"
        f"background:rgb({r},{g},{b});border:1px solid #444'></span>"
    )


WIDEST = 9.5  # inches: the widest figure a notebook shows whole (the canvas beside its toolbar)


def new_figure(ncols: int, *, width: float = 9.0, height: float = 3.2, **subplot_kw):
    """(figure, axes) made without displaying it (pyplot, so ipympl gives its canvas widget)."""
    import matplotlib.pyplot as plt

    with plt.ioff():
        fig, axes = plt.subplots(1, ncols, figsize=(width, height), squeeze=False, **subplot_kw)
    fig.canvas.header_visible = False
    return fig, list(axes[0])


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

"""A student's trace beside the reference's, opened at the first divergence (the check cell)."""

from __future__ import annotations

import html

import ipywidgets as widgets

from ..exercises.compare import MISSING, aligned, first_difference
from ..exercises.core import Outcome
from ..exercises.display import comparison_html, event_fields, event_title
from ..exercises.verdict import Verdict
from ._common import DisplaysWidget

WINDOW = 4  # events shown before and after the current one


def _rows(yours: list, reference: list, rtol: float) -> tuple[list, list, list[int]]:
    """Both traces aligned row by row (gaps as MISSING) and the rows that differ."""
    pairs = list(aligned(yours, reference))
    diverging = [i for i, (_, a, b) in enumerate(pairs) if first_difference(a, b, rtol) is not None]
    return [a for _, a, _ in pairs], [b for _, _, b in pairs], diverging


def _event_row(index: int, event: object, current: bool, differs: bool) -> str:
    """One event on a line: its number, kind and place, then its fields as a student reads them."""
    text = "" if event is MISSING else event_fields(event)
    style = "background:#ffe9a8;" if current else ""
    style += "border-left:4px solid #c62828;" if differs else "border-left:4px solid transparent;"
    head = f"<b>{index + 1}. {html.escape(event_title(event))}</b>"
    return (
        f"<div style='{style}padding:2px 6px;font-size:12px'>"
        f"{head}<br><span style='font-family:monospace'>{html.escape(text)}</span></div>"
    )


class TraceComparison(DisplaysWidget):
    """Your events and the reference's side by side, starting at the first difference.

    Parameters
    ----------
    yours, reference : Outcome
        The runs of one case (`scanviz.exercises.core.run_case`).
    verdict : Verdict
        Their comparison (`scanviz.exercises.core.judge`).

    Attributes
    ----------
    slider : ipywidgets.IntSlider
        The row shown (0-based; rows pair your events with the reference's, a gap
        where one side has no such event); starts at the first diverging row.
    first_button, next_button, prev_button, next_difference_button : ipywidgets.Button
    yours_pane, reference_pane : ipywidgets.HTML
    widget : ipywidgets.VBox
    """

    def __init__(self, yours: Outcome, reference: Outcome, verdict: Verdict, rtol: float = 0.0):
        self.verdict = verdict
        self.yours, self.reference, self.diverging = _rows(yours.trace, reference.trace, rtol)
        count = max(len(self.reference), 1)
        start = self.diverging[0] if self.diverging else 0
        self.slider = widgets.IntSlider(min=0, max=count - 1, value=start, description="row")
        self.prev_button = widgets.Button(description="◀ prev", layout={"width": "auto"})
        self.next_button = widgets.Button(description="next ▶", layout={"width": "auto"})
        self.first_button = widgets.Button(description="first difference", layout={"width": "auto"})
        self.next_difference_button = widgets.Button(
            description="next difference", layout={"width": "auto"}
        )
        self.prev_button.on_click(lambda _: self._go(self.slider.value - 1))
        self.next_button.on_click(lambda _: self._go(self.slider.value + 1))
        self.first_button.on_click(lambda _: self._go(start))
        self.next_difference_button.on_click(lambda _: self._next_difference())
        self.first_button.disabled = self.next_difference_button.disabled = not self.diverging
        self.yours_pane = widgets.HTML(layout={"width": "50%"})
        self.reference_pane = widgets.HTML(layout={"width": "50%"})
        self.slider.observe(lambda change: self._show(change["new"]), names="value")
        heading = widgets.HTML(
            f"<b>case {html.escape(verdict.case.label)!s}</b>: "
            + (
                html.escape(f"{len(self.diverging)} of {count} rows differ")
                if self.diverging
                else "every event agrees"
            )
            + "; left: yours, right: the reference"
        )
        parts = [
            heading,
            widgets.HBox(
                [
                    self.prev_button,
                    self.slider,
                    self.next_button,
                    self.first_button,
                    self.next_difference_button,
                ]
            ),
            widgets.HBox([self.yours_pane, self.reference_pane]),
        ]
        self.rtol = rtol
        # the current row's two events, field by field; min_width 0 lets its table scroll
        self.detail_pane = widgets.HTML(layout={"min_width": "0", "width": "100%"})
        parts.append(self.detail_pane)
        self.widget = widgets.VBox(parts, layout={"min_width": "0", "width": "100%"})
        self._show(start)

    def _go(self, index: int) -> None:
        self.slider.value = min(max(index, self.slider.min), self.slider.max)

    def _next_difference(self) -> None:
        later = [i for i in self.diverging if i > self.slider.value]
        if later:
            self._go(later[0])

    def _pane(self, events: list, title: str, current: int) -> str:
        low, high = max(current - WINDOW, 0), min(current + WINDOW + 1, len(events))
        rows = [
            _event_row(i, events[i], i == current, i in self.diverging) for i in range(low, high)
        ]
        count = sum(e is not MISSING for e in events)
        return f"<div><b>{title}</b> ({count} events)</div>" + "".join(rows)

    def _show(self, index: int) -> None:
        self.yours_pane.value = self._pane(self.yours, "yours", index)
        self.reference_pane.value = self._pane(self.reference, "reference", index)
        if index < len(self.reference):
            mine, theirs = self.yours[index], self.reference[index]
            title = event_title(theirs if mine is MISSING else mine)
            self.detail_pane.value = (  # width 0, min-width 100%: the table may not widen the pane
                f"<div style='width:0;min-width:100%'><b>row {index + 1}: {html.escape(title)}</b>"
                + comparison_html(mine, theirs, self.rtol)
                + "</div>"
            )
        self.prev_button.disabled = index <= self.slider.min
        self.next_button.disabled = index >= self.slider.max

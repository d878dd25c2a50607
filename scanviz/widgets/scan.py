"""Step through a traced scan conversion: pixel grid, scanline, spans, edge table and AET.

The view reads the events of `scanviz.raster.scanline` (``edge_table_built``,
``edges_retired``, ``edges_activated``, ``aet_sorted``, ``span``) and shows
the state after each step; `scan_conversion_stepper` runs the traced scan
conversion and wraps the view in a `Stepper`.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..conventions import SAMPLE_MODES, check_choice, check_raster_size, sample_offset
from ..geometry import Polygon
from ..raster import scan_convert
from ..trace import AetSorted, Trace
from ..trace.display import scroll_box
from ..trace.table import format_number
from ._common import WIDEST, draw_outline, html_table, listed, new_figure, pixel_image
from .stepper import SampleDots, Stepper, draw_pixel_grid, figure_widget, refresh_figure

DETAIL_LIMIT = 128 * 128  # larger rasters get no per-pixel grid lines


def aet_changes(previous: AetSorted | None, current: AetSorted) -> dict[int, str]:
    """What changed in the active edge table from `previous` to `current`, by edge id.

    "entering" for edges new in the table, "moved" for edges the sort put in
    another order relative to the others, "x changed" for the rest whose x
    changed. Unchanged edges are left out.

    Examples
    --------
    >>> from scanviz.trace import AetEntry
    >>> def aet(*xs):
    ...     entries = [AetEntry(e, x, None, 0.0, None, 9.0, 1) for e, x in xs]
    ...     return AetSorted(0, 0, tuple(entries), 0)
    >>> aet_changes(aet((0, 1.0), (1, 5.0)), aet((1, 0.5), (0, 1.0), (2, 7.0)))
    {1: 'moved', 0: 'moved', 2: 'entering'}
    >>> aet_changes(aet((0, 1.0), (1, 5.0)), aet((0, 1.0), (1, 4.0)))
    {1: 'x changed'}
    """
    before = {} if previous is None else {e.edge: e for e in previous.entries}
    stayed = [e.edge for e in current.entries if e.edge in before]
    old_order = [e.edge for e in previous.entries if e.edge in stayed] if previous else []
    changes = {}
    for entry in current.entries:
        old = before.get(entry.edge)
        if old is None:
            changes[entry.edge] = "entering"
        elif old_order[stayed.index(entry.edge)] != entry.edge:
            changes[entry.edge] = "moved"
        elif (old.x_exact, old.x) != (entry.x_exact, entry.x):
            changes[entry.edge] = "x changed"
    return changes


def _edge_name(record) -> str:
    return f"e{record.edge} ({record.x0:g},{record.y0:g})→({record.x1:g},{record.y1:g})"


class ScanNarrator:
    """One plain sentence per scan-conversion event, read from the trace: what happened and why.

    Parameters
    ----------
    trace : Trace
        Events of `scanviz.raster.scanline` (a filtered trace is fine).
    sample : {"corner", "center"}
        The sample mode of the scan conversion (where a row's samples lie).

    Attributes
    ----------
    row_at : list of (int, int) or None
        For every step, the (polygon, row) reached.
    table_at, aet_at : list of int
        For every step, the index of the last ``edge_table_built`` and
        ``aet_sorted`` event so far (-1 if none).

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> trace = scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace
    >>> narrator = ScanNarrator(trace)
    >>> narrator.narrate(2)
    'Row y = 0: e1 (4,0)→(4,3) and e2 (0,0)→(4,3) enter the AET: row 0 is the first whose samples (y = 0) lie at or above their ymin 0.'
    """

    def __init__(self, trace: Trace, sample: str = "corner") -> None:
        self.trace = trace
        self.offset = sample_offset(check_choice("sample", sample, SAMPLE_MODES))
        self.row_at: list[tuple[int, int] | None] = [None]
        self.table_at, self.aet_at = [-1], [-1]
        self._previous_aet: dict[int, int] = {}  # aet_sorted index -> the one before, same polygon
        last_aet_of: dict[int, int] = {}
        for index, event in enumerate(trace):
            y = getattr(event, "y", None)
            self.row_at.append(self.row_at[-1] if y is None else (event.polygon, y))
            self.table_at.append(index if event.kind == "edge_table_built" else self.table_at[-1])
            self.aet_at.append(index if event.kind == "aet_sorted" else self.aet_at[-1])
            if event.kind == "aet_sorted":
                self._previous_aet[index] = last_aet_of.get(event.polygon, -1)
                last_aet_of[event.polygon] = index

    def previous_aet(self, index: int) -> AetSorted | None:
        """The ``aet_sorted`` event of the same polygon before the one at `index` (None if first)."""
        previous = self._previous_aet[index]
        return self.trace[previous] if previous >= 0 else None

    def edge_records(self, step: int) -> dict:
        """The edge table's records by edge id, as the last table up to `step` holds them."""
        index = self.table_at[step]
        return {} if index < 0 else {e.edge: e for e in self.trace[index].edges}

    def narrate(self, step: int) -> str:
        """What event `step` did and why, in one sentence (step 0: the start)."""
        if step == 0:
            return "The start: nothing is scanned yet; the first step builds the edge table."
        event = self.trace[step - 1]
        say = getattr(self, f"_{event.kind}", None)
        return say(step, event) if say else event.kind.replace("_", " ") + "."

    def _sample_y(self, y: int) -> str:
        return f"{y + self.offset:g}"

    def _edge_table_built(self, step, event) -> str:
        buckets: dict[int, list[str]] = {}
        for record in sorted(event.edges, key=lambda e: (e.bucket, e.edge)):
            if not record.kept_for_topology:
                buckets.setdefault(record.bucket, []).append(f"e{record.edge}")
        placed = "; ".join(f"row {row} gets {listed(names)}" for row, names in buckets.items())
        kept = [
            f"{_edge_name(e)} is "
            + ("horizontal" if e.horizontal else "between two sample rows")
            + ", kept only for topology"
            for e in event.edges
            if e.kept_for_topology
        ]
        return (
            f"Polygon {event.polygon}'s edge table puts each edge in the bucket of the first "
            f"sample row it crosses: {placed or 'no edge crosses a sample row'}"
            + "".join(f"; {note}" for note in kept)
            + "."
        )

    def _moving_edges(self, step, event, verbs: tuple[str, str]):
        """The event's edges in the edge table, their names, and the verb (one, many) and pronoun."""
        records = self.edge_records(step)
        found = [records[e] for e in event.edges if e in records]
        names = listed([_edge_name(e) for e in found] or [f"e{e}" for e in event.edges])
        verb, their = (verbs[0], "its") if len(event.edges) == 1 else (verbs[1], "their")
        return found, names, verb, their

    def _edges_activated(self, step, event) -> str:
        entering, names, verb, their = self._moving_edges(step, event, ("enters", "enter"))
        if not entering:  # the trace was filtered: no edge table to read ymin from
            return f"Row y = {event.y}: {names} {verb} the AET: this row is {their} bucket."
        ymins = listed(sorted({f"{e.ymin:g}" for e in entering}, key=float))
        if all(e.bucket < event.y for e in entering):
            return (
                f"Row y = {event.y}: {names} {verb} the AET on the raster's first scanned row: "
                f"{their} ymin {ymins} is below it."
            )
        return (
            f"Row y = {event.y}: {names} {verb} the AET: row {event.y} is the first whose "
            f"samples (y = {self._sample_y(event.y)}) lie at or above {their} ymin {ymins}."
        )

    def _edges_retired(self, step, event) -> str:
        leaving, names, verb, their = self._moving_edges(step, event, ("leaves", "leave"))
        if not leaving:  # the trace was filtered: no edge table to read ymax from
            return f"Row y = {event.y}: {names} {verb} the AET: the row reached {their} ymax."
        ymaxes = listed(sorted({f"{e.ymax:g}" for e in leaving}, key=float))
        return (
            f"Row y = {event.y}: {names} {verb} the AET because the row's samples "
            f"(y = {self._sample_y(event.y)}) reached {their} ymax {ymaxes}: an edge is active "
            "only while ymin ≤ y < ymax."
        )

    def _aet_sorted(self, step, event) -> str:
        if not event.entries:
            return f"Row y = {event.y}: the AET is empty, so the row has nothing to fill."
        previous = self.previous_aet(step - 1)
        if previous is not None:
            changes = aet_changes(previous, event)
            entered = [f"e{e}" for e, change in changes.items() if change == "entering"]
        else:  # the first row recorded: only an edges_activated of this row says who entered
            activated = self.trace[step - 2] if step >= 2 else None
            same_row = activated is not None and activated.kind == "edges_activated"
            same_row = same_row and (activated.polygon, activated.y) == (event.polygon, event.y)
            entered = [f"e{e}" for e in activated.edges] if same_row else []
        stayed = previous is not None and len(event.entries) > len(entered)
        clauses = ["the edges already active moved their x by dx/dy"] if stayed else []
        if entered:
            clauses.append(f"{listed(entered)} entered")
        order = ", ".join(f"e{e.edge} at {format_number(e.x, e.x_exact)}" for e in event.entries)
        swaps = (
            "already in order, no swap"
            if event.swaps == 0
            else f"{event.swaps} swap{'s' * (event.swaps != 1)} in the sort"
        )
        return f"Row y = {event.y}: {', and '.join(clauses)}; sorted by x the AET is {order} ({swaps})."

    def _span(self, step, event) -> str:
        first, last = event.x_start + self.offset, event.x_end - 1 + self.offset
        if event.x_end - event.x_start == 1:
            filled = f"pixel x = {event.x_start} is filled: its sample x = {first:g} lies"
        else:
            filled = (
                f"pixels {event.x_start} ≤ x < {event.x_end} are filled: their samples "
                f"x = {first:g} … {last:g} lie"
            )
        index = self.aet_at[step]
        entries = self.trace[index].entries if index >= 0 else ()
        pair = next(
            (
                (a, b)
                for a, b in zip(entries, entries[1:], strict=False)
                if a.x <= first and b.x > last
            ),
            None,
        )
        between = ""
        if pair is not None:
            a, b = pair
            between = (
                f" between the crossings {format_number(a.x, a.x_exact)} (e{a.edge}) and "
                f"{format_number(b.x, b.x_exact)} (e{b.edge}),"
            )
        return (
            f"Row y = {event.y}: {filled}{between} where the winding count is "
            f"{event.winding:+d}, so inside."
        )


class ScanConversionView:
    """A scan conversion trace, one step at a time.

    Left: the pixel grid with the image so far (the spans emitted up to the
    step), sample points (filled dark when covered, hollow grey when not),
    the polygon, the active edges, the current scanline and the span just
    emitted. Right: the final image. Below them, the edge table and the
    active edge table of the current row; table rows that changed at this
    step are highlighted: edges entering or retiring, and on ``aet_sorted``
    the entries that entered, moved in the sort or whose x changed.
    ``narrate(step)`` says in one sentence what the step did and why.

    Parameters
    ----------
    polygon : Polygon or array_like
        The polygon that was scan-converted (its outline is drawn).
    width, height : int
        The raster size it was scan-converted at.
    trace : Trace
        From ``scan_convert(..., trace=True)`` or a filtering `Recorder`.
    sample : {"corner", "center"}
        The sample mode used (where the dots and the scanline go).

    Attributes
    ----------
    widget : ipywidgets.VBox
    figure : matplotlib Figure
    image : AxesImage
        Coverage counts so far, ``trace.image_at(step, width, height)``.
    samples : SampleDots or None
        The sample points, covered or not (None above `DOTS_LIMIT` pixels a side).
    scanline : Line2D
        Horizontal line at the current row's sample y; hidden before any row.
    et_html, aet_html : ipywidgets.HTML
    highlights : dict of int to str
        The AET entries highlighted at this step, edge id to "entering",
        "retiring", "moved" or "x changed".

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> triangle = [(0, 0), (4, 0), (4, 3)]
    >>> view = ScanConversionView(triangle, 5, 3, scan_convert(triangle, 5, 3, trace=True).trace)
    >>> view.show(3)
    >>> view.scanline.get_ydata(), view.highlights
    ([0.0, 0.0], {2: 'entering', 1: 'entering'})
    >>> view.narrate(4)
    'Row y = 0: pixels 0 ≤ x < 4 are filled: their samples x = 0 … 3 lie between the crossings 0 (e2) and 4 (e1), where the winding count is +1, so inside.'
    >>> view.widget  # doctest: +SKIP
    """

    def __init__(
        self, polygon: object, width: int, height: int, trace: Trace, *, sample: str = "corner"
    ) -> None:
        from matplotlib.collections import LineCollection
        from matplotlib.patches import Rectangle

        self.polygon = Polygon(polygon)
        self.width, self.height = check_raster_size(width, height)
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        self.trace = trace
        self.narrator = ScanNarrator(trace, sample)
        self.offset = self.narrator.offset
        self.highlights: dict[int, str] = {}

        final = trace.image_at(len(trace), self.width, self.height)
        # Two square panels side by side, as large as a notebook's width allows.
        panel = min(0.4 * max(self.width, self.height) + 1, (WIDEST - 0.4) / 2)
        self.figure, (axes, final_axes) = new_figure(2, width=2 * panel + 0.4, height=panel + 0.4)
        shown = {"cmap": "Blues", "vmin": 0, "vmax": 1.6 * max(final.max(), 1)}
        self.image = pixel_image(axes, np.zeros_like(final), **shown)
        pixel_image(final_axes, final, **shown)
        if self.width * self.height <= DETAIL_LIMIT:
            for ax in (axes, final_axes):
                draw_pixel_grid(ax, (0, self.width, 0, self.height))
        for ax in (axes, final_axes):
            draw_outline(ax, self.polygon.contours, linewidth=1.2)
            ax.set(xlim=(0, self.width), ylim=(0, self.height), aspect="equal")
        final_axes.set_title("final image")
        self.active_edges = LineCollection([], colors="darkorange", linewidths=3, zorder=5)
        axes.add_collection(self.active_edges)
        self.scanline = axes.axhline(0, color="orange", linewidth=2, zorder=6, visible=False)
        self.span = Rectangle((0, 0), 0, 1, fill=False, edgecolor="red", linewidth=2, zorder=7)
        axes.add_patch(self.span)
        self.title = axes.set_title("")
        self.figure.subplots_adjust(left=0.06, right=0.98, bottom=0.08, top=0.92, wspace=0.15)
        shape = (self.height, self.width)
        self.samples = SampleDots(axes, shape, sample) if SampleDots.fit(shape) else None

        self.et_html, self.aet_html = widgets.HTML(), widgets.HTML()
        self._canvas = figure_widget(self.figure)
        # Tables under the figures, wrapping onto two lines when the notebook is narrow.
        tables = widgets.HBox(
            [self.et_html, self.aet_html], layout={"margin": "8px 0 0 0", "flex_flow": "row wrap"}
        )
        self.et_html.layout.margin = "0 24px 8px 0"
        self.widget = widgets.VBox([self._canvas, tables])
        self.show(0)

    def narrate(self, step: int) -> str:
        """What event `step` did and why, in one sentence (see `ScanNarrator`)."""
        return self.narrator.narrate(step)

    def show(self, step: int) -> None:
        """Show the state after the first `step` events (artists and tables updated in place)."""
        image = self.trace.image_at(step, self.width, self.height)
        self.image.set_data(image)
        if self.samples is not None:
            self.samples.show(image > 0)
        event = self.trace[step - 1] if step else None
        row = self.narrator.row_at[step]
        self.scanline.set_visible(row is not None)
        if row is not None:
            self.scanline.set_ydata([row[1] + self.offset] * 2)
        self.span.set_visible(event is not None and event.kind == "span")
        if self.span.get_visible():
            self.span.set_bounds(event.x_start, event.y, event.x_end - event.x_start, 1)
        self.title.set_text(f"step {step}" + ("" if row is None else f", row {row[1]}"))
        self.et_html.value = self._edge_table(step, event)
        self.aet_html.value = self._active_edge_table(step, event, row)
        refresh_figure(self.figure, self._canvas)

    def _edge_table(self, step: int, event) -> str:
        index = self.narrator.table_at[step]
        if index < 0:
            return "<b>edge table</b>: not built yet"
        changes = {}
        if event is not None and event.kind in ("edges_activated", "edges_retired"):
            change = "entering" if event.kind == "edges_activated" else "retiring"
            changes = dict.fromkeys(event.edges, change)
        table = self.trace[index]
        edges = sorted(table.edges, key=lambda e: (e.bucket, e.edge))
        rows = [
            (
                f"e{e.edge}",
                f"({e.x0:g}, {e.y0:g})",
                f"({e.x1:g}, {e.y1:g})",
                e.bucket,
                f"{e.ymax:g}",
                format_number(e.x, e.x_exact),
                format_number(e.dxdy, e.dxdy_exact),
                f"{e.winding:+d}",
                changes.get(e.edge) or _topology_note(e),
            )
            for e in edges
        ]
        header = ("edge", "lower", "upper", "bucket", "ymax", "x", "dx/dy", "winding", "")
        states = ["current" if e.edge in changes else "" for e in edges]
        caption = f"<b>edge table</b> of polygon {table.polygon} (bucket = ceil(ymin))"
        return caption + scroll_box(html_table(header, rows, states=states))

    def _active_edge_table(self, step: int, event, row) -> str:
        index = self.narrator.aet_at[step]
        aet = self.trace[index] if index >= 0 else None
        if aet is not None and (aet.polygon, aet.y) == row:
            caption = f"<b>AET of row {aet.y}</b> ({aet.swaps} swaps in the sort)"
            self.highlights = (
                aet_changes(self.narrator.previous_aet(index), aet) if index == step - 1 else {}
            )
        else:  # between rows: the last AET, with the edges leaving it marked
            retiring = event.edges if event is not None and event.kind == "edges_retired" else ()
            self.highlights = dict.fromkeys(retiring, "retiring")
            caption = "<b>AET</b>: empty" if aet is None else f"<b>AET of row {aet.y}</b>"
            if row is not None and aet is not None:
                caption += f", before the update for row {row[1]}"
        entries = aet.entries if aet is not None else ()
        self._show_active_edges(entries, step)
        rows = [
            (
                f"e{e.edge}",
                format_number(e.x, e.x_exact),
                format_number(e.dxdy, e.dxdy_exact),
                f"{e.ymax:g}",
                f"{e.winding:+d}",
                self.highlights.get(e.edge, ""),
            )
            for e in entries
        ]
        header = ("edge", "x", "dx/dy", "ymax", "winding", "change")
        states = ["current" if e.edge in self.highlights else "" for e in entries]
        return caption + html_table(header, rows, states=states)

    def _show_active_edges(self, entries, step: int) -> None:
        records = self.narrator.edge_records(step)
        self.active_edges.set_segments(
            [
                [(r.x0, r.y0), (r.x1, r.y1)]
                for r in (records.get(e.edge) for e in entries)
                if r is not None
            ]
        )


def _topology_note(edge) -> str:
    if edge.horizontal:
        return "horizontal: crosses no row, never active"
    return "between two rows: crosses none, never active" if edge.kept_for_topology else ""


def scan_conversion_stepper(polygon: object, width: int, height: int, **scan_options) -> Stepper:
    """Scan-convert `polygon` with tracing and step through it in a `ScanConversionView`.

    Parameters
    ----------
    polygon : Polygon or array_like
    width, height : int
    **scan_options
        Passed to `scanviz.scan_convert` (``sample``, ``rule``,
        ``subpixel_bits``, ``arithmetic``); ``trace`` may be a `Recorder`
        with a filter (rows, kinds, region) to step through less.

    Returns
    -------
    Stepper

    Examples
    --------
    >>> from scanviz.catalog import get
    >>> stepper = scan_conversion_stepper(get("umbc_example").polygon, 14, 13)
    >>> stepper.slider.value = 5
    >>> "3 7/10" in stepper.views[0].aet_html.value
    True
    >>> stepper  # doctest: +SKIP
    """
    scan_options.setdefault("trace", True)
    result = scan_convert(polygon, width, height, **scan_options)
    if result.trace is None:
        raise ValueError("'trace' must be True or a Recorder, so that there is a trace to show")
    view = ScanConversionView(
        polygon, width, height, result.trace, sample=scan_options.get("sample", "corner")
    )
    return Stepper(result.trace, [view], title="Scan conversion: edge table and active edge table")

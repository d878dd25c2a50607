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
from ..trace.table import format_number
from ._common import html_table, new_figure
from .stepper import Stepper, draw_pixel_grid, figure_widget, refresh_figure

DETAIL_LIMIT = 128 * 128  # larger rasters get no per-pixel grid lines or sample dots


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


class ScanConversionView:
    """A scan conversion trace, one step at a time.

    Left: the pixel grid with the image so far (the spans emitted up to the
    step), sample points (dark when covered), the polygon, the active edges,
    the current scanline and the span just emitted. Right: the final image.
    Beside them, the edge table and the active edge table of the current
    row; table rows that changed at this step are highlighted: edges
    entering or retiring, and on ``aet_sorted`` the entries that entered,
    moved in the sort or whose x changed.

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
    samples : (Line2D, Line2D) or None
        The covered and the uncovered sample points (None above `DETAIL_LIMIT` pixels).
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
    >>> view.widget  # doctest: +SKIP
    """

    def __init__(
        self, polygon: object, width: int, height: int, trace: Trace, *, sample: str = "corner"
    ) -> None:
        from matplotlib.collections import LineCollection
        from matplotlib.patches import Rectangle

        self.polygon = Polygon(polygon)
        self.width, self.height = check_raster_size(width, height)
        self.offset = sample_offset(check_choice("sample", sample, SAMPLE_MODES))
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        self.trace = trace
        self.highlights: dict[int, str] = {}
        self._index_steps()

        final = trace.image_at(len(trace), self.width, self.height)
        size = min(0.4 * max(self.width, self.height) + 1, 5.5)
        self.figure, (axes, final_axes) = new_figure(2, width=2 * size, height=size, dpi=80)
        shown = {"origin": "lower", "cmap": "Blues", "vmin": 0, "vmax": 1.6 * max(final.max(), 1)}
        shown |= {"extent": (0, self.width, 0, self.height), "interpolation": "nearest"}
        self.image = axes.imshow(np.zeros_like(final), **shown)
        final_axes.imshow(final, **shown)
        self.samples = None  # (covered, not covered) sample dots: markers draw fast in Agg
        if self.width * self.height <= DETAIL_LIMIT:
            self.samples = (
                axes.plot([], [], ".", color="navy", markersize=5, zorder=3)[0],
                axes.plot([], [], ".", color="0.6", markersize=4, zorder=3)[0],
            )
            for ax in (axes, final_axes):
                draw_pixel_grid(ax, (0, self.width, 0, self.height))
        for ax in (axes, final_axes):
            for contour in self.polygon.contours:
                closed = np.vstack([contour, contour[:1]])
                ax.plot(closed[:, 0], closed[:, 1], color="crimson", linewidth=1.2, zorder=4)
            ax.set(xlim=(0, self.width), ylim=(0, self.height), aspect="equal")
        final_axes.set_title("final image")
        self.active_edges = LineCollection([], colors="darkorange", linewidths=3, zorder=5)
        axes.add_collection(self.active_edges)
        self.scanline = axes.axhline(0, color="orange", linewidth=2, zorder=6, visible=False)
        self.span = Rectangle((0, 0), 0, 1, fill=False, edgecolor="red", linewidth=2, zorder=7)
        axes.add_patch(self.span)
        self.title = axes.set_title("")
        self.figure.subplots_adjust(left=0.06, right=0.98, bottom=0.07, top=0.93, wspace=0.12)

        self.et_html, self.aet_html = widgets.HTML(), widgets.HTML()
        self._canvas = figure_widget(self.figure)
        # Tables under the figures: side by side they get squeezed off a notebook's width.
        tables = widgets.HBox([self.et_html, self.aet_html], layout={"margin": "8px 0 0 0"})
        self.aet_html.layout.margin = "0 0 0 24px"
        self.widget = widgets.VBox([self._canvas, tables])
        self.show(0)

    def _index_steps(self) -> None:
        """For every step: the current (polygon, row), the last edge table and the last AET."""
        self._rows: list[tuple[int, int] | None] = [None]
        self._tables, self._aets = [-1], [-1]
        self._previous_aet: dict[int, int] = {}  # aet_sorted index -> the one before, same polygon
        last_aet_of: dict[int, int] = {}
        for index, event in enumerate(self.trace):
            if hasattr(event, "y"):
                self._rows.append((getattr(event, "polygon", 0), event.y))
            else:
                self._rows.append(self._rows[-1])
            self._tables.append(index if event.kind == "edge_table_built" else self._tables[-1])
            self._aets.append(index if event.kind == "aet_sorted" else self._aets[-1])
            if event.kind == "aet_sorted":
                self._previous_aet[index] = last_aet_of.get(event.polygon, -1)
                last_aet_of[event.polygon] = index

    def show(self, step: int) -> None:
        """Show the state after the first `step` events (artists and tables updated in place)."""
        image = self.trace.image_at(step, self.width, self.height)
        self.image.set_data(image)
        if self.samples is not None:
            for dots, samples in zip(self.samples, (image > 0, image == 0), strict=True):
                ys, xs = np.nonzero(samples)
                dots.set_data(xs + self.offset, ys + self.offset)
        event = self.trace[step - 1] if step else None
        row = self._rows[step]
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
        index = self._tables[step]
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
        return caption + html_table(header, rows, states=states)

    def _active_edge_table(self, step: int, event, row) -> str:
        index = self._aets[step]
        aet = self.trace[index] if index >= 0 else None
        if aet is not None and (aet.polygon, aet.y) == row:
            caption = f"<b>AET of row {aet.y}</b> ({aet.swaps} swaps in the sort)"
            self.highlights = (
                aet_changes(self._previous_aet_event(index), aet) if index == step - 1 else {}
            )
        else:  # between rows: the last AET, with the edges leaving it marked
            retiring = event.edges if event is not None and event.kind == "edges_retired" else ()
            self.highlights = dict.fromkeys(retiring, "retiring")
            caption = "<b>AET</b>: empty" if aet is None else f"<b>AET of row {aet.y}</b>"
            if row is not None and aet is not None:
                caption += f", before the update for row {row[1]}"
        entries = aet.entries if aet is not None else ()
        self._show_active_edges(entries, self._tables[step])
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

    def _previous_aet_event(self, index: int) -> AetSorted | None:
        previous = self._previous_aet[index]
        return self.trace[previous] if previous >= 0 else None

    def _show_active_edges(self, entries, table_index: int) -> None:
        records = {} if table_index < 0 else {e.edge: e for e in self.trace[table_index].edges}
        self.active_edges.set_segments(
            [
                [(r.x0, r.y0), (r.x1, r.y1)]
                for r in (records.get(e.edge) for e in entries)
                if r is not None
            ]
        )


def _topology_note(edge) -> str:
    if edge.horizontal:
        return "horizontal, kept for topology"
    return "crosses no sample row, kept for topology" if edge.kept_for_topology else ""


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

"""Step through scanline visibility one span at a time: the xz slice of the scanline, the AST, the SST.

`ScanlineVisibilityView` shows, after each step of a traced
``solve("scanline", ...)``, the current scanline's xz slice (x across, depth
up: each active surface's depth along the row, the spans as bands, the
visible surface drawn thick in its color, reused spans in green, splits as
dashed lines), the AST and SST as tables, and the image decided so far
beside the final image and the z-buffer's. `scanline_visibility_stepper`
solves screen polygons with a `Recorder` and wraps the view in a `Stepper`.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.patches import Rectangle

from ..trace import Trace
from ..visibility.scanline_visibility import Scanline
from ._common import WIDEST, fmt, html_table, listed, new_figure, note_label, pixel_image
from .stepper import Stepper, figure_widget, first_steps, refresh_figure
from .visibility import against_zbuffer, polygon_color, polygon_colors, solve_traced

SCANLINE_KINDS = ("surface_table_built", "active_surfaces", "visible_span")
BAND_COLORS = {"decided": (1.0, 0.91, 0.66, 0.6), "reused": (0.70, 0.92, 0.70, 0.6)}
SPAN_COLUMNS = (
    "x_start",
    "x_end",
    "surfaces",
    "depths at x_start",
    "visible",
    "reused",
    "split at",
)


def _band_color(span) -> tuple[float, ...]:
    """Yellow for a span decided on its row, green for one reused, clear for the background."""
    if not span.surfaces:
        return (1.0, 1.0, 1.0, 0.0)
    return BAND_COLORS["reused" if span.reused else "decided"]


class ScanlineVisibilityView:
    """The xz slice of the current scanline, the AST and SST, and the image decided so far.

    Parameters
    ----------
    trace : Trace
        ``surface_table_built``, ``active_surfaces`` and ``visible_span`` events
        of a traced ``solve("scanline", ...)``.
    result : VisibilityResult
        The same solve: the final ids, and in ``detail.planes`` the surfaces'
        depth planes, which the slice draws between the recorded depths.
    zbuffer_result : ZBufferResult or VisibilityResult
        The z-buffer's solve of the same polygons, for comparison.
    note : str, optional
        Shown above the figure (e.g. that the trace was cut).

    Attributes
    ----------
    widget : ipywidgets.VBox
    row : int or None
        The scanline shown (the last ``active_surfaces`` reached).
    surface_lines : matplotlib LineCollection
        One segment per surface and span of the row: its depth along the span.
    visible_lines : matplotlib LineCollection
        The visible surface over each span decided so far (thick, its color).
    bands : matplotlib PolyCollection
        One band per span decided so far: yellow decided, green reused.
    splits : matplotlib LineCollection
        Dashed verticals where an interpenetration split a span.
    decided_image : matplotlib AxesImage
        The ids decided by the spans so far, as colors.
    ast, sst, spans : ipywidgets.HTML
        The active surface table, the sorted surface table, the row's spans.
    """

    def __init__(self, trace: Trace, result, zbuffer_result, *, note: str = "") -> None:
        self.trace, self.result = trace, result
        height, width = result.polygon.shape
        self._planes = result.detail.planes
        self._spans = [(i, e) for i, e in enumerate(trace) if e.kind == "visible_span"]
        self._rows = [(i, e) for i, e in enumerate(trace) if e.kind == "active_surfaces"]
        self._table = next((e for e in trace if e.kind == "surface_table_built"), None)
        depths = [z for _, e in self._spans for z in e.depths]
        low, high = (min(depths), max(depths)) if depths else (0.0, 1.0)
        pad = 0.05 * (high - low) or 0.05

        fig, axes = new_figure(
            4, width=WIDEST, height=3.0, gridspec_kw={"width_ratios": [2, 1, 1, 1]}
        )
        ax_slice, ax_decided, ax_final, ax_zbuffer = axes
        ax_slice.set_xlim(0, width)
        ax_slice.set_ylim(low - pad, high + pad)
        ax_slice.set_xlabel("x")
        ax_slice.set_ylabel("z (the viewer is below: smaller is nearer)")
        self.bands = PolyCollection([], edgecolors="0.55", linewidths=0.6, zorder=1)
        self.surface_lines = LineCollection([], linewidths=1.0, zorder=2)
        self.visible_lines = LineCollection([], linewidths=3.5, zorder=3)
        self.splits = LineCollection([], colors="0.2", linestyles="--", linewidths=1, zorder=4)
        for artist in (self.bands, self.surface_lines, self.visible_lines, self.splits):
            ax_slice.add_collection(artist)
        self.current_band = Rectangle(
            (0, low - pad), 0, high - low + 2 * pad, fill=False, ec="black", lw=2, visible=False
        )
        ax_slice.add_patch(self.current_band)
        empty = polygon_colors(np.full((height, width), -1))
        self.decided_image = pixel_image(ax_decided, empty)
        self.scanline = ax_decided.axhline(0, color="black", lw=1.5, ls="--", visible=False)
        against_zbuffer(ax_final, ax_zbuffer, result.polygon, zbuffer_result.polygon)
        titles = (
            "xz slice of the scanline",
            "decided so far",
            "scanline: final",
            "z-buffer (red: differs)",
        )
        for ax, title in zip(axes, titles, strict=True):
            ax.set_title(title, fontsize=10)
        fig.tight_layout()
        self.figure, self.axes = fig, axes

        self.ast, self.sst, self.spans = widgets.HTML(), widgets.HTML(), widgets.HTML()
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        tables = widgets.HBox([self.ast, self.sst, self.spans], layout={"flex_flow": "row wrap"})
        self.widget = widgets.VBox([self.note, self._canvas, tables])
        self.row = None
        self.step = 0
        self.show(0)

    def decided(self, step: int) -> np.ndarray:
        """(H, W) int64 ids the first `step` events decided (-1: not yet, or background)."""
        ids = np.full(self.result.polygon.shape, -1, np.int64)
        for index, e in self._spans:
            if index >= step:
                break
            ids[e.y, e.x_start : e.x_end] = e.visible
        return ids

    def show(self, step: int) -> None:
        """Show the scanline, its spans and the tables after the first `step` events."""
        self.step = int(step)
        rows = [e for index, e in self._rows if index < self.step]
        row = rows[-1] if rows else None
        self.row = None if row is None else row.y
        here = [(i, e) for i, e in self._spans if row is not None and e.y == row.y]
        done = [e for i, e in here if i < self.step]
        self._draw_slice(here, done)
        self.decided_image.set_data(polygon_colors(self.decided(self.step)))
        self.scanline.set_visible(row is not None)
        if row is not None:
            self.scanline.set_ydata([row.y + 0.5, row.y + 0.5])
        self._show_tables(row, here)
        refresh_figure(self.figure, self._canvas)

    def _draw_slice(self, here, done) -> None:
        """Every surface's depth over the row's spans; the bands, visible surface, splits so far."""
        segments, colors = [], []
        for _, e in here:
            for p, z in zip(e.surfaces, e.depths, strict=True):
                segments.append(self._segment(p, z, e.x_start, e.x_end))
                colors.append((*polygon_color(p), 0.45))
        self.surface_lines.set_segments(segments)
        self.surface_lines.set_colors(colors)
        visible = [e for e in done if e.visible >= 0]
        self.visible_lines.set_segments([self._visible_segment(e) for e in visible])
        self.visible_lines.set_colors([polygon_color(e.visible) for e in visible])
        low, high = self.axes[0].get_ylim()
        self.bands.set_verts(
            [[(e.x_start, low), (e.x_end, low), (e.x_end, high), (e.x_start, high)] for e in done]
        )
        self.bands.set_facecolors([_band_color(e) for e in done])
        self.splits.set_segments(
            [[(e.split_at, low), (e.split_at, high)] for e in done if e.split_at is not None]
        )
        current = done[-1] if done and here and here[len(done) - 1][0] == self.step - 1 else None
        self.current_band.set_visible(current is not None)
        if current is not None:
            self.current_band.set_x(current.x_start)
            self.current_band.set_width(current.x_end - current.x_start)

    def _segment(self, p: int, z: float, x_start: int, x_end: int) -> list[tuple[float, float]]:
        """Surface p's depth from sample x_start (recorded: z) to x_end along its plane's dz/dx."""
        return [(x_start, z), (x_end, z + self._planes[p, 3] * (x_end - x_start))]

    def _visible_segment(self, span) -> list[tuple[float, float]]:
        depth = span.depths[span.surfaces.index(span.visible)]
        return self._segment(span.visible, depth, span.x_start, span.x_end)

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the surface table, a row's active surfaces, or a
        span with the surfaces over it, their depths and the one visible."""
        if step == 0:
            return (
                "The start: the polygons go into a surface table sorted by their first row; "
                "then each row is cut into spans, and each span shows its nearest surface."
            )
        event = self.trace[step - 1]
        if event.kind == "surface_table_built":
            rows = "; ".join(
                f"{r.polygon} on rows {r.y_start}..{r.y_end - 1}" for r in event.surfaces
            )
            return f"The sorted surface table lists {len(event.surfaces)} polygons by first row: {rows}."
        if event.kind == "active_surfaces":
            changes = [f"{listed(event.entered)} enter{'s' if len(event.entered) == 1 else ''}"]
            changes = changes if event.entered else []
            if event.exhausted:
                changes.append(
                    f"{listed(event.exhausted)} {'is' if len(event.exhausted) == 1 else 'are'} exhausted"
                )
            what = " and ".join(changes) or "no polygon enters or leaves"
            return f"Row y = {event.y}: {what}; the active surfaces are {listed(event.active) or 'none'}."
        span = (
            f"{event.x_start}"
            if event.x_end - event.x_start == 1
            else f"{event.x_start}..{event.x_end - 1}"
        )
        where = f"Row {event.y}, x {span}"
        if not event.surfaces:
            return f"{where}: no surface covers it, so it shows the background."
        depths = listed(
            f"{p} (z {fmt(z, 3)})" for p, z in zip(event.surfaces, event.depths, strict=True)
        )
        if event.reused:
            return (
                f"{where}: the same surfaces as on the row below ({depths}), so its decision is "
                f"reused: {event.visible} is visible."
            )
        split = (
            f" after the planes cross at x = {fmt(event.split_at, 4)}"
            if event.split_at is not None
            else ""
        )
        if len(event.surfaces) == 1:
            return f"{where}{split}: only surface {depths} covers it, so it is visible."
        return f"{where}{split}: surfaces {depths} overlap; {event.visible} is the nearest at x = {event.x_start}, so it is visible."

    def _show_tables(self, row, here) -> None:
        """The AST of the row, the SST (pending, active, exhausted) and the row's spans."""
        if row is None:
            self.ast.value = "<i>no scanline yet</i>"
        else:
            self.ast.value = f"<b>AST, row y = {row.y}</b> (sorted on x)" + html_table(
                ("active", "entered", "exhausted"), [(row.active, row.entered, row.exhausted)]
            )
        records = self._table.surfaces if self._table is not None and self.step > 0 else ()
        self.sst.value = "<b>SST</b> (by first row)" + html_table(
            ("polygon", "y_start", "y_end"),
            [(r.polygon, r.y_start, r.y_end) for r in records],
            states=[_surface_state(r, row) for r in records],
        )
        rows = [
            (
                e.x_start,
                e.x_end,
                e.surfaces,
                e.depths,
                e.visible,
                "yes" if e.reused else "",
                e.split_at,
            )
            for _, e in here
        ]
        states = [
            "current" if i == self.step - 1 else "done" if i < self.step else "pending"
            for i, _ in here
        ]
        self.spans.value = "<b>spans of the row</b>" + html_table(SPAN_COLUMNS, rows, states=states)


def _surface_state(record, row) -> str:
    """An SST entry's state at `row`: not entered yet, in the AST, or exhausted."""
    if row is None or record.y_start > row.y:
        return "pending"
    return "current" if record.polygon in row.active else "done"


def scanline_visibility_stepper(polygons, width: int, height: int, **options) -> Stepper:
    """Solve `polygons` with scanline visibility, traced, and step through it span by span.

    Parameters
    ----------
    polygons : ScreenPolygons
        E.g. one of `scanviz.visibility.examples`.
    width, height : int
        Raster size.
    **options
        ``coherence`` (of `Scanline`); ``sample``, ``subpixel_bits``,
        ``perspective`` (of `solve`).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `ScanlineVisibilityView`. A trace longer than
        ``Stepper.MAX_STEPS`` is cut, and the view says so.

    Examples
    --------
    >>> from scanviz.visibility import examples
    >>> stepper = scanline_visibility_stepper(examples.slides_painter(), 16, 12)
    >>> stepper.slider.value = stepper.slider.max
    >>> stepper.views[0].row, stepper.views[0].spans.value.count("<tr") - 1
    (9, 3)
    """
    chosen = Scanline(coherence=options.pop("coherence", True))
    result, reference = solve_traced(chosen, polygons, width, height, SCANLINE_KINDS, **options)
    trace, note = first_steps(result.trace)
    view = ScanlineVisibilityView(trace, result, reference, note=note)
    return Stepper(trace, [view], title="scanline visibility: one span per step")

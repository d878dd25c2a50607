"""The Floating Perimeter Algorithm one event at a time (`perimeter_stepper`).

A facet starts, each of its edges is tested, the perimeter grows: the points
tested so far (visible black, hidden light red), the current edge, and the
perimeter arrays top[x], bottom[x] (over the columns) and right[y], left[y]
(over the rows), replayed from the ``perimeter_update`` events; beside it the
grid from above with the current facet. Raster point (x, y) is drawn at the
centre of its pixel square, so a point is hidden iff it lies strictly between
both pairs of curves.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.colors import to_rgba
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ..surfaces import GridSurface, PerimeterResult, View, floating_perimeter
from ..trace import Trace
from ._common import WIDEST, html_table, new_figure, note_label, pixel_image
from .stepper import Stepper, figure_widget, first_steps, refresh_figure
from .surface_grid import CURRENT, GridFromAbove, check_surface_view, enumerated_event

VISIBLE = "#000000"
HIDDEN = "#f4a0a0"  # a hidden point: light red
PERIMETER_COLORS = {"top": "#1f77b4", "bottom": "#08519c", "right": "#2ca02c", "left": "#006d2c"}
COVERED = "#e8e8e8"  # samples covered by the facets processed so far
MAX_POINT_ROWS = 40  # rows of the current edge's point table


def _steps_lines(
    values: np.ndarray, known: np.ndarray, along_x: bool
) -> tuple[np.ndarray, np.ndarray]:
    """A step curve through pixel centres: entry i spans i - 1/2 .. i + 1/2; unknown entries are gaps."""
    at = np.repeat(np.arange(len(values)), 2) + np.tile([-0.5, 0.5], len(values))
    level = np.repeat(np.where(known, values, np.nan).astype(np.float64), 2)
    return (at, level) if along_x else (level, at)


class PerimeterView:
    """The screen after each FPA event: points so far, the current edge, the perimeter arrays.

    Parameters
    ----------
    trace : Trace
        Of ``floating_perimeter(..., mode="lines", trace=True)``: its
        ``facets_enumerated``, ``perimeter_facet``, ``perimeter_edge`` and
        ``perimeter_update`` events (others are ignored). Each event is a step.
    result : PerimeterResult
        The same run (its raster size).
    surface : GridSurface
        The surface traced (its x- and y-planes, for the grid from above).
    view : View
        The view traced (the viewpoint drawn from above).
    coverage : (H, W) ndarray of int64, optional
        The facet (grid element k = r (Nx - 1) + c, -1 none) seen at each
        sample front to back, e.g. ``floating_perimeter(..., "surface",
        sample="center").facet``: the samples covered by the facets processed
        so far are shaded, so a hole (inside the perimeter, covered by none)
        shows.
    region : (x_start, y_start, x_end, y_end), optional
        Zoom the screen panel to these pixels (half-open).
    note : str, optional
        Shown above the figure.

    Attributes
    ----------
    widget : ipywidgets.VBox
    points_image : matplotlib AxesImage
        The points tested so far: visible `VISIBLE`, hidden `HIDDEN`, else transparent.
    edge_points : matplotlib PathCollection
        The current edge's points (empty unless the step is an edge).
    facet_outline : matplotlib Line2D
        The current facet's four sides on the screen.
    curves : dict of str to matplotlib Line2D
        "top", "bottom" (over columns), "right", "left" (over rows).
    grid : GridFromAbove
    text : ipywidgets.HTML
        The step: the facet, the edge with each point's test, or the update.
    """

    def __init__(
        self,
        trace: Trace,
        result: PerimeterResult,
        surface: GridSurface,
        view: View,
        *,
        coverage: np.ndarray | None = None,
        region: tuple[int, int, int, int] | None = None,
        note: str = "",
    ) -> None:
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        if not isinstance(result, PerimeterResult) or result.mode != "lines":
            raise TypeError(
                "'result' must be the PerimeterResult of a lines-mode floating_perimeter"
            )
        check_surface_view(surface, view)
        self.trace, self.result = trace, result
        self.height, self.width = result.lines.shape
        self.events = list(trace)
        self._read_events(enumerated_event(trace))
        self._coverage = self._check_coverage(coverage)
        self.step = 0

        fig, (ax_screen, ax_grid) = new_figure(2, width=WIDEST, height=4.9)
        self._draw_screen(ax_screen, region)
        self.grid = GridFromAbove(ax_grid, surface.x, surface.y, self.enumerated, view)
        handles = [
            Patch(fc=VISIBLE, label="visible point"),
            Patch(fc=HIDDEN, label="hidden point"),
            *(Line2D([], [], color=c, lw=1.5, label=k) for k, c in PERIMETER_COLORS.items()),
        ]
        if self._coverage is not None:
            handles.append(Patch(fc=COVERED, ec="0.7", label="covered so far"))
        fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=9)
        fig.tight_layout(rect=(0, 0.11, 1, 1))
        self.grid.number_facets()
        self.figure, self.axes = fig, (ax_screen, ax_grid)
        self.text = widgets.HTML()
        self.note = note_label(note)
        self._canvas = figure_widget(fig)
        self.widget = widgets.VBox([self.note, widgets.HBox([self._canvas]), self.text])
        self.show(0)

    def _read_events(self, enumerated) -> None:
        """Index the events once: points per edge, the facet of each step, the perimeter changes."""
        self.enumerated = enumerated
        edges = [(i, e) for i, e in enumerate(self.events) if e.kind == "perimeter_edge"]
        if not edges:
            raise ValueError(
                "'trace' holds no perimeter_edge events: pass the trace of a lines-mode "
                "floating_perimeter(..., trace=True)"
            )
        counts = [len(e.points) for _, e in edges]
        self._points = np.array([p for _, e in edges for p in e.points], np.int64).reshape(-1, 2)
        self._visible = np.array([v for _, e in edges for v in e.visible], bool)
        self._point_event = np.repeat([i for i, _ in edges], counts)
        self._ends = {
            (e.edge.kind, e.edge.row, e.edge.column): (e.points[0], e.points[-1]) for _, e in edges
        }
        facet, updated, self._facet_at, self._updated_at = None, 0, [None], [0]
        for event in self.events:  # the state after each step
            if event.kind == "perimeter_facet":
                facet = event
            elif event.kind == "perimeter_update":
                updated += 1
            self._facet_at.append(facet)
            self._updated_at.append(updated)
        updates = [(i, e) for i, e in enumerate(self.events) if e.kind == "perimeter_update"]
        self._columns = np.array(
            [(i, *c) for i, e in updates for c in e.columns], np.int64
        ).reshape(-1, 4)
        self._rows = np.array([(i, *r) for i, e in updates for r in e.rows], np.int64).reshape(
            -1, 4
        )

    def _check_coverage(self, coverage):
        if coverage is None:
            return None
        coverage = np.asarray(coverage)
        if coverage.shape != (self.height, self.width) or not np.issubdtype(
            coverage.dtype, np.integer
        ):
            raise ValueError(
                f"'coverage' must be an ({self.height}, {self.width}) integer array of facets "
                f"(-1: none); got shape {coverage.shape} of {coverage.dtype}"
            )
        order = np.asarray(self.enumerated.order).reshape(-1)
        return np.where(coverage >= 0, order[np.maximum(coverage, 0)], 0)  # facet numbers, 0 none

    def _draw_screen(self, axes, region) -> None:
        blank = np.zeros((self.height, self.width, 4))
        if self._coverage is not None:
            self.coverage_image = pixel_image(axes, blank, offset=-0.5)
        self.points_image = pixel_image(axes, blank, offset=-0.5)
        self.curves = {}
        for name, color in PERIMETER_COLORS.items():
            (self.curves[name],) = axes.plot([], [], color=color, lw=1.3, label=name)
        (self.facet_outline,) = axes.plot([], [], color=CURRENT, lw=1, ls="--")
        self.edge_points = axes.scatter(
            [], [], s=30, marker="s", edgecolors=CURRENT, linewidths=1.5, zorder=4
        )
        x0, y0, x1, y1 = region if region is not None else (0, 0, self.width, self.height)
        axes.set_xlim(x0 - 0.5, x1 - 0.5)
        axes.set_ylim(y0 - 0.5, y1 - 0.5)
        axes.set_aspect("equal")
        axes.set_title("screen: points tested and the perimeter", fontsize=10)

    def perimeter(self, step: int) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
        """The perimeter arrays after `step` events, replayed from the ``perimeter_update`` events.

        Returns
        -------
        arrays : dict of str to ndarray of int64
            "top", "bottom" (W,) and "right", "left" (H,); entries no update set
            keep the initial values 0, H, 0, W.
        known : dict of str to ndarray of bool
            "columns" (W,) and "rows" (H,): the entries some update has set.
        """
        arrays = {
            "top": np.zeros(self.width, np.int64),
            "bottom": np.full(self.width, self.height, np.int64),
            "right": np.zeros(self.height, np.int64),
            "left": np.full(self.height, self.width, np.int64),
        }
        known = {"columns": np.zeros(self.width, bool), "rows": np.zeros(self.height, bool)}
        for changes, names, axis in (
            (self._columns, ("top", "bottom"), "columns"),
            (self._rows, ("right", "left"), "rows"),
        ):
            done = changes[changes[:, 0] < step]
            # Each entry keeps the value of its last update: unique over the reversed list.
            index, last = np.unique(done[::-1, 1], return_index=True)
            for k, name in enumerate(names):
                arrays[name][index] = done[::-1][last, 2 + k]
            known[axis][index] = True
        return arrays, known

    def step_of(self, point: int) -> int:
        """The step that tests point number `point` (an index into `PerimeterResult.points`).

        The points of the ``perimeter_edge`` events, edge after edge, are the
        result's points in the same order.
        """
        if isinstance(point, bool) or not isinstance(point, int | np.integer):
            raise TypeError(f"'point' must be an int; got {point!r}")
        if not 0 <= point < len(self._points):
            raise ValueError(f"'point' must be in 0..{len(self._points) - 1}; got {point}")
        return int(self._point_event[point]) + 1

    def show(self, step: int) -> None:
        """Show the state after the first `step` events."""
        self.step = int(step)
        event = self.events[self.step - 1] if self.step else None
        done = self._point_event < self.step
        image = np.zeros((self.height, self.width, 4))
        for flag, color in ((False, HIDDEN), (True, VISIBLE)):  # visible drawn over hidden
            chosen = self._points[done & (self._visible == flag)]
            image[chosen[:, 1], chosen[:, 0]] = to_rgba(color)
        self.points_image.set_data(image)
        arrays, known = self.perimeter(self.step)
        for name in ("top", "bottom"):
            self.curves[name].set_data(*_steps_lines(arrays[name], known["columns"], True))
        for name in ("right", "left"):
            self.curves[name].set_data(*_steps_lines(arrays[name], known["rows"], False))
        facet = self._facet_at[self.step]
        processed = self._updated_at[self.step]
        self.grid.highlight(None if facet is None else facet.number, processed)
        self._show_facet(facet)
        self._show_edge(event if event is not None and event.kind == "perimeter_edge" else None)
        if self._coverage is not None:
            covered = (self._coverage > 0) & (self._coverage <= processed)
            self.coverage_image.set_data(np.where(covered[..., None], to_rgba(COVERED), 0.0))
        self.text.value = self._describe(event, arrays)
        refresh_figure(self.figure, self._canvas)

    def _show_facet(self, facet) -> None:
        bottom = top = None
        if facet is not None:  # a trace cut short may lack the edge events of a side
            bottom = self._ends.get(("h", facet.row, facet.column))
            top = self._ends.get(("h", facet.row + 1, facet.column))
        if bottom is None or top is None:
            self.facet_outline.set_data([], [])
            return
        corners = np.array([bottom[0], bottom[1], top[1], top[0], bottom[0]], np.float64)
        self.facet_outline.set_data(corners[:, 0], corners[:, 1])

    def _show_edge(self, edge) -> None:
        if edge is None:
            self.edge_points.set_offsets(np.zeros((0, 2)))
            return
        self.edge_points.set_offsets(np.array(edge.points, np.float64))
        self.edge_points.set_facecolors([VISIBLE if v else HIDDEN for v in edge.visible])

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the enumeration, a facet, an edge's points tested
        against the perimeter (the first hidden one with its numbers), or an update."""
        if step == 0:
            return (
                "The start: the perimeter is empty (top 0, bottom H, right 0, left W), so "
                "nothing is hidden yet."
            )
        event = self.events[step - 1]
        if event.kind == "facets_enumerated":
            rows, columns = np.shape(event.order)
            row, column = (int(v[0]) for v in np.nonzero(np.asarray(event.order) == 1))
            return (
                f"The viewpoint gives viewing case {event.case}, so the {rows * columns} facets "
                f"are numbered nearest first, from facet 1 at row {row}, column {column}."
            )
        if event.kind == "perimeter_facet":
            return (
                f"Facet {event.number} (row {event.row}, column {event.column}, region class "
                f"{event.region_class}) is next nearest: its sides {', '.join(event.sides)} are "
                "drawn and tested against the perimeter."
            )
        if event.kind == "perimeter_update":
            return (
                f"Facet {event.facet}'s {event.points} visible points grow the perimeter: "
                f"{len(event.columns)} columns (top, bottom) and {len(event.rows)} rows "
                "(right, left) change."
            )
        if event.kind != "perimeter_edge":
            return event.kind.replace("_", " ")
        edge, count = event.edge, len(event.points)
        head = f"Edge {edge.kind}({edge.row}, {edge.column}) of facet {event.facet}: "
        if all(event.visible):
            return head + f"all {count} points lie outside the perimeter, so all are visible."
        arrays, _ = self.perimeter(step - 1)
        k = event.visible.index(False)
        x, y = event.points[k]
        why = (
            f"bottom[{x}] = {arrays['bottom'][x]} < {y} < top[{x}] = {arrays['top'][x]} and "
            f"left[{y}] = {arrays['left'][y]} < {x} < right[{y}] = {arrays['right'][y]}"
        )
        shown = sum(event.visible)
        return head + (
            f"{shown} of {count} points visible; point ({x}, {y}) is hidden as {why}."
            if shown
            else f"all {count} points are hidden, e.g. ({x}, {y}) as {why}."
        )

    def _describe(self, event, arrays) -> str:
        if event is None:
            return "<i>start: top 0, bottom H, right 0, left W (nothing hides)</i>"
        if event.kind == "facets_enumerated":
            return (
                f"<b>viewing case {event.case}</b>, viewpoint cell {event.vp_cell}: the facets "
                "are numbered nearest first (right)."
            )
        if event.kind == "perimeter_facet":
            return (
                f"<b>facet {event.number}</b> (row {event.row}, column {event.column}, class "
                f"{event.region_class}) processes its sides <b>{event.sides}</b>: "
                + ", ".join(f"{e.kind}({e.row}, {e.column})" for e in event.edges)
            )
        if event.kind == "perimeter_update":
            return (
                f"<b>facet {event.facet}: perimeter update</b> with its {event.points} visible "
                f"points (Bbuf): {len(event.columns)} columns and {len(event.rows)} rows changed."
            )
        if event.kind != "perimeter_edge":
            return html.escape(event.kind)
        edge = event.edge
        rows = [
            (
                x,
                y,
                arrays["bottom"][x],
                arrays["top"][x],
                arrays["left"][y],
                arrays["right"][y],
                "visible" if v else "hidden",
            )
            for (x, y), v in zip(event.points[:MAX_POINT_ROWS], event.visible, strict=False)
        ]
        more = len(event.points) - len(rows)
        return (
            f"<b>facet {event.facet}, edge {edge.kind}({edge.row}, {edge.column})</b>: "
            f"{len(event.points)} points, {sum(event.visible)} visible: <b>{event.verdict}</b>. "
            "Hidden iff bottom[x] &lt; y &lt; top[x] and left[y] &lt; x &lt; right[y]."
            + html_table(("x", "y", "bottom[x]", "top[x]", "left[y]", "right[y]", "point"), rows)
            + (f"<i>and {more} more points</i>" if more > 0 else "")
        )


def perimeter_stepper(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    coverage: bool = True,
    region: tuple[int, int, int, int] | None = None,
) -> Stepper:
    """Trace the Floating Perimeter Algorithm (lines) and step through it, one event per step.

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
        Raster size (keep it small: every edge point is drawn and listed).
    coverage : bool
        Shade the samples covered by the facets processed so far (from the
        front-to-back coverage-mask render, sampled where the points are tested).
    region : (x_start, y_start, x_end, y_end), optional
        Zoom the screen panel to these pixels.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `PerimeterView`. Steps: the enumeration, then per
        facet its start, one per edge it processes and the perimeter update.

    Examples
    --------
    >>> from scanviz.surfaces import gaussian
    >>> stepper = perimeter_stepper(gaussian(4), View((3, 4, 3), (-3, -4, -3)), 32, 32)
    >>> stepper.slider.max  # 1 + 2 x 9 facets + 24 edges
    43
    """
    check_surface_view(surface, view)
    result = floating_perimeter(surface, view, width, height, trace=True)
    trace, note = first_steps(result.trace, "events")
    covered = None
    if coverage:
        covered = floating_perimeter(
            surface, view, width, height, "surface", shading="flat", sample="center"
        ).facet
    perimeter_view = PerimeterView(
        trace, result, surface, view, coverage=covered, region=region, note=note
    )
    return Stepper(
        trace, [perimeter_view], title="floating perimeter: one facet, edge or update per step"
    )

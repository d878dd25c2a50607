"""Edit a polygon's vertices and watch its scan conversion, edge table and AET change.

`PolygonEditor` keeps the vertices as text ("x,y x,y ..."); under ipympl the
vertices can also be dragged. Every change re-runs `scanviz.scan_convert`
with a trace (the core) and shows the coverage and the ET/AET it recorded.
Bad input is reported in a label, never raised.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..geometry import Polygon
from ..raster import scan_convert
from ..trace.display import scroll_box
from ._common import DisplaysWidget, html_table, new_figure, say, status_label
from .stepper import coverage_image, figure_widget, refresh_figure

EDGE_COLUMNS = ("edge", "(x0, y0)", "(x1, y1)", "bucket", "row_end", "x", "dx/dy", "winding")
GRAB_RADIUS = 0.5  # pixels: how near a click must be to a vertex to drag it


def parse_vertices(text: str) -> np.ndarray:
    """'x,y x,y ...' as an (N, 2) ndarray of float64; ValueError naming the bad pair.

    Examples
    --------
    >>> parse_vertices("0,0 4,0 4,3").tolist()
    [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0]]
    """
    pairs = text.replace(";", " ").split()
    points = []
    for k, pair in enumerate(pairs):
        try:
            x, y = (float(v) for v in pair.split(","))
        except ValueError:
            raise ValueError(f"vertex {k} must be 'x,y' with two numbers; got {pair!r}") from None
        points.append((x, y))
    return np.array(points, dtype=np.float64).reshape(-1, 2)


def format_vertices(vertices: np.ndarray) -> str:
    """The inverse of `parse_vertices` (10 significant digits)."""
    return " ".join(f"{x:.10g},{y:.10g}" for x, y in np.asarray(vertices, float))


class PolygonEditor(DisplaysWidget):
    """A polygon as editable text (and draggable vertices) with its live scan conversion.

    Parameters
    ----------
    vertices : (N, 2) array_like of float
        The starting polygon, pixels, y up.
    width, height : int
        Raster size.
    sample : {"corner", "center"}
        Passed to `scan_convert`; where the sample dots are drawn.

    Attributes
    ----------
    widget : ipywidgets.VBox
    text : ipywidgets.Text
        "x,y x,y ..."; setting it re-runs the scan conversion.
    error : ipywidgets.HTML
        Why the text was not accepted (empty when it was).
    result : ScanResult
        The last accepted polygon's scan conversion, with its trace.
    vertices : (N, 2) ndarray of float64
        The last accepted vertices.
    coverage : matplotlib AxesImage
        Its array is ``result.mask``.
    samples : SampleDots or None
        Each pixel's sample point, filled where ``result.mask`` is set
        (None above `DOTS_LIMIT` pixels a side).
    edge_table, active_edges : ipywidgets.HTML
        The edge table (``edge_table_built``) and the AET of every row (``aet_sorted``).

    Examples
    --------
    >>> editor = PolygonEditor([(0, 0), (4, 0), (4, 3)], 5, 3)
    >>> editor.text.value = "0,0 5,0 5,3"
    >>> int(editor.result.mask.sum())
    9
    >>> editor.text.value = "0,0 5"
    >>> editor.error.value != "", int(editor.result.mask.sum())
    (True, 9)
    """

    def __init__(self, vertices, width: int, height: int, *, sample: str = "corner") -> None:
        self.width, self.height, self.sample = int(width), int(height), sample
        fig, (ax,) = new_figure(1, width=5.0, height=5.0 * height / max(width, height) + 0.4)
        self.coverage, self.samples = coverage_image(
            ax, np.zeros((height, width), bool), sample=sample
        )
        (self.outline,) = ax.plot([], [], color="crimson", lw=1.5, zorder=4)
        # The vertex handles, over the sample dots.
        (self.handles,) = ax.plot([], [], "o", color="crimson", ms=6, zorder=5)
        ax.set_xlim(-0.5, width + 0.5)
        ax.set_ylim(-0.5, height + 0.5)
        ax.set_aspect("equal")
        fig.tight_layout()
        self.figure, self.ax = fig, ax
        self._dragging: int | None = None
        for name, handler in (
            ("button_press_event", self._pressed),
            ("motion_notify_event", self._moved),
            ("button_release_event", self._released),
        ):
            fig.canvas.mpl_connect(name, handler)
        self.text = widgets.Text(
            description="vertices",
            placeholder="x,y x,y x,y ...",
            continuous_update=False,
            layout={"width": "36em"},
        )
        self.error = status_label()
        self.edge_table, self.active_edges = widgets.HTML(), widgets.HTML()
        self._canvas = figure_widget(fig)
        tables = widgets.VBox(
            [self.edge_table, self.active_edges], layout={"min_width": "0", "flex": "1 1 30em"}
        )
        self.widget = widgets.VBox(
            [
                self.text,
                self.error,
                widgets.HBox([self._canvas, tables], layout={"flex_flow": "row wrap"}),
            ]
        )
        self.result = None
        self.vertices = np.zeros((0, 2))
        self.text.observe(lambda change: self.edit(change["new"]), names="value")
        self.text.value = format_vertices(Polygon(vertices).vertices)
        if self.result is None:  # the starting polygon itself was refused
            raise ValueError(f"'vertices' were not accepted: {self.error.value}")

    def edit(self, text: str) -> None:
        """Scan-convert the polygon `text` describes, or show why it cannot be."""
        try:
            vertices = parse_vertices(text)
            result = scan_convert(vertices, self.width, self.height, sample=self.sample, trace=True)
        except (ValueError, TypeError) as error:
            say(self.error, str(error), error=True)
            return
        say(self.error, "")
        self.vertices, self.result = vertices, result
        self._draw()

    def _draw(self) -> None:
        closed = np.vstack([self.vertices, self.vertices[:1]])
        self.outline.set_data(closed[:, 0], closed[:, 1])
        self.handles.set_data(self.vertices[:, 0], self.vertices[:, 1])
        self.coverage.set_data(self.result.mask)
        if self.samples is not None:
            self.samples.show(self.result.mask)
        table = self.result.trace.of_kind("edge_table_built")
        self.edge_table.value = "<b>edge table</b>" + scroll_box(
            html_table(
                EDGE_COLUMNS,
                [
                    (
                        e.edge,
                        (e.x0, e.y0),
                        (e.x1, e.y1),
                        e.bucket,
                        e.row_end,
                        e.x,
                        e.dxdy,
                        e.winding,
                    )
                    for event in table
                    for e in event.edges
                    if not e.kept_for_topology
                ],
            )
        )
        rows = [
            (event.y, ", ".join(f"e{a.edge}: x={a.x:.4g}" for a in event.entries), event.swaps)
            for event in self.result.trace.of_kind("aet_sorted")
        ]
        self.active_edges.value = "<b>active edge table per row</b>" + scroll_box(
            html_table(("y", "AET (sorted by x)", "swaps"), rows)
        )
        refresh_figure(self.figure, self._canvas)

    def _pressed(self, event) -> None:
        if event.inaxes is not self.ax or event.xdata is None or not len(self.vertices):
            return
        distance = np.hypot(*(self.vertices - (event.xdata, event.ydata)).T)
        nearest = int(np.argmin(distance))
        self._dragging = nearest if distance[nearest] <= GRAB_RADIUS else None

    def _moved(self, event) -> None:
        if self._dragging is None or event.inaxes is not self.ax or event.xdata is None:
            return
        moved = self.vertices.copy()
        moved[self._dragging] = (event.xdata, event.ydata)
        closed = np.vstack([moved, moved[:1]])
        self.outline.set_data(closed[:, 0], closed[:, 1])  # preview only; release re-scans
        self.handles.set_data(moved[:, 0], moved[:, 1])
        self.figure.canvas.draw_idle()

    def _released(self, event) -> None:
        if self._dragging is None:
            return
        moved = self.vertices.copy()
        if event.xdata is not None:
            moved[self._dragging] = np.round((event.xdata, event.ydata), 2)
        self._dragging = None
        self.text.value = format_vertices(moved)

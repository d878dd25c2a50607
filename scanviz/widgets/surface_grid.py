"""The grid from above: the nine regions of the viewing cases, the viewpoint, the facet enumeration.

Shared by the grid-surface widgets (`scanviz.widgets.surfaces`): colours, checks and
`GridFromAbove`, drawn from the ``facets_enumerated`` event of a traced FPA run.
"""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib
import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.colors import to_rgba
from matplotlib.patches import Rectangle

from ..surfaces import GridSurface, View, floating_perimeter, viewing_case
from ..trace import Recorder, Trace
from ._common import WIDEST

# Region class k, and region k of the viewing cases, is tinted CLASS_COLORS[k - 1].
CLASS_COLORS = (*matplotlib.colormaps["Pastel1"].colors[:8], "#cccccc")  # its 9th is near white
CURRENT = "#ff8c00"  # the current edge, facet or curve
SMALLEST_NUMBER = 9.0  # points: facets whose number would be smaller are left unnumbered
MAX_PANELS = 4  # grids from above side by side
FAR = 4.0  # a viewpoint farther than this many domain sizes is drawn at that distance


# --- the grid from above --------------------------------------------------------------------


def check_surface_view(surface: object, view: object) -> None:
    if not isinstance(surface, GridSurface):
        raise TypeError(f"'surface' must be a scanviz.surfaces.GridSurface; got {surface!r}")
    if not isinstance(view, View):
        raise TypeError(f"'view' must be a scanviz.surfaces.View; got {view!r}")


def enumerated_event(trace: Trace):
    found = trace.of_kind("facets_enumerated")
    if not len(found):
        raise ValueError(
            "'trace' holds no facets_enumerated event: pass the trace of "
            "floating_perimeter(..., trace=True)"
        )
    return found[0]


def _check_event_grid(event, x: np.ndarray, y: np.ndarray) -> None:
    shape = np.shape(event.order)
    if shape != (y.size - 1, x.size - 1):
        raise ValueError(
            f"the enumeration has {shape[0]} x {shape[1]} facets (rows x columns) but the surface "
            f"{y.size - 1} x {x.size - 1}: the trace is not of this surface"
        )


class GridFromAbove:
    """The grid's domain from above, drawn on `axes` from a ``facets_enumerated`` event.

    Parameters
    ----------
    axes : matplotlib Axes
    x : (Nx,) ndarray of float
        The surface's x-planes.
    y : (Ny,) ndarray of float
        Its y-planes.
    event : FacetsEnumerated
        The viewing case, the viewpoint cell, each facet's number and class.
    view : View
        Where the viewpoint and its direction are drawn (a parallel view has
        no viewpoint: its direction is drawn into the domain).

    Attributes
    ----------
    cells : matplotlib PolyCollection
        One square per facet, in facet-number order (``cells`` path n - 1 is
        facet n), tinted by its region class.
    current : matplotlib Rectangle
        Around the current facet; hidden until `highlight` is called.
    """

    def __init__(self, axes, x, y, event, view: View) -> None:
        self.axes, self.event = axes, event
        self.x, self.y = np.asarray(x, np.float64), np.asarray(y, np.float64)
        _check_event_grid(event, self.x, self.y)
        order, classes = np.asarray(event.order), np.asarray(event.classes)
        rows, columns = np.nonzero(order > 0)
        by_number = np.argsort(order[rows, columns])
        self.rows, self.columns = rows[by_number], columns[by_number]
        self.classes = classes[self.rows, self.columns]
        x0, x1 = self.x[self.columns], self.x[self.columns + 1]
        y0, y1 = self.y[self.rows], self.y[self.rows + 1]
        squares = np.stack(
            [np.stack(c, axis=-1) for c in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))], 1
        )
        self.colors = np.array([to_rgba(CLASS_COLORS[c - 1]) for c in self.classes])
        self.cells = PolyCollection(squares, facecolors=self.colors, edgecolors="0.45", lw=0.6)
        axes.add_collection(self.cells)
        self._draw_regions_and_viewpoint(view)
        self._centres = np.stack([(x0 + x1) / 2, (y0 + y1) / 2], axis=1)
        self.numbered = False
        self.current = Rectangle((0, 0), 0, 0, fill=False, ec=CURRENT, lw=2.5, visible=False)
        axes.add_patch(self.current)
        axes.set_aspect("equal")
        axes.set_xlabel("x")
        axes.set_ylabel("y")
        axes.set_title(f"from above: viewing case {event.case}", fontsize=10)

    def _draw_regions_and_viewpoint(self, view: View) -> None:
        xmin, xmax, ymin, ymax = self.x[0], self.x[-1], self.y[0], self.y[-1]
        size = max(xmax - xmin, ymax - ymin)
        centre = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2])
        direction = np.array(view.direction[:2]) / np.linalg.norm(view.direction)
        if view.projection == "parallel":  # the viewpoint is at infinity behind the direction
            shown = centre - 1.2 * size * direction / max(np.linalg.norm(direction), 1e-12)
            label = "direction (parallel)"
        else:
            point = np.array(view.point[:2])
            offset = point - centre
            distance = np.linalg.norm(offset)
            shown = point if distance <= FAR * size else centre + offset * (FAR * size / distance)
            label = f"VP ({view.point[0]:.3g}, {view.point[1]:.3g}, {view.point[2]:.3g})"
            self.axes.plot(*shown, "o", color=CURRENT, mec="k", ms=8, zorder=5)
        low = np.minimum([xmin, ymin], shown) - 0.35 * size
        high = np.maximum([xmax, ymax], shown) + 0.35 * size
        for value in (xmin, xmax):
            self.axes.axvline(value, color="0.3", lw=1, ls="--", zorder=0.5)
        for value in (ymin, ymax):
            self.axes.axhline(value, color="0.3", lw=1, ls="--", zorder=0.5)
        middles = [(low + [xmin, ymin]) / 2, centre, (high + [xmax, ymax]) / 2]
        domain = (xmin, xmax, ymin, ymax)
        for at in ((middles[i][0], middles[j][1]) for i in range(3) for j in range(3)):
            region = viewing_case(domain, View((*at, 0.0), (0.0, 0.0, -1.0)))
            self.axes.text(
                *(at if region != 1 else (xmin, ymax)),  # the domain's own label on its corner
                str(region),
                ha="center",
                va="center",
                fontsize=9,
                color="0.25",
                fontweight="bold",
                zorder=4,
                bbox={"boxstyle": "circle,pad=0.25", "fc": CLASS_COLORS[region - 1], "ec": "0.4"},
            )
        arrow = direction * 0.6 * size  # short when looking steeply down
        self.axes.annotate(
            "",
            xy=shown + arrow,
            xytext=shown,
            zorder=5,
            arrowprops={"arrowstyle": "-|>", "color": CURRENT, "lw": 2},
        )
        self.axes.text(
            *(shown + [0, 0.08 * size]),
            label,
            fontsize=9,
            ha="center",
            va="bottom",
            bbox={"fc": "white", "ec": "none", "alpha": 0.7, "pad": 1},
        )
        self.axes.set_xlim(low[0], high[0])
        self.axes.set_ylim(low[1], high[1])

    def number_facets(self) -> None:
        """Write each facet's number in it, once the figure is laid out, if it fits at 9 pt.

        The numbers are left out where a facet is too small for them (`numbered` says which).
        """
        size = min(10.0, 1.3 * self._cell_points() / len(str(len(self.rows))))  # digit: 0.64 em
        self.numbered = size >= SMALLEST_NUMBER
        if self.numbered:
            for n, (cx, cy) in enumerate(self._centres, 1):
                self.axes.text(cx, cy, str(n), ha="center", va="center", fontsize=size)

    def _cell_points(self) -> float:
        """The side of the smallest facet in typographic points, as the axes are laid out now."""
        box = self.axes.get_window_extent()
        (x_low, x_high), (y_low, y_high) = self.axes.get_xlim(), self.axes.get_ylim()
        per_unit = min(box.width / (x_high - x_low), box.height / (y_high - y_low))  # equal aspect
        smallest = min(np.diff(self.x).min(), np.diff(self.y).min())
        return float(smallest * per_unit * 72 / self.axes.figure.dpi)

    def highlight(self, number: int | None, processed: int) -> None:
        """Outline facet `number` (None: none) and fade the facets after the first `processed`."""
        colors = self.colors.copy()
        colors[processed:, 3] = 0.15
        self.cells.set_facecolors(colors)
        self.current.set_visible(number is not None)
        if number is not None:
            row, column = self.rows[number - 1], self.columns[number - 1]
            self.current.set_xy((self.x[column], self.y[row]))
            self.current.set_width(self.x[column + 1] - self.x[column])
            self.current.set_height(self.y[row + 1] - self.y[row])


def _enumeration_event(surface: GridSurface, view: View):
    """The ``facets_enumerated`` event of `surface` and `view`, from a traced FPA run.

    The enumeration does not depend on the raster, so a small one serves.
    """
    recorder = Recorder(kinds=["facets_enumerated"])
    floating_perimeter(surface, view, 8, 8, trace=recorder)
    return recorder.trace()[0]


def plot_grid(surface: GridSurface, views: View | Sequence[View]):
    """The grid from above: nine regions, the viewpoint, facet numbers tinted by region class.

    Parameters
    ----------
    surface : GridSurface
    views : View or sequence of View
        One panel per view, side by side (at most 4).

    Returns
    -------
    matplotlib.figure.Figure
        `WIDEST` wide for several views; the facet numbers are those of the
        FPA's enumeration (1 is processed first), the circled digits the nine
        regions, each numbered with the viewing case of a viewpoint inside it.

    Raises
    ------
    TypeError
        If `surface` is not a GridSurface or a view is not a View.
    ValueError
        If there are no views or more than 4.

    Examples
    --------
    >>> from scanviz.surfaces import gaussian
    >>> figure = plot_grid(gaussian(5), [View((3, 4, 3), (-3, -4, -3)), View((0, -4, 2), (0, 1, -0.5))])
    >>> [axes.get_title() for axes in figure.axes]
    ['from above: viewing case 9', 'from above: viewing case 2']
    """
    from matplotlib.figure import Figure

    views = [views] if isinstance(views, View) else list(views)
    if not 1 <= len(views) <= MAX_PANELS:
        raise ValueError(f"'views' must hold 1 to {MAX_PANELS} views; got {len(views)}")
    for view in views:
        check_surface_view(surface, view)
    side = min(4.6, WIDEST / len(views))
    figure = Figure(figsize=(side * len(views), side))
    grids = [
        GridFromAbove(
            figure.add_subplot(1, len(views), k + 1),
            surface.x,
            surface.y,
            _enumeration_event(surface, view),
            view,
        )
        for k, view in enumerate(views)
    ]
    figure.tight_layout()
    for grid in grids:
        grid.number_facets()
    return figure


# --- the floating perimeter, step by step ---------------------------------------------------

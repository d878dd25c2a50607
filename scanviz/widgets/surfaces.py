"""Grid surfaces z = f(x, y): the enumeration from above, the floating perimeter, the horizon.

Four views, each drawn from what a traced run of `scanviz.surfaces` recorded
(the steppers live in `perimeter` and `horizon`, the grid from above in
`surface_grid`; all are importable from here):

* `plot_grid`: the XY domain from above, the four limit lines that cut the
  plane into the nine regions of the viewing cases, the viewpoint and its
  direction, and each facet's number in the enumeration, tinted by its
  region class (the ``facets_enumerated`` event).
* `PerimeterView` / `perimeter_stepper`: the Floating Perimeter Algorithm
  one event at a time (a facet starts, each of its edges is tested, the
  perimeter grows): the points tested so far, visible black and hidden light
  red, the current edge's points, and the perimeter arrays top[x], bottom[x]
  (step curves over the columns) and right[y], left[y] (over the rows),
  replayed from the ``perimeter_update`` events; beside it the grid from
  above with the current facet.
* `HorizonView` / `horizon_stepper`: the floating horizon curve by curve:
  the visible parts drawn so far, the current curve, and the upper and lower
  horizons replayed from the ``horizon_column`` events.
* `plot_results` and `plot_mismatch`: the FPA's hidden lines, the FHA's, the
  FPA's shaded surface and the z-buffer's render side by side, and the points
  where the FPA disagrees with the z-buffer (`compare_with_zbuffer`).

Screen panels put raster point (x, y) at the centre of its pixel square
(images on ``extent=(-0.5, W - 0.5, -0.5, H - 0.5)``, row 0 at the bottom),
so a perimeter curve passes through the pixels on the perimeter: a point is
hidden iff it lies strictly between both pairs of curves.
"""

from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgb
from matplotlib.patches import Patch, Rectangle

from ..surfaces import GridSurface, View, ZBufferComparison, surface_results
from ._common import WIDEST, pixel_image
from .horizon import HorizonView, horizon_stepper
from .perimeter import VISIBLE, PerimeterView, perimeter_stepper
from .surface_grid import CURRENT, GridFromAbove, check_surface_view, plot_grid

__all__ = [
    "GridFromAbove",
    "HorizonView",
    "PerimeterView",
    "horizon_stepper",
    "perimeter_stepper",
    "plot_grid",
    "plot_mismatch",
    "plot_results",
]

HOLE, STRUCTURAL, FALSE_HIDDEN, FALSE_VISIBLE = "#e00000", "#9e00c8", "#ff9900", "#0072b2"

# --- results beside the z-buffer ------------------------------------------------------------


def _screen_axes(axes, image, title: str) -> None:
    pixel_image(axes, image, offset=-0.5)
    axes.set_title(title, fontsize=10)
    axes.set_xticks([])
    axes.set_yticks([])


def plot_results(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    family: str = "x",
    shading: str = "phong",
):
    """The FPA's hidden lines, the FHA's, the FPA's shaded surface and the z-buffer's render.

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
        Raster size, each at least 2.
    family : {"x", "y"}
        The FHA's family of curves.
    shading : str
        The shading of the FPA's surface mode and of the z-buffer render.

    Returns
    -------
    matplotlib.figure.Figure
        Four panels; the surface panel's title counts the pixels where its
        facet differs from the z-buffer's.

    Examples
    --------
    >>> from scanviz.surfaces import gaussian
    >>> figure = plot_results(gaussian(5), View((3, 4, 3), (-3, -4, -3)), 24, 24)
    >>> [axes.get_title().split(":")[0] for axes in figure.axes]
    ['FPA hidden lines', 'FHA (family x)', 'FPA hidden surfaces', 'z-buffer']
    """
    from matplotlib.figure import Figure

    check_surface_view(surface, view)
    results = surface_results(surface, view, width, height, family=family, shading=shading)
    panel = WIDEST / 2  # two panels a row, two rows
    figure = Figure(figsize=(WIDEST, 2 * (panel * max(height / width, 0.5) + 0.5)))
    panels = (
        (results.lines.image, f"FPA hidden lines:\n{results.lines.stats.segments} segments"),
        (results.horizon.image, f"FHA (family {family}):\n{results.horizon.stats.segments} parts"),
        (results.shaded.image, f"FPA hidden surfaces:\n{results.facets_differ} px differ"),
        (results.zbuffer.image, "z-buffer:\nrender(surface.scene(...))"),
    )
    for k, (image, title) in enumerate(panels):
        _screen_axes(figure.add_subplot(2, 2, k + 1), image, title)
    figure.tight_layout()
    return figure


def plot_mismatch(
    comparison: ZBufferComparison, *, region: tuple[int, int, int, int] | None = None
):
    """The FPA's lines with the points where it disagrees with the z-buffer, optionally zoomed.

    Parameters
    ----------
    comparison : ZBufferComparison
        From `compare_with_zbuffer`.
    region : (x_start, y_start, x_end, y_end), optional
        A second panel shows these pixels (half-open), outlined on the first.

    Returns
    -------
    matplotlib.figure.Figure
        Black: points both show; light grey: points both hide; red: holes
        (hidden by the FPA, shown by the z-buffer, no earlier facet covers
        them), purple where structural (inside the exact spans too);
        orange: other false hidden points; blue: false visible points. On
        the full view each mismatch is also circled.

    Raises
    ------
    TypeError
        If `comparison` is not a ZBufferComparison.
    ValueError
        If `region` is not 4 ints inside the raster with x_start < x_end and y_start < y_end.

    Examples
    --------
    >>> from scanviz.surfaces import compare_with_zbuffer, gaussian
    >>> c = compare_with_zbuffer(gaussian(5), View((3, 4, 3), (-3, -4, -3)), 24, 24)
    >>> plot_mismatch(c).axes[0].get_title().startswith("FPA against the z-buffer")
    True
    """
    from matplotlib.figure import Figure

    if not isinstance(comparison, ZBufferComparison):
        raise TypeError(f"'comparison' must be a ZBufferComparison; got {comparison!r}")
    fpa = comparison.fpa
    height, width = fpa.lines.shape
    if region is not None:
        region = _check_region(region, width, height)
    points, shown, zshown = fpa.points, fpa.visible, comparison.zbuffer_visible
    hole, structural = comparison.hole, comparison.structural
    kinds = (
        (~shown & ~zshown, "#cfcfcf"),
        (shown & zshown, VISIBLE),
        (~shown & zshown & ~hole, FALSE_HIDDEN),
        (shown & ~zshown, FALSE_VISIBLE),
        (hole, HOLE),
        (structural, STRUCTURAL),
    )
    image = np.ones((height, width, 3))
    for chosen, color in kinds:  # later kinds are drawn over earlier ones
        image[points[chosen, 1], points[chosen, 0]] = to_rgb(color)
    columns = 2 if region is not None else 1
    side = WIDEST / 2 if region is not None else 4.75
    figure = Figure(figsize=(side * columns, side * max(height / width, 0.5) + 1.1))
    axes = figure.add_subplot(1, columns, 1)
    _screen_axes(axes, image, f"FPA against the z-buffer (case {comparison.case})")
    wrong = points[(shown != zshown)]
    axes.scatter(wrong[:, 0], wrong[:, 1], s=60, facecolors="none", edgecolors=HOLE, lw=0.8)
    if region is not None:
        x0, y0, x1, y1 = region
        axes.add_patch(
            Rectangle((x0 - 0.5, y0 - 0.5), x1 - x0, y1 - y0, fill=False, ec=CURRENT, lw=1.5)
        )
        zoomed = figure.add_subplot(1, 2, 2)
        _screen_axes(zoomed, image, f"pixels x {x0}..{x1 - 1}, y {y0}..{y1 - 1}")
        zoomed.set_xlim(x0 - 0.5, x1 - 0.5)
        zoomed.set_ylim(y0 - 0.5, y1 - 0.5)
    handles = [
        Patch(fc=HOLE, label=f"hole ({comparison.holes - comparison.structural_holes})"),
        Patch(fc=STRUCTURAL, label=f"structural hole ({comparison.structural_holes})"),
        Patch(
            fc=FALSE_HIDDEN,
            label=f"other false hidden ({comparison.false_hidden - comparison.holes})",
        ),
        Patch(fc=FALSE_VISIBLE, label=f"false visible ({comparison.false_visible})"),
    ]
    figure.legend(handles=handles, loc="lower center", ncol=2, fontsize=9)
    figure.tight_layout(rect=(0, 0.12, 1, 1))
    return figure


def _check_region(region: object, width: int, height: int) -> tuple[int, int, int, int]:
    try:
        x0, y0, x1, y1 = (int(v) for v in region)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise TypeError(
            f"'region' must be 4 ints (x_start, y_start, x_end, y_end); got {region!r}"
        ) from None
    if not (0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height):
        raise ValueError(
            f"'region' must satisfy 0 <= x_start < x_end <= {width} and "
            f"0 <= y_start < y_end <= {height}; got {region!r}"
        )
    return x0, y0, x1, y1

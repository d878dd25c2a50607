"""Views of one scan conversion's samples: `plot_scan` (static) and `sampling_view` (corner/center toggle)."""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..conventions import SAMPLE_MODES, check_raster_size, sample_offset
from ..geometry import Polygon
from ..raster import scan_convert
from ._common import WIDEST, DisplaysWidget, draw_outline, new_figure
from .stepper import SampleDots, coverage_image, figure_widget, refresh_figure


def plot_scan(polygon, result, *, sample: str = "corner", step: int | None = None, ax=None):
    """Draw a scan conversion on a pixel grid (y up, row 0 at the bottom).

    Covered pixels are filled; each pixel's sample point is a dot, filled
    dark when inside and hollow grey when outside (rasters up to
    `DOTS_LIMIT` pixels a side); the polygon's contours are drawn with
    arrows showing their direction. With a trace and `step`, only the spans
    emitted in the first `step` events are shown and the current scanline is
    marked.

    Parameters
    ----------
    polygon : Polygon or array_like
    result : ScanResult
        From `scanviz.scan_convert` (with ``trace=True`` to use `step`).
    sample : {"corner", "center"}
        The sample mode `result` was made with (where the dots go).
    step : int, optional
        Show the state after this many trace events.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    import matplotlib.pyplot as plt

    polygon = Polygon(polygon)
    height, width = result.mask.shape
    if ax is None:
        _, ax = plt.subplots(
            figsize=(min(0.45 * width + 1, WIDEST), min(0.45 * height + 1, WIDEST))
        )
    covered = result.mask
    row = None
    if step is not None and result.trace is not None:
        covered = result.trace.image_at(step, width, height) > 0
        rows = [e.y for e in result.trace[:step] if hasattr(e, "y")]
        row = rows[-1] if rows else None
    coverage_image(ax, covered, alpha=0.9, sample=sample)
    draw_outline(ax, polygon.contours, arrows=True)
    if row is not None:
        ax.axhline(row + sample_offset(sample), color="orange", linewidth=2, zorder=5)
    ax.set_xlim(0, width)
    ax.set_ylim(0, height)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y (up)")
    return ax


WHERE = {
    "corner": (
        "its lower-left corner (x, y), so each filled square lies up and to the right of its "
        "sample and the fill sits about half a pixel up and right of the polygon"
    ),
    "center": (
        "its centre (x + ½, y + ½), so each filled square is centred on its sample and the "
        "fill sits over the polygon"
    ),
}


class SamplingView(DisplaysWidget):
    """A polygon's fill under corner or center sampling, with the sample points that decide it.

    The pixel squares a scan conversion fills, each pixel's sample point as
    a dot (filled dark inside, hollow grey outside), the polygon's outline,
    and a toggle between ``sample="corner"`` and ``sample="center"`` that
    shows `scan_convert`'s result for that mode and says what moved. Pixels
    filled in only one of the two modes are outlined: green where the mode
    shown fills them, orange where the other one does.

    Parameters
    ----------
    polygon : Polygon or array_like
    width, height : int
        Raster size.

    Attributes
    ----------
    widget : ipywidgets.VBox
    toggle : ipywidgets.ToggleButtons
        "corner" or "center"; setting it redraws in place.
    results : dict of str to ScanResult
        ``scan_convert(polygon, width, height, sample=mode)`` for both modes.
    coverage : matplotlib AxesImage
        Its array is the mask of the mode shown.
    samples : SampleDots or None
        The sample points of the mode shown (None above `DOTS_LIMIT` pixels a side).
    only_here, only_there : matplotlib PolyCollection
        The squares filled only in the mode shown, and only in the other one.
    explanation : ipywidgets.HTML
        Where the samples are and what that did to the fill, in plain words.

    Examples
    --------
    >>> view = sampling_view([(1, 1), (5, 1), (5, 4)], 6, 5)
    >>> xs, ys = view.samples.inside.get_data()  # row 1 first: samples (1, 1) ... (4, 1)
    >>> int(view.coverage.get_array().sum()), xs[:4].tolist(), ys[:4].tolist()
    (7, [1.0, 2.0, 3.0, 4.0], [1.0, 1.0, 1.0, 1.0])
    >>> view.toggle.value = "center"
    >>> xs, ys = view.samples.inside.get_data()  # row 1 first: (1.5, 1.5) is outside now
    >>> int(view.coverage.get_array().sum()), xs[:3].tolist(), ys[:3].tolist()
    (6, [2.5, 3.5, 4.5], [1.5, 1.5, 1.5])
    >>> view  # doctest: +SKIP
    """

    def __init__(self, polygon: object, width: int, height: int) -> None:
        from matplotlib.collections import PolyCollection

        self.polygon = Polygon(polygon)
        self.width, self.height = check_raster_size(width, height)
        self.results = {
            mode: scan_convert(self.polygon, self.width, self.height, sample=mode)
            for mode in SAMPLE_MODES
        }
        size = min(0.4 * max(self.width, self.height) + 1.2, 6.0)
        aspect = self.height / max(self.width, self.height, 1)
        self.figure, (ax,) = new_figure(1, width=size, height=size * aspect + 0.5)
        shape = (self.height, self.width)
        self.coverage, _ = coverage_image(ax, np.zeros(shape, bool))
        self.samples = SampleDots(ax, shape) if SampleDots.fit(shape) else None
        self.only_here = PolyCollection([], facecolors="none", edgecolors="green", lw=2, zorder=3.5)
        self.only_there = PolyCollection(
            [], facecolors="none", edgecolors="darkorange", linestyles="--", lw=1.5, zorder=3.5
        )
        ax.add_collection(self.only_here)
        ax.add_collection(self.only_there)
        draw_outline(ax, self.polygon.contours)
        ax.set(xlim=(0, self.width), ylim=(0, self.height), aspect="equal")
        self.title = ax.set_title("", fontsize=10)
        self.figure.tight_layout()
        self.ax = ax
        self.toggle = widgets.ToggleButtons(
            options=list(SAMPLE_MODES), value="corner", description="sample at"
        )
        self.explanation = widgets.HTML(layout={"max_width": "44em"})
        self._canvas = figure_widget(self.figure)
        self.widget = widgets.VBox([self.toggle, self.explanation, self._canvas])
        self.toggle.observe(lambda change: self.show(change["new"]), names="value")
        self.show("corner")

    def show(self, sample: str) -> None:
        """Show the fill, sample points and explanation of `sample` ("corner" or "center")."""
        mask = self.results[sample].mask
        other = "center" if sample == "corner" else "corner"
        other_mask = self.results[other].mask
        self.coverage.set_data(mask)
        if self.samples is not None:
            self.samples.offset = sample_offset(sample)
            self.samples.show(mask)
        self.only_here.set_verts(_squares(mask & ~other_mask))
        self.only_there.set_verts(_squares(other_mask & ~mask))
        self.title.set_text(f'sample="{sample}": {int(mask.sum())} pixels inside')
        joined, left = int((mask & ~other_mask).sum()), int((other_mask & ~mask).sum())
        moved = (
            f"Compared with {other} sampling, {_pixels(joined)} {'is' if joined == 1 else 'are'} "
            f"filled only here (green) and {_pixels(left)} only there (orange dashes)."
            if joined or left
            else f"Here {other} sampling fills the very same pixels."
        )
        self.explanation.value = (
            f"<b>{sample.capitalize()} sampling</b>: pixel (x, y) is inside when its sample "
            f"point is, and its sample is {WHERE[sample]}. {moved}"
        )
        refresh_figure(self.figure, self._canvas)


def _pixels(count: int) -> str:
    return f"{count} pixel{'s' * (count != 1)}"


def _squares(where: np.ndarray) -> list[np.ndarray]:
    """The unit squares of the pixels set in `where`, as polygons for a PolyCollection."""
    ys, xs = np.nonzero(where)
    corners = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], float)
    return [corners + (x, y) for x, y in zip(xs, ys, strict=True)]


def sampling_view(polygon: object, width: int, height: int) -> SamplingView:
    """Toggle between corner and center sampling of `polygon` and see the fill move.

    Pixel squares, each pixel's sample point as a dot (filled dark inside,
    hollow grey outside) and the polygon outline; a corner/center toggle
    re-shows `scan_convert`'s result with that sample mode and says in a
    sentence what moved. See `SamplingView`.

    Parameters
    ----------
    polygon : Polygon or array_like
    width, height : int
        Raster size.

    Returns
    -------
    SamplingView
        Display it (or its ``.widget``) in a notebook.

    Examples
    --------
    >>> view = sampling_view([(0.6, 0.6), (4.6, 0.6), (4.6, 3.6)], 6, 5)
    >>> view.toggle.value = "center"
    >>> "Center sampling" in view.explanation.value
    True
    """
    return SamplingView(polygon, width, height)

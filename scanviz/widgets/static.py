"""Static matplotlib views of a scan conversion: pixel grid, samples, polygon, spans."""

from __future__ import annotations

import numpy as np

from ..conventions import sample_offset
from ..geometry import Polygon


def plot_scan(polygon, result, *, sample: str = "corner", step: int | None = None, ax=None):
    """Draw a scan conversion on a pixel grid (y up, row 0 at the bottom).

    Covered pixels are filled, sample points are dots (filled when covered),
    the polygon's contours are drawn with arrows showing their direction.
    With a trace and `step`, only the spans emitted in the first `step`
    events are shown and the current scanline is marked.

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

    from .stepper import coverage_image

    polygon = Polygon(polygon)
    height, width = result.mask.shape
    if ax is None:
        _, ax = plt.subplots(figsize=(min(0.45 * width + 1, 9), min(0.45 * height + 1, 9)))
    covered = result.mask
    row = None
    if step is not None and result.trace is not None:
        covered = result.trace.image_at(step, width, height) > 0
        rows = [e.y for e in result.trace[:step] if hasattr(e, "y")]
        row = rows[-1] if rows else None
    coverage_image(ax, covered, alpha=0.9)
    offset = sample_offset(sample)
    ys, xs = np.mgrid[0:height, 0:width]
    ax.scatter(xs[~covered] + offset, ys[~covered] + offset, s=6, color="0.6", zorder=3)
    ax.scatter(xs[covered] + offset, ys[covered] + offset, s=10, color="navy", zorder=3)
    for contour in polygon.contours:
        closed = np.vstack([contour, contour[:1]])
        ax.plot(closed[:, 0], closed[:, 1], color="crimson", linewidth=1.5, zorder=4)
        for start, end in zip(closed[:-1], closed[1:], strict=True):
            middle, half = (start + end) / 2, (end - start) * 0.04
            ax.annotate(
                "",
                xy=middle + half,
                xytext=middle - half,
                zorder=4,
                arrowprops={"arrowstyle": "-|>", "color": "crimson"},
            )
    if row is not None:
        ax.axhline(row + offset, color="orange", linewidth=2, zorder=5)
    ax.set_xlim(0, width)
    ax.set_ylim(0, height)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y (up)")
    return ax

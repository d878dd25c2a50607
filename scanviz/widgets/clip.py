"""A static view of one polygon's clipping: the input, the view volume, the clipped polygon."""

from __future__ import annotations

import numpy as np

from ..trace.events import PolygonClipped
from ..transform.clip import CLIP_PLANES


def _projected(points: np.ndarray, axes: tuple[int, int]) -> np.ndarray:
    """Two coordinates over w of clip-space points in front of the eye (w > 0; others dropped)."""
    points = np.asarray(points, dtype=float).reshape(-1, 4)
    ahead = points[points[:, 3] > 0]
    return ahead[:, list(axes)] / ahead[:, 3:4]


VIEWS = (  # (coordinates, the visible range's corner and size, axis labels)
    ((0, 1), (-1, -1, 2, 2), ("x / w", "y / w")),
    ((0, 2), (-1, 0, 2, 1), ("x / w", "z / w")),
)


def plot_clip(clip_points, event: PolygonClipped):
    """Draw a polygon before and after clipping: from the front (x/w, y/w) and from above (x/w, z/w).

    The grey area is the visible part of the view volume, -1 <= x/w, y/w <= 1
    and 0 <= z/w <= 1; the dashed outline is the input polygon (its vertices
    with w > 0), the filled one the clipped polygon of `event`. The title gives
    the verdict and the vertex count after each plane.

    Parameters
    ----------
    clip_points : (N, 4) array_like of float
        The polygon's clip-space vertices, as `scanviz.transform.clip_polygon` took them.
    event : PolygonClipped
        Its ``polygon_clipped`` event.

    Returns
    -------
    matplotlib Figure
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon as Patch
    from matplotlib.patches import Rectangle

    if not isinstance(event, PolygonClipped):
        raise TypeError(f"'event' must be a PolygonClipped event; got {type(event).__name__}")
    with plt.ioff():
        figure, axes = plt.subplots(1, 2, figsize=(8, 3.8))
    clipped = np.array(event.vertices, dtype=float).reshape(-1, 4)
    for ax, (coordinates, (x, y, w, h), (xlabel, ylabel)) in zip(axes, VIEWS, strict=True):
        ax.add_patch(Rectangle((x, y), w, h, color="0.9", zorder=0))
        before, after = _projected(clip_points, coordinates), _projected(clipped, coordinates)
        if len(before):
            ax.add_patch(Patch(before, closed=True, fill=False, ls="--", color="0.35", zorder=1))
            ax.plot(*before.T, "o", color="0.35", ms=4)
        if len(after):
            ax.add_patch(Patch(after, closed=True, alpha=0.45, color="tab:orange", zorder=2))
            ax.plot(*after.T, "o", color="tab:red", ms=5, zorder=3)
        shown = np.vstack([before, after, [[x, y], [x + w, y + h]]])
        low, high = shown.min(axis=0) - 0.2, shown.max(axis=0) + 0.2
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_aspect("equal")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
    counts = ", ".join(f"{plane} {n}" for plane, n in zip(CLIP_PLANES, event.counts, strict=False))
    figure.suptitle(
        f"{event.verdict}" + (f"; vertices after {counts}" if counts else ""), fontsize=9
    )
    return figure

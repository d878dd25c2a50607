"""Anti-aliased feature edges of a render: post-anti-aliasing of what `render(edges=True)` draws.

`render(scene, w, h, edges=True)` paints each silhouette, boundary and crease
edge as a black midpoint line where the z-buffer shows it
(`scanviz.pipeline.feature_lines.feature_edge_runs`). `feature_edge_segments` turns
those depth-tested pixels back into segments, one per run of shown pixels,
with the edge's own sub-pixel ends; `antialiased_edges` blends them over the
rendered image with the line table of §4.8 (`post_antialias`) or DISLOP_L
areas. Nothing is re-rendered: the picture and its depth come from the
result, as the dissertation's post-process takes an already rendered image.
"""

from __future__ import annotations

import numpy as np

from ..conventions import check_choice
from ..pipeline.feature_lines import feature_edge_runs
from ..scene.model import Scene
from .line import dislop_line
from .post import post_antialias

METHODS = ("post", "dislop")


def feature_edge_segments(scene: Scene, depth: np.ndarray) -> np.ndarray:
    """The visible runs of the scene's feature edges, as (N, 2, 2) segments in pixels.

    A run is a stretch of consecutive midpoint-line pixels the depth test
    shows. Its segment follows the edge's exact screen line, from half a pixel
    step before its first pixel to half a step after its last (clipped to the
    edge's ends), so a wholly visible edge keeps its own sub-pixel ends.

    Parameters
    ----------
    scene : Scene
    depth : (H, W) ndarray
        The render's depth (`RenderResult.depth`), which the edges are tested against.
    """
    height, width = np.shape(depth)
    segments = []
    for run in feature_edge_runs(scene, depth, width, height):
        if not run.shown.any():
            continue
        count = len(run.along)
        half = 0.5 / (count - 1) if count > 1 else 0.0
        # starts and ends of the runs of True in `shown`
        edges = np.diff(np.concatenate([[0], run.shown.astype(np.int8), [0]]))
        for first, last in zip(
            np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1, strict=True
        ):
            t0 = max(run.along[first] - half, 0.0)
            t1 = min(run.along[last] + half, 1.0)
            a, b = run.ends
            segments.append([a + t0 * (b - a), a + t1 * (b - a)])
    return np.array(segments, dtype=np.float64).reshape(-1, 2, 2)


def antialiased_edges(
    scene: Scene,
    result,
    *,
    method: str = "post",
    color: object = (0.0, 0.0, 0.0),
) -> np.ndarray:
    """The render's image with its feature edges anti-aliased over it, (H, W, 3) in [0, 1].

    Parameters
    ----------
    scene : Scene
        The scene `result` was rendered from.
    result : RenderResult
        A render with ``edges=False`` (its image is the background the edges
        are blended over; with ``edges=True`` the aliased edges would stay).
    method : {"post", "dislop"}
        "post": the line table of §4.8 (`post_antialias`), three table pixels
        per column; "dislop": each segment's DISLOP_L areas, combined as
        1 - prod(1 - a) and blended once.
    color : RGB
        The edges' colour (black, as `render(edges=True)`).

    Raises
    ------
    ValueError
        An unknown `method`; `result` rendered with ``edges=True``.

    Examples
    --------
    >>> from scanviz import render
    >>> from scanviz.scene.builtin import builtin_scene
    >>> scene = builtin_scene("umbc_zbuffer")
    >>> plain = render(scene, 40, 30)
    >>> smooth = antialiased_edges(scene, plain)
    >>> bool((smooth <= plain.image + 1e-12).all())  # black edges only darken
    True
    """
    check_choice("method", method, METHODS)
    if result.record is not None and result.record.edges is not None:
        raise ValueError(
            "'result' must be rendered with edges=False: its aliased edges would stay under the "
            "anti-aliased ones"
        )
    segments = feature_edge_segments(scene, result.depth)
    image = np.array(result.image, dtype=np.float64)
    if method == "post":
        return post_antialias(image, segments, kind="line", color=color)
    height, width = result.depth.shape
    clear = np.ones((height, width))
    for p0, p1 in segments:
        clear *= 1.0 - dislop_line(p0, p1, width, height)
    covered = (1.0 - clear)[..., None]
    return covered * np.asarray(color, dtype=np.float64) + (1.0 - covered) * image

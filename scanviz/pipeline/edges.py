"""Feature edges over the image: silhouettes, boundaries and creases, depth-tested midpoint lines."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..progress import progress
from ..scene.model import Scene
from ..transform import clip_from_eye, eye_from_world
from .prepare import _object_in_world
from .shade import _viewer

PROGRESS_EDGES = 20000  # feature edges drawn one by one: a bar above this many

EDGE_DEPTH_TOLERANCE = 1e-4  # NDC depth by which an edge pixel may lie behind the surface drawn


def _draw_feature_edges(scene: Scene, image, depth, width: int, height: int) -> int:
    """Draw every object's silhouette, boundary and crease edges where the z-buffer shows them.

    Edges with an end behind the eye plane are left out. Returns the pixels drawn.
    """
    drawn = 0
    for run in feature_edge_runs(scene, depth, width, height):
        image[run.ys[run.shown], run.xs[run.shown]] = 0.0
        drawn += int(run.shown.sum())
    return drawn


@dataclass(frozen=True)
class EdgeRun:
    """One feature edge as drawn: its screen ends and its midpoint-line pixels, depth-tested.

    ``ends`` (2, 2): the edge's endpoints in pixels; ``xs``, ``ys``: the pixels of
    the midpoint line from floor(ends[0]) to floor(ends[1]) that lie on the
    raster; ``along``: each pixel's parameter in [0, 1] along the edge;
    ``shown``: the pixels the z-buffer shows (within `EDGE_DEPTH_TOLERANCE`).
    """

    ends: np.ndarray
    xs: np.ndarray
    ys: np.ndarray
    along: np.ndarray
    shown: np.ndarray


def feature_edge_runs(scene: Scene, depth, width: int, height: int) -> Iterator[EdgeRun]:
    """Every object's silhouette, boundary and crease edge with its depth-tested pixels.

    `render(edges=True)` paints the shown pixels black; `scanviz.antialias.edges`
    post-anti-aliases the shown runs instead. Edges with an end behind the eye
    plane, or beyond +-2**20 pixels, are left out.
    """
    from ..raster.lines import midpoint_line
    from ..shading import feature_edges

    clip_from_world = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    eye, view_dir = _viewer(scene.camera)
    for obj in scene.objects:
        o = _object_in_world(obj)
        found = feature_edges(o.world, o.flat_faces, eye, view_dir=view_dir)
        pairs = np.concatenate([found["silhouette"], found["boundary"], found["crease"]])
        clip = np.hstack([o.world, np.ones((len(o.world), 1))]) @ clip_from_world.T
        with progress(len(pairs), "feature edges", threshold=PROGRESS_EDGES) as bar:
            for a, b in pairs:
                bar.update(1)
                if clip[a, 3] <= 0 or clip[b, 3] <= 0:
                    continue
                ends = np.array(
                    [
                        (
                            (clip[v, 0] / clip[v, 3] + 1) / 2 * width,
                            (clip[v, 1] / clip[v, 3] + 1) / 2 * height,
                        )
                        for v in (a, b)
                    ]
                )
                if np.abs(ends).max() > 2**20:
                    continue
                xs, ys = midpoint_line(*(int(np.floor(c)) for c in ends.ravel()))
                along = np.linspace(0.0, 1.0, len(xs))
                z = clip[a, 2] / clip[a, 3] + along * (
                    clip[b, 2] / clip[b, 3] - clip[a, 2] / clip[a, 3]
                )
                inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
                xs, ys, z, along = xs[inside], ys[inside], z[inside], along[inside]
                shown = z <= depth[ys, xs] + EDGE_DEPTH_TOLERANCE
                yield EdgeRun(ends, xs, ys, along, shown)

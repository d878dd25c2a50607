"""Feature edges over the image: silhouettes, boundaries and creases, depth-tested midpoint lines."""

from __future__ import annotations

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
    from ..raster.lines import midpoint_line
    from ..shading import feature_edges

    clip_from_world = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    eye, view_dir = _viewer(scene.camera)
    drawn = 0
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
                ends = [
                    (
                        (clip[v, 0] / clip[v, 3] + 1) / 2 * width,
                        (clip[v, 1] / clip[v, 3] + 1) / 2 * height,
                    )
                    for v in (a, b)
                ]
                if max(abs(c) for end in ends for c in end) > 2**20:
                    continue
                xs, ys = midpoint_line(*(int(np.floor(c)) for end in ends for c in end))
                along = np.linspace(0.0, 1.0, len(xs))
                z = clip[a, 2] / clip[a, 3] + along * (
                    clip[b, 2] / clip[b, 3] - clip[a, 2] / clip[a, 3]
                )
                inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
                xs, ys, z = xs[inside], ys[inside], z[inside]
                shown = z <= depth[ys, xs] + EDGE_DEPTH_TOLERANCE
                image[ys[shown], xs[shown]] = 0.0
                drawn += int(shown.sum())
    return drawn

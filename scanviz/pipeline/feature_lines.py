"""Feature edges over the image: silhouettes, boundaries and creases, depth-tested midpoint lines.

Each edge's midpoint line runs from floor(end 0) to floor(end 1), but only its
pixels on the raster are walked (`scanviz.raster.lines.line_windows`, all
edges of a chunk in one compiled call), so an edge costs its pixels on the
raster, not its length: an edge reaching 2**20 pixels off screen costs nothing
more. With ``midpoint_step`` replaced (`scanviz.steps`) the reference
`midpoint_line` walks each whole line instead.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from .. import steps
from ..progress import progress
from ..scene.model import Scene
from ..transform import clip_from_eye, eye_from_world
from .prepare import _object_in_world
from .shade import _viewer

PROGRESS_EDGES = 20000  # feature edges drawn one by one: a bar above this many
EDGE_CHUNK = 4096  # edges per compiled call: the bar moves, and Ctrl-C stops, between chunks

EDGE_DEPTH_TOLERANCE = 1e-4  # NDC depth by which an edge pixel may lie behind the surface drawn


def _draw_feature_edges(scene: Scene, image, depth, width: int, height: int) -> int:
    """Draw every object's silhouette, boundary and crease edges where the z-buffer shows them.

    Edges with an end behind the eye plane are left out. Returns the pixels drawn.
    """
    drawn = 0
    for chunk in _edge_chunks(scene, depth, width, height):
        image[chunk.ys[chunk.shown], chunk.xs[chunk.shown]] = 0.0
        drawn += int(chunk.shown.sum())
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

    `render(edges=True)` paints the shown pixels black; `scanviz.antialias.post_edges`
    post-anti-aliases the shown runs instead. Edges with an end behind the eye
    plane, or beyond +-2**20 pixels, are left out.
    """
    for chunk in _edge_chunks(scene, depth, width, height):
        for i, ends in enumerate(chunk.ends):
            run = slice(chunk.offsets[i], chunk.offsets[i + 1])
            yield EdgeRun(ends, chunk.xs[run], chunk.ys[run], chunk.along[run], chunk.shown[run])


@dataclass(frozen=True)
class _EdgeChunk:
    """Edges as `EdgeRun`s in flat arrays: edge i's pixels are [offsets[i], offsets[i + 1])."""

    ends: np.ndarray  # (K, 2, 2)
    offsets: np.ndarray  # (K + 1,)
    xs: np.ndarray
    ys: np.ndarray
    along: np.ndarray
    shown: np.ndarray


def _edge_chunks(scene: Scene, depth, width: int, height: int) -> Iterator[_EdgeChunk]:
    """The feature edges of every object, `EDGE_CHUNK` at a time, in order."""
    from ..shading import feature_edges

    clip_from_world = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    eye, view_dir = _viewer(scene.camera)
    for obj in scene.objects:
        o = _object_in_world(obj)
        found = feature_edges(o.world, o.flat_faces, eye, view_dir=view_dir)
        pairs = np.concatenate([found["silhouette"], found["boundary"], found["crease"]])
        clip = np.hstack([o.world, np.ones((len(o.world), 1))]) @ clip_from_world.T
        with progress(len(pairs), "feature edges", threshold=PROGRESS_EDGES) as bar:
            for start in range(0, len(pairs), EDGE_CHUNK):
                chunk = pairs[start : start + EDGE_CHUNK]
                yield _chunk_pixels(clip, chunk.reshape(-1, 2), depth, width, height)
                bar.update(len(chunk))


def _chunk_pixels(clip, pairs, depth, width: int, height: int) -> _EdgeChunk:
    """The edges `pairs` (K, 2) of vertices with clip coordinates `clip`: ends, pixels, depths."""
    from ..raster.lines import line_windows

    a, b = pairs[:, 0], pairs[:, 1]
    pairs = pairs[(clip[a, 3] > 0) & (clip[b, 3] > 0)]  # both ends in front of the eye plane
    w = clip[pairs, 3]
    ends = np.stack(
        [(clip[pairs, 0] / w + 1) / 2 * width, (clip[pairs, 1] / w + 1) / 2 * height], axis=2
    )
    kept = ~(np.abs(ends).max(axis=(1, 2)) > 2**20)
    ends, pairs, w = ends[kept], pairs[kept], w[kept]
    pixel_ends = np.floor(ends).astype(np.int64).reshape(-1, 4)
    if "midpoint_step" in steps.replaced():  # the reference walks each whole line with it
        walks = [_reference_window(*line, width, height) for line in pixel_ends.tolist()]
        offsets = np.cumsum([0] + [len(walk[0]) for walk in walks])
        xs, ys, index = (
            np.concatenate([walk[n] for walk in walks] + [np.zeros(0, np.int64)]) for n in range(3)
        )
    else:
        offsets, xs, ys, index = line_windows(pixel_ends, width, height)
    edge = np.repeat(np.arange(len(pairs)), np.diff(offsets))
    # As np.linspace(0, 1, n)[index], n the whole line's pixel count: index * (1 / (n - 1)).
    pixel_count = np.abs(pixel_ends[:, 2:] - pixel_ends[:, :2]).max(axis=1) + 1
    along = index * (1.0 / np.maximum(pixel_count - 1, 1))[edge]
    along[(index == pixel_count[edge] - 1) & (index > 0)] = 1.0  # linspace ends exactly at 1
    z_a, z_b = clip[pairs[:, 0], 2] / w[:, 0], clip[pairs[:, 1], 2] / w[:, 1]
    z = z_a[edge] + along * (z_b[edge] - z_a[edge])
    shown = z <= depth[ys, xs] + EDGE_DEPTH_TOLERANCE
    return _EdgeChunk(ends, offsets, xs, ys, along, shown)


def _reference_window(x0: int, y0: int, x1: int, y1: int, width: int, height: int):
    """`line_windows` of one line by the reference: the whole line walked, then clipped."""
    from ..raster.lines import midpoint_line

    xs, ys = midpoint_line(x0, y0, x1, y1)
    inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
    return xs[inside], ys[inside], np.flatnonzero(inside)

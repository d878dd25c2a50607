"""Faces of polygon meshes as flat arrays, validated at once, and their Newell normals.

Shared by the stages that walk faces (culling, clipping, normals, feature
edges), so a 50,000-face mesh is flattened with a handful of numpy calls
rather than one check per face.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class FaceCorners(NamedTuple):
    """Every corner of every face, in face order (C corners, F faces).

    corner : (C,) int64 vertex index of each corner
    following : (C,) int64 vertex index of the next corner around its face
    face : (C,) int64 face of each corner
    starts : (F,) int64 first corner of each face
    """

    corner: np.ndarray
    following: np.ndarray
    face: np.ndarray
    starts: np.ndarray


def face_corners(faces: object, vertex_count: int) -> FaceCorners:
    """Flatten and validate `faces`: an (F, k) int array or a sequence of 1-D int arrays, k >= 3.

    A `FaceCorners` passes through unchanged, so a caller that flattens once can
    hand the result to every stage.

    >>> c = face_corners([[0, 1, 2], [2, 1, 3, 4]], 5)
    >>> c.corner.tolist(), c.following.tolist(), c.starts.tolist()
    ([0, 1, 2, 2, 1, 3, 4], [1, 2, 0, 1, 3, 4, 2], [0, 3])
    >>> face_corners([[0, 1, 7]], 5)
    Traceback (most recent call last):
    ...
    ValueError: 'faces[0]' indexes outside 0..4: [0, 1, 7]
    """
    if isinstance(faces, FaceCorners):  # flattened and validated already
        return faces
    if isinstance(faces, str) or not hasattr(faces, "__len__"):
        raise TypeError(f"'faces' must be a sequence of index arrays; got {type(faces).__name__}")
    arrays = [np.asarray(face) for face in faces]  # type: ignore[attr-defined]
    for f, array in enumerate(arrays):
        if array.ndim != 1 or (array.size and array.dtype.kind not in "iu"):
            raise TypeError(
                f"'faces[{f}]' must be a 1-D sequence of int indices; got {array.tolist()!r}"
            )
    sizes = np.fromiter((a.size for a in arrays), np.int64, len(arrays))
    short = np.flatnonzero(sizes < 3)
    if short.size:
        raise ValueError(f"'faces[{short[0]}]' has {sizes[short[0]]} vertices; a face needs >= 3")
    corner = np.concatenate(arrays).astype(np.int64) if arrays else np.zeros(0, np.int64)
    starts = np.cumsum(sizes) - sizes
    outside = np.flatnonzero((corner < 0) | (corner >= vertex_count))
    if outside.size:
        f = int(np.searchsorted(starts, outside[0], side="right") - 1)
        raise ValueError(
            f"'faces[{f}]' indexes outside 0..{vertex_count - 1}: {arrays[f].tolist()}"
        )
    following = np.arange(1, len(corner) + 1)
    following[starts + sizes - 1] = starts  # the last corner of a face joins its first
    return FaceCorners(corner, corner[following], np.repeat(np.arange(len(sizes)), sizes), starts)


def newell(
    positions: np.ndarray, corners: FaceCorners
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newell's sums per face, its centroid, and the spread of its corners about the centroid.

    The sum over the edges (i, j) of (y_i - y_j)(z_i + z_j), (z_i - z_j)(x_i + x_j),
    (x_i - x_j)(y_i + y_j) is twice the face's area vector (the best-fitting plane's
    normal for a non-planar face). Corners are taken relative to the centroid, so
    faces far from the origin keep their precision. ``spread`` is the sum of the
    corners' squared distances from the centroid: a scale for "degenerate".

    Returns (area (F, 3), centroid (F, 3), spread (F,)), all float64.
    """
    face_count = len(corners.starts)
    if not face_count:
        return np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0)
    sizes = np.diff(np.append(corners.starts, len(corners.corner)))
    centroid = np.add.reduceat(positions[corners.corner], corners.starts, axis=0) / sizes[:, None]
    a = positions[corners.corner] - centroid[corners.face]
    b = positions[corners.following] - centroid[corners.face]
    terms = np.column_stack(
        [
            (a[:, 1] - b[:, 1]) * (a[:, 2] + b[:, 2]),
            (a[:, 2] - b[:, 2]) * (a[:, 0] + b[:, 0]),
            (a[:, 0] - b[:, 0]) * (a[:, 1] + b[:, 1]),
        ]
    )
    spread = np.add.reduceat(
        a[:, 0] * a[:, 0] + a[:, 1] * a[:, 1] + a[:, 2] * a[:, 2], corners.starts
    )
    return np.add.reduceat(terms, corners.starts, axis=0), centroid, spread

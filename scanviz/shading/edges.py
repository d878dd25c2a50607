"""Feature edges of a polygon mesh: silhouettes, boundaries and creases (Gooch et al. 1998).

Lines drawn over a shaded image carry the shape: the silhouette, where the
surface turns away from the viewer; the boundary of an open surface; and
creases, where neighbouring faces meet at a sharp angle. On a mesh each is a
set of edges, found from the faces on either side:

- silhouette: one face is front-facing (N.V > 0) and the other is not;
- boundary: the edge has only one face;
- crease: the angle between the two face normals exceeds a threshold.

The pipeline projects the edges and draws them with
`scanviz.raster.lines.midpoint_line`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..scene.faces import face_corners
from .illumination import _dot, _face_area_vectors, _rows, _to_viewer, _unit


def _edge_set(edges: np.ndarray, chosen: np.ndarray) -> np.ndarray:
    return edges[np.unique(chosen)].reshape(-1, 2)


def feature_edges(
    positions: object,
    faces: Sequence[object],
    eye: object,
    crease_degrees: float = 30.0,
    *,
    view_dir: object = None,
) -> dict[str, np.ndarray]:
    """The silhouette, boundary and crease edges of a mesh seen from `eye` (or along `view_dir`).

    Parameters
    ----------
    positions : (V, 3) array_like of float
    faces : sequence of (k,) array_like of int
        Vertex indices, k >= 3, counter-clockwise seen from the front.
    eye : (3,) array_like of float or None
        The viewer's position; None for an orthographic viewer given by `view_dir`.
    crease_degrees : float
        An edge is a crease if its faces' normals differ by more than this
        angle, in [0, 180] (0 for coplanar faces, 90 for a cube's edges).
    view_dir : (3,) array_like of float, optional
        Direction toward an orthographic viewer. Give exactly one of `eye` and `view_dir`.

    Returns
    -------
    dict of str to (E, 2) ndarray of int64
        ``"silhouette"``, ``"boundary"`` and ``"crease"``: vertex index pairs
        (smaller index first, rows sorted), each edge once.

    Notes
    -----
    A face is front-facing if N.V > 0 at its centroid, as for back-face
    culling; an edge-on face (N.V = 0) counts as back-facing, so a cube seen
    face-on has its front square as silhouette. The slides' test
    (V.N0)(V.N1) <= 0 differs only in such exact ties. Edges with more than
    two faces are tested on each pair of faces that are neighbours in index
    order; pairs with a degenerate (zero-normal) face are not tested.

    Examples
    --------
    Two unit squares folded at a right angle along the edge 0-1, seen from above:

    >>> positions = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, -1), (1, 0, -1)]
    >>> edges = feature_edges(positions, [[0, 1, 2, 3], [0, 4, 5, 1]], (0.5, 0.5, 5))
    >>> edges["silhouette"].tolist(), edges["crease"].tolist()
    ([[0, 1]], [[0, 1]])
    >>> edges["boundary"].tolist()
    [[0, 3], [0, 4], [1, 2], [1, 5], [2, 3], [4, 5]]
    """
    positions = _rows("positions", positions, 3)
    if isinstance(crease_degrees, bool) or not isinstance(crease_degrees, int | float):
        raise TypeError(f"'crease_degrees' must be a number; got {crease_degrees!r}")
    if not 0 <= crease_degrees <= 180:
        raise ValueError(f"'crease_degrees' must be in [0, 180]; got {crease_degrees}")
    corners = face_corners(faces, len(positions))
    corner, following, face = corners.corner, corners.following, corners.face
    area, centroid = _face_area_vectors(positions, corners)
    normal, length = _unit(area)
    front = _dot(normal, _to_viewer(centroid, eye, view_dir)) > 0

    # Each corner gives the edge to the next corner; sort so an edge's faces are adjacent.
    keep = corner != following
    low, high, face = (
        np.minimum(corner, following)[keep],
        np.maximum(corner, following)[keep],
        face[keep],
    )
    order = np.lexsort((face, high, low))
    low, high, face = low[order], high[order], face[order]
    new_edge = np.ones(len(low), dtype=bool)
    new_edge[1:] = (low[1:] != low[:-1]) | (high[1:] != high[:-1])
    edge_of = np.cumsum(new_edge) - 1
    edges = np.stack([low[new_edge], high[new_edge]], axis=1)

    # Pairs of faces that share an edge: neighbours in the sorted list.
    second = np.flatnonzero(~new_edge)
    f0, f1 = face[second - 1], face[second]
    tested = (length[f0] > 0) & (length[f1] > 0)
    cosine = _dot(normal[f0], normal[f1])
    cross = np.cross(normal[f0], normal[f1])
    sine = np.sqrt(_dot(cross, cross))
    angle = np.degrees(np.arctan2(sine, cosine))
    return {
        "silhouette": _edge_set(edges, edge_of[second][tested & (front[f0] != front[f1])]),
        "boundary": edges[np.bincount(edge_of, minlength=len(edges)) == 1],
        "crease": _edge_set(edges, edge_of[second][tested & (angle > crease_degrees)]),
    }

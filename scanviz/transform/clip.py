"""Clipping polygons to the view volume in homogeneous clip space (Sutherland-Hodgman).

A clip-space point (x, y, z, w) is inside the view volume iff its signed
distance to each of six planes is >= 0 (see `scanviz.transform.viewing`)::

    near    z          far     w - z
    left    w + x      right   w - x
    bottom  w + y      top     w - y

Each distance is linear in the homogeneous point, so along an edge from P to
Q it is ``d(t) = d_P + t (d_Q - d_P)`` and the edge crosses the plane at
``t = d_P / (d_P - d_Q)``. Attributes given with the vertices are
interpolated with the same t, in clip space: an attribute linear in (x, y, z,
w) stays exact, which is what perspective-correct interpolation needs later.
Clipping before the divide also handles points at or behind the eye (w <= 0):
the near plane z >= 0 removes them, and every point that survives has w > 0.

Outcodes (Cohen-Sutherland) set bit i when a vertex is outside plane
``CLIP_PLANES[i]``. A polygon whose outcodes are all 0 is trivially accepted
and returned as is; one whose outcodes share a bit lies outside that plane
and is trivially rejected. Only the planes some vertex is outside are clipped
against: the others cannot cut a convex combination of inside points. Each
of those passes is the replaceable step ``clip_against_plane`` (`scanviz.steps`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .. import steps
from ..trace.events import PolygonClipped
from ._checks import as_points, check_tracer, flatten_faces

CLIP_PLANES = ("near", "far", "left", "right", "bottom", "top")

# One row per plane: signed distance = row . (x, y, z, w), >= 0 inside.
PLANE_DISTANCES = np.array(
    [
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, -1.0, 1.0],
        [1.0, 0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0, 1.0],
        [0.0, 1.0, 0.0, 1.0],
        [0.0, -1.0, 0.0, 1.0],
    ]
)


@njit(cache=True, inline="always")
def outcode(x, y, z, w):
    """Bit i set when (x, y, z, w) is outside plane ``CLIP_PLANES[i]`` (a row of `PLANE_DISTANCES`)."""
    code = 0
    for bit, distance in enumerate((z, w - z, w + x, w - x, w + y, w - y)):
        if distance < 0:
            code |= 1 << bit
    return code


@njit(cache=True)
def _outcodes(points):  # pragma: no cover - compiled
    codes = np.empty(points.shape[0], np.int64)
    for i in range(points.shape[0]):
        codes[i] = outcode(points[i, 0], points[i, 1], points[i, 2], points[i, 3])
    return codes


def outcodes(clip_points: object) -> np.ndarray:
    """Which planes each point is outside of: bit i set for ``CLIP_PLANES[i]``.

    Parameters
    ----------
    clip_points : (N, 4) array_like of float

    Returns
    -------
    (N,) ndarray of int64
        0 for a point inside the view volume (boundary included).

    Examples
    --------
    >>> outcodes([[0, 0, 0.5, 1], [2, 0, 0.5, 1], [-2, 3, -1, 1], [1, 1, 1, 1]]).tolist()
    [0, 8, 37, 0]
    """
    return _outcodes(as_points("clip_points", clip_points, (4,)))


def classify(clip_points: object, faces: object) -> np.ndarray:
    """Trivial accept / reject of every face by its vertices' outcodes, so work can be skipped.

    Parameters
    ----------
    clip_points : (V, 4) array_like of float
    faces : (F, k) array_like of int, or sequence of (k_i,) array_like of int, k_i >= 3

    Returns
    -------
    (F,) ndarray of str
        "accept" (all vertices inside), "reject" (all outside one plane) or
        "clip" (run `clip_polygon`, which may still reject it).

    Examples
    --------
    >>> points = [[0, 0, 0.5, 1], [0.5, 0, 0.5, 1], [0, 0.5, 0.5, 1], [3, 0, 0.5, 1], [3, 1, 0.5, 1]]
    >>> classify(points, [[0, 1, 2], [1, 3, 4], [3, 4, 4]]).tolist()
    ['accept', 'clip', 'reject']
    """
    codes = outcodes(clip_points)
    indices, starts = flatten_faces(faces, len(codes))
    if not len(starts):
        return np.empty(0, dtype="<U6")
    return np.array(VERDICTS)[face_verdicts(codes, indices, starts)]


VERDICTS = ("accept", "clip", "reject")  # `face_verdicts` gives their indices
ACCEPT, CLIP, REJECT = range(3)


@njit(cache=True)
def face_verdicts(codes, corners, starts):  # pragma: no cover - compiled
    """(F,) int8 index into `VERDICTS` of each face (corners[starts[f]:starts[f + 1]]).

    `classify` without the strings, for the pipeline: `codes` are the
    vertices' `outcodes`. ACCEPT when every corner is inside, REJECT when all
    share an outside bit, else CLIP.
    """
    faces = starts.shape[0]
    verdict = np.empty(faces, np.int8)
    for f in range(faces):
        stop = starts[f + 1] if f + 1 < faces else corners.shape[0]
        every, some = -1, 0
        for k in range(starts[f], stop):
            every &= codes[corners[k]]
            some |= codes[corners[k]]
        verdict[f] = REJECT if every != 0 else (ACCEPT if some == 0 else CLIP)
    return verdict


@steps.step(
    "clip_against_plane",
    takes="a polygon's vertices [(x, y, z, w, attributes...), ...] in order and a plane "
    "(a, b, c, d): signed distance a x + b y + c z + d w, >= 0 inside",
    returns="the vertices of its part inside the plane, in order (one Sutherland-Hodgman stage)",
)
def clip_against_plane(vertices: list, plane: tuple) -> list:
    """One Sutherland-Hodgman stage: clip a closed polygon to the half-space of `plane`.

    Each edge (S, P), from the previous vertex S to the vertex P (the first
    edge starts at the last vertex), contributes its crossing of the plane if
    S and P lie strictly on opposite sides, then P if P is inside (distance
    >= 0). A crossing interpolates every column, attributes included, with
    the same t, from the inside end (so an edge shared by two polygons gives
    both the same point); a plane bounding one coordinate puts it exactly on it.

    Examples
    --------
    The right plane x = w, distance w - x, cuts the tip off a triangle:

    >>> clip_against_plane([(0, 0, 0, 1, 0), (3, 0, 0, 1, 3), (0, 1, 0, 1, 0)], (-1, 0, 0, 1))
    [(0, 0, 0, 1, 0), (1.0, 0.0, 0.0, 1.0, 1.0), (1.0, 0.6666666666666667, 0.0, 1.0, 1.0), (0, 1, 0, 1, 0)]
    """
    a, b, c, d = plane
    distances = [a * v[0] + b * v[1] + c * v[2] + d * v[3] for v in vertices]
    bounded = [k for k in range(3) if plane[k] != 0]
    clipped: list = []
    start, start_distance = vertices[-1], distances[-1]
    for vertex, distance in zip(vertices, distances, strict=True):
        if start_distance < 0 < distance or distance < 0 < start_distance:  # a strict crossing
            inner, d_inner, outer, d_outer = (
                (start, start_distance, vertex, distance)
                if start_distance > 0
                else (vertex, distance, start, start_distance)
            )
            t = d_inner / (d_inner - d_outer)
            crossing = [p + t * (q - p) for p, q in zip(inner, outer, strict=True)]
            if len(bounded) == 1:  # exactly on the plane
                crossing[bounded[0]] = -d * crossing[3] / plane[bounded[0]]
            clipped.append(tuple(crossing))
        if distance >= 0:
            clipped.append(vertex)
        start, start_distance = vertex, distance
    return clipped


def _clip_to_planes(rows: np.ndarray, planes: int) -> tuple[np.ndarray, list[int]]:
    """Rows (x, y, z, w, attributes...) clipped to every plane whose bit is set in `planes`.

    Also returns the vertex count after each plane of `CLIP_PLANES`.
    """
    clip = steps.get("clip_against_plane")
    vertices = [tuple(row) for row in rows.tolist()]
    counts = []
    for plane in range(len(CLIP_PLANES)):
        if planes >> plane & 1 and vertices:
            vertices = clip(vertices, tuple(PLANE_DISTANCES[plane].tolist()))
            if not isinstance(vertices, list | tuple):
                raise TypeError(
                    "the 'clip_against_plane' step must return a list of vertices; "
                    f"got {type(vertices).__name__}"
                )
        counts.append(len(vertices))
    if not vertices:
        return rows[:0], counts
    try:
        clipped = np.array(vertices, dtype=np.float64)
    except (TypeError, ValueError):
        clipped = None
    if clipped is None or clipped.shape[1:] != rows.shape[1:]:
        raise ValueError(
            f"the 'clip_against_plane' step must return vertices of {rows.shape[1]} numbers each"
        )
    return clipped, counts


def clip_polygon(clip_points: object, attributes: object = None, *, trace=None, polygon: int = 0):
    """Clip a polygon to the view volume, interpolating its vertex attributes.

    Parameters
    ----------
    clip_points : (N, 4) array_like of float, N >= 3
        Vertices in clip space, in order (any orientation; convex polygons
        give convex results, others may gain zero-width bridges along planes).
    attributes : (N, K) array_like of float, or None
        Per-vertex values (colors, normals, texture coordinates, ...).
    trace : Tracer or None
        Receives one ``polygon_clipped`` event.
    polygon : int
        Label of the polygon in the event.

    Returns
    -------
    clip_points : (M, 4) ndarray of float64
    attributes : (M, K) ndarray of float64, or None if `attributes` is None
        Trivially accepted input comes back as the very same arrays (a
        float64 ndarray is not copied); a rejected polygon, or a result with
        fewer than 3 vertices, gives M = 0.

    Examples
    --------
    A triangle poking out of the right plane x = w loses its tip; the
    attribute (here x itself) follows the new vertices:

    >>> points = [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]
    >>> clipped, attributes = clip_polygon(points, [[0], [3], [0]])
    >>> clipped
    array([[0.        , 0.        , 0.5       , 1.        ],
           [1.        , 0.        , 0.5       , 1.        ],
           [1.        , 0.33333333, 0.5       , 1.        ],
           [0.        , 0.5       , 0.5       , 1.        ]])
    >>> attributes.ravel()
    array([0., 1., 1., 0.])
    """
    trace = check_tracer(trace)
    points = as_points("clip_points", clip_points, (4,), min_rows=3)
    values = None
    if attributes is not None:
        values = as_points("attributes", attributes, None)
        if len(values) != len(points):
            raise ValueError(
                f"'attributes' must have one row per vertex ({len(points)}); got {len(values)}"
            )
    codes = _outcodes(points)
    outside = int(np.bitwise_or.reduce(codes))
    counts: list[int] = []
    if not outside:
        verdict = "accepted"  # every vertex inside: nothing to cut
    else:
        rows = points if values is None else np.hstack([points, values])
        if np.bitwise_and.reduce(codes):
            rows = rows[:0]  # every vertex outside one plane
        else:
            rows, counts = _clip_to_planes(rows, outside)
        if len(rows) < 3:
            rows = rows[:0]  # a point or a segment covers nothing
        verdict = "clipped" if len(rows) else "rejected"
        points = np.ascontiguousarray(rows[:, :4])
        values = None if values is None else np.ascontiguousarray(rows[:, 4:])
    if trace is not None and trace.wants("polygon_clipped", polygon=polygon):
        trace.emit(
            PolygonClipped(
                polygon=int(polygon),
                verdict=verdict,
                outcodes=tuple(codes.tolist()),
                counts=tuple(counts),
                vertices=tuple(tuple(row) for row in points.tolist()),
            )
        )
    return points, values

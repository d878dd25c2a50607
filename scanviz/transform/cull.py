"""Back-face culling: skip the faces of a closed mesh that turn away from the eye.

A face is back-facing when its outward normal N points away from the viewer,
``V . N >= 0`` with V the viewing vector (UMBC CMSC 435 slides): from the eye
to a point on the face for a perspective camera, the view direction
``look_at - eye`` for an orthographic one. Faces seen exactly edge-on
(V . N = 0) are culled too: they cover no area on screen.

Normals come from Newell's method, which sums over the edges (i, j = i + 1)::

    N = ( sum (y_i - y_j)(z_i + z_j),  sum (z_i - z_j)(x_i + x_j),  sum (x_i - x_j)(y_i + y_j) )

For a planar polygon this is twice its area times the unit normal, oriented
by the right-hand rule (counter-clockwise seen from outside points out); for
a slightly non-planar one it is the normal of the best-fitting plane, and no
choice of three vertices can make it fail. The sums are taken about the
face's centroid, which changes nothing exactly and keeps far-away faces
accurate. The face point used for the perspective test is the centroid.

A face with a zero normal (all vertices collinear or coincident) has no side
to show; it is never culled, and renders as nothing anyway. For a face seen
nearly edge-on, the sign of V . N is decided by floating-point rounding; either
verdict is harmless, since such a face covers (almost) no area on screen.
The test is done in world space: `eye_from_world` is rigid, so the sign is the
same in eye space.
"""

from __future__ import annotations

import numpy as np

from .. import steps
from ..scene import Camera
from ..scene.faces import face_corners, newell
from ..trace.events import FaceCulled
from ._checks import as_points, check_camera, check_tracer


def face_normals(positions: object, faces: object) -> np.ndarray:
    """Newell normals of the faces, not normalized (length = twice the area if planar).

    Parameters
    ----------
    positions : (V, 3) array_like of float
    faces : (F, k) array_like of int, or sequence of (k_i,) array_like of int, k_i >= 3

    Returns
    -------
    (F, 3) ndarray of float64

    Examples
    --------
    >>> face_normals([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], [[0, 1, 2, 3], [3, 2, 1, 0]])
    array([[ 0.,  0.,  4.],
           [ 0.,  0., -4.]])
    """
    positions = as_points("positions", positions, (3,))
    return newell(positions, face_corners(faces, len(positions)))[0]


@steps.step(
    "back_face_test",
    takes="a face's Newell normal N and its viewing vector V (eye to face, or the view "
    "direction): two (x, y, z) tuples of floats",
    returns="True if the face is culled: it turns away, V . N >= 0, and N is not zero",
)
def back_face_test(normal: tuple, view: tuple) -> bool:
    """Whether a face with outward normal `normal`, seen along `view`, is back-facing.

    Examples
    --------
    >>> back_face_test((0.0, 0.0, 4.0), (0.0, 0.0, -5.0)), back_face_test((4.0, 0.0, 0.0), (0.0, 0.0, -5.0))
    (False, True)
    """
    dot = normal[0] * view[0] + normal[1] * view[1] + normal[2] * view[2]
    return dot >= 0 and any(normal)  # edge-on (dot = 0) is culled; a zero normal has no back


def _dots(normals: np.ndarray, views: np.ndarray) -> np.ndarray:
    """Row-wise N . V, summed left to right as `back_face_test` sums it (same bits)."""
    return (normals[:, 0] * views[:, 0] + normals[:, 1] * views[:, 1]) + normals[:, 2] * views[:, 2]


def cull_faces(camera: Camera, world_positions: object, faces: object, *, trace=None):
    """The back-face test for every face of a mesh.

    Parameters
    ----------
    camera : Camera
    world_positions : (V, 3) array_like of float
    faces : (F, k) array_like of int, or sequence of (k_i,) array_like of int, k_i >= 3
        Counter-clockwise seen from outside.
    trace : Tracer or None
        Receives a ``face_culled`` event per face (polygon = face index). With a
        tracer, or while a step is replaced, each face goes through the step
        ``back_face_test`` (`scanviz.steps`); else all faces at once, to the same bits.

    Returns
    -------
    culled : (F,) ndarray of bool
        True for back-facing faces (dot >= 0 and a nonzero normal).
    dots : (F,) ndarray of float64
        The test values dot(normal, view vector).

    Examples
    --------
    The unit cube's faces +x, +y, +z face an eye at (3, 4, 5); the others are culled:

    >>> corners = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    >>> faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    >>> culled, dots = cull_faces(Camera(eye=(3, 4, 5)), corners, faces)
    >>> culled.tolist()  # -x, +x, -y, +y, -z, +z
    [True, False, True, False, True, False]
    """
    camera = check_camera(camera)
    trace = check_tracer(trace)
    positions = as_points("world_positions", world_positions, (3,))
    normals, centroids, _ = newell(positions, face_corners(faces, len(positions)))
    if camera.projection == "perspective":
        views = centroids - np.array(camera.eye)
    else:
        views = np.broadcast_to(np.subtract(camera.look_at, camera.eye), normals.shape)
    dots = _dots(normals, views)
    if trace is None and not steps.replaced():
        culled = (dots >= 0) & normals.any(axis=1)  # `back_face_test` on every face at once
    else:
        test = steps.get("back_face_test")
        pairs = zip(normals.tolist(), views.tolist(), strict=True)
        culled = np.array([bool(test(tuple(n), tuple(v))) for n, v in pairs], dtype=bool)
    if trace is not None:
        for face in range(len(normals)):
            if trace.wants("face_culled", polygon=face):
                normal, view = tuple(normals[face].tolist()), tuple(views[face].tolist())
                trace.emit(FaceCulled(face, normal, view, float(dots[face]), bool(culled[face])))
    return culled, dots


def back_facing(camera: Camera, world_face_points: object) -> bool:
    """Whether one face, given by its (k, 3) world-space vertices in order, is back-facing.

    Examples
    --------
    >>> square = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]  # counter-clockwise from +z
    >>> back_facing(Camera(eye=(0, 0, 5)), square), back_facing(Camera(eye=(0, 0, -5)), square)
    (False, True)
    """
    points = as_points("world_face_points", world_face_points, (3,), min_rows=3)
    return bool(cull_faces(camera, points, [np.arange(len(points))])[0][0])

"""Compiled steps of `prepare` (numba): clip coordinates, trivial accept/reject, screen vertices.

One pass per step over an object's vertices, corners or faces, where numpy
would make a temporary per operation. Both paths of `render` (traced and
compiled) prepare through these, so the z-buffer's two paths see the same
bits. The arithmetic is written out: each clip coordinate is
``m[r,0]*x + m[r,1]*y + m[r,2]*z + m[r,3]`` summed left to right, and the
screen vertex is ``((x/w + 1)/2 * width, (y/w + 1)/2 * height, z/w, 1/w)``,
as `prepare._screen_polygons` divides.
"""

from __future__ import annotations

import numpy as np
from numba import njit

ACCEPT, CLIP, REJECT = 0, 1, 2  # as `scanviz.transform.clip.VERDICTS`
# Signed distances to the six clip planes (near, far, left, right, bottom, top), as
# `scanviz.transform.clip.PLANE_DISTANCES`: rows . (x, y, z, w) >= 0 inside.


@njit(cache=True, inline="always")
def _outcode(x, y, z, w):
    """Bit i set when the point is outside plane i (`scanviz.transform.clip.outcodes`)."""
    code = 0
    if z < 0:
        code |= 1
    if w - z < 0:
        code |= 2
    if x + w < 0:
        code |= 4
    if w - x < 0:
        code |= 8
    if y + w < 0:
        code |= 16
    if w - y < 0:
        code |= 32
    return code


@njit(cache=True)
def clip_coordinates(world, matrix):
    """((V, 4) clip coordinates of the world points, (V,) outcodes, whether all are finite)."""
    count = world.shape[0]
    clip = np.empty((count, 4))
    codes = np.empty(count, np.int64)
    finite = np.ones(count, np.bool_)
    for i in range(count):
        x, y, z = world[i, 0], world[i, 1], world[i, 2]
        for r in range(4):
            clip[i, r] = matrix[r, 0] * x + matrix[r, 1] * y + matrix[r, 2] * z + matrix[r, 3]
        finite[i] = (
            np.isfinite(clip[i, 0])
            and np.isfinite(clip[i, 1])
            and np.isfinite(clip[i, 2])
            and np.isfinite(clip[i, 3])
        )
        codes[i] = _outcode(clip[i, 0], clip[i, 1], clip[i, 2], clip[i, 3])
    return clip, codes, finite


@njit(cache=True)
def face_verdicts(codes, corners, starts):
    """(F,) int8: ACCEPT when every corner is inside, REJECT when all share an outside bit, else CLIP."""
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


@njit(cache=True, error_model="numpy")
def screen_vertices(clip, corners, width, height):
    """(xy (C, 2), z (C,), inv_w (C,)) of the corners' clip points, divided by w (no checks).

    w = 0 gives inf or NaN, as numpy does: `prepare` then names the object.
    """
    count = corners.shape[0]
    xy = np.empty((count, 2))
    z = np.empty(count)
    inv_w = np.empty(count)
    for k in range(count):
        v = corners[k]
        w = clip[v, 3]
        xy[k, 0] = (clip[v, 0] / w + 1) / 2 * width
        xy[k, 1] = (clip[v, 1] / w + 1) / 2 * height
        z[k] = clip[v, 2] / w
        inv_w[k] = 1 / w
    return xy, z, inv_w


@njit(cache=True)
def within(array, limit):
    """Whether every entry of the 2-D `array` is within +-limit (False on NaN)."""
    for i in range(array.shape[0]):
        for j in range(array.shape[1]):
            if not abs(array[i, j]) <= limit:
                return False
    return True


@njit(cache=True)
def in_range(vector, low, high):
    """Whether every entry of `vector` is in [low, high] (False on NaN)."""
    for i in range(vector.shape[0]):
        if not (vector[i] >= low and vector[i] <= high):
            return False
    return True

"""Compiled steps of `prepare` (numba): clip coordinates and outcodes, screen vertices, checks.

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

from ..transform.clip import outcode


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
        codes[i] = outcode(clip[i, 0], clip[i, 1], clip[i, 2], clip[i, 3])
    return clip, codes, finite


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

"""Compiled twin of the Phong illumination model (numba): `illuminate`'s colors, bit for bit.

`shade_rows` runs `illumination._shade` point by point, with the same
operations in the same order (products left to right, dot products summed
x, y, z, the power as one scalar ``**``, the overflow-safe unit vectors of
`scanviz.vectors`), so every point gets exactly the numpy model's color and
the traced `illuminate_traced` stays equal to it. Points are shared among
numba's threads; a point's color does not depend on the others.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..threads import use_threads
from ..vectors import _SAFE_HIGH, _SAFE_LOW

DIRECTIONAL, POINT = 0, 1  # light kinds, as `shade_rows` takes them


@njit(cache=True, inline="always")
def _squared(x, y, z):
    return x * x + y * y + z * z


@njit(cache=True, inline="always")
def unit_and_length(x, y, z):
    """(ux, uy, uz, length) as `vectors.unit_vectors` and `vectors.vector_norm` give them."""
    squares = _squared(x, y, z)
    if squares > _SAFE_LOW and squares < _SAFE_HIGH:
        root = math.sqrt(squares)
        return x / root, y / root, z / root, root
    scale = max(abs(x), abs(y), abs(z))  # NaN never reaches here: inputs are checked finite
    safe = scale if scale > 0 else 1.0
    sx, sy, sz = x / safe, y / safe, z / safe
    length = math.sqrt(_squared(sx, sy, sz))
    if length > 0:
        return sx / length, sy / length, sz / length, scale * length
    return 0.0, 0.0, 0.0, scale * length


PARALLEL_POINTS = 2**14  # fewer points are shaded on the calling thread


def shade_rows(positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light):
    """(N, 3) colors of `illumination._shade` without steps.

    `eye` (3,) is used when view_dir[0] is NaN (perspective), else the unit
    `view_dir` (3,) toward an orthographic viewer; light i is of kind
    kinds[i] with vectors[i] its position (point) or its unit direction
    toward the light (directional, `_unit(-direction)`), colors[i] its RGB.
    Many points are shared among numba's threads, a few shaded here.
    """
    out = np.empty((positions.shape[0], 3))
    shade = _shade_shared if use_threads(len(positions), PARALLEL_POINTS) else _shade_here
    shade(positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out)
    return out


def shade_image(polygon, values, eye, view_dir, kinds, vectors, colors, ambient_light, background):
    """(H, W, 3): `shade_rows` of every pixel with polygon >= 0 from its values (normal,
    position, material: 15 columns), the background elsewhere; no pixel is gathered first.
    """
    flat = values.reshape(-1, values.shape[-1])
    ids = polygon.ravel()
    out = np.empty((len(ids), 3))
    shade = _shade_image_shared if use_threads(len(ids), PARALLEL_POINTS) else _shade_image_here
    shade(ids, flat[:, 3:6], flat[:, 0:3], flat[:, 6:15], eye, view_dir, kinds, vectors, colors, ambient_light, background, out)  # fmt: skip
    return out.reshape(*polygon.shape, 3)


@njit(cache=True, parallel=True)
def _shade_image_shared(ids, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, background, out):  # fmt: skip
    for i in prange(ids.shape[0]):
        if ids[i] < 0:
            out[i, 0], out[i, 1], out[i, 2] = background[0], background[1], background[2]
        else:
            shade_point(i, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out)  # fmt: skip


@njit(cache=True)
def _shade_image_here(ids, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, background, out):  # fmt: skip
    for i in range(ids.shape[0]):
        if ids[i] < 0:
            out[i, 0], out[i, 1], out[i, 2] = background[0], background[1], background[2]
        else:
            shade_point(i, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out)  # fmt: skip


@njit(cache=True, parallel=True)
def _shade_shared(positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out):  # fmt: skip
    for i in prange(positions.shape[0]):
        shade_point(i, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out)  # fmt: skip


@njit(cache=True)
def _shade_here(positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out):  # fmt: skip
    for i in range(positions.shape[0]):
        shade_point(i, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out)  # fmt: skip


@njit(cache=True, inline="always")
def shade_point(i, positions, normals, materials, eye, view_dir, kinds, vectors, colors, ambient_light, out):  # fmt: skip
    """Point i's color into out[i]."""
    perspective = math.isnan(view_dir[0])
    px, py, pz = positions[i, 0], positions[i, 1], positions[i, 2]
    if perspective:
        vx, vy, vz, _ = unit_and_length(
            eye[0] / 2 - px / 2, eye[1] / 2 - py / 2, eye[2] / 2 - pz / 2
        )
    else:
        vx, vy, vz = view_dir[0], view_dir[1], view_dir[2]
    nx, ny, nz, _ = unit_and_length(normals[i, 0], normals[i, 1], normals[i, 2])
    if nx * vx + ny * vy + nz * vz < 0:  # seen from behind: light the visible side
        nx, ny, nz = -nx, -ny, -nz
    ka, kd, ks = materials[i, 3], materials[i, 4], materials[i, 5]
    exponent, fudge = materials[i, 6], materials[i, 8]
    for c in range(3):
        out[i, c] = ka * ambient_light[c] * materials[i, c]
    for light in range(kinds.shape[0]):
        if kinds[light] == POINT:
            q = vectors[light]
            lx, ly, lz, half = unit_and_length(
                q[0] / 2 - px / 2, q[1] / 2 - py / 2, q[2] / 2 - pz / 2
            )
            distance = 2 * half
        else:
            lx, ly, lz = vectors[light, 0], vectors[light, 1], vectors[light, 2]
            distance = 0.0
        n_dot_l = nx * lx + ny * ly + nz * lz
        twice = 2 * n_dot_l
        r_dot_v = (twice * nx - lx) * vx + (twice * ny - ly) * vy + (twice * nz - lz) * vz
        specular = 0.0
        if n_dot_l > 0:  # no highlight on the unlit side
            specular = ks * max(r_dot_v, 0.0) ** exponent
        falloff = fudge * distance if fudge > 0 else 0.0
        attenuation = 1 / (1 + falloff)
        lit = max(n_dot_l, 0.0)
        for c in range(3):
            diffuse = kd * materials[i, c] * lit
            out[i, c] = out[i, c] + attenuation * colors[light, c] * (diffuse + specular)
    for c in range(3):
        out[i, c] = min(max(out[i, c], 0.0), 1.0)

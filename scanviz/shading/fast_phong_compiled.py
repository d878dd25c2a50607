"""Fast Phong over many triangles in one compiled pass (`fast_phong_triangles`).

`scanviz.shading.fast_phong.fast_phong_triangle` shades one triangle and is
the reference: a traced loop and two small kernels, with the triangle's set
up (normal plane, rational forms, Taylor series) in Python around compiled
helpers. This module does the same for a whole batch inside numba, for
`render(shading="fast_phong")`: per triangle the same compiled helpers of
`scanviz.shading.taylor` (`_unit3`, `_plane`, `_halfway`, `_forms`,
`theta_series`, `phi_series`), per row the span of the triangle's exact
edge crossings (the samples `triangle_samples` finds; the shared triangle
walk of `scanviz.raster.walk_compiled`), per span a direct
start and forward differences, per sample the table level by binary search.
Only samples whose owner in `owners` is the triangle's polygon are written,
so the visibility of the caller decides what is drawn. Same inputs, same
operations in the same order: the colours equal the reference's bit for bit
(tests/shading/test_fast_phong_kernels.py).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..limits import check_memory
from ..raster.walk_compiled import triangle_span, triangle_walk
from .lut import lut_level_compiled
from .taylor import LEVELS, _forms, _halfway, _plane, _unit3, phi_series, theta_series

TERMS = 5  # stepped quadratics per light: cos θ, the highlight's cosine, three channels


@njit(cache=True)
def _quadratics(plane, to_light, to_viewer, blinn, diffuse, ambient, out):
    """Fill `out` (5, 6) as `fast_phong._quadratics` does, for one light."""
    a, b, c = plane
    light, _ = _unit3(to_light)
    viewer, _ = _unit3(to_viewer)
    halfway, _ = _halfway(light, viewer)
    s = _forms(a, b, c, light, viewer, halfway)
    # s: a b c aa bb cc d e f g h i l m o p q w k_lv ha hb hc (RationalForms' field order)
    d, e, f, g, h, i = s[6], s[7], s[8], s[9], s[10], s[11]
    out[:] = 0.0
    if i > 0:
        root = math.sqrt(i)
        theta = theta_series(s[0], s[1], s[2], d, e, f, g, h, i, root)
        if blinn:
            specular = theta_series(s[19], s[20], s[21], d, e, f, g, h, i, root)
        else:
            specular = phi_series(s[12], s[13], s[14], s[15], s[16], s[17], d, e, f, g, h, i, s[18])
        for k in range(6):
            out[0, k] = theta[k]
            out[1, k] = specular[k]
    for channel in range(3):
        for k in range(6):
            out[2 + channel, k] = diffuse[channel] * out[0, k]
        out[2 + channel, 5] += ambient[channel]


@njit(cache=True)
def _span_start(quadratic, x, y):
    """Q and dQ at a span's first sample, as `fast_phong._difference_kernel` evaluates them."""
    t5, t4, t3, t2, t1, t0 = quadratic
    value = t5 * x * x + t4 * x * y + t3 * y * y + t2 * x + t1 * y + t0
    return value, t5 * (2 * x + 1) + t4 * y + t2


@njit(cache=True)
def _shade_sample(values, model_of, lights, ambients, tables, table_offsets, total):
    """`total` (3,): the sample's clipped levels under each light, summed (not yet clipped)."""
    total[:] = 0.0
    for light in range(lights):
        m = model_of[light]
        table = tables[table_offsets[m] : table_offsets[m + 1]]
        level = lut_level_compiled(table, values[light, 1])
        specular = float(level) if values[light, 0] > 0 else 0.0
        for c in range(3):
            diffuse, ambient = values[light, 2 + c], ambients[m, c]
            colour = (diffuse if diffuse > ambient else ambient) + specular
            total[c] += min(max(colour, 0.0), LEVELS)


@njit(cache=True)
def _shade_batch(
    units, scale, vertices, normals, to_lights, to_viewers, models, polygons, owners,
    centroid, offset, blinn, diffuse, ambients, tables, table_offsets, image,
):  # fmt: skip
    """Shade every triangle's visible samples into `image`; returns how many were written."""
    height, width = owners.shape
    lights = to_lights.shape[1]
    quadratics = np.empty((lights, TERMS, 6))
    values, steps = np.empty((lights, TERMS)), np.empty((lights, TERMS))
    origin, total = np.empty(2), np.empty(3)
    written = 0
    for t in range(units.shape[0]):
        x0, y0, x1, y1, x2, y2 = (
            units[t, 0, 0], units[t, 0, 1], units[t, 1, 0],
            units[t, 1, 1], units[t, 2, 0], units[t, 2, 1],
        )  # fmt: skip
        if (x1 - x0) * (y2 - y0) == (x2 - x0) * (y1 - y0):
            continue  # zero area once snapped: the reference shades nothing
        v = vertices[t]
        if centroid:
            origin[0] = (v[0, 0] + v[1, 0] + v[2, 0]) / 3
            origin[1] = (v[0, 1] + v[1, 1] + v[2, 1]) / 3
        else:
            origin[0], origin[1] = v[0, 0], v[0, 1]
        a, b, c, _ = _plane(v, normals[t], origin)
        for light in range(lights):
            m = models[t, light]
            _quadratics((a, b, c), to_lights[t, light], to_viewers[t], blinn, diffuse[m], ambients[m], quadratics[light])  # fmt: skip
        sx, sy = origin[0] - offset, origin[1] - offset  # sample (px, py) is at px - sx
        first, stop, walk = triangle_walk(x0, y0, x1, y1, x2, y2, scale, height)
        for y in range(first, stop):
            start, end, walk = triangle_span(walk, y, scale, width)
            for x in range(start, end):
                for light in range(lights):
                    for j in range(TERMS):
                        if x == start:
                            values[light, j], steps[light, j] = _span_start(quadratics[light, j], x - sx, y - sy)  # fmt: skip
                        else:  # two additions
                            values[light, j] += steps[light, j]
                            steps[light, j] += 2 * quadratics[light, j, 0]
                if owners[y, x] != polygons[t]:
                    continue
                _shade_sample(values, models[t], lights, ambients, tables, table_offsets, total)
                for k in range(3):
                    image[y, x, k] = min(max(total[k], 0.0), LEVELS) / LEVELS
                written += 1
    return written


def fast_phong_triangles(
    units, scale, sample_shift, normals, to_lights, to_viewers, models, polygons, owners, image,
    *, expansion, sample_offset, blinn, diffuse, ambients, tables,
):  # fmt: skip
    """Shade a batch of snapped triangles into `image` where `owners` shows their polygon.

    Parameters
    ----------
    units : (T, 3, 2) ndarray of int64
        Snapped grid units (`scanviz.raster.fixed.snap_units`), `scale` per pixel;
        a vertex is at (units + sample_shift) / scale pixels.
    normals : (T, 3, 3) ndarray
        Vertex normals, already turned toward the viewer.
    to_lights : (T, L, 3) ndarray; to_viewers : (T, 3) ndarray
        Raw directions (normalised here, once, as `fast_phong_triangle` does).
    models : (T, L) ndarray of int
        Model per triangle and light: a row of `diffuse` (M, 3) and `ambients`
        (M, 3), and table m = ``tables[m]`` (a list of M 1-D arrays).
    polygons : (T,) ndarray of int; owners : (H, W) ndarray of int
        A triangle writes the samples where ``owners == polygons[t]``.
    image : (H, W, 3) float64 ndarray
        Written in place: the lights' clipped levels summed, clipped, / 255.

    Returns
    -------
    int
        Samples written.
    """
    vertices = (units + sample_shift) / scale  # exact: a power-of-two scale
    entries = sum(len(t) for t in tables)
    check_memory(8.0 * entries, f"fast Phong's {len(tables)} specular tables ({entries} entries)")
    flat = np.concatenate([np.zeros(0)] + [np.asarray(t, dtype=np.float64) for t in tables])
    offsets = np.cumsum([0] + [len(t) for t in tables]).astype(np.int64)
    return _shade_batch(
        units.astype(np.int64), np.int64(scale), vertices, normals.astype(np.float64),
        to_lights.astype(np.float64), to_viewers.astype(np.float64), models.astype(np.int64),
        polygons.astype(np.int64), owners.astype(np.int64), expansion == "centroid",
        float(sample_offset), bool(blinn), np.asarray(diffuse, np.float64).reshape(-1, 3),
        np.asarray(ambients, np.float64).reshape(-1, 3), flat, offsets, image,
    )  # fmt: skip

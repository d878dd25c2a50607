"""The per-column area formulas of DISLOP (Wang 1989, ch. 4), in the first-octant frame.

Every formula works in one pixel column, in coordinates centred on the
*middle* pixel, the pixel whose row holds the line (or edge) at the column
centre: the column is x in [-1/2, 1/2], the middle pixel y in [-1/2, 1/2],
and the line is ``y = dxy + m x`` with ``0 <= m <= 1`` and ``-1/2 < dxy <= 1/2``.
The other octants reach this frame by reflection (`scanviz.antialias.line`).

The functions are plain Python and compiled with numba from the same source,
so the traced reference and the compiled kernels do the same float arithmetic.
Derivations: docs/antialiasing.md.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# Branches of the DISLOP_L middle formula (Fig 4-2), as the trace names them.
LINE_BRANCHES = ("flat", "two", "three", "three_triangle")
# Branches of the DISLOP_E formula (Figs 4-5, 4-6).
EDGE_BRANCHES = ("one_pixel", "two_pixel")


def line_column(m: float, dxy: float) -> tuple[float, float, float, float, float, int]:
    """DISLOP_L in one column: (up, mid, low, fcv, scv, branch) of a 1-pixel-wide line.

    The band ``|y - dxy - m x| <= Ta / 2``, Ta = sqrt(1 + m^2), covers Ta per
    column; `up` is its part above the middle pixel, `low` below, `mid` the rest.
    `branch` indexes `LINE_BRANCHES`. Exact for m <= 0.75; above, the band can
    reach a fourth pixel, whose area the formula credits to `up` or `low`.

    >>> [round(v, 4) for v in line_column(math.tan(math.radians(5)), 0.0)[:3]]
    [0.0119, 0.98, 0.0119]
    """
    thickness = math.sqrt(1.0 + m * m)  # Ta = 1 / cos(a): the band's vertical thickness
    dw = thickness - 1.0
    fcv = 0.5 * (m + dw)  # first critical value: past it the lower pixel is untouched
    ad = abs(dxy)
    scv = ad + 0.5 * dw  # second critical value: the mean overhang above the middle pixel
    if m == 0.0:
        up, low, branch = ad, 0.0, 0
    elif ad > fcv:  # the band stays clear of the lower pixel: two pixels
        up, low, branch = scv, 0.0, 1
    elif scv > 0.5 * m:  # the overhang above is a trapezoid, the one below a triangle
        up, low, branch = scv, (fcv - ad) * (fcv - ad) / (2.0 * m), 2
    else:  # both overhangs are triangles
        up, low = (ad + fcv) * (ad + fcv) / (2.0 * m), (fcv - ad) * (fcv - ad) / (2.0 * m)
        branch = 3
    if dxy < 0.0:  # reflect about the middle pixel's centre line
        up, low = low, up
    return up, thickness - up - low, low, fcv, scv, branch


def ramp_mean(h: float, m: float) -> float:
    """Mean of clamp(h + m x, 0, 1) over x in [-1/2, 1/2]: a column's area under a line.

    >>> ramp_mean(0.5, 0.0), ramp_mean(0.0, 1.0), ramp_mean(2.0, 1.0)
    (0.5, 0.125, 1.0)
    """
    low, high = h - 0.5 * m, h + 0.5 * m
    if high <= 0.0:
        return 0.0
    if low >= 1.0:
        return 1.0
    if low >= 0.0 and high <= 1.0:  # no clamping: the mean of a linear function
        return h
    inside_low, inside_high = max(low, 0.0), min(high, 1.0)
    area = 0.5 * (inside_high - inside_low) * (inside_high + inside_low) + max(high - 1.0, 0.0)
    return area / m


def band_row(m: float, dxy: float, row: int) -> float:
    """Exact area of the infinite band |y - dxy - m x| <= Ta/2 in pixel `row` of the column.

    `row` counts from the middle pixel (0), up positive.

    >>> round(band_row(1.0, 0.5, 2), 6), round(band_row(1.0, 0.5, 1), 6)
    (0.021447, 0.68566)
    """
    half = 0.5 * math.sqrt(1.0 + m * m)
    bottom = row - 0.5
    return ramp_mean(dxy + half - bottom, m) - ramp_mean(dxy - half - bottom, m)


def edge_column(m: float, dxy: float, flag: int) -> tuple[float, float, float, float, float, int]:
    """DISLOP_E in one column: (up, mid, low, cv, corner, branch) of the polygon's side of an edge.

    ``flag == 1``: the edge is on the top of the polygon (inside below);
    ``flag == 0``: on the bottom (inside above). Only the pixels the edge cuts
    are reported; the others are 0 here (the polygon fill covers them). `cv`
    is the critical value (> 0: the edge leaves the middle pixel), `corner`
    the triangle AA it cuts off beyond the middle pixel (0 if it does not),
    `branch` indexes `EDGE_BRANCHES`. Exact for all m in [0, 1].

    >>> [round(v, 4) for v in edge_column(math.tan(math.radians(40)), -0.5, 1)[:3]]
    [0.0, 0.1049, 0.8951]
    """
    ad = abs(dxy)
    cv = ad + 0.5 * (m - 1.0)
    if m == 0.0 or cv < 0.0:  # the edge stays inside the middle pixel
        return 0.0, (0.5 + dxy if flag == 1 else 0.5 - dxy), 0.0, cv, 0.0, 0
    corner = cv * cv / (2.0 * m)  # AA: the triangle cut off beyond the middle pixel
    if dxy > 0.0:
        up = corner if flag == 1 else 1.0 - corner
        return up, (0.5 + ad if flag == 1 else 1.5 - ad) - up, 0.0, cv, corner, 1
    low = 1.0 - corner if flag == 1 else corner
    return 0.0, (1.5 - ad if flag == 1 else 0.5 + ad) - low, low, cv, corner, 1


def clip_area(xs, ys, n, x0: float, y0: float, x1: float, y1: float, work) -> float:
    """Area of the polygon (xs[:n], ys[:n]) inside the box [x0, x1] x [y0, y1], signed.

    Sutherland-Hodgman against the four sides, then the shoelace formula;
    `work` is a (4, 2 n + 8) float64 scratch array. Exact for any simple
    polygon (the clipped pieces of a non-convex one may share zero-area seams).
    """
    count = n
    source = 0
    for i in range(count):
        work[0, i], work[1, i] = xs[i], ys[i]
    for side in range(4):
        target = 2 - source
        kept = 0
        for i in range(count):
            ax, ay = (
                work[source, i - 1 if i > 0 else count - 1],
                work[source + 1, i - 1 if i > 0 else count - 1],
            )
            bx, by = work[source, i], work[source + 1, i]
            if side == 0:
                da, db = ax - x0, bx - x0
            elif side == 1:
                da, db = x1 - ax, x1 - bx
            elif side == 2:
                da, db = ay - y0, by - y0
            else:
                da, db = y1 - ay, y1 - by
            if (da >= 0.0) != (db >= 0.0):  # the edge crosses the side: keep the crossing
                t = da / (da - db)
                work[target, kept], work[target + 1, kept] = ax + t * (bx - ax), ay + t * (by - ay)
                kept += 1
            if db >= 0.0:
                work[target, kept], work[target + 1, kept] = bx, by
                kept += 1
        count, source = kept, target
    area = 0.0
    for i in range(count):
        j = i - 1 if i > 0 else count - 1
        area += work[source, j] * work[source + 1, i] - work[source, i] * work[source + 1, j]
    return 0.5 * area


def band_corners(u0: float, v0: float, u1: float, v1: float, slope: float):
    """(xs, ys): the corners of the 1-wide band around the segment, counter-clockwise.

    >>> [v.tolist() for v in band_corners(0.0, 0.0, 2.0, 0.0, 0.0)]
    [[0.0, 2.0, 2.0, 0.0], [-0.5, -0.5, 0.5, 0.5]]
    """
    thickness = math.sqrt(1.0 + slope * slope)
    nx, ny = -0.5 * slope / thickness, 0.5 / thickness  # half the unit normal, pointing up
    xs = np.array([u0 - nx, u1 - nx, u1 + nx, u0 + nx])
    ys = np.array([v0 - ny, v1 - ny, v1 + ny, v0 + ny])
    return xs, ys


line_column_compiled = njit(cache=True)(line_column)
band_corners_compiled = njit(cache=True)(band_corners)
ramp_mean_compiled = njit(cache=True)(ramp_mean)
edge_column_compiled = njit(cache=True)(edge_column)
clip_area_compiled = njit(cache=True)(clip_area)


@njit(cache=True)
def band_row_compiled(m, dxy, row):  # pragma: no cover - compiled copy of `band_row`
    half = 0.5 * math.sqrt(1.0 + m * m)
    bottom = row - 0.5
    return ramp_mean_compiled(dxy + half - bottom, m) - ramp_mean_compiled(dxy - half - bottom, m)

"""Independent exact oracles for the DISLOP tests: disk-in-box area in closed form, bands by shapely."""

from __future__ import annotations

import math

import numpy as np
import shapely


def _disk_below(x0: float, x1: float, y: float, r: float) -> float:
    """Area of {x0 <= X <= x1, Y <= y} inside the disk of radius r at the origin (x0 <= x1)."""

    def s(x):
        return math.sqrt(max(r * r - x * x, 0.0))

    def half(x):  # antiderivative of s
        x = min(max(x, -r), r)
        return 0.5 * (x * s(x) + r * r * math.asin(x / r))

    x0, x1 = max(x0, -r), min(x1, r)
    if x1 <= x0:
        return 0.0
    # the integrand min(y, s) - (-s), clipped at 0: break where s(x) = |y|
    cut = math.sqrt(max(r * r - y * y, 0.0)) if abs(y) < r else 0.0
    points = sorted({x0, x1, *(p for p in (-cut, cut) if x0 < p < x1)})
    total = 0.0
    for a, b in zip(points, points[1:], strict=False):
        mid = 0.5 * (a + b)
        if y >= s(mid):  # the whole chord lies below y
            total += 2.0 * (half(b) - half(a))
        elif y > -s(mid):  # from the bottom of the circle to y
            total += (half(b) - half(a)) + y * (b - a)
    return total


def disk_box_area(cx, cy, r, x0, y0, x1, y1) -> float:
    """Exact area of the disk (centre (cx, cy), radius r) inside the box [x0, x1] x [y0, y1]."""
    if r <= 0.0:
        return 0.0
    a, b = x0 - cx, x1 - cx
    return _disk_below(a, b, y1 - cy, r) - _disk_below(a, b, y0 - cy, r)


def disk_coverage(cx, cy, r, width, height) -> np.ndarray:
    """Exact (height, width) coverage of pixels [x, x+1] x [y, y+1] by the disk."""
    image = np.zeros((height, width))
    for y in range(max(0, math.floor(cy - r)), min(height, math.ceil(cy + r) + 1)):
        for x in range(max(0, math.floor(cx - r)), min(width, math.ceil(cx + r) + 1)):
            image[y, x] = disk_box_area(cx, cy, r, x, y, x + 1, y + 1)
    return image


def ring_coverage(cx, cy, r, width, height) -> np.ndarray:
    """Exact coverage by the annulus r - 1/2 <= distance <= r + 1/2 (r >= 1/2)."""
    return disk_coverage(cx, cy, r + 0.5, width, height) - disk_coverage(
        cx, cy, r - 0.5, width, height
    )


def band_coverage(p0, p1, width, height) -> np.ndarray:
    """Coverage by the square-ended rectangle of width 1 on segment p0-p1 (shapely, exact clipping)."""
    band = shapely.LineString([p0, p1]).buffer(0.5, cap_style="flat")
    image = np.zeros((height, width))
    if band.is_empty:
        return image
    xmin, ymin, xmax, ymax = band.bounds
    for y in range(max(0, math.floor(ymin)), min(height, math.ceil(ymax))):
        for x in range(max(0, math.floor(xmin)), min(width, math.ceil(xmax))):
            image[y, x] = band.intersection(shapely.box(x, y, x + 1, y + 1)).area
    return image

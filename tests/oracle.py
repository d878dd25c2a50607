"""An exact oracle for scan conversion, written independently of `scanviz.raster`.

It shares no code with the scan converter: vertices are snapped again here
from the float input, and every sample is decided by the winding number of
the point (sx + eps, sy + eps**2) for an infinitesimal eps > 0 (DESIGN §2).

Derivation of the per-row rule used by `oracle_mask`, from `winding_number`:

* The ray from P = (sx + eps, sy + eps**2) to the right meets the line of an
  edge between y0 and y1 iff exactly one endpoint is above P. ``y > sy + eps**2``
  holds iff ``y > sy`` (eps**2 is smaller than any positive real), so the edge
  counts on row sy iff ``min(y0, y1) <= sy < max(y0, y1)``. Horizontal edges
  never count.
* Where it meets, x(eps) - (sx + eps) = D - eps + k * eps**2 with
  ``D = x_c - sx`` (x_c the crossing at height sy, k = dx/dy). The crossing lies
  right of P iff D > 0, or D == 0 and -1 > 0 (never): iff ``sx < x_c``.
* So an edge adds its winding to exactly the samples ``sx < x_c`` of its row:
  pixels ``px < ceil(x_c - offset)`` where ``sx = px + offset``.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np


def snapped_contours(contours, bits: int | None) -> list[list[tuple[Fraction, Fraction]]]:
    """The contours' vertices as exact Fractions on the 1/2**bits grid (unrounded for None).

    >>> snapped_contours([[(0.1, 0.5), (1.3, 0.75), (0.0, 2.0)]], 2)[0][:2]
    [(Fraction(0, 1), Fraction(1, 2)), (Fraction(5, 4), Fraction(3, 4))]
    """

    def snap_value(value: float) -> Fraction:
        if bits is None:
            return Fraction(float(value))
        return Fraction(int(np.rint(float(value) * 2.0**bits)), 2**bits)

    return [[(snap_value(x), snap_value(y)) for x, y in contour] for contour in contours]


def _sign(*coefficients: Fraction) -> int:
    """Sign of c0 + c1*eps + c2*eps**2 + ... for an infinitesimal eps > 0."""
    for c in coefficients:
        if c:
            return 1 if c > 0 else -1
    return 0


def winding_number(contours, sx: Fraction, sy: Fraction) -> int:
    """Winding number of (sx + eps, sy + eps**2) around exact contours (crossing count).

    >>> square = [[(0, 0), (2, 0), (2, 2), (0, 2)]]
    >>> [winding_number(square, x, y) for x, y in [(0, 0), (2, 0), (0, 2), (1, 1), (-1, 1)]]
    [1, 0, 0, 1, 0]
    """
    total = 0
    for contour in contours:
        for (x0, y0), (x1, y1) in zip(contour, contour[1:] + contour[:1], strict=True):
            above0 = _sign(y0 - sy, 0, -1) > 0
            above1 = _sign(y1 - sy, 0, -1) > 0
            if above0 == above1:
                continue
            k = Fraction(x1 - x0) / (y1 - y0)
            crossing_minus_point = _sign(x0 + (sy - y0) * k - sx, -1, k)
            if crossing_minus_point > 0:
                total += 1 if y1 > y0 else -1
    return total


def _integer_grid(contours) -> tuple[list[list[tuple[int, int]]], int]:
    """Exact contours scaled to Python ints, and the (even) scale that did it."""
    denominators = [v.denominator for contour in contours for point in contour for v in point]
    scale = 2 * max(denominators)  # every denominator is a power of two; 2x holds the 1/2 offset
    return [[(int(x * scale), int(y * scale)) for x, y in c] for c in contours], scale


def winding_image(polygon, width: int, height: int, sample: str, subpixel_bits) -> np.ndarray:
    """Winding number of every sample: (height, width) ndarray of int64 (row 0 at the bottom)."""
    contours = [np.asarray(c, dtype=np.float64).tolist() for c in polygon.contours]
    grid, scale = _integer_grid(snapped_contours(contours, subpixel_bits))
    offset = scale // 2 if sample == "center" else 0  # sample offset in grid units
    delta = np.zeros((height, width + 1), dtype=np.int64)
    for contour in grid:
        for (x0, y0), (x1, y1) in zip(contour, contour[1:] + contour[:1], strict=True):
            if y0 == y1:
                continue
            winding = 1 if y1 > y0 else -1
            (xa, ya), (xb, yb) = sorted([(x0, y0), (x1, y1)], key=lambda p: p[1])
            dx, dy = xb - xa, yb - ya
            first = max(0, -((offset - ya) // scale))  # rows with ya <= row*scale + offset
            stop = min(height, -((offset - yb) // scale))  # ... and row*scale + offset < yb
            for row in range(first, stop):
                sy = row * scale + offset
                # ceil((x_c - offset) / scale), x_c = xa + (sy - ya) * dx / dy
                numerator = (xa - offset) * dy + (sy - ya) * dx
                pixels = -((-numerator) // (dy * scale))
                delta[row, 0] += winding
                delta[row, min(max(pixels, 0), width)] -= winding
    return np.cumsum(delta, axis=1)[:, :width]


def oracle_mask(
    polygon, width: int, height: int, sample: str, rule: str, subpixel_bits: int | None
) -> np.ndarray:
    """Covered samples by the exact winding number: (height, width) ndarray of bool.

    `polygon` is a `scanviz.Polygon` (only its float contours are read).

    >>> from scanviz import Polygon
    >>> oracle_mask(Polygon([(0, 0), (4, 0), (4, 3)]), 5, 3, "corner", "nonzero", 8)[::-1].astype(int)
    array([[0, 0, 0, 1, 0],
           [0, 0, 1, 1, 0],
           [1, 1, 1, 1, 0]])
    """
    winding = winding_image(polygon, width, height, sample, subpixel_bits)
    return (winding % 2 == 1) if rule == "evenodd" else (winding != 0)


def point_oracle_mask(polygon, width, height, sample, rule, subpixel_bits) -> np.ndarray:
    """`oracle_mask` by calling `winding_number` per sample: slow, to check the row formula."""
    contours = [np.asarray(c, dtype=np.float64).tolist() for c in polygon.contours]
    exact = snapped_contours(contours, subpixel_bits)
    offset = Fraction(1, 2) if sample == "center" else Fraction(0)
    mask = np.zeros((height, width), dtype=bool)
    for y in range(height):
        for x in range(width):
            w = winding_number(exact, x + offset, y + offset)
            mask[y, x] = w % 2 == 1 if rule == "evenodd" else w != 0
    return mask

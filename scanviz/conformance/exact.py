"""Exact oracles for the conformance suite, written apart from the code they check.

Nothing here calls the raster, area or mask code: vertices are snapped again
from the float input with `fractions.Fraction`, and every decision is exact.

* `snap_contours`: vertices on the 1/2**bits grid (round half to even, as
  ``numpy.rint``), or the float64 values exactly for ``bits=None``.
* `lattice_winding`: the winding number of every sample of a regular lattice,
  each sample (sx, sy) taken as the point (sx + eps, sy + eps**2) for an
  infinitesimal eps > 0 (DESIGN §2). The ray to the right from that point
  meets an edge iff ``min(y0, y1) <= sy < max(y0, y1)``, and the crossing lies
  right of it iff ``sx < x_c`` (x_c the crossing at height sy): if x_c == sx
  the point sits eps to its right. Horizontal edges never count.
* `box_area`: the signed area of a contour clipped to an axis-aligned box
  (Sutherland-Hodgman). Clipping against a half-plane keeps the winding number
  inside it, so this is the integral of the winding number over the box: the
  covered area wherever the winding is 0 or 1.
* `barycentric`: exact barycentric weights of a point in a triangle.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

Point = tuple[Fraction, Fraction]


def snap_value(value: float, bits: int | None) -> Fraction:
    """`value` on the 1/2**bits grid, ties to even (`round` of a Fraction rounds half to even).

    >>> snap_value(0.3, 2), snap_value(0.375, 2), snap_value(0.625, 2), snap_value(0.1, None)
    (Fraction(1, 4), Fraction(1, 2), Fraction(1, 2), Fraction(3602879701896397, 36028797018963968))
    """
    exact = Fraction(float(value))
    if bits is None:
        return exact
    return Fraction(round(exact * 2**bits), 2**bits)


def snap_contours(contours, bits: int | None) -> list[list[Point]]:
    """Every contour's vertices snapped exactly: lists of (x, y) Fractions."""
    return [[(snap_value(x, bits), snap_value(y, bits)) for x, y in c] for c in contours]


def _edges(contour: list[Point]):
    return zip(contour, contour[1:] + contour[:1], strict=True)


def lattice_winding(
    contours: list[list[Point]],
    shape: tuple[int, int],
    origin: tuple[Fraction, Fraction] = (Fraction(0), Fraction(0)),
    step: tuple[Fraction, Fraction] = (Fraction(1), Fraction(1)),
) -> np.ndarray:
    """Winding numbers of the samples (ox + i * sx, oy + j * sy), i < nx, j < ny: (ny, nx) int64.

    `shape` is (nx, ny). Coordinates are scaled to a common integer grid, so
    every comparison is an exact integer one.

    >>> square = [[(0, 0), (2, 0), (2, 2), (0, 2)]]
    >>> lattice_winding(snap_contours(square, 8), (3, 3))[::-1].tolist()  # top row first
    [[0, 0, 0], [1, 1, 0], [1, 1, 0]]
    """
    (nx, ny), (ox, oy), (sx, sy) = shape, origin, step
    values = [ox, oy, sx, sy, *(v for c in contours for p in c for v in p)]
    scale = math.lcm(*(Fraction(v).denominator for v in values))

    def grid(v) -> int:
        return int(Fraction(v) * scale)

    ox, oy, sx, sy = grid(ox), grid(oy), grid(sx), grid(sy)
    delta = np.zeros((ny, nx + 1), dtype=np.int64)
    for contour in contours:
        for (x0, y0), (x1, y1) in _edges([(grid(x), grid(y)) for x, y in contour]):
            if y0 == y1:
                continue
            winding = 1 if y1 > y0 else -1
            (xa, ya), (xb, yb) = sorted([(x0, y0), (x1, y1)], key=lambda p: p[1])
            dx, dy = xb - xa, yb - ya
            first = max(0, -((oy - ya) // sy))  # rows with ya <= oy + j * sy
            stop = min(ny, -((oy - yb) // sy))  # ... and oy + j * sy < yb
            for j in range(first, stop):
                # samples i with ox + i * sx < x_c: i < ceil((x_c - ox) / sx)
                numerator = (xa - ox) * dy + (oy + j * sy - ya) * dx
                count = -((-numerator) // (dy * sx))
                delta[j, 0] += winding
                delta[j, min(max(count, 0), nx)] -= winding
    return np.cumsum(delta, axis=1)[:, :nx]


def sample_winding(contours, width: int, height: int, sample: str = "corner") -> np.ndarray:
    """Winding number at every pixel sample ((x, y) or (x + 1/2, y + 1/2)): (height, width)."""
    offset = Fraction(1, 2) if sample == "center" else Fraction(0)
    return lattice_winding(contours, (width, height), (offset, offset))


def inside(winding: np.ndarray, rule: str = "nonzero") -> np.ndarray:
    """Which winding numbers are inside under `rule` ("nonzero" or "evenodd")."""
    return winding % 2 == 1 if rule == "evenodd" else winding != 0


def oracle_mask(
    contours, width: int, height: int, sample="corner", rule="nonzero", bits: int | None = 8
) -> np.ndarray:
    """The covered samples of float contours (snapped here), as `scan_convert` must give them."""
    return inside(sample_winding(snap_contours(contours, bits), width, height, sample), rule)


def _clip(points: list[Point], axis: int, bound: Fraction, keep_above: bool) -> list[Point]:
    """Sutherland-Hodgman: the part of a closed contour with coordinate `axis` >= (<=) bound."""

    def kept(p: Point) -> bool:
        return p[axis] >= bound if keep_above else p[axis] <= bound

    result: list[Point] = []
    for a, b in _edges(points) if points else ():
        if kept(a):
            result.append(a)
        if kept(a) != kept(b):
            t = (bound - a[axis]) / (b[axis] - a[axis])
            result.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    return result


def signed_area(points: list[Point]) -> Fraction:
    """Shoelace area, positive counter-clockwise."""
    return sum((a[0] * b[1] - b[0] * a[1] for a, b in _edges(points)), Fraction(0)) / 2


def box_area(contour: list[Point], x0, y0, x1, y1) -> Fraction:
    """Signed area of `contour` clipped to [x0, x1] x [y0, y1]: the integral of its winding there.

    >>> triangle = [(Fraction(0), Fraction(0)), (Fraction(2), Fraction(0)), (Fraction(0), Fraction(1))]
    >>> box_area(triangle, 0, 0, 1, 1), box_area(triangle, 1, 0, 2, 1)
    (Fraction(3, 4), Fraction(1, 4))
    """
    points = contour
    for axis, bound, above in ((0, x0, True), (0, x1, False), (1, y0, True), (1, y1, False)):
        points = _clip(points, axis, Fraction(bound), above)
    return signed_area(points)


def coverage(contours: list[list[Point]], width: int, height: int) -> np.ndarray:
    """Per pixel, the integral of the winding number over the pixel square: (height, width) of Fraction.

    Equals the covered area when the winding is 0 or 1 everywhere (simple
    counter-clockwise contours, holes clockwise inside them).
    """
    image = np.full((height, width), Fraction(0), dtype=object)
    for contour in contours:
        xs, ys = [p[0] for p in contour], [p[1] for p in contour]
        for y in range(max(0, math.floor(min(ys))), min(height, math.ceil(max(ys)))):
            for x in range(max(0, math.floor(min(xs))), min(width, math.ceil(max(xs)))):
                image[y, x] += box_area(contour, x, y, x + 1, y + 1)
    return image


def barycentric(triangle: list[Point], px: Fraction, py: Fraction) -> tuple[Fraction, ...]:
    """Exact barycentric weights of (px, py) with respect to the triangle's three vertices.

    >>> [str(w) for w in barycentric([(0, 0), (4, 0), (0, 4)], Fraction(1), Fraction(1))]
    ['1/2', '1/4', '1/4']
    """
    (x0, y0), (x1, y1), (x2, y2) = triangle
    area2 = Fraction((x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0))
    w1 = ((px - x0) * (y2 - y0) - (py - y0) * (x2 - x0)) / area2
    w2 = ((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)) / area2
    return 1 - w1 - w2, w1, w2

"""The exact side of a cut: which piece of a split polygon owns a point, decided without rounding.

Cutting polygon p by the plane of polygon q sorts p's points by the sign of
the depth difference of the two planes,

    gap(x, y) = z_p(x, y) - z_q(x, y),   z(x, y) = z0 + dzdx (x - x0) + dzdy (y - y0),

taken *exactly* on the planes' float coefficients (each plane is the five
numbers `scanviz.raster.interpolate.plane_depth` takes): > 0 is behind q's
plane. Rounded, the sign is noise wherever the planes are nearly parallel,
so a rounded cut scatters samples between the pieces far from the line the
pieces' vertices describe; exact, the pieces are the polygon on either side
of one straight line, and their vertices (clipped at that line) describe
their samples to the last bit of a double.

A point on the line (gap exactly 0) goes to the piece on its +x side, or
its +y side when the line is parallel to x: the fill rule's ownership
(`scanviz.conventions`: a polygon owns no sample on its maximum border), so
"touching extents are apart" holds for pieces as for polygons.

The arithmetic is a float filter, then Shewchuk's exact expansions (1997,
"Adaptive precision floating-point arithmetic and fast robust geometric
predicates", sections 2.5-2.6) where the filter cannot decide: the gap is a
sum of 18 exactly computed products and differences, summed without loss.
It is exact for coefficients whose products neither overflow nor
underflow (magnitudes between about 1e-150 and 1e150).
"""

from __future__ import annotations

import numpy as np
from numba import njit

_FILTER = 1e-15  # > 8 eps: bounds the rounding of the plain evaluation below, relative to its terms
_SPLITTER = 134217729.0  # 2**27 + 1: splits a double into two 26-bit halves (Dekker 1971)


@njit(cache=True, inline="always")
def _two_sum(a, b):
    """(s, e) with s = fl(a + b) and s + e = a + b exactly (Knuth)."""
    s = a + b
    virtual = s - a
    return s, (a - (s - virtual)) + (b - virtual)


@njit(cache=True, inline="always")
def _two_product(a, b):
    """(p, e) with p = fl(a * b) and p + e = a * b exactly (Dekker)."""
    p = a * b
    c = _SPLITTER * a
    a_high = c - (c - a)
    a_low = a - a_high
    c = _SPLITTER * b
    b_high = c - (c - b)
    b_low = b - b_high
    return p, a_low * b_low - (((p - a_high * b_high) - a_low * b_high) - a_high * b_low)


@njit(cache=True, inline="always")
def _grow(expansion, size, value):
    """Add `value` to the nonoverlapping expansion[:size] (Shewchuk's Grow-Expansion); new size."""
    for i in range(size):
        value, expansion[i] = _two_sum(value, expansion[i])
    expansion[size] = value
    return size + 1


@njit(cache=True, inline="always")
def _add_plane(expansion, size, plane, sign, x, y):
    """Add sign * plane's depth at (x, y), exactly: z0 + dzdx (x - x0) + dzdy (y - y0)."""
    size = _grow(expansion, size, sign * plane[2])
    for slope, at, origin in ((plane[3], x, plane[0]), (plane[4], y, plane[1])):
        difference, rest = _two_sum(at, -origin)
        for part in (difference, rest):
            product, error = _two_product(sign * slope, part)
            size = _grow(expansion, size, product)
            size = _grow(expansion, size, error)
    return size


@njit(cache=True, inline="always")
def _compensated(own, other, x, y):
    """(value, bound): the gap summed in twice the working precision (Ogita, Rump and Oishi's
    Dot2, 2005) and the least |value| for which it is the exact gap rounded to a few ulps:
    its error is below eps |gap| + gamma_10 ** 2 (about 1.2e-30) x the sum of |terms|."""
    total, carry, size = 0.0, 0.0, 0.0
    for plane, sign in ((own, 1.0), (other, -1.0)):
        total, error = _two_sum(total, sign * plane[2])
        carry += error
        size += abs(plane[2])
        for slope, at, origin in ((plane[3], x, plane[0]), (plane[4], y, plane[1])):
            difference, rest = _two_sum(at, -origin)
            for part in (difference, rest):
                product, low = _two_product(sign * slope, part)
                total, error = _two_sum(total, product)
                carry += error + low
                size += abs(product)
    return total + carry, 1e-15 * size


@njit(cache=True)
def gap(own, other, x, y):
    """z_own(x, y) - z_other(x, y), exact and then rounded (so its sign is exact).

    `own` and `other` are planes (x0, y0, z0, dzdx, dzdy). Summed in twice
    the working precision; where even that cannot vouch for the sign, summed
    exactly.

    >>> a = np.array([0.0, 0.0, 0.1, 0.1, 0.0]); b = np.array([0.0, 0.0, 0.0, 0.2, 0.0])
    >>> float(gap(a, b, 1.0, 0.0)), gap(a, b, 0.5, 0.0) > 0, gap(a, b, 2.0, 0.0) < 0
    (0.0, True, True)
    """
    value, bound = _compensated(own, other, x, y)
    if abs(value) > bound:
        return value
    expansion = np.empty(18)
    size = _add_plane(expansion, 0, own, 1.0, x, y)
    size = _add_plane(expansion, size, other, -1.0, x, y)
    total = 0.0
    for i in range(size):  # smallest first: the rounded sum keeps the sign of the largest
        total += expansion[i]
    return total


@njit(cache=True)
def side(own, other, x, y) -> int:
    """The sign of `gap` (1, 0 or -1): the plain evaluation where its rounding cannot flip it."""
    terms = 0.0
    value = 0.0
    for plane, sign in ((own, 1.0), (other, -1.0)):
        dx, dy = x - plane[0], y - plane[1]
        value += sign * (plane[2] + plane[3] * dx + plane[4] * dy)
        terms += abs(plane[2]) + abs(plane[3] * dx) + abs(plane[4] * dy)
    if abs(value) <= _FILTER * terms:
        value = gap(own, other, x, y)
    return (value > 0.0) - (value < 0.0)


@njit(cache=True)
def gaps(owns, other, xs, ys):
    """`gap` of plane owns[i] at every point (xs[i], ys[i]): (n,) ndarray of float64."""
    out = np.empty(xs.shape[0])
    for i in range(xs.shape[0]):
        out[i] = gap(owns[i], other, xs[i], ys[i])
    return out


@njit(cache=True)
def behind_owns_line(own, other) -> bool:
    """Whether the piece behind `other`'s plane owns the points on the cut line (gap == 0).

    The piece on the line's +x side owns it (+y when the line is parallel
    to x): the gap grows towards the behind piece along the gradient
    (dzdx_own - dzdx_other, dzdy_own - dzdy_other), whose signs compare exactly.
    """
    if own[3] != other[3]:
        return own[3] > other[3]
    return own[4] > other[4]


@njit(cache=True)
def keeps(cuts, x, y) -> bool:
    """Whether sample (x, y) is on the kept side of every cut of a piece.

    A cut row (11 numbers) is the piece's plane, the cutting polygon's plane
    (five numbers each) and 1.0 to keep the samples behind that plane, 0.0
    to keep the others.
    """
    for i in range(cuts.shape[0]):
        own, other = cuts[i, 0:5], cuts[i, 5:10]
        sign = side(own, other, float(x), float(y))
        behind = sign > 0 or (sign == 0 and behind_owns_line(own, other))
        if behind != (cuts[i, 10] == 1.0):
            return False
    return True

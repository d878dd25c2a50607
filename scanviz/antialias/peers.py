"""The classic line anti-aliasers, beside DISLOP_L: Wu, Gupta-Sproull, supersampling, masks, exact area.

Every line function draws the same 1-pixel-wide segment p0-p1 (the band of
width 1 centred on it, flat ends at the endpoints, as `dislop_line`) on a
``width`` x ``height`` raster and returns the (height, width) float64
coverage, row 0 at the bottom, pixel (x, y) the unit square [x, x+1] x
[y, y+1] (DESIGN §2). The endpoints ``p0, p1`` are (2,) array_like of float,
(x, y) in pixels within +-2**20, the size ints in 0..2**16; anything else
raises a TypeError or ValueError naming the argument. The docstrings below
list only their functions' further parameters and errors. The loops are
compiled (numba) so that the benchmark compares algorithms, not
interpreters; `exact_band_line` and `abuffer_line` call scanviz's own
compiled area and mask code.

* `wu_line`: Xiaolin Wu (1991), real endpoints: the centre line's height at
  each major-axis pixel centre is split between the two nearest pixels by its
  fractional part; the end columns are weighted by the part of the column
  the segment spans (the "xgap" of the usual pseudo-code).
* `gupta_sproull_line`: Gupta & Sproull (1981) as Foley-van Dam §3.17.3
  give it: the midpoint line's pixel and its two minor-axis neighbours, each
  given the cone filter's volume over the band at its distance D from the
  centre line, looked up in a table of 1/16-pixel steps.
* `supersampled_line`: k x k point samples per pixel, averaged.
* `abuffer_line`: the bits of the band's a-buffer pixel mask, as a fraction
  (corners snapped to 1/256 pixel by default, as the a-buffer does).
* `exact_band_line`: the exact area (`area_coverage` of the rectangle), the
  ground truth.

Derivations and measured errors: docs/antialias-bench.md.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..abuffer.area import area_coverage
from ..abuffer.masks import MASK_LAYOUTS, pixel_masks, popcount
from ..conventions import check_choice, check_int, check_subpixel_bits
from ._inputs import check_point, new_raster

__all__ = [
    "GS_STEPS",
    "abuffer_line",
    "band_rectangle",
    "cone_band_volume",
    "exact_band_line",
    "gupta_sproull_line",
    "supersampled_line",
    "wu_line",
]

MAX_SAMPLES = 64  # k x k samples per pixel, k at most this
GS_STEPS = 16  # Gupta-Sproull table entries per pixel of distance


# ---------------------------------------------------------------- Wu


def wu_line(p0: object, p1: object, width: int, height: int) -> np.ndarray:
    """Xiaolin Wu's anti-aliased line (1991), with real endpoints.

    Returns
    -------
    (height, width) ndarray of float64
        Intensity of each pixel in [0, 1], row 0 at the bottom.

    Notes
    -----
    The variant is the real-endpoint form of Wu's algorithm in the widely
    copied pseudo-code (Wikipedia, "Xiaolin Wu's line algorithm"), in
    pixel-centred coordinates (ours minus 1/2): the major axis is x unless
    |dy| > |dx|; in each major column c the centre line's height v(c) is
    split between rows floor(v) and floor(v) + 1 by 1 - frac(v) and frac(v).
    The end columns round(u0), round(u1) (round = floor(u + 1/2)) take the
    centre line's height there times the part of the column the segment spans
    (1 - frac(u0 + 1/2), frac(u1 + 1/2)). One change: when both ends fall in
    the same column the pseudo-code plots it twice; here it gets the weight
    u1 - u0 once. Every column sums to 1, so the total is the major-axis
    extent |u1 - u0|, not the length: a 45-degree line is 1/sqrt(2) as bright
    per unit length as a horizontal one (Wang's criticism of such methods).

    Examples
    --------
    >>> wu_line((0, 1.25), (4, 1.25), 4, 3)[::-1]  # top row first
    array([[0.  , 0.  , 0.  , 0.  ],
           [0.75, 0.75, 0.75, 0.75],
           [0.25, 0.25, 0.25, 0.25]])
    """
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    image = new_raster(width, height, "wu_line")
    _wu_kernel(x0 - 0.5, y0 - 0.5, x1 - 0.5, y1 - 0.5, image)
    return image


@njit(cache=True, inline="always")
def _along_major_axis(u0, v0, u1, v1):
    """(steep, u0, v0, u1, v1): the segment with u the major axis (x and y swapped if steep), u0 <= u1."""
    steep = abs(v1 - v0) > abs(u1 - u0)
    if steep:
        u0, v0, u1, v1 = v0, u0, v1, u1
    if u0 > u1:
        u0, v0, u1, v1 = u1, v1, u0, v0
    return steep, u0, v0, u1, v1


@njit(cache=True, inline="always")
def _plot(image, steep, major, minor, value):
    column, row = (minor, major) if steep else (major, minor)
    if 0 <= row < image.shape[0] and 0 <= column < image.shape[1]:
        image[row, column] += value


@njit(cache=True, inline="always")
def _plot_pair(image, steep, major, v, weight):
    """Split `weight` between the two rows nearest the centre line's height v."""
    row = math.floor(v)
    fraction = v - row
    _plot(image, steep, major, row, (1.0 - fraction) * weight)
    _plot(image, steep, major, row + 1, fraction * weight)


@njit(cache=True)
def _wu_kernel(u0, v0, u1, v1, image):  # pragma: no cover - compiled
    steep, u0, v0, u1, v1 = _along_major_axis(u0, v0, u1, v1)
    gradient = (v1 - v0) / (u1 - u0) if u1 > u0 else 1.0
    first, last = math.floor(u0 + 0.5), math.floor(u1 + 0.5)
    if first == last:  # both ends in one column: the part of it the segment spans
        _plot_pair(image, steep, first, v0 + gradient * (first - u0), u1 - u0)
        return
    gap0 = 1.0 - (u0 + 0.5 - math.floor(u0 + 0.5))
    gap1 = u1 + 0.5 - math.floor(u1 + 0.5)
    _plot_pair(image, steep, first, v0 + gradient * (first - u0), gap0)
    _plot_pair(image, steep, last, v1 + gradient * (last - u1), gap1)
    extent = image.shape[0] if steep else image.shape[1]
    for column in range(max(first + 1, 0), min(last, extent)):  # only columns on the raster
        _plot_pair(image, steep, column, v0 + gradient * (column - u0), 1.0)


# ---------------------------------------------------------------- Gupta-Sproull


def cone_band_volume(distance: float) -> float:
    """Volume of the unit-volume cone of radius 1 over a band of width 1 at `distance` from its apex.

    The cone's marginal across the band is g(t) = (3/pi)(w - t**2 ln((1 + w)/|t|)),
    w = sqrt(1 - t**2); its integral from 0 is
    G(t) = (2 t w + asin t - t**3 ln((1 + w)/t)) / pi, G(1) = 1/2; the
    volume is G(D + 1/2) - G(D - 1/2).

    >>> round(cone_band_volume(0.0), 4), cone_band_volume(1.5)
    (0.7799, 0.0)
    """

    def integral(t: float) -> float:  # G, odd, constant 1/2 beyond the cone
        s = min(abs(t), 1.0)
        if s == 0.0:
            return 0.0
        w = math.sqrt(1.0 - s * s)
        value = (2.0 * s * w + math.asin(s) - s**3 * math.log((1.0 + w) / s)) / math.pi
        return math.copysign(value, t)

    return integral(abs(distance) + 0.5) - integral(abs(distance) - 0.5)


GS_TABLE = np.array([cone_band_volume(i / GS_STEPS) for i in range(3 * GS_STEPS // 2 + 1)])
"""Filter(D) at D = i / GS_STEPS, i = 0..24 (D = 1.5: the band misses the cone, 0)."""


def gupta_sproull_line(p0: object, p1: object, width: int, height: int) -> np.ndarray:
    """Gupta-Sproull's filtered line (1981): the midpoint line, three pixels a column, a cone filter.

    Returns
    -------
    (height, width) ndarray of float64
        Intensity of each pixel in [0, 0.78], row 0 at the bottom.

    Notes
    -----
    In pixel-centred coordinates the midpoint line runs over the major-axis
    columns round(u0)..round(u1), both included (round = floor(u + 1/2)),
    picking in each the pixel nearest the centre line; that pixel and its two
    minor-axis neighbours, at perpendicular distances D = |j - dv| cos(a)
    (j = -1, 0, 1, dv the centre line's offset from the middle pixel, a the
    angle to the major axis), get Filter(D) from `GS_TABLE`, the nearest entry
    of 1/16-pixel steps. Filter(D) = `cone_band_volume`: the volume over the
    1-wide band of a cone of radius 1 and volume 1. So Filter(0) = 0.780 and
    the rows of an infinite horizontal line sum to exactly 1, the band's area
    per column (Filter(D - 1) + Filter(D) + Filter(D + 1) = 1 for D in
    [0, 1/2]: the band's translates by whole pixels tile the plane). Like
    Foley-van Dam's version, the ends are not filtered (the paper's endpoint
    tables are not used): each end column is drawn whole, so a segment is
    about one column brighter than its band; a zero-length segment draws
    nothing.

    Examples
    --------
    >>> gupta_sproull_line((0.5, 1.5), (3.5, 1.5), 4, 3)[::-1].round(3)  # top row first
    array([[0.11, 0.11, 0.11, 0.11],
           [0.78, 0.78, 0.78, 0.78],
           [0.11, 0.11, 0.11, 0.11]])
    """
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    image = new_raster(width, height, "gupta_sproull_line")
    _gupta_sproull_kernel(x0 - 0.5, y0 - 0.5, x1 - 0.5, y1 - 0.5, GS_TABLE, GS_STEPS, image)
    return image


@njit(cache=True)
def _gupta_sproull_kernel(u0, v0, u1, v1, table, steps, image):  # pragma: no cover - compiled
    steep, u0, v0, u1, v1 = _along_major_axis(u0, v0, u1, v1)
    if u1 == u0 and v1 == v0:
        return
    gradient = (v1 - v0) / (u1 - u0)
    cos_a = 1.0 / math.sqrt(1.0 + gradient * gradient)  # perpendicular distance per minor unit
    extent = image.shape[0] if steep else image.shape[1]
    first = max(math.floor(u0 + 0.5), 0)
    for column in range(first, min(math.floor(u1 + 0.5) + 1, extent)):
        v = v0 + gradient * (column - u0)
        row = math.floor(v + 0.5)  # the midpoint line's pixel: nearest the centre line
        for j in range(-1, 2):
            index = int(abs(row + j - v) * cos_a * steps + 0.5)
            if index < table.shape[0]:
                _plot(image, steep, column, row + j, table[index])


# ---------------------------------------------------------------- supersampling


def supersampled_line(p0: object, p1: object, width: int, height: int, k: int = 4) -> np.ndarray:
    """The fraction of k x k point samples per pixel inside the 1-wide band.

    Parameters
    ----------
    k : int in 1..64
        Samples per pixel side, at (x + (i + 1/2)/k, y + (j + 1/2)/k).

    Returns
    -------
    (height, width) ndarray of float64
        Covered samples / k**2 per pixel, row 0 at the bottom.

    Raises
    ------
    TypeError, ValueError
        If `k` is not an int in 1..64, or another argument breaks a rule of
        the module docstring.

    Notes
    -----
    A sample s is inside when 0 <= (s - p0) . d < |p1 - p0| and
    -1/2 <= (s - p0) . n < 1/2 (d the unit direction, n its left normal).
    Each sample row is cut with the two slabs to find the samples to test, so
    the work is the rows plus the samples inside. As a 45-degree band slides
    across a pixel, the count of its 16 samples (k = 4) inside jumps by whole
    diagonals of samples, up to 15 (Wang reports at most 13 for his recursive
    subdivision, §4.3): the "ropiness" of supersampled lines.

    Examples
    --------
    >>> supersampled_line((0, 1.0), (3, 1.0), 3, 3, k=2)[::-1]  # top row first
    array([[0. , 0. , 0. ],
           [0.5, 0.5, 0.5],
           [0.5, 0.5, 0.5]])
    """
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    k = check_int("k", k, 1, MAX_SAMPLES)
    image = new_raster(width, height, "supersampled_line")
    _supersample_kernel(x0, y0, x1, y1, k, image)
    return image


@njit(cache=True, inline="always")
def _slab(offset, rate, lo, hi, xa, xb):
    """Narrow [xa, xb] to the x with lo <= offset + rate x < hi (a little wide: samples are retested)."""
    if rate == 0.0:
        return (xa, xb) if lo <= offset < hi else (1.0, 0.0)
    ta, tb = (lo - offset) / rate, (hi - offset) / rate
    return max(xa, min(ta, tb)), min(xb, max(ta, tb))


@njit(cache=True)
def _supersample_kernel(x0, y0, x1, y1, k, image):  # pragma: no cover - compiled
    length = math.hypot(x1 - x0, y1 - y0)
    if length == 0.0:
        return
    dx, dy = (x1 - x0) / length, (y1 - y0) / length
    height, width = image.shape
    half = 0.5 * (abs(dx) + abs(dy))  # the band's reach beyond the segment's box, per axis
    row_lo = max(math.floor((min(y0, y1) - half) * k) - 1, 0)
    row_hi = min(math.ceil((max(y0, y1) + half) * k) + 1, height * k)
    weight = 1.0 / (k * k)
    for j in range(row_lo, row_hi):
        sy = (j + 0.5) / k
        along, across = (sy - y0) * dy, (sy - y0) * dx  # the sample's (along, across) at x = x0
        xa, xb = _slab(along - x0 * dx, dx, 0.0, length, -1.0, width + 1.0)
        xa, xb = _slab(across + x0 * dy, -dy, -0.5, 0.5, xa, xb)
        for i in range(max(math.floor(xa * k) - 1, 0), min(math.ceil(xb * k) + 1, width * k)):
            sx = (i + 0.5) / k
            a = (sx - x0) * dx + (sy - y0) * dy
            c = (sy - y0) * dx - (sx - x0) * dy
            if 0.0 <= a < length and -0.5 <= c < 0.5:
                image[j // k, i // k] += weight


# ---------------------------------------------------------------- exact area and masks


def band_rectangle(p0: object, p1: object, width: int, height: int) -> np.ndarray | None:
    """The 1-wide band of p0-p1 as a (4, 2) rectangle, cut to what can reach the raster; None if empty.

    The segment is first clipped (Liang-Barsky) to the raster grown by 1
    pixel: the part of the band beyond a cut lies over 1/2 pixel outside the
    raster, so the coverage is unchanged and the corners stay in range.

    >>> band_rectangle((1, 1), (3, 1), 4, 4).tolist()
    [[1.0, 0.5], [3.0, 0.5], [3.0, 1.5], [1.0, 1.5]]
    """
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    dx, dy = x1 - x0, y1 - y0
    t0, t1 = 0.0, 1.0
    for delta, start, lo, hi in ((dx, x0, -1.0, width + 1.0), (dy, y0, -1.0, height + 1.0)):
        if delta == 0.0:
            if not lo <= start <= hi:
                return None
            continue
        ta, tb = sorted(((lo - start) / delta, (hi - start) / delta))
        t0, t1 = max(t0, ta), min(t1, tb)
    length = math.hypot(dx, dy)
    if t0 >= t1 or length == 0.0:
        return None
    nx, ny = -0.5 * dy / length, 0.5 * dx / length  # half the left unit normal
    a = (x0 + t0 * dx, y0 + t0 * dy)
    b = (x0 + t1 * dx, y0 + t1 * dy)
    corners = np.array([(a[0] - nx, a[1] - ny), (b[0] - nx, b[1] - ny), (b[0] + nx, b[1] + ny), (a[0] + nx, a[1] + ny)])  # fmt: skip
    return (
        corners if len(np.unique(corners, axis=0)) >= 3 else None
    )  # a sliver below float precision


def exact_band_line(p0: object, p1: object, width: int, height: int) -> np.ndarray:
    """The exact area of each pixel inside the 1-wide band: `area_coverage` of its rectangle.

    Returns
    -------
    (height, width) ndarray of float64
        Covered area of each pixel, row 0 at the bottom; it sums to |p1 - p0|
        when the band lies on the raster.

    Examples
    --------
    >>> exact_band_line((0, 1.25), (3, 1.25), 3, 3)[::-1]  # top row first
    array([[0.  , 0.  , 0.  ],
           [0.75, 0.75, 0.75],
           [0.25, 0.25, 0.25]])
    """
    image = new_raster(width, height, "exact_band_line")
    height, width = image.shape
    corners = band_rectangle(p0, p1, width, height)
    if corners is None:
        return image
    return area_coverage(corners, width, height, subpixel_bits=None)


def abuffer_line(
    p0: object,
    p1: object,
    width: int,
    height: int,
    mask: str = "8x8",
    *,
    subpixel_bits: int | None = 8,
) -> np.ndarray:
    """The band's a-buffer pixel masks (`pixel_masks`): covered bits / all bits per pixel.

    Parameters
    ----------
    mask : {"8x8", "8x4", "4x4"}
        Sub-sample layout per pixel (`scanviz.abuffer.masks.MASK_LAYOUTS`).
    subpixel_bits : int in 0..16, or None
        Snap the band's corners to 1/2**bits pixel, as the a-buffer does
        (fast integer decisions); None decides the float corners exactly
        (about 20 times slower).

    Returns
    -------
    (height, width) ndarray of float64
        Row 0 at the bottom.

    Raises
    ------
    TypeError, ValueError
        If `mask` is not a layout, `subpixel_bits` is not an int in 0..16 or
        None, or another argument breaks a rule of the module docstring.

    Examples
    --------
    >>> abuffer_line((0, 1.25), (2, 1.25), 2, 3, mask="4x4")[::-1]  # top row first
    array([[0.  , 0.  ],
           [0.75, 0.75],
           [0.25, 0.25]])
    """
    check_choice("mask", mask, tuple(MASK_LAYOUTS))
    bits = check_subpixel_bits(subpixel_bits)
    image = new_raster(width, height, "abuffer_line")
    height, width = image.shape
    corners = band_rectangle(p0, p1, width, height)
    if corners is None:
        return image
    result = pixel_masks(corners, width, height, mask=mask, subpixel_bits=bits)
    cols, rows = MASK_LAYOUTS[mask]
    image[result.ys, result.xs] = popcount(result.masks) / (cols * rows)
    return image

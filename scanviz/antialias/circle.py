"""DISLOP_C and DISLOP_S: area-sampled circles (1-pixel-wide rings) and disks (Wang 1989, §4.4-4.5).

The dissertation draws a circle as a polygon of N = 8 R / sqrt(2) sides around
it, each side by DISLOP_L (a disk: each side by DISLOP_E). Its worked example
(Fig 4-12) shows the effective construction: one tangent per boundary column,
touching the circle at the column centre (per row in the octants steeper
than 45 degrees). scanviz does exactly that: pixel (x, y) belongs to the
column sector if its centre is at least as far from the circle's centre
vertically as horizontally, else to the row sector; in its column (row) the
tangent at the column (row) centre gives the slope and the distance dxy, and
`columns.line_column` (ring) or `columns.edge_column` (disk) the areas. A pixel
beyond the cut ones takes 1 inside and 0 outside. No pixel is counted twice.
A column past 45 degrees (|x - cx| > R / sqrt(2)) uses the tangent at the
45-degree point, slope 1, for its few sector pixels near the diagonal.
A radius of 0 draws nothing. Measured errors: docs/antialiasing.md.
"""

from __future__ import annotations

import math

from numba import njit

from ..trace.events import DislopColumn
from . import columns
from ._inputs import as_tracer, check_point, check_radius, finish, new_raster

SQRT2 = math.sqrt(2.0)
HALF_SQRT2 = 0.5 * SQRT2


def dislop_circle(center: object, radius: float, width: int, height: int, *, trace: object = None):
    """Coverage of every pixel by the 1-pixel-wide ring of the circle (DISLOP_C).

    Parameters
    ----------
    center : (2,) array_like of float
        The centre (x, y) in pixels, within +-2**20.
    radius : float
        Radius of the ring's centre line, in 0..2**20; the ring is
        R - 1/2 <= distance <= R + 1/2 (for R >= 1/2).
    width, height : int
        Raster size in pixels, in 0..2**16.
    trace : None, True or Tracer
        None runs the compiled kernel; a tracer gets one ``dislop_column`` per
        tangent, two per column, then two per row (True: a new Recorder,
        returned with the image).

    Returns
    -------
    (height, width) ndarray of float64
        Covered area of each pixel, row 0 at the bottom; with ``trace=True``
        the pair (image, Trace).

    Raises
    ------
    TypeError, ValueError
        If `center` is not two finite reals within +-2**20, `radius` is not a
        finite real in 0..2**20, or the size is not an int in 0..2**16.

    Examples
    --------
    >>> ring = dislop_circle((8, 8), 5.0, 16, 16)
    >>> round(float(ring.sum()), 3), round(2 * math.pi * 5.0, 3)  # area, true area
    (31.664, 31.416)
    """
    return _round("dislop_circle", center, radius, width, height, trace, ring=True)


def dislop_disk(center: object, radius: float, width: int, height: int, *, trace: object = None):
    """Coverage of every pixel by the disk (a sphere's silhouette, DISLOP_S).

    Parameters
    ----------
    radius : float
        In 0..2**20.
    center, width, height, trace
        As `dislop_circle`.

    Returns
    -------
    (height, width) ndarray of float64
        Covered area of each pixel, as `dislop_circle`.

    Raises
    ------
    TypeError, ValueError
        As `dislop_circle`.

    Examples
    --------
    >>> disk = dislop_disk((100.65, 100.12), 4.75, 110, 110)  # Wang's Fig 4-12, shifted by 1/2
    >>> round(float(disk[104, 101]), 6)  # the tangent trapezoid; the exact area is 0.784100
    0.79333
    """
    return _round("dislop_disk", center, radius, width, height, trace, ring=False)


def _round(caller: str, center, radius, width, height, trace, *, ring: bool):
    """The ring (`ring`) or the disk of `radius` about `center`, checked, then walked."""
    cx, cy = check_point("center", center)
    radius = check_radius(radius)
    tracer = as_tracer(trace)
    image = new_raster(width, height, caller)
    if radius == 0.0:  # no circumference, no area
        pass
    elif tracer is None:
        _round_kernel(cx - 0.5, cy - 0.5, radius, ring, image)
    else:
        _round_reference(cx - 0.5, cy - 0.5, radius, ring, image, tracer)
    return finish(image, trace, tracer)


def sector_value(ring: bool, slope: float, dxy: float, offset: int) -> float:
    """Area of the pixel `offset` rows outward of the middle one, in the tangent's frame.

    The frame is the column's, reflected so that the circle's inside is below
    the tangent ``y = dxy + slope x`` (0 <= slope <= 1).
    """
    if ring:
        if offset < -1 or offset > 1:
            return 0.0
        up, mid, low, _, _, _ = columns.line_column_compiled(slope, dxy)
        return up if offset == 1 else (mid if offset == 0 else low)
    if offset < -1:
        return 1.0
    if offset > 1:
        return 0.0
    up, mid, low, _, _, branch = columns.edge_column_compiled(slope, dxy, 1)
    if offset == -1:  # an unreported pixel below the cut one is inside: coverage 1
        return low if branch == 1 and dxy <= 0.0 else 1.0
    return mid if offset == 0 else up


sector_value_compiled = njit(cache=True)(sector_value)


def _in_sector(axis: int, side: int, j: int, minor_centre: float, across: float) -> bool:
    """Pixel j of this column (row) belongs to its column (row) sector on this side."""
    outward = side * (j - minor_centre)
    if axis == 0:  # ties go to the column sectors, the centre pixel to the top
        return outward >= across and not (side == -1 and j - minor_centre == 0.0)
    return outward > across


_in_sector_compiled = njit(cache=True)(_in_sector)


def _column(i, major_centre, minor_centre, minor_size, radius):
    """(across, along, slope, low_j, high_j) of column (row) i: its tangent and the pixels to visit.

    `across` is the column's distance from the centre, `along` the tangent
    point's. Up to 45 degrees the tangent at the column centre; past it the
    tangent at the 45-degree point (slope 1), the polygon's side there: a
    column tangent steeper than 1 would sweep the whole column, far from
    where it touches.
    """
    across = abs(i - major_centre)
    if across <= radius * HALF_SQRT2:
        along = math.sqrt(radius * radius - across * across)
        slope = across / along
    else:
        along, slope = radius * SQRT2 - across, 1.0
    low_j = max(0, math.floor(minor_centre - along - 3.0))
    high_j = min(minor_size - 1, math.ceil(minor_centre + along + 3.0))
    return across, along, slope, low_j, high_j


_column_compiled = njit(cache=True)(_column)


def _walk(cx, cy, radius, shape, axis):
    """Yield (i, minor_centre, across, along, slope, low_j, high_j) per column (axis 0) or row."""
    height, width = shape
    major_size, minor_size = (width, height) if axis == 0 else (height, width)
    major_centre, minor_centre = (cx, cy) if axis == 0 else (cy, cx)
    first = max(0, math.floor(major_centre - radius - 1.0))  # a pixel further off is outside
    last = min(major_size - 1, math.ceil(major_centre + radius + 1.0))
    for i in range(first, last + 1):
        yield i, minor_centre, *_column(i, major_centre, minor_centre, minor_size, radius)


def _round_reference(cx, cy, radius, ring, image, tracer) -> None:
    for axis in range(2):  # 0: the column sectors (top, bottom); 1: the row sectors (right, left)
        for i, minor_centre, across, along, slope, low_j, high_j in _walk(
            cx, cy, radius, image.shape, axis
        ):
            for side in (1, -1):  # the far arc, then the near one reflected onto it
                centre = side * minor_centre + along  # the tangent point, reflected frame
                row = math.ceil(centre - 0.5)
                dxy = centre - row
                x, y = (i, side * row) if axis == 0 else (side * row, i)
                if tracer.wants("dislop_column", y=y):
                    tracer.emit(_event(ring, axis, x, y, slope, dxy))
                for j in range(low_j, high_j + 1):
                    if _in_sector(axis, side, j, minor_centre, across):
                        value = sector_value(ring, slope, dxy, side * j - row)
                        image[(j, i) if axis == 0 else (i, j)] = value


def _event(ring, axis, x, y, slope, dxy) -> DislopColumn:
    """The tangent of one column (row) as a trace event; areas as `sector_value` writes them."""
    up, mid, low = (sector_value(ring, slope, dxy, offset) for offset in (1, 0, -1))
    if ring:
        fcv, scv, branch = columns.line_column(slope, dxy)[3:]
        name = columns.LINE_BRANCHES[branch]
    else:
        fcv, scv, branch = columns.edge_column(slope, dxy, 1)[3:]
        name = columns.EDGE_BRANCHES[branch]
    major = "x" if axis == 0 else "y"
    return DislopColumn(x, y, major, slope, dxy, fcv, scv, name, up, mid, low, 0.0)


@njit(cache=True)
def _round_kernel(cx, cy, radius, ring, image):  # pragma: no cover - compiled `_round_reference`
    height, width = image.shape
    for axis in range(2):
        major_size, minor_size = (width, height) if axis == 0 else (height, width)
        major_centre, minor_centre = (cx, cy) if axis == 0 else (cy, cx)
        first = max(0, math.floor(major_centre - radius - 1.0))
        last = min(major_size - 1, math.ceil(major_centre + radius + 1.0))
        for i in range(first, last + 1):
            across, along, slope, low_j, high_j = _column_compiled(
                i, major_centre, minor_centre, minor_size, radius
            )
            for side in (1, -1):
                centre = side * minor_centre + along
                row = math.ceil(centre - 0.5)
                dxy = centre - row
                for j in range(low_j, high_j + 1):
                    if _in_sector_compiled(axis, side, j, minor_centre, across):
                        value = sector_value_compiled(ring, slope, dxy, side * j - row)
                        if axis == 0:
                            image[j, i] = value
                        else:
                            image[i, j] = value

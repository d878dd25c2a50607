"""DISLOP_L: the area-sampled 1-pixel-wide line (Wang 1989, §4.2, Figs 4-1..4-3).

The line is the rectangle of width 1 centred on the segment p0-p1, with square
ends at the endpoints and no extension. Each pixel gets the area of its unit
square inside it. Pixel (x, y) is the square [x, x+1] x [y, y+1] (DESIGN §2);
the dissertation centres pixels on integers, so its coordinates are ours
minus 1/2 ("centred" coordinates below).

The walk is column by column in the first octant: other octants reflect into
it (swap x and y if steep, then negate y if the slope is negative; both map
pixel centres to pixel centres). Per column, the middle pixel iy = the row of
the centre line at the column centre, dxy its offset, and the three areas
up/mid/low come from `columns.line_column`. The three columns at each end are
clipped exactly (the dissertation's nine end cases, Fig 4-3, are this
geometry case by case). ``exact=True`` replaces the middle formula by the
exact band area in five rows (`columns.band_row`), which adds the fourth pixel
the formula misses for slopes over 0.75.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import steps
from ..trace import Tracer
from ..trace.events import DislopColumn
from . import columns
from ._inputs import as_tracer, check_flag, check_point, finish, new_raster

ROWS = (-2, -1, 0, 1, 2)  # the rows a band of slope <= 1 can touch, from the middle pixel


def canonical(p0, p1) -> tuple[float, float, float, float, bool, bool]:
    """The segment in centred first-octant coordinates: (u0, v0, u1, v1, steep, flip).

    ``steep``: x and y were swapped; ``flip``: v was negated. Then u0 <= u1
    and 0 <= v1 - v0 <= u1 - u0.

    >>> canonical((0.5, 0.5), (2.5, 4.5))
    (0.0, 0.0, 4.0, 2.0, True, False)
    """
    u0, v0, u1, v1 = p0[0] - 0.5, p0[1] - 0.5, p1[0] - 0.5, p1[1] - 0.5
    steep = abs(v1 - v0) > abs(u1 - u0)
    if steep:
        u0, v0, u1, v1 = v0, u0, v1, u1
    if u1 < u0:
        u0, v0, u1, v1 = u1, v1, u0, v0
    flip = v1 < v0
    if flip:
        v0, v1 = -v0, -v1
    return u0, v0, u1, v1, steep, flip


@steps.step(
    "dislop_column",
    takes="a middle column's first-octant slope m (0 <= m <= 1) and dxy (-1/2 < dxy <= 1/2), the "
    "line's offset from the middle pixel's centre at the column centre",
    returns="(up, mid, low): the areas of the pixels above, at and below the middle one, by the "
    "dissertation's formula (Fig 4-2; exact for m <= 0.75)",
)
def middle_column(m: float, dxy: float) -> tuple[float, float, float]:
    """The areas (up, mid, low) of a middle column by the printed DISLOP_L formula.

    >>> [round(v, 4) for v in middle_column(0.08, 0.0)]  # Table 4-8, j = 25
    [0.0108, 0.9816, 0.0108]
    """
    up, mid, low, _, _, _ = columns.line_column(m, dxy)
    return up, mid, low


def dislop_line(
    p0: object,
    p1: object,
    width: int,
    height: int,
    *,
    trace: object = None,
    exact: bool = False,
):
    """Coverage of every pixel by the 1-pixel-wide line p0-p1 (DISLOP_L).

    Parameters
    ----------
    p0, p1 : (2,) array_like of float
        Endpoints (x, y) in pixels, within +-2**20.
    width, height : int
        Raster size in pixels, in 0..2**16.
    trace : None, True or Tracer
        None runs the compiled kernel (the reference loop while a step of
        `scanviz.steps` is replaced); a tracer gets one ``dislop_column`` per
        column (True: a new Recorder, returned with the image).
    exact : bool
        False: the dissertation's middle formula (a fourth pixel's area is
        credited to its neighbour for slopes over 0.75, at most 0.0214).
        True: the exact area of the band in every column.

    Returns
    -------
    (height, width) ndarray of float64
        The area of each pixel inside the band (row 0 at the bottom); with
        ``trace=True`` the pair (image, Trace).

    Raises
    ------
    TypeError, ValueError
        If an endpoint is not two finite real numbers within +-2**20, the size
        is not an int in 0..2**16, `exact` is not a bool, or `trace` is not a tracer.

    Examples
    --------
    >>> dislop_line((0, 1.5), (4, 1.5), 4, 3)[::-1]  # top row first
    array([[0., 0., 0., 0.],
           [1., 1., 1., 1.],
           [0., 0., 0., 0.]])
    >>> round(float(dislop_line((0.7, 0.6), (8.3, 5.1), 10, 7).sum()), 6)  # the length
    8.832327
    """
    p0, p1 = check_point("p0", p0), check_point("p1", p1)
    exact = check_flag("exact", exact)
    tracer = as_tracer(trace)
    image = new_raster(width, height, "dislop_line")
    u0, v0, u1, v1, steep, flip = canonical(p0, p1)
    if tracer is None and not steps.replaced():  # the kernel has no step table
        _line_kernel(u0, v0, u1, v1, steep, flip, exact, image)
    else:
        _line_reference(u0, v0, u1, v1, steep, flip, exact, image, tracer)
    return finish(image, trace, tracer)


def _line_reference(u0, v0, u1, v1, steep, flip, exact, image, tracer: Tracer | None) -> None:
    if u1 == u0:  # zero length (a canonical segment with u1 == u0 has v1 == v0)
        return
    slope = (v1 - v0) / (u1 - u0)
    xs, ys = columns.band_corners(u0, v0, u1, v1, slope)
    work = np.empty((4, 16))
    start, end = math.floor(u0 + 0.5), math.floor(u1 + 0.5)  # the end pixels' columns
    columns_in_raster = image.shape[0] if steep else image.shape[1]
    areas_of = steps.get("dislop_column")
    for column in range(max(start - 1, 0), min(end + 1, columns_in_raster - 1) + 1):
        centre = v0 + (column - u0) * slope  # the centre line at the column centre
        row = math.ceil(centre - 0.5)  # the middle pixel: dxy in (-1/2, 1/2]
        dxy = centre - row
        _, _, _, fcv, scv, branch = columns.line_column(slope, dxy)  # the event's critical values
        name = columns.LINE_BRANCHES[branch]
        if column <= start + 1 or column >= end - 1:  # an end column: clip the rectangle
            name = "cap"
            areas = [0.0] * len(ROWS)
            for k, r in enumerate(ROWS):
                bottom = row + r - 0.5
                box = (column - 0.5, bottom, column + 0.5, bottom + 1.0)
                areas[k] = columns.clip_area(xs, ys, 4, *box, work)
        elif exact:  # the exact band: five rows, one of which may be the fourth pixel
            name = "exact"
            areas = [columns.band_row(slope, dxy, r) for r in ROWS]
        else:  # the dissertation's middle formula, a replaceable step
            up, mid, low = areas_of(slope, dxy)
            areas = [0.0, low, mid, up, 0.0]  # rows -2..2 from the middle pixel
        x, y = raster_pixel(column, row, steep, flip)
        if tracer is not None and tracer.wants("dislop_column", y=y):
            spill = areas[4] if dxy > 0.0 else areas[0]
            tracer.emit(
                DislopColumn(
                    x, y, "y" if steep else "x", float(slope), float(dxy), float(fcv),
                    float(scv), name, float(areas[3]), float(areas[2]), float(areas[1]),
                    float(spill),
                )
            )  # fmt: skip
        for k, r in enumerate(ROWS):
            _put(image, column, row + r, areas[k], steep, flip)


def raster_pixel(column: int, row: int, steep: bool, flip: bool) -> tuple[int, int]:
    """The raster (x, y) of first-octant pixel (column, row)."""
    row = -row if flip else row
    return (row, column) if steep else (column, row)


raster_pixel_compiled = njit(cache=True, inline="always")(raster_pixel)


@njit(cache=True)
def _put(image, column, row, value, steep, flip):  # pragma: no cover - compiled
    """Add `value` at first-octant pixel (column, row) if it is on the raster."""
    if value == 0.0:
        return
    x, y = raster_pixel_compiled(column, row, steep, flip)
    if 0 <= x < image.shape[1] and 0 <= y < image.shape[0]:
        image[y, x] += value


@njit(cache=True)
def _line_kernel(u0, v0, u1, v1, steep, flip, exact, image):  # pragma: no cover - compiled
    if u1 == u0:
        return
    slope = (v1 - v0) / (u1 - u0)
    xs, ys = columns.band_corners_compiled(u0, v0, u1, v1, slope)
    work = np.empty((4, 16))
    start, end = math.floor(u0 + 0.5), math.floor(u1 + 0.5)
    columns_in_raster = image.shape[0] if steep else image.shape[1]
    for column in range(max(start - 1, 0), min(end + 1, columns_in_raster - 1) + 1):
        centre = v0 + (column - u0) * slope
        row = math.ceil(centre - 0.5)
        dxy = centre - row
        if column <= start + 1 or column >= end - 1:
            for r in range(-2, 3):
                bottom = row + r - 0.5
                area = columns.clip_area_compiled(
                    xs, ys, 4, column - 0.5, bottom, column + 0.5, bottom + 1.0, work
                )
                _put(image, column, row + r, area, steep, flip)
        elif exact:
            for r in range(-2, 3):
                _put(image, column, row + r, columns.band_row_compiled(slope, dxy, r), steep, flip)
        else:
            up, mid, low, _, _, _ = columns.line_column_compiled(slope, dxy)
            _put(image, column, row + 1, up, steep, flip)
            _put(image, column, row, mid, steep, flip)
            _put(image, column, row - 1, low, steep, flip)

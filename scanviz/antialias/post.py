"""Post-anti-aliasing by table look-up (Wang 1989, §4.8, §5.1, §5.2).

The image is already rendered, aliased; every visible line or silhouette edge
is then walked column by column in its first-octant frame (`line.canonical`:
steep segments walk rows), and in each column the slope index i, the distance
index j (`tables.column_indices`' recurrence) and a read of the 51 x 51 x 3
table give the areas of the three pixels the segment cuts, which are blended
over the image: ``out = A * color + (1 - A) * out`` per channel.

Which columns (first-octant frame, ixs = round(xs), ixe = round(xe)):

* edges: ixs + 1 .. ixe - 1, the columns of Fig 5-6; the end columns belong to
  the polygon's other edges and are left as they are;
* lines: ixs + 2 .. ixe - 2 from the table; the three columns at each end
  (ixs - 1 .. ixs + 1, ixe - 1 .. ixe + 1) are DISLOP_L's caps, the rectangle
  clipped exactly to each pixel (`columns.clip_area`), as `dislop_line` does.
  So on black, white, the result differs from `dislop_line` only by the
  table's quantisation of m and dxy.

The recurrence starts at X0 = ixs as in Fig 5-2 (so the simple one gives Fig
5-2's indices), or, if ixs is off the raster, at column 0 with its dxy
evaluated there: the part of a segment off the raster costs nothing.
"""

from __future__ import annotations

import math
import numbers

import numpy as np
from numba import njit

from .. import steps
from ..conventions import as_array, check_choice, short_repr
from ..geometry import as_coordinates
from ..trace.events import PostColumn
from . import columns, tables
from ._inputs import as_tracer, finish
from .line import canonical, raster_pixel, raster_pixel_compiled


def post_antialias(
    image: object,
    segments: object,
    *,
    kind: str = "line",
    flags: object = None,
    color: object = (1.0, 1.0, 1.0),
    table: str = "area",
    levels: int = 64,
    recurrence: str = "exact",
    trace: object = None,
):
    """Blend table look-ups of lines or polygon edges over an already rendered image (§4.8).

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like of float
        The aliased image (or background), values in 0..1, row 0 at the bottom.
    segments : (N, 2, 2) array_like of float
        N segments ((x0, y0), (x1, y1)) in scanviz pixel coordinates.
    kind : {"line", "edge"}
        1-pixel-wide lines (DISLOP_L table, end caps exact) or polygon edges
        (the flag's DISLOP_E table, columns ixs+1..ixe-1).
    flags : (N,) array_like of 0/1, for edges
        1: the inside is below the edge (lower y) if ``|dy| <= |dx|``, on the
        -x side if steeper; 0: above, or on the +x side.
    color : (3,) array_like of float
        RGB in 0..1 of the lines or of the polygon.
    table : {"area", "intensity"}
        Areas (any background), or `levels`-level intensities, which the
        dissertation uses on a black background only: a non-black `image` is
        refused. The intensity I is applied as the coverage I / (levels - 1).
    levels : int
        Intensity levels, 2..256, for ``table="intensity"``.
    recurrence : {"exact", "simple"}
        The dxy recurrence, or ``j = (j + i) mod 50`` (`tables.column_indices`).
    trace : None, True or Tracer
        Gets one ``post_column`` per table look-up (True: a new Recorder,
        returned with the image). The pixels are the same either way.

    Returns
    -------
    (H, W, 3) ndarray of float64
        A new image; with ``trace=True`` the pair (image, Trace).

    Raises
    ------
    TypeError, ValueError
        If an argument has the wrong type, shape or range; the message names it.

    Examples
    --------
    >>> out = post_antialias(np.zeros((3, 8)), [((0, 1.5), (8, 1.5))])
    >>> out[::-1, :, 0]  # top row first
    array([[0., 0., 0., 0., 0., 0., 0., 0.],
           [1., 1., 1., 1., 1., 1., 1., 1.],
           [0., 0., 0., 0., 0., 0., 0., 0.]])
    """
    out = _check_image(image)
    segments = as_coordinates(segments, "'segments'", ("N", 2, 2))
    check_choice("kind", kind, tables.KINDS)
    flags = _check_flags(flags, kind, len(segments))
    color = _check_color(color)
    check_choice("table", table, ("area", "intensity"))
    levels = tables.check_levels(levels)
    check_choice("recurrence", recurrence, tables.RECURRENCES)
    if table == "intensity" and out.any():
        raise ValueError("'image' must be black (all 0) with table='intensity'; use table='area'")
    tracer = as_tracer(trace)
    lut = tables.line_table()[None] if kind == "line" else tables.edge_tables()
    quantum = 0.0
    if table == "intensity":
        lut, quantum = tables.intensities(np.clip(lut, 0.0, 1.0), levels) / (levels - 1), levels - 1
    for index, (p0, p1) in enumerate(segments):
        u0, v0, u1, v1, steep, flip = canonical(p0, p1)
        lut_flag = int(flags[index]) ^ flip if kind == "edge" else 0  # the flag in the frame
        arguments = (
            out, u0, v0, u1, v1, steep, flip, kind == "edge", lut[lut_flag], float(quantum),
            color, recurrence == "simple",
        )  # fmt: skip
        if tracer is None and not steps.replaced():  # the kernel has no step table
            _segment_kernel(*arguments)
        else:
            _segment_reference(*arguments, tracer, index)
    return finish(out, trace, tracer)


def _check_image(image: object) -> np.ndarray:
    """`image` as a new (H, W, 3) float64 array in 0..1."""
    array = np.asarray(image)
    if array.dtype == bool or not np.issubdtype(array.dtype, np.number):
        raise TypeError(f"'image' must be an array of real numbers; got dtype {array.dtype}")
    if array.ndim not in (2, 3) or (array.ndim == 3 and array.shape[2] != 3):
        raise ValueError(f"'image' must be an (H, W) or (H, W, 3) array; got shape {array.shape}")
    if not np.all((array >= 0) & (array <= 1)):
        raise ValueError("'image' values must be finite and in 0..1")
    out = np.empty((*array.shape[:2], 3))
    out[...] = array[:, :, None] if array.ndim == 2 else array
    return out


def _check_color(color: object) -> np.ndarray:
    array = as_array(color, "'color' must be three real numbers (r, g, b)", copy=True)
    if array.shape != (3,) or not np.all((array >= 0.0) & (array <= 1.0)):
        raise ValueError(f"'color' must be (r, g, b) in 0..1; got {short_repr(color)}")
    return array


def _check_flags(flags: object, kind: str, count: int) -> np.ndarray:
    if kind == "line":
        if flags is not None:
            raise ValueError("'flags' is for kind='edge' only; got flags with kind='line'")
        return np.zeros(count, dtype=np.int64)
    if flags is None:
        raise ValueError("'flags' is required with kind='edge': (N,) 0/1, 1 = inside below")
    array = np.asarray(flags)
    if array.shape != (count,):
        raise ValueError(f"'flags' must be an (N,) array with N = {count}; got shape {array.shape}")
    if array.size and not np.issubdtype(array.dtype, np.integer) and array.dtype != bool:
        raise TypeError(f"'flags' must be integers 0/1; got dtype {array.dtype}")
    bad = np.flatnonzero((array != 0) & (array != 1))
    if bad.size:
        raise ValueError(f"'flags'[{bad[0]}] must be 0 or 1; got {array[bad[0]]!r}")
    return array.astype(np.int64)


def _segment_reference(
    image, u0, v0, u1, v1, steep, flip, edge, lut, quantum, color, simple, tracer, segment
) -> None:
    """`_segment_kernel`'s walk in Python, emitting ``post_column`` per table column. The
    indices come from the step ``table_index`` (`scanviz.steps`): at every table column, or,
    with the simple recurrence, once at X0 (then j steps by i)."""
    if u1 == u0:
        return
    slope = (v1 - v0) / (u1 - u0)
    indices_of = steps.get("table_index")
    start, end = math.floor(u0 + 0.5), math.floor(u1 + 0.5)
    first, last = (start + 1, end - 1) if edge else (start - 1, end + 1)
    first, last = max(first, 0), min(last, (image.shape[0] if steep else image.shape[1]) - 1)
    xs, ys = columns.band_corners(u0, v0, u1, v1, slope)
    work = np.empty((4, 16))
    walk = max(start, 0)  # the recurrence starts at X0 = ixs (Fig 5-2), or at the raster's edge
    row, dxy, _ = tables.first_column(u0, v0, slope, walk)
    i, j = indices_of(slope, dxy) if simple else (0, 0)
    for column in range(first, last + 1):
        while walk < column:  # one step of the recurrence per column
            walk += 1
            row, dxy, j = tables.next_column(row, dxy, i, j, slope, simple)
        if not edge and (column <= start + 1 or column >= end - 1):  # a cap column: clip exactly
            _blend_cap(image, column, u0, v0, slope, xs, ys, work, quantum, steep, flip, color)
            continue
        if not simple:
            i, j = indices_of(slope, dxy)
            for index in (i, j):  # a float index, even 13.0, is not one (the table is an array)
                if isinstance(index, bool) or not isinstance(index, numbers.Integral):
                    raise TypeError(
                        f"step 'table_index' must return two ints; got {(i, j)!r}: "
                        f"{index!r} is a {type(index).__name__}"
                    )
        if not (0 <= i <= 50 and 0 <= j <= 50):
            raise ValueError(f"step 'table_index' must give indices in 0..50; got {(i, j)!r}")
        up, mid, low = (float(area) for area in lut[i, j])
        _blend(image, column, row + 1, up, steep, flip, color)
        _blend(image, column, row, mid, steep, flip, color)
        _blend(image, column, row - 1, low, steep, flip, color)
        x, y = raster_pixel(column, row, steep, flip)
        if tracer is not None and tracer.wants("post_column", y=y):
            major = "y" if steep else "x"
            tracer.emit(PostColumn(segment, x, y, major, int(i), int(j), dxy, up, mid, low))


@njit(cache=True)
def _blend(image, column, row, area, steep, flip, color):  # pragma: no cover - compiled
    """out = A * color + (1 - A) * out at first-octant pixel (column, row), if on the raster."""
    if area == 0.0:
        return
    x, y = raster_pixel_compiled(column, row, steep, flip)
    if 0 <= x < image.shape[1] and 0 <= y < image.shape[0]:
        for c in range(3):
            image[y, x, c] = area * color[c] + (1.0 - area) * image[y, x, c]


@njit(cache=True)
def _blend_cap(
    image, column, u0, v0, slope, xs, ys, work, quantum, steep, flip, color
):  # pragma: no cover - compiled
    """A cap column: the band (corners `xs`, `ys`) clipped exactly to the five pixels about
    the centre line, each area (quantized if `quantum` > 0) blended over `image`."""
    middle = math.ceil(v0 + (column - u0) * slope - 0.5)
    for r in range(-2, 3):
        bottom = middle + r - 0.5
        area = columns.clip_area_compiled(
            xs, ys, 4, column - 0.5, bottom, column + 0.5, bottom + 1.0, work
        )
        if quantum > 0.0:
            area = math.floor(min(max(area, 0.0), 1.0) * quantum + 0.5) / quantum
        _blend(image, column, middle + r, area, steep, flip, color)


@njit(cache=True)
def _segment_kernel(
    image, u0, v0, u1, v1, steep, flip, edge, lut, quantum, color, simple
):  # pragma: no cover - compiled
    """Walk one canonical segment, blending the table's areas over `image`."""
    if u1 == u0:
        return
    slope = (v1 - v0) / (u1 - u0)
    i = int(slope * 50 + 0.5)
    start, end = math.floor(u0 + 0.5), math.floor(u1 + 0.5)
    first, last = (start + 1, end - 1) if edge else (start - 1, end + 1)
    first, last = max(first, 0), min(last, (image.shape[0] if steep else image.shape[1]) - 1)
    xs, ys = columns.band_corners_compiled(u0, v0, u1, v1, slope)
    work = np.empty((4, 16))
    walk = max(start, 0)  # the recurrence starts at X0 = ixs (Fig 5-2), or at the raster's edge
    row, dxy, j = tables.first_column_compiled(u0, v0, slope, walk)
    for column in range(first, last + 1):
        while walk < column:  # one step of the recurrence per column
            walk += 1
            row, dxy, j = tables.next_column_compiled(row, dxy, i, j, slope, simple)
        if not edge and (column <= start + 1 or column >= end - 1):  # a cap column: clip exactly
            _blend_cap(image, column, u0, v0, slope, xs, ys, work, quantum, steep, flip, color)
            continue
        up, mid, low = lut[i, j, 0], lut[i, j, 1], lut[i, j, 2]
        _blend(image, column, row + 1, up, steep, flip, color)
        _blend(image, column, row, mid, steep, flip, color)
        _blend(image, column, row - 1, low, steep, flip, color)


def silhouette_mask(image: object, threshold: float) -> np.ndarray:
    """Pixels with a 4-neighbour whose intensity differs by more than `threshold` (§5.2, 3b).

    In a self-overlapping image a silhouette edge runs between two such
    pixels; both are marked, since both colours must be blended. The
    difference of RGB pixels is the largest of the channels' differences.

    Parameters
    ----------
    image : (H, W) or (H, W, 3) array_like of float
        Values in 0..1.
    threshold : float
        In 0..1; the dissertation gives none. A smooth shading changes by much
        less than a level step between neighbours, so e.g. 0.1 marks the
        silhouettes and not the shading.

    Returns
    -------
    (H, W) ndarray of bool

    Examples
    --------
    >>> silhouette_mask([[0, 0, 1, 1]], 0.5).astype(int).tolist()
    [[0, 1, 1, 0]]
    """
    array = _check_image(image)
    if isinstance(threshold, bool) or not isinstance(threshold, int | float | np.floating):
        raise TypeError(f"'threshold' must be a real number; got {short_repr(threshold)}")
    if not 0.0 <= threshold <= 1.0:
        raise ValueError(f"'threshold' must be in 0..1; got {short_repr(threshold)}")
    across = np.abs(np.diff(array, axis=1)).max(axis=2) > threshold  # (H, W-1): x vs x+1
    along = np.abs(np.diff(array, axis=0)).max(axis=2) > threshold  # (H-1, W): y vs y+1
    mask = np.zeros(array.shape[:2], dtype=bool)
    mask[:, :-1] |= across
    mask[:, 1:] |= across
    mask[:-1, :] |= along
    mask[1:, :] |= along
    return mask

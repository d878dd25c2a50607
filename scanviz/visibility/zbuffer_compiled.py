"""Compiled twin of the traced z-buffer (numba): the reference's depths, ids and values, fast.

`zbuffer_polygons` draws all polygons in one call, with the edge walker of
`scanviz.raster.walk_compiled` and the interpolation formulas of
`scanviz.raster.interpolate`, compiled from the same source (one definition,
one order of operations, so the same bits as the reference).

Unlike the plain scan kernel, the walker sorts the active edge table here by
the exact crossing x = Q + R/DEN, not by ceil(x): a span takes its values from
the two crossings that bound it, so the order within a pixel matters. Per-edge
values live in arrays indexed by the edge's column in the edge table; AET
entries carry that column in `edge_of`.
"""

from __future__ import annotations

import numba
import numpy as np
from numba import njit, prange

from ..raster import interpolate as formulas
from ..raster.walk_compiled import (
    CEIL,
    DEN,
    LOWER,
    ROW_END,
    ROW_START,
    TABLE_FIELDS,
    UPPER,
    WINDING,
    Y0,
    Y1,
    Q,
    R,
    ceil_div,
    edge_table,
    scratch_aet,
    step_row,
)
from ..threads import use_threads
from .cut_side import keeps

depth_plane = njit(cache=True)(formulas.depth_plane)
plane_depth = njit(cache=True, inline="always")(formulas.plane_depth)
compensated_step = njit(cache=True, inline="always")(formulas.compensated_step)
reaches_raster = njit(cache=True, inline="always")(formulas.reaches_raster)
crossing_x = njit(cache=True, inline="always")(formulas.crossing_x)
edge_slope = njit(cache=True, inline="always")(formulas.edge_slope)
edge_start = njit(cache=True, inline="always")(formulas.edge_start)
span_slope = njit(cache=True, inline="always")(formulas.span_slope)
span_start = njit(cache=True, inline="always")(formulas.span_start)
perspective_divide = njit(cache=True, inline="always")(formulas.perspective_divide)

# Fields of the stats array returned by `zbuffer_polygons`.
ROWS, SPANS, FRAGMENTS, PASSED, FAILED, DRAWN, SKIPPED = range(7)
STAT_FIELDS = 7
# The per-sample test of `draw_span`: the z-buffer's, paint over (back to front), paint
# under (front to back: only empty samples), or write where the decided id is this polygon.
DEPTH, OVER, UNDER, TARGET = range(4)
WHOLE = 2**62  # rows -WHOLE..WHOLE: a whole polygon, no row left out
BAND_ROWS = 16  # sample rows per band of the parallel z-buffer (its unit of work)
PARALLEL_WORK = 2**16  # polygons listed in bands plus pixels: below this, one thread draws


@njit(cache=True, inline="always")
def start_edge(table, e, channels, scale, y, edge_value, edge_dvdy):
    """edges_activated: edge e's d(value)/dy, and its values on row y from its lower end."""
    lower, upper = table[LOWER, e], table[UPPER, e]
    y_lower, y_upper = table[Y0, e] / scale, table[Y1, e] / scale
    for k in range(channels.shape[1]):
        dvdy = edge_slope(channels[lower, k], channels[upper, k], y_lower, y_upper)
        edge_dvdy[e, k] = dvdy
        edge_value[e, k] = edge_start(channels[lower, k], dvdy, y_lower, y)


@njit(cache=True, inline="always")
def writes(mode, z, depth, ids, target, polygon, cuts, x, y):
    """The per-sample test of each mode: depth test, paint over, paint under, or the decided id."""
    if mode == DEPTH:
        write = z < depth[y, x]
    elif mode == OVER:
        write = True
    elif mode == UNDER:
        write = ids[y, x] < 0
    else:
        write = target[y, x] == polygon
    return write and (cuts.shape[0] == 0 or keeps(cuts, x, y))


@njit(cache=True, inline="always")
def draw_span(polygon, y, start, end, z, dzdx, span_value, span_dvdx, depth, ids, values, stats, mode, cuts, target):  # fmt: skip
    """depth_test (or the mode's test) each sample of [start, end): store depth, id and values."""
    value_count = values.shape[2]
    perspective = span_value.shape[0] > value_count  # the last channel is 1/w
    z_carry, passed = 0.0, 0
    for x in range(start, end):
        if writes(mode, z, depth, ids, target, polygon, cuts, x, y):
            depth[y, x] = z
            ids[y, x] = polygon
            for k in range(value_count):
                if perspective:
                    values[y, x, k] = perspective_divide(span_value[k], span_value[value_count])
                else:
                    values[y, x, k] = span_value[k]
            passed += 1
        z, z_carry = compensated_step(z, z_carry, dzdx)
        for k in range(span_value.shape[0]):
            span_value[k] += span_dvdx[k]
    stats[FRAGMENTS] += end - start
    stats[PASSED] += passed
    stats[FAILED] += end - start - passed


@njit(cache=True, inline="always")
def start_span(aet, i, edge_of, edge_value, start, span_value, span_dvdx):
    """span_values: d(value)/dx between crossings i and i + 1, and the values at sample `start`."""
    x_left = crossing_x(aet[Q, i], aet[R, i], aet[DEN, i])
    x_right = crossing_x(aet[Q, i + 1], aet[R, i + 1], aet[DEN, i + 1])
    left, right = edge_of[i], edge_of[i + 1]
    for k in range(span_value.shape[0]):
        dvdx = span_slope(edge_value[left, k], edge_value[right, k], x_left, x_right)
        span_dvdx[k] = dvdx
        span_value[k] = span_start(edge_value[left, k], dvdx, x_left, start)


@njit(cache=True, inline="always")
def draw_polygon(
    polygon, units, offsets, scale, plane, channels, buffers, depth, ids, values, stats, mode, cuts,
    target, rows,
):  # fmt: skip
    """Scan polygon `polygon` (rows offsets[0]:offsets[1] of `units`) into the buffers.

    `plane` is (x_first, y_first, z_first, dzdx, dzdy); `buffers` the scratch
    arrays (aet, xs, edge_of, edge_value, edge_dvdy, span_value, span_dvdx,
    the edge table);
    `mode`, `cuts` and `target` choose the per-sample test (`writes`);
    only rows rows[0] <= y < rows[1] are drawn (a piece's rows: the others
    are walked, so that every value is stepped as the z-buffer steps it).
    """
    height, width = depth.shape
    x_first, y_first, z_first, dzdx, dzdy = plane
    aet, xs, edge_of, edge_value, edge_dvdy, span_value, span_dvdx, table = buffers
    count, _, _ = edge_table(units, offsets, scale, height, table)
    n_active = entering = 0
    z_row, z_carry, previous_row = 0.0, 0.0, -2  # no row yet
    y = table[ROW_START, 0] if count else height
    while y < min(height, rows[1]) and (n_active > 0 or entering < count):
        for i in range(n_active):  # the edges still active on row y step their values
            if aet[ROW_END, i] > y:
                e = edge_of[i]
                for k in range(edge_dvdy.shape[1]):
                    edge_value[e, k] += edge_dvdy[e, k]
        entered = entering
        y, n_active, entering = step_row(
            table, count, entering, aet, xs, edge_of, n_active, y, scale, True, np.float64, True
        )
        for e in range(entered, entering):
            start_edge(table, e, channels, scale, y, edge_value, edge_dvdy)
        if y == previous_row + 1:  # between rows: z_row += dz/dy
            z_row, z_carry = compensated_step(z_row, z_carry, dzdy)
        else:
            z_row, z_carry = plane_depth(x_first, y_first, z_first, dzdx, dzdy, 0.0, y), 0.0
        previous_row = y
        if y < rows[0]:
            y += 1
            continue
        stats[ROWS] += 1
        winding = 0
        for i in range(n_active - 1):  # span: nonzero-winding runs between crossings
            winding += aet[WINDING, i]
            start, end = max(aet[CEIL, i], 0), min(aet[CEIL, i + 1], width)
            if winding != 0 and start < end:
                if span_value.shape[0]:  # no channels (flat shading): no crossing is needed
                    start_span(aet, i, edge_of, edge_value, start, span_value, span_dvdx)
                z = z_row + dzdx * start
                draw_span(polygon, y, start, end, z, dzdx, span_value, span_dvdx, depth, ids, values, stats, mode, cuts, target)  # fmt: skip
                stats[SPANS] += 1
        y += 1


def zbuffer_polygons(units, positions, z, channels, offsets, scale, width, height, value_count):
    """Draw polygons p = 0, 1, ... (rows offsets[p]:offsets[p+1]) through a z-buffer.

    `units` (M, 2) int64 are the snapped vertices on the grid, `positions`
    the same divided by `scale` (sample frame), `z` (M,) their depths and
    `channels` (M, C) the quantities interpolated; C > value_count means
    perspective: the first value_count channels are value/w, the last 1/w.
    Returns (depth, ids, values, stats): (H, W) float64, +inf where empty;
    (H, W) int64, -1 where empty; (H, W, value_count) float64; the (7,)
    int64 counts ROWS, SPANS, FRAGMENTS, PASSED, FAILED, DRAWN, SKIPPED.

    The raster is cut into bands of `BAND_ROWS` sample rows, and the bands
    are shared among the threads. A band draws, in drawing order, every
    polygon with a row in it, on its own rows only: each polygon's edges and
    depth are walked from its first row, as `draw_polygon` walks them, so
    every sample gets the bits the one-thread pass gives, and each pixel
    sees its polygons in the same order. The result does not depend on the
    number of threads (`numba.set_num_threads`).
    """
    # np.zeros here, not in numba: the pages of a large buffer are zeroed by the system as
    # they are first written (calloc), so the values of pixels never drawn cost nothing.
    values = np.zeros((height, width, value_count))
    planes, first_row, stop_row, skipped = _polygon_rows(
        units, positions, z, offsets, scale, width, height
    )
    band_start, listed = _bands(first_row, stop_row, height)
    largest = int(np.diff(offsets).max()) if len(offsets) > 1 else 0
    # Threads pay from about this much work: fewer listed polygons and pixels run here.
    threads = (
        numba.get_num_threads() if use_threads(len(listed) + height * width, PARALLEL_WORK) else 1
    )
    depth = np.empty((height, width))
    ids = np.empty((height, width), np.int64)
    thread_stats = np.zeros((threads, STAT_FIELDS), np.int64)
    drew = np.zeros(len(offsets) - 1, np.bool_)
    draw = _draw_bands if threads > 1 else _draw_bands_here
    draw(
        units, offsets, scale, planes, channels, band_start, listed, largest, depth, ids,
        values, thread_stats, drew,
    )  # fmt: skip
    stats = thread_stats.sum(axis=0)
    stats[DRAWN], stats[SKIPPED] = drew.sum(), skipped.sum()
    return depth, ids, values, stats


def _polygon_rows(units, positions, z, offsets, scale, width, height):
    """Per polygon: its plane, the rows first_row <= y < stop_row it scans, and whether it is skipped."""
    count = offsets.shape[0] - 1
    planes = np.zeros((count, 5))
    first_row = np.zeros(count, np.int64)
    stop_row = np.zeros(count, np.int64)
    skipped = np.ones(count, np.bool_)
    rows = _polygon_rows_shared if use_threads(count, PARALLEL_WORK // 8) else _polygon_rows_here
    rows(units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped)
    return planes, first_row, stop_row, skipped


@njit(cache=True, parallel=True)
def _polygon_rows_shared(units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped):  # fmt: skip
    for p in prange(offsets.shape[0] - 1):
        _polygon_row(p, units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped)  # fmt: skip


@njit(cache=True)
def _polygon_rows_here(units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped):  # fmt: skip
    for p in range(offsets.shape[0] - 1):
        _polygon_row(p, units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped)  # fmt: skip


@njit(cache=True, inline="always")
def _polygon_row(p, units, positions, z, offsets, scale, width, height, planes, first_row, stop_row, skipped):  # fmt: skip
    """Polygon p's entries of `_polygon_rows`."""
    first, stop = offsets[p], offsets[p + 1]
    _, _, c, dzdx, dzdy, z_first = depth_plane(
        positions[first:stop, 0], positions[first:stop, 1], z[first:stop]
    )
    xs, ys = units[first:stop, 0], units[first:stop, 1]
    y_min, y_max = ys.min(), ys.max()
    if c != 0.0 and reaches_raster(xs.min(), xs.max(), y_min, y_max, scale, width, height):
        planes[p, 0], planes[p, 1], planes[p, 2] = positions[first, 0], positions[first, 1], z_first
        planes[p, 3], planes[p, 4] = dzdx, dzdy
        skipped[p] = False
        first_row[p] = max(ceil_div(y_min, scale), 0)
        # The row above the last is scanned too: its edges are retired there (ROWS counts it).
        stop_row[p] = min(ceil_div(y_max, scale) + 1, height)


@njit(cache=True)
def _bands(first_row, stop_row, height):
    """(band_start, listed): band b draws polygons listed[band_start[b]:band_start[b + 1]], in order."""
    bands = (height + BAND_ROWS - 1) // BAND_ROWS
    band_start = np.zeros(bands + 1, np.int64)
    for p in range(first_row.shape[0]):
        if stop_row[p] > first_row[p]:
            for b in range(first_row[p] // BAND_ROWS, (stop_row[p] - 1) // BAND_ROWS + 1):
                band_start[b + 1] += 1
    for b in range(bands):
        band_start[b + 1] += band_start[b]
    listed = np.empty(band_start[bands], np.int64)
    filled = band_start[:bands].copy()
    for p in range(first_row.shape[0]):
        if stop_row[p] > first_row[p]:
            for b in range(first_row[p] // BAND_ROWS, (stop_row[p] - 1) // BAND_ROWS + 1):
                listed[filled[b]] = p
                filled[b] += 1
    return band_start, listed


@njit(cache=True)
def _draw_bands_here(
    units, offsets, scale, planes, channels, band_start, listed, largest, depth, ids, values,
    thread_stats, drew,
):  # fmt: skip
    """`_draw_bands` on the calling thread (small work: starting threads would cost more)."""
    buffers = scratch(largest, channels.shape[1])
    for b in range(band_start.shape[0] - 1):
        _draw_band(
            b, units, offsets, scale, planes, channels, band_start, listed, buffers, depth,
            ids, values, thread_stats[0], drew,
        )  # fmt: skip


@njit(cache=True, parallel=True)
def _draw_bands(
    units, offsets, scale, planes, channels, band_start, listed, largest, depth, ids, values,
    thread_stats, drew,
):  # fmt: skip
    """Thread t draws bands t, t + threads, ... (interleaved, so the work is balanced)."""
    threads = thread_stats.shape[0]
    bands = band_start.shape[0] - 1
    for t in prange(threads):
        buffers = scratch(largest, channels.shape[1])
        for b in range(t, bands, threads):
            _draw_band(
                b, units, offsets, scale, planes, channels, band_start, listed, buffers, depth,
                ids, values, thread_stats[t], drew,
            )  # fmt: skip


@njit(cache=True)
def _draw_band(
    b, units, offsets, scale, planes, channels, band_start, listed, buffers, depth, ids, values,
    stats, drew,
):  # fmt: skip
    """Band b: clear its rows, then draw its polygons in order on those rows only."""
    height = depth.shape[0]
    low, high = b * BAND_ROWS, min((b + 1) * BAND_ROWS, height)
    depth[low:high] = np.inf
    ids[low:high] = -1
    target = np.zeros((1, 1), np.int64)
    no_cuts = np.zeros((0, 11))
    for k in range(band_start[b], band_start[b + 1]):
        p = listed[k]
        fragments = stats[FRAGMENTS]
        plane = (planes[p, 0], planes[p, 1], planes[p, 2], planes[p, 3], planes[p, 4])
        draw_polygon(
            p, units, offsets[p : p + 2], scale, plane, channels, buffers, depth, ids, values,
            stats, DEPTH, no_cuts, target, (low, high),
        )  # fmt: skip
        if stats[FRAGMENTS] > fragments:
            drew[p] = True


@njit(cache=True)
def scratch(largest, channel_count):
    """`draw_polygon`'s scratch arrays for polygons of up to `largest` vertices."""
    aet, xs, edge_of = scratch_aet(largest, np.float64)
    return (
        aet,
        xs,
        edge_of,
        np.empty((largest, channel_count)),
        np.empty((largest, channel_count)),
        np.empty(channel_count),
        np.empty(channel_count),
        np.empty((TABLE_FIELDS, largest), np.int64),
    )


@njit(cache=True)
def paint_pieces(
    units, positions, z, channels, offsets, scale, width, height, value_count,
    piece_polygon, cut_starts, cut_rows, piece_rows, mode, target,
):  # fmt: skip
    """Draw pieces i = 0, 1, ... of polygons piece_polygon[i] with the per-sample test `mode`.

    Piece i keeps the samples of its polygon on the kept side of its cuts,
    rows cut_starts[i]:cut_starts[i + 1] of `cut_rows` (see `keeps`), on
    sample rows piece_rows[i, 0] <= y < piece_rows[i, 1] (its extent);
    `target` (H, W) is the decided polygon per sample for mode TARGET. The
    other arguments and the result are those of `zbuffer_polygons`; DRAWN
    and SKIPPED count pieces.
    """
    depth = np.full((height, width), np.inf)
    ids = np.full((height, width), -1, np.int64)
    values = np.zeros((height, width, value_count))
    stats = np.zeros(STAT_FIELDS, np.int64)
    largest = 0
    for p in range(offsets.shape[0] - 1):
        largest = max(largest, offsets[p + 1] - offsets[p])
    buffers = scratch(largest, channels.shape[1])
    for i in range(piece_polygon.shape[0]):
        p = piece_polygon[i]
        first, stop = offsets[p], offsets[p + 1]
        _, _, c, dzdx, dzdy, z_first = depth_plane(
            positions[first:stop, 0], positions[first:stop, 1], z[first:stop]
        )
        xs, ys = units[first:stop, 0], units[first:stop, 1]
        if c == 0.0 or not reaches_raster(
            xs.min(), xs.max(), ys.min(), ys.max(), scale, width, height
        ):
            stats[SKIPPED] += 1  # seen edge-on, or off the raster: never scanned
            continue
        fragments = stats[FRAGMENTS]
        plane = (positions[first, 0], positions[first, 1], z_first, dzdx, dzdy)
        cuts = cut_rows[cut_starts[i] : cut_starts[i + 1]]
        draw_polygon(
            p, units, offsets[p : p + 2], scale, plane, channels, buffers, depth, ids, values,
            stats, mode, cuts, target, (piece_rows[i, 0], piece_rows[i, 1]),
        )  # fmt: skip
        stats[DRAWN] += stats[FRAGMENTS] > fragments
    return depth, ids, values, stats


@njit(cache=True)
def polygon_planes(units, positions, z, offsets, scale, width, height):
    """Per polygon: its plane (x_first, y_first, z_first, dzdx, dzdy), Newell's (a, b, c), and drawn.

    The planes `paint_pieces` and `zbuffer_polygons` compute (the same
    `depth_plane`); drawn is False where those skip the polygon.
    """
    count = offsets.shape[0] - 1
    planes, normals = np.zeros((count, 5)), np.zeros((count, 3))
    drawn = np.zeros(count, np.bool_)
    for p in range(count):
        first, stop = offsets[p], offsets[p + 1]
        a, b, c, dzdx, dzdy, z_first = depth_plane(
            positions[first:stop, 0], positions[first:stop, 1], z[first:stop]
        )
        planes[p, 0], planes[p, 1], planes[p, 2] = positions[first, 0], positions[first, 1], z_first
        planes[p, 3], planes[p, 4] = dzdx, dzdy
        normals[p, 0], normals[p, 1], normals[p, 2] = a, b, c
        xs, ys = units[first:stop, 0], units[first:stop, 1]
        drawn[p] = c != 0.0 and reaches_raster(
            xs.min(), xs.max(), ys.min(), ys.max(), scale, width, height
        )
    return planes, normals, drawn

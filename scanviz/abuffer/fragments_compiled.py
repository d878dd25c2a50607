"""Compiled twin of `scanviz.abuffer.fragments.polygon_fragments`: all polygons in one pass.

`polygon_fragments` makes one polygon's fragments with numpy, a few
milliseconds of Python a polygon. `chunk_fragments` makes the fragments of a
run of polygons in two compiled passes (shared among numba's threads), into
flat arrays in drawing order, each polygon's fragments sorted by y then x,
equal to the reference's:

* masks: the scan converter's own compiled kernel (`raster.scan_compiled.scan_polygon`)
  on the polygon snapped and scaled by (cols, rows), as `masks.pixel_masks`
  runs it; its sub-sample spans are cut at pixel borders into the bits
  `masks._gather_spans` makes;
* areas: `area._coverage_kernel`, the exact-area kernel of `pixel_areas`, run
  on the raster cut at the right of the polygon's window, keeping the
  window's columns (the columns it reaches see the same operations: nothing
  there is clipped);
* depth ranges: `raster.interpolate.depth_plane` compiled from the same source;
* shading points and attributes: the operations of `fragments.fragment_points`
  and `fragments.fragment_values`, elementwise in the same order, with numpy's
  pairwise summation where the reference sums over edges (`_pairwise_sum`).

So masks, areas, depths and values are bit-identical to the reference. A
polygon the kernel cannot take is flagged `REFERENCE` and made by
`polygon_fragments` instead: a grid finer than `MAX_SUBPIXEL_BITS` (unsnapped
input whose coordinates need more bits, where the scan converter needs
Python integers) or an exact area past `area.MAX_WORK` edge visits (the
reference raises its error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from ..conventions import MAX_SUBPIXEL_BITS
from ..limits import check_memory
from ..raster import interpolate
from ..raster.fixed import exact_bits_compiled
from ..raster.scan_compiled import has_three_distinct, scan_polygon
from ..threads import use_threads
from .area import MAX_WORK, _coverage_kernel

depth_plane = njit(cache=True)(interpolate.depth_plane)

DONE, REFERENCE = 0, 1  # per-polygon status of `chunk_fragments`
WINDOW_MARGIN = 1  # pixels around a polygon's bounding box: room for rounding of edge x


@njit(cache=True)
def _snapped(xy, bits):
    """Vertices snapped to 1/2**bits pixel (`rint`, ties to even); bits < 0 keeps them."""
    if bits < 0:
        return xy.copy()
    return np.rint(xy * 2.0**bits) / 2.0**bits


@njit(cache=True)
def polygon_windows(xy, offsets, width, height, bits):
    """(P, 4) int64 pixel windows (row0, row1, col0, col1) holding each polygon's fragments.

    The bounding box of the snapped vertices, `WINDOW_MARGIN` pixels wider on
    every side, clipped to the raster (empty when the polygon misses it).
    """
    windows = np.zeros((len(offsets) - 1, 4), np.int64)
    for p in range(len(offsets) - 1):
        grid = _snapped(xy[offsets[p] : offsets[p + 1]], bits)
        for axis, size in ((1, height), (0, width)):
            low = math.floor(grid[:, axis].min()) - WINDOW_MARGIN
            high = math.floor(grid[:, axis].max()) + 1 + WINDOW_MARGIN
            windows[p, 2 - 2 * axis] = min(max(low, 0), size)
            windows[p, 3 - 2 * axis] = max(min(high, size), windows[p, 2 - 2 * axis])
    return windows


@njit(cache=True)
def _window_masks(grid, width, height, cols, rows, window, cast):
    """(masks over `window`, True), or (zeros, False) if the grid is too fine for the int64 kernel.

    `masks.subsample_polygon` + `scan_snapped` + `masks._gather_spans`: scale by
    (cols, rows), put on the center-sample grid of the finest bits it needs,
    scan convert at sub-sample resolution, or each span's bits into its pixel.
    """
    row0, row1, col0, col1 = window
    masks = np.zeros((row1 - row0, col1 - col0), np.uint64)
    scaled = np.empty_like(grid)
    scaled[:, 0], scaled[:, 1] = grid[:, 0] * float(cols), grid[:, 1] * float(rows)
    bits = exact_bits_compiled(scaled, MAX_SUBPIXEL_BITS)
    if bits > MAX_SUBPIXEL_BITS:
        return masks, False
    units = np.empty(grid.shape, np.int64)
    for i in range(len(grid)):  # `raster.fixed.snap_units`, "center"
        for axis in range(2):
            units[i, axis] = 2 * np.int64(np.rint(scaled[i, axis] * 2.0**bits)) - 2**bits
    offsets = np.array([0, len(units)], np.int64)
    sub_height = height * rows
    most = sub_height * (len(units) + 1)  # a sub-row has fewer spans than edges
    spans, _, _ = scan_polygon(
        units, offsets, 2 ** (bits + 1), width * cols, sub_height, False, True, cast,
        np.empty((0, 0), np.int32), most,
    )  # fmt: skip
    for k in range(len(spans)):
        sub_row, start, end = spans[k, 0], spans[k, 1], spans[k, 2]
        y, j = sub_row // rows, sub_row % rows
        for x in range(start // cols, (end - 1) // cols + 1):
            low, high = max(start - x * cols, 0), min(end - x * cols, cols)
            shift = np.uint64(low + j * cols)
            bits_set = ((np.uint64(1) << np.uint64(high - low)) - np.uint64(1)) << shift
            masks[y - row0, x - col0] |= bits_set
    return masks, True


@njit(cache=True)
def _window_areas(grid, width, height, window):
    """(first row, (rows, window's columns) areas, within MAX_WORK); clip them to [0, 1].

    `area._edge_arrays` + `_row_range` + the coverage kernel, on a raster as
    wide as the window's right end (no column the polygon reaches is cut),
    keeping the window's columns (the columns left of it get nothing).
    """
    n = len(grid)
    count = 0
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        count += grid[i, 1] != grid[j, 1]  # horizontal edges bound no strip
    ax, ay, bx, by = np.empty(count), np.empty(count), np.empty(count), np.empty(count)
    winding = np.empty(count, np.int64)
    count = 0
    for i in range(n):  # insertion by lower y, after equal ones: a stable sort, as the reference's
        j = i + 1 if i + 1 < n else 0
        x0, y0, x1, y1 = grid[i, 0], grid[i, 1], grid[j, 0], grid[j, 1]
        if y0 == y1:
            continue
        up = y1 > y0
        k = count
        while k > 0 and ay[k - 1] > (y0 if up else y1):
            ax[k], ay[k], bx[k], by[k], winding[k] = (
                ax[k - 1],
                ay[k - 1],
                bx[k - 1],
                by[k - 1],
                winding[k - 1],
            )
            k -= 1
        ax[k], ay[k] = (x0, y0) if up else (x1, y1)
        bx[k], by[k] = (x1, y1) if up else (x0, y0)
        winding[k] = 1 if up else -1
        count += 1
    row0 = row1 = 0
    if count:
        row0 = min(max(0, math.floor(ay.min())), height)
        row1 = max(min(height, math.ceil(by.max())), row0)
    areas, work = _coverage_kernel(
        ax, ay, bx, by, winding, window[3], height, False, row0, row1, MAX_WORK, window[2]
    )
    return row0, areas, work <= MAX_WORK  # unclipped: the caller clips what it reads


@njit(cache=True, inline="always")
def _minimum(a, b):
    """numpy.minimum of two non-NaN floats (a on ties, so signed zeros agree)."""
    return a if a <= b else b


@njit(cache=True, inline="always")
def _maximum(a, b):
    return a if a >= b else b


@njit(cache=True, inline="always")
def _clip(a, low, high):
    return _minimum(_maximum(a, low), high)


@njit(cache=True)
def _pairwise_sum(a, n):
    """numpy's sum of a[:n] (float64 add.reduce along a row: pairwise, 8 partial sums)."""
    if n < 8:
        total = 0.0
        for i in range(n):
            total += a[i]
        return total
    if n <= 128:
        r = a[:8].copy()
        i = 8
        while i < n - n % 8:
            for k in range(8):
                r[k] += a[i + k]
            i += 8
        total = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]))
        while i < n:
            total += a[i]
            i += 1
        return total
    half = n // 2
    half -= half % 8
    return _pairwise_sum(a, half) + _pairwise_sum(a[half:], n - half)


@njit(cache=True)
def _sliver_point(sx, sy, x, y, scratch_x, scratch_y):
    """`fragments._sliver_points` for pixel (x, y): mean midpoint of the edges clipped to it."""
    n = len(sx)
    count = 0
    for e in range(n):
        x0, y0 = sx[e], sy[e]
        nxt = e + 1 if e + 1 < n else 0
        dx, dy = sx[nxt] - x0, sy[nxt] - y0
        low, high = 0.0, 1.0
        for start, delta, lo, hi in ((x0, dx, x, x + 1), (y0, dy, y, y + 1)):
            moving = delta != 0
            safe = delta if moving else 1.0
            t_lo, t_hi = (lo - start) / safe, (hi - start) / safe
            if moving:
                low = _maximum(low, _minimum(t_lo, t_hi))
                high = _minimum(high, _maximum(t_lo, t_hi))
            elif start < lo or start > hi:  # parallel to the slab, outside it
                high = -1.0
        meets = low <= high
        middle = (low + high) / 2
        scratch_x[e] = x0 + middle * dx if meets else 0.0
        scratch_y[e] = y0 + middle * dy if meets else 0.0
        count += meets
    if count == 0:
        return x + 0.5, y + 0.5
    return _pairwise_sum(scratch_x, n) / count, _pairwise_sum(scratch_y, n) / count


@njit(cache=True)
def row_sums(cols):
    """Per value r of one mask row (cols bits): (set bits, sum of their (i + 0.5) / cols)."""
    counts, sums = np.zeros(2**cols, np.int64), np.zeros(2**cols)
    for r in range(2**cols):
        for i in range(cols):
            if (r >> i) & 1:
                counts[r] += 1
                sums[r] += (i + 0.5) / cols
    return counts, sums


@njit(cache=True, inline="always")
def _covered_centroid(mask, x, y, cols, rows, row_counts, row_sums):
    """`fragments._covered_centroids`: the mean of the set bits' sub-sample centres.

    Row by row from a table of the row's bits; every term is a multiple of
    1 / (2 cols) or 1 / (2 rows) and the sums stay far below 2**53 of them,
    so they are exact in any order: the reference's matrix product's value.
    """
    sum_x = sum_y = 0.0
    count = 0
    row_mask = np.uint64(2**cols - 1)
    for j in range(rows):
        r = (mask >> np.uint64(j * cols)) & row_mask
        if r:
            sum_x += row_sums[r]
            sum_y += row_counts[r] * ((j + 0.5) / rows)
            count += row_counts[r]
    return sum_x / count + x, sum_y / count + y


@njit(cache=True, inline="always")
def _scanline_values(sx, sy, channels, px, py, out, crossing, t):
    """`fragments._scanline_values` at one point: along the nearest edges left/right, then across."""
    n = len(sx)
    py = _clip(py, sy.min(), sy.max())
    left = right = 0
    left_x, right_x = -np.inf, np.inf
    any_span = False
    for e in range(n):
        nxt = e + 1 if e + 1 < n else 0
        x0, y0 = sx[e], sy[e]
        dx, dy = sx[nxt] - x0, sy[nxt] - y0
        spans = (dy != 0) and (_minimum(y0, y0 + dy) <= py) and (py <= _maximum(y0, y0 + dy))
        t[e] = _clip((py - y0) / (dy if dy != 0 else 1.0), 0.0, 1.0)
        crossing[e] = x0 + t[e] * dx
        any_span |= spans
        if spans and crossing[e] <= px and crossing[e] > left_x:  # argmax: the first of equals
            left, left_x = e, crossing[e]
        if spans and crossing[e] >= px and crossing[e] < right_x:
            right, right_x = e, crossing[e]
    has_left, has_right = np.isfinite(left_x), np.isfinite(right_x)
    if not any_span:  # no edge spans the row (all horizontal): vertex 0
        t[:] = 0.0
    if not has_left:
        left = right
    if not has_right:
        right = left
    x_left, x_right = crossing[left], crossing[right]
    gap = x_right - x_left
    s = _clip((px - x_left) / (gap if gap > 0 else 1.0), 0.0, 1.0) if gap > 0 else 0.0
    a, b = left + 1 if left + 1 < n else 0, right + 1 if right + 1 < n else 0
    for k in range(channels.shape[1]):
        v_left = channels[left, k] + t[left] * (channels[a, k] - channels[left, k])
        v_right = channels[right, k] + t[right] * (channels[b, k] - channels[right, k])
        out[k] = v_left + s * (v_right - v_left)


@njit(cache=True, inline="always")
def _fragment_values(sx, sy, channels, low, high, perspective, px, py, out, row, scratch):
    """`fragments.fragment_values` at one point into `out[row]` (K,): interpolate, divide, clip."""
    buffer, crossing, t = scratch[0], scratch[1], scratch[2]
    _scanline_values(sx, sy, channels, px, py, buffer, crossing, t)
    last = channels.shape[1] - 1
    for k in range(out.shape[1]):
        value = buffer[k] / buffer[last] if perspective else buffer[k]
        out[row, k] = _clip(value, low[k], high[k])


@njit(cache=True)
def _polygon_coverage(q, xy, offsets, windows, first, width, height, cols, rows, bits, cast, cells,
                      masks_out, areas_out):  # fmt: skip
    """Polygon p = first + q's masks and clipped areas over its window, row by row, into its cells.

    Returns how many cells hold a fragment (a set bit or an area above 0),
    or -1 (REFERENCE: the cells are not written).
    """
    p = first + q
    window, lo, hi = windows[p], offsets[p], offsets[p + 1]
    if window[0] == window[1] or window[2] == window[3] or not has_three_distinct(xy[lo:hi]):
        return 0
    grid = _snapped(xy[lo:hi], bits)
    masks, exact = _window_masks(grid, width, height, cols, rows, window, cast)
    area_row0, areas, within = _window_areas(grid, width, height, window)
    if not (exact and within):
        return -1
    count, cell = 0, cells[q]
    for y in range(window[0], window[1]):
        for x in range(window[2], window[3]):
            mask = masks[y - window[0], x - window[2]]
            area = 0.0
            if area_row0 <= y < area_row0 + areas.shape[0]:  # np.clip(areas, 0, 1) as the reference
                area = _clip(areas[y - area_row0, x - window[2]], 0.0, 1.0)
            masks_out[cell], areas_out[cell] = mask, area
            count += mask != 0 or area > 0.0
            cell += 1
    return count


@njit(cache=True)
def _polygon_into(q, xy, z, inv_w, values, offsets, windows, first, cols, rows, bits, perspective,
                  row_counts, row_totals, cells, masks, areas, made, starts, out):  # fmt: skip
    """Polygon p = first + q's fragments from its window's cells into rows starts[q], ... of `out`."""
    if made[q] <= 0:
        return  # no fragments, or REFERENCE
    x_out, y_out, polygon_out, mask_out, area_out, zmin_out, zmax_out, values_out = out
    p = first + q
    window, lo, hi = windows[p], offsets[p], offsets[p + 1]
    grid = _snapped(xy[lo:hi], bits)
    sx, sy, zs = grid[:, 0], grid[:, 1], z[lo:hi]
    _, _, c, dzdx, dzdy, z_first = depth_plane(sx, sy, zs)
    z_low, z_high = zs.min(), zs.max()
    n, k_values = hi - lo, values.shape[1]
    if perspective:
        channels = np.empty((n, k_values + 1))
        for v in range(n):
            channels[v, :k_values] = values[lo + v] * inv_w[lo + v]
            channels[v, k_values] = inv_w[lo + v]
    else:
        channels = values[lo:hi].copy()
    low, high = np.empty(k_values), np.empty(k_values)
    for k in range(k_values):
        low[k], high[k] = values[lo:hi, k].min(), values[lo:hi, k].max()
    scratch = np.empty((3, max(n, k_values + 1)))
    count, cell = starts[q], cells[q]
    for y in range(window[0], window[1]):
        for x in range(window[2], window[3]):
            mask, area = masks[cell], areas[cell]
            cell += 1
            if mask == 0 and not area > 0.0:
                continue
            x_out[count], y_out[count], polygon_out[count] = x, y, p
            mask_out[count], area_out[count] = mask, area
            if c == 0.0:
                z_min = z_max = zs[0]
            else:
                z_min, z_max = np.inf, -np.inf
                for dx in (0, 1):
                    for dy in (0, 1):
                        depth = z_first + dzdx * ((x + dx) - sx[0]) + dzdy * ((y + dy) - sy[0])
                        z_min, z_max = min(z_min, depth), max(z_max, depth)
            zmin_out[count] = _clip(z_min, z_low, z_high)
            zmax_out[count] = _clip(z_max, z_low, z_high)
            if mask != 0:
                px, py = _covered_centroid(mask, x, y, cols, rows, row_counts, row_totals)
            else:
                px, py = _sliver_point(sx, sy, x, y, scratch[1], scratch[2])
            _fragment_values(
                sx, sy, channels, low, high, perspective, px, py, values_out, count, scratch
            )
            count += 1


# Each pass in two twins: over numba's threads (`_shared`) and on this one (`_here`, for small
# chunks: the threads' start and their spinning on a busy machine cost more than they save).
# A polygon's cells and rows are fixed before the pass, so the output is the same either way.


@njit(cache=True, parallel=True)
def _coverage_shared(xy, offsets, windows, first, width, height, cols, rows, bits, cast, cells,
                     masks, areas, made):  # fmt: skip
    for q in prange(len(made)):
        made[q] = _polygon_coverage(q, xy, offsets, windows, first, width, height, cols, rows,
                                    bits, cast, cells, masks, areas)  # fmt: skip


@njit(cache=True)
def _coverage_here(xy, offsets, windows, first, width, height, cols, rows, bits, cast, cells,
                   masks, areas, made):  # fmt: skip
    for q in range(len(made)):
        made[q] = _polygon_coverage(q, xy, offsets, windows, first, width, height, cols, rows,
                                    bits, cast, cells, masks, areas)  # fmt: skip


@njit(cache=True, parallel=True)
def _fill_shared(xy, z, inv_w, values, offsets, windows, first, cols, rows, bits, perspective,
                 row_counts, row_totals, cells, masks, areas, made, starts, out):  # fmt: skip
    for q in prange(len(made)):
        _polygon_into(q, xy, z, inv_w, values, offsets, windows, first, cols, rows, bits,
                      perspective, row_counts, row_totals, cells, masks, areas, made, starts, out)  # fmt: skip


@njit(cache=True)
def _fill_here(xy, z, inv_w, values, offsets, windows, first, cols, rows, bits, perspective,
               row_counts, row_totals, cells, masks, areas, made, starts, out):  # fmt: skip
    for q in range(len(made)):
        _polygon_into(q, xy, z, inv_w, values, offsets, windows, first, cols, rows, bits,
                      perspective, row_counts, row_totals, cells, masks, areas, made, starts, out)  # fmt: skip


PARALLEL_WORK = 2**12  # polygons plus window pixels in a chunk: below this, one thread works


def chunk_fragments(
    xy, z, inv_w, values, offsets, windows, first, stop, width, height, cols, rows, bits,
    perspective, cast,
):  # fmt: skip
    """Fragments of polygons [first, stop) in drawing order, as `polygon_fragments` makes them.

    `windows` are `polygon_windows`; `bits` the sub-pixel bits (-1: unsnapped). Returns (count, starts, status, x, y,
    polygon, mask, area, zmin, zmax, attributes): polygon p's fragments are
    rows starts[p - first]:starts[p - first + 1]; status[p - first] is DONE
    or REFERENCE (no rows: make it with the reference).

    Two passes, each shared among numba's threads when the chunk is large
    (`PARALLEL_WORK`): every polygon's masks and areas into its cells of a
    window-sized scratch (and its fragment count), then, with the counts
    summed into each polygon's first row, its fragments from those cells.
    """
    sizes = (windows[first:stop, 1] - windows[first:stop, 0]) * (
        windows[first:stop, 3] - windows[first:stop, 2]
    )
    cells = np.zeros(stop - first + 1, np.int64)
    np.cumsum(sizes, out=cells[1:])
    capacity = int(cells[-1])
    shared = use_threads(stop - first + capacity, PARALLEL_WORK)
    masks, areas = np.empty(capacity, np.uint64), np.empty(capacity)
    made = np.empty(stop - first, np.int64)
    coverage = _coverage_shared if shared else _coverage_here
    coverage(xy, offsets, windows, first, width, height, cols, rows, bits, cast, cells, masks,
             areas, made)  # fmt: skip
    status = np.where(made < 0, REFERENCE, DONE)
    starts = np.zeros(stop - first + 1, np.int64)
    np.cumsum(np.maximum(made, 0), out=starts[1:])
    count = int(starts[-1])
    out = (
        np.empty(count, np.int64), np.empty(count, np.int64), np.empty(count, np.int64),
        np.empty(count, np.uint64), np.empty(count), np.empty(count), np.empty(count),
        np.empty((count, values.shape[1])),
    )  # fmt: skip
    fill = _fill_shared if shared else _fill_here
    fill(xy, z, inv_w, values, offsets, windows, first, cols, rows, bits, perspective,
         *row_sums(cols), cells, masks, areas, made, starts, out)  # fmt: skip
    return (count, starts, status, *out)


CHUNK_POLYGONS = 4096  # polygons per compiled call: the progress bar and Ctrl-C act between calls
CHUNK_FRAGMENTS = 2**20  # and at most about this many fragments (window areas) per call


@dataclass(frozen=True)
class FlatFragments:
    """Fragments of many polygons in drawing order, each polygon's sorted by y then x.

    x, y, polygon: (F,) int64; mask: (F,) uint64; area, zmin, zmax: (F,)
    float64; values: (F, K) float64 (as `fragments.PolygonFragments`).
    """

    x: np.ndarray
    y: np.ndarray
    polygon: np.ndarray
    mask: np.ndarray
    area: np.ndarray
    zmin: np.ndarray
    zmax: np.ndarray
    values: np.ndarray

    @property
    def count(self) -> int:
        return len(self.x)

    @classmethod
    def join(cls, parts: list[FlatFragments], value_count: int) -> FlatFragments:
        """One table of `parts`, in order."""
        if not parts:
            empty = np.zeros(0, np.int64)
            return cls(empty, empty, empty, np.zeros(0, np.uint64), *[np.zeros(0)] * 3,
                       np.zeros((0, value_count)))  # fmt: skip
        fields = cls.__dataclass_fields__
        return cls(*(np.concatenate([getattr(p, name) for p in parts]) for name in fields))

    @classmethod
    def of_polygon(cls, found, p: int) -> FlatFragments:
        """The rows of one polygon's `PolygonFragments`."""
        return cls(found.xs, found.ys, np.full(len(found.xs), p, np.int64), found.masks,
                   found.areas, found.zmin, found.zmax, found.values)  # fmt: skip


def fragment_chunks(polygons, width, height, *, mask, subpixel_bits, perspective, what=""):
    """Yield (polygons done, FlatFragments) chunk by chunk over `polygons` (ScreenPolygons).

    Each chunk is one `chunk_fragments` call (at most `CHUNK_POLYGONS`
    polygons and about `CHUNK_FRAGMENTS` fragments of window), its output
    buffers checked against the memory limit first (the error names `what`);
    polygons it flags `REFERENCE` are made by `polygon_fragments` in their place.
    """
    from .masks import MASK_LAYOUTS

    cols, rows = MASK_LAYOUTS[mask]
    options = {"mask": mask, "subpixel_bits": subpixel_bits, "perspective": perspective}
    bits = -1 if subpixel_bits is None else subpixel_bits
    offsets = np.asarray(polygons.offsets, np.int64)
    xy, z, inv_w = polygons.xy, polygons.z, polygons.inv_w
    values = np.ascontiguousarray(polygons.values, dtype=np.float64)
    windows = polygon_windows(xy, offsets, width, height, bits)
    sizes = (windows[:, 1] - windows[:, 0]) * (windows[:, 3] - windows[:, 2])
    per_fragment = 8 * (7 + values.shape[1])
    first = 0
    while first < polygons.count:
        ends = np.cumsum(sizes[first : first + CHUNK_POLYGONS])
        stop = first + max(int(np.searchsorted(ends, CHUNK_FRAGMENTS, side="right")), 1)
        capacity = int(ends[stop - first - 1])
        check_memory(
            capacity * per_fragment, f"{what or 'fragments'}: polygons {first}..{stop - 1} at once"
        )
        _, starts, status, *found = chunk_fragments(
            xy, z, inv_w, values, offsets, windows, first, stop, width, height, cols, rows,
            bits, perspective, np.float64,
        )  # fmt: skip
        found = FlatFragments(*found)
        if (status == REFERENCE).any():
            found = _spliced(
                found,
                starts,
                status,
                first,
                (xy, z, inv_w, values, offsets),
                width,
                height,
                options,
            )
        yield stop - first, found
        first = stop


def _spliced(found, starts, status, first, arrays, width, height, options):
    """A chunk's `found` with the polygons flagged REFERENCE made by `polygon_fragments`, in place."""
    from .fragments import polygon_fragments

    xy, z, inv_w, values, offsets = arrays
    parts, done, stop = [], 0, first + len(status)
    for p in [*np.flatnonzero(status == REFERENCE) + first, stop]:
        parts.append(FlatFragments(*(getattr(found, name)[starts[done] : starts[p - first]]
                                     for name in FlatFragments.__dataclass_fields__)))  # fmt: skip
        if p < stop:
            rows = slice(offsets[p], offsets[p + 1])
            part = polygon_fragments(
                xy[rows], z[rows], inv_w[rows], values[rows], width, height,
                polygon_index=int(p), **options,
            )  # fmt: skip
            if part is not None:
                parts.append(FlatFragments.of_polygon(part, int(p)))
            done = p - first + 1
    return FlatFragments.join(parts, found.values.shape[1])

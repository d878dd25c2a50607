"""Pixel masks: which sub-samples of each pixel a polygon covers (Rendermatic thesis §6.3.2).

A pixel mask is a grid of ``cols x rows`` sub-samples per pixel, stored as the
bits of a uint64. Sub-sample (i, j) of pixel (x, y) sits at the center of its
sub-cell, (x + (i + 0.5) / cols, y + (j + 0.5) / rows), and is bit
``j * cols + i`` (row 0 at the bottom, as images are).

Each bit is decided by the scan converter's own exact rule (DESIGN §2): the
polygon is snapped as `scanviz.raster.fixed.snap` does, and a sub-sample on an
edge counts as the point (sx + eps, sy + eps**2). Polygons that share an edge
therefore split its sub-samples between them: no bit is lost or counted twice.

Two implementations give the same masks:

* `pixel_masks` scales the snapped polygon by (cols, rows), which is exact
  (powers of two) and keeps the eps rule (a positive scale of eps), scan
  converts it at sub-sample resolution with the compiled kernel, and gathers
  the spans into per-pixel bits.
* `mask_buffer_rows` is the thesis' mask buffer, traced: row by row, every
  active edge is scanned into the buffer as an edge mask (its sub-samples at
  or right of its crossings), and the masks of a pixel are combined by
  winding. For a convex corner inside a pixel this is the thesis' "and" of
  the edge masks (Fig. 6.10); summing windings also gets holes, overlaps and
  the even-odd rule right, and the winding carried in from the left fills
  pixels that no edge crosses (under a horizontal edge, the mask is partial).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ..conventions import RULES, check_choice, check_raster_size, check_subpixel_bits
from ..geometry import Polygon
from ..raster.api import as_tracer, scan_snapped
from ..raster.fixed import SnappedPolygon, exact_bits, snap_units
from ..raster.scanline import bucketed_edge_table, scan_rows
from ..trace import Recorder, Trace, Tracer
from ..trace.events import EdgeMask, EdgeMaskEntry, MaskBufferPixel, MaskBufferRow, MaskRun

MASK_LAYOUTS = {"4x4": (4, 4), "8x4": (8, 4), "8x8": (8, 8)}  # name: (columns, rows)
DEFAULT_MASK = "8x8"


@dataclass(frozen=True)
class MaskResult:
    """The pixel masks of one polygon: pixel (xs[k], ys[k]) has mask masks[k].

    Attributes
    ----------
    ys, xs : (K,) ndarray of int64
        Every pixel with at least one covered sub-sample, sorted by y then x.
    masks : (K,) ndarray of uint64
        Their masks, never 0; bit ``j * cols + i`` is sub-sample (i, j).
    layout : str
        A key of `MASK_LAYOUTS`.
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    ys: np.ndarray
    xs: np.ndarray
    masks: np.ndarray
    layout: str
    trace: Trace | None = None


def _layout(mask: object) -> tuple[int, int]:
    return MASK_LAYOUTS[check_choice("mask", mask, tuple(MASK_LAYOUTS))]


def subsample_positions(layout: str = DEFAULT_MASK) -> np.ndarray:
    """Offsets of the sub-samples from a pixel's lower-left corner, in bit order.

    Returns
    -------
    (n, 2) ndarray of float64
        Row k is (x, y) of bit k, n = cols * rows.

    Examples
    --------
    >>> subsample_positions("4x4")[[0, 1, 4]].tolist()
    [[0.125, 0.125], [0.375, 0.125], [0.125, 0.375]]
    """
    cols, rows = _layout(layout)
    j, i = np.divmod(np.arange(cols * rows), cols)
    return np.column_stack([(i + 0.5) / cols, (j + 0.5) / rows])


def full_mask(layout: str = DEFAULT_MASK) -> np.uint64:
    """The mask with every sub-sample set.

    >>> int(full_mask("4x4")), int(full_mask("8x8")) == 2**64 - 1
    (65535, True)
    """
    cols, rows = _layout(layout)
    return np.uint64(2 ** (cols * rows) - 1)


def popcount(masks: object) -> np.ndarray:
    """Number of set bits of each mask: an int64 array of the shape of `masks`.

    >>> popcount([0, 1, 0b1011, 2**64 - 1]).tolist()
    [0, 1, 3, 64]
    """
    return np.bitwise_count(np.asarray(masks, dtype=np.uint64)).astype(np.int64)


def mask_to_grid(mask: object, layout: str = DEFAULT_MASK) -> np.ndarray:
    """A mask as a (rows, cols) ndarray of bool, row 0 at the bottom (show with origin="lower").

    >>> mask_to_grid(0b0000_0000_0011_0001, "4x4")[::-1].astype(int)  # top row first
    array([[0, 0, 0, 0],
           [0, 0, 0, 0],
           [1, 1, 0, 0],
           [1, 0, 0, 0]])
    """
    cols, rows = _layout(layout)
    bits = np.uint64(int(mask)) >> np.arange(cols * rows, dtype=np.uint64)
    return (bits & np.uint64(1)).astype(bool).reshape(rows, cols)


def _grid_to_mask(grid: np.ndarray) -> int:
    """The int mask of a (rows, cols) bool grid (inverse of `mask_to_grid`)."""
    return sum(1 << int(k) for k in np.flatnonzero(grid.ravel()))


def subsample_polygon(polygon: Polygon, mask: str, subpixel_bits: int | None) -> SnappedPolygon:
    """The polygon snapped at `subpixel_bits`, scaled by (cols, rows), on the center-sample grid.

    In the scaled frame sub-sample (i, j) of pixel (x, y) is the center
    sample of pixel (x * cols + i, y * rows + j). Scaling by powers of two is
    exact, so the grid is as fine as the snapped values need, no finer.
    """
    cols, rows = _layout(mask)
    vertices = polygon.vertices
    if subpixel_bits is not None:
        vertices = np.rint(vertices * 2.0**subpixel_bits) / 2.0**subpixel_bits
    scaled = vertices * np.array([cols, rows], dtype=np.float64)
    bits = exact_bits(scaled)
    return SnappedPolygon(snap_units(scaled, "center", bits), polygon.offsets, bits, "center")


def _gather_spans(spans: np.ndarray, mask: str, width: int) -> tuple[np.ndarray, ...]:
    """(ys, xs, masks) of sub-sample spans (Y, X_start, X_end): each span cut at pixel borders."""
    cols, rows = _layout(mask)
    if len(spans) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0, np.uint64)
    sub_row, start, end = spans.T
    first = start // cols
    pieces = (end - 1) // cols - first + 1  # pixels each span touches
    span = np.repeat(np.arange(len(spans)), pieces)
    x = first[span] + np.arange(pieces.sum()) - np.repeat(np.cumsum(pieces) - pieces, pieces)
    low = np.maximum(start[span] - x * cols, 0)
    high = np.minimum(end[span] - x * cols, cols)
    shift = (low + (sub_row[span] % rows) * cols).astype(np.uint64)
    bits = ((np.uint64(1) << (high - low).astype(np.uint64)) - np.uint64(1)) << shift
    key = (sub_row[span] // rows) * width + x
    order = np.argsort(key, kind="stable")
    key, bits = key[order], bits[order]
    starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    ys, xs = np.divmod(key[starts], width)
    return ys, xs, np.bitwise_or.reduceat(bits, starts)


def pixel_masks(
    polygon: object,
    width: int,
    height: int,
    *,
    mask: str = DEFAULT_MASK,
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
    trace: object = None,
    polygon_index: int = 0,
) -> MaskResult:
    """The pixel mask of every pixel a polygon covers at least one sub-sample of.

    Parameters
    ----------
    polygon : Polygon or array_like
        Anything `Polygon` accepts.
    width, height : int
        Raster size in pixels.
    mask : {"8x8", "8x4", "4x4"}
        Sub-sample layout, (columns, rows) per pixel (`MASK_LAYOUTS`).
    rule : {"nonzero", "evenodd"}
        Fill rule.
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel, as `scan_convert` does; None decides
        the float64 input exactly.
    trace : None, True, or Tracer
        None runs the compiled scan converter at sub-sample resolution; a
        tracer runs the traced mask buffer `mask_buffer_rows` (same masks).
    polygon_index : int
        The ``polygon`` field of trace events.

    Returns
    -------
    MaskResult

    Examples
    --------
    A triangle inside pixel (1, 0), seen with 4x4 sub-samples:

    >>> result = pixel_masks([(1, 0), (2, 0), (1, 1)], 3, 1, mask="4x4")
    >>> result.xs.tolist(), result.ys.tolist(), popcount(result.masks).tolist()
    ([1], [0], [6])
    >>> mask_to_grid(result.masks[0], "4x4")[::-1].astype(int)  # top row first
    array([[0, 0, 0, 0],
           [1, 0, 0, 0],
           [1, 1, 0, 0],
           [1, 1, 1, 0]])
    """
    if trace is not None and trace is not False:  # the traced mask buffer checks the arguments
        return mask_buffer_rows(
            polygon,
            width,
            height,
            mask=mask,
            rule=rule,
            subpixel_bits=subpixel_bits,
            trace=trace,
            polygon_index=polygon_index,
        )
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    cols, rows = _layout(mask)
    check_choice("rule", rule, RULES)
    bits = check_subpixel_bits(subpixel_bits)
    scaled = subsample_polygon(polygon, mask, bits)
    spans, _ = scan_snapped(scaled, width * cols, height * rows, rule=rule)
    return MaskResult(*_gather_spans(spans, mask, width), mask)


def mask_buffer_rows(
    polygon: object,
    width: int,
    height: int,
    *,
    mask: str = DEFAULT_MASK,
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
    trace: object = True,
    polygon_index: int = 0,
) -> MaskResult:
    """The thesis' mask buffer (§6.3.2-6.3.3): pixel masks row by row from edge masks, traced.

    The sub-rows are the rows of the ET/AET walk (`scan_rows`) of the polygon
    scaled by the mask's sub-samples per pixel, so the replaceable steps
    (``edge_table_entry``, ``aet_update``) drive the mask buffer as they drive
    `scan_convert`. For each pixel row y: take the active edges' crossings of
    its sub-rows from their AETs; scan each edge into the mask buffer, where
    on every sub-row it crosses it marks the sub-samples at or right of its
    crossing with its winding; combine the edge masks of each pixel with the
    winding carried in from the left, sub-row by sub-row, under the fill rule.
    Emits one `mask_buffer_row` event per pixel row and one `edge_mask` event
    per edge and crossed pixel.

    Parameters are those of `pixel_masks`; `trace` defaults to a new `Recorder`.

    Returns
    -------
    MaskResult
        Equal to `pixel_masks` with ``trace=None``, plus the trace.

    Examples
    --------
    The corner of Fig. 6.10: edges 0 and 1 meet inside pixel (1, 0); edge 2,
    at x = 0, carries winding 1 into the sub-rows they do not close in pixel 0.

    >>> result = mask_buffer_rows([(0, 0), (1.75, 0.5), (0, 1)], 2, 1, mask="4x4")
    >>> corner = result.trace.of_kind("mask_buffer_row")[0].pixels[1]
    >>> corner.x, corner.carry, [(e.edge, e.winding) for e in corner.edges]
    (1, (0, 1, 1, 0), [(0, -1), (1, -1)])
    >>> mask_to_grid(corner.mask, "4x4")[::-1].astype(int)  # top row first
    array([[0, 0, 0, 0],
           [1, 0, 0, 0],
           [1, 0, 0, 0],
           [0, 0, 0, 0]])
    """
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    cols, rows = _layout(mask)
    check_choice("rule", rule, RULES)
    bits = check_subpixel_bits(subpixel_bits)
    tracer = as_tracer(trace)
    scaled = subsample_polygon(polygon, mask, bits)
    table = bucketed_edge_table(scaled, height * rows)
    ys: list[int] = []
    xs: list[int] = []
    masks: list[int] = []
    sub_rows = scan_rows(scaled, table, width * cols, height * rows, rule=rule)  # the ET/AET walk
    for y, row_sub_rows in itertools.groupby(sub_rows, key=lambda sub_row: sub_row.y // rows):
        crossings = [  # (a) the active edges' crossings of the row's sub-rows, from their AETs
            (table.edges[item.edge], sub_row.y - y * rows, item.x)
            for sub_row in row_sub_rows
            for item in sub_row.aet
        ]
        if not crossings:
            continue  # edges only retired here
        buffer = _mask_buffer(crossings, (cols, rows), width, rule == "evenodd")  # (b)
        for x, pixel_mask in _row_masks(*buffer[:2]):
            ys.append(y)
            xs.append(x)
            masks.append(pixel_mask)
        if tracer is not None:
            active = tuple(sorted({edge.edge for edge, _, _ in crossings}))
            _emit_row(tracer, polygon_index, y, mask, active, *buffer)
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return MaskResult(
        np.array(ys, dtype=np.int64),
        np.array(xs, dtype=np.int64),
        np.array(masks, dtype=np.uint64),
        mask,
        recorded,
    )


def _edge_masks(crossings, layout, width):
    """Every active edge scanned into the buffer of a row, before combining.

    `crossings` are (edge, sub-row j, x) in the scaled frame; an edge's
    sub-samples at or right of x, from column ceil(x), are its edge mask (a
    sub-sample exactly on the edge is right of it). Returns (crossed,
    carry_steps): crossed[x][edge] = [winding, (rows, cols) grid of the edge's
    bits, exact crossing x per sub-row or None] for each pixel x the edge
    crosses, and (first_column, sub_row, winding) per crossing, from which the
    winding carried into any pixel follows.
    """
    cols, rows = layout
    crossed: dict[int, dict[int, list]] = {}
    carry_steps = []
    for edge, j, x_crossing in crossings:
        column = math.ceil(x_crossing)
        carry_steps.append((column, j, edge.winding))
        if not 0 <= column < width * cols:
            continue  # left of the raster it only adds to the carry; right of it, nothing
        x, i = divmod(column, cols)
        entry = crossed.setdefault(x, {}).setdefault(
            edge.edge, [edge.winding, np.zeros((rows, cols), bool), [None] * rows]
        )
        entry[1][j, i:] = True
        entry[2][j] = (x_crossing + Fraction(1, 2)) / cols  # back to pixels
    return crossed, carry_steps


def _carry(carry_steps, column: int, rows: int) -> np.ndarray:
    """(rows,) winding entering sub-sample `column` from the left, per sub-row."""
    carry = np.zeros(rows, np.int64)
    for first, j, winding in carry_steps:
        if first < column:
            carry[j] += winding
    return carry


def _inside(winding: np.ndarray, evenodd: bool) -> np.ndarray:
    return winding % 2 == 1 if evenodd else winding != 0


def _run_mask(carry, cols, evenodd) -> int:
    """The mask of a pixel no edge crosses: whole sub-rows, by their carry."""
    return _grid_to_mask(np.repeat(_inside(carry, evenodd)[:, None], cols, axis=1))


def _mask_buffer(crossings, layout, width, evenodd):
    """The mask buffer of a row from its crossings (`_edge_masks`): (pixels, runs, crossed).

    `pixels` are the `MaskBufferPixel` of the crossed pixels (each bit: its
    sub-row's carry plus the windings of the edge masks holding it, under the
    fill rule), `runs` the `MaskRun` of uncrossed pixels with a nonzero mask,
    `crossed` as `_edge_masks` returns it.
    """
    cols, rows = layout
    crossed, carry_steps = _edge_masks(crossings, layout, width)
    pixels, runs, x_start = [], [], 0
    for x in [*sorted(crossed), width]:
        run_mask = _run_mask(_carry(carry_steps, x_start * cols, rows), cols, evenodd)
        if run_mask and x_start < x:
            runs.append(MaskRun(x_start, x, run_mask))
        if x < width:
            carry = _carry(carry_steps, x * cols, rows)
            entries = sorted(crossed[x].items())
            winding = carry[:, None] + sum(w * grid for _, (w, grid, _) in entries)
            edge_masks = tuple(EdgeMaskEntry(e, w, _grid_to_mask(g)) for e, (w, g, _) in entries)
            pixel_mask = _grid_to_mask(_inside(winding, evenodd))
            pixels.append(MaskBufferPixel(x, tuple(carry.tolist()), edge_masks, pixel_mask))
        x_start = x + 1
    return pixels, runs, crossed


def _row_masks(pixels, runs) -> list[tuple[int, int]]:
    """(x, mask) of every pixel of the row with a nonzero mask, by x."""
    masks = [(p.x, p.mask) for p in pixels if p.mask]
    masks.extend((x, run.mask) for run in runs for x in range(run.x_start, run.x_end))
    return sorted(masks)


def _emit_row(tracer: Tracer, polygon: int, y: int, mask: str, active, pixels, runs, crossed):
    """The row's `edge_mask` events and its `mask_buffer_row` (`active`: the sorted edge ids)."""
    if tracer.wants("edge_mask", polygon=polygon, y=y):
        for pixel in pixels:
            for e in pixel.edges:
                crossings = tuple(crossed[pixel.x][e.edge][2])
                tracer.emit(EdgeMask(polygon, y, pixel.x, e.edge, e.winding, crossings, e.mask))
    if tracer.wants("mask_buffer_row", polygon=polygon, y=y):
        tracer.emit(MaskBufferRow(polygon, y, mask, active, tuple(pixels), tuple(runs)))

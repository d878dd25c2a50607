"""The common output of the visibility algorithms: paint pieces in an order, or fill decided ids.

Each algorithm decides *what* is visible; painting here turns its decision
into the z-buffer's buffers (depth, polygon id and interpolated values per
sample), drawing every polygon with the z-buffer's own scan conversion and
interpolation, so where an algorithm picks the polygon the z-buffer picks,
the pixel is the same to the bit. Three modes:

- ``"over"``: pieces back to front, each overwriting what is there (painter's
  algorithm, depth sort, BSP back to front);
- ``"under"``: pieces front to back, each writing only samples still empty
  (BSP front to back with a coverage mask);
- ``"target"``: every drawn polygon writes only where the algorithm decided it
  is visible (the image-space algorithms: scanline, Warnock).

Traced, each sample emits `pixel_painted`; untraced, the compiled kernel
(`scanviz.visibility.zbuffer_compiled.paint_pieces`) gives the same buffers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import steps
from ..raster.api import as_tracer
from ..raster.fixed import SnappedPolygon
from ..raster.interpolate import interpolate_rows, polygon_plane, span_samples
from ..trace.events import PixelPainted
from . import cut_side, zbuffer_compiled
from .screen_polygons import Piece, Surfaces
from .zbuffer import ZBufferStats, _attributes

MODES = ("over", "under", "target")
_KERNEL_MODE = {
    "over": zbuffer_compiled.OVER,
    "under": zbuffer_compiled.UNDER,
    "target": zbuffer_compiled.TARGET,
}


@dataclass(frozen=True)
class Painted:
    """The buffers after painting: as `ZBufferResult` without the trace."""

    depth: np.ndarray
    polygon: np.ndarray
    values: np.ndarray
    stats: ZBufferStats


def paint(
    surfaces: Surfaces,
    pieces: list[Piece],
    mode: str,
    *,
    target: np.ndarray | None = None,
    trace=None,
) -> Painted:
    """Paint `pieces` in order with `mode` (see the module); `target` (H, W) ids for "target"."""
    if mode not in MODES:
        raise ValueError(f"'mode' must be one of {MODES}; got {mode!r}")
    if (mode == "target") != (target is not None):
        raise ValueError("'target' is needed for mode 'target', and only there")
    trace = as_tracer(trace)
    compiled = trace is None and surfaces.units.dtype == np.int64 and not steps.replaced()
    if compiled:
        return _paint_compiled(surfaces, pieces, mode, target)
    return _paint_reference(surfaces, pieces, mode, target, trace)


def samples(surfaces: Surfaces, piece: Piece) -> np.ndarray:
    """(H, W) bool: the samples `piece` covers, painted alone (a whole polygon's, or its cut part)."""
    return paint(surfaces, [piece], "over").polygon >= 0


def fill(surfaces: Surfaces, target: np.ndarray, *, trace=None) -> Painted:
    """Draw every drawn polygon where `target` says it is visible (mode "target")."""
    return paint(surfaces, surfaces.pieces(), "target", target=target, trace=trace)


def _paint_compiled(surfaces, pieces, mode, target) -> Painted:
    cut_rows = [surfaces.cut_rows(piece) for piece in pieces]
    starts = np.concatenate([[0], np.cumsum([len(r) for r in cut_rows])]).astype(np.int64)
    rows = np.concatenate([np.zeros((0, 11)), *cut_rows])
    polygons = surfaces.polygons
    depth, ids, values, counts = zbuffer_compiled.paint_pieces(
        surfaces.units, surfaces.units / surfaces.scale, polygons.z, surfaces.channels,
        polygons.offsets, surfaces.scale, surfaces.width, surfaces.height, polygons.value_count,
        np.array([piece.polygon for piece in pieces], np.int64), starts, rows,
        np.array([piece.rows() for piece in pieces], np.int64).reshape(-1, 2), _KERNEL_MODE[mode], np.zeros((1, 1), np.int64) if target is None else target,
    )  # fmt: skip
    return Painted(depth, ids, values, ZBufferStats.from_counts(counts, len(pieces), "compiled"))


def _paint_reference(surfaces, pieces, mode, target, trace) -> Painted:
    """The traced painter: `zbuffer_reference` with the mode's test in place of the depth test."""
    width, height, polygons = surfaces.width, surfaces.height, surfaces.polygons
    depth = np.full((height, width), np.inf)
    ids = np.full((height, width), -1, np.int64)
    values = np.zeros((height, width, polygons.value_count))
    counts = np.zeros(zbuffer_compiled.STAT_FIELDS, np.int64)
    for piece in pieces:
        p = piece.polygon
        first, stop = polygons.offsets[p], polygons.offsets[p + 1]
        snapped = SnappedPolygon(
            surfaces.units[first:stop], np.array([0, stop - first]), surfaces.bits, surfaces.sample
        )
        plane = polygon_plane(snapped, polygons.z[first:stop])
        if not surfaces.drawn[p]:
            counts[zbuffer_compiled.SKIPPED] += 1
            continue
        fragments = counts[zbuffer_compiled.FRAGMENTS]
        cuts = surfaces.cut_rows(piece)  # built once per piece, not per sample
        y_low, y_high = piece.rows()
        for y, spans in interpolate_rows(
            snapped, plane, surfaces.channels[first:stop], width, height
        ):
            if y >= y_high:
                break
            if y < y_low:
                continue
            counts[zbuffer_compiled.ROWS] += 1
            counts[zbuffer_compiled.SPANS] += len(spans)
            traced = trace is not None and trace.wants("pixel_painted", polygon=p, y=y)
            for span in spans:
                for x, z, channel_values in span_samples(span):
                    previous = int(ids[y, x])
                    if mode == "over":
                        write = True
                    elif mode == "under":
                        write = previous < 0
                    else:
                        write = int(target[y, x]) == p
                    write = write and (not piece.cuts or bool(cut_side.keeps(cuts, x, y)))
                    if traced:
                        trace.emit(PixelPainted(p, piece.label, x, y, float(z), previous, write))
                    if write:
                        depth[y, x], ids[y, x] = z, p
                        values[y, x] = _attributes(channel_values, surfaces.perspective)
                    counts[zbuffer_compiled.FRAGMENTS] += 1
                    counts[zbuffer_compiled.PASSED if write else zbuffer_compiled.FAILED] += 1
        counts[zbuffer_compiled.DRAWN] += counts[zbuffer_compiled.FRAGMENTS] > fragments
    return Painted(
        depth, ids, values, ZBufferStats.from_counts(counts, len(pieces), "traced reference")
    )

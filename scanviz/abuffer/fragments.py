"""From screen polygons to a-buffer fragments: one per polygon per pixel it touches.

A fragment carries what the a-buffer needs (thesis Fig. 6.6): the pixel mask
(`masks.pixel_masks`, the exact rule per sub-sample), the exact area of
polygon ∩ pixel (`area.pixel_areas`), the depth range zmin..zmax and the
attributes from which the pipeline shades its color.

Depths come from each polygon's plane (Newell's method through its snapped
vertices, as the z-buffer uses): zmin/zmax are the plane's extremes over the
pixel square, clamped to the polygon's own depth range (conservative for
partly covered pixels).

Attributes are taken where the fragment is, not at the pixel center (which
may lie outside the polygon, where the planes extrapolate): at the centroid
of the covered sub-samples (GPU "centroid sampling"), or, for a fragment
whose mask is empty (a sliver between sub-samples), at the mean of the
midpoints of the polygon's edges clipped to the pixel. At that point they
are interpolated as the z-buffer interpolates them: along the two edges
crossing its row nearest to it on either side, then across the span between
them (value/w and 1/w when perspective-correct). Every step is a convex
combination, so each attribute stays within its vertices' range; the result
is clamped to that range only to undo rounding (docs/abuffer.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry import Polygon
from ..raster.interpolate import depth_plane, vertex_channels
from .area import pixel_areas
from .masks import pixel_masks, subsample_positions

CHUNK_ENTRIES = 2**20  # fragments x edges handled at once: bounds the temporary arrays


@dataclass(frozen=True)
class PolygonFragments:
    """The fragments of one polygon, sorted by y then x."""

    ys: np.ndarray  # (F,) int64
    xs: np.ndarray  # (F,) int64
    masks: np.ndarray  # (F,) uint64
    areas: np.ndarray  # (F,) float64
    zmin: np.ndarray  # (F,) float64
    zmax: np.ndarray  # (F,) float64
    values: np.ndarray  # (F, K) float64 attributes where each fragment is (see the module doc)


def _plane_at(xs, ys, channel, px, py):
    """The plane through (xs, ys, channel) evaluated at points (px, py)."""
    _, _, c, dzdx, dzdy, first = depth_plane(xs, ys, channel)
    if c == 0.0:
        return np.full(len(px), channel[0])
    return first + dzdx * (px - xs[0]) + dzdy * (py - ys[0])


def _covered_centroids(xs, ys, masks, layout):
    """(F, 2) centroid of each fragment's covered sub-samples (NaN where the mask is empty)."""
    offsets = subsample_positions(layout)
    bits = (masks[:, None] >> np.arange(len(offsets), dtype=np.uint64)) & np.uint64(1)
    bits = bits.astype(np.float64)
    count = bits.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        centre = (bits @ offsets) / count[:, None]
    return centre + np.column_stack([xs, ys])


def _sliver_points(sx, sy, xs, ys):
    """(F, 2) mean midpoint of the polygon's edges clipped to each pixel (Liang-Barsky).

    A point of (polygon ∩ pixel)'s closure for a convex polygon; the pixel
    center if no edge meets the pixel.
    """
    x0, y0 = sx[None, :], sy[None, :]
    dx, dy = np.roll(sx, -1)[None, :] - x0, np.roll(sy, -1)[None, :] - y0
    low, high = np.zeros((len(xs), len(sx))), np.ones((len(xs), len(sx)))
    for start, delta, lo, hi in ((x0, dx, xs, xs + 1), (y0, dy, ys, ys + 1)):
        lo, hi = lo[:, None], hi[:, None]
        moving = delta != 0
        safe = np.where(moving, delta, 1.0)
        t_lo, t_hi = (lo - start) / safe, (hi - start) / safe
        enter, leave = np.minimum(t_lo, t_hi), np.maximum(t_lo, t_hi)
        low = np.where(moving, np.maximum(low, enter), low)
        high = np.where(moving, np.minimum(high, leave), high)
        outside = ~moving & ((start < lo) | (start > hi))  # parallel to the slab, outside it
        high = np.where(outside, -1.0, high)
    meets = low <= high
    middle = (low + high) / 2
    count = meets.sum(axis=1)
    px = np.where(meets, x0 + middle * dx, 0.0).sum(axis=1)
    py = np.where(meets, y0 + middle * dy, 0.0).sum(axis=1)
    found = count > 0
    safe_count = np.where(found, count, 1)
    return np.column_stack(
        [np.where(found, px / safe_count, xs + 0.5), np.where(found, py / safe_count, ys + 0.5)]
    )


def _scanline_values(sx, sy, channels, px, py):
    """Channels at points (px, py) interpolated along edges and the span, as the z-buffer does.

    On the row y = py, each edge spanning it is crossed at x_c with the edge's
    value there; the point takes the nearest crossings left and right of it
    and interpolates between them (one crossing only: its value). Every weight
    is clamped to [0, 1], so the result is a convex combination of the
    vertices' channels wherever the point is.
    """
    x0, y0 = sx[None, :], sy[None, :]
    nxt = np.roll(np.arange(len(sx)), -1)
    dx, dy = sx[nxt][None, :] - x0, sy[nxt][None, :] - y0
    py = np.clip(py, sy.min(), sy.max())[:, None]  # a row the polygon spans
    spans = (dy != 0) & (np.minimum(y0, y0 + dy) <= py) & (py <= np.maximum(y0, y0 + dy))
    t = np.clip((py - y0) / np.where(dy != 0, dy, 1.0), 0.0, 1.0)
    crossing = x0 + t * dx
    px = px[:, None]
    left_x = np.where(spans & (crossing <= px), crossing, -np.inf)
    right_x = np.where(spans & (crossing >= px), crossing, np.inf)
    left, right = left_x.argmax(axis=1), right_x.argmin(axis=1)
    rows = np.arange(len(px))
    has_left, has_right = np.isfinite(left_x[rows, left]), np.isfinite(right_x[rows, right])
    if not (has_left | has_right).all():  # no edge spans the row (all horizontal): vertex 0
        t = np.where(spans.any(axis=1, keepdims=True), t, 0.0)
    left = np.where(has_left, left, right)
    right = np.where(has_right, right, left)

    def along(edge):
        weight = t[rows, edge][:, None]
        return channels[edge] + weight * (channels[nxt[edge]] - channels[edge])

    x_left, x_right = crossing[rows, left], crossing[rows, right]
    gap = x_right - x_left
    s = np.clip((px[:, 0] - x_left) / np.where(gap > 0, gap, 1.0), 0.0, 1.0)
    s = np.where(gap > 0, s, 0.0)[:, None]
    v_left = along(left)
    return v_left + s * (along(right) - v_left)


def fragment_values(sx, sy, values, inv_w, points, perspective):
    """(F, K) attributes at `points` (F, 2), within the vertices' range of each attribute.

    `sx`, `sy` are the snapped vertices; chunks keep temporaries within
    `CHUNK_ENTRIES` fragments x edges.
    """
    channels = vertex_channels(values, inv_w, perspective)
    chunk = max(1, CHUNK_ENTRIES // len(sx))
    parts = [
        _scanline_values(sx, sy, channels, points[k : k + chunk, 0], points[k : k + chunk, 1])
        for k in range(0, len(points), chunk)
    ]
    result = np.concatenate(parts) if parts else np.zeros((0, channels.shape[1]))
    if perspective:  # 1/w interpolated is a convex combination of positive values: > 0
        result = result[:, :-1] / result[:, -1:]
    return np.clip(result, values.min(axis=0), values.max(axis=0))  # rounding only


def fragment_points(sx, sy, xs, ys, masks, layout):
    """(F, 2) where each fragment is shaded: its covered sub-samples' centroid, else a sliver point."""
    points = _covered_centroids(xs, ys, masks, layout)
    empty = np.flatnonzero(masks == 0)
    chunk = max(1, CHUNK_ENTRIES // len(sx))
    for k in range(0, len(empty), chunk):
        rows = empty[k : k + chunk]
        points[rows] = _sliver_points(sx, sy, xs[rows], ys[rows])
    return points


def polygon_fragments(
    xy: np.ndarray,
    z: np.ndarray,
    inv_w: np.ndarray,
    values: np.ndarray,
    width: int,
    height: int,
    *,
    mask: str = "8x8",
    subpixel_bits: int | None = 8,
    perspective: bool = True,
    trace=None,
    polygon_index: int = 0,
) -> PolygonFragments | None:
    """Fragments of the polygon with vertices `xy` (display pixels), or None if it touches no pixel."""
    try:
        polygon = Polygon(xy)
    except ValueError:  # fewer than 3 distinct vertices: no area, no samples
        return None
    traced = trace is not None and trace.wants("mask_buffer_row", polygon=polygon_index)
    masks = pixel_masks(
        polygon,
        width,
        height,
        mask=mask,
        subpixel_bits=subpixel_bits,
        trace=trace if traced else None,
        polygon_index=polygon_index,
    )
    area_ys, area_xs, areas = pixel_areas(polygon, width, height, subpixel_bits=subpixel_bits)
    mask_keys = masks.ys * width + masks.xs
    area_keys = area_ys * width + area_xs
    keys = np.union1d(mask_keys, area_keys)
    if not len(keys):
        return None
    ys, xs = keys // width, keys % width
    fragment_masks = np.zeros(len(keys), np.uint64)
    fragment_masks[np.searchsorted(keys, mask_keys)] = masks.masks
    fragment_areas = np.zeros(len(keys))
    fragment_areas[np.searchsorted(keys, area_keys)] = areas
    grid = xy if subpixel_bits is None else np.rint(xy * 2.0**subpixel_bits) / 2.0**subpixel_bits
    sx, sy = grid[:, 0].tolist(), grid[:, 1].tolist()
    corners = [_plane_at(sx, sy, z.tolist(), xs + dx, ys + dy) for dx in (0, 1) for dy in (0, 1)]
    zmin = np.clip(np.min(corners, axis=0), z.min(), z.max())
    zmax = np.clip(np.max(corners, axis=0), z.min(), z.max())
    points = fragment_points(grid[:, 0], grid[:, 1], xs, ys, fragment_masks, mask)
    at_points = fragment_values(grid[:, 0], grid[:, 1], values, inv_w, points, perspective)
    return PolygonFragments(ys, xs, fragment_masks, fragment_areas, zmin, zmax, at_points)

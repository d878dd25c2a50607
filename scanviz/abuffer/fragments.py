"""From screen polygons to a-buffer fragments: one per polygon per pixel it touches.

A fragment carries what the a-buffer needs (thesis Fig. 6.6): the pixel mask
(`masks.pixel_masks`, the exact rule per sub-sample), the exact area of
polygon ∩ pixel (`area.pixel_areas`), the depth range zmin..zmax and the
attributes at the pixel center, from which the pipeline shades its color.

Depths and attributes come from each polygon's planes (Newell's method through
its snapped vertices, as the z-buffer uses): zmin/zmax are the plane's extremes
over the pixel square, clamped to the polygon's own depth range (conservative
for partly covered pixels); attributes are the planes evaluated at the pixel
center (x + 0.5, y + 0.5), divided by the 1/w plane when perspective-correct.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..geometry import Polygon
from ..raster.interpolate import depth_plane, vertex_channels
from .area import pixel_areas
from .masks import pixel_masks


@dataclass(frozen=True)
class PolygonFragments:
    """The fragments of one polygon, sorted by y then x."""

    ys: np.ndarray  # (F,) int64
    xs: np.ndarray  # (F,) int64
    masks: np.ndarray  # (F,) uint64
    areas: np.ndarray  # (F,) float64
    zmin: np.ndarray  # (F,) float64
    zmax: np.ndarray  # (F,) float64
    values: np.ndarray  # (F, K) float64 attributes at the pixel centers


def _plane_at(xs, ys, channel, px, py):
    """The plane through (xs, ys, channel) evaluated at points (px, py)."""
    _, _, c, dzdx, dzdy, first = depth_plane(xs, ys, channel)
    if c == 0.0:
        return np.full(len(px), channel[0])
    return first + dzdx * (px - xs[0]) + dzdy * (py - ys[0])


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
    channels = vertex_channels(values, inv_w, perspective)
    at_centers = np.column_stack(
        [
            _plane_at(sx, sy, channels[:, k].tolist(), xs + 0.5, ys + 0.5)
            for k in range(channels.shape[1])
        ]
    ).reshape(len(keys), channels.shape[1])
    if perspective:
        one_over_w = at_centers[:, -1:]
        at_centers = np.where(
            one_over_w > 0, at_centers[:, :-1] / np.where(one_over_w > 0, one_over_w, 1), 0.0
        )
    return PolygonFragments(ys, xs, fragment_masks, fragment_areas, zmin, zmax, at_centers)

"""The anti-aliased path of `render`: every polygon's fragments, resolved by the a-buffer."""

from __future__ import annotations

import numpy as np

from ..limits import check_memory
from ..progress import progress
from .shade import _shade_pixels

PROGRESS_POLYGONS = 2000  # a-buffer renders of more polygons show a progress bar

FRAGMENT_BYTES = 8 * 3 * 12  # per a-buffer fragment, held about three times (parts, table, resolve)

SHADING_BYTES = 8 * 64  # per fragment shaded by Phong/Gooch: vectors of every light term


def _antialiased(
    scene,
    prepared,
    width,
    height,
    shading,
    visibility,
    mask,
    weights,
    *,
    subpixel_bits,
    perspective,
    tracer,
):
    """(image, depth, polygon, a-buffer result): fragments per pixel, resolved by the a-buffer.

    Every fragment is shaded where it is, at the centroid of its covered
    sub-samples (the a-buffer needs every fragment's color before it knows
    which are seen). `depth` and `polygon` are those of each pixel's nearest
    fragment.
    """
    from ..abuffer import MASK_LAYOUTS, Fragments, resolve

    polygons, stats = prepared.polygons, prepared.stats
    parts, owners = _polygon_fragments(
        polygons, width, height, mask, subpixel_bits, perspective, tracer, visibility
    )
    owner = np.concatenate(owners) if owners else np.zeros(0, np.int64)
    values = (
        np.concatenate([f.values for f in parts])
        if parts
        else np.zeros((0, polygons.values.shape[1]))
    )
    if shading == "flat":
        colors = prepared.flat_colors[owner]
    elif shading == "gouraud":
        colors = values
    else:
        colors = _shade_pixels(scene, shading, values)
        stats.shaded_pixels = len(owner)

    def joined(field, dtype):
        return (
            np.concatenate([getattr(f, field) for f in parts]).astype(dtype)
            if parts
            else np.zeros(0, dtype)
        )

    fragments = Fragments(
        x=joined("xs", np.int64),
        y=joined("ys", np.int64),
        polygon=owner.astype(np.int64),
        object=prepared.polygon_object[owner],
        mask=joined("masks", np.uint64),
        area=joined("areas", np.float64),
        zmin=joined("zmin", np.float64),
        zmax=joined("zmax", np.float64),
        color=np.asarray(colors, dtype=np.float64).reshape(-1, 3),
        opacity=prepared.polygon_opacity[owner],
    )
    result = resolve(
        fragments,
        width,
        height,
        layout=MASK_LAYOUTS[mask],
        weights=weights,
        background=scene.background,
        mode="abuffer" if visibility == "abuffer" else "flawed",
        trace=tracer,
    )
    stats.fragments, stats.path = len(owner), result.stats.path
    depth = np.full((height, width), np.inf)
    nearest = np.full((height, width), -1, np.int64)
    order = np.lexsort((-fragments.zmin, fragments.x, fragments.y))  # per pixel, nearest last
    depth[fragments.y[order], fragments.x[order]] = fragments.zmin[order]
    nearest[fragments.y[order], fragments.x[order]] = owner[order]
    return result.image, depth, nearest, result


def _polygon_fragments(polygons, width, height, mask, subpixel_bits, perspective, tracer, mode):
    """Every polygon's fragments, in drawing order, with a progress bar for large scenes.

    Storage grows polygon by polygon and is checked against the memory limit
    as it grows; Ctrl-C stops between polygons (KeyboardInterrupt, nothing returned).
    """
    from ..abuffer.fragments import polygon_fragments

    parts, owners, stored = [], [], 0
    per_fragment = FRAGMENT_BYTES + 8 * polygons.value_count + SHADING_BYTES
    what = f"the fragments of a {width}x{height} {mode} render"
    with progress(polygons.count, f"{mode} polygons", threshold=PROGRESS_POLYGONS) as bar:
        for p in range(polygons.count):
            rows = slice(polygons.offsets[p], polygons.offsets[p + 1])
            found = polygon_fragments(
                polygons.xy[rows],
                polygons.z[rows],
                polygons.inv_w[rows],
                polygons.values[rows],
                width,
                height,
                mask=mask,
                subpixel_bits=subpixel_bits,
                perspective=perspective,
                trace=tracer,
                polygon_index=p,
            )
            bar.update(1)
            if found is None:
                continue
            stored += len(found.xs)
            check_memory(stored * per_fragment, f"{what} ({stored} fragments by polygon {p})")
            parts.append(found)
            owners.append(np.full(len(found.xs), p))
    return parts, owners

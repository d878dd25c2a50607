"""The anti-aliased path of `render`: every polygon's fragments, resolved by the a-buffer."""

from __future__ import annotations

import numpy as np

from .. import steps
from ..limits import check_memory
from ..progress import progress
from .shade import _shade_pixels

PROGRESS_POLYGONS = 2000  # a-buffer renders of more polygons show a progress bar

FRAGMENT_BYTES = 8 * 3 * 12  # per a-buffer fragment, held about three times (parts, table, resolve)

SHADING_BYTES = 8 * 64  # per fragment shaded by Phong/Gooch: vectors of every light term

SHADE_FRAGMENTS = 2**17  # fragments shaded at once: the light terms' vectors stay this long


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
    merge="none",
    subpixel_bits,
    perspective,
    tracer,
):
    """(image, depth, polygon, a-buffer result): fragments per pixel, resolved by the a-buffer.

    Every fragment is shaded where it is, at the centroid of its covered
    sub-samples (the a-buffer needs every fragment's color before it knows
    which are seen). `depth` and `polygon` are those of each pixel's nearest
    fragment. `merge` is `resolve`'s (Carpenter's per-object merge, or none).
    """
    from ..abuffer import MASK_LAYOUTS, Fragments, resolve
    from ..abuffer.pixelstruct_compiled import nearest_fragments

    polygons, stats = prepared.polygons, prepared.stats
    found = _polygon_fragments(
        polygons, width, height, mask, subpixel_bits, perspective, tracer, visibility
    )
    owner = found.polygon
    if shading == "flat":
        colors = prepared.flat_colors[owner]
    elif shading == "gouraud":
        colors = found.values
    else:  # fragment by fragment arithmetic: slices shade as the whole would
        colors = np.empty((len(owner), 3))
        for start in range(0, len(owner), SHADE_FRAGMENTS):
            part = slice(start, start + SHADE_FRAGMENTS)
            colors[part] = _shade_pixels(scene, shading, found.values[part]).reshape(-1, 3)
        stats.shaded_pixels = len(owner)
    fragments = Fragments(
        x=found.x,
        y=found.y,
        polygon=owner,
        object=prepared.polygon_object[owner],
        mask=found.mask,
        area=found.area,
        zmin=found.zmin,
        zmax=found.zmax,
        color=np.asarray(colors, dtype=np.float64).reshape(-1, 3),
        opacity=prepared.polygon_opacity[owner],
    )
    del found, owner, colors  # `fragments` holds copies: the attributes go before resolving
    result = resolve(
        fragments,
        width,
        height,
        layout=MASK_LAYOUTS[mask],
        weights=weights,
        background=scene.background,
        mode="abuffer" if visibility == "abuffer" else "flawed",
        merge=merge,
        trace=tracer,
    )
    stats.fragments, stats.path = fragments.count, result.stats.path
    depth, nearest = nearest_fragments(
        fragments.y * width + fragments.x, fragments.zmin, fragments.polygon, width * height
    )
    return result.image, depth.reshape(height, width), nearest.reshape(height, width), result


def _polygon_fragments(polygons, width, height, mask, subpixel_bits, perspective, tracer, mode):
    """Every polygon's fragments (`FlatFragments`), in drawing order, with a progress bar.

    Untraced, `fragment_kernels.fragment_chunks` makes them compiled, a chunk
    of polygons per call; with a tracer, or while a step of `scanviz.steps` is
    replaced, `polygon_fragments` makes them polygon by polygon (the masks
    traced). Both give the same fragments. Storage is checked against the
    memory limit as it grows; Ctrl-C stops between chunks or polygons
    (KeyboardInterrupt, nothing returned).
    """
    from ..abuffer.fragments_compiled import FlatFragments, fragment_chunks

    parts, stored = [], 0
    per_fragment = FRAGMENT_BYTES + 8 * polygons.value_count + SHADING_BYTES
    what = f"the fragments of a {width}x{height} {mode} render"
    options = {"mask": mask, "subpixel_bits": subpixel_bits, "perspective": perspective}
    if tracer is None and not steps.replaced():
        chunks = fragment_chunks(polygons, width, height, what=what, **options)
    else:
        chunks = _traced_fragments(polygons, width, height, tracer, options)
    with progress(polygons.count, f"{mode} polygons", threshold=PROGRESS_POLYGONS) as bar:
        for done, found in chunks:
            bar.update(done)
            if not found.count:
                continue
            stored += found.count
            last = int(found.polygon[-1])
            check_memory(stored * per_fragment, f"{what} ({stored} fragments by polygon {last})")
            parts.append(found)
    return FlatFragments.join(parts, polygons.value_count)


def _traced_fragments(polygons, width, height, tracer, options):
    """Yield (1, FlatFragments) polygon by polygon from the reference `polygon_fragments`."""
    from ..abuffer.fragments import polygon_fragments
    from ..abuffer.fragments_compiled import FlatFragments

    for p in range(polygons.count):
        rows = slice(polygons.offsets[p], polygons.offsets[p + 1])
        found = polygon_fragments(
            polygons.xy[rows],
            polygons.z[rows],
            polygons.inv_w[rows],
            polygons.values[rows],
            width,
            height,
            trace=tracer,
            polygon_index=p,
            **options,
        )
        yield (
            1,
            (
                FlatFragments.join([], polygons.value_count)
                if found is None
                else FlatFragments.of_polygon(found, p)
            ),
        )

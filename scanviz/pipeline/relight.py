"""Relighting: the image function again over what a render keeps per pixel (`RenderResult.relight`).

The opaque renders with per-pixel shading (Phong, Gooch) keep, per visible
pixel, the interpolated normal, world position and material their image
function reads; a relight runs only that function, under new lights,
ambient light and materials, and equals a fresh `render` of the changed scene
bit for bit. docs/relight.md lists what can and cannot be relit, and why.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np

from ..conventions import check_choice
from ..limits import check_memory
from ..scene.model import Material, Scene
from .prepare import ATTRIBUTES
from .render import (
    ANTIALIASED,
    FIXED_BEFORE_VISIBILITY,
    RELIGHTABLE,
    SHADING_BYTES,
    SHADINGS,
    _plan,
    _transparent,
)
from .result import PixelRecord, RenderResult
from .shade import _image_function


def _relight(result, lights, materials, shading, ambient) -> RenderResult:
    """`RenderResult.relight`: the image function again over the kept record (docs/relight.md)."""
    record = result.record
    if record is None:
        raise ValueError("relight needs a RenderResult made by scanviz.render")
    shading = record.shading if shading is None else shading
    check_choice("shading", shading, SHADINGS)
    _check_relightable(record, shading)
    scene = _relit_scene(record.scene, lights, ambient)
    chosen = {**record.materials, **_material_overrides(materials, len(scene.objects))}
    height, width = result.polygon.shape
    visible = int((result.polygon >= 0).sum())
    check_memory(
        visible * (8 * ATTRIBUTES[shading] + SHADING_BYTES) + width * height * 8 * 3,
        f"relighting a {width}x{height} render ({visible} visible pixels)",
    )
    image, _ = _image_function(
        scene, shading, result.polygon, result.visibility.values, record.polygon_object, chosen
    )
    if record.edges is not None:
        image[record.edges] = 0.0
    np.clip(image, 0.0, 1.0, out=image)
    stats = replace(result.stats)
    edges = record.edges is not None
    plan = _plan(
        _transparent(scene, chosen), stats, record.stages, shading, record.visibility, edges, None
    )
    relit = replace(record, scene=scene, shading=shading, materials=chosen)
    return RenderResult(
        image, result.depth, result.polygon, stats, plan, None, None, None, result.visibility, relit
    )


def _check_relightable(record: PixelRecord, shading: str) -> None:
    """Refuse, naming what to re-render, a relight whose colors the record cannot recompute."""
    again = "re-render with scanviz.render"
    if record.visibility in ANTIALIASED:
        raise ValueError(
            f"relight: a visibility={record.visibility!r} render packs every fragment's color "
            f"into its pixels, and its fragments are not kept; {again}"
        )
    if record.shading not in RELIGHTABLE:
        when = FIXED_BEFORE_VISIBILITY.get(record.shading, "while it scans")
        raise ValueError(
            f"relight: a shading={record.shading!r} render fixes its colors {when} and keeps no "
            f"per-pixel normals; {again}, or render with shading in {RELIGHTABLE} to relight"
        )
    if shading not in RELIGHTABLE:
        raise ValueError(
            f"relight: 'shading' must be one of {RELIGHTABLE} (shaded per pixel from the kept "
            f"normal, position and material); got {shading!r}: {again}"
        )


def _relit_scene(scene: Scene, lights, ambient) -> Scene:
    """The scene with new lights and ambient light, validated as any Scene is."""
    if lights is not None and not isinstance(lights, tuple | list):
        raise TypeError(
            f"'lights' must be a tuple of Light (one light: (light,)); got {type(lights).__name__}"
        )
    return replace(
        scene,
        lights=scene.lights if lights is None else tuple(lights),
        ambient=scene.ambient if ambient is None else ambient,
    )


def _material_overrides(materials, count: int) -> dict[int, Material]:
    """{object index: Material} from a mapping or a sequence with one entry (or None) per object."""
    if materials is None:
        return {}
    if isinstance(materials, Mapping):
        items = list(materials.items())
    elif isinstance(materials, Sequence) and not isinstance(materials, str):
        if len(materials) != count:
            raise ValueError(
                f"'materials' as a sequence needs one entry per scene object ({count}); "
                f"got {len(materials)}"
            )
        items = [(i, m) for i, m in enumerate(materials) if m is not None]
    else:
        raise TypeError(
            "'materials' must be a mapping {object index: Material} or a sequence of Material "
            f"or None per object; got {type(materials).__name__}"
        )
    for index, material in items:
        if (
            not isinstance(index, numbers.Integral)
            or isinstance(index, bool)
            or not 0 <= index < count
        ):
            raise ValueError(
                f"'materials' keys must be object indices 0..{count - 1}; got {index!r}"
            )
        if not isinstance(material, Material):
            raise TypeError(
                f"'materials[{index}]' must be a Material; got {type(material).__name__}"
            )
    return {int(index): material for index, material in items}

"""Shading the visible pixels: the image function (Phong, Gooch), the viewer, the headlight, the trace."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..scene.model import Material, Scene
from ..vectors import unit_vectors

MATERIAL = slice(6, 15)  # the material columns of a pixel's attributes (normal, position, material)


def _viewer(camera):
    """(eye, view_dir) for `illuminate`: the eye point, or the direction toward an orthographic viewer."""
    if camera.projection == "perspective":
        return np.array(camera.eye), None
    return None, unit_vectors(np.subtract(camera.eye, camera.look_at))


def _lit(scene, positions, normals, materials):
    from ..shading import illuminate

    eye, view_dir = _viewer(scene.camera)
    return illuminate(
        positions,
        normals,
        materials,
        eye=eye,
        view_dir=view_dir,
        lights=scene.lights,
        ambient_light=np.array(scene.ambient),
    )


def _shade_pixels(scene: Scene, shading: str, values: np.ndarray) -> np.ndarray:
    """Colors of visible pixels from their interpolated normal, position and material."""
    normals, positions, materials = values[:, 0:3], values[:, 3:6], values[:, 6:15]
    if shading == "phong":
        return _lit(scene, positions, normals, materials)
    from ..shading import gooch

    eye, view_dir = _viewer(scene.camera)
    # Gooch tones are defined for one light; without any, light from the viewer (a headlight).
    light = scene.lights[0] if scene.lights else _headlight(scene.camera)
    return gooch(positions, normals, materials, eye, light, view_dir=view_dir)


def _image_function(
    scene: Scene,
    shading: str,
    polygon: np.ndarray,
    values: np.ndarray,
    polygon_object: np.ndarray,
    materials: Mapping[int, Material],
) -> tuple[np.ndarray, int]:
    """(image, pixels shaded): the last stage (thesis ch. 7), each visible pixel's attributes to a color.

    `polygon` (H, W) and `values` (H, W, 15) are what visibility kept;
    `materials` gives objects (by index, through `polygon_object`) one
    material in place of the kept one. Row by row arithmetic (`illuminate`),
    so the colors do not depend on which other pixels are shaded.
    """
    visible = polygon >= 0
    attributes = values[visible]
    if materials:
        owner = polygon_object[polygon[visible]]
        for index, material in materials.items():
            attributes[owner == index, MATERIAL] = _material_row(material)
    image = np.empty((*polygon.shape, 3))
    image[...] = scene.background
    image[visible] = _shade_pixels(scene, shading, attributes)
    return image, len(attributes)


def _material_row(material: Material) -> np.ndarray:
    from ..shading import material_array

    return material_array([material])[0]


def _exact_materials(polygons, result) -> None:
    """Give the pixels of a polygon of one material that material's row, not its interpolation.

    Interpolating a constant with forward differences returns it only to
    rounding (1e-16 off, differently for each value); the exact row is what a
    relight with a new material reproduces bit for bit.
    """
    if not polygons.count:
        return
    starts = polygons.offsets[:-1]
    rows = polygons.values[:, MATERIAL]
    uniform = (np.minimum.reduceat(rows, starts) == np.maximum.reduceat(rows, starts)).all(axis=1)
    ys, xs = np.nonzero(result.polygon >= 0)
    ids = result.polygon[ys, xs]
    one = uniform[ids]
    result.values[ys[one], xs[one], MATERIAL] = rows[starts[ids[one]]]


def _headlight(camera):
    from ..scene.model import Light

    return Light(kind="directional", direction=tuple(np.subtract(camera.look_at, camera.eye)))


def _trace_illumination(scene: Scene, tracer, result) -> None:
    """Record the Phong terms of every visible pixel the tracer wants (same colors as drawn)."""
    from ..shading import illuminate_traced

    eye, view_dir = _viewer(scene.camera)
    for y, x in np.argwhere(result.polygon >= 0):
        polygon = int(result.polygon[y, x])
        if tracer.wants("illumination", polygon=polygon, y=int(y)):
            values = result.values[y, x]
            illuminate_traced(
                values[3:6],
                values[0:3],
                values[6:15],
                eye,
                scene.lights,
                np.array(scene.ambient),
                trace=tracer,
                pixel=(int(x), int(y)),
                view_dir=view_dir,
                polygon=polygon,
            )

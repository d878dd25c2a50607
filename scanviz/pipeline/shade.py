"""Shading the visible pixels: the image function (Phong, Gooch), the viewer, the headlight, the trace."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numba import njit, prange

from ..scene.model import Material, Scene
from ..threads import use_threads
from ..vectors import unit_vectors

PARALLEL_PIXELS = 2**16  # rasters of more pixels get their exact materials from numba's threads
MATERIAL_FIRST, MATERIAL_STOP = 6, 15
MATERIAL = slice(
    MATERIAL_FIRST, MATERIAL_STOP
)  # the material columns of a pixel's attributes (normal, position, material)


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
    if shading == "phong" and not materials:  # each visible pixel shaded where it is kept
        return _phong_image(scene, polygon, values), int((polygon >= 0).sum())
    visible = np.flatnonzero(polygon.ravel() >= 0)
    attributes = values.reshape(-1, values.shape[-1])[visible]
    if materials:
        owner = polygon_object[polygon.ravel()[visible]]
        for index, material in materials.items():
            attributes[owner == index, MATERIAL] = _material_row(material)
    image = np.empty((*polygon.shape, 3))
    image[...] = scene.background
    image.reshape(-1, 3)[visible] = _shade_pixels(scene, shading, attributes)
    return image, len(attributes)


def _phong_image(scene: Scene, polygon: np.ndarray, values: np.ndarray) -> np.ndarray:
    """`_image_function` for Phong without new materials: the compiled model over the buffers."""
    from ..shading.illumination import _light_arrays
    from ..shading.shade_compiled import shade_image

    eye, view_dir = _viewer(scene.camera)
    return shade_image(
        polygon, values, *_light_arrays(eye, view_dir, scene.lights),
        np.asarray(scene.ambient, np.float64), np.asarray(scene.background, np.float64),
    )  # fmt: skip


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
    _put_exact_materials(polygons.values, polygons.offsets, result.polygon, result.values)


def _put_exact_materials(vertex_values, offsets, polygon, values) -> None:
    """`_exact_materials` in two passes: which polygons have one material, then their pixels."""
    uniform = _uniform_materials(vertex_values, offsets)
    put = _put_rows_shared if use_threads(polygon.size, PARALLEL_PIXELS) else _put_rows_here
    put(vertex_values, offsets, uniform, polygon, values)


@njit(cache=True)
def _uniform_materials(vertex_values, offsets):  # pragma: no cover - compiled
    uniform = np.ones(offsets.shape[0] - 1, np.bool_)
    for p in range(offsets.shape[0] - 1):
        for v in range(offsets[p] + 1, offsets[p + 1]):
            for k in range(MATERIAL_FIRST, MATERIAL_STOP):
                if vertex_values[v, k] != vertex_values[offsets[p], k]:
                    uniform[p] = False
    return uniform


@njit(cache=True, parallel=True)
def _put_rows_shared(vertex_values, offsets, uniform, polygon, values):  # pragma: no cover
    for y in prange(polygon.shape[0]):
        _put_row(y, vertex_values, offsets, uniform, polygon, values)


@njit(cache=True)
def _put_rows_here(vertex_values, offsets, uniform, polygon, values):  # pragma: no cover
    for y in range(polygon.shape[0]):
        _put_row(y, vertex_values, offsets, uniform, polygon, values)


@njit(cache=True, inline="always")
def _put_row(y, vertex_values, offsets, uniform, polygon, values):  # pragma: no cover
    for x in range(polygon.shape[1]):
        p = polygon[y, x]
        if p >= 0 and uniform[p]:
            for k in range(MATERIAL_FIRST, MATERIAL_STOP):
                values[y, x, k] = vertex_values[offsets[p], k]


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

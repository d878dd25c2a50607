"""Shading the visible pixels: Phong and Gooch per pixel, the viewer, the headlight, and the trace."""

from __future__ import annotations

import numpy as np

from ..scene.model import Scene
from ..vectors import unit_vectors


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

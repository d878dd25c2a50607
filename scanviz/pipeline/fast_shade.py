"""`render(shading="fast_phong")`: Wang's fast Phong over each visible triangle (`scanviz.shading.fast_phong`).

After visibility, every drawn polygon is fanned into triangles (0, k, k + 1),
and each triangle is shaded by `fast_phong_triangle`: its normal plane in
screen space, the Taylor quadratics of cos θ and cos φ about the chosen
expansion point stepped by forward differences, the highlight from the
specular table. Its colours are written only at the samples where the
visibility algorithm shows that polygon, so visibility is exactly the other
modes'. The mapping from scanviz's `Material` and lights to the
dissertation's model (docs/shading-fast-phong.md, "In render"):

* levels: intensities are 8-bit levels, Ia = 255 x ambient light, Ip = 255 x
  the brightest channel of the light; colours come back divided by 255;
* ka = ambient x colour, kd = diffuse x colour x (light colour / its
  brightest channel), ks = specular, n = exponent, r + r0 = 1 (no
  attenuation: the dissertation's distance term is a constant);
* one light per call of the model, the lights' colours summed and clipped
  (ambient counted once), as `illuminate` sums them;
* L and V constant over a triangle: toward a directional light, toward a
  point light and toward the eye from the triangle's centroid (world space);
* two-sided: a triangle whose normals, summed, face away from the viewer has
  all three reversed;
* one material per polygon, its first vertex's.
"""

from __future__ import annotations

import numpy as np

from ..scene.model import Scene
from ..shading.fast_phong import ReflectionModel, fast_phong_triangle
from ..vectors import unit_vectors

EXPONENT_FLOOR = 1e-6  # the table needs n > 0; a material of exponent 0 has a flat highlight


def fast_phong_image(
    scene: Scene, polygons, result, width: int, height: int, sample, bits, expansion="vertex"
):
    """(image, shaded samples): the visible pixels of `result` shaded by fast Phong."""
    image = np.empty((height, width, 3))
    image[...] = scene.background
    if not (result.polygon >= 0).any():
        return image, 0
    ambient = np.asarray(scene.ambient, dtype=np.float64)
    models: dict = {}
    shaded = 0
    visible = np.unique(result.polygon[result.polygon >= 0])
    for p in visible.tolist():
        first, stop = int(polygons.offsets[p]), int(polygons.offsets[p + 1])
        xy, values = polygons.xy[first:stop], polygons.values[first:stop]
        normals, positions, material = values[:, 0:3], values[:, 3:6], values[0, 6:15]
        for k in range(1, stop - first - 1):
            corners = [0, k, k + 1]
            colours = _triangle(scene, ambient, models, xy[corners], normals[corners], positions[corners], material, width, height, sample, bits, expansion)  # fmt: skip
            if colours is None:
                continue
            ys, xs, rgb = colours
            mine = result.polygon[ys, xs] == p
            image[ys[mine], xs[mine]] = rgb[mine]
            shaded += int(mine.sum())
    return image, shaded


def _triangle(
    scene, ambient, models, xy, normals, positions, material, width, height, sample, bits, expansion
):
    """(ys, xs, colours in [0, 1]) of one screen triangle under every light, or None if it has no area."""
    area = (xy[1, 0] - xy[0, 0]) * (xy[2, 1] - xy[0, 1]) - (xy[2, 0] - xy[0, 0]) * (
        xy[1, 1] - xy[0, 1]
    )
    if area == 0:
        return None
    centroid = positions.mean(axis=0)
    camera = scene.camera
    if camera.projection == "perspective":
        to_viewer = unit_vectors(np.subtract(camera.eye, centroid))
    else:
        to_viewer = unit_vectors(np.subtract(camera.eye, camera.look_at))
    unit = unit_vectors(normals)
    # Two-sided per triangle: a triangle seen from behind gets all three normals reversed. (Per
    # vertex, a silhouette triangle would interpolate between normals turned opposite ways.)
    facing = -unit if unit.sum(axis=0) @ to_viewer < 0 else unit
    lights = scene.lights or ()
    total = None
    for index, light in enumerate(lights or (None,)):
        model = _model(models, material, light, ambient if index == 0 else np.zeros(3))
        to_light = _toward(light, centroid) if light is not None else to_viewer
        try:
            run = fast_phong_triangle(
                xy, facing, to_light, to_viewer, model, width=width, height=height,
                expansion=expansion, sample=sample, subpixel_bits=bits,
            )  # fmt: skip
        except ValueError:  # snapped to zero area, or a normal plane through zero: nothing to shade
            return None
        total = run.colors if total is None else total + run.colors
    return run.ys, run.xs, np.clip(total, 0.0, 255.0) / 255.0


def _toward(light, point) -> np.ndarray:
    if light.kind == "point":
        return unit_vectors(np.subtract(light.position, point))
    return unit_vectors(-np.asarray(light.direction, dtype=np.float64))


def _model(models: dict, material: np.ndarray, light, ambient: np.ndarray) -> ReflectionModel:
    """The dissertation's model for one material and one light (cached: the table is built once)."""
    key = (material.tobytes(), None if light is None else (light.color,), ambient.tobytes())
    if key not in models:
        colour, ka, kd, ks, exponent = (
            material[0:3],
            material[3],
            material[4],
            material[5],
            material[6],
        )
        light_colour = np.zeros(3) if light is None else np.asarray(light.color, dtype=np.float64)
        brightest = float(light_colour.max()) if light_colour.max() > 0 else 1.0
        models[key] = ReflectionModel(
            Ia=tuple((255.0 * ambient).tolist()),
            ka=tuple((ka * colour).tolist()),
            Ip=255.0 * brightest,
            kd=tuple((kd * colour * light_colour / brightest).tolist()),
            ks=float(ks) if light_colour.max() > 0 else 0.0,
            n=max(float(exponent), EXPONENT_FLOOR),
            r_plus_r0=1.0,
        )
    return models[key]

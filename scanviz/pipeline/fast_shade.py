"""`render(shading="fast_phong")`: Wang's fast Phong over each visible triangle (`scanviz.shading.fast_phong`).

After visibility, every drawn polygon is fanned into triangles (0, k, k + 1),
and each triangle is shaded as `fast_phong_triangle` shades it: its normal plane in
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
* tables stop at level 255 (``top_level=255``): each light's colour is clipped
  at 255 levels, so a higher level changes no pixel, and a bright light
  (colour 10^6, N = 2.55 x 10^8) costs 2 KiB of table instead of 2 GiB;
* one light per call of the model, the lights' colours summed and clipped
  (ambient counted once), as `illuminate` sums them;
* L and V constant over a triangle: toward a directional light, toward a
  point light and toward the eye from the triangle's centroid (world space);
  a point light exactly at a centroid is taken to shine from the viewer;
* two-sided: a triangle whose normals, summed, face away from the viewer has
  all three reversed;
* one material per polygon, its first vertex's.

All triangles go through one compiled pass (`fast_phong_triangles`); the
loop over `fast_phong_triangle` stays as its reference (``compiled=False``,
while a step of `scanviz.steps` is replaced, and the fallback for a vertex grid int64 cannot hold), and the two give the
same image bit for bit (tests/test_render_fast_phong.py).
"""

from __future__ import annotations

import numpy as np

from .. import steps
from ..raster.api import _snap_batch
from ..scene.model import Scene
from ..shading.fast_phong import ReflectionModel, fast_phong_triangle
from ..shading.fast_phong_compiled import fast_phong_triangles
from ..shading.taylor import LEVELS
from ..vectors import unit_vectors

EXPONENT_FLOOR = 1e-6  # the table needs n > 0; a material of exponent 0 has a flat highlight


def fast_phong_image(
    scene: Scene,
    polygons,
    result,
    width: int,
    height: int,
    sample,
    bits,
    expansion="vertex",
    *,
    compiled: bool = True,
):
    """(image, shaded samples): the visible pixels of `result` shaded by fast Phong."""
    image = np.empty((height, width, 3))
    image[...] = scene.background
    visible = np.unique(result.polygon[result.polygon >= 0])
    fan = _Fan(polygons, visible)
    if not len(fan.owner):
        return image, 0
    to_lights, to_viewers, normals = _directions(scene, fan)
    models, table = _models(scene, fan)
    # a replaced step of scanviz.steps runs the reference loop, as every traced path promises
    compiled = compiled and not steps.replaced()
    snapped = _snap_batch(fan.xy, sample, bits) if compiled else None
    if snapped is None:
        shaded = _reference(fan, normals, to_lights, to_viewers, models, table, result, image,
                            width, height, sample, bits, expansion)  # fmt: skip
        return image, shaded
    units, scale = snapped
    shaded = fast_phong_triangles(
        units, scale, scale // 2 if sample == "center" else 0, normals, to_lights, to_viewers,
        table, fan.owner, result.polygon, image, expansion=expansion,
        sample_offset=0.5 if sample == "center" else 0.0, blinn=False,
        diffuse=[m.diffuse_scale for m in models], ambients=[m.ambient_term for m in models],
        tables=[m.table for m in models],
    )  # fmt: skip
    return image, shaded


class _Fan:
    """The fan triangles (0, k, k + 1) of the visible polygons, with nonzero (unsnapped) area.

    Attributes: owner (T,) polygon index; corners (T, 3) rows of the packed
    polygons; xy (T, 3, 2), normals (T, 3, 3), positions (T, 3, 3); material
    (T, 9) the polygon's first vertex's.
    """

    def __init__(self, polygons, visible: np.ndarray) -> None:
        first = polygons.offsets[visible]
        sizes = polygons.offsets[visible + 1] - first
        count = np.maximum(sizes - 2, 0)
        owner = np.repeat(visible, count)
        base = np.repeat(first, count)
        k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count) + 1
        corners = np.stack([base, base + k, base + k + 1], axis=1)
        xy = polygons.xy[corners]
        area = (xy[:, 1, 0] - xy[:, 0, 0]) * (xy[:, 2, 1] - xy[:, 0, 1]) - (
            xy[:, 2, 0] - xy[:, 0, 0]
        ) * (xy[:, 1, 1] - xy[:, 0, 1])
        keep = area != 0
        self.owner, self.corners = owner[keep], corners[keep]
        self.xy = np.ascontiguousarray(xy[keep], dtype=np.float64)
        values = polygons.values[self.corners]
        self.normals, self.positions = values[:, :, 0:3], values[:, :, 3:6]
        self.material = polygons.values[base[keep], 6:15]


def _directions(scene: Scene, fan: _Fan):
    """(to_lights (T, L, 3), to_viewers (T, 3), normals turned toward the viewer (T, 3, 3))."""
    centroids = fan.positions.mean(axis=1)
    camera = scene.camera
    if camera.projection == "perspective":
        to_viewers = unit_vectors(np.subtract(camera.eye, centroids))
    else:
        to_viewers = np.broadcast_to(
            unit_vectors(np.subtract(camera.eye, camera.look_at)), centroids.shape
        ).copy()
    unit = unit_vectors(fan.normals)
    # Two-sided per triangle: a triangle seen from behind gets all three normals reversed. (Per
    # vertex, a silhouette triangle would interpolate between normals turned opposite ways.)
    behind = np.einsum("ti,ti->t", unit.sum(axis=1), to_viewers) < 0
    normals = np.where(behind[:, None, None], -unit, unit)
    lights = scene.lights or ()
    if not lights:  # ambient light only: the model's table is empty, L = V is a placeholder
        return to_viewers[:, None, :].copy(), to_viewers, normals
    to_lights = np.empty((len(centroids), len(lights), 3))
    for index, light in enumerate(lights):
        if light.kind == "point":
            to_lights[:, index] = unit_vectors(np.subtract(light.position, centroids))
        else:
            to_lights[:, index] = unit_vectors(-np.asarray(light.direction, dtype=np.float64))
    # A point light exactly at a centroid has no direction: it is taken to shine from the viewer.
    none = ~np.any(to_lights, axis=2)
    to_lights[none] = np.broadcast_to(to_viewers[:, None, :], to_lights.shape)[none]
    return to_lights, to_viewers, normals


def _models(scene: Scene, fan: _Fan) -> tuple[list[ReflectionModel], np.ndarray]:
    """(models, (T, L) index of each triangle's model per light): one per material and light."""
    ambient = np.asarray(scene.ambient, dtype=np.float64)
    lights = scene.lights or (None,)
    if (fan.material == fan.material[0]).all():  # one material: skip np.unique's sort
        materials, inverse = fan.material[:1], np.zeros(len(fan.material), np.int64)
    else:
        materials, inverse = np.unique(fan.material, axis=0, return_inverse=True)
    models, table = [], np.empty((len(fan.owner), len(lights)), np.int64)
    for m, material in enumerate(materials):
        for index, light in enumerate(lights):
            models.append(_model(material, light, ambient if index == 0 else np.zeros(3)))
            table[inverse.ravel() == m, index] = len(models) - 1
    return models, table


def _reference(fan, normals, to_lights, to_viewers, models, table, result, image,
               width, height, sample, bits, expansion) -> int:  # fmt: skip
    """`fast_phong_triangle` triangle by triangle, light by light: what the kernel equals."""
    shaded = 0
    for t, p in enumerate(fan.owner.tolist()):
        total = None
        for index, m in enumerate(table[t].tolist()):
            run = fast_phong_triangle(
                fan.xy[t], normals[t], to_lights[t, index], to_viewers[t], models[m],
                width=width, height=height, expansion=expansion, sample=sample,
                subpixel_bits=bits,
            )  # fmt: skip
            total = run.colors if total is None else total + run.colors
        if not len(run.ys):
            continue
        mine = result.polygon[run.ys, run.xs] == p
        image[run.ys[mine], run.xs[mine]] = np.clip(total[mine], 0.0, 255.0) / 255.0
        shaded += int(mine.sum())
    return shaded


def _model(material: np.ndarray, light, ambient: np.ndarray) -> ReflectionModel:
    """The dissertation's model for one material and one light."""
    colour, ka, kd, ks, exponent = (
        material[0:3],
        material[3],
        material[4],
        material[5],
        material[6],
    )
    light_colour = np.zeros(3) if light is None else np.asarray(light.color, dtype=np.float64)
    brightest = float(light_colour.max()) if light_colour.max() > 0 else 1.0
    return ReflectionModel(
        Ia=tuple((255.0 * ambient).tolist()),
        ka=tuple((ka * colour).tolist()),
        Ip=255.0 * brightest,
        kd=tuple((kd * colour * light_colour / brightest).tolist()),
        ks=float(ks) if light_colour.max() > 0 else 0.0,
        n=max(float(exponent), EXPONENT_FLOOR),
        r_plus_r0=1.0,
        top_level=int(LEVELS),  # colours clip at 255 levels: higher entries change no pixel
    )

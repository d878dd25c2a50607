"""Pipeline categories: interpolation, traced == compiled, and every built-in scene rendered."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .. import render, scan_convert, triangle_samples
from ..abuffer.masks import mask_buffer_rows, pixel_masks
from ..io import load_scene
from ..pipeline import ANTIALIASED, SHADINGS, VISIBILITIES
from ..scene import BUILTIN_SCENES
from ..visibility import ScreenPolygons, zbuffer
from . import exact
from .cases import (
    RULES,
    SAMPLES,
    Outcome,
    Tally,
    grid_points,
    round_list,
    samples_image,
    star_polygon,
    thousands,
)
from .classify import one_line

RENDER_MODES = [  # fast Phong shades an opaque algorithm's visible triangles only
    (s, v) for s in SHADINGS for v in VISIBILITIES if not (s == "fast_phong" and v in ANTIALIASED)
]


def interpolation_vs_barycentric(rng: np.random.Generator) -> Outcome:
    """Interpolated attributes (triangle_samples weights, z-buffer values) against exact barycentrics."""
    tally, samples = Tally(), 0
    size = 12
    for k in range(30):
        sample = SAMPLES[k % 2]
        perspective = k % 3 == 0
        triangle = grid_points(rng, -1, size + 1, (3, 2))
        values = rng.uniform(0, 1, (3, 2))
        inv_w = rng.uniform(0.5, 2, 3) if perspective else np.ones(3)
        snapped = exact.snap_contours([triangle], 8)[0]
        if exact.signed_area(snapped) == 0:
            continue
        offset = Fraction(1, 2) if sample == "center" else Fraction(0)
        found = triangle_samples(triangle, size, size, sample=sample)
        result = zbuffer(
            ScreenPolygons.from_polygons(
                [np.column_stack([triangle, [0.5] * 3])], [values], [inv_w]
            ),
            size,
            size,
            sample=sample,
            perspective=perspective,
        )
        for y, x, weights in zip(found.ys, found.xs, found.barycentric, strict=True):
            samples += 1
            want = exact.barycentric(snapped, x + offset, y + offset)
            tally.check(
                np.abs(weights - np.array(want, float)).max() <= 1e-12,
                (
                    f"triangle_samples barycentric at ({x}, {y}) of {round_list(triangle)}: "
                    f"got {weights.tolist()}, want {[float(w) for w in want]}"
                ),
            )
            w = [Fraction(float(a)) * Fraction(float(b)) for a, b in zip(want, inv_w, strict=True)]
            weights_w = [float(a / sum(w)) for a in w]  # perspective-correct weights
            expected = np.array(weights_w if perspective else [float(a) for a in want]) @ values
            got = result.values[y, x]
            tally.check(
                np.abs(got - expected).max() <= 1e-9,
                (
                    f"zbuffer values perspective={perspective} at ({x}, {y}) of "
                    f"{round_list(triangle)}: got {got.tolist()}, want {expected.tolist()}"
                ),
            )
        tally.check(
            np.array_equal(result.polygon >= 0, samples_image([triangle], size, size, sample) > 0),
            f"zbuffer covers other samples than triangle_samples for {round_list(triangle)}",
        )
    return tally.outcome(f"{thousands(samples)} samples x 2 interpolators")


ABUFFER_TOLERANCE = 1e-12


def traced_equals_compiled(rng: np.random.Generator) -> Outcome:
    """The traced references give the compiled kernels' spans, masks, depths and images."""
    tally, cases = Tally(), 0
    size = 10
    for k in range(16):
        sample, rule = SAMPLES[k % 2], RULES[(k // 2) % 2]
        contours = [
            star_polygon(rng, grid_points(rng, 3, 7, 2), rng.uniform(1, 5), int(rng.integers(3, 8)))
        ]
        if k % 3 == 0:
            contours.append(contours[0][::-1] * 0.5 + 2)
        traced = scan_convert(contours, size, size, sample=sample, rule=rule, trace=True)
        compiled = scan_convert(contours, size, size, sample=sample, rule=rule)
        cases += 1
        tally.check(
            np.array_equal(traced.spans, compiled.spans) and len(traced.trace) > 0,
            f"scan_convert spans traced != compiled for {[round_list(c) for c in contours]}",
        )
        compiled_masks = pixel_masks(contours, size, size, mask="4x4", rule=rule)
        traced_masks = mask_buffer_rows(contours, size, size, mask="4x4", rule=rule)
        cases += 1
        tally.check(
            all(
                np.array_equal(getattr(compiled_masks, f), getattr(traced_masks, f))
                for f in ("ys", "xs", "masks")
            ),
            f"pixel_masks traced != compiled for {[round_list(c) for c in contours]}",
        )
    scenes = [("umbc_zbuffer", {}), ("painter", {}), ("sphere", {"level": 1})]
    for name, params in scenes:
        scene = load_scene(f"builtin:{name}") if not params else _builtin(name, **params)
        for shading in ("flat", "gouraud", "phong"):
            for visibility in ("zbuffer", "abuffer"):
                cases += 1
                options = {"shading": shading, "visibility": visibility, "mask": "4x4"}
                compiled_image = render(scene, 12, 12, **options).image
                traced_image = render(scene, 12, 12, trace=True, **options).image
                # The z-buffer's twins agree to the bit; the a-buffer's sums to 1e-12 (its tests').
                tolerance = 0.0 if visibility == "zbuffer" else ABUFFER_TOLERANCE
                tally.check(
                    np.abs(compiled_image - traced_image).max() <= tolerance,
                    (
                        f"render builtin:{name} {options}: traced differs from compiled by up "
                        f"to {np.abs(compiled_image - traced_image).max():.3g}"
                    ),
                )
    return tally.outcome(f"{thousands(cases)} traced/compiled pairs")


def _builtin(name: str, **params):
    from ..scene import builtin_scene

    return builtin_scene(name, **params)


SCENE_PARAMS = {"sphere": {"level": 1}, "function_surface": {"n": 6}, "terrain": {"n": 8}}
SMALL_SPHERE_FACES = 80  # icosphere(1): stands in for larger icospheres of scenes without a size


def _small_scene(name: str):
    """A built-in scene at its small parameters; an icosphere of a fixed-size scene made level 1.

    The a-buffer's cost is per polygon, so the 1,280-face sphere of
    ``transparent_cube`` alone would take most of the suite's time.
    """
    from dataclasses import replace

    from ..scene import icosphere

    scene = _builtin(name, **SCENE_PARAMS.get(name, {}))
    if name in SCENE_PARAMS:
        return scene
    objects = tuple(
        replace(o, mesh=icosphere(1)) if len(o.mesh.faces) > 4 * SMALL_SPHERE_FACES else o
        for o in scene.objects
    )
    return replace(scene, objects=objects)


def builtin_scenes(rng: np.random.Generator) -> Outcome:
    """Every built-in scene in every shading x visibility: a finite image in [0, 1], no raise."""
    tally, renders = Tally(), 0
    for name in BUILTIN_SCENES:
        scene = _small_scene(name)
        for k, (shading, visibility) in enumerate(RENDER_MODES):
            renders += 1
            options = {
                "shading": shading,
                "visibility": visibility,
                "perspective_correct": k % 2 == 0,  # each visibility meets both
                "mask": "4x4",
                "edges": bool(rng.random() < 0.25),
            }
            try:
                image = render(scene, 10, 8, **options).image
            except Exception as error:  # noqa: BLE001 -- report it as this case's failure
                tally.check(False, f"render builtin:{name} {options}: {one_line(error)}")
                continue
            tally.check(
                image.shape == (8, 10, 3)
                and bool(np.isfinite(image).all())
                and image.min() >= 0.0
                and image.max() <= 1.0,
                (f"render builtin:{name} {options}: image not finite in [0, 1]"),
            )
    return tally.outcome(f"{thousands(renders)} renders / {len(BUILTIN_SCENES)} scenes")

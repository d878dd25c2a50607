"""Input-edge categories: degenerate polygons render nothing; huge and non-finite inputs.

Coordinates up to 2**20 render correctly; beyond it, NaN and infinities
give a clear error (`scanviz.conformance.classify.clear_error`).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import (
    Polygon,
    area_coverage,
    fill_polygons,
    midpoint_line,
    rasterize_triangles,
    scan_convert,
    triangle_samples,
)
from ..abuffer.masks import pixel_masks
from ..catalog import SHAPES
from . import exact
from .cases import (
    AREA_TOLERANCE,
    SAMPLES,
    Outcome,
    Tally,
    compare_all,
    grid_points,
    mask_image,
    round_list,
    samples_image,
    thousands,
)
from .classify import clear_error, short_repr


def degenerate_polygons(rng: np.random.Generator) -> Outcome:
    """Zero area, collinear, repeated vertices: every entry point renders nothing and does not raise."""
    tally, cases = Tally(), 0
    size = 12
    shapes = [s.polygon.contours[0] for s in SHAPES.values() if s.degenerate]
    for _ in range(30):
        start, direction = grid_points(rng, 0, size, 2), grid_points(rng, -3, 3, 2)
        if not direction.any():
            continue
        steps = rng.integers(-3, 4, int(rng.integers(3, 7))).astype(float)
        if len(np.unique(steps)) < 3:
            steps = np.array([0.0, 1.0, 2.0, 1.0])
        shapes.append(start + steps[:, None] * direction)  # collinear, with retraced edges
    for contour in shapes:
        zero_area = _collinear(contour)  # else (a sliver between rows) it has area, no samples
        for sample in SAMPLES:
            cases += 1
            masks = {
                "scan_convert": scan_convert(contour, size, size, sample=sample).mask,
                "fill_polygons": fill_polygons([contour], size, size, sample=sample),
                "rasterize_triangles": rasterize_triangles(
                    [contour[[0, 1, -1]]], size, size, sample=sample
                ),
                "triangle_samples": samples_image([contour[[0, 1, -1]]], size, size, sample),
            }
            if zero_area:
                masks["area_coverage"] = area_coverage(contour, size, size)
                masks["pixel_masks"] = mask_image(contour, size, size)
            for name, image in masks.items():
                # area_coverage rounds in float64: a few ulps, as its docs say, may remain.
                tolerance = AREA_TOLERANCE if name == "area_coverage" else 0
                tally.check(
                    np.abs(image.astype(float)).max(initial=0) <= tolerance,
                    (
                        f"{name} sample={sample} covered something of the zero-area "
                        f"{round_list(contour)}"
                    ),
                )
    for repeated in ([(1, 1), (1, 1), (1, 1)], [(2, 2), (5, 2), (2, 2)]):
        cases += 1
        tally.check(
            not rasterize_triangles([repeated], size, size).any()
            and not triangle_samples(repeated, size, size).xs.size,
            f"a triangle with repeated vertices {repeated} covered a sample",
        )
    return tally.outcome(f"{thousands(cases)} degenerate inputs x 6 entry points")


def _collinear(contour) -> bool:
    """Whether every snapped vertex lies on one line (zero area in every region)."""
    points = exact.snap_contours([contour], 8)[0]
    (x0, y0), (x1, y1) = points[0], next((p for p in points if p != points[0]), points[0])
    return all((x1 - x0) * (y - y0) == (y1 - y0) * (x - x0) for x, y in points)


def _clear_error(call: Callable[[], object]) -> str:
    """'' if `call` raises a ValueError/TypeError whose message names its argument, else what happened."""
    try:
        call()
    except Exception as error:  # noqa: BLE001 -- any other exception is what this reports
        return "" if clear_error(error) else f"{type(error).__name__}: {error}"
    return "returned without error"


def huge_and_non_finite(rng: np.random.Generator) -> Outcome:
    """±2**20 renders correctly; 2**20+1, NaN, ±inf, 10**400 give a clear error from every entry point."""
    tally, cases = Tally(), 0
    size = 8
    limit = 2**20
    for sample in SAMPLES:  # vertices at the limit: a valid, huge triangle covering the raster
        triangle = np.array([(-limit, -limit), (limit, -limit), (0, limit)], float)
        cases += 1
        compare_all(tally, triangle, size, size, sample, 8)
        compare_all(tally, triangle[::-1], size, size, sample, None)
        cases += 1
        area = area_coverage(triangle, size, size)
        tally.check(
            np.abs(area - 1).max() <= AREA_TOLERANCE,
            "area_coverage of a ±2**20 triangle is not 1 in every pixel",
        )
    bad_values = [limit + 1, -limit - 1, np.nan, np.inf, -np.inf, 10**400, 2**1024]
    for bad in bad_values:
        triangle = [(0, 0), (4, 0), (bad, 3)]
        calls = {
            "Polygon": lambda t=triangle: Polygon(t),
            "scan_convert": lambda t=triangle: scan_convert(t, size, size),
            "fill_polygons": lambda t=triangle: fill_polygons([t], size, size),
            "rasterize_triangles": lambda t=triangle: rasterize_triangles([t], size, size),
            "triangle_samples": lambda t=triangle: triangle_samples(t, size, size),
            "area_coverage": lambda t=triangle: area_coverage(t, size, size),
            "pixel_masks": lambda t=triangle: pixel_masks(t, size, size),
        }
        if isinstance(bad, int):
            calls["midpoint_line"] = lambda b=bad: midpoint_line(0, 0, b, 1)
        for name, call in calls.items():
            cases += 1
            problem = _clear_error(call)
            tally.check(not problem, f"{name} with coordinate {short_repr(bad, 30)}: {problem}")
    return tally.outcome(f"{thousands(cases)} huge or non-finite inputs")

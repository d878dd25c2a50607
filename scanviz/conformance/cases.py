"""What the conformance categories share: `Outcome`, `Tally`, seeded case generators and comparisons.

Case generators put vertices on the 1/256 sub-pixel grid (`grid_points`,
`star_polygon`) so the exact oracle (`scanviz.conformance.exact`) sees the
same vertices as the code it checks.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import fill_polygons, rasterize_triangles, scan_convert, triangle_samples
from ..abuffer.masks import pixel_masks
from . import exact

SAMPLES = ("corner", "center")
RULES = ("nonzero", "evenodd")
AREA_TOLERANCE = 1e-12  # per pixel: area_coverage's float64 rounding (scanviz.abuffer.area)


@dataclass(frozen=True)
class Outcome:
    """What one category found: pass or fail, what it counted, and its first failing case."""

    passed: bool
    counts: str
    failure: str = ""


class Tally:
    """Counts checks and keeps the first failing case."""

    def __init__(self) -> None:
        self.failure = ""

    def check(self, ok: bool, case: str) -> bool:
        if not ok and not self.failure:
            self.failure = case
        return bool(ok)

    def same(self, got: np.ndarray, want: np.ndarray, case: str) -> bool:
        """Check two images are equal; a failing case ends with where they first differ."""
        if np.array_equal(got, want):
            return True
        return self.check(False, f"{case}: {first_difference(got, want)}")

    def outcome(self, counts: str) -> Outcome:
        return Outcome(not self.failure, counts, self.failure)


def thousands(count: int) -> str:
    return f"{count:,}"


def first_difference(got: np.ndarray, want: np.ndarray) -> str:
    """Where two images first differ, or '' if they are equal (booleans shown as 0 and 1)."""
    got, want = (a.astype(int) if a.dtype == bool else a for a in (got, want))
    different = np.argwhere(got != want)
    if not len(different):
        return ""
    y, x = different[0].tolist()
    return f"pixel (x={x}, y={y}): got {got[y, x]}, want {want[y, x]}"


def round_list(points) -> list:
    return [[float(v) for v in p] for p in points]


def grid_points(
    rng: np.random.Generator, low: float, high: float, size, bits: int = 8
) -> np.ndarray:
    """Random coordinates on the 1/2**bits grid, a quarter of them on whole pixels."""
    values = np.round(rng.uniform(low, high, size) * 2**bits) / 2**bits
    whole = rng.random(size) < 0.25
    return np.where(whole, np.round(values), values)


def star_polygon(
    rng: np.random.Generator, center, radius: float, count: int, bits: int = 8
) -> np.ndarray:
    """A simple counter-clockwise polygon of `count` vertices around `center`, on the grid.

    Angles are evenly spaced with a jitter of a quarter step, radii in [0.4, 1]
    times `radius`: for count >= 4 every gap is under 180 degrees, so the
    polygon is star-shaped about `center` and stays 0.15 * radius away from it.
    """
    spacing = 2 * np.pi / count
    angles = rng.uniform(0, 2 * np.pi) + spacing * (
        np.arange(count) + rng.uniform(-0.25, 0.25, count)
    )
    radii = rng.uniform(0.4, 1.0, count) * radius
    points = np.column_stack([np.cos(angles), np.sin(angles)]) * radii[:, None] + center
    return np.round(points * 2**bits) / 2**bits


def simple_ccw(points: np.ndarray) -> bool:
    """Whether a polygon's snapped area is positive and no vertex repeats (star polygons)."""
    contour = exact.snap_contours([points], 8)[0]
    return exact.signed_area(contour) > 0 and len(set(contour)) == len(contour)


def samples_image(triangles, width: int, height: int, sample: str, bits=8) -> np.ndarray:
    """Coverage counts of `triangle_samples` over several triangles: (height, width) int."""
    image = np.zeros((height, width), int)
    for triangle in triangles:
        found = triangle_samples(triangle, width, height, sample=sample, subpixel_bits=bits)
        np.add.at(image, (found.ys, found.xs), 1)
    return image


def compare_all(tally: Tally, contour, width, height, sample, bits, rules=RULES) -> None:
    """scan_convert (both rules), fill_polygons and, for triangles, the triangle rasterizers vs the oracle."""
    for rule in rules:
        want = exact.oracle_mask([contour], width, height, sample, rule, bits)
        got = {
            "scan_convert": scan_convert(
                contour, width, height, sample=sample, rule=rule, subpixel_bits=bits
            ).mask,
            "fill_polygons": fill_polygons(
                [contour], width, height, sample=sample, rule=rule, subpixel_bits=bits
            ),
        }
        if len(contour) == 3:
            got["rasterize_triangles"] = rasterize_triangles(
                [contour], width, height, sample=sample, subpixel_bits=bits
            )
            got["triangle_samples"] = samples_image([contour], width, height, sample, bits)
        for name, image in got.items():
            tally.same(
                image,
                want,
                f"{name} sample={sample} rule={rule} bits={bits} polygon {round_list(contour)}",
            )


def mask_image(contours, width: int, height: int, **options) -> np.ndarray:
    """`pixel_masks` as a (height, width) image of uint64 masks (0 where nothing is covered)."""
    result = pixel_masks(contours, width, height, **options)
    image = np.zeros((height, width), np.uint64)
    image[result.ys, result.xs] = result.masks
    return image

"""Coverage categories: area_coverage against exact clipping, A-buffer masks against sub-samples."""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .. import area_coverage
from ..abuffer.masks import MASK_LAYOUTS
from ..bench import optional_module
from . import exact
from .cases import (
    AREA_TOLERANCE,
    RULES,
    Outcome,
    Tally,
    grid_points,
    mask_image,
    round_list,
    simple_ccw,
    star_polygon,
    thousands,
)


def exact_coverage(rng: np.random.Generator) -> Outcome:
    """area_coverage against exact Fraction clipping of the polygon to each pixel."""
    shapely = optional_module("shapely")
    tally, pixels, polygons = Tally(), 0, 0
    size = 8
    for k in range(24):
        bits = (8, None)[k % 2]
        center, radius = grid_points(rng, 2, 6, 2), rng.uniform(1, 4.5)
        contour = star_polygon(rng, center, radius, int(rng.integers(4, 9)))
        if bits is None:
            contour = contour + rng.uniform(-0.01, 0.01, contour.shape)
        if not simple_ccw(contour):
            continue
        contours = [contour]
        if k % 3 == 0:  # a hole: a clockwise square about the centre, well inside the star
            half = 0.08 * radius
            contours.append(center + half * np.array([(-1, -1), (-1, 1), (1, 1), (1, -1)]))
        exact_contours = exact.snap_contours(contours, bits)
        want = exact.coverage(exact_contours, size, size).astype(float)
        got = area_coverage(contours, size, size, subpixel_bits=bits)
        polygons += 1
        pixels += size * size
        error = np.abs(got - want).max()
        tally.check(
            error <= AREA_TOLERANCE,
            f"area_coverage bits={bits} of {[round_list(c) for c in contours]}: "
            f"error {error:.3g} at pixel {np.unravel_index(np.abs(got - want).argmax(), got.shape)[::-1]}",
        )
        if shapely is not None:
            pixels += size * size
            reference = _shapely_coverage(shapely, exact_contours, size)
            tally.check(
                np.abs(reference - want).max() <= 1e-12,
                f"the Fraction oracle disagrees with shapely on {[round_list(c) for c in contours]}",
            )
    note = " (+ shapely)" if shapely is not None else " (shapely not installed)"
    return tally.outcome(f"{thousands(pixels)} pixels / {thousands(polygons)} polygons{note}")


def _shapely_coverage(shapely, contours, size: int) -> np.ndarray:
    rings = [[(float(x), float(y)) for x, y in c] for c in contours]
    shape = shapely.Polygon(rings[0], rings[1:])
    image = np.zeros((size, size))
    for y in range(size):
        for x in range(size):
            image[y, x] = shape.intersection(shapely.box(x, y, x + 1, y + 1)).area
    return image


def masks_vs_supersampling(rng: np.random.Generator) -> Outcome:
    """A-buffer pixel masks against the exact winding number at every sub-sample position."""
    tally, subsamples, polygons = Tally(), 0, 0
    size = 5
    for k in range(18):
        layout = tuple(MASK_LAYOUTS)[k % 3]
        cols, rows = MASK_LAYOUTS[layout]
        rule = RULES[k % 2]
        contours = [
            star_polygon(
                rng, grid_points(rng, 1, 4, 2), rng.uniform(0.5, 3), int(rng.integers(3, 7))
            )
        ]
        if k % 4 == 0:
            contours.append(star_polygon(rng, grid_points(rng, 1, 4, 2), 2.0, 5)[::-1])
        winding = exact.lattice_winding(
            exact.snap_contours(contours, 8),
            (size * cols, size * rows),
            (Fraction(1, 2 * cols), Fraction(1, 2 * rows)),
            (Fraction(1, cols), Fraction(1, rows)),
        )
        covered = exact.inside(winding, rule)  # (size*rows, size*cols)
        got = mask_image(contours, size, size, mask=layout, rule=rule)
        bits = np.left_shift(1, np.arange(cols * rows, dtype=np.uint64)).reshape(rows, cols)
        blocks = covered.reshape(size, rows, size, cols).transpose(0, 2, 1, 3)
        want = (blocks * bits).sum(axis=(2, 3), dtype=np.uint64)
        polygons += 1
        subsamples += covered.size
        tally.same(
            got,
            want,
            f"pixel_masks mask={layout} rule={rule} of {[round_list(c) for c in contours]}",
        )
    return tally.outcome(f"{thousands(subsamples)} sub-samples / {thousands(polygons)} polygons")

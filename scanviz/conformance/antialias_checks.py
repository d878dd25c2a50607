"""Conformance of area-sampling anti-aliasing: DISLOP's areas against the exact areas.

On seeded random segments in all eight octants (sub-pixel endpoints, long and
short, partly off the raster, and the near-degenerate |dx| = |dy|, horizontal,
vertical and shorter than a pixel): `dislop_line(exact=True)` must equal the
exact band area (`peers.exact_band_line`: `area_coverage` of the band's
rectangle); the printed formula must stay within the bound docs/antialiasing.md
states (exact for first-octant slopes up to 0.75, the fourth pixel's spill
above); the eight reflections of the raster must reflect the image; the
coverage of a line on the raster must sum to its length; `post_antialias` of
one segment on black must stay within the look-up table's error of
`dislop_line`. On random simple, holed and self-intersecting polygons,
`dislop_edge` must equal `area_coverage(subpixel_bits=None)`; and the total of
`dislop_disk` must exceed the disk's area by the documented margin.
"""

from __future__ import annotations

import math

import numpy as np

from ..abuffer.area import area_coverage
from ..antialias import dislop_disk, dislop_edge, dislop_line, post_antialias
from ..antialias.peers import exact_band_line
from .cases import Outcome, Tally, grid_points, round_list, star_polygon, thousands

AREA_TOLERANCE = 1e-9  # per pixel, and for a line's total: float rounding of the exact areas
SYMMETRY_TOLERANCE = 1e-12  # per pixel, between a reflected segment and the reflected image
EXACT_SLOPE = 0.75  # up to this first-octant slope the printed formula is exact
PRINTED_SPILL = (3 - 2 * math.sqrt(2)) / 8  # 0.021447: the fourth pixel at m = 1, dxy = 1/2
TABLE_ERROR = 0.0136  # the 51 x 51 x 3 look-up's worst, measured 0.013527 on a 2000^2 grid
DISK_EXCESS = {True: (0.30, 0.36), False: (0.20, 0.42)}  # total - pi R^2, for R >= 4.75 or not
KINDS = ("any", "long", "short", "diagonal", "horizontal", "vertical", "snapped")
SEGMENTS = 700
REFLECTED = 96  # segments also drawn in the 8 reflections of the raster
POLYGONS = 120
LONG_LINES = 60
DISKS = 300


def _segment(rng: np.random.Generator, k: int, width: int, height: int):
    """Case `k`: its kind and endpoints p0, p1; the float kinds run in octant k % 8."""
    kind, size = KINDS[k % len(KINDS)], max(width, height)
    if kind in ("any", "long", "short"):
        length = {"any": rng.uniform(1, size), "long": rng.uniform(size, 2 * size)}.get(kind)
        length = rng.uniform() if length is None else length
        angle = (k % 8 + rng.uniform()) * math.pi / 4
        p0 = rng.uniform(-3, (width + 3, height + 3))
        return kind, p0, p0 + length * np.array([math.cos(angle), math.sin(angle)])
    p0 = grid_points(rng, -3, size + 3, 2)  # on the 1/256 grid, so dx and dy are exact
    step = float(grid_points(rng, 0, size, 1)[0]) * rng.choice([-1.0, 1.0], 2)
    delta = {"diagonal": step, "horizontal": step * (1, 0), "vertical": step * (0, 1)}.get(kind)
    return kind, p0, p0 + (grid_points(rng, -size, size, 2) if delta is None else delta)


def _first_octant_slope(p0, p1) -> float:
    dx, dy = abs(p1[0] - p0[0]), abs(p1[1] - p0[1])
    return min(dx, dy) / max(dx, dy) if max(dx, dy) > 0 else 0.0


def _error(got: np.ndarray, want: np.ndarray) -> tuple[float, str]:
    """The largest pixel error, and a message saying how large and where."""
    difference = np.abs(got - want)
    y, x = np.unravel_index(difference.argmax(), difference.shape)
    return float(difference[y, x]), f"error {difference[y, x]:.3g} at pixel (x={x}, y={y})"


def _lines(rng: np.random.Generator, tally: Tally) -> int:
    """Exact mode vs the exact band, printed mode vs its bound, post vs printed: pixels compared."""
    pixels = 0
    for k in range(SEGMENTS):
        width, height = (int(n) for n in rng.integers(12, 48, 2))
        kind, p0, p1 = _segment(rng, k, width, height)
        label = f"{kind} segment {round_list([p0, p1])} on {width}x{height}"
        want = exact_band_line(p0, p1, width, height)
        exact = dislop_line(p0, p1, width, height, exact=True)
        error, where = _error(exact, want)
        tally.check(error <= AREA_TOLERANCE, f"dislop_line exact=True, {label}: {where}")
        printed = dislop_line(p0, p1, width, height)
        slope = _first_octant_slope(p0, p1)
        bound = AREA_TOLERANCE if slope <= EXACT_SLOPE else PRINTED_SPILL + AREA_TOLERANCE
        error, where = _error(printed, want)
        tally.check(
            error <= bound, f"dislop_line, slope {slope:.4g}, {label}: {where} > {bound:.3g}"
        )
        posted = post_antialias(np.zeros((height, width)), [(p0, p1)])[:, :, 0]
        error, where = _error(posted, printed)
        tally.check(error <= TABLE_ERROR, f"post_antialias vs dislop_line, {label}: {where}")
        pixels += 3 * width * height
    return pixels


def _reflections(p0, p1, width: int, height: int):
    """The 8 symmetries of the raster: (endpoints, size, image map) for each."""
    for transpose in (False, True):
        for flip_x in (False, True):
            for flip_y in (False, True):

                def move(p, fx=flip_x, fy=flip_y, t=transpose):
                    x, y = (width - p[0] if fx else p[0]), (height - p[1] if fy else p[1])
                    return (y, x) if t else (x, y)

                def image_map(image, fx=flip_x, fy=flip_y, t=transpose):
                    image = image[:: -1 if fy else 1, :: -1 if fx else 1]
                    return image.T if t else image

                name = f"transpose={transpose} flip_x={flip_x} flip_y={flip_y}"
                ends = (move(p0), move(p1))[:: -1 if flip_x != flip_y else 1]  # either direction
                size = (height, width) if transpose else (width, height)
                yield name, ends, size, image_map


def _symmetry(rng: np.random.Generator, tally: Tally) -> int:
    """Exact mode in the 8 reflections of the raster: pixels compared."""
    pixels = 0
    for k in range(REFLECTED):
        width, height = (int(n) for n in rng.integers(12, 40, 2))
        kind, p0, p1 = _segment(rng, k, width, height)
        image = dislop_line(p0, p1, width, height, exact=True)
        for name, (q0, q1), (w, h), image_map in _reflections(p0, p1, width, height):
            error, where = _error(dislop_line(q0, q1, w, h, exact=True), image_map(image))
            tally.check(
                error <= SYMMETRY_TOLERANCE,
                f"dislop_line exact=True of {kind} segment {round_list([p0, p1])} on "
                f"{width}x{height} reflected ({name}): {where}",
            )
            pixels += width * height
    return pixels


def _lengths(rng: np.random.Generator, tally: Tally) -> int:
    """A line on the raster holds its length (Ta per column), in both modes: lines checked."""
    size = 96
    for _ in range(LONG_LINES):
        p0, p1 = rng.uniform(1, size - 1, (2, 2))
        while math.dist(p0, p1) < size / 3:
            p1 = rng.uniform(1, size - 1, 2)
        length = math.dist(p0, p1)
        for exact in (True, False):
            total = float(dislop_line(p0, p1, size, size, exact=exact).sum())
            tally.check(
                abs(total - length) <= AREA_TOLERANCE,
                f"dislop_line exact={exact} of {round_list([p0, p1])}: total {total!r}, "
                f"length {length!r}",
            )
    return LONG_LINES


def _polygon(rng: np.random.Generator, k: int, size: int):
    """Case `k`: a simple star (snapped, or unsnapped with a hole), or random points (crossing)."""
    count = int(rng.integers(3, 10))
    if k % 3 == 2:  # self-intersecting as a rule; some vertices off the raster
        return [rng.uniform(-2, size + 2, (count, 2))]
    center, radius = rng.uniform(6, size - 6, 2), rng.uniform(1.5, 9)
    star = star_polygon(rng, center, radius, max(count, 4))
    if k % 3 == 0:
        return [star]
    hole = center + 0.1 * radius * np.array([(-1, -1), (-1, 1), (1, 1), (1, -1)])  # clockwise
    return [star + rng.uniform(-0.01, 0.01, star.shape), hole]


def _edges(rng: np.random.Generator, tally: Tally) -> int:
    """dislop_edge vs area_coverage unsnapped: pixels compared."""
    size = 21
    for k in range(POLYGONS):
        contours = _polygon(rng, k, size)
        error, where = _error(
            dislop_edge(contours, size, size),
            area_coverage(contours, size, size, subpixel_bits=None),
        )
        tally.check(
            error <= AREA_TOLERANCE,
            f"dislop_edge of {[round_list(c) for c in contours]}: {where}",
        )
    return POLYGONS * size * size


def _disks(rng: np.random.Generator, tally: Tally) -> int:
    """dislop_disk's total over the exact area, within the documented margin: pixels compared."""
    pixels = 0
    for k in range(DISKS):
        radius = rng.uniform(1, 4.75) if k % 2 else rng.uniform(1, 20)
        if k % 4 == 3:  # on a 1/4 grid of radii and centres
            radius = max(1.0, round(radius * 4) / 4)
        size = math.ceil(2 * radius + 6)
        center = size / 2 + rng.uniform(-1, 1, 2)
        if k % 4 == 3:
            center = np.round(center * 4) / 4
        disk = dislop_disk(center, radius, size, size)
        low, high = DISK_EXCESS[radius >= 4.75]
        excess = float(disk.sum()) - math.pi * radius**2
        tally.check(
            low <= excess <= high and 0.0 <= disk.min() and disk.max() <= 1.0,
            f"dislop_disk({round_list([center])[0]}, {radius!r}, {size}, {size}): total - pi R^2 "
            f"= {excess:.4f}, not in {low}..{high}, or areas in {disk.min():.3g}..{disk.max():.3g}",
        )
        pixels += size * size
    return pixels


def dislop_vs_exact_area(rng: np.random.Generator) -> Outcome:
    """DISLOP lines, edges, disks and the post-anti-aliasing look-up against the exact areas."""
    tally = Tally()
    pixels = _lines(rng, tally) + _symmetry(rng, tally) + _edges(rng, tally)
    lines = _lengths(rng, tally)
    pixels += _disks(rng, tally)
    return tally.outcome(
        f"{thousands(pixels)} pixels / {SEGMENTS + REFLECTED * 8 + lines} segments / "
        f"{POLYGONS} polygons / {DISKS} disks"
    )

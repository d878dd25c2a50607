"""Raster benchmark: the compiled scan converter against OpenCV on the same scenes.

Scenes (seeded, 1024 x 1024 raster, corner sampling, 8 sub-pixel bits):

* 1,000 large random triangles (vertices uniform over the raster);
* 100,000 small random triangles (vertices within 12 px of a random center);
* 100 random 50-vertex star polygons (radius 20..200 px, concave, simple).

scanviz counts coverage per sample; OpenCV overwrites a uint8 mask. OpenCV is
measured with ``shift=8`` fixed-point vertices, as one call per polygon
(``fillConvexPoly`` for triangles, ``fillPoly`` for stars) from a Python loop,
which is how independent polygons are drawn with it. Its fill rule differs
from scanviz's (it draws boundary pixels on both sides), so the table also
prints how many samples the two disagree on.
"""

from __future__ import annotations

import numpy as np

from ..raster import fill_polygons, rasterize_triangles
from . import best_time, optional_module

SIZE = 1024


def random_triangles(count: int, spread: float | None, seed: int) -> np.ndarray:
    """(count, 3, 2) float64 triangles: uniform over the raster, or within `spread` of a center."""
    rng = np.random.default_rng(seed)
    if spread is None:
        return rng.uniform(0, SIZE, (count, 3, 2))
    centers = rng.uniform(0, SIZE, (count, 1, 2))
    return np.clip(centers + rng.uniform(-spread, spread, (count, 3, 2)), 0, SIZE)


def random_stars(count: int, points: int, seed: int) -> list[np.ndarray]:
    """`count` simple star polygons of `points` vertices each, radii alternating outer/inner."""
    rng = np.random.default_rng(seed)
    stars = []
    for _ in range(count):
        center = rng.uniform(200, SIZE - 200, 2)
        outer = rng.uniform(20, 200)
        angles = np.sort(rng.uniform(0, 2 * np.pi, points))
        radii = np.where(np.arange(points) % 2 == 0, outer, outer * rng.uniform(0.2, 0.6, points))
        stars.append(center + radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)]))
    return stars


def _opencv_fill(cv2, polygons, convex: bool) -> np.ndarray:
    image = np.zeros((SIZE, SIZE), np.uint8)
    fixed = [np.rint(np.asarray(p) * 256).astype(np.int32) for p in polygons]
    if convex:
        for points in fixed:
            cv2.fillConvexPoly(image, points, 1, cv2.LINE_8, 8)
    else:
        for points in fixed:
            cv2.fillPoly(image, [points], 1, cv2.LINE_8, 8)
    return image


def run_raster(*, quick: bool = False) -> list[dict]:
    """Time each scene, print the table, return its rows."""
    scale = 10 if quick else 1
    scenes = [
        ("1,000 large triangles", random_triangles(1000 // scale, None, 1), True),
        ("100,000 small triangles", random_triangles(100_000 // scale, 12.0, 2), True),
        ("100 stars of 50 vertices", random_stars(100 // scale, 50, 3), False),
    ]
    cv2 = optional_module("cv2")
    rows = []
    print(f"raster benchmark: {SIZE}x{SIZE}, corner sampling, subpixel_bits=8 (median of runs)")
    header = f"{'scene':<26}{'scanviz ms':>11}{'Msmp/s':>9}"
    if cv2 is not None:
        header += f"{'OpenCV ms':>11}{'Msmp/s':>9}{'ratio':>8}{'differ':>9}"
    print(header)
    for name, polygons, triangles in scenes:
        if triangles:
            draw = lambda p=polygons: rasterize_triangles(p, SIZE, SIZE)  # noqa: E731
        else:
            draw = lambda p=polygons: fill_polygons(p, SIZE, SIZE)  # noqa: E731
        seconds = best_time(draw)
        counts = draw()
        samples = int(counts.sum())
        row = {"scene": name, "scanviz_ms": seconds * 1e3, "samples": samples}
        line = f"{name:<26}{seconds * 1e3:>11.2f}{samples / seconds / 1e6:>9.1f}"
        if cv2 is not None:
            theirs = best_time(lambda p=polygons, c=triangles: _opencv_fill(cv2, p, c))
            their_mask = _opencv_fill(cv2, polygons, triangles) > 0
            differ = int(np.count_nonzero(their_mask != (counts > 0)))
            row |= {"opencv_ms": theirs * 1e3, "ratio": theirs / seconds, "differ": differ}
            line += f"{theirs * 1e3:>11.2f}{samples / theirs / 1e6:>9.1f}{theirs / seconds:>7.2f}x{differ:>9}"
        print(line)
        rows.append(row)
    if cv2 is None:
        print("OpenCV not installed (pip install 'scanviz[bench]') - peers not measured")
    else:
        print("ratio = OpenCV time / scanviz time (> 1: scanviz is faster); differ = samples whose")
        print("coverage differs (OpenCV's fill rule includes boundary pixels on both sides)")
    print(
        "Msamples/s = samples filled, summed over polygons (overlaps count each time), per second"
    )
    return rows

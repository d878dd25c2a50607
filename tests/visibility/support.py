"""Shared oracles for the visibility algorithms: random scenes and where the nearest is unique.

`unique_nearest(polygons, w, h, tol)` is True at the samples where the
nearest covering polygon is nearer than every other covering polygon by more
than `tol` in depth (or is the only one): there every correct visibility
algorithm must show the z-buffer's polygon. Each polygon's own depth map
comes from drawing it alone (coverage is the z-buffer's by construction);
the comparison across polygons is plain sorting.

`random_scene(rng, n, size, interpenetrating)` draws random slanted
triangles and quads; without interpenetration every pair whose projections
overlap (shapely, exact enough for a test) keeps one polygon in front over
the whole overlap, decided at the overlap's vertices with a margin.
"""

from __future__ import annotations

import numpy as np
import shapely

from scanviz.visibility import ScreenPolygons, solve, zbuffer

TOLERANCE = 1e-7  # depth gap below which either polygon may be shown


def polygon_depths(polygons: ScreenPolygons, width: int, height: int, **options) -> np.ndarray:
    """(P, H, W) depth of each polygon drawn alone (+inf where it does not cover the sample)."""
    maps = []
    for p in range(polygons.count):
        rows = slice(polygons.offsets[p], polygons.offsets[p + 1])
        alone = ScreenPolygons(
            xy=polygons.xy[rows],
            z=polygons.z[rows],
            inv_w=polygons.inv_w[rows],
            values=polygons.values[rows],
            offsets=np.array([0, rows.stop - rows.start]),
        )
        maps.append(zbuffer(alone, width, height, **options).depth)
    return np.array(maps).reshape(polygons.count, height, width)


def unique_nearest(polygons, width, height, tol=TOLERANCE, **options) -> np.ndarray:
    """(H, W) bool: the nearest covering polygon is unique by more than `tol` (or none covers)."""
    depths = polygon_depths(polygons, width, height, **options)
    if len(depths) < 2:
        return np.ones((height, width), bool)
    ordered = np.sort(depths, axis=0)
    with np.errstate(invalid="ignore"):
        gap = ordered[1] - ordered[0]
    return np.isinf(ordered[0]) | np.isinf(ordered[1]) | (gap > tol)


def assert_agrees(name, polygons, width, height, tol=TOLERANCE, **options):
    """`solve(name)` shows the z-buffer's polygon, depth and values wherever the nearest is unique."""
    result = solve(name, polygons, width, height, **options)
    reference = zbuffer(polygons, width, height, **options)
    where = unique_nearest(polygons, width, height, tol, **options)
    wrong = where & (result.polygon != reference.polygon)
    assert not wrong.any(), (
        f"{name}: {int(wrong.sum())} samples differ from the z-buffer where the nearest is "
        f"unique by > {tol}, first at (x, y) = {tuple(np.argwhere(wrong)[0][::-1].tolist())}"
    )
    same = where & (reference.polygon >= 0)
    assert np.array_equal(result.depth[same], reference.depth[same])
    assert np.array_equal(result.values[same], reference.values[same])
    return result, reference, where


def random_polygon(rng, size: float) -> list[tuple[float, float, float]]:
    """A random triangle or convex quad over a size x size raster, with a random depth plane."""
    n = int(rng.choice([3, 4]))
    center = rng.uniform(-0.1 * size, 1.1 * size, 2)
    radius = rng.uniform(0.1, 0.6) * size
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    z0, dzdx, dzdy = rng.uniform(0.1, 0.9), *rng.uniform(-0.02, 0.02, 2) * 24 / size
    points = []
    for a in angles:
        x, y = center + radius * np.array([np.cos(a), np.sin(a)])
        z = z0 + dzdx * (x - center[0]) + dzdy * (y - center[1])
        points.append((float(x), float(y), float(z)))
    return points[::-1] if rng.random() < 0.5 else points  # clockwise: seen from the back


def _plane(polygon):
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = polygon[:3]
    a = np.array([[x0, y0, 1], [x1, y1, 1], [x2, y2, 1]])
    return np.linalg.solve(a, [z0, z1, z2])


def interpenetrate(p, q, margin: float = 1e-3) -> bool:
    """Whether p and q cross in depth over the overlap of their projections (or nearly do)."""
    sp, sq = shapely.Polygon([v[:2] for v in p]), shapely.Polygon([v[:2] for v in q])
    if not sp.is_valid or not sq.is_valid:
        return True
    overlap = sp.intersection(sq)
    if overlap.area < 1e-9:
        return False
    points = np.array(shapely.get_coordinates(overlap))
    (a1, b1, c1), (a2, b2, c2) = _plane(p), _plane(q)
    difference = (a1 - a2) * points[:, 0] + (b1 - b2) * points[:, 1] + (c1 - c2)
    return not ((difference > margin).all() or (difference < -margin).all())


def random_scene(rng, n: int, size: int, interpenetrating: bool = False) -> ScreenPolygons:
    """n random polygons over a size x size raster; none crossing another unless asked."""
    polygons = []
    attempts = 0
    while len(polygons) < n and attempts < 200 * n:
        attempts += 1
        candidate = random_polygon(rng, size)
        if shapely.Polygon([v[:2] for v in candidate]).area < 1.0:
            continue
        if not interpenetrating and any(interpenetrate(candidate, q) for q in polygons):
            continue
        polygons.append(candidate)
    values = [
        np.column_stack([np.full(len(p), i), [v[2] for v in p]]) for i, p in enumerate(polygons)
    ]
    return ScreenPolygons.from_polygons(polygons, values)

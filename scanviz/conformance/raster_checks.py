"""Sample-coverage categories: the fill convention, watertight meshes, invariances and ties.

Each checks scan_convert, fill_polygons, rasterize_triangles and
triangle_samples against the exact oracle or an exact invariant.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .. import area_coverage, fill_polygons, rasterize_triangles, scan_convert
from ..catalog import SHAPES
from . import exact
from .cases import (
    RULES,
    SAMPLES,
    Outcome,
    Tally,
    compare_all,
    grid_points,
    round_list,
    samples_image,
    star_polygon,
    thousands,
)


def fill_convention(rng: np.random.Generator) -> Outcome:
    """Samples exactly on left/right/top/bottom edges and vertices, under both sample modes.

    Axis-aligned rectangles with sides on sample rows and columns, both
    orientations: DESIGN §2 says a sample is in iff x0 <= sx < x1 and
    y0 <= sy < y1. Triangles and diamonds with vertices on samples go to the
    exact oracle.
    """
    tally, probed, polygons = Tally(), 0, 0
    size = 10
    for sample in SAMPLES:
        offset = 0.5 if sample == "center" else 0.0
        for _ in range(24):
            x0, x1 = sorted(rng.choice(np.arange(-1, size + 2), 2, replace=False))
            y0, y1 = sorted(rng.choice(np.arange(-1, size + 2), 2, replace=False))
            px, py = np.arange(size) + offset, np.arange(size) + offset
            want = ((py[:, None] >= y0) & (py[:, None] < y1)) & ((px >= x0) & (px < x1))
            corners = np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], float) + offset
            rows, columns = py[:, None], px[None, :]
            on_sides = ((columns == x0) | (columns == x1)) & (rows >= y0) & (rows <= y1)
            on_sides |= ((rows == y0) | (rows == y1)) & (columns >= x0) & (columns <= x1)
            for contour in (corners, corners[::-1]):
                polygons += 1
                probed += int(on_sides.sum())
                triangles = [contour[[0, 1, 2]], contour[[0, 2, 3]]]
                other_diagonal = [contour[[0, 1, 3]], contour[[1, 2, 3]]]
                results = {
                    f"scan_convert {rule}": scan_convert(
                        contour, size, size, sample=sample, rule=rule
                    ).mask
                    for rule in RULES
                }
                results["fill_polygons"] = fill_polygons([contour], size, size, sample=sample)
                for name, tris in (("", triangles), (" other diagonal", other_diagonal)):
                    results["rasterize_triangles" + name] = rasterize_triangles(
                        tris, size, size, sample=sample
                    )
                results["triangle_samples"] = samples_image(triangles, size, size, sample)
                for name, got in results.items():
                    tally.same(got, want, f"{name} sample={sample} rectangle {round_list(contour)}")
        for _ in range(12):  # vertices and sloped edges through samples
            center = rng.integers(2, size - 2, 2) + offset
            reach = rng.integers(1, 4, 2)
            diamond = np.array(
                [
                    (center[0], center[1] - reach[1]),
                    (center[0] + reach[0], center[1]),
                    (center[0], center[1] + reach[1]),
                    (center[0] - reach[0], center[1]),
                ],
                float,
            )
            dx = np.abs(np.arange(size)[None, :] + offset - center[0])
            dy = np.abs(np.arange(size)[:, None] + offset - center[1])
            on_edges = dx * reach[1] + dy * reach[0] == reach[0] * reach[1]
            for shape in (diamond, diamond[:3], diamond[[0, 2, 3]]):
                polygons += 1
                probed += int(on_edges.sum())
                compare_all(tally, shape, size, size, sample, 8)
    return tally.outcome(
        f"{thousands(probed)} samples on edges or vertices / {thousands(polygons)} polygons"
    )


def _jittered_mesh(rng: np.random.Generator, cells: int, size: int, sample: str):
    """A grid of cells x cells quads over the raster, inner vertices jittered on the grid.

    Returns (quads, triangles, outline): (Q, 4, 2) quads, (2Q, 3, 2)
    triangles (each quad cut along a random diagonal) and the outer contour.
    """
    step = size / cells
    offset = 0.5 if sample == "center" else 0.0
    ticks = np.arange(cells + 1) * step
    points = np.stack(np.meshgrid(ticks, ticks, indexing="xy"), axis=-1) + offset
    jitter = grid_points(rng, -0.35 * step, 0.35 * step, points.shape)
    on_sample = rng.random(points.shape[:2]) < 0.3
    jitter[on_sample] = np.round(jitter[on_sample])  # some vertices exactly on samples
    points[1:-1, 1:-1] += jitter[1:-1, 1:-1]
    quads, triangles = [], []
    for j in range(cells):
        for i in range(cells):
            a, b, c, d = points[j, i], points[j, i + 1], points[j + 1, i + 1], points[j + 1, i]
            quads.append([a, b, c, d])
            if rng.random() < 0.5:
                triangles += [[a, b, c], [a, c, d]]
            else:
                triangles += [[a, b, d], [b, c, d]]
    outline = np.concatenate([points[0, :-1], points[:-1, -1], points[-1, :0:-1], points[:0:-1, 0]])
    return np.array(quads), np.array(triangles), outline


def shared_edges(rng: np.random.Generator) -> Outcome:
    """Random meshes: coverage counts are <= 1 everywhere and == 1 inside the union."""
    tally, samples, meshes = Tally(), 0, 0
    size = 12
    for k in range(16):
        sample = SAMPLES[k % 2]
        quads, triangles, outline = _jittered_mesh(rng, int(rng.integers(2, 5)), size, sample)
        want = exact.oracle_mask([outline], size + 2, size + 2, sample, "nonzero", 8).astype(int)
        meshes += 1
        samples += want.size
        for name, got in (
            ("fill_polygons quads", fill_polygons(quads, size + 2, size + 2, sample=sample)),
            (
                "fill_polygons triangles",
                fill_polygons(triangles, size + 2, size + 2, sample=sample),
            ),
            (
                "rasterize_triangles",
                rasterize_triangles(triangles, size + 2, size + 2, sample=sample),
            ),
        ):
            tally.same(got, want, f"{name} sample={sample} mesh {k}")
    return tally.outcome(f"{thousands(samples)} samples / {thousands(meshes)} meshes")


def watertight_fans(rng: np.random.Generator) -> Outcome:
    """A disk cut into N triangles around its centre: every sample inside covered exactly once."""
    tally, samples, fans = Tally(), 0, 0
    size = 16
    for k in range(64):
        sample = SAMPLES[k % 2]
        count = int(rng.integers(3, 24))
        center = grid_points(rng, 5, 11, 2)
        radius = rng.uniform(2, 7)
        angles = rng.uniform(0, 2 * np.pi) + 2 * np.pi * np.arange(count) / count
        rim = (
            np.round((center + radius * np.column_stack([np.cos(angles), np.sin(angles)])) * 256)
            / 256
        )
        triangles = np.array([[center, rim[i], rim[(i + 1) % count]] for i in range(count)])
        want = exact.oracle_mask([rim], size, size, sample, "nonzero", 8).astype(int)
        fans += 1
        samples += int(want.sum())
        for name, got in (
            ("rasterize_triangles", rasterize_triangles(triangles, size, size, sample=sample)),
            ("fill_polygons", fill_polygons(triangles, size, size, sample=sample)),
            ("triangle_samples", samples_image(triangles, size, size, sample)),
        ):
            tally.same(got, want, f"{name} sample={sample} fan of {count} around {center.tolist()}")
    return tally.outcome(f"{thousands(samples)} samples / {thousands(fans)} fans")


def translation_invariance(rng: np.random.Generator) -> Outcome:
    """Integer translations shift the mask exactly; grid-step translations move it as the oracle says.

    Whole-pixel shifts (any vertices) must move the mask by the same pixels.
    A half-pixel shift must turn center sampling into corner sampling exactly,
    and a shift by a multiple of the sub-pixel grid (grid vertices) must give
    the oracle's mask of the shifted polygon and the same coverage area shifted.
    """
    tally, cases = Tally(), 0
    size, pad = 12, 6
    for _ in range(40):
        polygon = star_polygon(
            rng, grid_points(rng, 3, 9, 2), rng.uniform(1, 5), int(rng.integers(3, 9))
        )
        polygon = polygon + rng.uniform(-1, 1, polygon.shape) * 1e-3 * (rng.random() < 0.5)
        dx, dy = (int(v) for v in rng.integers(-pad, pad + 1, 2))
        for sample in SAMPLES:
            for rule in RULES:
                cases += 1
                big = size + 2 * pad
                base = scan_convert(polygon + pad, big, big, sample=sample, rule=rule).mask
                moved = scan_convert(polygon + pad + (dx, dy), big, big, sample=sample, rule=rule)
                want = np.zeros_like(base)
                want[max(dy, 0) : big + min(dy, 0), max(dx, 0) : big + min(dx, 0)] = base[
                    max(-dy, 0) : big - max(dy, 0), max(-dx, 0) : big - max(dx, 0)
                ]
                tally.same(
                    moved.mask,
                    want,
                    f"scan_convert shift ({dx}, {dy}) sample={sample} rule={rule} of "
                    f"{round_list(polygon)}",
                )
        centered = scan_convert(polygon, size, size, sample="center").mask
        cornered = scan_convert(polygon - 0.5, size, size, sample="corner").mask
        cases += 1
        tally.check(
            np.array_equal(centered, cornered),
            f"center sampling != corner sampling of the polygon moved by -1/2: {round_list(polygon)}",
        )
        step = Fraction(int(rng.integers(1, 256)), 256)
        grid_polygon = np.round(polygon * 256) / 256
        shifted = grid_polygon + float(step)
        cases += 1
        want = exact.oracle_mask([shifted], size, size, "corner", "nonzero", 8)
        got = scan_convert(shifted, size, size).mask
        tally.same(got, want, f"scan_convert shift {step} of {round_list(grid_polygon)}")
        whole = np.round(polygon) + (dx, dy)
        base_area = area_coverage(np.round(polygon) + pad, size + 2 * pad, size + 2 * pad)
        moved_area = area_coverage(whole + pad, size + 2 * pad, size + 2 * pad)
        cases += 1
        tally.check(
            abs(base_area.sum() - moved_area.sum()) < 1e-9 or _leaves(whole + pad, size + 2 * pad),
            f"area_coverage total changed under shift ({dx}, {dy}) of {round_list(np.round(polygon))}",
        )
    return tally.outcome(f"{thousands(cases)} translated polygons")


def _leaves(points: np.ndarray, size: int) -> bool:
    """Whether a polygon reaches outside the size x size raster (its area may then be cut)."""
    return bool(points.min() < 0 or points.max() > size)


def exact_ties(rng: np.random.Generator) -> Outcome:
    """Vertices and edges through samples: integer and half-integer polygons, every API, every grid."""
    tally, polygons = Tally(), 0
    size = 10
    for k in range(60):
        sample = SAMPLES[k % 2]
        bits = (8, None, 0, 1)[k % 4]
        count = int(rng.integers(3, 7))
        offset = 0.5 if sample == "center" else 0.0
        contour = rng.integers(-1, size + 2, (count, 2)) + offset
        if rng.random() < 0.5:
            contour = contour / 2.0 + 0.5 * rng.integers(0, 2, (1, 2))  # half-pixel ties
        if len(np.unique(contour, axis=0)) < 3:
            continue
        polygons += 1
        compare_all(tally, contour, size, size, sample, bits)
    for shape in SHAPES.values():  # the catalog's tie cases, at their own sizes
        for sample in SAMPLES:
            polygons += 1
            for rule in RULES:
                want = exact.oracle_mask(
                    shape.polygon.contours, shape.width, shape.height, sample, rule, None
                )
                got = scan_convert(
                    shape.polygon, shape.width, shape.height, sample=sample, rule=rule,
                    subpixel_bits=None,
                ).mask  # fmt: skip
                tally.same(
                    got,
                    want,
                    f"scan_convert catalog {shape.name!r} sample={sample} rule={rule} bits=None",
                )
    return tally.outcome(f"{thousands(polygons)} polygons with ties")


def long_edge_drift(rng: np.random.Generator) -> Outcome:
    """Edges spanning 65,536 rows: every row's crossing exact, against the oracle."""
    tally, rows = Tally(), 0
    height, width = 65536, 6
    for k in range(4):
        sample = SAMPLES[k % 2]
        x_low, x_high = grid_points(rng, 0, width, 2, bits=8)
        spread = rng.uniform(0.25, 2.0)
        triangle = np.array([(x_low, 0.0), (x_high, float(height)), (x_low + spread, 3.0)])
        triangle = np.round(triangle * 256) / 256
        want = exact.oracle_mask([triangle], width, height, sample, "nonzero", 8)
        rows += height
        for name, got in (
            ("scan_convert", scan_convert(triangle, width, height, sample=sample).mask),
            ("rasterize_triangles", rasterize_triangles([triangle], width, height, sample=sample)),
            ("fill_polygons", fill_polygons([triangle], width, height, sample=sample)),
        ):
            tally.same(got, want, f"{name} sample={sample} triangle {round_list(triangle)}")
    return tally.outcome(f"{thousands(rows)} rows of 65,536-row edges")


def winding_and_parity(rng: np.random.Generator) -> Outcome:
    """Nested and overlapping contours: nonzero and evenodd against the exact winding number."""
    tally, polygons = Tally(), 0
    size = 14
    for k in range(40):
        sample = SAMPLES[k % 2]
        contours = []
        for _ in range(int(rng.integers(2, 5))):
            star = star_polygon(
                rng, grid_points(rng, 3, 11, 2), rng.uniform(1.5, 6), int(rng.integers(3, 8))
            )
            contours.append(star if rng.random() < 0.5 else star[::-1])
        winding = exact.sample_winding(exact.snap_contours(contours, 8), size, size, sample)
        polygons += 1
        for rule in RULES:
            want = exact.inside(winding, rule)
            for name, got in (
                ("scan_convert", scan_convert(contours, size, size, sample=sample, rule=rule).mask),
                ("fill_polygons", fill_polygons([contours], size, size, sample=sample, rule=rule)),
            ):
                tally.same(
                    got,
                    want,
                    f"{name} rule={rule} sample={sample} contours "
                    f"{[round_list(c) for c in contours]}",
                )
    return tally.outcome(f"{thousands(polygons)} multi-contour polygons x 2 rules")


def t_junctions(rng: np.random.Generator) -> Outcome:
    """A vertex of one polygon on the edge of another: no cracks, no double hits."""
    tally, samples, cases = Tally(), 0, 0
    width, height = 12, 10
    for k in range(40):
        sample = SAMPLES[k % 2]
        offset = 0.5 if sample == "center" else 0.0
        # A cut from p (bottom) to q (top) splits the box; m, a grid point on the cut, is a
        # vertex of the two right-hand pieces only.
        p = np.array([grid_points(rng, 2, 5, 1)[0], 0.0])
        q = np.array([grid_points(rng, 6, 9, 1)[0], float(height - 1)])
        parts = 2 ** int(rng.integers(1, 5))
        m = p + (q - p) * int(rng.integers(1, parts)) / parts
        r = np.array([width - 1.0, grid_points(rng, 1, height - 2, 1)[0]])
        a, b, c, d = (
            (0.0, 0.0),
            (width - 1.0, 0.0),
            (width - 1.0, height - 1.0),
            (0.0, height - 1.0),
        )
        pieces = [np.array(v) + offset for v in ([a, p, q, d], [p, b, r, m], [m, r, c, q])]
        outline = np.array([a, b, c, d]) + offset
        want = exact.oracle_mask([outline], width, height, sample, "nonzero", 8).astype(int)
        fans = [piece[[0, i, i + 1]] for piece in pieces for i in range(1, len(piece) - 1)]
        cases += 1
        samples += int(want.sum())
        for name, got in (
            ("fill_polygons", fill_polygons(pieces, width, height, sample=sample)),
            ("rasterize_triangles", rasterize_triangles(fans, width, height, sample=sample)),
        ):
            tally.same(
                got, want, f"{name} sample={sample} pieces {[round_list(x) for x in pieces]}"
            )
    return tally.outcome(f"{thousands(samples)} samples / {thousands(cases)} T-junctions")

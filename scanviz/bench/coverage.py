"""Coverage benchmark: anti-aliasing methods, run time against error from the exact area.

Scene (seeded): 20 polygons on a 256 x 256 raster — 8 random stars, 8 random
triangles and 4 catalog shapes scaled up (pentagram, bow tie, square with
hole, comb) — each drawn on its own (coverage is per polygon; times are summed
over the polygons). Vertices are snapped to 1/256 pixel once, so every method
sees the same polygon. Fill rule: nonzero.

Methods:

* point sampling: the `scan_convert` mask with center sampling;
* k x k supersampling (k = 2, 4, 8, 16): the polygon scaled by k, scan
  converted on a kW x kH raster with center sampling, box-filtered down (exact
  for powers of two);
* a-buffer pixel masks 4x4, 8x4, 8x8: covered bits / all bits of
  `scanviz.abuffer.masks.pixel_masks`;
* exact area (`area_coverage`), the reference (error 0 by definition);
* skia-python, when installed: an anti-aliased path fill into an A8 surface
  (y flipped, as skia is y-down).

Error is measured against the exact area over the pixels that matter: edge
pixels (0 < exact < 1) plus every pixel where the method disagrees with an
exact 0 or 1 (coverage where there is none, a hole in a full pixel). Table:
total ms, RMS and max error over those pixels, pooled over the polygons.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .. import catalog
from ..abuffer.area import area_coverage
from ..raster import scan_convert
from . import best_time, optional_module

SIZE = 256
BITS = 8
MASK_NAMES = ("4x4", "8x4", "8x8")


def _snapped(vertices: np.ndarray) -> np.ndarray:
    return np.rint(np.asarray(vertices, dtype=np.float64) * 2.0**BITS) / 2.0**BITS


def coverage_scene(count: int, size: int, seed: int = 7) -> list[list[np.ndarray]]:
    """`count` polygons (lists of snapped contours) on a `size` raster: stars, triangles, catalog."""
    rng = np.random.default_rng(seed)
    polygons = []
    catalog_names = ("pentagram", "bow_tie", "square_with_hole", "comb")
    for i in range(count):
        kind = i % 5
        if kind in (0, 1):  # star: 20..60 vertices, radius up to a quarter of the raster
            points = int(rng.integers(10, 31)) * 2
            center = rng.uniform(0.3 * size, 0.7 * size, 2)
            outer = rng.uniform(0.05 * size, 0.25 * size)
            angles = np.sort(rng.uniform(0, 2 * np.pi, points))
            radii = np.where(
                np.arange(points) % 2 == 0, outer, outer * rng.uniform(0.3, 0.7, points)
            )
            contours = [center + radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])]
        elif kind in (2, 3):  # triangle with vertices anywhere on the raster
            contours = [rng.uniform(0, size, (3, 2))]
        else:  # a catalog shape scaled from its 32-pixel raster, at a random offset
            shape = catalog.get(catalog_names[(i // 5) % len(catalog_names)])
            scale = size / 32 * rng.uniform(0.4, 0.9)
            offset = rng.uniform(0, size - 32 * scale, 2)
            contours = [c * scale + offset for c in shape.polygon.contours]
        polygons.append([_snapped(c) for c in contours])
    return polygons


def point_sampled(contours, size: int) -> np.ndarray:
    return scan_convert(contours, size, size, sample="center").mask.astype(np.float64)


def supersampled(contours, size: int, k: int) -> np.ndarray:
    """k x k center samples per pixel, averaged."""
    scaled = [c * k for c in contours]
    mask = scan_convert(scaled, k * size, k * size, sample="center", subpixel_bits=BITS).mask
    return mask.reshape(size, k, size, k).mean(axis=(1, 3))


def _mask_method(name: str) -> Callable | None:
    try:
        from ..abuffer.masks import MASK_LAYOUTS, pixel_masks, popcount
    except ImportError:
        return None
    cols, rows = MASK_LAYOUTS[name]

    def coverage(contours, size: int) -> np.ndarray:
        result = pixel_masks(contours, size, size, mask=name, subpixel_bits=BITS)
        image = np.zeros((size, size))
        image[result.ys, result.xs] = popcount(result.masks) / (cols * rows)
        return image

    return coverage


def _skia_method() -> Callable | None:
    skia = optional_module("skia")
    if skia is None:
        return None
    paint = skia.Paint(AntiAlias=True, Color=skia.ColorBLACK)

    def coverage(contours, size: int) -> np.ndarray:
        surface = skia.Surface.MakeRaster(skia.ImageInfo.MakeA8(size, size))
        path = skia.Path()
        for contour in contours:
            path.addPoly([skia.Point(x, size - y) for x, y in contour.tolist()], True)  # y-down
        path.setFillType(skia.PathFillType.kWinding)
        surface.getCanvas().drawPath(path, paint)
        alpha = surface.makeImageSnapshot().toarray(colorType=skia.kAlpha_8_ColorType)
        return alpha[::-1] / 255.0

    return coverage


def methods() -> list[tuple[str, Callable | None]]:
    """(name, coverage(contours, size) -> (size, size) float64, or None if unavailable)."""
    table: list[tuple[str, Callable | None]] = [("point sample (center)", point_sampled)]
    table += [
        (f"supersample {k}x{k}", lambda c, s, k=k: supersampled(c, s, k)) for k in (2, 4, 8, 16)
    ]
    table += [(f"a-buffer mask {name}", _mask_method(name)) for name in MASK_NAMES]
    table.append(("skia anti-aliased fill", _skia_method()))
    table.append(("exact area", lambda c, s: area_coverage(c, s, s, subpixel_bits=BITS)))
    return table


def coverage_errors(coverage: np.ndarray, exact: np.ndarray) -> np.ndarray:
    """Errors at edge pixels and at pixels where `coverage` disagrees with an exact 0 or 1."""
    edge = (exact > 0) & (exact < 1)
    wrong_where_decided = ((exact == 0) | (exact == 1)) & (coverage != exact)
    return (coverage - exact)[edge | wrong_where_decided]


def run_coverage(*, quick: bool = False, plot: str | None = "coverage.png") -> list[dict]:
    """Time each method on the scene, print the table, save the plot, return the rows."""
    count, size = (5, 64) if quick else (20, SIZE)
    scene = coverage_scene(count, size)
    exact = [area_coverage(c, size, size, subpixel_bits=BITS) for c in scene]
    repeat = 1 if quick else 3
    print(
        f"coverage benchmark: {count} polygons drawn one at a time on {size}x{size}, nonzero rule, "
        f"subpixel_bits={BITS}; error = method - exact area"
    )
    print(f"{'method':<26}{'ms':>10}{'RMS error':>12}{'max error':>12}{'pixels':>9}")
    rows = []
    for name, method in methods():
        if method is None:
            print(f"{name:<26}{'not available':>43}")
            rows.append({"method": name, "available": False})
            continue
        seconds = best_time(lambda m=method: [m(c, size) for c in scene], repeat=repeat)
        errors = np.concatenate(
            [coverage_errors(method(c, size), e) for c, e in zip(scene, exact, strict=True)]
        )
        rms = float(np.sqrt(np.mean(errors**2))) if len(errors) else 0.0
        worst = float(np.abs(errors).max()) if len(errors) else 0.0
        print(f"{name:<26}{seconds * 1e3:>10.2f}{rms:>12.2e}{worst:>12.2e}{len(errors):>9}")
        rows.append(
            {"method": name, "available": True, "ms": seconds * 1e3, "rms": rms, "max": worst}
        )
    print(
        "pixels = edge pixels (0 < exact < 1) plus pixels where the method misses an exact 0 or 1"
    )
    if plot:
        save_plot(rows, plot)
        print(f"plot: {plot}")
    return rows


def save_plot(rows: list[dict], path: str) -> None:
    """Log-log plot of RMS error against time, one labelled point per method."""
    from matplotlib.figure import Figure  # no pyplot: leaves the caller's backend alone

    measured = [row for row in rows if row["available"]]
    floor = min([row["rms"] for row in measured if row["rms"] > 0], default=1e-3) / 10
    figure = Figure(figsize=(7, 5))
    axes = figure.subplots()
    for row in measured:
        error = row["rms"] if row["rms"] > 0 else floor  # exact area: error 0, drawn at the floor
        label = row["method"] if row["rms"] > 0 else f"{row['method']} (error 0)"
        axes.loglog(row["ms"], error, "o")
        axes.annotate(
            label, (row["ms"], error), textcoords="offset points", xytext=(5, 3), fontsize=8
        )
    axes.set_xlabel("time per scene (ms)")
    axes.set_ylabel("RMS coverage error at edge pixels")
    axes.set_title("Anti-aliasing: error against time")
    axes.grid(True, which="both", alpha=0.3)
    axes.margins(x=0.3, y=0.15)  # room for the labels
    figure.tight_layout()
    figure.savefig(path, dpi=120)

"""Anti-aliasing benchmark: DISLOP against the world's anti-aliasers, error from the exact area and time.

Three scenes (seeded), each drawn one shape at a time on a square raster:

* lines: a fan of 1-pixel-wide segments at angles 0..180 degrees (slopes 0
  to 1, steeper and negative), random sub-pixel centres, all the same length;
* edges: random triangles and stars (20..40 vertices), vertices snapped to
  1/256 pixel so that every method sees the same polygon;
* disks: random sub-pixel centres, radii 2 .. size/4.

The reference is the exact area of each pixel inside the shape: the band's
rectangle (`exact_band_line`), the polygon (`area_coverage`), the disk (closed
form, `disk_coverage`). Error is measured as in `bench coverage`: over the
edge pixels (0 < exact < 1) and every pixel where a method disagrees with an
exact 0 or 1 (a halo, a hole); max and RMS, pooled over the shapes.
"Intensity" is a shape's total coverage over its exact area (for a line: the
intensity per unit length); the table gives its min and max over the shapes,
and for lines a second table its mean by angle, folded into 0..45 degrees.
Time is the median of repeated runs over the whole scene after a warm-up
run (numba compiles or loads its kernels).

Methods missing at run time (DISLOP not yet in the tree, a peer library not
installed) are printed as "not available".
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import njit

from ..abuffer.area import area_coverage
from ..abuffer.masks import pixel_masks, popcount
from ..antialias import peers
from ..progress import progress
from ..raster import scan_convert
from ..raster.lines import paint_lines
from . import best_time
from .antialias_peers import LIBRARIES, PEERS, skia_polygon
from .coverage import coverage_errors, supersampled

BITS = 8
KINDS = ("line", "edge", "disk")
ANGLE_BINS = (0.0, 10.0, 20.0, 30.0, 40.0, 45.0)  # folded angle (degrees) bins of the lines table


def _dislop(name: str):
    """A DISLOP entry point if the module exists yet, else None."""
    try:
        if name == "line":
            from ..antialias.line import dislop_line as function
        elif name == "edge":
            from ..antialias.edge_algorithm import dislop_edge as function
        else:
            from ..antialias.circle import dislop_disk as function
    except ImportError:
        return None
    return function


# ---------------------------------------------------------------- scenes


def line_scene(count: int, size: int, seed: int = 13) -> list[tuple[np.ndarray, np.ndarray]]:
    """`count` segments of length 0.6 size at angles spread over 0..180 degrees, random sub-pixel centres."""
    rng = np.random.default_rng(seed)
    length = 0.6 * size
    lines = []
    for angle in np.linspace(0.0, 180.0, count, endpoint=False) + rng.uniform(
        0, 180 / count, count
    ):
        a = math.radians(angle)
        centre = rng.uniform(0.45 * size, 0.55 * size, 2)
        half = 0.5 * length * np.array([math.cos(a), math.sin(a)])
        lines.append((centre - half, centre + half))
    return lines


def edge_scene(count: int, size: int, seed: int = 17) -> list[np.ndarray]:
    """`count` polygons: random triangles and stars, vertices on the 1/256 grid."""
    rng = np.random.default_rng(seed)
    polygons = []
    for i in range(count):
        if i % 2 == 0:
            vertices = rng.uniform(0.05 * size, 0.95 * size, (3, 2))
        else:
            points = int(rng.integers(10, 21)) * 2
            angles = np.sort(rng.uniform(0, 2 * np.pi, points))
            outer = rng.uniform(0.15 * size, 0.4 * size)
            radii = np.where(
                np.arange(points) % 2 == 0, outer, outer * rng.uniform(0.4, 0.8, points)
            )
            centre = rng.uniform(0.45 * size, 0.55 * size, 2)
            vertices = centre + radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])
        polygons.append(np.rint(vertices * 2.0**BITS) / 2.0**BITS)
    return polygons


def disk_scene(count: int, size: int, seed: int = 19) -> list[tuple[np.ndarray, float]]:
    """`count` (centre, radius) disks inside the raster."""
    rng = np.random.default_rng(seed)
    disks = []
    for _ in range(count):
        radius = float(rng.uniform(2.0, size / 4))
        disks.append((rng.uniform(radius + 1, size - radius - 1, 2), radius))
    return disks


# ---------------------------------------------------------------- the exact disk


@njit(cache=True)
def _disk_quadrant(x, y, r):  # pragma: no cover - compiled
    """Area of the disk of radius r at the origin inside {X <= x, Y <= y}."""
    x, y = min(max(x, -r), r), min(max(y, -r), r)
    c = math.sqrt(max(r * r - y * y, 0.0))  # the chord at height y spans -c..c

    def column_integral(a, b, full):  # integral of the chord (full) or of (s + y) over [a, b]
        if b <= a:
            return 0.0
        ha = 0.5 * (a * math.sqrt(r * r - a * a) + r * r * math.asin(a / r))
        hb = 0.5 * (b * math.sqrt(r * r - b * b) + r * r * math.asin(b / r))
        return 2.0 * (hb - ha) if full else (hb - ha) + y * (b - a)

    if y >= 0.0:  # outside |X| <= c the whole chord is below y
        return (
            column_integral(-r, min(x, -c), True)
            + column_integral(-c, min(x, c), False)
            + column_integral(c, x, True)
        )
    return column_integral(-c, min(x, c), False)  # only |X| < c reaches below y


@njit(cache=True)
def _disk_kernel(cx, cy, r, image):  # pragma: no cover - compiled
    height, width = image.shape
    for y in range(max(0, math.floor(cy - r)), min(height, math.ceil(cy + r) + 1)):
        for x in range(max(0, math.floor(cx - r)), min(width, math.ceil(cx + r) + 1)):
            x0, y0, x1, y1 = x - cx, y - cy, x + 1 - cx, y + 1 - cy
            image[y, x] = (
                _disk_quadrant(x1, y1, r)
                - _disk_quadrant(x0, y1, r)
                - _disk_quadrant(x1, y0, r)
                + _disk_quadrant(x0, y0, r)
            )


def disk_coverage(center, radius: float, width: int, height: int) -> np.ndarray:
    """Exact area of every pixel inside the disk (closed form: inclusion-exclusion of quadrants).

    >>> round(float(disk_coverage((8.3, 7.9), 5.5, 16, 16).sum()), 9) == round(math.pi * 5.5**2, 9)
    True
    """
    image = np.zeros((height, width))
    if radius > 0:
        _disk_kernel(float(center[0]), float(center[1]), float(radius), image)
    return image


def _disk_samples(center, radius: float, size: int, k: int) -> np.ndarray:
    """k x k point samples per pixel inside the disk, averaged (numpy over the disk's box)."""
    image = np.zeros((size, size))
    lo = np.clip(np.floor(np.asarray(center) - radius).astype(int), 0, size)
    hi = np.clip(np.ceil(np.asarray(center) + radius).astype(int) + 1, 0, size)
    xs = (np.arange(lo[0] * k, hi[0] * k) + 0.5) / k
    ys = (np.arange(lo[1] * k, hi[1] * k) + 0.5) / k
    inside = (xs[None, :] - center[0]) ** 2 + (ys[:, None] - center[1]) ** 2 < radius * radius
    box = inside.reshape(len(ys) // k, k, len(xs) // k, k).mean(axis=(1, 3))
    image[lo[1] : hi[1], lo[0] : hi[0]] = box
    return image


# ---------------------------------------------------------------- methods


def _line_methods(size: int) -> list[tuple[str, Callable | None]]:
    dislop = _dislop("line")

    def midpoint(p0, p1):  # the pixels whose squares hold the endpoints, binary
        ends = np.floor([[p0[0], p0[1], p1[0], p1[1]]]).astype(np.int64)
        return paint_lines(ends, size, size).astype(np.float64)

    def masks(p0, p1):
        return peers.abuffer_line(p0, p1, size, size, mask="8x8")

    table: list[tuple[str, Callable | None]] = [
        ("midpoint (binary)", midpoint),
        ("Wu", lambda p0, p1: peers.wu_line(p0, p1, size, size)),
        ("Gupta-Sproull", lambda p0, p1: peers.gupta_sproull_line(p0, p1, size, size)),
    ]
    table += [
        (f"supersample {k}x{k}", lambda p0, p1, k=k: peers.supersampled_line(p0, p1, size, size, k))
        for k in (2, 4, 8)
    ]
    table.append(("a-buffer mask 8x8", masks))
    for label, exact in (("DISLOP_L (printed)", False), ("DISLOP_L exact", True)):
        method = None if dislop is None else (lambda p0, p1, e=exact: dislop(p0, p1, size, size, exact=e))  # fmt: skip
        table.append((label, method))
    table += _peer_methods("line", size)
    if "skia" in PEERS:  # skia strokes a 1-px line as a hairline; its fill of the band is area AA
        table.append(("skia band fill", lambda p0, p1: _band_fill(p0, p1, size)))
    table.append(("exact band", lambda p0, p1: peers.exact_band_line(p0, p1, size, size)))
    return table


def _band_fill(p0, p1, size: int) -> np.ndarray:
    corners = peers.band_rectangle(p0, p1, size, size)
    return np.zeros((size, size)) if corners is None else skia_polygon(corners, size, size)


def _edge_methods(size: int) -> list[tuple[str, Callable | None]]:
    dislop = _dislop("edge")

    def masks(vertices):
        result = pixel_masks(vertices, size, size, mask="8x8", subpixel_bits=BITS)
        image = np.zeros((size, size))
        image[result.ys, result.xs] = popcount(result.masks) / 64.0
        return image

    table: list[tuple[str, Callable | None]] = [
        (
            "point sample (center)",
            lambda v: scan_convert(v, size, size, sample="center").mask.astype(np.float64),
        ),  # fmt: skip
    ]
    table += [
        (f"supersample {k}x{k}", lambda v, k=k: supersampled([v], size, k)) for k in (2, 4, 8)
    ]
    table.append(("a-buffer mask 8x8", masks))
    table.append(("DISLOP_E", None if dislop is None else (lambda v: dislop(v, size, size))))
    table += _peer_methods("edge", size)
    table.append(("exact area", lambda v: area_coverage(v, size, size, subpixel_bits=BITS)))
    return table


def _disk_methods(size: int) -> list[tuple[str, Callable | None]]:
    dislop = _dislop("disk")
    table: list[tuple[str, Callable | None]] = [
        ("point sample (center)", lambda c, r: _disk_samples(c, r, size, 1)),
    ]
    table += [(f"supersample {k}x{k}", lambda c, r, k=k: _disk_samples(c, r, size, k)) for k in (2, 4, 8)]  # fmt: skip
    table.append(("DISLOP_S", None if dislop is None else (lambda c, r: dislop(c, r, size, size))))
    table += _peer_methods("disk", size)
    table.append(("exact area", lambda c, r: disk_coverage(c, r, size, size)))
    return table


def _peer_methods(kind: str, size: int) -> list[tuple[str, Callable | None]]:
    table: list[tuple[str, Callable | None]] = []
    for library in LIBRARIES:
        function = PEERS.get(library, {}).get(kind)
        table.append((library, None if function is None else (lambda *s, f=function: f(*s, size, size))))  # fmt: skip
    return table


def methods(kind: str, size: int) -> list[tuple[str, Callable | None]]:
    """(name, draw(*shape) -> (size, size) float64, or None if not available) for "line", "edge", "disk"."""
    return {"line": _line_methods, "edge": _edge_methods, "disk": _disk_methods}[kind](size)


# ---------------------------------------------------------------- the run


def _folded_angle(p0, p1) -> float:
    """The segment's angle folded into the first octant, 0..45 degrees."""
    dx, dy = abs(p1[0] - p0[0]), abs(p1[1] - p0[1])
    return math.degrees(math.atan2(min(dx, dy), max(dx, dy)))


def run_antialias(*, quick: bool = False, plot: str | None = None) -> list[dict]:
    """Time and measure every method on the three scenes, print the tables, return the rows.

    ``quick``: a 64 x 64 raster, 12 lines, 4 polygons and 4 disks, one timed run.
    `plot` is a file for the time-against-error plot (log-log) and intensity against angle.
    """
    size, counts, repeat = (64, (12, 4, 4), 1) if quick else (128, (48, 12, 12), 5)
    scenes = {
        "line": line_scene(counts[0], size),
        "edge": [(polygon,) for polygon in edge_scene(counts[1], size)],
        "disk": disk_scene(counts[2], size),
    }
    print(
        f"anti-aliasing benchmark: {size}x{size}, {counts[0]} lines (1 px wide, length "
        f"{0.6 * size:g}), {counts[1]} polygons, {counts[2]} disks, one shape at a time; "
        f"time = median of {repeat} run(s) over the scene"
    )
    tables = {kind: methods(kind, size) for kind in KINDS}
    rows, lines = [], []
    with progress(sum(len(t) for t in tables.values()), "antialias bench") as bar:
        for kind in KINDS:
            shapes = scenes[kind]
            exact = [tables[kind][-1][1](*shape) for shape in shapes]
            for name, method in tables[kind]:
                rows.append(_measure(kind, name, method, shapes, exact, repeat))
                bar.update(1)
    header = f"{'shapes':<7}{'method':<24}{'ms':>9}{'max err':>9}{'RMS err':>9}{'intensity min..max':>20}"
    lines.append(header)
    for row in rows:
        lines.append(_format(row))
    print("\n".join(lines))
    print(
        "error over edge pixels and pixels that miss an exact 0 or 1; intensity = total coverage / "
        "exact area (lines: per unit length)"
    )
    print(_angle_table([r for r in rows if r["kind"] == "line"]))
    if plot:
        save_plot(rows, plot)
        print(f"plot: {plot}")
    return rows


def _measure(kind, name, method, shapes, exact, repeat) -> dict:
    row = {"kind": kind, "method": name, "available": method is not None}
    if method is None:
        return row
    seconds = best_time(lambda: [method(*shape) for shape in shapes], repeat=repeat)
    images = [method(*shape) for shape in shapes]
    errors = np.concatenate([coverage_errors(i, e) for i, e in zip(images, exact, strict=True)])
    intensity = np.array([i.sum() / e.sum() for i, e in zip(images, exact, strict=True)])
    row.update(
        ms=1e3 * seconds,
        max=float(np.abs(errors).max()) if len(errors) else 0.0,
        rms=float(np.sqrt(np.mean(errors**2))) if len(errors) else 0.0,
        intensity=intensity,
    )
    if kind == "line":
        row["angles"] = np.array([_folded_angle(*shape) for shape in shapes])
    return row


def _format(row: dict) -> str:
    head = f"{row['kind']:<7}{row['method']:<24}"
    if not row["available"]:
        return head + f"{'not available':>16}"
    spread = f"{row['intensity'].min():.3f}..{row['intensity'].max():.3f}"
    return head + f"{row['ms']:>9.2f}{row['max']:>9.4f}{row['rms']:>9.4f}{spread:>20}"


def _angle_table(rows: list[dict]) -> str:
    """Mean intensity per unit length of each line method by folded angle."""
    bins = list(zip(ANGLE_BINS, ANGLE_BINS[1:], strict=False))
    labels = "".join(f"{f'{a:g}-{b:g}°':>9}" for a, b in bins)
    out = [
        f"lines: intensity per unit length by angle (folded into 0..45°)\n{'method':<24}{labels}"
    ]
    for row in rows:
        if not row["available"]:
            continue
        cells = []
        for a, b in bins:
            chosen = row["intensity"][(row["angles"] >= a) & (row["angles"] < b + (b == 45.0))]
            cells.append(f"{chosen.mean():>9.3f}" if len(chosen) else f"{'-':>9}")
        out.append(f"{row['method']:<24}" + "".join(cells))
    return "\n".join(out)


def save_plot(rows: list[dict], path: str) -> None:
    """Log-log RMS error against time per scene, and the lines' intensity against angle."""
    import matplotlib
    from matplotlib.figure import Figure  # no pyplot: leaves the caller's backend alone

    measured = [row for row in rows if row["available"]]
    floor = 1e-6  # exact methods (error 0 up to rounding) are drawn here
    colours = matplotlib.colormaps["tab20"].colors
    figure = Figure(figsize=(15, 4.5))
    axes = figure.subplots(1, 4)
    for axis, kind in zip(axes[:3], KINDS, strict=True):
        for row in (r for r in measured if r["kind"] == kind):
            error = max(row["rms"], floor)
            label = row["method"] + (" (exact)" if row["rms"] < floor else "")
            axis.loglog(row["ms"], error, "o")
            axis.annotate(label, (row["ms"], error), textcoords="offset points", xytext=(4, 2), fontsize=7)  # fmt: skip
        axis.set_title(f"{kind}s: RMS error against time")
        axis.set_xlabel("time per scene (ms)")
        axis.set_ylabel("RMS coverage error")
        axis.grid(True, which="both", alpha=0.3)
        axis.margins(x=0.3, y=0.15)
    for i, row in enumerate(r for r in measured if r["kind"] == "line"):
        order = np.argsort(row["angles"])
        axes[3].plot(row["angles"][order], row["intensity"][order], ".-", color=colours[i % 20], label=row["method"], lw=0.8)  # fmt: skip
    axes[3].set_title("lines: intensity per unit length")
    axes[3].set_xlabel("angle folded into 0..45 degrees")
    axes[3].legend(fontsize=6)
    figure.tight_layout()
    figure.savefig(path, dpi=100)

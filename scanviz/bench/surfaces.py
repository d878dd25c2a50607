"""Grid-surface benchmark: the floating horizon, the Floating Perimeter Algorithm and the z-buffer.

The comparisons of Wang (1989) §2.4, Tables 2-2 to 2-4 (spec §1.7), rerun on
scanviz. Surfaces: the smooth exp(-x^2 - y^2) and the random heights of
`GridSurface.random` (seed 0, uniform on [0, 1)), both on [-2, 2]^2 with
n x n points; the viewpoint (6, 8, 3) (viewing case 9) looks at the centre of
the grid's bounding box. Algorithms (`ALGORITHMS`), each timed from the
surface and the view to the finished image:

* ``fha``: `floating_horizon` (the curves y = const);
* ``fpa-lines``: `floating_perimeter` in lines mode (the dissertation's FPA);
* ``fpa-flat``, ``fpa-phong``: `floating_perimeter` in surface mode, front to
  back with the coverage mask, flat or Phong shaded;
* ``zbuf-flat``, ``zbuf-phong``: ``render(surface.scene(view, w, h), w, h)``,
  the z-buffer, flat or Phong shaded (Phong is `render`'s default).

Every algorithm runs once on a 5 x 5 grid first (numba compiles or loads its
kernels), then at least `repeat` times per cell, and more until the cell
has taken `LEAST_SECONDS` (fast cells: the median steadies): the median
is printed. Times are the process's CPU time (`time.process_time`), as the
dissertation's are CPU seconds; on a shared machine they are much steadier
than wall time. Time is measured against grid size at one image side and
against image side at one grid size; the growth exponent k of time ~ facets^k and time ~ side^k is the
least-squares slope on log-log (`scanviz.bench.visibility.growth_exponent`,
runs under 1 ms left out). The dissertation's 1985 VAX-11/780 seconds
(`WANG_SMOOTH`, `WANG_RANDOM`) are printed beside ours only as trends: ratios
and exponents, never seconds.

Storage: Table 2-4's byte formulas (`fha_storage`, `anderson_storage`,
`fpa_storage`) beside the bytes of the arrays a scanviz run actually holds
(`measured_storage`), at Wang's own Nx = Ny = 40, HR x VR = 768 x 480.
Anderson's algorithm cannot be built from the dissertation's summary
(spec §1.5): it is a formula row only. Results and discussion:
``docs/surfaces-bench.md``.
"""

from __future__ import annotations

import statistics
from collections.abc import Callable
from dataclasses import dataclass
from time import process_time

import numpy as np

from ..pipeline import render
from ..progress import progress
from ..surfaces import GridSurface, View, floating_horizon, floating_perimeter
from ..surfaces.grid import _count, gaussian_height
from .visibility import FIT_FLOOR, growth_exponent

GRIDS = (10, 20, 30, 40, 50, 60, 100, 200)  # points per side
IMAGES = (100, 200, 300, 400, 500, 600)  # image side, as Tables 2-2/2-3
GRID_IMAGE = 300  # the image side of the sweep over grid sizes
IMAGE_GRID = 60  # the grid of the sweep over image sides
REPEAT = 3
LEAST_SECONDS = 0.25  # a fast cell runs until it has taken this long: the median steadies
MAX_RUNS = 100
VIEWPOINT = (6.0, 8.0, 3.0)
DOMAIN = (-2.0, 2.0)
SURFACES = ("smooth", "random")
STORAGE_GRID, STORAGE_RASTER = 40, (768, 480)  # Wang's example of §2.4: 34,250 bytes for the FPA

ALGORITHMS: dict[str, Callable[[GridSurface, View, int], object]] = {
    "fha": lambda s, v, n: floating_horizon(s, v, n, n),
    "fpa-lines": lambda s, v, n: floating_perimeter(s, v, n, n, "lines"),
    "fpa-flat": lambda s, v, n: floating_perimeter(s, v, n, n, "surface", shading="flat"),
    "fpa-phong": lambda s, v, n: floating_perimeter(s, v, n, n, "surface", shading="phong"),
    "zbuf-flat": lambda s, v, n: render(s.scene(v, n, n), n, n, shading="flat"),
    "zbuf-phong": lambda s, v, n: render(s.scene(v, n, n), n, n),
}
"""Each algorithm as ``f(surface, view, side)``: an image of side x side pixels."""

# Tables 2-2 (smooth) and 2-3 (random) of Wang 1989, seconds on a VAX-11/780, as the spec reads the
# OCR: {grid: {image side or "anderson": seconds}}. The cells the OCR lost hold the spec's estimates
# (2.3 for its "2.?0", ...); WANG_ESTIMATED lists them, never used in a ratio or a fit.
WANG_SMOOTH = {
    10: {100: 0.17, 200: 0.30, 300: 0.40, 400: 0.52, 500: 0.58, 600: 0.73, "anderson": 0.184},
    20: {100: 0.5, 200: 0.70, 300: 0.87, 400: 1.1, 500: 1.37, 600: 1.57, "anderson": 0.725},
    30: {100: 0.88, 200: 1.25, 300: 1.57, 400: 1.88, 500: 2.25, 600: 2.58, "anderson": 1.6},
    40: {100: 1.50, 200: 1.90, 300: 2.3, 400: 2.76, 500: 3.23, 600: 3.68, "anderson": 2.886},
    50: {100: 2.20, 200: 2.72, 300: 3.30, 400: 3.80, 500: 4.33, 600: 4.95, "anderson": 4.527},
    60: {100: 2.93, 200: 3.65, 300: 4.30, 400: 4.9, 500: 5.57, 600: 6.18, "anderson": 6.532},
}
WANG_RANDOM = {
    10: {100: 0.22, 200: 0.35, 300: 0.45, 400: 0.63, 500: 0.78, 600: 0.93, "anderson": 0.221},
    20: {100: 0.62, 200: 0.97, 300: 1.32, 400: 1.67, 500: 1.98, 600: 2.40, "anderson": 0.99},
    30: {100: 1.27, 200: 1.97, 300: 2.62, 400: 3.28, 500: 3.98, 600: 4.67, "anderson": 2.315},
    40: {100: 2.20, 200: 3.28, 300: 4.35, 400: 5.45, 500: 6.53, 600: 7.65, "anderson": 4.2},
    50: {100: 3.42, 200: 5.13, 300: 6.87, 400: 8.55, 500: 10.22, 600: 11.98, "anderson": 6.515},
    60: {100: 4.78, 200: 7.10, 300: 9.48, 400: 11.8, 500: 14.13, 600: 16.28, "anderson": 9.534},
}
WANG_ESTIMATED = {
    "smooth": {(20, 100), (20, 400), (30, "anderson"), (40, 300), (60, 400)},
    "random": {(20, "anderson"), (40, "anderson"), (60, 400)},
}
WANG_TABLES = {"smooth": WANG_SMOOTH, "random": WANG_RANDOM}

# --- storage: Table 2-4 ---------------------------------------------------------------------------

PURPOSES = (
    "grid points",
    "viewpoint, direction",
    "viewing case",
    "image size",
    "horizons / perimeters",
    "pseudoangles, radii",
    "enumerated facets",
    "point flags",
    "edge flags",
    "visible-point buffer",
)
"""Table 2-4's rows, in its order."""
SCANVIZ_PURPOSES = (
    "projected points",
    "edge list",
    "raster points",
    "mesh",
    "depth + polygon buffers",
    "output",
    "output image",
)
"""The rows `measured_storage` adds for arrays Table 2-4 has no row for."""


def _check_sizes(**sizes: object) -> None:
    for name, value in sizes.items():
        _count(name, value, 1 if name in ("hr", "vr") else 2)  # grid points >= 2, pixels >= 1


def fha_storage(nx: int, hr: int) -> dict[str, int]:
    """Table 2-4's FHA column in bytes, per purpose (float, int 4 bytes; short 2).

    ``float gp[Nx][3]`` (one curve at a time), ``float VP[3], VA[3]``,
    ``short up[HR], low[HR]``, ``int Cflag, Pflag``.

    >>> fha_storage(40, 768)["horizons / perimeters"]
    3072
    """
    _check_sizes(nx=nx, hr=hr)
    return {
        "grid points": 12 * nx,
        "viewpoint, direction": 24,
        "horizons / perimeters": 4 * hr,
        "point flags": 8,
    }


def anderson_storage(nx: int, ny: int) -> dict[str, int]:
    """Table 2-4's Anderson column in bytes, per purpose (a formula only: see the module).

    ``float gp[Nx][Ny][3]``, ``float VP[3], VA[3]``, ``short view_case``,
    ``short in[(Nx+Ny)*2][2], out[(Nx+Ny)*2][2]``, ``float a[Nx][Ny], r[Nx][Ny]``.

    >>> anderson_storage(40, 40)["pseudoangles, radii"]
    12800
    """
    _check_sizes(nx=nx, ny=ny)
    return {
        "grid points": 12 * nx * ny,
        "viewpoint, direction": 24,
        "viewing case": 2,
        "horizons / perimeters": 16 * (nx + ny),
        "pseudoangles, radii": 8 * nx * ny,
    }


def fpa_storage(nx: int, ny: int, hr: int, vr: int) -> dict[str, int]:
    """Table 2-4's FPA column in bytes, per purpose (struct facet is 3 shorts, 6 bytes).

    ``float gp[Nx][Ny][3]``, ``float VP[3], VA[3]``, ``short view_case``,
    ``short image_size``, ``short top[HR], bottom[HR], right[VR], left[VR]``,
    ``struct facet fcs[(Nx-1)*(Ny-1)]``, ``unsigned char vifg[50], ivfg[50]``,
    ``unsigned char tvifg, tivfg``, ``short Tvp; short Bbuf[200][2]``.

    >>> fpa_storage(40, 40, 768, 480)["enumerated facets"]
    9126
    """
    _check_sizes(nx=nx, ny=ny, hr=hr, vr=vr)
    return {
        "grid points": 12 * nx * ny,
        "viewpoint, direction": 24,
        "viewing case": 2,
        "image size": 2,
        "horizons / perimeters": 4 * hr + 4 * vr,
        "enumerated facets": 6 * (nx - 1) * (ny - 1),
        "point flags": 100,
        "edge flags": 2,
        "visible-point buffer": 2 + 800,
    }


def fha_storage_bytes(nx: int, hr: int) -> int:
    """The FHA's bytes by Table 2-4: 12 Nx + 24 + 4 HR + 8.

    >>> fha_storage_bytes(40, 768)
    3584
    """
    return sum(fha_storage(nx, hr).values())


def anderson_storage_bytes(nx: int, ny: int) -> int:
    """Anderson's bytes by Table 2-4: 12 Nx Ny + 24 + 2 + 16 (Nx + Ny) + 8 Nx Ny.

    >>> anderson_storage_bytes(40, 40), anderson_storage_bytes(50, 50)
    (33306, 51626)
    """
    return sum(anderson_storage(nx, ny).values())


def fpa_storage_bytes(nx: int, ny: int, hr: int, vr: int) -> int:
    """The FPA's bytes by Table 2-4: 12 Nx Ny + 28 + 4 (HR + VR) + 6 (Nx - 1)(Ny - 1) + 906.

    >>> fpa_storage_bytes(40, 40, 768, 480), fpa_storage_bytes(50, 50, 768, 480)
    (34250, 50330)
    """
    return sum(fpa_storage(nx, ny, hr, vr).values())


def _nbytes(*arrays: np.ndarray) -> int:
    return sum(int(a.nbytes) for a in arrays)


def measured_storage(surface: GridSurface, view: View, width: int, height: int) -> dict[str, dict]:
    """Bytes of the arrays one untraced run of each scanviz algorithm holds, per purpose.

    Returns ``{"fha": {...}, "fpa": {...}, "zbuffer": {...}}`` keyed by the
    `PURPOSES` of Table 2-4 where one applies, then `SCANVIZ_PURPOSES`:
    "projected points" (screen float64 and, for the FPA, pixel int64
    coordinates of every grid point, recomputed as the run computes them),
    "edge list", "raster points" (every point of every edge, kept for the
    result), "mesh", "depth + polygon buffers", "output" (segments and the
    bool line raster) and "output image" ((H, W, 3) float64). Python objects
    (tuples, ints) are not counted.

    >>> from scanviz.surfaces import gaussian
    >>> bytes_ = measured_storage(gaussian(5), View((6, 8, 3), (-6, -8, -3)), 16, 12)
    >>> bytes_["fpa"]["horizons / perimeters"], bytes_["fha"]["horizons / perimeters"]
    (448, 256)
    """
    grid = _nbytes(surface.x, surface.y, surface.z)
    viewing = np.array([*view.point, *view.direction]).nbytes
    screen = view.screen_from_world(surface.points(), width, height)[0]
    horizon = floating_horizon(surface, view, width, height)
    lines = floating_perimeter(surface, view, width, height, "lines")
    scene = surface.scene(view, width, height)
    zbuffer = render(scene, width, height)
    mesh = scene.objects[0].mesh
    enumeration, edges, perimeter = lines.enumeration, lines.edges, lines.perimeter
    return {
        "fha": {
            "grid points": grid,
            "viewpoint, direction": viewing,
            "horizons / perimeters": _nbytes(horizon.up, horizon.low),
            "projected points": screen.nbytes,
            "output": _nbytes(horizon.segments, horizon.lines),
            "output image": horizon.image.nbytes,
        },
        "fpa": {
            "grid points": grid,
            "viewpoint, direction": viewing,
            "horizons / perimeters": _nbytes(
                perimeter.top, perimeter.bottom, perimeter.right, perimeter.left
            ),
            "enumerated facets": _nbytes(
                enumeration.order, enumeration.classes, enumeration.sequence
            ),
            "point flags": _nbytes(lines.visible, lines.on_perimeter),
            "visible-point buffer": 0,  # the compiled pass merges each facet's points in place
            "projected points": 2 * screen.nbytes,  # float screen and int64 pixel coordinates
            "edge list": _nbytes(edges.edges, edges.facet),
            "raster points": _nbytes(lines.points, lines.point_edge),
            "output": _nbytes(lines.segments, lines.lines),
            "output image": lines.image.nbytes,
        },
        "zbuffer": {
            "grid points": grid,
            "viewpoint, direction": viewing,
            "mesh": _nbytes(mesh.positions, *mesh.faces),
            "depth + polygon buffers": _nbytes(zbuffer.depth, zbuffer.polygon),
            "output image": zbuffer.image.nbytes,
        },
    }


def print_storage(surface: GridSurface, view: View, width: int, height: int) -> dict[str, dict]:
    """Print Table 2-4's formulas beside `measured_storage`; return both, keyed by column."""
    nx, ny = surface.nx, surface.ny
    measured = measured_storage(surface, view, width, height)
    columns = {
        "FHA 1985": fha_storage(nx, width),
        "FHA ours": measured["fha"],
        "Anderson 1985": anderson_storage(nx, ny),
        "FPA 1985": fpa_storage(nx, ny, width, height),
        "FPA ours": measured["fpa"],
        "z-buf ours": measured["zbuffer"],
    }
    print(
        f"storage (bytes) at Nx = {nx}, Ny = {ny}, HR x VR = {width} x {height}: "
        "Table 2-4's formulas (1985: float/int 4 bytes, short 2) beside the arrays of a scanviz run"
    )
    print(f"{'purpose':<24}" + "".join(f"{name:>14}" for name in columns))
    for purpose in PURPOSES + SCANVIZ_PURPOSES:
        cells = [column.get(purpose) for column in columns.values()]
        print(f"{purpose:<24}" + "".join(f"{'-' if c is None else f'{c:,}':>14}" for c in cells))
    totals = [sum(column.values()) for column in columns.values()]
    print(f"{'total':<24}" + "".join(f"{t:,}".rjust(14) for t in totals))
    no_image = [sum(v for p, v in c.items() if p != "output image") for c in columns.values()]
    print(f"{'total without image':<24}" + "".join(f"{t:,}".rjust(14) for t in no_image))
    print(
        "Anderson: formula only -- his algorithm cannot be built from the dissertation's summary "
        "(spec §1.5); ours: .nbytes of the run's arrays (float64/int64; Python objects not counted)"
    )
    return columns


# --- timing ---------------------------------------------------------------------------------------


def bench_surface(kind: str, n: int) -> GridSurface:
    """The smooth exp(-x^2 - y^2) or the random surface (seed 0) on [-2, 2]^2, n x n points.

    >>> bench_surface("random", 3).z.shape, float(bench_surface("smooth", 3).z[1, 1])
    ((3, 3), 1.0)
    """
    if kind == "smooth":
        return GridSurface.from_function(gaussian_height, DOMAIN, DOMAIN, n, n)
    if kind == "random":
        return GridSurface.random(n, n, seed=0, x_range=DOMAIN, y_range=DOMAIN)
    raise ValueError(f"'kind' must be one of {SURFACES}; got {kind!r}")


def bench_view(surface: GridSurface) -> View:
    """The viewpoint (6, 8, 3) looking at the centre of the grid's bounding box (case 9).

    >>> bench_view(bench_surface("smooth", 3)).direction
    (-6.0, -8.0, -2.5)
    """
    centre = np.array(
        [
            (surface.x[0] + surface.x[-1]) / 2,
            (surface.y[0] + surface.y[-1]) / 2,
            (surface.z.min() + surface.z.max()) / 2,
        ]
    )
    return View(VIEWPOINT, tuple((centre - VIEWPOINT).tolist()))


@dataclass(frozen=True)
class Timing:
    """One cell: `algorithm` on the `surface` ("smooth"/"random") of `grid`^2 points at `image`^2."""

    surface: str
    algorithm: str
    grid: int
    image: int
    seconds: float  # median of `runs` CPU times
    runs: int

    @property
    def facets(self) -> int:
        """(grid - 1)^2."""
        return (self.grid - 1) ** 2


@dataclass(frozen=True)
class SurfacesBench:
    """What `run_surfaces` measured: the two sweeps' cells and the storage table's columns."""

    by_grid: tuple[Timing, ...]
    by_image: tuple[Timing, ...]
    storage: dict[str, dict]


def _time(function: Callable[[], object], repeat: int, least: float) -> list[float]:
    """CPU times of at least `repeat` runs, and of more until `least` seconds are spent (at most 100)."""
    times: list[float] = []
    while len(times) < repeat or (sum(times) < least and len(times) < MAX_RUNS):
        tick = process_time()
        function()
        times.append(process_time() - tick)
    return times


def _check_run(names, grids, images, grid_image, image_grid, repeat) -> None:
    for name in names:
        if name not in ALGORITHMS:
            raise ValueError(f"'algorithms': {name!r} is not one of {', '.join(ALGORITHMS)}")
    for label, values in (("grids", grids), ("images", images)):
        if not values or any(
            isinstance(v, bool) or not isinstance(v, int) or v < 2 for v in values
        ):
            raise ValueError(f"{label!r} must be ints >= 2 (points or pixels per side); got {values!r}")  # fmt: skip
    for label, value, low in (
        ("grid_image", grid_image, 2),
        ("image_grid", image_grid, 2),
        ("repeat", repeat, 1),
    ):
        if isinstance(value, bool) or not isinstance(value, int) or value < low:
            raise ValueError(f"{label!r} must be an int >= {low}; got {value!r}")


def run_surfaces(
    *,
    quick: bool = False,
    grids: tuple[int, ...] | None = None,
    images: tuple[int, ...] | None = None,
    grid_image: int | None = None,
    image_grid: int | None = None,
    repeat: int | None = None,
    algorithms: tuple[str, ...] | None = None,
    plot: str | None = None,
) -> SurfacesBench:
    """Time every algorithm on both surfaces, print the tables, the trends and the storage.

    Parameters
    ----------
    quick : bool
        Grids 10 and 20 at 64^2, images 64 and 100 at 10 x 10, one run each.
    grids : tuple of int, optional
        Points per side of the grid sweep (default `GRIDS`), each >= 2.
    images : tuple of int, optional
        Sides of the image sweep (default `IMAGES`), each >= 2.
    grid_image, image_grid : int, optional
        The image side of the grid sweep (`GRID_IMAGE`) and the grid of the
        image sweep (`IMAGE_GRID`).
    repeat : int, optional
        Least runs per cell (`REPEAT`; more until `LEAST_SECONDS`, not in
        quick mode); the median is kept.
    algorithms : tuple of str, optional
        Names of `ALGORITHMS` (default: all).
    plot : str, optional
        A file for the log-log plots of time against facets and against image side.

    Returns
    -------
    SurfacesBench

    Raises
    ------
    ValueError
        Naming the option: an unknown algorithm, a size < 2, a repeat < 1.
    """
    names = tuple(ALGORITHMS) if algorithms is None else tuple(dict.fromkeys(algorithms))
    grids = tuple(sorted(set(((10, 20) if quick else GRIDS) if grids is None else grids)))
    images = tuple(sorted(set(((64, 100) if quick else IMAGES) if images is None else images)))
    grid_image = (64 if quick else GRID_IMAGE) if grid_image is None else grid_image
    image_grid = (10 if quick else IMAGE_GRID) if image_grid is None else image_grid
    repeat = (1 if quick else REPEAT) if repeat is None else repeat
    least = 0.0 if quick else LEAST_SECONDS
    _check_run(names, grids, images, grid_image, image_grid, repeat)
    print(
        f"surfaces benchmark: exp(-x^2-y^2) ('smooth') and random heights in [0, 1) (seed 0) on "
        f"[-2, 2]^2, viewpoint {VIEWPOINT} (case 9) looking at the grid's centre; untraced, "
        f"warm; CPU ms, median of >= {repeat} runs (more until {least:g} s per cell)"
    )
    cells = len(names) * len(SURFACES) * (len(grids) + len(images))
    measured: dict[tuple, Timing] = {}
    with progress(cells, "surfaces bench", enabled=not quick) as bar:
        warm = bench_surface("smooth", 5)
        for name in names:
            ALGORITHMS[name](warm, bench_view(warm), 32)  # numba compiles or loads its kernels

        def timing(kind: str, name: str, grid: int, image: int) -> Timing:
            key = (kind, name, grid, image)
            if key not in measured:
                surface = bench_surface(kind, grid)
                view = bench_view(surface)
                times = _time(lambda: ALGORITHMS[name](surface, view, image), repeat, least)
                measured[key] = Timing(
                    kind, name, grid, image, statistics.median(times), len(times)
                )
            bar.update(1)
            return measured[key]

        by_grid = tuple(
            timing(kind, name, grid, grid_image)
            for kind in SURFACES
            for grid in grids
            for name in names
        )
        by_image = tuple(
            timing(kind, name, image_grid, image)
            for kind in SURFACES
            for image in images
            for name in names
        )
    _print_sweep(f"time against grid size at {grid_image}x{grid_image}", by_grid, names)
    _print_sweep(f"time against image side at {image_grid}x{image_grid} points", by_image, names)  # fmt: skip
    _print_trends(by_grid, by_image, names, grid_image, image_grid)
    surface = bench_surface("smooth", STORAGE_GRID)
    storage = print_storage(surface, bench_view(surface), *STORAGE_RASTER)
    if plot:
        save_plot(by_grid, by_image, plot)
        print(f"plot: {plot}")
    return SurfacesBench(by_grid, by_image, storage)


def _print_sweep(title: str, timings: tuple[Timing, ...], names: tuple[str, ...]) -> None:
    print(title + " (CPU ms)")
    print(
        f"{'surface':<8}{'grid':>9}{'facets':>8}{'image':>7}" + "".join(f"{n:>11}" for n in names)
    )
    for start in range(0, len(timings), len(names)):
        row = timings[start : start + len(names)]
        first = row[0]
        print(
            f"{first.surface:<8}{f'{first.grid}x{first.grid}':>9}{first.facets:>8,}{first.image:>7}"
            + "".join(f"{t.seconds * 1e3:>11.2f}" for t in row)
        )


def _ratio(timings: dict[int, float], low: int, high: int) -> float | None:
    if low in timings and high in timings:
        return timings[high] / timings[low]
    return None


def _fit(sizes, seconds) -> float | None:
    fit = growth_exponent(list(sizes), list(seconds))
    return None if fit is None else fit[0]


def _cell(value: float | None, width: int) -> str:
    text = "n/a" if value is None else f"{value:.2f}"
    return f"{text:>{width}}"


def wang_trends(kind: str, grid_image: int, image_grid: int) -> dict[str, tuple]:
    """The 1985 trends of Table 2-2 ("smooth") or 2-3 ("random"), on the legible cells only.

    Returns ``{"fpa": (ratio 60/10, k facets, ratio 600/100, k side), "anderson": (ratio,
    k facets, None, None)}``: the FPA at image side `grid_image` (None if the
    table has no such column) and on the `image_grid` row; a ratio is None
    where an end is lost in the OCR or only estimated (`WANG_ESTIMATED`).

    >>> ratio, k, _, _ = wang_trends("smooth", 300, 60)["anderson"]
    >>> round(ratio, 1), round(k, 2)
    (35.5, 0.95)
    """
    table, estimated = WANG_TABLES[kind], WANG_ESTIMATED[kind]

    def legible(grid, column) -> float | None:
        value = table.get(grid, {}).get(column)
        return None if (grid, column) in estimated else value

    def along_grids(column):
        kept = [(g, legible(g, column)) for g in table if legible(g, column) is not None]
        ratio = _ratio(dict(kept), 10, 60)
        return ratio, _fit([(g - 1) ** 2 for g, _ in kept], [s for _, s in kept])

    row = {c: legible(image_grid, c) for c in IMAGES if legible(image_grid, c) is not None}
    side_ratio = _ratio(row, 100, 600)
    side_k = _fit(list(row), list(row.values())) if len(row) > 1 else None
    return {
        "fpa": (*along_grids(grid_image), side_ratio, side_k),
        "anderson": (*along_grids("anderson"), None, None),
    }


def _print_trends(by_grid, by_image, names, grid_image, image_grid) -> None:
    low, high = min(t.grid for t in by_grid), max(t.grid for t in by_grid)
    small, large = min(t.image for t in by_image), max(t.image for t in by_image)
    print(
        f"trends: growth k of time ~ facets^k (grid sweep) and ~ side^k (image sweep), "
        f"least squares on log-log over runs > {FIT_FLOOR * 1e3:g} ms; ratios of times"
    )
    columns = ("60x60/10x10", "k 10..60", f"k {low}..{high}", f"{large}/{small}", "k side")
    print(f"{'surface':<8}{'algorithm':<15}" + "".join(f"{c:>13}" for c in columns))
    for kind in SURFACES:
        for name in names:
            grid = {t.grid: t.seconds for t in by_grid if (t.surface, t.algorithm) == (kind, name)}
            side = {
                t.image: t.seconds for t in by_image if (t.surface, t.algorithm) == (kind, name)
            }
            up_to_60 = {g: s for g, s in grid.items() if 10 <= g <= 60}
            values = (
                _ratio(grid, 10, 60),
                _fit([(g - 1) ** 2 for g in up_to_60], up_to_60.values()),
                _fit([(g - 1) ** 2 for g in grid], grid.values()),
                _ratio(side, small, large),
                _fit(side, side.values()),
            )
            print(f"{kind:<8}{name:<15}" + "".join(_cell(v, 13) for v in values))
        wang = wang_trends(kind, grid_image, image_grid)
        fpa, anderson = wang["fpa"], wang["anderson"]
        print(
            f"{kind:<8}{'1985 FPA':<15}{_cell(fpa[0], 13)}{_cell(fpa[1], 13)}{'-':>13}"
            f"{_cell(fpa[2], 13)}{_cell(fpa[3], 13)}"
        )
        print(
            f"{kind:<8}{'1985 Anderson':<15}{_cell(anderson[0], 13)}{_cell(anderson[1], 13)}"
            f"{'-':>13}{'-':>13}{'-':>13}"
        )
    print(
        f"1985: VAX-11/780 seconds of Tables 2-2/2-3 (hidden lines), FPA at image {grid_image} "
        f"and on the {image_grid}x{image_grid} row (600/100 over the dissertation's 100..600); "
        "ratios and fits use legible cells only (never the spec's estimates); n/a: not measured or not in the table"
    )


def save_plot(by_grid: tuple[Timing, ...], by_image: tuple[Timing, ...], path: str) -> None:
    """Log-log plots of time against facets and against image side, one line per algorithm and surface."""
    from matplotlib.figure import Figure  # no pyplot: leaves the caller's backend alone
    from matplotlib.ticker import FuncFormatter

    figure = Figure(figsize=(9.5, 5.2))
    facets_axes, side_axes = figure.subplots(1, 2)
    styles = {"smooth": "o-", "random": "s--"}
    names = list(dict.fromkeys(t.algorithm for t in by_grid + by_image))
    colors = {name: f"C{i}" for i, name in enumerate(names)}
    for axes, timings, x_of in (
        (facets_axes, by_grid, lambda t: t.facets),
        (side_axes, by_image, lambda t: t.image),
    ):
        for kind in SURFACES:
            for name in names:
                cells = [t for t in timings if (t.surface, t.algorithm) == (kind, name)]
                if cells:
                    axes.loglog(
                        [x_of(t) for t in cells],
                        [t.seconds * 1e3 for t in cells],
                        styles[kind],
                        color=colors[name],
                        markersize=3,
                        label=f"{name} ({kind})",
                    )
        axes.grid(True, which="both", alpha=0.3)
        axes.set_ylabel("CPU time (ms)")
        for axis in (axes.xaxis, axes.yaxis):  # plain numbers, not 6 x 10^0
            axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))
            axis.set_minor_formatter(FuncFormatter(lambda value, _: ""))
    side_axes.set_xticks(sorted({t.image for t in by_image}))  # log axis: label every side measured
    facets_axes.set_xlabel(f"facets (image {by_grid[0].image}x{by_grid[0].image})")
    side_axes.set_xlabel(f"image side (grid {by_image[0].grid}x{by_image[0].grid})")
    facets_axes.set_title("time against grid size")
    side_axes.set_title("time against image size")
    handles, labels = facets_axes.get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower center", ncol=6, fontsize=7)
    figure.tight_layout(rect=(0, 0.1, 1, 1))
    figure.savefig(path, dpi=120)

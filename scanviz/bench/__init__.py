"""Benchmarks that ship with the package: ``python -m scanviz bench SUITE``.

Each suite prints a table of run times (and, where it applies, errors) and
measures installed peers (OpenCV, ...) on the same scenes in the same run;
``grading`` prints how many students a class is graded at per minute;
``visibility`` times every visibility algorithm against the z-buffer;
``surfaces`` times the floating horizon, the Floating Perimeter Algorithm and
the z-buffer on grid surfaces and prints Wang's Table 2-4 storage beside ours;
``shading`` times flat, Gouraud, fast Phong and Phong against their error;
``antialias`` compares DISLOP with Wu, Gupta-Sproull, supersampling, masks,
skia and OpenCV on lines, edges and disks against the exact area.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

SUITES = (
    "raster",
    "render",
    "coverage",
    "grading",
    "visibility",
    "surfaces",
    "shading",
    "antialias",
)


def best_time(function: Callable[[], object], *, repeat: int = 5, budget: float = 2.0) -> float:
    """Median wall time in seconds of `function` over up to `repeat` runs (after one warm-up)."""
    function()
    times: list[float] = []
    started = time.perf_counter()
    while len(times) < repeat and (not times or time.perf_counter() - started < budget):
        tick = time.perf_counter()
        function()
        times.append(time.perf_counter() - tick)
    return statistics.median(times)


def run(suite: str, *, quick: bool = False, plot: str | None = None, **options: object) -> None:
    """Run one benchmark suite and print its table.

    `plot` is where "coverage" (default coverage.png), "visibility",
    "surfaces" or "antialias" (default: no plot) saves its plot; `options` go to
    `run_visibility` or `run_surfaces`.
    """
    if suite == "raster":
        from .raster import run_raster

        run_raster(quick=quick)
    elif suite == "render":
        from .render import run_render

        run_render(quick=quick)
    elif suite == "coverage":
        from .coverage import run_coverage

        run_coverage(quick=quick, plot=plot or "coverage.png")
    elif suite == "grading":
        from .grading import run_grading

        run_grading(quick=quick)
    elif suite == "visibility":
        from .visibility import run_visibility

        run_visibility(quick=quick, plot=plot, **options)
    elif suite == "surfaces":
        from .surfaces import run_surfaces

        run_surfaces(quick=quick, plot=plot, **options)
    elif suite == "shading":
        from .shading import run_shading

        run_shading(quick=quick, plot=plot, **options)
    elif suite == "antialias":
        from .antialias import run_antialias

        run_antialias(quick=quick, plot=plot)
    else:
        raise ValueError(f"'suite' must be one of {SUITES}; got {suite!r}")

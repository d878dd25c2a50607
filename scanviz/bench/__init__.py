"""Benchmarks that ship with the package: ``python -m scanviz bench SUITE``.

Each suite prints a table of run times (and, where it applies, errors) and
measures installed peers (OpenCV, ...) on the same scenes in the same run;
``grading`` prints how many students a class is graded at per minute.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable

SUITES = ("raster", "render", "coverage", "grading")


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


def run(suite: str, *, quick: bool = False, plot: str | None = "coverage.png") -> None:
    """Run one benchmark suite and print its table (`plot`: where "coverage" saves its plot)."""
    if suite == "raster":
        from .raster import run_raster

        run_raster(quick=quick)
    elif suite == "render":
        from .render import run_render

        run_render(quick=quick)
    elif suite == "coverage":
        from .coverage import run_coverage

        run_coverage(quick=quick, plot=plot)
    elif suite == "grading":
        from .grading import run_grading

        run_grading(quick=quick)
    else:
        raise ValueError(f"'suite' must be one of {SUITES}; got {suite!r}")

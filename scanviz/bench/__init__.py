"""Benchmarks that ship with the package: ``python -m scanviz bench SUITE``.

Each suite prints a table of run times (and, where it applies, errors) and
measures installed peers (OpenCV, ...) on the same scenes in the same run;
``grading`` prints how many students a class is graded at per minute;
``visibility`` times every visibility algorithm against the z-buffer;
``surfaces`` times the floating horizon, the Floating Perimeter Algorithm and
the z-buffer on grid surfaces and prints Wang's Table 2-4 storage beside ours;
``shading`` times flat, Gouraud, fast Phong and Phong against their error;
``antialias`` compares DISLOP with Wu, Gupta-Sproull, supersampling, masks,
skia and OpenCV on lines, edges and disks against the exact area;
``scaling`` times the z-buffer, the a-buffer and the scan converter over
10^3..10^6 triangles and 256^2..4096^2 pixels and fits the growth exponents.
``python -m scanviz bench all --report PATH.md`` runs every suite into one
Markdown report (`scanviz.bench.report`).
"""

from __future__ import annotations

import importlib
import statistics
import time
from collections.abc import Callable
from types import ModuleType

SUITES = (
    "raster",
    "render",
    "coverage",
    "grading",
    "visibility",
    "surfaces",
    "shading",
    "antialias",
    "scaling",
)
PLOTTING = ("coverage", "visibility", "surfaces", "shading", "antialias", "scaling")
"""The suites whose ``run_*`` takes ``plot=`` (a file to save a plot in, or None)."""


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


def optional_module(name: str) -> ModuleType | None:
    """The module `name` if it is installed, else None: a peer library to compare against."""
    try:
        return importlib.import_module(name)
    except ImportError:
        return None


def suite_function(suite: str) -> Callable[..., list[dict]]:
    """The function ``run_<suite>`` of module ``scanviz.bench.<suite>``, which returns its rows."""
    if suite not in SUITES:
        raise ValueError(f"'suite' must be one of {SUITES}; got {suite!r}")
    return getattr(importlib.import_module(f"{__name__}.{suite}"), f"run_{suite}")


def run(
    suite: str, *, quick: bool = False, plot: str | None = None, **options: object
) -> list[dict]:
    """Run one benchmark suite, print its table and return its rows.

    `plot` is where a suite of `PLOTTING` saves its plot ("coverage": default
    coverage.png; the others: no plot); `options` go to `run_visibility`,
    `run_surfaces` or `run_shading`.
    """
    function = suite_function(suite)
    if suite in PLOTTING:
        options["plot"] = plot or ("coverage.png" if suite == "coverage" else None)
    return function(quick=quick, **options)

"""The conformance suite: the table of categories, the runner and its one-line output.

Each category is a small function returning an `Outcome`; they live in `raster_checks`,
`input_checks`, `coverage_checks`, `pipeline_checks`, `visibility_checks`, `surfaces_checks`
and `antialias_checks`; this module lists them, runs them and prints one line each.
Every category builds its cases from a seeded generator, runs the public entry points
and compares them with an exact oracle (`scanviz.conformance.exact`) or with an
invariant that must hold exactly. ``docs/conformance.md`` lists
what each category checks and why.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from .antialias_checks import dislop_vs_exact_area
from .cases import Outcome
from .classify import one_line
from .coverage_checks import exact_coverage, masks_vs_supersampling
from .input_checks import degenerate_polygons, huge_and_non_finite
from .pipeline_checks import builtin_scenes, interpolation_vs_barycentric, traced_equals_compiled
from .raster_checks import (
    exact_ties,
    fill_convention,
    long_edge_drift,
    shared_edges,
    t_junctions,
    translation_invariance,
    watertight_fans,
    winding_and_parity,
)
from .surfaces_checks import fpa_vs_zbuffer
from .visibility_checks import SCENES, visibility_agrees

VISIBILITY = "visibility agrees with the z-buffer"  # its random scenes: `run_category`'s `scenes`
CATEGORIES: dict[str, Callable[[np.random.Generator], Outcome]] = {
    "fill convention": fill_convention,
    "no double hits": shared_edges,
    "watertight fans": watertight_fans,
    "translation invariance": translation_invariance,
    "exact ties": exact_ties,
    "long-edge drift": long_edge_drift,
    "degenerate polygons": degenerate_polygons,
    "huge and non-finite": huge_and_non_finite,
    "winding and parity": winding_and_parity,
    "T-junctions": t_junctions,
    "exact coverage": exact_coverage,
    "masks vs supersampling": masks_vs_supersampling,
    "interpolation": interpolation_vs_barycentric,
    "traced == compiled": traced_equals_compiled,
    "built-in scenes": builtin_scenes,
    VISIBILITY: visibility_agrees,
    "FPA vs z-buffer": fpa_vs_zbuffer,
    "DISLOP vs exact area": dislop_vs_exact_area,
}


NAME_WIDTH = max(map(len, CATEGORIES))  # the names line up in the output


def run_category(name: str, seed: int = 0, scenes: int = SCENES) -> Outcome:
    """Run one category with its own seeded generator; an unexpected exception is a FAIL.

    `scenes` is the number of random scenes of the visibility category.
    """
    index = list(CATEGORIES).index(name)
    rng = np.random.default_rng([seed, index])
    try:
        return visibility_agrees(rng, scenes) if name == VISIBILITY else CATEGORIES[name](rng)
    except Exception as error:  # noqa: BLE001 -- a category that raises fails, saying why
        return Outcome(False, "", f"raised {one_line(error)}")


def format_line(name: str, outcome: Outcome) -> str:
    """``PASS  name  counts``, or ``FAIL  name  counts; first failure: case`` (one line)."""
    line = f"{'PASS' if outcome.passed else 'FAIL'}  {name:<{NAME_WIDTH}}  {outcome.counts}"
    return line if outcome.passed else f"{line}; first failure: {outcome.failure}"


def run_suite(seed: int = 0, out=print, scenes: int = SCENES) -> bool:
    """Run every category, printing one line each and a summary; True when all pass."""
    start = time.perf_counter()
    passed = 0
    for name in CATEGORIES:
        outcome = run_category(name, seed, scenes)
        passed += outcome.passed
        out(format_line(name, outcome))
    seconds = time.perf_counter() - start
    failed = len(CATEGORIES) - passed
    out(f"conformance: {passed} passed, {failed} failed in {seconds:.1f} s (seed {seed})")
    return failed == 0

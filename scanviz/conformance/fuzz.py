"""The fuzz campaign: hostile, extreme and random valid inputs for every public entry point.

Each entry point has a hypothesis strategy (`scanviz.conformance.strategies`)
and a check (`scanviz.conformance.checks`); this module runs them and counts
the outcomes. Every outcome is one of

* **correct**: the call returned and the check found the result right (exact
  oracle for the raster entry points, finite values in range elsewhere);
* **clear error**: `scanviz.conformance.classify.clear_error` (a ValueError or
  TypeError, OSError for files, naming what was wrong in one line);
* **anything else**: a wrong result, NaN in an output, any other exception, a
  call over the time budget, a MemoryError, a CLI exit other than 0 or 2 or
  with more than one line on stderr, a traceback or a line over 300 characters.
  Two kinds of it have their own columns: **too slow** (over the time budget,
  or over a scaling input's bound) and **over memory** (a MemoryError, or a
  scaling input whose peak memory passed its allowance).

The entry "time and memory against size" is not random: it runs every input
of `scanviz.conformance.checks.scaling_cases` once (polygons of 20,000
vertices, 50,000 triangles, rasters under and over a 64M memory limit, deep
JSON, long OBJ text, hundreds of triangles for each visibility algorithm, ...),
each within a time bound proportional to its size (`check_scaling`), so a
regression to quadratic time or an allocation the limits did not estimate is
a failure row.

Every call runs under ``scanviz.limits.memory_limit("1G")`` and, where the
platform has it, an address-space cap a little above that (so a request the
limits should have refused fails fast as MemoryError instead of taking the
machine) and a wall-clock alarm (`CALL_SECONDS`).

hypothesis runs with a seed (`hypothesis.seed`), no example database, no
deadline and generation only (nothing is shrunk: no call raises inside it).
"""

from __future__ import annotations

import contextlib
import os
import time
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import hypothesis
from hypothesis import HealthCheck, Phase
from hypothesis import strategies as st

from ..limits import memory_limit, wall_clock_limit
from .checks import (
    check_area_coverage,
    check_cli,
    check_fill_polygons,
    check_limit,
    check_midpoint_line,
    check_obj,
    check_polygon,
    check_rasterize_triangles,
    check_scaling,
    check_scan_convert,
    check_scene_dict,
    check_scene_file,
    check_trace,
    check_triangle_samples,
    limit_cases,
    scaling_cases,
)
from .classify import clear_error, one_line, short_repr
from .strategies import (
    OBJ_LINES,
    cli_argvs,
    file_bytes,
    line_ends,
    materialize,
    odd_arrays,
    oddballs,
    option_values,
    polygon_inputs,
    raster_options,
    scan_convert_args,
    scene_dicts,
    sizes,
    subpixel_bits_values,
    trace_texts,
    triangle_inputs,
)

CALL_SECONDS = 10.0  # wall-clock budget of one call
MEMORY_LIMIT = "1G"
ADDRESS_HEADROOM = 2 * 2**30  # bytes of address space a call may add
MAX_REPORTED = 20
TOO_SLOW, OVER_MEMORY = "too slow", "over memory"  # how a failure's description starts


@dataclass
class Counts:
    """Outcomes of one entry point."""

    tried: int = 0
    clear: int = 0
    correct: int = 0
    other: int = 0  # anything else, of which:
    slow: int = 0  # too slow
    memory: int = 0  # over memory
    cases: list[str] = field(default_factory=list)

    def add(self, verdict: str, what: str, reproducer: str) -> None:
        """Count one outcome of `classify`; keep the reproducer of anything else."""
        self.tried += 1
        if verdict == "clear":
            self.clear += 1
        elif verdict == "correct":
            self.correct += 1
        else:
            self.other += 1
            self.slow += what.startswith(TOO_SLOW)
            self.memory += what.startswith(OVER_MEMORY)
            self.cases.append(f"{reproducer} -> {what}")


class CallTimeout(BaseException):
    """A call ran over `CALL_SECONDS` (a BaseException, so no `except Exception` swallows it)."""


# --- the entry points --------------------------------------------------------------------------


@dataclass(frozen=True)
class EntryPoint:
    strategy: Callable[[], st.SearchStrategy]
    call: Callable[[dict], str]
    files: bool = False
    share: float = 1.0  # relative number of inputs
    inputs: Callable[[], list[dict]] | None = None  # a fixed list, each run once, for any count


def _sized(**fields) -> Callable[[], st.SearchStrategy]:
    return lambda: st.fixed_dictionaries({k: v() for k, v in fields.items()})


def _on_raster(options: Callable, **shape) -> Callable[[], st.SearchStrategy]:
    """`_sized` of a raster entry point's shape argument, then width, height and `options`."""
    return _sized(**shape, width=sizes, height=sizes, options=options)


ENTRY_POINTS: dict[str, EntryPoint] = {
    "Polygon": EntryPoint(_sized(contours=polygon_inputs), check_polygon),
    "scan_convert": EntryPoint(lambda: scan_convert_args(False), check_scan_convert, share=1.5),
    "scan_convert (valid, oracle)": EntryPoint(
        lambda: scan_convert_args(True), check_scan_convert, share=1.5
    ),
    "fill_polygons": EntryPoint(
        _on_raster(
            lambda: raster_options(True),
            polygons=lambda: st.one_of(st.lists(polygon_inputs(), max_size=3), polygon_inputs()),
        ),
        check_fill_polygons,
    ),
    "rasterize_triangles": EntryPoint(
        _on_raster(
            lambda: raster_options(False),
            triangles=lambda: st.one_of(
                st.lists(triangle_inputs(), max_size=3), odd_arrays(), oddballs()
            ),
        ),
        check_rasterize_triangles,
    ),
    "triangle_samples": EntryPoint(
        _on_raster(
            lambda: st.fixed_dictionaries(
                {},
                optional={
                    "sample": option_values(("corner", "center")),
                    "subpixel_bits": subpixel_bits_values(),
                    "polygon": st.one_of(st.integers(0, 3), oddballs()),
                },
            ),
            triangle=triangle_inputs,
        ),
        check_triangle_samples,
    ),
    "midpoint_line": EntryPoint(_sized(ends=line_ends), check_midpoint_line),
    "area_coverage": EntryPoint(
        _on_raster(lambda: raster_options(True), polygon=polygon_inputs), check_area_coverage
    ),
    "scene dict + render": EntryPoint(
        _sized(scene=scene_dicts, mode=lambda: st.integers(0, 11)),
        check_scene_dict,
        files=True,  # a string is a path to load_scene
        share=1.5,
    ),
    "scene file + render": EntryPoint(
        _sized(
            data=file_bytes,
            mode=lambda: st.integers(0, 11),
            kind=lambda: st.sampled_from(["file", "file", "file", "missing", "directory"]),
            name=lambda: st.sampled_from(["scene.json"] * 4 + ["s", "s.obj", "a\nb.json"]),
        ),
        check_scene_file,
        files=True,
    ),  # fmt: skip
    "OBJ text": EntryPoint(
        _sized(lines=lambda: st.lists(st.sampled_from(OBJ_LINES), max_size=10)), check_obj
    ),
    "Trace.from_json": EntryPoint(_sized(text=trace_texts), check_trace),
    "CLI": EntryPoint(_sized(argv=cli_argvs), check_cli, files=True, share=0.5),
    "memory limits": EntryPoint(
        _sized(case=lambda: st.sampled_from(sorted(limit_cases()))), check_limit, share=0.3
    ),
    "time and memory against size": EntryPoint(
        _sized(case=lambda: st.sampled_from(list(scaling_cases()))),
        check_scaling,
        files=True,  # named pipes, files over the limit
        share=0,
        inputs=lambda: [{"case": name} for name in scaling_cases()],
    ),
}


# --- running -------------------------------------------------------------------------------------


@contextlib.contextmanager
def guarded_call() -> Iterator[None]:
    """The memory limit, an address-space cap above it, and the time budget, around one call.

    Warnings are silenced: what they warn of shows in the outcome (NaN in an
    output, a coordinate of a wrong type accepted).
    """
    with (
        warnings.catch_warnings(),
        memory_limit(MEMORY_LIMIT),
        _address_space_cap(),
        wall_clock_limit(CALL_SECONDS, CallTimeout, f"over the {CALL_SECONDS:g} s budget"),
    ):
        warnings.simplefilter("ignore")
        yield


@contextlib.contextmanager
def _address_space_cap() -> Iterator[None]:
    try:
        import resource
    except ImportError:  # not on this platform: the memory limit alone
        yield
        return
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    cap = _address_space() + ADDRESS_HEADROOM
    if hard != resource.RLIM_INFINITY:
        cap = min(cap, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _address_space() -> int:
    """This process's virtual memory size in bytes (Linux), or 0 when unknown."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError):
        return 0


def classify(name: str, entry: EntryPoint, value: dict) -> tuple[str, str]:
    """('correct' | 'clear' | 'other', what happened) of one input."""
    start = time.perf_counter()
    try:
        with guarded_call():
            problem = entry.call(materialize(value))
    except CallTimeout as error:
        return "other", f"{TOO_SLOW}: {error}"
    except Exception as error:  # noqa: BLE001 -- classifying every exception is the point
        if isinstance(error.__cause__ or error.__context__, CallTimeout):  # raised inside numba
            return "other", f"{TOO_SLOW}: over the {CALL_SECONDS:g} s budget (inside a compiled kernel)"  # fmt: skip
        if clear_error(error, files=entry.files):
            return "clear", ""
        if isinstance(error, MemoryError):
            return "other", f"{OVER_MEMORY}: {one_line(error)}"
        return "other", one_line(error)
    if time.perf_counter() - start > CALL_SECONDS:
        return "other", f"{TOO_SLOW}: took {time.perf_counter() - start:.1f} s"
    return ("other", problem) if problem else ("correct", "")


def run_entry(name: str, examples: int, seed: int) -> Counts:
    """Run `examples` inputs of one entry point (its fixed `inputs`, if any, for any count > 0)."""
    entry, counts = ENTRY_POINTS[name], Counts()
    if entry.inputs is not None:
        for value in entry.inputs() if examples > 0 else ():
            counts.add(*classify(name, entry, value), f"{name}: {short_repr(value)}")
        return counts

    @hypothesis.settings(
        max_examples=examples,
        database=None,
        deadline=None,
        derandomize=False,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @hypothesis.seed(seed)
    @hypothesis.given(entry.strategy())
    def probe(value: dict) -> None:
        counts.add(*classify(name, entry, value), f"{name}: {short_repr(value)}")

    if examples > 0:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", hypothesis.errors.HypothesisWarning)
            probe()
    return counts


def campaign(total: int, seed: int = 0) -> dict[str, Counts]:
    """Spread `total` inputs over the entry points by their shares (and the fixed inputs)."""
    shares = sum(e.share for e in ENTRY_POINTS.values())
    return {
        name: run_entry(name, max(1, round(total * entry.share / shares)), seed)
        for name, entry in ENTRY_POINTS.items()
    }


def _row(name: str, c: Counts) -> str:
    return f"{name:<30} {c.tried:>7,} {c.clear:>13,} {c.correct:>8,} {c.other:>14,} {c.slow:>9,} {c.memory:>12,}"  # fmt: skip


def format_table(results: dict[str, Counts]) -> list[str]:
    """The counts table, a total row, and up to MAX_REPORTED reproducers.

    "too slow" and "over memory" are the part of "anything else" over a time or memory bound.
    """
    lines = [
        f"{'entry point':<30} {'tried':>7} {'clear errors':>13} {'correct':>8} {'anything else':>14} {TOO_SLOW:>9} {OVER_MEMORY:>12}"  # fmt: skip
    ]
    total = Counts()
    for name, c in results.items():
        lines.append(_row(name[:30], c))
        for column in ("tried", "clear", "correct", "other", "slow", "memory"):
            setattr(total, column, getattr(total, column) + getattr(c, column))
        total.cases += c.cases
    lines.append(_row("total", total))
    lines += [f"  {case}" for case in total.cases[:MAX_REPORTED]]
    if len(total.cases) > MAX_REPORTED:
        lines.append(f"  ... and {len(total.cases) - MAX_REPORTED} more")
    return lines


def run_campaign(total: int, seed: int = 0, out=print) -> bool:
    """Run the campaign, print the table; True when nothing gave "anything else"."""
    start = time.perf_counter()
    results = campaign(total, seed)
    for line in format_table(results):
        out(line)
    others = sum(c.other for c in results.values())
    out(
        f"fuzz: {total:,} inputs in {time.perf_counter() - start:.1f} s (seed {seed}), {others} anything else"
    )
    return others == 0

"""The table of replaceable textbook steps that the traced reference loops call.

Each reference loop (scan conversion, the midpoint line, edge functions,
interpolation, the z-buffer, culling, clipping, viewing, the a-buffer) takes
its textbook steps -- the span rule, the AET update, the midpoint decision,
the depth test, an a-buffer insertion, ... -- from this table instead of
calling them directly. The default table is the reference. An exercise swaps
in a student's function for one step and runs the real algorithm, so the
trace shows what the student's step does::

    with steps.using(span_rule=my_span_rule):
        scan_convert(polygon, 8, 8, trace=recorder)

While any step is replaced, the entry points run their traced reference
loop, never a compiled kernel (the kernels have no table). The replacement is
held in a `contextvars.ContextVar`, so it is local to the thread or task that
made it. A reference loop trusts what its steps return: a replacement of a
step listed in `CHECKS` is called through that step's check (`check`), which
raises a clear error on a result the loop cannot use and hands the loop the
result in the reference's form (the scan steps' checks:
`scanviz.exercises.scan_checks`). ``docs/exercises.md`` lists every step
(`table()`): what it takes, what it returns.
"""

from __future__ import annotations

import difflib
import importlib
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from types import MappingProxyType

from .trace.schema import shown


@dataclass(frozen=True)
class Step:
    """One replaceable step: its name, the module whose loop calls it, its signature in words."""

    name: str
    module: str
    takes: str
    returns: str
    reference: Callable


# Where each step is registered, in the order of the course (the exercises' order). A name
# is looked up here and only its module is imported: no package imports every other one.
LOCATIONS: dict[str, str] = {
    "midpoint_step": "scanviz.raster.lines",
    "edge_table_entry": "scanviz.raster.scanline",
    "aet_update": "scanviz.raster.scanline",
    "span_rule": "scanviz.raster.scanline",
    "owns_boundary": "scanviz.raster.edgefn",
    "edge_function": "scanviz.raster.edgefn",
    "span_step": "scanviz.raster.interpolate",
    "depth_test": "scanviz.visibility.zbuffer",
    "back_face_test": "scanviz.transform.cull",
    "clip_against_plane": "scanviz.transform.clip",
    "viewing_matrix": "scanviz.transform.viewing",
    "insert_fragment": "scanviz.abuffer.pixelstruct",
    "pack_pixel": "scanviz.abuffer.pixelstruct",
    "depth_order_test": "scanviz.visibility.depth_sort",
    "bsp_display_order": "scanviz.visibility.bsp",
    "perimeter_test": "scanviz.surfaces.perimeter",
    "perimeter_merge": "scanviz.surfaces.perimeter",
    "specular_level": "scanviz.shading.lut",
    "forward_difference": "scanviz.shading.fast_phong",
    "dislop_column": "scanviz.antialias.line",
    "table_index": "scanviz.antialias.tables",
}
# The module that registers the check of a replacement of each checked step (`check`); looked
# up by name as LOCATIONS is, so this module imports no exercise module.
CHECKS: dict[str, str] = {
    "edge_table_entry": "scanviz.exercises.scan_checks",
    "aet_update": "scanviz.exercises.scan_checks",
}
_TABLE: dict[str, Step] = {}
_CHECKERS: dict[str, Callable] = {}
_NONE: MappingProxyType = MappingProxyType({})
_REPLACED: ContextVar[MappingProxyType] = ContextVar("scanviz_steps", default=_NONE)


def step(name: str, *, takes: str, returns: str) -> Callable[[Callable], Callable]:
    """Register the decorated function as the reference of step `name`.

    `takes` and `returns` describe the arguments and the result in one line
    each, in the algorithm's terms; they are the table in docs/exercises.md.
    """

    def register(function: Callable) -> Callable:
        if LOCATIONS.get(name) != function.__module__:
            raise TypeError(f"step {name!r} is not listed in LOCATIONS as {function.__module__!r}")
        if name in _TABLE:
            raise TypeError(f"step {name!r} is registered twice")
        _TABLE[name] = Step(name, function.__module__, takes, returns, function)
        return function

    return register


def check(name: str) -> Callable[[Callable], Callable]:
    """Register the decorated function as the check of step `name`'s replacements.

    It is called as ``checker(replacement, **context)`` (`context`: what the
    loop passes to `get`) and returns the function the loop calls instead.
    """

    def register(checker: Callable) -> Callable:
        if CHECKS.get(name) != checker.__module__:
            raise TypeError(f"the check of step {name!r} is not listed in CHECKS")
        _CHECKERS[name] = checker
        return checker

    return register


def get(name: str, **context) -> Callable:
    """The function that currently implements step `name` (the reference unless replaced).

    A replacement comes through its step's check (`CHECKS`), made afresh for
    this call with the loop's `context` (e.g. the grid's scale): a loop gets
    its steps once per run.
    """
    replaced = _REPLACED.get()
    if name not in replaced:
        return _registered(name).reference
    if name not in CHECKS:
        return replaced[name]
    if name not in _CHECKERS:
        importlib.import_module(CHECKS[name])
    return _CHECKERS[name](replaced[name], **context)


def replaced() -> frozenset[str]:
    """The names of the steps replaced in this context (empty: the reference table)."""
    return frozenset(_REPLACED.get())


def table() -> list[Step]:
    """Every step, in the order of the course (`LOCATIONS`)."""
    return [_registered(name) for name in LOCATIONS]


def _registered(name: str) -> Step:
    """Step `name`, importing the module that registers it on first use."""
    if name not in _TABLE:
        importlib.import_module(LOCATIONS[name])
    return _TABLE[name]


def _check_name(name: str) -> None:
    if name not in LOCATIONS:
        close = difflib.get_close_matches(name, LOCATIONS, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise ValueError(f"unknown step {name!r}{hint}; known steps: {sorted(LOCATIONS)}")


@contextmanager
def using(**replacements: Callable) -> Iterator[None]:
    """Run the reference loops with some steps replaced, inside a ``with`` block.

    Examples
    --------
    >>> from scanviz import steps
    >>> with steps.using(span_rule=lambda *args: []):
    ...     sorted(steps.replaced())
    ['span_rule']
    >>> sorted(steps.replaced())
    []
    """
    for name, function in replacements.items():
        _check_name(name)
        if not callable(function):
            raise TypeError(f"step {name!r} must be replaced by a callable; got {shown(function)}")
    token = _REPLACED.set(MappingProxyType({**_REPLACED.get(), **replacements}))
    try:
        yield
    finally:
        _REPLACED.reset(token)

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
made it. ``docs/exercises.md`` lists every step (`table()`): what it takes,
what it returns.
"""

from __future__ import annotations

import difflib
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


_TABLE: dict[str, Step] = {}
_NONE: MappingProxyType = MappingProxyType({})
_REPLACED: ContextVar[MappingProxyType] = ContextVar("scanviz_steps", default=_NONE)


def step(name: str, *, takes: str, returns: str) -> Callable[[Callable], Callable]:
    """Register the decorated function as the reference of step `name`.

    `takes` and `returns` describe the arguments and the result in one line
    each, in the algorithm's terms; they are the table in docs/exercises.md.
    """

    def register(function: Callable) -> Callable:
        if name in _TABLE:
            raise TypeError(f"step {name!r} is registered twice")
        _TABLE[name] = Step(name, function.__module__, takes, returns, function)
        return function

    return register


def get(name: str) -> Callable:
    """The function that currently implements step `name` (the reference unless replaced)."""
    replaced = _REPLACED.get()
    return replaced[name] if name in replaced else _TABLE[name].reference


def replaced() -> frozenset[str]:
    """The names of the steps replaced in this context (empty: the reference table)."""
    return frozenset(_REPLACED.get())


def table() -> list[Step]:
    """Every registered step, in the order the modules registered them."""
    _load_reference_modules()
    return list(_TABLE.values())


def _check_name(name: str) -> None:
    _load_reference_modules()
    if name not in _TABLE:
        close = difflib.get_close_matches(name, _TABLE, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise ValueError(f"unknown step {name!r}{hint}; known steps: {sorted(_TABLE)}")


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


def _load_reference_modules() -> None:
    """Import every module that registers steps, so the table is complete."""
    from . import abuffer, antialias, pipeline, raster, surfaces, transform, visibility  # noqa: F401

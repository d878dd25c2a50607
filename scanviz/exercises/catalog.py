"""The exercise catalog: every exercise registers itself here, in course order.

Each stage's exercises live in their own module (listed in `MODULES`) and
call `register` at import. `exercises()` imports them all and returns the
catalog sorted by number; the number is the ``NN`` of the student notebook
``notebooks/exercises/NN_<id>.ipynb``.
"""

from __future__ import annotations

import difflib
import importlib

from .core import Exercise

MODULES = (
    "lines", "scan", "triangles", "interpolation", "zbuffer", "viewing", "abuffer", "depth_sort",
    "bsp", "perimeter", "fast_phong", "antialias",
)  # fmt: skip

_CATALOG: dict[str, Exercise] = {}


def register(exercise: Exercise) -> Exercise:
    """Add `exercise` to the catalog (ids and numbers are unique)."""
    if exercise.id in _CATALOG:
        raise ValueError(f"exercise {exercise.id!r} is registered twice")
    taken = {e.number: e.id for e in _CATALOG.values()}
    if exercise.number in taken:
        raise ValueError(
            f"exercise number {exercise.number} is taken by {taken[exercise.number]!r}"
        )
    _CATALOG[exercise.id] = exercise
    return exercise


def _load() -> None:
    for module in MODULES:
        importlib.import_module(f"{__package__}.{module}")


def exercises() -> list[Exercise]:
    """Every exercise, in course order."""
    _load()
    return sorted(_CATALOG.values(), key=lambda e: e.number)


def get(exercise_id: str) -> Exercise:
    """The exercise with id `exercise_id`; an unknown id raises ValueError with a suggestion."""
    _load()
    if not isinstance(exercise_id, str):
        raise TypeError(f"'exercise_id' must be a str; got {type(exercise_id).__name__}")
    if exercise_id not in _CATALOG:
        close = difflib.get_close_matches(exercise_id, _CATALOG, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise ValueError(f"unknown exercise {exercise_id!r}{hint}; known: {sorted(_CATALOG)}")
    return _CATALOG[exercise_id]

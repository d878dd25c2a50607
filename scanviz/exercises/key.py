"""The course key: the secret the hidden cases come from, points, and the grading limits.

The key is a TOML file on the teacher's machine, never released::

    secret = "9f86d0..."          # 64 hex characters from secrets.token_hex(32)
    reveal = "never"              # hidden inputs in feedback: "never", "after_due", "always"
    per_student = false           # true: every student gets their own hidden cases

    [limits]
    cpu_seconds = 60.0            # CPU time of one submission's worker process
    memory_mb = 1024              # address space of the worker
    case_seconds = 10.0           # wall time of one exercise's cases

    [exercises.span_rule]
    points = 4
    hidden_cases = 8

`new_key` makes one with a fresh secret, `write_key` writes it (commented),
`load_key` reads and checks it.
"""

from __future__ import annotations

import difflib
import json
import math
import os
import re
import secrets
import tomllib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from ..limits import read_bounded

REVEALS = ("never", "after_due", "always")
HIDDEN_CASES = 8
MIN_SECRET_HEX = 32
MIN_MEMORY_MB = 512  # the worker maps about 350 MB once scanviz and numba are imported
MAX_HIDDEN_CASES = 10_000
_HEX = re.compile(r"[0-9a-fA-F]+")
_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


@dataclass(frozen=True)
class ExerciseKey:
    """One exercise's entry in the key: its points and how many hidden cases it gets."""

    points: int
    hidden_cases: int


@dataclass(frozen=True)
class CourseKey:
    """A course key (see the module docstring for the meaning of every field)."""

    secret: str
    reveal: str
    per_student: bool
    cpu_seconds: float
    memory_mb: int
    case_seconds: float
    exercises: dict[str, ExerciseKey]


def new_key(exercises: Iterable[str] | None = None) -> CourseKey:
    """A key with a fresh random secret for `exercises` (ids; default: the whole catalog).

    >>> key = new_key(["span_rule"])
    >>> len(key.secret), key.exercises["span_rule"].hidden_cases
    (64, 8)
    """
    from .catalog import exercises as catalog
    from .catalog import get

    chosen = [get(e) for e in exercises] if exercises is not None else catalog()
    return CourseKey(
        secret=secrets.token_hex(32),
        reveal="never",
        per_student=False,
        cpu_seconds=60.0,
        memory_mb=1024,
        case_seconds=10.0,
        exercises={e.id: ExerciseKey(e.points, HIDDEN_CASES) for e in chosen},
    )


def _toml_key(name: str) -> str:
    return name if _BARE_KEY.fullmatch(name) else json.dumps(name)


def key_text(key: CourseKey) -> str:
    """The TOML text of `key`, with comments (what `write_key` writes)."""
    lines = [
        "# scanviz course key: keep this file private (never release or commit it).",
        "# The hidden cases are derived from the secret: whoever has it can compute them.",
        f"secret = {json.dumps(key.secret)}",
        "# Hidden inputs in student feedback: " + ", ".join(json.dumps(r) for r in REVEALS),
        f"reveal = {json.dumps(key.reveal)}",
        "# true: every student gets their own hidden cases (harder to share answers)",
        f"per_student = {'true' if key.per_student else 'false'}",
        "",
        "[limits]",
        "# CPU seconds of one submission's worker process (all its exercises)",
        f"cpu_seconds = {float(key.cpu_seconds)!r}",
        f"# address space of the worker in MB (at least {MIN_MEMORY_MB}: "
        "scanviz and numba take about 350)",
        f"memory_mb = {int(key.memory_mb)}",
        "# wall-clock seconds for one exercise's cases",
        f"case_seconds = {float(key.case_seconds)!r}",
    ]
    for exercise_id, entry in key.exercises.items():
        lines += [
            "",
            f"[exercises.{_toml_key(exercise_id)}]",
            f"points = {entry.points}",
            f"hidden_cases = {entry.hidden_cases}",
        ]
    return "\n".join(lines) + "\n"


def write_key(key: CourseKey, path: str | os.PathLike) -> None:
    """Write `key` to `path` as commented TOML; an existing file is never overwritten."""
    try:
        with open(path, "x", encoding="utf-8") as file:
            file.write(key_text(key))
    except FileExistsError:
        raise FileExistsError(
            f"{os.fspath(path)!r} exists; a course key is never overwritten "
            "(its secret defines the hidden cases): choose another file name"
        ) from None
    os.chmod(path, 0o600)


def load_key(path: str | os.PathLike) -> CourseKey:
    """The key in the TOML file `path`; a missing or wrong field raises ValueError naming it."""
    name = os.fspath(path)
    try:
        data = tomllib.loads(read_bounded(Path(path)))
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{name!r} is not valid TOML: {error}") from None
    return _parse(data, name)


def _parse(data: dict, name: str) -> CourseKey:
    _known_fields(data, ("secret", "reveal", "per_student", "limits", "exercises"), name, "")
    secret = data.get("secret")
    if not isinstance(secret, str) or not _HEX.fullmatch(secret) or len(secret) < MIN_SECRET_HEX:
        raise ValueError(
            f"{name!r}: 'secret' must be a string of at least {MIN_SECRET_HEX} hex characters "
            "(make one with `python -m scanviz exercises key new`)"
        )
    reveal = data.get("reveal", "never")
    if reveal not in REVEALS:
        raise ValueError(f"{name!r}: 'reveal' must be one of {REVEALS}; got {reveal!r}")
    per_student = data.get("per_student", False)
    if not isinstance(per_student, bool):
        raise ValueError(f"{name!r}: 'per_student' must be true or false; got {per_student!r}")
    limits = _table(data, "limits", name)
    _known_fields(limits, ("cpu_seconds", "memory_mb", "case_seconds"), name, "limits.")
    return CourseKey(
        secret=secret,
        reveal=reveal,
        per_student=per_student,
        cpu_seconds=_seconds(limits, "cpu_seconds", 60.0, name),
        memory_mb=_integer(limits, "memory_mb", 1024, name, "limits.", MIN_MEMORY_MB),
        case_seconds=_seconds(limits, "case_seconds", 10.0, name),
        exercises=_exercises(_table(data, "exercises", name), name),
    )


def _known_fields(table: dict, fields: tuple[str, ...], name: str, prefix: str) -> None:
    for field in table:
        if field not in fields:
            close = difflib.get_close_matches(field, fields, n=1)
            hint = f" (did you mean {prefix + close[0]!r}?)" if close else ""
            raise ValueError(
                f"{name!r}: unknown field {prefix + field!r}{hint}; known: {list(fields)}"
            )


def _table(data: dict, field: str, name: str) -> dict:
    table = data.get(field, {})
    if not isinstance(table, dict):
        raise ValueError(f"{name!r}: {field!r} must be a table ([{field}])")
    return table


def _seconds(table: dict, field: str, default: float, name: str) -> float:
    value = table.get(field, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{name!r}: 'limits.{field}' must be a number; got {value!r}")
    if value <= 0:
        raise ValueError(f"{name!r}: 'limits.{field}' must be > 0; got {value!r}")
    return float(value)


def _integer(table: dict, field: str, default: int, name: str, prefix: str, low: int) -> int:
    value = table.get(field, default)
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{name!r}: '{prefix}{field}' must be an integer; got {value!r}")
    if value < low:
        raise ValueError(f"{name!r}: '{prefix}{field}' must be >= {low}; got {value}")
    return value


def _exercises(table: dict, name: str) -> dict[str, ExerciseKey]:
    from .catalog import exercises

    catalog = {e.id: e for e in exercises()}
    chosen = {}
    for exercise_id, entry in table.items():
        if exercise_id not in catalog:
            close = difflib.get_close_matches(exercise_id, catalog, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(
                f"{name!r}: [exercises.{exercise_id}]: unknown exercise {exercise_id!r}{hint}"
            )
        prefix = f"exercises.{exercise_id}."
        if not isinstance(entry, dict):
            raise ValueError(f"{name!r}: 'exercises.{exercise_id}' must be a table")
        _known_fields(entry, ("points", "hidden_cases"), name, prefix)
        points = _integer(entry, "points", catalog[exercise_id].points, name, prefix, 0)
        hidden = _integer(entry, "hidden_cases", HIDDEN_CASES, name, prefix, 0)
        if hidden > MAX_HIDDEN_CASES:
            raise ValueError(
                f"{name!r}: '{prefix}hidden_cases' must be <= {MAX_HIDDEN_CASES}; got {hidden}"
            )
        chosen[exercise_id] = ExerciseKey(points, hidden)
    if not chosen:
        raise ValueError(f"{name!r}: the key grades no exercise: add an [exercises.<id>] table")
    return chosen

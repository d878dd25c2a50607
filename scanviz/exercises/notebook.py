"""Read a student's notebook and find its answers by their marker lines.

An answer cell is a code cell whose first line is exactly
``# scanviz: answer <exercise-id>`` (trailing whitespace is tolerated). The
marker, not the cell's position or metadata, is how the grader finds an
answer, so it survives copying, reordering and re-downloading the notebook.
A marker in a markdown cell is ignored. Only the answer cell is graded: it
runs alone, so it imports what it uses itself. If several cells carry the
same marker, the last one is graded and the feedback says so.

Examples
--------
>>> from nbformat import v4
>>> notebook = v4.new_notebook(cells=[
...     v4.new_markdown_cell("# scanviz: answer span_rule"),
...     v4.new_code_cell("import math"),
...     v4.new_code_cell("# scanviz: answer span_rule\\ndef span_rule(crossings, rule): ..."),
... ])
>>> found = find_answers(notebook)
>>> sorted(found.answers), found.notes, found.problems
(['span_rule'], {}, {})
"""

from __future__ import annotations

import difflib
import json
import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..limits import json_nesting, read_bounded

ANSWER_MARKER = "# scanviz: answer "
if TYPE_CHECKING:
    import nbformat

MAX_NESTING = 100  # JSON levels; a notebook's deepest (widget state) is far less


class NotebookError(ValueError):
    """The file is not a readable notebook (the message names the file and the problem)."""


@dataclass
class Answers:
    """What a notebook holds for the grader.

    ``answers`` maps an exercise id to its answer cell's whole source (marker
    line included, so line numbers match the cell); ``notes`` an answered
    exercise id to what the grader chose (which of several marked cells it
    graded); ``problems`` an unanswered id to why (an unknown id, a marker
    that is almost right).
    """

    answers: dict[str, str] = field(default_factory=dict)
    notes: dict[str, str] = field(default_factory=dict)
    problems: dict[str, str] = field(default_factory=dict)


def read_notebook(path: str | os.PathLike) -> nbformat.NotebookNode:
    """The notebook at `path`; anything that is not a readable notebook raises `NotebookError`.

    The file is read within `scanviz.limits.current_file_limit()`. Only the
    structure the grader needs is checked (a list of cells, each with a type
    and a source), so notebooks from other front ends still read.
    """
    name = os.fspath(path)
    try:
        text = read_bounded(path)
    except (OSError, ValueError) as error:
        raise NotebookError(f"{name!r} cannot be read: {error}") from None
    if json_nesting(text)[0] > MAX_NESTING:
        raise NotebookError(f"{name!r} is not a notebook: JSON nested over {MAX_NESTING} levels")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise NotebookError(
            f"{name!r} is not valid JSON: {error.msg} at line {error.lineno} column {error.colno}"
        ) from None
    import nbformat  # on first use: importing it costs a second of a notebook's first cell

    return nbformat.from_dict(_checked(data, name))


def _checked(data: object, name: str) -> dict:
    if not isinstance(data, dict):
        raise NotebookError(f"{name!r} is not a notebook: the top level is not a JSON object")
    version = data.get("nbformat")
    if not isinstance(version, int) or isinstance(version, bool):
        raise NotebookError(f"{name!r} is not a notebook: it has no 'nbformat' version number")
    if version < 4:
        try:
            import nbformat

            data = nbformat.convert(nbformat.from_dict(data), 4)
        except Exception as error:
            raise NotebookError(
                f"{name!r}: a version {version} notebook that cannot be upgraded: {error}"
            ) from None
    cells = data.get("cells")
    if not isinstance(cells, list):
        raise NotebookError(f"{name!r} is not a notebook: 'cells' must be a list")
    for index, cell in enumerate(cells, 1):
        if not isinstance(cell, dict) or not isinstance(cell.get("cell_type"), str):
            raise NotebookError(f"{name!r}: cell {index} has no 'cell_type'")
        source = cell.get("source", "")
        if not (
            isinstance(source, str)
            or (isinstance(source, list) and all(isinstance(s, str) for s in source))
        ):
            raise NotebookError(
                f"{name!r}: cell {index}: 'source' must be a string or a list of strings"
            )
    return data


def _source(cell: dict) -> str:
    source = cell.get("source", "")
    return source if isinstance(source, str) else "".join(source)


def find_answers(notebook: dict) -> Answers:
    """The answer cells of `notebook`, found by their first lines (module docstring)."""
    from .catalog import exercises

    known = [e.id for e in exercises()]
    found = Answers()
    cells: dict[str, list[int]] = {}
    for index, cell in enumerate(notebook.get("cells", []), 1):
        if cell.get("cell_type") != "code":
            continue
        source = _source(cell)
        first = source.split("\n", 1)[0].rstrip()
        if first.startswith(ANSWER_MARKER):
            exercise_id = first[len(ANSWER_MARKER) :].strip()
            cells.setdefault(exercise_id, []).append(index)
            found.answers[exercise_id] = source  # the last marked cell wins
        else:
            _near_miss(source, index, known, found.problems)
    for exercise_id, where in cells.items():
        if exercise_id not in known:
            del found.answers[exercise_id]
            close = difflib.get_close_matches(exercise_id, known, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            found.problems[exercise_id] = (
                f"cell {where[0]} starts with {(ANSWER_MARKER + exercise_id)!r}: "
                f"unknown exercise {exercise_id!r}{hint}"
            )
            continue
        found.problems.pop(exercise_id, None)  # an almost-marker elsewhere does not matter
        if len(where) > 1:
            numbers = ", ".join(map(str, where[:-1])) + f" and {where[-1]}"
            found.notes[exercise_id] = (
                f"{len(where)} cells start with {(ANSWER_MARKER + exercise_id)!r} "
                f"(cells {numbers}): the last one, cell {where[-1]}, was graded"
            )
    return found


def _near_miss(source: str, index: int, known: list[str], problems: dict[str, str]) -> None:
    """Note a cell whose first non-blank line is almost an answer marker for a known exercise."""
    first = next((line.strip() for line in source.splitlines() if line.strip()), "")
    squeezed = "".join(first.lower().split())
    if not squeezed.startswith("#scanviz:answer"):
        return
    exercise_id = squeezed[len("#scanviz:answer") :]
    if exercise_id in known and exercise_id not in problems:
        problems[exercise_id] = (
            f"cell {index} starts with {first!r}, which is not the answer marker: the cell's "
            f"first line must be exactly {(ANSWER_MARKER + exercise_id)!r}"
        )


def merge_answers(parts: list[tuple[str, Answers]]) -> Answers:
    """The answers of several notebooks of one student, (name, answers) each, in name order.

    An exercise answered in two notebooks is graded from the one named as
    the released notebook of that exercise (``NN_<id>.ipynb``) if there is
    one, else from the last, and the feedback says so.
    """
    merged = Answers()
    found: dict[str, list[tuple[str, Answers]]] = {}
    for name, answers in parts:
        for exercise_id, problem in answers.problems.items():
            merged.problems.setdefault(exercise_id, f"{name}: {problem}")
        for exercise_id in answers.answers:
            found.setdefault(exercise_id, []).append((name, answers))
    for exercise_id, places in found.items():
        released = [p for p in places if p[0].endswith(f"_{exercise_id}.ipynb")]
        name, answers = (released or places)[-1]
        merged.answers[exercise_id] = answers.answers[exercise_id]
        merged.problems.pop(exercise_id, None)
        if len(places) > 1:
            names = ", ".join(p[0] for p in places)
            merged.notes[exercise_id] = (
                f"exercise {exercise_id!r} is answered in {len(places)} notebooks ({names}): "
                f"the one in {name} was graded"
            )
        elif exercise_id in answers.notes:
            merged.notes[exercise_id] = f"{name}: {answers.notes[exercise_id]}"
    return merged

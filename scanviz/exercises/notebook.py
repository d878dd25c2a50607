"""Read a student's notebook and find its answers by their marker lines.

An answer cell is a code cell whose first line is exactly
``# scanviz: answer <exercise-id>`` (trailing whitespace is tolerated); a
setup cell is a code cell whose first line is ``# scanviz: setup``. The
marker, not the cell's position or metadata, is how the grader finds an
answer, so it survives copying, reordering and re-downloading the notebook.
A marker in a markdown cell is ignored.

Examples
--------
>>> from nbformat import v4
>>> notebook = v4.new_notebook(cells=[
...     v4.new_markdown_cell("# scanviz: answer span_rule"),
...     v4.new_code_cell("# scanviz: setup\\nimport math"),
...     v4.new_code_cell("# scanviz: answer span_rule\\ndef span_rule(crossings, rule): ..."),
... ])
>>> found = find_answers(notebook)
>>> sorted(found.answers), len(found.setup), found.problems
(['span_rule'], 1, {})
"""

from __future__ import annotations

import difflib
import json
import os
from dataclasses import dataclass, field

import nbformat

from ..limits import json_nesting, read_bounded

ANSWER_MARKER = "# scanviz: answer "
SETUP_MARKER = "# scanviz: setup"
MAX_NESTING = 100  # JSON levels; a notebook's deepest (widget state) is far less


class NotebookError(ValueError):
    """The file is not a readable notebook (the message names the file and the problem)."""


@dataclass
class Answers:
    """What a notebook holds for the grader.

    ``answers`` maps an exercise id to its answer cell's whole source (marker
    line included, so line numbers match the cell); ``setup`` the setup cells'
    sources in notebook order; ``problems`` an exercise id to a message
    (duplicated marker, unknown id, a marker that is almost right);
    ``duplicated`` the ids whose marker starts more than one cell.
    """

    answers: dict[str, str] = field(default_factory=dict)
    setup: list[str] = field(default_factory=list)
    problems: dict[str, str] = field(default_factory=dict)
    duplicated: set[str] = field(default_factory=set)


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
    return nbformat.from_dict(_checked(data, name))


def _checked(data: object, name: str) -> dict:
    if not isinstance(data, dict):
        raise NotebookError(f"{name!r} is not a notebook: the top level is not a JSON object")
    version = data.get("nbformat")
    if not isinstance(version, int) or isinstance(version, bool):
        raise NotebookError(f"{name!r} is not a notebook: it has no 'nbformat' version number")
    if version < 4:
        try:
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
    """The answer and setup cells of `notebook`, found by their first lines (module docstring)."""
    from .catalog import exercises

    known = [e.id for e in exercises()]
    found = Answers()
    cells: dict[str, list[int]] = {}
    for index, cell in enumerate(notebook.get("cells", []), 1):
        if cell.get("cell_type") != "code":
            continue
        source = _source(cell)
        first = source.split("\n", 1)[0].rstrip()
        if first == SETUP_MARKER:
            found.setup.append(source)
        elif first.startswith(ANSWER_MARKER):
            exercise_id = first[len(ANSWER_MARKER) :].strip()
            cells.setdefault(exercise_id, []).append(index)
            found.answers.setdefault(exercise_id, source)
        else:
            _near_miss(source, index, known, found.problems)
    for exercise_id, where in cells.items():
        if exercise_id in known and len(where) == 1:
            found.problems.pop(exercise_id, None)  # an almost-marker elsewhere does not matter
        elif exercise_id not in known:
            del found.answers[exercise_id]
            close = difflib.get_close_matches(exercise_id, known, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            found.problems[exercise_id] = (
                f"cell {where[0]} starts with {(ANSWER_MARKER + exercise_id)!r}: "
                f"unknown exercise {exercise_id!r}{hint}"
            )
        elif len(where) > 1:
            del found.answers[exercise_id]
            found.duplicated.add(exercise_id)
            numbers = ", ".join(map(str, where[:-1])) + f" and {where[-1]}"
            found.problems[exercise_id] = (
                f"exercise {exercise_id!r}: {len(where)} cells start with "
                f"{(ANSWER_MARKER + exercise_id)!r} (cells {numbers}); keep one"
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
    """The answers of several notebooks of one student, (name, answers) each.

    An exercise answered in two notebooks is a duplicate, named with both
    notebooks; setup cells run in the order of the notebooks.
    """
    merged = Answers()
    where: dict[str, str] = {}
    for name, answers in parts:
        merged.setup.extend(answers.setup)
        merged.duplicated |= answers.duplicated
        for exercise_id, problem in answers.problems.items():
            merged.problems.setdefault(exercise_id, f"{name}: {problem}")
        for exercise_id, source in answers.answers.items():
            if exercise_id in where:
                merged.duplicated.add(exercise_id)
                merged.problems[exercise_id] = (
                    f"exercise {exercise_id!r} is answered in two notebooks "
                    f"({where[exercise_id]} and {name}); keep one"
                )
                continue
            where[exercise_id] = name
            merged.answers[exercise_id] = source
    for exercise_id in merged.duplicated:  # as in one notebook: a duplicate is not graded
        merged.answers.pop(exercise_id, None)
    return merged

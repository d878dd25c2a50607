"""Grading benchmark: students graded per minute with ``--jobs 1`` and ``--jobs 2``.

A synthetic class of notebooks, one per student: student k answers exercise
e with the catalog's solution or one of its known-wrong variants, option
``k % (1 + len(e.variants))`` (so student 0 is all correct), each in an
answer cell whose first line is the marker ``# scanviz: answer <id>``. The
class is graded with a fresh course key (random secret, default hidden
cases and limits), every answer in the jail (bubblewrap; unjailed where it
cannot start, and the table says so), once with each number of jobs
(judging processes); the grades must agree. ``speedup`` is one job's time
over this one's.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import nbformat

from ..exercises.catalog import exercises
from ..exercises.release import answer_cell_source, notebook_text

STUDENTS = 20  # the class size; --quick grades 2
QUICK_EXERCISES = 3  # --quick grades the catalog's first 3 exercises
JOBS = (1, 2)


def synthetic_notebook(student: int) -> nbformat.NotebookNode:
    """Student `student`'s notebook: an answer cell per exercise (see the module docstring)."""
    cells = [nbformat.v4.new_markdown_cell(f"Synthetic submission {student}")]
    for exercise in exercises():
        options = [exercise.solution, *(v.source for v in exercise.variants)]
        body = options[student % len(options)]
        cells.append(nbformat.v4.new_code_cell(answer_cell_source(exercise, body)))
    return nbformat.v4.new_notebook(cells=cells)


def synthetic_class(folder: Path, students: int) -> list[Path]:
    """Write `students` synthetic notebooks ``student-NN.ipynb`` into `folder`."""
    paths = []
    for k in range(students):
        path = folder / f"student-{k:02d}.ipynb"
        path.write_text(notebook_text(synthetic_notebook(k)), encoding="utf-8")
        paths.append(path)
    return paths


def _table(grades) -> list[tuple]:
    return [(s.student, g.exercise, round(g.score, 9), g.status) for s in grades for g in s.grades]


def run_grading(*, quick: bool = False, students: int | None = None) -> list[dict]:
    """Grade a synthetic class with each of `JOBS`; print and return the rates."""
    from ..exercises.grading import grade_submissions
    from ..exercises.jail import launch
    from ..exercises.key import new_key

    students = students or (2 if quick else STUDENTS)
    jail = "bwrap" if launch.unavailable("bwrap") is None else "none"
    catalog = exercises()[:QUICK_EXERCISES] if quick else exercises()
    key = new_key([e.id for e in catalog])
    rows, tables = [], []
    cases = sum(len(e.public) + key.exercises[e.id].hidden_cases for e in catalog)
    print(
        f"grading: {students} synthetic students x {len(catalog)} exercises (solutions and "
        f"known-wrong variants), {cases} public and hidden cases per student, a fresh course key, "
        f"answers run {'in bubblewrap' if jail == 'bwrap' else 'unjailed (no bubblewrap here)'}"
    )
    print(f"{'jobs':>4}{'seconds':>10}{'students/min':>14}{'s/student':>11}{'speedup':>9}")
    with tempfile.TemporaryDirectory(prefix="scanviz-bench-grading-") as folder:
        synthetic_class(Path(folder), students)
        for jobs in JOBS:
            started = time.perf_counter()
            grades = grade_submissions(folder, key, jobs=jobs, progress=False, jail=jail)
            seconds = time.perf_counter() - started
            tables.append(_table(grades))
            rows.append({"jobs": jobs, "seconds": seconds, "per_minute": 60 * students / seconds})
            print(
                f"{jobs:>4}{seconds:>10.1f}{60 * students / seconds:>14.1f}"
                f"{seconds / students:>11.2f}{rows[0]['seconds'] / seconds:>9.2f}"
            )
    first = next(s for s in grades if "student-00" in s.student)
    print(
        f"student-00 (every solution): {first.score:g} of {first.max_score:g} points; "
        f"same grades with every --jobs: {'yes' if all(t == tables[0] for t in tables) else 'NO'}"
    )
    return rows

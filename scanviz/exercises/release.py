"""Student notebooks made from the catalog: ``notebooks/exercises/NN_<id>.ipynb``.

Each notebook has the idea in a few lines, a stepper on the reference, the
answer cell and a check cell. The answer cell's first line is exactly
``# scanviz: answer <id>``: that marker, not the cell's position or metadata,
is how the grader finds the answer. The teacher's copy (`with_solutions`)
has the solution in the answer cell instead of the stub.
"""

from __future__ import annotations

from pathlib import Path

import nbformat

from .catalog import exercises
from .core import Exercise
from .notebook import ANSWER_MARKER

KERNEL = {"display_name": "Python 3", "language": "python", "name": "python3"}


def notebook_name(exercise: Exercise) -> str:
    """``NN_<id>.ipynb``, NN the exercise's number in the course."""
    return f"{exercise.number:02d}_{exercise.id}.ipynb"


def answer_cell_source(exercise: Exercise, body: str) -> str:
    """The answer cell: the marker line, then `body` (the stub or an answer)."""
    return f"{ANSWER_MARKER}{exercise.id}\n{body.rstrip()}\n"


def _intro(exercise: Exercise) -> str:
    what = (
        f"Write the step `{exercise.answer}`; the real algorithm runs with it plugged in, so "
        "the trace shows what your step does."
        if exercise.kind == "step"
        else f"Write the whole loop `{exercise.answer}`, emitting the events to the `tracer` "
        "you are given; they are compared event by event with the reference."
    )
    return (
        f"# Exercise {exercise.number:02d} · {exercise.title}\n\n"
        f"*{exercise.stage} · {exercise.points} points · id `{exercise.id}`*\n\n"
        f"{exercise.idea.strip()}\n\n{what}"
    )


_HOW = (
    "## Your answer\n\n"
    "Keep the first line of the next cell exactly as it is: it tells the grader where your "
    "answer is (you may move the cell; if several cells start with it, the last one is "
    "graded). **Only this cell is graded, and it runs alone**, in a fresh Python with the "
    "standard library, numpy and `scanviz.trace.events`: import what it uses in the cell "
    "itself (nothing else of scanviz is there). Run it, then run the check below, which runs "
    "it exactly that way."
)

_CHECK = (
    "## Check\n\n"
    "The check runs the public cases and shows, for the first case that differs, the first "
    "diverging event, where else it differs, the samples you miss or add, and a likely "
    "cause. Hidden cases are run when your work is graded. Try more random cases with "
    '`check("{id}", practice=20)`.'
)


def build_notebook(exercise: Exercise, *, with_solution: bool = False) -> nbformat.NotebookNode:
    """The student notebook of `exercise` (the teacher's solved copy if `with_solution`)."""
    prefix = f"{exercise.number:02d}"
    cells = [
        nbformat.v4.new_markdown_cell(_intro(exercise)),
        nbformat.v4.new_code_cell(
            "%matplotlib widget\n"
            "from scanviz.exercises import check, public_inputs\n\n"
            f'CASE = public_inputs("{exercise.id}")  # the first public case\n'
            f"{exercise.stepper.strip()}"
        ),
        nbformat.v4.new_markdown_cell(_HOW),
        nbformat.v4.new_code_cell(
            answer_cell_source(exercise, exercise.solution if with_solution else exercise.stub)
        ),
        nbformat.v4.new_markdown_cell(_CHECK.format(id=exercise.id)),
        nbformat.v4.new_code_cell(f'check("{exercise.id}")'),
    ]
    for index, cell in enumerate(cells):
        cell["id"] = f"{prefix}-{index:02d}"
    notebook = nbformat.v4.new_notebook(cells=cells, metadata={"kernelspec": KERNEL})
    nbformat.validate(notebook)
    return notebook


def notebook_text(notebook: nbformat.NotebookNode) -> str:
    """The notebook's JSON as written to disk (one fixed format, so released files compare)."""
    return nbformat.writes(notebook) + "\n"


def write_notebooks(out_dir: str | Path, *, with_solutions: bool = False) -> list[Path]:
    """Write every exercise's notebook into `out_dir` (created if needed); return the paths."""
    out_dir = Path(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise NotADirectoryError(f"OUT_DIR {str(out_dir)!r} exists and is not a folder")
    out_dir.mkdir(parents=True, exist_ok=True)
    paths = []
    for exercise in exercises():
        path = out_dir / notebook_name(exercise)
        path.write_text(
            notebook_text(build_notebook(exercise, with_solution=with_solutions)), encoding="utf-8"
        )
        paths.append(path)
    return paths

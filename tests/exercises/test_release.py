"""Released notebooks: one per exercise, in the repository exactly as the catalog makes them."""

import dataclasses
from pathlib import Path

import nbformat
import pytest

from scanviz.exercises import exercises
from scanviz.exercises.release import (
    ANSWER_MARKER,
    build_notebook,
    notebook_name,
    notebook_text,
    write_notebooks,
)

FOLDER = Path(__file__).parents[2] / "notebooks" / "exercises"


def test_the_catalog_has_at_least_twelve_exercises_with_unique_ids():
    catalog = exercises()
    assert len(catalog) >= 12
    assert len({e.id for e in catalog}) == len(catalog)
    assert [e.number for e in catalog] == sorted(e.number for e in catalog)


@pytest.mark.parametrize("exercise", exercises(), ids=lambda e: e.id)
def test_repository_notebook_is_the_released_one(exercise):
    path = FOLDER / notebook_name(exercise)
    assert path.exists(), "run: python -m scanviz exercises release notebooks/exercises"
    assert path.read_text(encoding="utf-8") == notebook_text(build_notebook(exercise)), (
        f"{path.name} is out of date: python -m scanviz exercises release notebooks/exercises"
    )


def test_no_stray_notebooks_in_the_exercise_folder():
    expected = {notebook_name(e) for e in exercises()}
    assert {p.name for p in FOLDER.glob("*.ipynb")} == expected


@pytest.mark.parametrize("exercise", exercises(), ids=lambda e: e.id)
def test_answer_cell_starts_with_the_marker_and_holds_the_stub(exercise):
    for with_solution, body in ((False, exercise.stub), (True, exercise.solution)):
        notebook = build_notebook(exercise, with_solution=with_solution)
        answers = [c for c in notebook.cells if c.source.startswith(ANSWER_MARKER)]
        assert len(answers) == 1
        first, rest = answers[0].source.split("\n", 1)
        assert first == f"# scanviz: answer {exercise.id}"
        assert rest.strip() == body.strip()


def test_write_notebooks_writes_valid_notebooks(tmp_path):
    paths = write_notebooks(tmp_path / "out", with_solutions=True)
    assert [p.name for p in paths] == [notebook_name(e) for e in exercises()]
    for path in paths:
        nbformat.validate(nbformat.read(path, as_version=4))


def test_write_notebooks_refuses_a_file_as_folder(tmp_path):
    target = tmp_path / "file"
    target.write_text("x")
    with pytest.raises(NotADirectoryError, match="is not a folder"):
        write_notebooks(target)


def test_released_blank_notebooks_score_zero_and_solved_ones_full_marks(tmp_path):
    from scanviz.exercises.grading import grade_submissions
    from scanviz.exercises.key import ExerciseKey, new_key

    write_notebooks(tmp_path / "class" / "blank")
    write_notebooks(tmp_path / "class" / "solved", with_solutions=True)
    key = dataclasses.replace(
        new_key(),
        secret="fixed secret of the release test",
        exercises={e.id: ExerciseKey(e.points, 2) for e in exercises()},
    )
    grades = {
        s.student: s for s in grade_submissions(tmp_path / "class", key, jobs=2, progress=False)
    }
    solved, blank = grades["solved"], grades["blank"]
    assert [(g.exercise, g.status) for g in solved.grades] == [
        (e.id, "passed") for e in exercises()
    ]
    assert solved.score == solved.max_score == sum(e.points for e in exercises())
    assert blank.score == 0 and {g.status for g in blank.grades} == {"error"}


def test_docs_list_every_exercise_variant_and_step():
    from scanviz import steps

    text = (Path(__file__).parents[2] / "docs" / "exercises.md").read_text(encoding="utf-8")
    for exercise in exercises():
        row = next((line for line in text.splitlines() if f"| `{exercise.id}` |" in line), "")
        assert row, f"docs/exercises.md has no catalog row for {exercise.id!r}"
        for variant in exercise.variants:
            assert f"`{variant.name}`" in row, (exercise.id, variant.name)
        features = f"| `{exercise.id}` | " + "; ".join(exercise.features) + " |"
        assert features in text, f"docs/exercises.md: the features of {exercise.id!r} changed"
    for step in steps.table():
        assert f"| `{step.name}` | `{step.module.removeprefix('scanviz.')}` |" in text, step.name


@pytest.mark.parametrize(
    "exercise", [e for e in exercises() if e.kind == "step"], ids=lambda e: e.id
)
def test_every_case_of_a_step_exercise_calls_the_step(exercise):
    # A case the step never runs in would give full marks to any answer, the stub included.
    from scanviz.exercises.core import practice_cases, reference_outcome

    for case in [*exercise.public, *practice_cases(exercise, 10, seed=1)]:
        assert reference_outcome(exercise, case).calls, (exercise.id, case.label)


def test_released_notebooks_hold_no_hidden_input(tmp_path):
    import json

    from scanviz.exercises.core import hidden_cases
    from scanviz.exercises.jail.wire import encode as to_plain

    text = "".join(p.read_text(encoding="utf-8") for p in write_notebooks(tmp_path))
    for exercise in exercises():
        for case in hidden_cases(exercise, "a course secret", 8):
            for value in case.inputs.values():
                shown = json.dumps(to_plain(value))
                if len(shown) > 12:  # long enough not to occur by chance
                    assert shown not in text, (exercise.id, case.label)

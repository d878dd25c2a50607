"""Grading a folder of notebooks and checking one (scanviz.exercises.grading)."""

from pathlib import Path

import nbformat
import pytest
from nbformat import v4

from scanviz.exercises import judging
from scanviz.exercises.catalog import get
from scanviz.exercises.core import compile_answer, hidden_cases, reference_outcome, run_case
from scanviz.exercises.grading import check_notebook, find_submissions, grade_submissions, in_shard
from scanviz.exercises.jail import JailUnavailable, launch
from scanviz.exercises.key import CourseKey, ExerciseKey
from scanviz.exercises.notebook import ANSWER_MARKER, NotebookError
from scanviz.exercises.verdict import judge

SECRET = "5ec2e7" * 8
SPAN = get("span_rule")
HIDDEN = 2


def _key(per_student=False, secret=SECRET):
    return CourseKey(
        secret, "never", per_student, 60.0, 1024, 2.0, {"span_rule": ExerciseKey(4, HIDDEN)}
    )


def _answer(body, exercise=SPAN):
    return v4.new_code_cell(f"{ANSWER_MARKER}{exercise.id}\n{body}")


def _write(path: Path, *cells) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(v4.new_notebook(cells=[v4.new_markdown_cell("# Exercise"), *cells]), path)
    return path


def _wrapped(prelude, call="_answer(crossings, rule)"):
    return f"{SPAN.solution}\n_answer = span_rule\ndef span_rule(crossings, rule):\n    {prelude}\n    return {call}\n"


HOSTILE = {  # student id -> (answer body, status)
    "loops": ("def span_rule(crossings, rule):\n    while True:\n        pass\n", "timeout"),
    "allocates": ("def span_rule(crossings, rule):\n    return bytearray(10 * 2**30)\n", "memory"),
    "raises": ("def span_rule(crossings, rule):\n    raise KeyError(rule)\n", "error"),
    "exits": ("import os\n" + _wrapped("os._exit(0)"), "crashed"),
    "patches": (
        "import scanviz.raster.scanline\nscanviz.raster.scanline.span_rule = lambda c, r: []\n",
        "error",
    ),
    "typo": ("def span_rule(crossings, rule)\n    return []\n", "syntax error"),
}


def _expected_score(body, key):
    """The score of `body`, run and judged in this process, without the grader or the sandbox."""
    function = compile_answer(body, SPAN.answer, "<answer span_rule>")
    cases = list(SPAN.public) + hidden_cases(SPAN, key.secret, HIDDEN)
    passed = sum(
        judge(SPAN, c, run_case(SPAN, function, c), reference_outcome(SPAN, c)).passed
        for c in cases
    )
    return 4 * passed / len(cases)


def test_a_synthetic_class_grades_correctly(tmp_path):
    folder = tmp_path / "submitted"
    _write(folder / "correct.ipynb", _answer(SPAN.solution))
    moved = v4.new_code_cell(
        f"{ANSWER_MARKER}span_rule\n{SPAN.solution}", metadata={"tags": ["copied"]}
    )
    _write(
        folder / "reordered" / "work.ipynb",
        v4.new_code_cell("x = 1"),
        v4.new_markdown_cell("notes"),
        moved,
    )
    _write(
        folder / "noisy.ipynb",
        _answer("import sys\n" + _wrapped("print('debug', crossings, file=sys.stderr)")),
    )
    _write(folder / "stub.ipynb", _answer(SPAN.stub))
    for variant in SPAN.variants:
        _write(folder / f"variant-{variant.name}.ipynb", _answer(variant.source))
    for student, (body, _) in HOSTILE.items():
        _write(folder / f"{student}.ipynb", _answer(body))
    (folder / "broken.ipynb").write_text('{"cells": [')
    _write(folder / "empty.ipynb", v4.new_code_cell("print('no answer here')"))
    _write(folder / "twice.ipynb", _answer(SPAN.variants[0].source), _answer(SPAN.solution))
    key = _key()
    grades = {g.student: g.grades for g in grade_submissions(folder, key, jobs=2, progress=False)}
    assert len(grades) == 7 + len(SPAN.variants) + len(HOSTILE)
    assert all(
        len(g) == 1 and g[0].exercise == "span_rule" and g[0].max_score == 4
        for g in grades.values()
    )
    got = {student: (g[0].score, g[0].status) for student, g in grades.items()}
    for student in ("correct", "reordered", "noisy"):
        assert got[student] == (4.0, "passed"), grades[student][0].message
        public, hidden = len(SPAN.public), max(HIDDEN, len(SPAN.features))
        assert grades[student][0].public_passed == (public, public)
        assert grades[student][0].hidden_passed == (hidden, hidden)
    assert got["stub"] == (0.0, "error")
    assert "no known mistake" not in grades["stub"][0].message
    assert "NotImplementedError" in grades["stub"][0].message
    for variant in SPAN.variants:
        grade = grades[f"variant-{variant.name}"][0]
        assert grade.status == "failed" and grade.score == _expected_score(variant.source, key) < 4
        assert variant.name in {v.variant.name for v in grade.verdicts if v.variant}
    for student, (_, status) in HOSTILE.items():
        assert got[student] == (0.0, status), grades[student][0].message
    assert got["broken"] == (0.0, "malformed notebook")
    assert "is not valid JSON" in grades["broken"][0].message
    assert got["empty"] == (0.0, "no answer")
    assert got["twice"] == (4.0, "passed")  # the last of the two marked cells
    assert "(cells 2 and 3): the last one, cell 3, was graded" in grades["twice"][0].message
    assert "ModuleNotFoundError: No module named 'scanviz.raster'" in grades["patches"][0].message


def test_same_key_and_submissions_give_the_same_grades_and_references_are_computed_once(
    tmp_path, monkeypatch
):
    calls = []
    monkeypatch.setattr(
        judging, "reference_outcome", lambda e, c: calls.append(c) or reference_outcome(e, c)
    )
    folder = tmp_path / "class"
    _write(folder / "ann.ipynb", _answer(SPAN.solution))
    _write(folder / "ben.ipynb", _answer(SPAN.solution))
    _write(folder / "cat.ipynb", _answer(SPAN.variants[0].source))

    def table(grades):
        return [
            (
                s.student,
                g.exercise,
                g.score,
                g.status,
                g.message,
                [v.describe() for v in g.verdicts],
            )
            for s in grades
            for g in s.grades
        ]

    first = table(grade_submissions(folder, _key(), jobs=1, progress=False))
    # once per case, reused for the three students (a hidden case per feature at least)
    assert len(calls) == len(SPAN.public) + max(HIDDEN, len(SPAN.features))
    assert table(grade_submissions(folder, _key(), jobs=2, progress=False)) == first


def test_hidden_cases_come_from_the_secret_and_per_student_from_the_student_too(tmp_path):
    folder = tmp_path / "class"
    _write(folder / "ann.ipynb", _answer(SPAN.solution))
    _write(folder / "ben.ipynb", _answer(SPAN.solution))

    def hidden(key):
        return {
            s.student: [dict(v.case.inputs) for v in s.grades[0].verdicts if v.hidden]
            for s in grade_submissions(folder, key, progress=False)
        }

    shared, own = hidden(_key()), hidden(_key(per_student=True))
    assert shared["ann"] == shared["ben"] and own["ann"] != own["ben"]
    assert hidden(_key(secret="ab" * 16))["ann"] != shared["ann"]


def test_find_submissions_knows_the_layouts(tmp_path):
    root = tmp_path / "submitted"
    paths = {
        "alice": _write(root / "alice.ipynb"),
        "bob": _write(root / "bob" / "work.ipynb"),
        "bob.ipynb": _write(root / "bob.ipynb"),
        "carol": _write(root / "carol" / "ps1" / "x.ipynb"),
        "frank": _write(root / "frank" / "y.ipynb"),
    }
    _write(root / ".ipynb_checkpoints" / "alice-checkpoint.ipynb")
    _write(root / "frank" / ".ipynb_checkpoints" / "y-checkpoint.ipynb")
    _write(root / "dave" / "a.ipynb")
    _write(root / "dave" / "b.ipynb")
    (root / "erin").mkdir()
    (root / "notes.txt").write_text("not a submission")
    paths.update(dave=root / "dave", erin=root / "erin")
    assert find_submissions(root) == sorted(paths.items())
    with pytest.raises(ValueError, match="must be a folder of submissions"):
        find_submissions(root / "alice.ipynb")


def test_a_student_folder_of_notebooks_is_graded_as_one_submission(tmp_path):
    root = tmp_path / "submitted"
    wrong = SPAN.variants[0].source
    _write(root / "dave" / "05_span_rule.ipynb", _answer(SPAN.solution))
    _write(root / "dave" / "notes.ipynb")  # no answer in it: nothing to merge
    _write(root / "gina" / "a.ipynb", _answer(SPAN.solution))
    _write(root / "gina" / "b.ipynb", _answer(wrong))
    (root / "erin").mkdir()
    grades = {s.student: s.grades[0] for s in grade_submissions(root, _key(), progress=False)}
    assert grades["dave"].status == "passed" and grades["dave"].score == 4
    assert grades["gina"].status == "failed"  # b.ipynb, the last: the variant
    assert "answered in 2 notebooks (a.ipynb, b.ipynb): the one in b.ipynb was graded" in (
        grades["gina"].message
    )
    assert grades["erin"].status == "malformed notebook"
    assert "holds no notebook" in grades["erin"].message


def test_grade_submissions_checks_its_arguments(tmp_path):
    with pytest.raises(ValueError, match="'jobs' must be an integer >= 1"):
        grade_submissions(tmp_path, _key(), jobs=0)
    with pytest.raises(
        ValueError, match=r"'span_rul' is not in the course key \(did you mean 'span_rule'"
    ):
        grade_submissions(tmp_path, _key(), exercises=["span_rul"])


def test_check_notebook_runs_the_public_cases_only(tmp_path):
    grade = check_notebook(_write(tmp_path / "mine.ipynb", _answer(SPAN.solution)))
    assert grade.student == "mine" and [g.status for g in grade.grades] == ["passed"]
    assert grade.grades[0].public_passed == (len(SPAN.public), len(SPAN.public))
    assert grade.grades[0].hidden_passed == (0, 0)
    variant = check_notebook(_write(tmp_path / "wrong.ipynb", _answer(SPAN.variants[0].source)))
    assert variant.grades[0].status == "failed" and variant.grades[0].score < SPAN.points
    nothing = tmp_path / "nothing.ipynb"
    _write(nothing, v4.new_code_cell("x = 1"))
    assert check_notebook(nothing).grades == []
    assert [g.status for g in check_notebook(nothing, ["span_rule"]).grades] == ["no answer"]
    (tmp_path / "bad.ipynb").write_text("{")
    with pytest.raises(NotebookError, match="bad.ipynb"):
        check_notebook(tmp_path / "bad.ipynb")


def test_shards_split_a_class_and_together_grade_it_whole(tmp_path):
    folder = tmp_path / "class"
    for name in ("ann", "ben", "cat", "dan", "eve"):
        _write(folder / f"{name}.ipynb", _answer(SPAN.solution))
    whole = [s.student for s in grade_submissions(folder, _key(), progress=False)]
    parts = [
        [s.student for s in grade_submissions(folder, _key(), progress=False, shard=(k, 3))]
        for k in (1, 2, 3)
    ]
    assert sorted(sum(parts, [])) == whole
    assert all(in_shard(student, (k + 1, 3)) for k, part in enumerate(parts) for student in part)
    with pytest.raises(ValueError, match=r"'shard' must be \(k, n\) with 1 <= k <= n"):
        grade_submissions(folder, _key(), shard=(4, 3))


def test_grading_refuses_without_a_jail_and_says_how_to_go_on(tmp_path, monkeypatch):
    monkeypatch.setattr(
        launch, "unavailable", lambda jail="bwrap": None if jail == "none" else f"no {jail} here"
    )
    with pytest.raises(JailUnavailable, match=r"\(bwrap: no bwrap here\)\. Pass --no-jail"):
        grade_submissions(tmp_path, _key(), progress=False)
    with pytest.raises(JailUnavailable, match="bwrap: no bwrap here; user: no user here"):
        grade_submissions(tmp_path, _key(), progress=False, jail="auto")
    _write(tmp_path / "ann.ipynb", _answer(SPAN.solution))
    grades = grade_submissions(tmp_path, _key(), progress=False, jail="none")
    assert grades[0].grades[0].status == "passed"


def test_a_key_the_jail_could_see_is_refused(tmp_path, monkeypatch):
    key = tmp_path / "key.toml"
    from scanviz.exercises.key import write_key

    write_key(_key(), key)
    monkeypatch.setattr(launch, "visible", lambda path: str(path) == str(key))
    with pytest.raises(ValueError, match="lies inside what the jail shows"):
        grade_submissions(tmp_path, key, progress=False)

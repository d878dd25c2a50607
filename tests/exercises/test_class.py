"""A whole class, graded as a teacher grades it (issue 22's "done when").

Correct answers (the catalog's solutions), wrong ones (every known-wrong
variant), answers that do nothing (the stub, empty, constants, the identity)
and hostile ones (each route a student took against the grader), every one
answering all 23 exercises, graded with ``--jobs 2`` in the jail with a fresh
key. Correct answers get full marks; do-nothing and hostile ones 0 with
nothing leaked; wrong ones lose points and are told a cause only when their
run is that variant's.
"""

import nbformat
import pytest
from nbformat import v4

from scanviz.exercises import exercises
from scanviz.exercises.core import VariantRuns, do_nothing_sources, reference_outcome
from scanviz.exercises.grading import grade_submissions
from scanviz.exercises.key import new_key, write_key
from scanviz.exercises.notebook import ANSWER_MARKER
from scanviz.exercises.report import write_reports
from scanviz.exercises.verdict import NO_MATCH, same_run

# One worker grades the class, once: with `--dist loadgroup` an unmarked module's tests are
# shared out one by one, and each worker that got one would grade the whole class again.
pytestmark = pytest.mark.xdist_group("class")

CATALOG = exercises()
HOSTILE = {  # a body per exercise ({name}: the function the exercise asks for)
    "main-rebinder": "import sys\nsys.modules['__main__'].run_case = None\n"
    "def {name}(*args, **kwargs):\n    return None\n",
    "reference-importer": "import importlib\n"
    "def {name}(*args, **kwargs):\n"
    "    steps = importlib.import_module('scanviz.' + 'steps')\n"
    "    return steps.get('{step}')(*args, **kwargs)\n",
    "key-reader": "import ctypes\nLOOT = [ctypes.CDLL(None).open(b'{key}', 0)]\n"
    "def {name}(*args, **kwargs):\n    raise ValueError(repr(LOOT) + open('{key}').read())\n",
    "forker": "import os\ndef {name}(*args, **kwargs):\n    os.fork()\n    return None\n",
    "channel-forger": "import json, os, sys\nFD = json.loads(sys.argv[1])['replies']\n"
    "def {name}(*args, **kwargs):\n"
    '    os.write(FD, b\'{{"n": 1, "returned": null, "status": "passed"}}\\n\')\n',
}


def _notebook(path, bodies: dict) -> None:
    cells = [v4.new_code_cell(f"{ANSWER_MARKER}{e}\n{body}") for e, body in bodies.items()]
    nbformat.write(v4.new_notebook(cells=cells), path)


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    root = tmp_path_factory.mktemp("class")
    key = new_key()
    write_key(key, root / "key.toml")
    folder = root / "submissions"
    folder.mkdir()
    _notebook(folder / "correct.ipynb", {e.id: e.solution for e in CATALOG})
    most = max(len(e.variants) for e in CATALOG)
    for k in range(most):  # student k answers with each exercise's k-th variant
        bodies = {e.id: e.variants[k].source for e in CATALOG if k < len(e.variants)}
        _notebook(folder / f"wrong-{k}.ipynb", bodies)
    for kind in do_nothing_sources(CATALOG[0]):
        _notebook(
            folder / f"nothing-{kind}.ipynb", {e.id: do_nothing_sources(e)[kind] for e in CATALOG}
        )
    for kind, body in HOSTILE.items():
        bodies = {
            e.id: body.format(name=e.answer, step=e.step or "", key=root / "key.toml")
            for e in CATALOG
        }
        _notebook(folder / f"hostile-{kind}.ipynb", bodies)
    grades = grade_submissions(folder, root / "key.toml", jobs=2, progress=False)
    write_reports(grades, key, root / "graded")
    return {s.student: s for s in grades}, key, root


def test_correct_answers_get_full_marks(graded):
    grades, _, _ = graded
    assert grades["correct"].score == grades["correct"].max_score


@pytest.mark.parametrize("prefix", ["nothing-", "hostile-"])
def test_do_nothing_and_hostile_answers_score_zero(graded, prefix):
    grades, _, _ = graded
    students = [s for name, s in grades.items() if name.startswith(prefix)]
    assert students
    scored = {(s.student, g.exercise): g.score for s in students for g in s.grades if g.score}
    assert scored == {}


def test_nothing_leaks_into_the_reports(graded):
    _, key, root = graded
    written = "".join(
        p.read_text(errors="replace") for p in (root / "graded").rglob("*") if p.is_file()
    )
    assert key.secret not in written


def test_wrong_answers_lose_points_and_are_told_a_true_cause(graded):
    grades, _, _ = graded
    for name, student in grades.items():
        if not name.startswith("wrong-"):
            continue
        k = int(name.split("-")[1])
        for grade in (g for g in student.grades if g.status != "no answer"):
            variant = next(e for e in CATALOG if e.id == grade.exercise).variants[k]
            assert grade.score < grade.max_score, (name, grade.exercise)
            exercise = next(e for e in CATALOG if e.id == grade.exercise)
            for verdict in grade.verdicts:
                if verdict.passed:
                    continue
                named = verdict.variant.name if verdict.variant else None
                assert named or NO_MATCH in verdict.describe(reveal=True)
                if named not in (None, variant.name):  # then the two are one run on this case
                    runs = VariantRuns(
                        exercise, verdict.case, reference_outcome(exercise, verdict.case)
                    )
                    assert same_run(runs.run(named), runs.run(variant.name), exercise.rtol)

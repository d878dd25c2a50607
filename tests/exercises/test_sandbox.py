"""The sandbox: hostile answers get a status and the grader goes on (sandbox.py, worker.py)."""

import os

import pytest

from scanviz.exercises import sandbox
from scanviz.exercises.catalog import exercises, get
from scanviz.exercises.core import judge, reference_outcome
from scanviz.exercises.notebook import ANSWER_MARKER, Answers
from scanviz.exercises.sandbox import Limits, run_submission
from scanviz.exercises.worker import banned_use

LIMITS = Limits(cpu_seconds=60.0, memory_mb=1024, case_seconds=1.5)

# A hostile answer body (__NAME__: the function the exercise asks for, __SOLUTION__: the
# catalog's solution), the status it must get, and a piece of the message.
HOSTILE = {
    "loop": ("def __NAME__(*args, **kwargs):\n    while True:\n        pass\n", "timeout", "time"),
    "alarm ignored": (
        "import signal, time\nsignal.signal(signal.SIGALRM, signal.SIG_IGN)\n"
        "def __NAME__(*args, **kwargs):\n    time.sleep(60)\n",
        "timeout",
        "stopped",
    ),
    "10 GB": (
        "def __NAME__(*args, **kwargs):\n    return bytearray(10 * 2**30)\n",
        "memory",
        "memory",
    ),
    "raises": (
        "def __NAME__(*args, **kwargs):\n    raise ValueError('no idea')\n",
        "error",
        "ValueError: no idea (in __NAME__, line 3)",
    ),
    "sys.exit": (
        "import sys\ndef __NAME__(*args, **kwargs):\n    sys.exit(1)\n",
        "not allowed",
        "sys.exit",
    ),
    "os._exit": (
        "import os\ndef __NAME__(*args, **kwargs):\n    os._exit(0)\n",
        "not allowed",
        "os._exit",
    ),
    "patches scanviz": (
        "import importlib\n"
        "setattr(importlib.import_module('scanviz.raster.' + 'scanline'), 'span_' + 'rule', None)\n"
        "__SOLUTION__",
        "not allowed",
        "scanviz.raster.scanline.span_rule",
    ),
    "patches span_rule by name": (
        "import scanviz.raster.scanline\nscanviz.raster.scanline.span_rule = None\n__SOLUTION__",
        "not allowed",
        "scanviz.raster.scanline",
    ),
    "reads /etc/passwd": (
        "def __NAME__(*args, **kwargs):\n    return open('/etc/passwd').read()\n",
        "not allowed",
        "'/etc/passwd', outside its folder",
    ),
    "syntax error": ("def __NAME__(*args, **kwargs)\n    return 1\n", "syntax error", "line 2"),
    "not defined": (
        "def __NAME___v2(*args, **kwargs):\n    return 1\n",
        "not defined",
        "does not define a function '__NAME__'",
    ),
    "segfault": (
        "import ctypes\ndef __NAME__(*args, **kwargs):\n    ctypes.string_at(0)\n",
        "crashed",
        "SIGSEGV",
    ),
    "prints to stderr": (
        "__SOLUTION__\nimport sys\n_answer = __NAME__\n"
        "def __NAME__(*args, **kwargs):\n    print('debugging', file=sys.stderr)\n"
        "    return _answer(*args, **kwargs)\n",
        "passed",
        "",
    ),
    "fakes the channel": (
        "import json, os\n"
        "line = json.dumps({'done': '__ID__', 'status': 'passed', 'message': '', 'outcomes': []})\n"
        "def __NAME__(*args, **kwargs):\n    print(line)\n    os.write(1, (line + '\\n').encode())\n"
        "    raise ValueError('still wrong')\n",
        "error",
        "still wrong",
    ),
}


def _body(kind: str, exercise) -> str:
    template = HOSTILE[kind][0] if kind != "solution" else "__SOLUTION__"
    body = template.replace("__SOLUTION__", exercise.solution)
    return body.replace("__NAME__", exercise.answer).replace("__ID__", exercise.id)


def _answer(exercise, body: str) -> str:
    return f"{ANSWER_MARKER}{exercise.id}\n{body}"


def _rounds():
    """Hostile kinds placed on every other exercise, solutions in between, as few runs as fit."""
    catalog = exercises()
    per_run = max(1, len(catalog) // 2)
    kinds = list(HOSTILE)
    return [kinds[k : k + per_run] for k in range(0, len(kinds), per_run)]


@pytest.mark.parametrize("kinds", _rounds(), ids=lambda kinds: ", ".join(kinds))
def test_each_hostile_answer_gets_its_status_and_the_others_are_still_graded(monkeypatch, kinds):
    monkeypatch.setattr(sandbox, "GRACE_SECONDS", 1.0)
    catalog = exercises()
    plan = {}  # exercise id -> kind
    for k, kind in enumerate(kinds):
        plan[catalog[(2 * k) % len(catalog)].id] = kind
    for k, exercise in enumerate(catalog):
        if exercise.id not in plan and k % 2 and len(plan) < len(catalog):
            plan[exercise.id] = "solution"
    answers = Answers({e: _answer(get(e), _body(kind, get(e))) for e, kind in plan.items()})
    cases = {e: list(get(e).public) for e in plan}
    results = run_submission(answers, cases, LIMITS, None)
    assert set(results) == set(plan)
    for exercise_id, kind in plan.items():
        result, exercise = results[exercise_id], get(exercise_id)
        status, message = ("passed", "") if kind == "solution" else HOSTILE[kind][1:]
        assert result.status == status, (kind, exercise_id, result.message, result.stderr)
        assert message.replace("__NAME__", exercise.answer) in result.message, (kind, result)
        if status == "passed":
            assert len(result.outcomes) == len(cases[exercise_id])
            for case, outcome in zip(cases[exercise_id], result.outcomes, strict=True):
                assert judge(exercise, case, outcome, reference_outcome(exercise, case)).passed
        if kind == "prints to stderr":
            assert result.stderr.startswith("debugging\n")


def test_the_worker_sees_no_secret_and_no_request(monkeypatch):
    monkeypatch.setenv("SCANVIZ_GRADING_SECRET", "s3cr3t-from-env")
    monkeypatch.setenv("COURSE_API_TOKEN", "t0ken-from-env")
    exercise = get("span_rule")
    body = (
        "import os\nprint(sorted(os.environ.items()))\nprint(os.listdir('..'))\n"
        "try:\n    open('../request.json')\nexcept BaseException as error:\n    print(repr(error))\n"
        + exercise.solution
    )
    results = run_submission(
        Answers({exercise.id: _answer(exercise, body)}),
        {exercise.id: list(exercise.public)},
        LIMITS,
        None,
    )
    result = results[exercise.id]
    assert "s3cr3t-from-env" not in result.stdout and "t0ken-from-env" not in result.stdout
    assert "request.json" not in result.stdout.splitlines()[1]  # read and deleted before
    assert result.status == "not allowed"  # it tried to open a file outside its folder


def test_the_answer_runs_in_a_copy_of_its_folder(tmp_path):
    folder = tmp_path / "alice"
    (folder / "sub").mkdir(parents=True)
    (folder / "data.txt").write_text("forty-two")
    (folder / "sub" / "more.txt").write_text("x")
    (folder / ".secret").write_text("hidden")
    os.symlink("/etc/passwd", folder / "link")
    exercise = get("span_rule")
    body = (
        "import os\nprint(open('data.txt').read())\n"
        "print(sorted(os.listdir('.')), os.listdir('sub'))\n"
        "open('scratch.txt', 'w').write('mine')\n" + exercise.solution
    )
    results = run_submission(
        Answers({exercise.id: _answer(exercise, body)}),
        {exercise.id: list(exercise.public)},
        LIMITS,
        folder,
    )
    assert results[exercise.id].status == "passed", results[exercise.id]
    assert results[exercise.id].stdout.splitlines() == [
        "forty-two",
        "['data.txt', 'sub'] ['more.txt']",
    ]
    assert not (folder / "scratch.txt").exists()  # it wrote into the copy


def test_exercises_without_an_answer_are_not_run():
    exercise = get("span_rule")
    assert run_submission(Answers(), {exercise.id: list(exercise.public)}, LIMITS, None) == {}


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        (
            "from scanviz.raster.scanline import span_rule",
            "line 1 imports 'scanviz.raster.scanline.span_rule'",
        ),
        ("import scanviz.raster.scanline as s", "line 1 imports 'scanviz.raster.scanline'"),
        ("from scanviz.raster import scanline", "line 1 imports 'scanviz.raster.scanline'"),
        (
            "import scanviz\nf = scanviz.raster.scanline.span_rule",
            "line 2 uses 'scanviz.raster.scanline.span_rule'",
        ),
        ("from scanviz import steps", "line 1 imports 'scanviz.steps'"),
        (
            "from scanviz.exercises.scan import SPAN_RULE_SOLUTION",
            "line 1 imports 'scanviz.exercises.scan.SPAN_RULE_SOLUTION'",
        ),
        ("import importlib\nm = importlib.import_module('scanviz.raster.scanline')", "line 2 uses"),
        ("def span_rule(crossings, rule):\n    return []", None),
        ("import math\nfrom fractions import Fraction\nfrom scanviz.trace import events", None),
    ],
)
def test_banned_use_finds_the_reference_in_the_source(source, expected):
    found = banned_use(source, ("scanviz.raster.scanline", "span_rule"))
    assert found is None if expected is None else expected in found


def test_no_catalog_solution_stub_or_variant_is_banned():
    for exercise in exercises():
        sources = [exercise.solution, exercise.stub, *(v.source for v in exercise.variants)]
        assert [banned_use(s, exercise.banned) for s in sources] == [None] * len(sources), (
            exercise.id
        )


def test_the_cpu_limit_stops_an_answer_and_a_fresh_worker_runs_the_rest():
    looping, other = exercises()[0], exercises()[1]
    answers = Answers(
        {
            looping.id: _answer(looping, _body("loop", looping)),
            other.id: _answer(other, other.solution),
        }
    )
    cases = {looping.id: list(looping.public), other.id: list(other.public)}
    results = run_submission(answers, cases, Limits(cpu_seconds=1.0, case_seconds=60.0), None)
    assert results[looping.id].status == "timeout"
    assert "CPU time of the submission" in results[looping.id].message
    assert results[other.id].status == "passed"

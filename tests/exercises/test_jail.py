"""The jail against a determined student: every route of issue 22 scores 0 and leaks nothing.

Each hostile answer runs as grading runs it (`judging.judge_answer` in a real
jailed `Session`, or `grade_submissions` on a class folder), and the tests
assert the score, the status, and that nothing got out: no secret or other
submission in any report, no file written outside, no process left running.
"""

import json
import os
import socket
import subprocess
import tempfile
import time
from pathlib import Path

import nbformat
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from nbformat import v4

from scanviz.exercises import get
from scanviz.exercises.grading import grade_submissions
from scanviz.exercises.jail import JailStopped, Limits, Session, launch
from scanviz.exercises.jail.session import RemoteAnswer
from scanviz.exercises.jail.wire import Encoder
from scanviz.exercises.judging import References, judge_answer
from scanviz.exercises.key import CourseKey, ExerciseKey, write_key
from scanviz.exercises.notebook import ANSWER_MARKER
from scanviz.exercises.report import write_reports

SPAN = get("span_rule")
LIMITS = Limits(cpu_seconds=20.0, memory_mb=512, case_seconds=5.0)
REFERENCES = References()
STUB = "def span_rule(crossings, rule):\n    return []\n"  # a do-nothing answer to fall back on
WALKER = (  # every file the answer can see: WALK, as os.walk('/') gives it, without /proc and /dev
    "import importlib, os, sys\n"
    "def _walk():\n"
    "    for d, dirs, names in os.walk('/'):\n"
    "        dirs[:] = [x for x in dirs if not (d == '/' and x in ('proc', 'dev', 'sys'))]\n"
    "        yield d, dirs, names\n"
    "WALK = list(_walk())\n"
)


def judged(source, exercise=SPAN, limits=LIMITS, hidden=0):
    """(status, message, score fraction, printed) of `source` on the exercise's cases, jailed."""
    from scanviz.exercises.core import hidden_cases

    cases = [(c, False) for c in exercise.public]
    cases += [(c, True) for c in hidden_cases(exercise, "jail-test", hidden)]
    with Session(limits) as session:
        result = judge_answer(session, exercise, source, cases, REFERENCES, limits.case_seconds)
    passed = sum(r.verdict.passed for r in result.runs)
    return result.status, result.message, passed / len(cases), result.output


def test_the_jail_starts_here():
    # make test installs bubblewrap: without a jail, grading refuses, and these tests must fail.
    assert launch.unavailable() is None


def test_rebinding_the_runners_main_does_nothing():
    # Issue 22: a setup cell rebound the worker's run_case through sys.modules['__main__'].
    source = (
        "import sys\nmain = sys.modules['__main__']\n"
        "main.run_case = lambda *a: None\nmain.Runner = None\nmain.judge = lambda *a: True\n" + STUB
    )
    status, _, score, _ = judged(source)
    assert status == "failed" and score == 0


@pytest.mark.parametrize(
    "reach",
    [
        "importlib.import_module('scanviz.raster.' + 'scanline').span_rule(crossings, rule)",
        "sys.modules['scanviz.' + 'steps']._TABLE['span_rule'].reference(crossings, rule)",
        "next(f for f in map(sys._getframe, range(1000)) if 'exercise' in f.f_locals)",
        "exec(open(next(os.path.join(d, 'scanline.py') for d, _, n in WALK if 'scanline.py' in n)).read())",
    ],
    ids=["importlib", "steps table", "stack frames", "reference source on disk"],
)
def test_the_reference_is_not_in_the_jail(reach):
    source = WALKER + f"def span_rule(crossings, rule):\n    return {reach}\n"
    status, message, score, _ = judged(source)
    assert score == 0 and status == "error", message


def test_nothing_of_scanviz_but_the_events_is_visible_anywhere():
    source = (
        WALKER + "found = [os.path.join(d, n) for d, _, names in WALK for n in names\n"
        "         if n.endswith('.py') and 'scanviz' in d]\n"
        "print(sorted(found))\n" + STUB
    )
    *_, printed = judged(source)
    visible = json.loads(printed.strip().replace("'", '"'))
    events = Path(launch.__file__).parents[2] / "trace" / "events"  # issue 24: one module a stage
    assert sorted("scanviz" + p.split("scanviz", 1)[1] for p in visible) == sorted([
        "scanviz/__init__.py", "scanviz/trace/__init__.py", "scanviz/trace/display.py",
        "scanviz/trace/schema.py", *(f"scanviz/trace/events/{m.name}" for m in events.glob("*.py")),
    ])  # fmt: skip


def test_the_key_and_other_submissions_are_out_of_reach(tmp_path):
    # Issue 22: libc open/read through ctypes read the key; raised in a public case, the
    # secret reached the feedback. Here the key, a classmate's notebook and the environment's
    # secrets are all targets, and every report is searched for them afterwards.
    secret = "f00d" * 16
    key = CourseKey(secret, "never", False, 20.0, 512, 5.0, {"span_rule": ExerciseKey(4, 2)})
    key_path = tmp_path / "course-key.toml"
    write_key(key, key_path)
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    _notebook(submissions / "classmate.ipynb", SPAN.solution + "# CLASSMATE-MARKER\n")
    thief = WALKER + (
        "import ctypes\n"
        "libc = ctypes.CDLL(None)\n"
        "loot = []\n"
        f"for path in [{str(key_path)!r}, {str(submissions / 'classmate.ipynb')!r}]:\n"
        "    fd = libc.open(path.encode(), 0)\n"
        "    buffer = ctypes.create_string_buffer(4096)\n"
        "    loot.append((fd, libc.read(fd, buffer, 4096) if fd >= 0 else -1, buffer.value[:200]))\n"
        "    try:\n        loot.append(open(path).read()[:200])\n"
        "    except OSError as error:\n        loot.append(str(error))\n"
        "loot.append([n for _, _, names in WALK for n in names if n.endswith(('.toml', '.ipynb'))])\n"
        "loot.append(sorted(os.environ.items()))\n"
        "def span_rule(crossings, rule):\n    raise ValueError(repr(loot))\n"
    )
    _notebook(submissions / "thief.ipynb", thief)
    os.environ["DATABASE_URL"] = "postgres://DBLEAK@host/db"
    os.environ["AWS_ACCESS_KEY_ID"] = "AKIALEAKLEAKLEAK"
    try:
        grades = grade_submissions(submissions, key_path, progress=False)
    finally:
        del os.environ["DATABASE_URL"], os.environ["AWS_ACCESS_KEY_ID"]
    out = tmp_path / "graded"
    write_reports(grades, key, out)
    by_student = {g.student: g.grades[0] for g in grades}
    assert by_student["thief"].score == 0 and by_student["thief"].status == "error"
    assert by_student["classmate"].score == 4
    written = "".join(p.read_text(errors="replace") for p in out.rglob("*") if p.is_file())
    assert "ValueError" in written  # the public error is shown in full ...
    for leak in (secret, "CLASSMATE-MARKER", "DBLEAK", "AKIALEAK"):
        assert leak not in written  # ... and it holds nothing it should not


def test_files_outside_the_jail_cannot_be_written(tmp_path):
    # Issue 22: files written outside via sqlite3, ctypes fopen and open() with the guard off.
    targets = [tmp_path / f"escape-{n}" for n in range(4)]
    source = (
        "import ctypes, sqlite3\n"
        f"targets = {[str(t) for t in targets]!r}\n"
        "def attempt(f):\n    try:\n        f()\n    except Exception:\n        pass\n"
        "attempt(lambda: open(targets[0], 'w').write('x'))\n"
        "attempt(lambda: sqlite3.connect(targets[1]).execute('create table t (x)'))\n"
        "attempt(lambda: ctypes.CDLL(None).fopen(targets[2].encode(), b'w'))\n"
        "attempt(lambda: open('/usr/escape', 'w'))\n"
        "attempt(lambda: open('/tmp/' + 'x' * 10, 'wb').write(b'x' * 2**26))\n" + STUB
    )
    status, _, score, _ = judged(source)
    assert score == 0 and status == "failed"
    assert not any(t.exists() for t in targets) and not Path("/usr/escape").exists()


def _processes(marker: str) -> list[str]:
    listing = subprocess.run(["ps", "-eo", "pid,args"], capture_output=True, text=True).stdout
    return [line for line in listing.splitlines() if marker in line]


def test_no_process_can_be_started_so_none_outlives_the_jail():
    # Issue 22: children forked through ctypes outlived the worker and held its pipe.
    marker = "sleep 317"
    source = (
        "import ctypes, os, subprocess\nlibc = ctypes.CDLL(None)\nresults = []\n"
        "for start in (lambda: libc.fork(), lambda: os.fork(), lambda: libc.vfork(),\n"
        f"              lambda: subprocess.Popen({marker.split()!r}).pid,\n"
        f"              lambda: libc.system({marker.encode()!r})):\n"
        "    try:\n        results.append(start())\n"
        "    except Exception as error:\n        results.append(type(error).__name__)\n"
        "print(results)\n" + STUB
    )
    started = time.monotonic()
    status, _, score, printed = judged(source)
    assert score == 0 and status == "failed"
    # system() reports a shell it could not start as exit status 127 (32512)
    assert printed.strip() == "[-1, 'PermissionError', -1, 'PermissionError', 32512]"
    assert time.monotonic() - started < 30 and not _processes(marker)


def test_forged_replies_on_the_channel_score_nothing():
    # Issue 22: forged "done" lines written with os.write gave `return []` 4 of 4.
    source = (
        "import json, os, sys\nreplies = json.loads(sys.argv[1])['replies']\n"
        "def span_rule(crossings, rule):\n"
        "    for n in range(1, 400):\n"
        "        line = {'n': n, 'returned': [], 'status': 'passed', 'score': 4, 'done': 'span_rule'}\n"
        "        os.write(replies, (json.dumps(line) + '\\n').encode())\n"
        "    return []\n"
    )
    status, message, score, _ = judged(source)
    assert score == 0 and status == "not allowed", message
    assert "on its channel to the grader" in message


def test_the_network_is_not_there():
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen()
        port = server.getsockname()[1]
        source = (
            "import socket\n"
            "try:\n"
            f"    socket.create_connection(('127.0.0.1', {port}), timeout=2)\n"
            "    print('connected')\nexcept OSError as error:\n    print('refused')\n" + STUB
        )
        *_, printed = judged(source)
    assert printed.strip() == "refused"


@pytest.mark.parametrize(
    ("body", "status", "words"),
    [
        ("while True:\n        pass", "timeout", "ran out of time (5 s) and was stopped"),
        ("import os\n    os.kill(os.getpid(), 9)", "crashed", "was killed by SIGKILL"),
        ("import ctypes\n    ctypes.string_at(0)", "crashed", "was killed by SIGSEGV"),
        ("import os\n    os._exit(3)", "crashed", "exited (status 3) before replying"),
        ("return bytearray(2**31)", "memory", "ran out of memory"),
        ("raise SystemExit(0)", "error", "SystemExit: 0 (in span_rule, line 3)"),
    ],
    ids=["loop", "SIGKILL", "segfault", "exit", "memory", "sys.exit"],
)
def test_an_answer_that_dies_is_reported_as_what_happened(body, status, words):
    source = f"def span_rule(crossings, rule):\n    {body}\n"
    got, message, score, _ = judged(f"{ANSWER_MARKER}span_rule\n{source}")
    assert (got, score) == (status, 0) and words in message, message


def test_the_cpu_limit_is_reported_as_such():
    source = "def span_rule(crossings, rule):\n    while True:\n        pass\n"
    limits = Limits(cpu_seconds=1.0, memory_mb=512, case_seconds=60.0)
    status, message, score, _ = judged(source, limits=limits)
    assert (status, score) == ("timeout", 0)
    assert "used up the CPU time of the submission (1 s) and was killed (SIGXCPU)" in message


def test_a_runaway_loop_is_stopped_by_the_event_cap():
    # Issue 22: a trace of 80,000 events cost the grader 225 CPU-s. A case may emit 20 times
    # the reference's events plus 1,000; the rest is refused in the jail.
    loop = get("scan_loop")
    source = (
        "from scanviz.trace.events import Span\n"
        "def scan_loop(polygon, width, height, rule, tracer):\n"
        "    for k in range(80_000):\n        tracer.emit(Span(0, 0, 0, 1, 1))\n"
    )
    status, message, score, _ = judged(source, loop)
    assert (status, score) == ("too many events", 0)
    assert "does a loop never end?" in message


def test_a_loop_answer_sends_its_events_and_they_are_checked():
    loop = get("scan_loop")
    status, _, score, _ = judged(loop.solution, loop, hidden=3)
    assert (status, score) == ("passed", 1)
    forged = (
        "def scan_loop(polygon, width, height, rule, tracer):\n    tracer.emit('not an event')\n"
    )
    status, message, score, _ = judged(forged, loop)
    assert (status, score) == ("error", 0)
    assert "'not an event', which is not an event" in message


class _Replies:
    """A session stand-in that answers every request with a given reply (no process)."""

    def __init__(self, reply):
        self.reply = reply

    def request(self, message):
        return self.reply

    def _broken(self, what):
        raise JailStopped("not allowed", what)


@settings(max_examples=200)
@given(
    st.recursive(
        st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=8),
        lambda inner: (
            st.lists(inner, max_size=3)
            | st.dictionaries(
                st.sampled_from(
                    ["returned", "raised", "changed", "events", "overflow", "$t", "$arg"]
                ),
                inner,
                max_size=3,
            )
        ),
        max_leaves=12,
    )
)
def test_random_replies_never_pass_a_case(reply):
    # Whatever comes back across the boundary is a value the answer could have returned, a
    # raised text, or a broken channel: span_rule's first public case never passes on it.
    from scanviz.exercises.core import run_case
    from scanviz.exercises.verdict import judge

    case = SPAN.public[0]
    answer = RemoteAnswer(_Replies(reply))
    try:
        yours = run_case(SPAN, answer, case)
    except JailStopped:
        return
    assert not judge(SPAN, case, yours, REFERENCES.reference(SPAN, case)).passed


def _notebook(path: Path, body: str) -> None:
    cell = v4.new_code_cell(f"{ANSWER_MARKER}span_rule\n{body}")
    nbformat.write(v4.new_notebook(cells=[cell]), path)


def test_encoder_gives_the_answer_no_object_of_the_grader():
    # What crosses is data only: a grader object in an argument arrives as its repr.
    plain = Encoder(identify=True).encode((REFERENCES, len))
    assert json.dumps(plain).count('"$r"') == 2


SYSTEM_PYTHON = "/usr/bin/python3.11"  # Debian's: the user nobody may run it (the grader's may not)


@pytest.fixture
def user_jail(monkeypatch):
    """The "user" jail, with an interpreter the user nobody can run (as on Gradescope)."""
    import sys

    if not os.path.exists(SYSTEM_PYTHON) or sys.version_info[:2] != (3, 11) or os.geteuid():
        pytest.fail("the user-jail tests need root and Debian's python3.11 (make test installs it)")
    monkeypatch.setattr(launch, "python_executable", lambda: SYSTEM_PYTHON)
    launch.unavailable.cache_clear()
    yield
    launch.unavailable.cache_clear()


def test_the_user_jail_runs_answers_as_nobody_without_processes_or_network(user_jail):
    assert launch.unavailable("user") is None
    source = (
        "import os, socket\nresults = [os.getuid()]\n"
        "for attempt in (os.fork, lambda: socket.socket(), lambda: open('/etc/shadow')):\n"
        "    try:\n        results.append(attempt())\n"
        "    except OSError as error:\n        results.append(type(error).__name__)\n"
        "print(results)\n" + SPAN.solution
    )
    with Session(LIMITS, jail="user") as session:
        cases = [(c, False) for c in SPAN.public]
        result = judge_answer(session, SPAN, source, cases, REFERENCES, LIMITS.case_seconds)
    assert result.status == "passed"
    assert (
        result.output.strip() == "[65534, 'PermissionError', 'PermissionError', 'PermissionError']"
    )


def test_the_user_jail_refuses_while_nobody_can_read_the_reference(
    user_jail, tmp_path, monkeypatch
):
    from scanviz.exercises.grading import jail_or_refuse

    # A reference open to all, wherever this checkout lives (a private clone is not).
    open_folder = Path(tempfile.mkdtemp(prefix="scanviz-open-"))
    open_folder.chmod(0o755)
    reference = open_folder / "scanline.py"
    reference.write_text("# the reference\n")
    reference.chmod(0o644)
    monkeypatch.setattr(launch, "reference_file", lambda: reference)
    assert launch.readable_by_nobody(launch.reference_file())
    with pytest.raises(ValueError, match="the 'user' jail runs answers as the user nobody"):
        jail_or_refuse("user", tmp_path)

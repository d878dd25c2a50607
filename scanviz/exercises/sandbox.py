"""Run one submission's answers in a fresh, limited subprocess and read back plain outcomes.

`run_submission` starts ``python -m scanviz.exercises.worker`` (see that
module) in a temporary copy of the submission's folder, with an environment
stripped of scanviz settings and secrets, and sends it only the answer and
setup sources and the cases' inputs as plain JSON. It reads back one
`WorkerResult` per exercise over a private channel (plain JSON, never
pickles). If the worker dies or stops answering, the exercise it was running
gets ``"crashed"`` or ``"timeout"`` and a fresh worker runs the rest.

The limits (`resource` in the worker): CPU seconds per worker process,
address space (``memory_mb``; the worker maps about 350 MB once scanviz and
numba are imported, so the minimum is 512), wall time of one exercise's cases
(``case_seconds``), 64 MiB per written file. They guard against accidents,
not attacks: run the grader in a throwaway container or account for an
adversarial class.
"""

from __future__ import annotations

import json
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import scanviz

from ..limits import current_file_limit
from .core import Case, Outcome
from .notebook import Answers
from .plain import to_plain

STARTUP_SECONDS = 120.0  # imports and warm-up: 1-3 s; numba compiling a missing cache: ~30 s
GRACE_SECONDS = 5.0  # beyond case_seconds before a silent worker is killed
OUTPUT_LIMIT = 20_000  # characters of an exercise's stdout/stderr kept
COPY_BYTES = 64 * 2**20  # of the submission's folder copied for the worker
COPY_FILES = 1000
_SECRET_NAME = re.compile(r"SECRET|TOKEN|PASSW|CREDENTIAL|API_?KEY|PRIVATE", re.IGNORECASE)


@dataclass(frozen=True)
class Limits:
    """The sandbox's limits (a `CourseKey` has the same three fields)."""

    cpu_seconds: float = 60.0
    memory_mb: int = 1024
    case_seconds: float = 10.0


@dataclass
class WorkerResult:
    """What the worker said about one exercise: a status of `results.STATUSES` and its outcomes.

    ``status == "passed"`` means only that every case ran; the grader judges
    the outcomes. ``outcomes`` has one entry per case, fewer if it stopped.
    """

    status: str
    message: str = ""
    outcomes: list[Outcome] = field(default_factory=list)
    stderr: str = ""
    stdout: str = ""


def run_submission(
    answers: Answers,
    cases: dict[str, list[Case]],
    limits: Limits,
    folder: Path | None,
) -> dict[str, WorkerResult]:
    """Run the answers of `answers` on the inputs of `cases` (per exercise id) in a sandbox.

    `folder` is the submission's folder (copied, up to 64 MiB and 1000
    files, hidden entries and links left out), a single file (copied alone)
    or None (an empty folder). Exercises without an answer are left out of
    the result. Never raises for anything the submission does.
    """
    names = {exercise_id: f"e{k}" for k, exercise_id in enumerate(cases)}
    pending = [e for e in cases if e in answers.answers]
    results: dict[str, WorkerResult] = {}
    with tempfile.TemporaryDirectory(prefix="scanviz-grade-") as temporary:
        root = Path(temporary)
        _copy_submission(folder, root / "work")
        (root / "capture").mkdir()
        while pending:
            request = {
                "setup": answers.setup,
                "limits": {
                    "cpu_seconds": float(limits.cpu_seconds),
                    "memory_mb": int(limits.memory_mb),
                    "case_seconds": float(limits.case_seconds),
                },
                "exercises": [
                    {
                        "id": e,
                        "answer": answers.answers[e],
                        "capture": names[e],
                        "cases": [to_plain(dict(c.inputs)) for c in cases[e]],
                    }
                    for e in pending
                ],
            }
            _Worker(root, request, limits).run(results)
            pending = [e for e in pending if e not in results]
        for exercise_id, result in results.items():
            result.stdout = _captured(root / "capture" / f"{names[exercise_id]}.stdout")
            result.stderr = _captured(root / "capture" / f"{names[exercise_id]}.stderr")
    return {e: results[e] for e in cases if e in results}


class _Worker:
    """One worker process: start it, follow its messages under deadlines, and end it."""

    def __init__(self, root: Path, request: dict, limits: Limits) -> None:
        self.root = root
        self.limits = limits
        (root / "request.json").write_text(json.dumps(request), encoding="utf-8")
        self.errors = tempfile.TemporaryFile(dir=root)
        self.process = subprocess.Popen(
            [sys.executable, "-P", "-m", "scanviz.exercises.worker", str(root)],
            cwd=root / "work",
            env=_environment(root / "work"),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=self.errors,
            start_new_session=True,
        )
        self.lines: queue.Queue = queue.Queue()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()
        self.first = request["exercises"][0]["id"]
        self.expected = {item["id"] for item in request["exercises"]}
        self.timed_out = False

    def _read(self) -> None:
        limit = current_file_limit()
        for line in iter(lambda: self.process.stdout.readline(limit), b""):
            self.lines.put(line)
            if not line.endswith(b"\n"):
                break  # over the limit: the rest is not read
        self.lines.put(None)

    def run(self, results: dict[str, WorkerResult]) -> None:
        """Fill `results` with every exercise this worker finishes or that kills it."""
        running, progressed, problem = None, False, ""
        deadline = time.monotonic() + STARTUP_SECONDS
        try:
            while True:
                try:
                    line = self.lines.get(timeout=max(0.0, deadline - time.monotonic()))
                except queue.Empty:
                    self.timed_out = True
                    break
                if line is None:
                    self._wait(GRACE_SECONDS)
                    break
                try:
                    message = json.loads(line)
                    if "start" in message:
                        running, progressed = str(message["start"]), True
                        deadline = time.monotonic() + self.limits.case_seconds + GRACE_SECONDS
                    elif "done" in message:
                        results[str(message["done"])] = _result(message)
                        running, deadline = None, time.monotonic() + GRACE_SECONDS
                        if self.expected <= results.keys():
                            break  # all done: no need to wait for it to exit
                    elif "restart" in message:
                        self._wait(GRACE_SECONDS)
                        break
                    elif "ready" not in message:
                        raise ValueError(f"unknown message {sorted(message)}")
                except (ValueError, TypeError, KeyError, RecursionError, AttributeError) as error:
                    problem = f"the worker sent a malformed message ({error})"
                    break
        finally:
            if self.process.poll() is None:
                self.process.kill()
            self.process.wait()
            self.reader.join(1.0)
            self.process.stdout.close()
        if not progressed:
            running = self.first  # it died before starting anything: charge the first exercise
            problem = problem or (
                f"the worker did not start within {STARTUP_SECONDS:g} s" if self.timed_out else ""
            )
        if running is not None and running not in results:
            results[running] = self._death(problem)
        self.errors.close()

    def _wait(self, seconds: float) -> None:
        try:
            self.process.wait(seconds)
        except subprocess.TimeoutExpired:
            pass

    def _death(self, problem: str) -> WorkerResult:
        code = self.process.returncode
        self.errors.seek(0)
        stderr = self.errors.read(OUTPUT_LIMIT).decode("utf-8", "replace")
        if self.timed_out and not problem:
            return WorkerResult(
                "timeout",
                f"the answer ran out of time ({self.limits.case_seconds:g} s) and was stopped",
                stderr=stderr,
            )
        if code in (-signal.SIGXCPU, -signal.SIGKILL) and not problem:
            return WorkerResult(
                "timeout",
                "the answer used up the CPU time of the submission "
                f"({self.limits.cpu_seconds:g} s)",
                stderr=stderr,
            )
        if not problem:
            died = f"signal {signal.Signals(-code).name}" if code < 0 else f"exit code {code}"
            problem = f"the process running the answer died ({died})"
        return WorkerResult("crashed", problem, stderr=stderr)


def _result(message: dict) -> WorkerResult:
    from .results import STATUSES

    status = message["status"]
    if status not in STATUSES:
        raise ValueError(f"unknown status {status!r}")
    outcomes = message["outcomes"]
    if not isinstance(outcomes, list):
        raise ValueError("'outcomes' must be a list")
    return WorkerResult(
        status, str(message.get("message", "")), [Outcome.from_plain(o) for o in outcomes]
    )


def _captured(path: Path) -> str:
    """The first `OUTPUT_LIMIT` characters of a capture file ('' if there is none)."""
    try:
        with open(path, "rb") as file:
            data = file.read(OUTPUT_LIMIT + 1)
            rest = os.fstat(file.fileno()).st_size - OUTPUT_LIMIT
    except OSError:
        return ""
    text = data[:OUTPUT_LIMIT].decode("utf-8", "replace")
    return text + (f"\n... ({rest} more bytes)" if rest > 0 else "")


def _environment(work: Path) -> dict[str, str]:
    """The worker's environment: no scanviz settings or secrets, one thread, home in the folder."""
    env = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith("SCANVIZ") and not _SECRET_NAME.search(k)
    }
    package_root = str(Path(scanviz.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [package_root, env.get("PYTHONPATH")]))
    env.update(
        HOME=str(work),
        TMPDIR=str(work),
        PYTHONDONTWRITEBYTECODE="1",
        PYTHONIOENCODING="utf-8",
        OPENBLAS_NUM_THREADS="1",
        OMP_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        NUMBA_NUM_THREADS="1",
    )
    return env


def _copy_submission(source: Path | None, work: Path) -> None:
    """Copy the submission's folder (or file) into `work`, within `COPY_BYTES` and `COPY_FILES`."""
    work.mkdir()
    if source is None:
        return
    source = Path(source)
    if source.is_file() and not source.is_symlink():
        if source.stat().st_size <= COPY_BYTES:
            shutil.copyfile(source, work / source.name)
        return
    budget, files = COPY_BYTES, 0
    for directory, subdirectories, names in os.walk(source):
        subdirectories[:] = sorted(d for d in subdirectories if not d.startswith("."))
        relative = Path(directory).relative_to(source)
        for name in sorted(names):
            path = Path(directory) / name
            if name.startswith(".") or path.is_symlink() or not path.is_file():
                continue
            size = path.stat().st_size
            if size > budget or files >= COPY_FILES:
                return
            (work / relative).mkdir(parents=True, exist_ok=True)
            try:
                shutil.copyfile(path, work / relative / name)
            except OSError:  # unreadable: the answer cannot read it either
                continue
            budget, files = budget - size, files + 1

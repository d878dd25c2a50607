"""One answer to one exercise, judged on its cases: what grading and the notebook check share.

`judge_answer` loads the answer cell into a runner (`scanviz.exercises.jail`),
runs every case here with the answer plugged in (`core.run_case`), within the
exercise's time, and judges each run against the reference's
(`verdict.judge`). It returns the status and message of the exercise and one
`CaseRun` per case. The reference's and the known-wrong variants' outcomes of
a case are computed once per process (`References`).

Statuses (keys of `results.STATUSES`): ``passed``; ``failed`` (some cases
differ); ``error`` (the answer raised on some cases, or the cell itself
raised: those cases fail, the others count); and, scoring 0, ``timeout``,
``memory``, ``too many events``, ``crashed``, ``not allowed`` (the runner
wrote something that is not a reply), ``syntax error``, ``not defined``.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass

from ..limits import wall_clock_limit
from .core import (
    Case,
    Exercise,
    Outcome,
    VariantRuns,
    event_limit,
    reference_outcome,
    run_case,
)
from .jail import JailStopped, LoadFailed, Session
from .jail.wire import encode
from .verdict import Verdict, builtin_error_name, judge

ZERO_STATUSES = (
    "syntax error",
    "not defined",
    "timeout",
    "memory",
    "too many events",
    "not allowed",
    "crashed",
    "grader error",
)


class ExerciseTimeout(BaseException):
    """The exercise's time ran out while the grader worked on what the answer returned."""


@dataclass
class CaseRun:
    """One case: its verdict and both outcomes (the check's side-by-side view reads them)."""

    verdict: Verdict
    yours: Outcome
    reference: Outcome


@dataclass
class Judged:
    """An answer judged on an exercise's cases: status, message, runs, what it printed."""

    status: str
    message: str
    runs: list[CaseRun]
    output: str = ""  # what the answer printed during its public cases


class References:
    """The reference's outcome and the variants' runs of each case, computed once per process."""

    def __init__(self) -> None:
        self._references: dict[tuple[str, str], Outcome] = {}
        self._variants: dict[tuple[str, str], VariantRuns] = {}

    @staticmethod
    def _key(exercise: Exercise, case: Case) -> tuple[str, str]:
        return exercise.id, json.dumps(encode(dict(case.inputs)), sort_keys=True)

    def reference(self, exercise: Exercise, case: Case) -> Outcome:
        key = self._key(exercise, case)
        if key not in self._references:
            self._references[key] = reference_outcome(exercise, case)
        return self._references[key]

    def variants(self, exercise: Exercise, case: Case) -> VariantRuns:
        key = self._key(exercise, case)
        if key not in self._variants:
            self._variants[key] = VariantRuns(exercise, case, self.reference(exercise, case))
        return self._variants[key]


def judge_answer(
    session: Session,
    exercise: Exercise,
    source: str,
    cases: list[tuple[Case, bool]],
    references: References,
    seconds: float,
) -> Judged:
    """Judge the answer cell `source` on `cases` ((case, hidden) pairs) within `seconds`.

    The runner is left running for the next exercise, or stopped (and
    restarted by the next request) if it ran out of time, died or ran out of
    memory.
    """
    remaining = seconds
    start = session.output_offset()
    try:
        with session.time_limit(remaining):
            answer = session.load(exercise.id, exercise.answer, source)
    except LoadFailed as failed:
        return _load_failure(failed)
    except JailStopped as stopped:
        return Judged(stopped.status, stopped.message, [])
    runs: list[CaseRun] = []
    outcomes: list[Outcome] = []
    public_end = session.output_offset()
    for case, hidden in cases:
        reference = references.reference(exercise, case)
        began = time.monotonic()
        try:
            with (
                session.time_limit(remaining),
                wall_clock_limit(remaining, ExerciseTimeout, "the exercise's time is up"),
            ):
                outcomes.append(run_case(exercise, answer, case, limit=event_limit(reference)))
        except JailStopped as stopped:  # the runner is gone; the next request starts another
            return Judged(stopped.status, stopped.message, runs, session.output(start, public_end))
        except ExerciseTimeout:
            session.close()
            message = f"the answer ran out of time ({seconds:g} s) and was stopped"
            return Judged("timeout", message, runs)
        remaining -= time.monotonic() - began
        if not hidden:
            public_end = session.output_offset()
        yours = outcomes[-1]
        verdict = judge(
            exercise,
            case,
            yours,
            reference,
            hidden=hidden,
            variants=references.variants(exercise, case),
        )
        runs.append(CaseRun(verdict, yours, reference))
    status, message = _status(runs)
    if status == "memory":
        session.close()  # a process that ran out of memory is not trusted to go on
    return Judged(status, message, runs, session.output(start, public_end))


def _load_failure(failed: LoadFailed) -> Judged:
    if failed.why == "syntax":
        return Judged("syntax error", f"the answer cell is not valid Python: {failed.message}", [])
    if failed.why == "undefined":
        return Judged("not defined", failed.message, [])
    message = f"the answer cell raised {failed.message}"
    if failed.message.startswith(("NameError", "ModuleNotFoundError", "ImportError")):
        message += (
            ". The answer cell runs alone, in a fresh process with Python's standard library, "
            "numpy and scanviz.trace.events: import what it uses in the cell itself"
        )
    if failed.message.startswith("MemoryError"):
        return Judged("memory", message, [])
    return Judged("error", message, [])


def _status(runs: list[CaseRun]) -> tuple[str, str]:
    verdicts = [r.verdict for r in runs]
    errors = [v for v in verdicts if v.error]
    if any(v.error.startswith("MemoryError") for v in errors):
        return "memory", "the answer ran out of memory (MemoryError)"
    if any(v.error.startswith("TooManyEvents") for v in errors):
        first = next(v.error for v in errors if v.error.startswith("TooManyEvents"))
        return (
            "too many events",
            f"a case emitted too many events ({first.split(': ', 1)[-1]}): does a loop never end?",
        )
    failed = [v for v in verdicts if not v.passed]
    if not failed:
        return "passed", ""
    if errors:
        return "error", _error_message(errors, len(verdicts))
    message = f"{len(failed)} of {len(verdicts)} cases differ from the reference"
    return "failed", message + cause(failed)


def _error_message(errors: list[Verdict], total: int) -> str:
    """What the answer raised, quoting a public case's error in full (hidden inputs stay hidden)."""
    public = next((v for v in errors if not v.hidden), None)
    if public is not None:
        return f"your code raised {public.error} (in {len(errors)} of {total} cases)"
    kind = builtin_error_name(errors[0].error)
    return (
        f"your code raised {kind} in {len(errors)} of {total} cases, all of them hidden "
        "(their messages are not shown)"
    )


def cause(failed: list[Verdict]) -> str:
    """The likely cause of the failed cases: a known mistake only if it explains every one."""
    named = {v.variant.name if v.variant else None for v in failed}
    if len(named) == 1 and None not in named:
        return f"; likely cause: {failed[0].variant.hint}"
    if named == {None}:
        return "; no known mistake matches: each case shows what differs"
    return "; no one known mistake explains every failed case: see each case"

"""What an exercise is, how one case runs, and how a run is compared with the reference.

An `Exercise` names the function the student writes (``answer``), how the
real algorithm runs with it (``call``), the reference, its public cases, a
generator of hidden cases, and a catalog of known-wrong variants. Two kinds:

- ``"step"``: the student writes one step of the step table
  (`scanviz.steps`); the reference loop runs with it plugged in. Each case runs
  twice: *free* (the student's step drives the algorithm; the trace shows the
  consequences) and *forced* (the reference step drives it, and the student's
  step is called on the same reference state at every call, so every wrong
  call is found, not only the first one and its cascade).
- ``"loop"``: the student writes the whole loop and emits events to the
  tracer they are given; the trace is compared event by event.

`run_case` produces an `Outcome` (plain data only, so it can cross the
sandbox boundary); `judge` compares a student's outcome with the
reference's and names the known-wrong variant it matches.
"""

from __future__ import annotations

import builtins
import copy
import dataclasses
import hashlib
import hmac
import os
import random
import re
import sysconfig
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..trace import Recorder
from .compare import (
    Difference,
    RasterDifference,
    TraceDifference,
    first_difference,
    raster_difference,
    show,
    trace_difference,
)
from .plain import Opaque, from_plain, to_plain

KINDS = ("step", "loop")


@dataclass(frozen=True)
class Case:
    """One input of an exercise: a label, a category (shown for hidden cases), plain inputs."""

    label: str
    inputs: Mapping[str, object]
    category: str = ""


@dataclass(frozen=True)
class Variant:
    """A known-wrong answer: its name, the hint shown when a student's run matches it, its source."""

    name: str
    hint: str
    source: str


@dataclass(frozen=True)
class Exercise:
    """One exercise of the catalog (see the module docstring and docs/exercises.md).

    ``call(fn, inputs, tracer)`` runs the algorithm with `fn` as the
    student's piece and returns whatever ``result`` and ``raster`` read:
    ``result(returned)`` the value compared after the trace, ``raster(returned)``
    the (H, W) bool samples of the raster diff. For a step exercise
    ``place(index, reference_trace)`` says where call `index` (0-based)
    happened ("row 5"), from the reference's trace of the case, and
    ``output(args, kwargs, returned)`` what a call produced (default: the
    return value; steps that change an argument in place return that argument).
    """

    id: str
    number: int
    title: str
    stage: str
    kind: str
    points: int
    answer: str
    idea: str
    stub: str
    solution: str
    call: Callable
    reference: Callable
    public: tuple[Case, ...]
    generate: Callable[[random.Random], Case]
    variants: tuple[Variant, ...]
    kinds: tuple[str, ...]
    step: str | None = None
    place: Callable[[int, list], str] | None = None
    output: Callable[[tuple, dict, object], object] | None = None
    result: Callable[[object], object] | None = None
    raster: Callable[[object], np.ndarray] | None = None
    rtol: float = 0.0
    stepper: str = ""
    banned: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(
                f"exercise {self.id!r}: 'kind' must be one of {KINDS}; got {self.kind!r}"
            )
        if (self.kind == "step") != (self.step is not None):
            raise ValueError(
                f"exercise {self.id!r}: a step exercise names its step, a loop one does not"
            )
        if not self.public:
            raise ValueError(f"exercise {self.id!r} needs at least one public case")
        if (
            not self.stub.lstrip().startswith(("def ", "import ", "from "))
            and self.answer not in self.stub
        ):
            raise ValueError(f"exercise {self.id!r}: the stub must define {self.answer!r}")


@dataclass
class Outcome:
    """A run of one case, as plain data: events, forced-call outputs, result, raster, error.

    ``calls`` holds the student's output at each forced call (step exercises).
    """

    trace: list = field(default_factory=list)
    calls: list = field(default_factory=list)
    result: object = None
    raster: object = None
    error: str | None = None

    def to_plain(self) -> dict:
        return {
            "trace": to_plain(self.trace),
            "calls": to_plain(self.calls),
            "result": to_plain(self.result),
            "raster": to_plain(self.raster),
            "error": self.error,
        }

    @classmethod
    def from_plain(cls, data: object) -> Outcome:
        """An outcome from plain data (as a worker sends it); malformed data raises ValueError."""
        if not isinstance(data, dict):
            raise ValueError(f"an outcome must be an object; got {type(data).__name__}")
        trace = from_plain(data.get("trace", []))
        calls = from_plain(data.get("calls", []))
        if not isinstance(trace, list) or not isinstance(calls, list):
            raise ValueError("an outcome's 'trace' and 'calls' must be lists")
        error = data.get("error")
        return cls(
            trace=trace,
            calls=calls,
            result=from_plain(data.get("result")),
            raster=from_plain(data.get("raster")),
            error=None if error is None else str(error),
        )


def _error_text(error: BaseException, answer: str) -> str:
    """``TypeError: ... (in update_aet, line 5)``: the error and the student's innermost line."""
    frames = [f for f in traceback.extract_tb(error.__traceback__) if _student_file(f.filename)]
    where = f" (in {frames[-1].name}, line {frames[-1].lineno})" if frames else ""
    message = str(error)
    return f"{type(error).__name__}{': ' + message if message else ''}{where}"


def _student_file(filename: str) -> bool:
    """Whether a traceback frame is the student's code (not scanviz, not Python's own files)."""
    if filename.startswith("<answer"):
        return True
    path = os.path.abspath(filename)
    return not (path.startswith(_PACKAGE) or path.startswith(_PYTHON) or filename.startswith("<"))


_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_PYTHON = os.path.abspath(sysconfig.get_paths()["stdlib"])


def _normalized(outcome: Outcome) -> Outcome:
    """The outcome as it reads back from plain data (tuples become lists, records Records)."""
    return Outcome.from_plain(outcome.to_plain())


def run_case(exercise: Exercise, fn: Callable, case: Case) -> Outcome:
    """Run `case` with `fn` as the student's piece: free, then (step exercises) forced."""
    outcome = Outcome()
    recorder = Recorder(exercise.kinds)
    try:
        returned = exercise.call(fn, dict(case.inputs), recorder)
    except Exception as error:
        outcome.error = _error_text(error, exercise.answer)
        returned = None
    outcome.trace = list(recorder.trace())
    if outcome.error is None:
        outcome.result = exercise.result(returned) if exercise.result else None
        outcome.raster = exercise.raster(returned) if exercise.raster else None
    if exercise.kind == "step":
        outcome.calls = _forced_calls(exercise, fn, case)
    return _normalized(outcome)


def _forced_calls(exercise: Exercise, fn: Callable, case: Case) -> list:
    """The student's output at every call of the step, each on the reference's own state."""
    reference = exercise.reference
    output = exercise.output or (lambda args, kwargs, returned: returned)
    calls = []

    def forced(*args, **kwargs):
        copied_args, copied_kwargs = copy.deepcopy((args, kwargs))
        expected = reference(*args, **kwargs)
        try:
            mine = output(copied_args, copied_kwargs, fn(*copied_args, **copied_kwargs))
        except Exception as error:
            mine = Opaque(f"raised {_error_text(error, exercise.answer)}")
        calls.append(mine)
        return expected

    exercise.call(forced, dict(case.inputs), None)
    return calls


def reference_outcome(exercise: Exercise, case: Case) -> Outcome:
    """The reference's outcome of `case` (computed by the grader, never by the student's process)."""
    return run_case(exercise, exercise.reference, case)


@dataclass(frozen=True)
class Verdict:
    """How one case went: passed or not, and every diagnostic the comparison found."""

    case: Case
    hidden: bool
    passed: bool
    error: str | None = None
    trace: TraceDifference | None = None
    wrong_calls: tuple[str, ...] = ()  # places of the forced calls that differ
    calls_total: int = 0
    first_call: Difference | None = None
    result: Difference | None = None
    raster: RasterDifference | None = None
    variant: Variant | None = None

    @property
    def signature(self) -> str:
        """What the class summary groups by: the first diverging event kind and field."""
        if self.passed:
            return ""
        if self.error is not None and self.trace is None:
            return f"error: {error_name(self.error)}"
        if self.trace is not None:
            path = re.sub(r" \(e\d+\)|\d", "", self.trace.difference.path)
            return f"{self.trace.kind}: {path}" if path else self.trace.kind
        if self.first_call is not None:
            return "step output"
        return "result"

    def summary(self, reveal: bool = True) -> str:
        """One line: the case, and where it first differs or what it raised."""
        first = self.describe(reveal).splitlines()
        detail = next((line.strip() for line in first[1:] if line.strip()), "")
        return first[0] + (f" -- {detail}" if detail else "")

    def describe(self, reveal: bool = True) -> str:
        """The diagnostics as plain text.

        A failed hidden case is redacted unless `reveal`: its category, where it
        first differs, the counts and the likely cause, but no value, raster or
        error message (a student's exception could carry the inputs).
        """
        if self.hidden and not reveal and not self.passed:
            return _redacted(self)
        name = (
            self.case.label
            if (reveal or not self.hidden)
            else (self.case.category or "hidden case")
        )
        mark = "passed" if self.passed else "FAILED"
        lines = [f"{'hidden' if self.hidden else 'public'} case {name!r}: {mark}"]
        if self.passed:
            return lines[0]
        if self.error:
            lines.append(f"  your code raised {self.error}")
        if self.trace is not None:
            lines.extend("  " + line for line in self.trace.describe().splitlines())
        if self.calls_total:
            if self.wrong_calls:
                places = ", ".join(self.wrong_calls[:12]) + (
                    " ..." if len(self.wrong_calls) > 12 else ""
                )
                lines.append(
                    f"  with the reference state fed in at every call, yours differs at "
                    f"{len(self.wrong_calls)} of {self.calls_total}: {places}"
                )
                if self.first_call is not None:
                    lines.append(f"    first: {self.first_call.describe()}")
            else:
                lines.append(
                    f"  with the reference state fed in, all {self.calls_total} calls agree: "
                    "the difference comes from an earlier wrong state"
                )
        if self.result is not None:
            lines.append(f"  result: {self.result.describe()}")
        if self.raster is not None:
            lines.extend("  " + line for line in self.raster.describe().splitlines())
        if self.variant is not None:
            lines.append(f"  likely cause: {self.variant.hint}")
        return "\n".join(lines)


def error_name(error: str) -> str:
    """The exception's name in an error text of `run_case` (``TypeError: ... (in f, line 5)``).

    >>> error_name("NotImplementedError (in span_rule, line 4)"), error_name("KeyError: 'x'")
    ('NotImplementedError', 'KeyError')
    """
    return re.match(r"\w*", error).group()


def builtin_error_name(error: str) -> str:
    """The exception's name if it is one of Python's own (a student's class name could be
    made from the inputs), else "an exception".

    >>> builtin_error_name("ValueError: [(9/4, 1)] (in span_rule, line 2)"), builtin_error_name("X_9_4: boom")
    ('ValueError', 'an exception')
    """
    name = error_name(error)
    known = getattr(builtins, name, None)
    return name if isinstance(known, type) and issubclass(known, BaseException) else "an exception"


def _redacted(verdict: Verdict) -> str:
    """A failed hidden case without its inputs: category, where it differs, counts, cause."""
    lines = [f"hidden case {verdict.case.category or 'hidden case'!r}: FAILED"]
    if verdict.error is not None:
        kind = builtin_error_name(verdict.error)
        lines.append(f"  your code raised {kind} (messages are not shown for hidden cases)")
    if verdict.trace is not None:
        place = f", {verdict.trace.place}" if verdict.trace.place else ""
        lines.append(
            f"  first difference at event {verdict.trace.index + 1} of {verdict.trace.length}"
            f" -- {verdict.trace.kind}{place}"
        )
    if verdict.wrong_calls:
        lines.append(
            f"  with the reference state fed in at every call, yours differs at "
            f"{len(verdict.wrong_calls)} of {verdict.calls_total}"
        )
    if verdict.result is not None:
        lines.append("  the result differs from the reference's")
    if verdict.raster is not None:
        r = verdict.raster
        lines.append(f"  samples: {r.matched} matched, {r.extra} extra, {r.missing} missing")
    if verdict.variant is not None:
        lines.append(f"  likely cause: {verdict.variant.hint}")
    return "\n".join(lines)


def judge(
    exercise: Exercise,
    case: Case,
    yours: Outcome,
    reference: Outcome,
    *,
    hidden: bool = False,
    variants: Mapping[str, Outcome] | None = None,
) -> Verdict:
    """Compare the student's outcome of `case` with the reference's.

    `variants` maps variant names to their outcomes of the same case
    (`variant_outcomes`); the first one the student's run matches is named.
    """
    rtol = exercise.rtol
    trace = trace_difference(yours.trace, reference.trace, rtol)
    wrong, first_call = [], None
    for index, expected in enumerate(reference.calls):
        mine = yours.calls[index] if index < len(yours.calls) else Opaque("no call")
        difference = first_difference(mine, expected, rtol)
        if difference is not None:
            wrong.append(
                exercise.place(index, reference.trace) if exercise.place else f"call {index + 1}"
            )
            first_call = first_call or difference
    result = first_difference(yours.result, reference.result, rtol)
    raster = (
        raster_difference(yours.raster, reference.raster) if reference.raster is not None else None
    )
    passed = (
        yours.error is None and trace is None and not wrong and result is None and raster is None
    )
    verdict = Verdict(
        case,
        hidden,
        passed,
        yours.error,
        trace,
        tuple(wrong),
        len(reference.calls),
        first_call,
        result,
        raster,
    )
    if passed or not variants:
        return verdict
    return _with_variant(exercise, verdict, yours, reference, variants)


def _same_run(a: Outcome, b: Outcome, rtol: float) -> bool:
    return (
        _error_kind(a) == _error_kind(b)
        and trace_difference(a.trace, b.trace, rtol) is None
        and first_difference(a.calls, b.calls, rtol) is None
        and first_difference(a.result, b.result, rtol) is None
        and first_difference(a.raster, b.raster) is None
    )


def _with_variant(
    exercise, verdict: Verdict, yours: Outcome, reference: Outcome, variants
) -> Verdict:
    """Name the known-wrong variant whose run is the student's, else the one that goes wrong first
    in the same place with the same value."""
    by_name = {v.name: v for v in exercise.variants}
    for name, outcome in variants.items():
        if _same_run(yours, outcome, exercise.rtol):
            return dataclasses.replace(verdict, variant=by_name[name])
    mine = _first_wrong(verdict.trace, verdict.first_call)
    if mine is None:
        return verdict
    for name, outcome in variants.items():
        theirs = _first_wrong(*_differences(outcome, reference, exercise.rtol))
        if theirs == mine:
            return dataclasses.replace(verdict, variant=by_name[name])
    return verdict


def _error_kind(outcome: Outcome) -> str | None:
    """The exception type a run raised (None if it did not): two runs that both raised at once
    are the same run only if they raised the same kind of error."""
    return None if outcome.error is None else error_name(outcome.error)


def _differences(outcome: Outcome, reference: Outcome, rtol: float):
    trace = trace_difference(outcome.trace, reference.trace, rtol)
    calls = [
        first_difference(a, b, rtol) for a, b in zip(outcome.calls, reference.calls, strict=False)
    ]
    return trace, next((c for c in calls if c is not None), None)


def _first_wrong(trace: TraceDifference | None, call: Difference | None) -> tuple | None:
    """A comparable key of the first wrong thing: (event index, path, value shown)."""
    if trace is not None:
        return ("event", trace.index, trace.difference.path, show(trace.difference.yours))
    if call is not None:
        return ("call", call.path, show(call.yours))
    return None


def edited_variant(solution: str, name: str, hint: str, *edits: tuple[str, str]) -> Variant:
    """The variant of `solution` with each (old, new) text edit applied; every old text must occur."""
    source = solution
    for old, new in edits:
        if old not in source:
            raise ValueError(f"variant {name!r}: {old!r} does not occur in the solution")
        source = source.replace(old, new)
    return Variant(name, hint, source)


def compile_answer(source: str, name: str, filename: str = "<answer>") -> Callable:
    """The function `name` defined by `source` (trusted code only: variants and solutions)."""
    namespace: dict = {"__name__": "scanviz_answer"}
    exec(compile(source, filename, "exec"), namespace)  # noqa: S102 - the catalog's own sources
    if not callable(namespace.get(name)):
        raise ValueError(f"the source does not define a function {name!r}")
    return namespace[name]


def variant_outcomes(exercise: Exercise, case: Case) -> dict[str, Outcome]:
    """Every known-wrong variant's outcome of `case` (run in the grader: the catalog's own code)."""
    return {
        v.name: run_case(
            exercise, compile_answer(v.source, exercise.answer, f"<answer {v.name}>"), case
        )
        for v in exercise.variants
    }


def hidden_cases(exercise: Exercise, secret: str, count: int, student: str = "") -> list[Case]:
    """`count` hidden cases of `exercise`, each from an HMAC of the course secret.

    Nothing about them is stored anywhere: the same secret always gives the
    same cases, and without it they cannot be derived.
    """
    cases = []
    for k in range(count):
        message = f"{exercise.id}:{k}:{student}".encode()
        digest = hmac.new(secret.encode(), message, hashlib.sha256).digest()
        case = _drawn(exercise, random.Random(int.from_bytes(digest[:8], "big")))
        cases.append(Case(case.label or f"hidden {k + 1}", case.inputs, case.category))
    return cases


def practice_cases(exercise: Exercise, count: int, seed: int | None = None) -> list[Case]:
    """`count` random cases from the hidden cases' distribution, from a local seed."""
    rng = random.Random(seed)
    return [_drawn(exercise, rng) for _ in range(count)]


DRAWS = 50  # generated cases tried before one that calls the step is found


def _drawn(exercise: Exercise, rng: random.Random) -> Case:
    """A generated case; for a step exercise, one in which the reference calls the step
    (else an answer that is never called, a stub included, would pass it)."""
    for _ in range(DRAWS):
        case = exercise.generate(rng)
        if exercise.kind != "step" or reference_outcome(exercise, case).calls:
            return case
    return case


def score(exercise: Exercise, verdicts: list[Verdict]) -> float:
    """The exercise's points times the fraction of cases passed."""
    if not verdicts:
        return 0.0
    return exercise.points * sum(v.passed for v in verdicts) / len(verdicts)

"""What an exercise is and how one case runs: the grader's side of every exercise.

An `Exercise` names the function the student writes (``answer``), how the
real algorithm runs with it (``call``), the reference, its public cases, a
generator of hidden cases with the features every hidden set must contain,
and a catalog of known-wrong variants. Two kinds:

- ``"step"``: the student writes one step of the step table
  (`scanviz.steps`); the reference loop runs with it plugged in. Each case runs
  twice: *free* (the student's step drives the algorithm; the trace shows the
  consequences) and *forced* (the reference step drives it, and the student's
  step is called on the same reference state at every call, so every wrong
  call is found, not only the first one and its cascade).
- ``"loop"``: the student writes the whole loop and emits events to the
  tracer they are given; the trace is compared event by event.

`run_case` runs the algorithm here, in the grader; the student's function
`answer` is either a local function (the catalog's own sources, tests) or a
`scanviz.exercises.jail.RemoteAnswer`, whose every call crosses into the
jail as plain data. `scanviz.exercises.verdict.judge` compares outcomes.
"""

from __future__ import annotations

import ast
import copy
import hashlib
import hmac
import random
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..trace import Recorder
from .jail.session import AnswerRaised, RemoteAnswer, TraceOverflow
from .jail.wire import Opaque, decode, encode

KINDS = ("step", "loop")
EVENT_LIMIT = 100_000  # events one case may emit when no reference length is known
DRAWS = 200  # generated cases tried for one hidden case before the generator is called broken


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

    ``generate(rng, feature)`` draws a case from a `random.Random`; with a
    `feature` (one of ``features``), a case that has it, which
    ``exercised(case, reference_outcome)`` confirms: the hidden cases of every
    student hold one case per feature, so a mistake a feature exposes fails
    for every student alike.
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
    generate: Callable[[random.Random, str | None], Case]
    variants: tuple[Variant, ...]
    kinds: tuple[str, ...]
    features: tuple[str, ...] = ()
    exercised: Callable[[Case, object], set[str]] | None = None
    step: str | None = None
    place: Callable[[int, list], str] | None = None
    output: Callable[[tuple, dict, object], object] | None = None
    result: Callable[[object], object] | None = None
    raster: Callable[[object], np.ndarray] | None = None
    rtol: float = 0.0
    stepper: str = ""

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
        if self.features and self.exercised is None:
            raise ValueError(f"exercise {self.id!r}: features need 'exercised' to confirm them")
        if self.answer not in _defined(self.stub):
            raise ValueError(f"exercise {self.id!r}: the stub must define {self.answer!r}")


def feature_tests(tests: Mapping[str, Callable[[Case, Outcome], bool]]) -> dict:
    """An exercise's ``features`` and ``exercised`` from a test per feature.

    Each test says whether a case has the feature, from the case's inputs and
    the reference's outcome of it (events, forced calls and their arguments).
    Use as ``Exercise(..., **feature_tests({...}))``.
    """

    def exercised(case: Case, reference: Outcome) -> set[str]:
        return {name for name, test in tests.items() if test(case, reference)}

    return {"features": tuple(tests), "exercised": exercised}


def _defined(source: str) -> dict[str, ast.FunctionDef]:
    return {n.name: n for n in ast.parse(source).body if isinstance(n, ast.FunctionDef)}


@dataclass
class Outcome:
    """A run of one case: events, forced-call outputs, result, raster, error.

    ``calls`` holds the student's output at each forced call (step exercises);
    ``arguments`` (the reference's outcome only) the arguments of each call.
    The outputs are as their plain form reads back (`normalized`), so a local
    answer's outcome and a jailed one's compare alike; the events, result and
    raster come from the grader's own algorithm either way.
    """

    trace: list = field(default_factory=list)
    calls: list = field(default_factory=list)
    result: object = None
    raster: object = None
    error: str | None = None
    arguments: list = field(default_factory=list, compare=False, repr=False)


def normalized(value: object) -> object:
    """`value` as its plain form reads back (tuples stay tuples; records of other classes Fields)."""
    return decode(encode(value))


class CappedRecorder(Recorder):
    """A recorder that stops a case once it has emitted `limit` events (kept or not)."""

    def __init__(self, kinds, limit: int) -> None:
        super().__init__(kinds)
        self.limit = limit
        self.emitted = 0

    def emit(self, event) -> None:
        self.emitted += 1
        if self.emitted > self.limit:
            raise TraceOverflow(f"more than {self.limit} events in one case")
        super().emit(event)


def event_limit(reference: Outcome | None) -> int:
    """Events a case may emit: 20 times the reference's, plus 1,000."""
    return EVENT_LIMIT if reference is None else 20 * len(reference.trace) + 1000


def run_case(
    exercise: Exercise, answer: Callable, case: Case, *, limit: int = EVENT_LIMIT
) -> Outcome:
    """Run `case` with `answer` as the student's piece: free, then (step exercises) forced.

    What the answer raised is kept as the outcome's error; so is an error
    the algorithm raised on what the answer returned. A case that emits more
    than `limit` events stops with the error ``TooManyEvents``. A jailed
    answer that ran out of time or died raises `JailStopped` out of here.
    """
    outcome = Outcome()
    recorder = CappedRecorder(exercise.kinds, limit)
    try:
        returned = exercise.call(answer, dict(case.inputs), recorder)
        # what a loop returned is the student's: reading it may fail too
        outcome.result = exercise.result(returned) if exercise.result else None
        outcome.raster = exercise.raster(returned) if exercise.raster else None
    except AnswerRaised as raised:
        outcome.error = raised.text
    except TraceOverflow as overflow:
        outcome.error = f"TooManyEvents: {overflow}"
    except Exception as error:  # a local answer's error, or the algorithm's on what it returned
        outcome.error = error_text(error)
    if outcome.error is not None:
        outcome.result = outcome.raster = None
    outcome.trace = list(recorder.trace())
    if exercise.kind == "step":
        outcome.calls, outcome.arguments = _forced_calls(exercise, answer, case)
    outcome.calls = normalized(outcome.calls)  # a jailed answer's and a local one's alike
    return outcome


def error_text(error: BaseException) -> str:
    """``TypeError: message (in update_aet, line 5)``: the error and the answer's innermost line.

    The answer's lines are those of a file named ``<answer ...>`` (local
    answers are compiled so); an error the algorithm raised has none.
    """
    frames = [
        f for f in traceback.extract_tb(error.__traceback__) if f.filename.startswith("<answer")
    ]
    where = f" (in {frames[-1].name}, line {frames[-1].lineno})" if frames else ""
    message = str(error)
    return f"{type(error).__name__}{': ' + message if message else ''}{where}"


def _forced_calls(exercise: Exercise, answer: Callable, case: Case) -> tuple[list, list]:
    """The answer's output at every call of the step, each on the reference's own state, and
    (for the reference itself) the calls' arguments.

    The reference runs alone first and every call's arguments are copied;
    then the answer is called on each copy (a jailed answer in one batch).
    """
    reference = exercise.reference
    arguments: list[tuple[tuple, dict]] = []

    def forced(*args, **kwargs):
        arguments.append(copy.deepcopy((args, kwargs)))
        return reference(*args, **kwargs)

    exercise.call(forced, dict(case.inputs), None)
    keep = answer is reference  # the reference's arguments are kept (`replayed_outputs`)
    outputs = _outputs(exercise, answer, copy.deepcopy(arguments) if keep else arguments)
    return outputs, arguments if keep else []


def _outputs(exercise: Exercise, answer: Callable, arguments: list) -> list:
    """What `answer` produced at each call (`Exercise.output`); the arguments take its changes."""
    output = exercise.output or (lambda args, kwargs, returned: returned)
    outputs = []
    for (args, kwargs), (ok, returned) in zip(arguments, call_each(answer, arguments), strict=True):
        if not ok:
            outputs.append(Opaque(f"raised {returned}"))
            continue
        try:
            outputs.append(output(args, kwargs, returned))
        except Exception as error:  # what it returned does not fit the step's output
            outputs.append(Opaque(f"returned something unusable: {error_text(error)}"))
    return outputs


def call_each(answer: Callable, calls: list[tuple[tuple, dict]]) -> list[tuple[bool, object]]:
    """(True, returned) or (False, what it raised) for each call (a jailed answer: one batch).

    The calls' arguments are changed in place where the answer changes them.
    """
    if isinstance(answer, RemoteAnswer):
        return answer.call_each(calls)
    results = []
    for args, kwargs in calls:
        try:
            results.append((True, answer(*args, **kwargs)))
        except Exception as error:
            results.append((False, error_text(error)))
    return results


def reference_outcome(exercise: Exercise, case: Case) -> Outcome:
    """The reference's outcome of `case` (computed by the grader, never in the jail)."""
    return run_case(exercise, exercise.reference, case)


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


class VariantRuns:
    """The known-wrong variants' runs of one case, each computed only when asked, then kept.

    `forced` is a variant's output at every forced call, replayed on the
    reference's arguments (cheap: the algorithm does not run), `run` its
    whole outcome; `scanviz.exercises.verdict.judge` runs a variant only if
    its forced outputs are the student's.
    """

    def __init__(self, exercise: Exercise, case: Case, reference: Outcome) -> None:
        self.exercise, self.case, self.reference = exercise, case, reference
        self._functions = {
            v.name: compile_answer(v.source, exercise.answer, f"<answer {v.name}>")
            for v in exercise.variants
        }
        self._forced: dict[str, list] = {}
        self._runs: dict[str, Outcome] = {}

    def forced(self, name: str) -> list:
        if name not in self._forced:
            function = self._functions[name]
            self._forced[name] = replayed_outputs(self.exercise, function, self.reference)
        return self._forced[name]

    def run(self, name: str) -> Outcome:
        if name not in self._runs:
            self._runs[name] = run_case(self.exercise, self._functions[name], self.case)
        return self._runs[name]


# --- answers that do nothing ------------------------------------------------------------------


def do_nothing_sources(exercise: Exercise) -> dict[str, str]:
    """Answers that do nothing, by name: the stub, empty, constants, the identity.

    Each is the stub's ``def`` line with another body. Every case, public and
    hidden, must fail each of them (tests/exercises), so they score 0.
    """
    definition = _defined(exercise.stub)[exercise.answer]
    parameters = [a.arg for a in definition.args.args]
    head = f"def {exercise.answer}({', '.join(parameters)}):\n    "
    bodies = {
        "empty": "pass",
        "None": "return None",
        "True": "return True",
        "False": "return False",
        "zero": "return 0",
        "one": "return 1",
        "empty list": "return []",
        "empty tuple": "return ()",
    }
    if parameters:
        bodies["identity"] = f"return {parameters[0]}"
        bodies["arguments"] = f"return ({', '.join(parameters)},)"
    sources = {name: head + body + "\n" for name, body in bodies.items()}
    return {"stub": exercise.stub, **sources}


_DO_NOTHING: dict[str, dict[str, Callable]] = {}


def _do_nothing(exercise: Exercise) -> dict[str, Callable]:
    if exercise.id not in _DO_NOTHING:
        _DO_NOTHING[exercise.id] = {
            name: compile_answer(source, exercise.answer, f"<answer {name}>")
            for name, source in do_nothing_sources(exercise).items()
        }
    return _DO_NOTHING[exercise.id]


def replayed_outputs(exercise: Exercise, function: Callable, reference: Outcome) -> list:
    """`function`'s output at every forced call of the reference's run (a step exercise), each
    on a copy of the reference's arguments, as `run_case` records them."""
    return normalized(_outputs(exercise, function, copy.deepcopy(reference.arguments)))


def catches_doing_nothing(exercise: Exercise, case: Case, reference: Outcome) -> bool:
    """Whether every do-nothing answer fails `case`.

    A loop exercise's do-nothing answers emit nothing, so a case with any
    reference event fails them. A step exercise fails an answer at any
    forced call whose output differs from the reference's; the calls are
    replayed on the reference's own arguments, without running the
    algorithm again.
    """
    if exercise.kind == "loop":
        return bool(reference.trace)
    from .compare import first_difference

    return all(
        first_difference(
            replayed_outputs(exercise, function, reference), reference.calls, exercise.rtol
        )
        is not None
        for function in _do_nothing(exercise).values()
    )


# --- hidden and practice cases ------------------------------------------------------------------


def hidden_cases(exercise: Exercise, secret: str, count: int, student: str = "") -> list[Case]:
    """The hidden cases of `exercise`: one per feature, then random ones, `count` in all.

    Each comes from an HMAC of the course secret, so the same secret always
    gives the same cases, and without it they cannot be derived. When
    `count` is positive but smaller than the number of features, every
    feature still gets its case.
    """
    total = max(count, len(exercise.features)) if count > 0 else 0
    cases = []
    for k in range(total):
        message = f"{exercise.id}:{k}:{student}".encode()
        digest = hmac.new(secret.encode(), message, hashlib.sha256).digest()
        feature = exercise.features[k] if k < len(exercise.features) else None
        case = drawn_case(exercise, random.Random(int.from_bytes(digest[:8], "big")), feature)
        cases.append(Case(case.label or f"hidden {k + 1}", case.inputs, case.category))
    return cases


def practice_cases(exercise: Exercise, count: int, seed: int | None = None) -> list[Case]:
    """`count` random cases drawn like the hidden ones, from a local seed."""
    rng = random.Random(seed)
    features = exercise.features
    return [
        drawn_case(exercise, rng, features[k % len(features)] if features else None)
        for k in range(count)
    ]


def drawn_case(exercise: Exercise, rng: random.Random, feature: str | None = None) -> Case:
    """A generated case that counts: the reference calls the step, it has `feature`, and it
    fails every do-nothing answer. A generator that cannot make one is a catalog bug."""
    for _ in range(DRAWS):
        case = exercise.generate(rng, feature)
        reference = reference_outcome(exercise, case)
        if exercise.kind == "step" and not reference.calls:
            continue
        if feature is not None and feature not in exercise.exercised(case, reference):
            continue
        if catches_doing_nothing(exercise, case, reference):
            return case
    raise RuntimeError(
        f"exercise {exercise.id!r}: {DRAWS} generated cases in a row lack "
        f"{feature or 'a call of the step'!r} or let a do-nothing answer pass"
    )


def score(exercise: Exercise, verdicts: list) -> float:
    """The exercise's points times the fraction of cases passed."""
    if not verdicts:
        return 0.0
    return exercise.points * sum(v.passed for v in verdicts) / len(verdicts)

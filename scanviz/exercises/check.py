"""The check cell of a student notebook: public cases, diagnostics inline, a side-by-side trace.

``check("span_rule")`` finds the student's function in the notebook's
namespace, runs it on the public cases (and on `practice` random cases from
a local seed, drawn like the hidden ones), and compares every run with the
reference's. It runs in the student's own kernel: this is their machine and
their code; grading (`scanviz.exercises.grading`) is the sandboxed one.
"""

from __future__ import annotations

import html
import inspect
from collections.abc import Callable
from dataclasses import dataclass

from ..limits import wall_clock_limit
from .catalog import get
from .core import (
    Case,
    Exercise,
    Outcome,
    Verdict,
    judge,
    practice_cases,
    reference_outcome,
    run_case,
    variant_outcomes,
)

CASE_SECONDS = 20.0  # wall time of one case in the notebook before it is stopped


class CaseTimeout(BaseException):
    """A case ran longer than `CASE_SECONDS` (a BaseException: the runs' ``except Exception`` lets it by)."""


@dataclass
class CaseCheck:
    """One checked case: the verdict and both outcomes (for the side-by-side view)."""

    verdict: Verdict
    yours: Outcome
    reference: Outcome


@dataclass
class CheckReport:
    """What `check` found: shown as HTML with a trace comparison in a notebook, as text elsewhere."""

    exercise: Exercise
    cases: list[CaseCheck]
    practice: int = 0
    problem: str = ""

    @property
    def passed(self) -> int:
        return sum(c.verdict.passed for c in self.cases)

    def headline(self) -> str:
        if self.problem:
            return f"{self.exercise.id} -- {self.problem}"
        public = [c for c in self.cases if not c.verdict.case.category.startswith("practice")]
        passed = sum(c.verdict.passed for c in public)
        line = f"{self.exercise.id} -- public cases {passed} of {len(public)}"
        if self.practice:
            practiced = [c for c in self.cases if c not in public]
            line += (
                f", practice cases {sum(c.verdict.passed for c in practiced)} of {self.practice}"
            )
        return line + " -- hidden cases are graded later"

    def __str__(self) -> str:
        """The headline, the first failing case in full, the others in a line each."""
        lines = [self.headline()]
        failing = [c.verdict for c in self.cases if not c.verdict.passed]
        lines.extend(v.describe() if i == 0 else v.summary() for i, v in enumerate(failing))
        rerun = next((c for c in self.cases if not c.verdict.passed), None)
        if rerun is not None:
            lines.append(
                f'rerun just this case: check("{self.exercise.id}", case={rerun.verdict.case.label!r})'
            )
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return f"<pre style='white-space:pre-wrap'>{html.escape(str(self))}</pre>"

    def _ipython_display_(self) -> None:
        from IPython.display import HTML, display

        display(HTML(self._repr_html_()))
        failing = next((c for c in self.cases if not c.verdict.passed), None)
        if failing is not None:
            from ..widgets.exercise import TraceComparison

            display(
                TraceComparison(
                    failing.yours, failing.reference, failing.verdict, self.exercise.rtol
                )
            )


def _answer_in(namespace: dict, exercise: Exercise) -> Callable | None:
    function = namespace.get(exercise.answer)
    return function if callable(function) else None


def _cases(exercise: Exercise, case: str | None, practice: int, seed: int | None) -> list[Case]:
    cases = list(exercise.public)
    if case is not None:
        cases = [c for c in cases if c.label == case]
        if not cases:
            labels = [c.label for c in exercise.public]
            raise ValueError(f"'case' must be one of the public cases {labels}; got {case!r}")
    practiced = [
        Case(f"practice {k + 1}: {c.label}", c.inputs, f"practice: {c.category}")
        for k, c in enumerate(practice_cases(exercise, practice, seed))
    ]
    return cases + practiced


def check_function(
    exercise: Exercise,
    function: Callable,
    *,
    case: str | None = None,
    practice: int = 0,
    seed: int | None = None,
) -> CheckReport:
    """Run `function` as `exercise`'s answer on its public (and practice) cases."""
    checked = []
    for item in _cases(exercise, case, practice, seed):
        reference = reference_outcome(exercise, item)
        try:
            with wall_clock_limit(
                CASE_SECONDS,
                CaseTimeout,
                f"stopped after {CASE_SECONDS:g} s: does a loop never end?",
            ):
                yours = run_case(exercise, function, item)
        except CaseTimeout as error:
            yours = Outcome(error=f"CaseTimeout: {error}")
        verdict = judge(exercise, item, yours, reference, variants=variant_outcomes(exercise, item))
        checked.append(CaseCheck(verdict, yours, reference))
    return CheckReport(exercise, checked, practice)


def check(
    exercise_id: str,
    *,
    case: str | None = None,
    practice: int = 0,
    seed: int | None = None,
    namespace: dict | None = None,
) -> CheckReport:
    """Check the answer to `exercise_id` defined in the notebook (the caller's globals).

    Parameters
    ----------
    exercise_id : str
        The id in the answer cell's marker, e.g. ``"span_rule"``.
    case : str, optional
        Run only the public case with this label.
    practice : int
        Also run this many random cases drawn like the hidden ones (local seed).
    seed : int, optional
        The seed of the practice cases (random if None).
    namespace : dict, optional
        Where to find the answer (default: the caller's globals).
    """
    exercise = get(exercise_id)
    if not isinstance(practice, int) or isinstance(practice, bool) or not 0 <= practice <= 1000:
        raise ValueError(f"'practice' must be an int in 0..1000; got {practice!r}")
    if namespace is None:
        namespace = inspect.currentframe().f_back.f_globals
    function = _answer_in(namespace, exercise)
    if function is None:
        return CheckReport(
            exercise,
            [],
            problem=f"no function {exercise.answer!r} yet: run the answer cell first "
            f"(its first line is '# scanviz: answer {exercise.id}')",
        )
    return check_function(exercise, function, case=case, practice=practice, seed=seed)


def public_inputs(exercise_id: str, index: int = 0) -> dict:
    """The inputs of public case `index` of an exercise (for the notebook's stepper cell)."""
    return dict(get(exercise_id).public[index].inputs)

"""The check cell of a student notebook: public cases, diagnostics inline, a side-by-side trace.

``check("span_rule")`` takes the source of the answer cell the student last
ran (the cell whose first line is ``# scanviz: answer span_rule``) and runs
it exactly as grading does: alone, in a runner process of its own (jailed
where bubblewrap can start, else plain), with the algorithm, the cases and
the comparison here. So an answer that leans on another cell's import fails
here too, and check and grade always agree. It runs the public cases (and,
with ``practice=N``, N random cases drawn like the hidden ones from a local
seed).
"""

from __future__ import annotations

import html
from dataclasses import dataclass

from .catalog import get
from .core import Case, Exercise, practice_cases
from .jail import Limits, Session, launch
from .judging import CaseRun, References, judge_answer
from .notebook import ANSWER_MARKER

CASE_SECONDS = 20.0  # wall time of the checked cases before the runner is stopped
_REFERENCES = References()  # the kernel's cache: a second check reuses the reference's runs


@dataclass
class CheckReport:
    """What `check` found: shown as HTML with a trace comparison in a notebook, as text elsewhere."""

    exercise: Exercise
    cases: list[CaseRun]
    practice: int = 0
    problem: str = ""
    status: str = ""

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
                f", practice cases {sum(c.verdict.passed for c in practiced)} of {len(practiced)}"
            )
        return line + " -- hidden cases are graded later"

    def __str__(self) -> str:
        """The headline, the first failing case in full, the others in a line each."""
        lines = [self.headline()]
        failing = [c.verdict for c in self.cases if not c.verdict.passed]
        lines.extend(v.describe() if i == 0 else v.summary() for i, v in enumerate(failing))
        if failing:
            lines.append(
                f'rerun just this case: check("{self.exercise.id}", case={failing[0].case.label!r})'
            )
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        """The headline, the first failing case in full (tables, the raster diff on its grid),
        the others in a line each."""
        from .display import verdict_html

        parts = [f"<p><b>{html.escape(self.headline())}</b></p>"]
        failing = [c for c in self.cases if not c.verdict.passed]
        for index, run in enumerate(failing):
            if index == 0:
                parts.append(
                    verdict_html(run.verdict, run.yours, run.reference, self.exercise.rtol)
                )
            else:
                parts.append(f"<div>{html.escape(run.verdict.summary())}</div>")
        if failing:
            rerun = f'check("{self.exercise.id}", case={failing[0].verdict.case.label!r})'
            parts.append(f"<p>rerun just this case: <code>{html.escape(rerun)}</code></p>")
        return "<div>" + "".join(parts) + "</div>"

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


def answer_cell(exercise_id: str, history: list[str] | None = None) -> str | None:
    """The source of the last cell run whose first line is the exercise's answer marker.

    `history` is the kernel's list of inputs (IPython's ``In``), by default
    that of the running IPython; None if there is none or no such cell ran.
    """
    if history is None:
        try:
            from IPython import get_ipython
        except ImportError:
            return None
        shell = get_ipython()
        history = shell.user_ns.get("In", []) if shell is not None else []
    marker = ANSWER_MARKER + exercise_id
    for source in reversed(history):
        if isinstance(source, str) and source.split("\n", 1)[0].rstrip() == marker:
            return source
    return None


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


def check(
    exercise_id: str,
    *,
    case: str | None = None,
    practice: int = 0,
    seed: int | None = None,
    source: str | None = None,
) -> CheckReport:
    """Check the answer to `exercise_id`: the answer cell last run in this notebook.

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
    source : str, optional
        The answer cell's source (default: the last run cell with the marker).

    Examples
    --------
    >>> from scanviz.exercises import check, get
    >>> print(check("span_rule", source=get("span_rule").solution).headline())
    span_rule -- public cases 5 of 5 -- hidden cases are graded later
    """
    exercise = get(exercise_id)
    if not isinstance(practice, int) or isinstance(practice, bool) or not 0 <= practice <= 1000:
        raise ValueError(f"'practice' must be an int in 0..1000; got {practice!r}")
    cases = _cases(exercise, case, practice, seed)
    if source is None:
        source = answer_cell(exercise.id)
    if source is None:
        return CheckReport(
            exercise,
            [],
            problem=f"no answer cell has run yet: run the cell whose first line is "
            f"'{ANSWER_MARKER}{exercise.id}', then this one",
        )
    limits = Limits(case_seconds=CASE_SECONDS)
    jail = "bwrap" if launch.unavailable("bwrap") is None else "none"  # the student's machine
    with Session(limits, jail=jail) as session:
        judged = judge_answer(
            session, exercise, source, [(c, False) for c in cases], _REFERENCES, CASE_SECONDS
        )
    ran = judged.status in ("passed", "failed", "error") and judged.runs
    problem = "" if ran else f"{judged.status}: {judged.message}"
    return CheckReport(exercise, judged.runs, practice, problem, judged.status)


def public_inputs(exercise_id: str, index: int = 0) -> dict:
    """The inputs of public case `index` of an exercise (for the notebook's stepper cell)."""
    return dict(get(exercise_id).public[index].inputs)

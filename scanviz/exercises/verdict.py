"""How a student's run of a case compares with the reference's: the `Verdict` and what it says.

`judge` compares two outcomes (`scanviz.exercises.core.Outcome`) and names a
known-wrong variant only when the student's run *is* that variant's run on
the case: the same events, the same output at every forced call, the same
result and raster (within the exercise's tolerance), the same kind of error.
A run that goes wrong in some other way is told that no known mistake
matches, and shown what differs.
"""

from __future__ import annotations

import builtins
import re
from dataclasses import dataclass

from .compare import (
    Difference,
    RasterDifference,
    TraceDifference,
    first_difference,
    first_places,
    raster_difference,
    trace_difference,
    traces_equal,
)
from .core import Case, Exercise, Outcome, Variant, VariantRuns
from .jail.wire import Opaque

NO_MATCH = "no known mistake matches this run: what differs is shown above"


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
    variant: Variant | None = None  # the known-wrong variant whose run this is
    unexplained: bool = False  # failed, and no known-wrong variant's run is this one

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

    @property
    def calls_summary(self) -> str:
        """How the forced calls went, without their places ('' when the exercise forces none)."""
        if self.wrong_calls:
            return (
                "with the reference state fed in at every call, yours differs at "
                f"{len(self.wrong_calls)} of {self.calls_total}"
            )
        if not self.calls_total:
            return ""
        return (
            f"with the reference state fed in, all {self.calls_total} calls agree: "
            "the difference comes from an earlier wrong state"
        )

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
            self.case.label if reveal or not self.hidden else (self.case.category or "hidden case")
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
            places = f": {first_places(self.wrong_calls)}" if self.wrong_calls else ""
            lines.append(f"  {self.calls_summary}{places}")
            if self.wrong_calls and self.first_call is not None:
                lines.append(f"    first: {self.first_call.describe()}")
        if self.result is not None:
            lines.append(f"  result: {self.result.describe()}")
        if self.raster is not None:
            lines.extend("  " + line for line in self.raster.describe().splitlines())
        lines.extend(self._cause())
        return "\n".join(lines)

    def _cause(self) -> list[str]:
        if self.variant is not None:
            return [f"  likely cause: {self.variant.hint}"]
        return [f"  {NO_MATCH}"] if self.unexplained else []


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
        lines.append(f"  {verdict.calls_summary}")
    if verdict.result is not None:
        lines.append("  the result differs from the reference's")
    if verdict.raster is not None:
        r = verdict.raster
        lines.append(f"  samples: {r.matched} matched, {r.extra} extra, {r.missing} missing")
    lines.extend(verdict._cause())
    return "\n".join(lines)


def judge(
    exercise: Exercise,
    case: Case,
    yours: Outcome,
    reference: Outcome,
    *,
    hidden: bool = False,
    variants: VariantRuns | None = None,
) -> Verdict:
    """Compare the student's outcome of `case` with the reference's.

    With the known-wrong variants' runs of the case (`VariantRuns`), a failed
    case names the variant whose run is the student's (`same_run`), if any.
    Linear in the traces.
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
    variant = None if passed or variants is None else matching_variant(variants, yours)
    return Verdict(
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
        variant,
        bool(variants and exercise.variants) and not passed and variant is None,
    )


def matching_variant(runs: VariantRuns, yours: Outcome) -> Variant | None:
    """The known-wrong variant whose run of the case is `yours`; a step exercise's variant runs
    only if its forced outputs, replayed, are already the student's."""
    exercise, rtol = runs.exercise, runs.exercise.rtol
    for variant in exercise.variants:
        if (
            exercise.kind == "step"
            and first_difference(runs.forced(variant.name), yours.calls, rtol) is not None
        ):
            continue
        if same_run(yours, runs.run(variant.name), rtol):
            return variant
    return None


def same_run(a: Outcome, b: Outcome, rtol: float) -> bool:
    """Whether two runs agree on everything a verdict looks at (errors by their kind)."""
    return (
        _error_kind(a) == _error_kind(b)
        and traces_equal(a.trace, b.trace, rtol)
        and first_difference(a.calls, b.calls, rtol) is None
        and first_difference(a.result, b.result, rtol) is None
        and first_difference(a.raster, b.raster) is None
    )


def _error_kind(outcome: Outcome) -> str | None:
    return None if outcome.error is None else error_name(outcome.error)

"""Grading an answer in-process, as the grader does but without the sandbox (for the tests)."""

from scanviz.exercises.core import (
    VariantRuns,
    compile_answer,
    reference_outcome,
    run_case,
)
from scanviz.exercises.verdict import judge


def grade(exercise, answer, cases, *, variants=True):
    """The verdicts of `answer` (its source, or the function) on `cases`; variants named if asked."""
    function = compile_answer(answer, exercise.answer) if isinstance(answer, str) else answer
    return [
        judge(
            exercise,
            case,
            run_case(exercise, function, case),
            reference_outcome(exercise, case),
            variants=VariantRuns(exercise, case, reference_outcome(exercise, case))
            if variants
            else None,
        )
        for case in cases
    ]


def known_variant(exercise, name):
    """The known-wrong variant `name` of `exercise`."""
    return next(v for v in exercise.variants if v.name == name)

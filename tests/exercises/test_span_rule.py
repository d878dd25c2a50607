"""The span_rule exercise, and the core's free and forced runs, verdicts and hidden cases on it."""

import pytest

from scanviz.exercises import get
from scanviz.exercises.core import (
    Outcome,
    compile_answer,
    hidden_cases,
    judge,
    reference_outcome,
    run_case,
    score,
    variant_outcomes,
)

EXERCISE = get("span_rule")


def _grade(source, cases):
    function = compile_answer(source, EXERCISE.answer)
    return [
        judge(
            EXERCISE,
            case,
            run_case(EXERCISE, function, case),
            reference_outcome(EXERCISE, case),
            variants=variant_outcomes(EXERCISE, case),
        )
        for case in cases
    ]


def test_solution_scores_full_marks_on_public_and_hidden_cases():
    verdicts = _grade(EXERCISE.solution, [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 20)])
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(EXERCISE, verdicts) == EXERCISE.points


def test_stub_scores_zero_and_says_it_raised():
    verdicts = _grade(EXERCISE.stub, EXERCISE.public)
    assert score(EXERCISE, verdicts) == 0
    assert all(v.error.startswith("NotImplementedError (in span_rule, line 4)") for v in verdicts)


@pytest.mark.parametrize("variant", EXERCISE.variants, ids=lambda v: v.name)
def test_every_variant_fails_a_public_case_and_is_named(variant):
    verdicts = _grade(variant.source, EXERCISE.public)
    assert score(EXERCISE, verdicts) < EXERCISE.points
    assert any(v.variant is not None and v.variant.name == variant.name for v in verdicts)
    assert all(v.variant is None or v.variant.name == variant.name for v in verdicts)


def test_floor_for_ceil_diagnostic_on_the_triangle():
    # Triangle (0,0), (6,0), (6,5): row 1 crosses the hypotenuse at x = 6/5, so ceil
    # starts the span at 2 and floor at 1; rows 1..4 all start one sample early.
    floor = next(v for v in EXERCISE.variants if v.name == "floor_for_ceil")
    verdict = _grade(floor.source, EXERCISE.public[:1])[0]
    text = verdict.describe()
    assert "first difference at event 4 of 10 -- span, row 1" in text
    assert "x_start: yours 1, reference 2" in text
    assert "yours differs at 4 of 6: row 1, row 2, row 3, row 4" in text
    assert "samples: 16 matched (#), 4 extra (!), 0 missing (?)" in text
    assert text.endswith(floor.hint)


def test_hidden_cases_come_from_the_secret_only():
    first = hidden_cases(EXERCISE, "secret one", 6)
    assert first == hidden_cases(EXERCISE, "secret one", 6)
    assert first != hidden_cases(EXERCISE, "secret two", 6)
    assert first != hidden_cases(EXERCISE, "secret one", 6, student="ada")


def test_forced_run_lists_every_wrong_call_not_only_the_first():
    wrong = "def span_rule(crossings, rule):\n    return []\n"
    verdict = _grade(wrong, EXERCISE.public[:1])[0]
    assert verdict.wrong_calls == ("row 0", "row 1", "row 2", "row 3", "row 4")


def test_an_outcome_from_a_worker_is_checked():
    with pytest.raises(ValueError):
        Outcome.from_plain({"trace": 3})
    with pytest.raises(ValueError):
        Outcome.from_plain([1, 2])
    with pytest.raises(ValueError, match="unknown event kind"):
        Outcome.from_plain({"trace": [{"$event": {"kind": "spam"}}]})

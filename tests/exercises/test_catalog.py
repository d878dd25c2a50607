"""What every exercise of the catalog must do: the solution full marks, the stub none, every
known-wrong variant caught and named, hidden cases from the secret only."""

import pytest

from scanviz.exercises import exercises
from scanviz.exercises.core import hidden_cases, score

from .support import grade

EXERCISES = exercises()
VARIANTS = [(e, v) for e in EXERCISES for v in e.variants]


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_solution_scores_full_marks_on_public_and_hidden_cases(exercise):
    cases = [*exercise.public, *hidden_cases(exercise, "test", 20)]
    verdicts = grade(exercise, exercise.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(exercise, verdicts) == exercise.points


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_stub_scores_zero_and_says_it_raised(exercise):
    verdicts = grade(exercise, exercise.stub, exercise.public, variants=False)
    assert score(exercise, verdicts) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in verdicts)


@pytest.mark.parametrize(
    ("exercise", "variant"), VARIANTS, ids=[f"{e.id}-{v.name}" for e, v in VARIANTS]
)
def test_every_variant_fails_a_public_case_and_is_named_there(exercise, variant):
    verdicts = grade(exercise, variant.source, exercise.public)
    assert score(exercise, verdicts) < exercise.points
    assert any(v.variant is not None and v.variant.name == variant.name for v in verdicts)
    assert all(v.variant is None or v.variant.name == variant.name for v in verdicts)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_hidden_cases_come_from_the_secret_only(exercise):
    first = hidden_cases(exercise, "secret one", 6)
    assert first == hidden_cases(exercise, "secret one", 6)
    assert first != hidden_cases(exercise, "secret two", 6)
    assert first != hidden_cases(exercise, "secret one", 6, student="ada")

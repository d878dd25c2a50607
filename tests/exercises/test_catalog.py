"""What every exercise of the catalog must do: the solution full marks, the stub none, every
known-wrong variant caught and named, hidden cases from the secret only."""

import pytest

from scanviz.exercises import exercises
from scanviz.exercises.core import hidden_cases, practice_cases, reference_outcome, score

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


STEPS = [e for e in EXERCISES if e.kind == "step"]


@pytest.mark.parametrize("exercise", STEPS, ids=lambda e: e.id)
def test_every_forced_call_is_placed_in_the_algorithms_terms(exercise):
    # "yours differs at row 5" must name the row (pixel, edge, plane) the call was made for.
    for case in [*exercise.public, *practice_cases(exercise, 10, seed=2)]:
        reference = reference_outcome(exercise, case)
        places = [exercise.place(i, reference.trace) for i in range(len(reference.calls))]
        assert not [p for p in places if p.startswith("call ")], (case.label, places)


def test_span_rule_is_called_once_per_sorted_aet():
    # _row_of_call maps call k to the k-th aet_sorted event: the loop must not call the
    # rule on rows without an AET.
    exercise = next(e for e in EXERCISES if e.id == "span_rule")
    for case in [*exercise.public, *practice_cases(exercise, 30, seed=4)]:
        reference = reference_outcome(exercise, case)
        rows = [e.y for e in reference.trace if e.kind == "aet_sorted"]
        assert len(rows) == len(reference.calls), case.label


# --- hidden cases that every student shares in kind (issue 22) --------------------------------

STUDENTS = ("", "ada", "bo", "cy")  # "" is a class without per_student
FEATURE_SECRET = "features-secret"


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_every_feature_is_in_every_students_hidden_cases(exercise):
    assert exercise.features, "declare the features its hidden cases must exercise"
    for student in STUDENTS:
        cases = hidden_cases(exercise, FEATURE_SECRET, 8, student)
        found = set().union(*(exercise.exercised(c, reference_outcome(exercise, c)) for c in cases))
        assert set(exercise.features) <= found, (student, set(exercise.features) - found)


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_answers_that_do_nothing_score_zero_for_every_student(exercise):
    from scanviz.exercises.core import do_nothing_sources

    cases = [*exercise.public]
    for student in STUDENTS[:2]:
        cases += hidden_cases(exercise, FEATURE_SECRET, 8, student)
    for name, source in do_nothing_sources(exercise).items():
        verdicts = grade(exercise, source, cases, variants=False)
        passed = [v.case.label for v in verdicts if v.passed]
        assert not passed, (name, passed)


@pytest.mark.parametrize(
    ("exercise", "variant"), VARIANTS, ids=[f"{e.id}-{v.name}" for e, v in VARIANTS]
)
def test_every_variant_fails_the_hidden_cases_of_every_student(exercise, variant):
    for student in STUDENTS:
        cases = hidden_cases(exercise, FEATURE_SECRET, 8, student)
        verdicts = grade(exercise, variant.source, cases, variants=False)
        assert not all(v.passed for v in verdicts), student


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_hidden_cases_run_every_line_of_the_step(exercise):
    # Each branch of the reference step (a loop exercise: of its solution) runs in every
    # student's hidden cases, so no branch goes untested for anyone.
    from .coverage import lines_run, step_lines

    target, compiled = step_lines(exercise)
    for student in STUDENTS[:2]:
        cases = hidden_cases(exercise, FEATURE_SECRET, 8, student)
        missed = target - lines_run(exercise, compiled, cases)
        assert not missed, (student, sorted(missed))

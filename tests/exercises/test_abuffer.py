"""The a-buffer exercises: fragment insertion (14) and the packer (15), graded at trace level."""

import pytest

from scanviz import steps
from scanviz.abuffer import Fragments, resolve
from scanviz.exercises.catalog import get
from scanviz.exercises.core import (
    compile_answer,
    hidden_cases,
    judge,
    reference_outcome,
    run_case,
    score,
    variant_outcomes,
)
from scanviz.trace import Recorder

EXERCISES = ("abuffer_insert", "pixel_pack")


def verdicts(exercise, fn, cases, *, with_variants=False):
    return [
        judge(
            exercise,
            case,
            run_case(exercise, fn, case),
            reference_outcome(exercise, case),
            variants=variant_outcomes(exercise, case) if with_variants else None,
        )
        for case in cases
    ]


def traced(exercise, inputs, **replaced):
    with steps.using(**replaced):
        result = resolve(
            Fragments.from_rows(inputs["fragments"]),
            inputs["width"],
            inputs["height"],
            layout=inputs["layout"],
            weights=inputs["weights"],
            background=inputs["background"],
            trace=Recorder(),
        )
    return list(result.trace)


@pytest.mark.parametrize("exercise_id", EXERCISES)
def test_the_solution_scores_full_marks_on_public_and_hidden_cases(exercise_id):
    exercise = get(exercise_id)
    solution = compile_answer(exercise.solution, exercise.answer)
    cases = list(exercise.public) + hidden_cases(exercise, "test", 20)
    results = verdicts(exercise, solution, cases)
    assert [v.describe() for v in results if not v.passed] == []
    assert score(exercise, results) == exercise.points


@pytest.mark.parametrize("exercise_id", EXERCISES)
def test_the_stub_raises_and_scores_zero(exercise_id):
    exercise = get(exercise_id)
    stub = compile_answer(exercise.stub, exercise.answer)
    results = verdicts(exercise, stub, exercise.public)
    assert score(exercise, results) == 0
    assert all(v.error.startswith("NotImplementedError") for v in results)


@pytest.mark.parametrize("exercise_id", EXERCISES)
def test_every_variant_fails_a_public_case_and_is_named_on_one(exercise_id):
    exercise = get(exercise_id)
    assert len(exercise.variants) >= 3
    for variant in exercise.variants:
        wrong = compile_answer(variant.source, exercise.answer)
        results = verdicts(exercise, wrong, exercise.public, with_variants=True)
        assert score(exercise, results) < exercise.points, variant.name
        assert any(not v.passed for v in results), variant.name
        assert any(v.variant is not None and v.variant.name == variant.name for v in results), (
            variant.name,
            [v.variant and v.variant.name for v in results],
        )


@pytest.mark.parametrize("exercise_id", EXERCISES)
def test_hidden_cases_come_from_the_secret(exercise_id):
    exercise = get(exercise_id)
    first = hidden_cases(exercise, "test", 5)
    assert [c.inputs for c in first] == [c.inputs for c in hidden_cases(exercise, "test", 5)]
    assert [c.inputs for c in first] != [c.inputs for c in hidden_cases(exercise, "other", 5)]
    for case in first:
        assert case.category and 1 <= case.inputs["width"] * case.inputs["height"] <= 16


@pytest.mark.parametrize("exercise_id", EXERCISES)
def test_the_reference_plugged_in_gives_the_default_trace(exercise_id):
    exercise = get(exercise_id)
    for case in list(exercise.public) + hidden_cases(exercise, "test", 3):
        default = traced(exercise, case.inputs)
        plugged = traced(exercise, case.inputs, **{exercise.step: exercise.reference})
        assert plugged == default
        assert any(e.kind in exercise.kinds for e in default)


def variant_verdict(exercise_id, variant_name, case_index):
    exercise = get(exercise_id)
    variant = next(v for v in exercise.variants if v.name == variant_name)
    wrong = compile_answer(variant.source, exercise.answer)
    (verdict,) = verdicts(exercise, wrong, [exercise.public[case_index]], with_variants=True)
    return verdict


def test_golden_diagnostic_of_an_insertion_that_never_discards():
    # Pixel (0, 0): a complete red fragment at z 0.2, then the left half (0x3333) of a green one
    # at z 0.6 behind it. The reference throws the green one away; the variant keeps it second.
    # 13 events: 9 insertions and 4 discards (pixels (0, 0), (1, 0), (2, 0), (0, 1)).
    text = variant_verdict("abuffer_insert", "never_discard", 0).describe()
    green = (
        f"FragmentRecord(z=0.6, zmax=0.6, area=0.5, mask={0x3333}, color=[0.0, 1.0, 0.0], "
        "opacity=1.0, object=1)"
    )
    assert "first difference at event 2 of 13 -- fragment_inserted, polygon 1, pixel (0, 0)" in text
    assert f"after[1]: extra in yours ({green}); the reference has none" in text
    assert "differs at 4 of 9: fragment 1 at pixel (0, 0), fragment 3 at pixel (1, 0)" in text
    assert "likely cause: nothing is thrown away" in text


def test_golden_diagnostic_of_a_packer_without_background():
    # Thesis Fig. 6.7 on a 4x4 mask: red left half in front, green bottom half behind, blue
    # background. The first step to finish is green's (level 1) on the right half: it covers
    # the bottom-right quarter and leaves the top-right quarter (weight 1/4) to the background,
    # so its color is green * 1/4 + blue * 1/4 = (0, 0.25, 0.25); without the background the
    # blue part is 0.
    text = variant_verdict("pixel_pack", "no_background", 0).describe()
    assert "first difference at event 1 of 2 -- pixel_packed, pixel (0, 0)" in text
    assert "steps[0].color[2]: yours 0.0, reference 0.25" in text
    assert "result: ['image'][0][0][2]: yours 0.0, reference 0.25" in text
    assert "likely cause: uncovered samples left black" in text

"""The a-buffer exercises: fragment insertion (14) and the packer (15), graded at trace level."""

import pytest

from scanviz import steps
from scanviz.exercises.abuffer import case_resolve
from scanviz.exercises.catalog import get
from scanviz.exercises.core import (
    compile_answer,
    hidden_cases,
)
from scanviz.trace import Recorder

from .support import grade

EXERCISES = ("abuffer_insert", "pixel_pack")


def traced(exercise, inputs, **replaced):
    with steps.using(**replaced):
        return list(case_resolve(inputs, Recorder()).trace)


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
    (verdict,) = grade(exercise, wrong, [exercise.public[case_index]])
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

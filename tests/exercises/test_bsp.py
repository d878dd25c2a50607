"""The BSP display-order exercise (17): bsp_display_order plugged into the real BSP display."""

import numpy as np
import pytest

from scanviz import steps
from scanviz.exercises.bsp import EXERCISE, case_options, case_polygons
from scanviz.exercises.core import hidden_cases, practice_cases, reference_outcome, score
from scanviz.trace import Recorder
from scanviz.visibility import examples, solve, zbuffer

from .support import grade, known_variant


def test_the_exercise_has_its_number_and_step():
    assert (EXERCISE.number, EXERCISE.step, EXERCISE.rtol) == (17, "bsp_display_order", 0.0)


def test_the_reference_plugged_in_gives_the_default_trace():
    for case in [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 5)]:
        inputs = dict(case.inputs)
        default = Recorder(EXERCISE.kinds)
        solve(
            case_options(inputs),
            case_polygons(inputs),
            inputs["width"],
            inputs["height"],
            trace=default,
        )
        plugged = Recorder(EXERCISE.kinds)
        EXERCISE.call(EXERCISE.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        assert not steps.replaced()


def test_the_public_cases_show_the_zbuffers_image():
    # Each public case has no ties: the reference display is the z-buffer's image exactly.
    for case in EXERCISE.public:
        inputs = dict(case.inputs)
        polygons = case_polygons(inputs)
        mine = EXERCISE.call(EXERCISE.reference, inputs, None)
        reference = zbuffer(polygons, inputs["width"], inputs["height"])
        assert np.array_equal(mine.polygon, reference.polygon), case.label


def test_the_first_public_case_is_the_slides_example():
    inputs = dict(EXERCISE.public[0].inputs)
    polygons, slides = case_polygons(inputs), examples.slides_bsp()
    assert np.array_equal(polygons.xy, slides.xy) and np.array_equal(polygons.z, slides.z)
    assert tuple(inputs["sequence"]) == examples.BSP_SEQUENCE


def test_the_solution_scores_full_marks_and_the_stub_none():
    cases = [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 12)]
    verdicts = grade(EXERCISE, EXERCISE.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(EXERCISE, verdicts) == EXERCISE.points
    stubbed = grade(EXERCISE, EXERCISE.stub, EXERCISE.public, variants=False)
    assert score(EXERCISE, stubbed) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stubbed)


@pytest.mark.parametrize("variant", EXERCISE.variants, ids=lambda v: v.name)
def test_every_variant_fails_a_public_case_and_is_named_there(variant):
    verdicts = grade(EXERCISE, variant.source, EXERCISE.public)
    assert score(EXERCISE, verdicts) < EXERCISE.points
    assert any(v.variant is not None and v.variant.name == variant.name for v in verdicts)
    assert all(v.variant is None or v.variant.name == variant.name for v in verdicts)


def test_hidden_cases_come_from_the_secret_and_call_the_step():
    first = hidden_cases(EXERCISE, "secret one", 6)
    assert first == hidden_cases(EXERCISE, "secret one", 6)
    assert first != hidden_cases(EXERCISE, "secret two", 6)
    assert all(reference_outcome(EXERCISE, case).calls for case in first)
    categories = {case.category for case in hidden_cases(EXERCISE, "s", 20)}
    assert categories == {"back to front", "front to back"}


def test_every_forced_call_is_placed_at_a_node():
    for case in [*EXERCISE.public, *practice_cases(EXERCISE, 10, seed=2)]:
        reference = reference_outcome(EXERCISE, case)
        places = [EXERCISE.place(i, reference.trace) for i in range(len(reference.calls))]
        assert places and all(p.startswith("node ") for p in places), (case.label, places)


def test_sides_swapped_diagnostic_on_the_slides():
    # At 3 the viewer is in front (back first); swapped, the front subtree (2) comes first.
    variant = known_variant(EXERCISE, "sides_swapped")
    text = grade(EXERCISE, variant.source, EXERCISE.public[:1])[0].describe()
    assert "first difference at event 1 of 7 -- bsp_visited" in text
    assert "first: yours 'front', reference 'back'" in text
    assert "yours differs at 6 of 6: node 0 (piece 3), node 4 (piece 4)" in text
    assert text.endswith(variant.hint)

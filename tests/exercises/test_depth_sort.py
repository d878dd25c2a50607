"""The depth sort exercise (16): depth_order_test plugged into the real depth sort."""

import numpy as np

import scanviz.exercises.depth_sort  # noqa: F401 - registers the exercise (until in MODULES)
from scanviz import steps
from scanviz.exercises.catalog import get
from scanviz.exercises.core import hidden_cases, practice_cases, reference_outcome, score
from scanviz.exercises.depth_sort import BEYOND, GAPS, NEAR, case_polygons
from scanviz.trace import Recorder
from scanviz.visibility import solve, zbuffer

from .support import grade, known_variant

EXERCISE = get("depth_sort_tests")


def test_the_exercise_has_its_number_and_step():
    assert (EXERCISE.number, EXERCISE.step, EXERCISE.rtol) == (16, "depth_order_test", 0.0)


def test_the_reference_plugged_in_gives_the_default_trace_and_the_zbuffer_image():
    for case in [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 6)]:
        inputs = dict(case.inputs)
        polygons, size = case_polygons(inputs), (inputs["width"], inputs["height"])
        default = Recorder(EXERCISE.kinds)
        result = solve("depth_sort", polygons, *size, trace=default)
        plugged = Recorder(EXERCISE.kinds)
        EXERCISE.call(EXERCISE.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        assert not steps.replaced()
        if "cyclic" in case.label:
            assert np.array_equal(result.polygon, zbuffer(polygons, *size).polygon)


def test_solution_scores_full_marks_and_the_stub_none():
    cases = [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 8)]
    verdicts = grade(EXERCISE, EXERCISE.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    stub = grade(EXERCISE, EXERCISE.stub, EXERCISE.public, variants=False)
    assert score(EXERCISE, stub) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stub)


def test_every_variant_fails_a_public_case_and_is_named_there():
    for variant in EXERCISE.variants:
        verdicts = grade(EXERCISE, variant.source, EXERCISE.public)
        assert score(EXERCISE, verdicts) < EXERCISE.points, variant.name
        names = {v.variant.name for v in verdicts if v.variant is not None}
        assert names == {variant.name}, (variant.name, names)


def test_hidden_cases_come_from_the_secret_and_call_the_step():
    first = hidden_cases(EXERCISE, "secret one", 4)
    assert first == hidden_cases(EXERCISE, "secret one", 4)
    assert first != hidden_cases(EXERCISE, "secret two", 4)
    assert all(reference_outcome(EXERCISE, case).calls for case in first)


def test_every_forced_call_is_placed_at_its_pair():
    for case in [*EXERCISE.public, *practice_cases(EXERCISE, 6, seed=2)]:
        reference = reference_outcome(EXERCISE, case)
        places = [EXERCISE.place(i, reference.trace) for i in range(len(reference.calls))]
        assert places and all(p.startswith("pair S = ") for p in places), (case.label, places)


def test_touching_extents_diagnostic_names_the_pair_and_the_test():
    # The two rectangles share the border x = 6: x_extent settles them. Counting touching
    # extents as overlapping, the answer falls through to no_overlap (they only touch).
    variant = known_variant(EXERCISE, "extents_touching_overlap")
    text = grade(EXERCISE, variant.source, EXERCISE.public[4:5])[0].describe()
    assert "first difference at event 1 of 1 -- pair_tested" in text
    assert "tests[1].passed: yours False, reference True" in text  # tests[1] is x_extent
    assert "yours differs at 1 of 1: pair S = 0, S' = 1" in text
    assert "first: yours 'no_overlap', reference 'x_extent'" in text
    assert text.endswith(variant.hint)


def _front(args) -> float:
    """How far the vertex of S nearest in front of the plane of S' is in front of it."""
    s, _, _, (x0, y0, z0, dzdx, dzdy), _ = args
    return max(z0 + dzdx * (x - x0) + dzdy * (y - y0) - z for x, y, z in s)


def test_near_equal_depths_are_built_exactly_and_each_exposes_its_variant():
    # The first call of each student's near-equal case has S in front of the plane of S' by
    # exactly the gap (quarter pixels, dyadic depths): 2^-32 within the tolerance 1e-9, 2^-28
    # beyond it; ignoring the tolerance fails the first, an epsilon of 1e-6 the second.
    wrong = {NEAR: "no_tolerance", BEYOND: "fixed_epsilon"}
    for student in ("", "ada", "bo"):
        cases = hidden_cases(EXERCISE, "near", len(EXERCISE.features), student)
        assert set(GAPS) <= {c.category for c in cases}
        for case in [c for c in cases if c.category in GAPS]:
            reference = reference_outcome(EXERCISE, case)
            first, _ = reference.arguments[0]
            assert _front(first) == GAPS[case.category] and first[4] == 1e-9, case.label
            assert (reference.calls[0] == "s_behind_plane") == (case.category == NEAR)
            variant = known_variant(EXERCISE, wrong[case.category])
            assert not grade(EXERCISE, variant.source, [case], variants=False)[0].passed
            assert grade(EXERCISE, EXERCISE.solution, [case], variants=False)[0].passed


def test_a_fixed_epsilon_is_named_where_a_square_is_just_beyond_the_tolerance():
    variant = known_variant(EXERCISE, "fixed_epsilon")
    text = grade(EXERCISE, variant.source, EXERCISE.public[5:6])[0].describe()
    assert "yours differs at 1 of 5: pair S = 2, S' = 0" in text
    assert "first: yours 's_behind_plane', reference None" in text
    assert text.endswith(variant.hint)
    near = grade(EXERCISE, known_variant(EXERCISE, "no_tolerance").source, EXERCISE.public[5:6])
    assert "first: yours 'other_in_front', reference 's_behind_plane'" in near[0].describe()

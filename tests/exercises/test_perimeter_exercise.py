"""The floating perimeter exercises (18, 19): perimeter_test and perimeter_merge plugged into the
real Floating Perimeter Algorithm (lines mode)."""

import dataclasses
import re
from pathlib import Path

import nbformat
import pytest

from scanviz import steps
from scanviz.exercises.catalog import get
from scanviz.exercises.core import hidden_cases, practice_cases, reference_outcome, score
from scanviz.exercises.perimeter import KINDS, VIEWINGS, case_surface, case_view
from scanviz.exercises.release import ANSWER_MARKER, answer_cell_source, notebook_name
from scanviz.surfaces import compare_with_zbuffer, floating_perimeter
from scanviz.trace import Recorder

from .support import grade, known_variant

TEST, MERGE = get("perimeter_test"), get("perimeter_merge")
BOTH = (TEST, MERGE)
FOLDER = Path(__file__).parents[2] / "notebooks" / "exercises"


def _lines(inputs, trace=None):
    return floating_perimeter(
        case_surface(inputs), case_view(inputs), inputs["width"], inputs["height"], trace=trace
    )


def test_the_exercises_have_their_numbers_and_steps():
    assert [(e.number, e.step, e.kind, e.rtol) for e in BOTH] == [
        (18, "perimeter_test", "step", 0.0),
        (19, "perimeter_merge", "step", 0.0),
    ]
    assert TEST.public == MERGE.public and TEST.kinds == MERGE.kinds == KINDS


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_the_reference_plugged_in_gives_the_default_trace_and_lines(exercise):
    for case in [*exercise.public, *hidden_cases(exercise, "test", 4)]:
        inputs = dict(case.inputs)
        default = Recorder(KINDS)
        result = _lines(inputs, default)
        plugged = Recorder(KINDS)
        mine = exercise.call(exercise.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        assert (mine.lines == result.lines).all() and (mine.lines == _lines(inputs).lines).all()
        assert not steps.replaced()


def test_the_public_cases_cover_the_kinds_of_viewing_case():
    results = [_lines(dict(case.inputs)) for case in TEST.public]
    assert [r.case for r in results] == [9, 2, 1, 8, 8]
    assert [case.inputs["projection"] for case in TEST.public].count("parallel") == 1
    assert all(r.stats.edges_partial and r.stats.visible < r.stats.points for r in results)
    assert sum(c.inputs["width"] != c.inputs["height"] for c in TEST.public) == 3


def test_the_hole_case_hides_points_the_zbuffer_shows_and_no_earlier_facet_covers():
    hole = TEST.public[-1]
    inputs = dict(hole.inputs)
    comparison = compare_with_zbuffer(
        case_surface(inputs), case_view(inputs), inputs["width"], inputs["height"]
    )
    points = comparison.fpa.points[comparison.hole].tolist()
    assert comparison.holes == 2 and points == [[11, 16], [12, 18]]
    assert set(comparison.fpa.edges.facet[comparison.fpa.point_edge[comparison.hole]]) == {4}
    # The reference grades them hidden: the trace the student must match says so.
    trace = reference_outcome(TEST, hole).trace
    flags = {
        (tuple(p), e.facet): v for e in trace if e.kind == "perimeter_edge"
        for p, v in zip(e.points, e.visible, strict=True)
    }  # fmt: skip
    assert flags[(11, 16), 4] is False and flags[(12, 18), 4] is False


def test_the_test_is_called_once_per_point_and_the_merge_once_per_facet():
    # The cases fit the grid to the raster, so every point is on it and is tested.
    for case in [*TEST.public, *practice_cases(TEST, 6, seed=3)]:
        inputs = dict(case.inputs)
        result = _lines(inputs)
        tests, merges = reference_outcome(TEST, case), reference_outcome(MERGE, case)
        assert len(tests.calls) == len(result.points) == result.stats.points, case.label
        assert len(merges.calls) == case_surface(inputs).facets, case.label
        assert merges.calls[-1] == {
            "top": result.perimeter.top.tolist(),
            "bottom": result.perimeter.bottom.tolist(),
            "right": result.perimeter.right.tolist(),
            "left": result.perimeter.left.tolist(),
        }


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_solution_scores_full_marks_and_the_stub_none(exercise):
    cases = [*exercise.public, *hidden_cases(exercise, "test", 8)]
    verdicts = grade(exercise, exercise.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(exercise, verdicts) == exercise.points
    stub = grade(exercise, exercise.stub, exercise.public, variants=False)
    assert score(exercise, stub) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stub)


FIG_2_4_TEST = """\
def perimeter_test(top, bottom, right, left, x, y):
    outside = x >= right[y] or x <= left[y] or y >= top[x] or y <= bottom[x]
    return not outside
"""
NUMPY_MERGE = """\
import numpy as np


def perimeter_merge(top, bottom, right, left, bbuf):
    if not bbuf:
        return top, bottom, right, left  # a return value is ignored: the arrays are the output
    x, y = np.array(bbuf).T
    np.maximum.at(top, x, y)
    np.minimum.at(bottom, x, y)
    np.maximum.at(right, y, x)
    np.minimum.at(left, y, x)
"""


@pytest.mark.parametrize(
    ("exercise", "answer"), [(TEST, FIG_2_4_TEST), (MERGE, NUMPY_MERGE)], ids=["fig_2_4", "numpy"]
)
def test_other_correct_answers_score_full_marks(exercise, answer):
    verdicts = grade(exercise, answer, [*exercise.public, *hidden_cases(exercise, "t", 4)])
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]


VARIANTS = [(e, v) for e in BOTH for v in e.variants]


@pytest.mark.parametrize(
    ("exercise", "variant"), VARIANTS, ids=[f"{e.id}-{v.name}" for e, v in VARIANTS]
)
def test_every_variant_fails_a_public_case_and_is_named_there(exercise, variant):
    verdicts = grade(exercise, variant.source, exercise.public)
    assert score(exercise, verdicts) < exercise.points
    assert {v.variant.name for v in verdicts if v.variant is not None} == {variant.name}


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_hidden_cases_come_from_the_secret_and_call_the_step(exercise):
    first = hidden_cases(exercise, "secret one", 4)
    assert first == hidden_cases(exercise, "secret one", 4)
    assert first != hidden_cases(exercise, "secret two", 4)
    assert all(reference_outcome(exercise, case).calls for case in first)
    assert {case.category for case in hidden_cases(exercise, "s", 16)} == set(VIEWINGS)


def test_generated_cases_are_in_the_viewing_case_their_category_names():
    cases = {"face-on": {1}, "edge-on": {2, 3, 4, 5}, "corner-on": {6, 7, 8, 9}}
    for case in practice_cases(TEST, 30, seed=6):
        result = _lines(dict(case.inputs))
        assert result.case in cases.get(case.category, range(1, 10)), case.label
        assert (case.inputs["projection"] == "parallel") == (case.category == "parallel")
        assert 3 <= len(case.inputs["x"]) <= 6 and 24 <= case.inputs["width"] <= 48


def test_most_generated_cases_hide_something():
    # Low viewpoints: in most cases some point is hidden, so the variants have work to fail.
    stats = [_lines(dict(case.inputs)).stats for case in practice_cases(TEST, 30, seed=5)]
    assert sum(s.visible < s.points for s in stats) >= 18


@pytest.mark.parametrize(("exercise", "prefix"), [(TEST, "point ("), (MERGE, "facet ")])
def test_every_forced_call_is_placed_at_its_point_or_facet(exercise, prefix):
    for case in [*exercise.public, *practice_cases(exercise, 6, seed=2)]:
        reference = reference_outcome(exercise, case)
        places = [exercise.place(i, reference.trace) for i in range(len(reference.calls))]
        assert places and all(p.startswith(prefix) for p in places), (case.label, places[:3])


def _describe(exercise, name, case):
    variant = known_variant(exercise, name)
    verdict = grade(exercise, variant.source, [case])[0]
    return verdict, verdict.describe()


def _perimeter_before(trace, facet, width, height):
    """top, bottom, right, left as the updates of the facets before `facet` left them."""
    top, bottom, right, left = [0] * width, [height] * width, [0] * height, [width] * height
    for event in trace:
        if event.kind == "perimeter_update" and event.facet < facet:
            for x, high, low in event.columns:
                top[x], bottom[x] = high, low
            for y, high, low in event.rows:
                right[y], left[y] = high, low
    return top, bottom, right, left


def test_columns_only_is_caught_where_a_point_is_beside_the_covered_rows():
    # On the ridge, only two points lie inside their column's span but outside their row's.
    case = TEST.public[1]
    verdict, text = _describe(TEST, "columns_only", case)
    assert "-- perimeter_edge" in text and "visible[1]: yours False, reference True" in text
    assert verdict.wrong_calls == ("point (29, 12) of facet 8", "point (6, 13) of facet 9")
    trace, size = reference_outcome(TEST, case).trace, (case.inputs["width"], case.inputs["height"])
    for (x, y), facet in (((29, 12), 8), ((6, 13), 9)):
        top, bottom, right, left = _perimeter_before(trace, facet, *size)
        assert bottom[x] < y < top[x] and not left[y] < x < right[y]
    assert text.endswith(known_variant(TEST, "columns_only").hint)


def test_swapped_axes_indexes_past_a_non_square_raster():
    # The ridge's raster is 36 x 18: right and left have 18 entries, indexed by x up to 35.
    verdict, text = _describe(TEST, "swapped_axes", TEST.public[1])
    assert verdict.error.startswith("IndexError: index 18 is out of bounds")
    assert verdict.error.endswith("(in perimeter_test, line 3)")
    assert verdict.variant.name == "swapped_axes"


def test_on_perimeter_hidden_differs_exactly_at_points_on_the_perimeter():
    # Facet 1 (4 edges and its update, events 1-5) hides nothing; its points are the perimeter.
    case = TEST.public[0]
    verdict, text = _describe(TEST, "on_perimeter_hidden", case)
    assert verdict.trace.kind == "perimeter_edge" and verdict.trace.index >= 5
    assert "yours False, reference True" in text and "first: yours True, reference False" in text
    trace, size = reference_outcome(TEST, case).trace, (case.inputs["width"], case.inputs["height"])
    for place in verdict.wrong_calls:
        x, y, facet = map(
            int, re.fullmatch(r"point \((\d+), (\d+)\) of facet (\d+)", place).groups()
        )
        top, bottom, right, left = _perimeter_before(trace, facet, *size)
        on = bottom[x] <= y <= top[x] and left[y] <= x <= right[y]
        assert on and not (bottom[x] < y < top[x] and left[y] < x < right[y]), place


def test_reset_each_facet_first_differs_at_the_second_facets_update():
    # Resetting the initial arrays before facet 1 changes nothing: facet 2's merge is the first
    # wrong one, after facet 1's 4 edges and update and facet 2's 3 edges (hill, case 9).
    verdict, text = _describe(MERGE, "reset_each_facet", MERGE.public[0])
    assert "first difference at event 9 of 56 -- perimeter_update" in text
    assert verdict.wrong_calls[0] == "facet 2" and "facet 1" not in verdict.wrong_calls
    assert len(verdict.wrong_calls) == verdict.calls_total - 1 == 15


@pytest.mark.parametrize("name", ["top_only", "min_max_swapped"])
def test_a_perimeter_that_never_encloses_hides_nothing(name):
    # Without a lowered bottom (or with min and max swapped) no point is strictly inside.
    from scanviz.exercises.core import compile_answer, run_case

    variant = known_variant(MERGE, name)
    for case in MERGE.public:
        outcome = run_case(MERGE, compile_answer(variant.source, MERGE.answer), case)
        edges = [e for e in outcome.trace if e.kind == "perimeter_edge"]
        assert edges and all(all(e.visible) for e in edges), case.label
        if name == "min_max_swapped":  # the arrays never change
            updates = [e for e in outcome.trace if e.kind == "perimeter_update"]
            assert all(u.columns == u.rows == () for u in updates), case.label


def test_a_wrong_merge_is_named_with_the_merged_array_and_entry():
    verdict, text = _describe(MERGE, "overwrites", MERGE.public[0])
    assert "first difference at event 5 of 56 -- perimeter_update" in text  # facet 1's update
    assert verdict.first_call.path.startswith(
        ("['bottom'][", "['left'][", "['right'][", "['top'][")
    )
    assert text.endswith(known_variant(MERGE, "overwrites").hint)


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_the_released_notebook_holds_the_stub_and_runs_the_perimeter_stepper(exercise):
    notebook = nbformat.read(FOLDER / notebook_name(exercise), as_version=4)
    answers = [c for c in notebook.cells if c.source.startswith(ANSWER_MARKER)]
    assert [a.source for a in answers] == [answer_cell_source(exercise, exercise.stub)]
    assert "perimeter_stepper(case_surface(CASE), case_view(CASE)" in notebook.cells[1].source
    assert "Wang 1989, ch. 2, Fig. 2-4" in notebook.cells[0].source  # cited by author and year


def test_the_released_notebooks_grade_blank_zero_and_solved_full(tmp_path):
    from scanviz.exercises.grading import grade_submissions
    from scanviz.exercises.key import ExerciseKey, new_key

    for student, body in (("blank", "stub"), ("solved", "solution")):
        folder = tmp_path / "class" / student
        folder.mkdir(parents=True)
        for exercise in BOTH:
            notebook = nbformat.read(FOLDER / notebook_name(exercise), as_version=4)
            for cell in notebook.cells:
                if cell.source.startswith(ANSWER_MARKER):
                    cell.source = answer_cell_source(exercise, getattr(exercise, body))
            nbformat.write(notebook, folder / notebook_name(exercise))
    key = dataclasses.replace(
        new_key(),
        secret="fixed secret of the perimeter exercises",
        exercises={e.id: ExerciseKey(e.points, 2) for e in BOTH},
    )
    grades = {s.student: s for s in grade_submissions(tmp_path / "class", key, progress=False)}
    solved, blank = grades["solved"], grades["blank"]
    assert [(g.exercise, g.status) for g in solved.grades] == [(e.id, "passed") for e in BOTH]
    assert solved.score == solved.max_score == sum(e.points for e in BOTH)
    assert blank.score == 0 and {g.status for g in blank.grades} == {"error"}

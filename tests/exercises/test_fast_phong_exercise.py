"""The fast Phong exercises (20, 21): specular_level and forward_difference plugged into the real
traced fast Phong shader (fast_phong_triangle)."""

import dataclasses
import re
from pathlib import Path

import nbformat
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.exercises.catalog import get
from scanviz.exercises.core import (
    compile_answer,
    hidden_cases,
    practice_cases,
    reference_outcome,
    run_case,
    score,
)
from scanviz.exercises.fast_phong import CATEGORIES, KINDS, QUADRATICS, _shade, case_model
from scanviz.exercises.release import ANSWER_MARKER, answer_cell_source, notebook_name
from scanviz.shading.lut import level_comparisons, lut_level, lut_level_coherent, specular_lut
from scanviz.trace import Recorder

from .support import grade, known_variant

LEVEL, DIFFERENCE = get("specular_level"), get("forward_difference")
BOTH = (LEVEL, DIFFERENCE)
FOLDER = Path(__file__).parents[2] / "notebooks" / "exercises"
AT_U, BLINN, NARROW, GRAZING, DULL = LEVEL.public


def _pixels(case):
    return [e for e in reference_outcome(LEVEL, case).trace if e.kind == "fast_phong_pixel"]


def _span_neighbours(pixels):
    """(previous, this) for every sample after a span's first."""
    return [(a, b) for a, b in zip(pixels, pixels[1:], strict=False) if not b.direct]


def test_the_exercises_have_their_numbers_and_steps():
    assert [(e.number, e.step, e.kind, e.rtol, e.points) for e in BOTH] == [
        (20, "specular_level", "step", 0.0, 3),
        (21, "forward_difference", "step", 0.0, 2),
    ]
    assert LEVEL.public == DIFFERENCE.public and LEVEL.kinds == DIFFERENCE.kinds == KINDS


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_the_reference_plugged_in_gives_the_default_trace_and_the_compiled_colours(exercise):
    for case in [*exercise.public, *hidden_cases(exercise, "test", 4)]:
        inputs = dict(case.inputs)
        default = Recorder(KINDS)
        traced = _shade(inputs, default)
        plugged = Recorder(KINDS)
        mine = exercise.call(exercise.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        compiled = _shade(inputs)  # no tracer, no step replaced: the numba kernels
        assert np.array_equal(mine.colors, traced.colors), case.label
        assert np.array_equal(compiled.colors, traced.colors), case.label
        assert np.array_equal(compiled.highlight, traced.highlight), case.label
        assert not steps.replaced()


def test_a_replaced_step_reaches_the_untraced_entry_point():
    inputs = dict(AT_U.inputs)
    assert _shade(inputs).highlight.max() == 119
    with steps.using(specular_level=lambda table, cos_phi, start: 0):
        assert _shade(inputs).highlight.max() == 0  # the reference loop ran, with the step
    with steps.using(forward_difference=lambda q, dq, t5: (q, dq)):
        flat = _shade(inputs)
    first = flat.ys == 0  # row 0 is one span: every sample keeps pixel (0, 0)'s values
    assert np.all(flat.colors[first] == flat.colors[0])
    assert _shade(inputs).highlight.max() == 119


def test_the_comparisons_traced_are_the_reference_searchs():
    for case in [*LEVEL.public, *practice_cases(LEVEL, 6, seed=8)]:
        table = case_model(case.inputs).table
        pixels = _pixels(case)
        level = None
        for pixel in pixels:
            start = None if pixel.direct else level
            expected = (
                lut_level(table, pixel.cos_specular, count=True)
                if start is None
                else lut_level_coherent(table, pixel.cos_specular, start, count=True)
            )
            assert (pixel.level, pixel.comparisons) == expected, (case.label, pixel)
            level = pixel.level


@settings(max_examples=60, derandomize=True, deadline=None)
@given(
    size=st.integers(0, 300),
    n=st.sampled_from([0.5, 1.0, 6.0, 60.0]),
    cosine=st.floats(-1.5, 1.5),
    start=st.integers(0, 300),
)
def test_level_comparisons_replays_both_searches(size, n, cosine, start):
    table = specular_lut(255, size / 255, 1, n)
    start = min(start, len(table))
    level, binary = lut_level(table, cosine, count=True)
    assert level_comparisons(len(table), level) == binary
    walked, coherent = lut_level_coherent(table, cosine, start, count=True)
    assert walked == level and level_comparisons(len(table), level, start) == coherent


def test_level_comparisons_takes_a_wrong_level_as_the_nearest_end():
    assert level_comparisons(10, -3) == level_comparisons(10, 0)
    assert level_comparisons(10, 14, 12) == level_comparisons(10, 10, 10)


def test_the_public_cases_show_what_their_labels_say():
    models = [case_model(case.inputs) for case in LEVEL.public]
    assert {m.specular for m in models} == {"phong", "blinn"}
    assert {case.inputs["expansion"] for case in LEVEL.public} == {"vertex", "centroid"}
    at_u = _pixels(AT_U)[0]
    assert (at_u.x, at_u.y, at_u.direct, at_u.cos_specular, at_u.level) == (0, 0, True, 1.0, 119)
    # Blinn about the centroid: on some span the level rises, then falls.
    blinn = _span_neighbours(_pixels(BLINN))
    assert any(b.level > a.level for a, b in blinn) and any(b.level < a.level for a, b in blinn)
    # The narrow highlight: N = 255, and the coherent walk crosses up to 51 entries a sample.
    assert len(models[2].table) == 255
    assert max(abs(b.level - a.level) for a, b in _span_neighbours(_pixels(NARROW))) == 51
    grazing, table = _pixels(GRAZING), models[3].table
    assert any(not e.lit for e in grazing)
    assert all(e.color == (25.5, 25.5, 25.5) for e in grazing if not e.lit)  # ambient only
    assert any(e.lit and e.cos_specular < table[0] and e.level == 0 for e in grazing)
    dull, entries = _pixels(DULL), set(models[4].table.tolist())
    assert len(models[4].table) == 128
    assert sum(e.cos_specular in entries for e in dull) == 10


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_solution_scores_full_marks_and_the_stub_none(exercise):
    cases = [*exercise.public, *hidden_cases(exercise, "test", 8)]
    verdicts = grade(exercise, exercise.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(exercise, verdicts) == exercise.points
    stub = grade(exercise, exercise.stub, exercise.public, variants=False)
    assert score(exercise, stub) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stub)


COUNTING_LEVEL = """\
def specular_level(table, cos_phi, start):
    return sum(1 for entry in table if entry <= cos_phi)  # ignores start: still the level
"""
NUMPY_LEVEL = """\
import numpy as np


def specular_level(table, cos_phi, start):
    return int(np.count_nonzero(table <= cos_phi))
"""
REORDERED_DIFFERENCE = """\
def forward_difference(q, dq, t5):
    return dq + q, t5 * 2.0 + dq  # additions commute: the same bits
"""


@pytest.mark.parametrize(
    ("exercise", "answer"),
    [(LEVEL, COUNTING_LEVEL), (LEVEL, NUMPY_LEVEL), (DIFFERENCE, REORDERED_DIFFERENCE)],
    ids=["counting", "numpy", "reordered"],
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
    assert {case.category for case in hidden_cases(exercise, "s", 20)} == set(CATEGORIES)


def test_generated_cases_are_what_their_category_names():
    for case in practice_cases(LEVEL, 30, seed=6):
        model, pixels = case_model(case.inputs), _pixels(case)
        steps_ = _span_neighbours(pixels)
        assert len(pixels) >= 6 and steps_, case.label
        assert any(abs(b.level - a.level) > 1 for a, b in steps_), case.label
        if case.category in ("phong highlight", "blinn highlight"):
            assert model.specular == case.category.split()[0], case.label
        if case.category == "narrow highlight":
            assert len(model.table) == 255 and model.n >= 40, case.label
        if case.category == "highlight at vertex U":
            first = pixels[0]
            vertex = case.inputs["vertices"][0]
            assert (first.x, first.y) == tuple(vertex) and first.cos_specular == 1.0, case.label
            assert first.level == len(model.table), case.label
        if case.category == "past the terminator":
            assert any(not e.lit for e in pixels) and any(e.lit for e in pixels), case.label
            assert any(e.level == 0 for e in pixels), case.label


def test_the_step_is_called_once_a_sample_and_five_times_a_stepped_sample():
    for case in [*LEVEL.public, *practice_cases(LEVEL, 6, seed=2)]:
        pixels = _pixels(case)
        levels, differences = reference_outcome(LEVEL, case), reference_outcome(DIFFERENCE, case)
        assert levels.calls == [e.level for e in pixels], case.label
        stepped = [e for e in pixels if not e.direct]
        assert len(differences.calls) == len(QUADRATICS) * len(stepped), case.label
        cos_specular = differences.calls[1 :: len(QUADRATICS)]
        assert [q for q, dq in cos_specular] == [e.cos_specular for e in stepped], case.label
        assert [dq for q, dq in cos_specular] == [e.cos_specular_step for e in stepped]


@pytest.mark.parametrize(
    ("exercise", "pattern"),
    [
        (LEVEL, r"pixel \(\d+, \d+\)( \(a span's first\))?"),
        (DIFFERENCE, r"(cos_theta|cos_specular|ambient_diffuse\[[012]\]) at pixel \(\d+, \d+\)"),
    ],
    ids=["level", "difference"],
)
def test_every_forced_call_is_placed_at_its_sample(exercise, pattern):
    for case in [*exercise.public, *practice_cases(exercise, 4, seed=2)]:
        reference = reference_outcome(exercise, case)
        places = [exercise.place(i, reference.trace) for i in range(len(reference.calls))]
        assert places and all(re.fullmatch(pattern, p) for p in places), (case.label, places[:3])
        assert exercise.place(len(reference.calls), reference.trace).startswith("call ")


def _describe(exercise, name, case):
    variant = known_variant(exercise, name)
    verdict = grade(exercise, variant.source, [case])[0]
    return verdict, verdict.describe()


def test_strict_is_one_level_low_at_vertex_u_where_cos_phi_is_1():
    verdict, text = _describe(LEVEL, "strict", AT_U)
    assert "first difference at event 1 of 28 -- fast_phong_pixel, pixel (0, 0)" in text
    assert "level: yours 118, reference 119" in text
    assert verdict.wrong_calls == ("pixel (0, 0) (a span's first)",)
    assert verdict.result.path == "[0, 0]"
    assert text.endswith(known_variant(LEVEL, "strict").hint)


def test_strict_differs_exactly_where_cos_phi_is_a_table_entry():
    verdict, _ = _describe(LEVEL, "strict", DULL)
    entries = set(case_model(DULL.inputs).table.tolist())
    on_entry = [
        f"pixel ({e.x}, {e.y})" + (" (a span's first)" if e.direct else "")
        for e in _pixels(DULL)
        if e.cos_specular in entries
    ]
    assert list(verdict.wrong_calls) == on_entry and len(on_entry) == 10


def test_one_entry_a_sample_first_goes_wrong_where_the_level_jumps():
    verdict, text = _describe(LEVEL, "one_entry_a_sample", NARROW)
    jumps = {
        f"pixel ({b.x}, {b.y})"
        for a, b in _span_neighbours(_pixels(NARROW))
        if abs(b.level - a.level) > 1
    }
    assert verdict.wrong_calls and set(verdict.wrong_calls) == jumps
    assert "-- fast_phong_pixel, pixel (" in text and "level: yours " in text


def test_walks_up_only_first_goes_wrong_where_the_level_falls():
    verdict, _ = _describe(LEVEL, "walks_up_only", AT_U)
    falls = {
        f"pixel ({b.x}, {b.y})" for a, b in _span_neighbours(_pixels(AT_U)) if b.level < a.level
    }
    assert verdict.wrong_calls and set(verdict.wrong_calls) == falls


def test_difference_first_is_wrong_at_the_first_stepped_sample_of_every_quadratic():
    verdict, text = _describe(DIFFERENCE, "difference_first", AT_U)
    assert "first difference at event 2 of 28 -- fast_phong_pixel, pixel (1, 0)" in text
    assert "cos_theta: yours " in text
    assert verdict.wrong_calls[: len(QUADRATICS)] == tuple(
        f"{name} at pixel (1, 0)" for name in QUADRATICS
    )
    assert len(verdict.wrong_calls) == verdict.calls_total
    assert text.endswith(known_variant(DIFFERENCE, "difference_first").hint)


@pytest.mark.parametrize("name", ["no_second_difference", "t5_once"])
def test_a_wrong_second_difference_keeps_q_right_one_sample_and_dq_wrong_at_once(name):
    # Q(x + 1) = Q + dQ is still right at a span's second sample; dQ there is already wrong.
    verdict, text = _describe(DIFFERENCE, name, AT_U)
    assert "first difference at event 2 of 28 -- fast_phong_pixel, pixel (1, 0)" in text
    assert "cos_theta_step: yours " in text
    assert verdict.first_call.path == "[1]"
    assert text.endswith(known_variant(DIFFERENCE, name).hint)


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_grading_is_deterministic(exercise):
    cases = [*exercise.public, *hidden_cases(exercise, "det", 3)]
    for variant in exercise.variants:
        first = [v.describe() for v in grade(exercise, variant.source, cases)]
        assert first == [v.describe() for v in grade(exercise, variant.source, cases)]


def test_a_wrong_return_type_is_an_error_of_the_run():
    answer = compile_answer(
        "def specular_level(table, cos_phi, start):\n    return None\n", "specular_level"
    )
    outcome = run_case(LEVEL, answer, AT_U)
    assert outcome.error == (
        "TypeError: step 'specular_level' must return an int level; got None, a NoneType"
    )


def test_an_integer_valued_float_level_is_told_it_is_not_an_int():
    # Issue 22: a level of 119.0 scored 0 with numpy's "only integers ... are valid indices",
    # raised in the answer's own walk when it got 119.0 back as start.
    floats = LEVEL.solution.replace("        return low\n", "        return float(low)\n")
    floats = floats.replace("    return level\n", "    return float(level)\n")
    verdict = grade(LEVEL, floats, [AT_U])[0]
    text = verdict.describe()
    assert "must return an int level; got 119.0, a float" in text
    assert "yours 119.0 (a float: an int is asked for), reference 119" in text


@pytest.mark.parametrize("exercise", BOTH, ids=lambda e: e.id)
def test_the_released_notebook_holds_the_stub_and_runs_the_fast_phong_stepper(exercise):
    notebook = nbformat.read(FOLDER / notebook_name(exercise), as_version=4)
    answers = [c for c in notebook.cells if c.source.startswith(ANSWER_MARKER)]
    assert [a.source for a in answers] == [answer_cell_source(exercise, exercise.stub)]
    assert "fast_phong_stepper(CASE['vertices']" in notebook.cells[1].source
    assert "Wang 1989, ch. 3" in notebook.cells[0].source
    # The stepper cell runs headless on the first public case.
    cell = notebook.cells[1].source.removeprefix("%matplotlib widget\n")
    namespace = {}
    exec(cell.replace("fast_phong_stepper(CASE", "stepper = fast_phong_stepper(CASE"), namespace)  # noqa: S102
    assert namespace["CASE"] == dict(AT_U.inputs)
    assert namespace["stepper"].slider.max == len(_pixels(AT_U))  # the start, then each sample


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
        secret="fixed secret of the fast Phong exercises",
        exercises={e.id: ExerciseKey(e.points, 2) for e in BOTH},
    )
    grades = {s.student: s for s in grade_submissions(tmp_path / "class", key, progress=False)}
    solved, blank = grades["solved"], grades["blank"]
    assert [(g.exercise, g.status) for g in solved.grades] == [(e.id, "passed") for e in BOTH]
    assert solved.score == solved.max_score == sum(e.points for e in BOTH)
    assert blank.score == 0 and {g.status for g in blank.grades} == {"error"}

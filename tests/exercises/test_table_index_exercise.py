"""The post-anti-aliasing exercise (23): table_index, the slope and distance indices of the
51 x 51 x 3 tables, plugged into the real traced post_antialias."""

import dataclasses
import re
from pathlib import Path

import nbformat
import numpy as np
import pytest

from scanviz import steps
from scanviz.antialias.post import post_antialias
from scanviz.antialias.tables import column_indices, line_table, table_indices
from scanviz.exercises.antialias import (
    HALF_OFF,
    POST_CATEGORIES,
    POST_KINDS,
    THROUGH_CENTRES,
    post_table,
)
from scanviz.exercises.catalog import get
from scanviz.exercises.core import (
    compile_answer,
    hidden_cases,
    practice_cases,
    reference_outcome,
    run_case,
    score,
)
from scanviz.exercises.release import ANSWER_MARKER, answer_cell_source, notebook_name
from scanviz.trace import Recorder

from .support import grade, known_variant

INDEX = get("table_index")
FOLDER = Path(__file__).parents[2] / "notebooks" / "exercises"
QUARTER, FIG_5_1, STEEP, LEVEL, TRIANGLE = INDEX.public


def _post(inputs, trace=None):
    return post_antialias(
        np.zeros((inputs["height"], inputs["width"])),
        inputs["segments"],
        kind=inputs["kind"],
        flags=inputs["flags"],
        trace=trace,
    )


def _looked_up(case):
    return [e for e in reference_outcome(INDEX, case).trace if e.kind == "post_column"]


def test_the_exercise_has_its_number_and_step():
    assert (INDEX.number, INDEX.step, INDEX.kind, INDEX.rtol, INDEX.points) == (
        23,
        "table_index",
        "step",
        0.0,
        2,
    )
    assert steps.get("table_index") is table_indices
    assert "table_index" in {s.name for s in steps.table()}


def test_the_reference_plugged_in_gives_the_default_trace_and_the_compiled_image():
    for case in [*INDEX.public, *hidden_cases(INDEX, "test", 6)]:
        inputs = dict(case.inputs)
        default = Recorder(POST_KINDS)
        traced = _post(inputs, default)
        plugged = Recorder(POST_KINDS)
        mine = INDEX.call(INDEX.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        compiled = _post(inputs)  # no tracer, no step replaced: the numba kernel
        assert np.array_equal(mine, traced) and np.array_equal(compiled, traced), case.label
        assert not steps.replaced()


def test_a_replaced_step_reaches_the_untraced_entry_point():
    inputs = dict(LEVEL.inputs)
    before = _post(inputs)
    with steps.using(table_index=lambda m, dxy: (0, 25)):  # every column reads m = 0, dxy = 0
        centred = _post(inputs)
    assert not np.array_equal(centred, before)  # the reference loop ran, with the step
    assert _post(inputs).tolist() == before.tolist()


def test_the_step_is_called_once_a_table_column_with_the_slope_and_dxy():
    for case in [*INDEX.public, *practice_cases(INDEX, 8, seed=3)]:
        seen = []

        def spy(m, dxy, seen=seen):
            seen.append((m, dxy))
            return table_indices(m, dxy)

        INDEX.call(spy, dict(case.inputs), None)
        looked_up = _looked_up(case)
        assert [dxy for _, dxy in seen] == [e.dxy for e in looked_up], case.label
        assert all(0 <= m <= 1 and -0.5 < dxy <= 0.5 for m, dxy in seen), case.label
        assert reference_outcome(INDEX, case).calls == [(e.i, e.j) for e in looked_up]


def test_the_public_cases_hold_the_dissertations_worked_indices():
    # Fig 5-1 (spec §3.8): m = 0.6747 -> i = 34; j in its columns 102..107, as column_indices.
    fig = _looked_up(FIG_5_1)
    assert {e.i for e in fig} == {34} and [e.j for e in fig] == [42, 26, 10, 44, 27, 11]
    whole = column_indices((100.8, 150.7), (109.1, 156.3))
    assert whole.j[2:8].tolist() == [e.j for e in fig]
    assert {e.i for e in _looked_up(STEEP)} == {4} and {e.major for e in _looked_up(STEEP)} == {"y"}
    # Slope 1/4: i = 13 from the tie 12.5, and both j ties, 13 (dxy = -1/4) and 38 (1/4).
    quarter = _looked_up(QUARTER)
    assert {e.i for e in quarter} == {13} and {e.j for e in quarter} == {13, 25, 38, 50}
    level = _looked_up(LEVEL)
    assert {(e.segment, e.i, e.j) for e in level} == {(0, 0, 50), (1, 50, 50)}
    triangle = _looked_up(TRIANGLE)
    assert {e.segment for e in triangle} == {0, 1, 2}


def test_the_areas_read_are_the_tables_entries():
    for case in INDEX.public[:4]:
        for e in _looked_up(case):
            assert [e.up, e.mid, e.low] == line_table()[e.i, e.j].tolist(), case.label


def test_solution_scores_full_marks_and_the_stub_none():
    cases = [*INDEX.public, *hidden_cases(INDEX, "test", 10)]
    verdicts = grade(INDEX, INDEX.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(INDEX, verdicts) == INDEX.points
    stub = grade(INDEX, INDEX.stub, INDEX.public, variants=False)
    assert score(INDEX, stub) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stub)


FLOORED = """\
import math


def table_index(m, dxy):
    return math.floor(abs(m) * 50 + 0.5), math.floor((dxy + 0.5) * 50 + 0.5)
"""


def test_floor_of_the_half_shift_is_also_right():
    verdicts = grade(INDEX, FLOORED, [*INDEX.public, *hidden_cases(INDEX, "floor", 6)])
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]


@pytest.mark.parametrize("variant", INDEX.variants, ids=lambda v: v.name)
def test_every_variant_fails_a_public_case_and_is_named_there(variant):
    verdicts = grade(INDEX, variant.source, INDEX.public)
    assert score(INDEX, verdicts) < INDEX.points
    assert {v.variant.name for v in verdicts if v.variant is not None} == {variant.name}


def _describe(name, case):
    variant = known_variant(INDEX, name)
    verdict = grade(INDEX, variant.source, [case])[0]
    return verdict, verdict.describe()


def test_round_half_even_is_wrong_at_the_slope_tie_in_every_column():
    verdict, text = _describe("round_half_even", QUARTER)
    assert "first difference at event 1 of 9 -- post_column, pixel (2, 1)" in text
    assert "i: yours 12, reference 13" in text
    assert len(verdict.wrong_calls) == verdict.calls_total == 9
    assert verdict.wrong_calls[0] == "segment 0, column 2 (middle pixel (2, 1))"
    assert text.endswith(known_variant(INDEX, "round_half_even").hint)


def test_round_half_even_passes_where_no_index_is_a_half():
    assert [v.passed for v in grade(INDEX, known_variant(INDEX, "round_half_even").source,
                                     [FIG_5_1, STEEP, LEVEL])] == [True, True, True]  # fmt: skip


def test_dxy_not_shifted_is_refused_by_the_loop_with_the_indices():
    verdict, text = _describe("dxy_not_shifted", QUARTER)
    assert verdict.error.startswith(
        "ValueError: step 'table_index' must give indices in 0..50; got (13, -12)"
    )
    assert "j: yours 0, reference 25" in text  # dxy = 0 read row 0 (dxy = -1/2)


def test_j_wraps_is_wrong_exactly_where_the_line_is_half_a_pixel_off_the_centres():
    verdict, text = _describe("j_wraps", LEVEL)
    assert "j: yours 0, reference 50" in text
    assert len(verdict.wrong_calls) == verdict.calls_total == len(_looked_up(LEVEL))
    assert verdict.result is not None  # the areas of dxy = -1/2 land on the wrong pixels
    assert text.endswith(known_variant(INDEX, "j_wraps").hint)
    fig = grade(INDEX, known_variant(INDEX, "j_wraps").source, [FIG_5_1])[0]
    assert fig.passed  # no j of 50 there


def test_truncated_differs_where_the_fraction_is_past_a_half():
    verdict, _ = _describe("truncated", FIG_5_1)
    assert verdict.first_call.path == "[0]"  # 33.7 divisions: 33 instead of 34
    assert len(verdict.wrong_calls) == 6


def test_a_steep_segment_names_its_calls_by_row():
    reference = reference_outcome(INDEX, STEEP)
    places = [INDEX.place(i, reference.trace) for i in range(len(reference.calls))]
    assert places and all(
        re.fullmatch(r"segment 0, row \d+ \(middle pixel \(\d+, \d+\)\)", p) for p in places
    )
    assert INDEX.place(len(reference.calls), reference.trace).startswith("call ")


def test_hidden_cases_come_from_the_secret_and_call_the_step():
    first = hidden_cases(INDEX, "secret one", 4)
    assert first == hidden_cases(INDEX, "secret one", 4)
    assert first != hidden_cases(INDEX, "secret two", 4)
    assert all(reference_outcome(INDEX, case).calls for case in first)
    categories = {case.category for case in hidden_cases(INDEX, "s", 25)}
    assert categories == set(POST_CATEGORIES) | set(INDEX.features)  # a feature's case names it


def test_generated_cases_are_what_their_category_names():
    for case in practice_cases(INDEX, 30, seed=6):
        looked_up = _looked_up(case)
        assert looked_up, case.label
        assert (case.inputs["kind"] == "edge") == (case.category == "polygon edges")
        slopes, distances = {e.i for e in looked_up}, {e.j for e in looked_up}
        if case.category in ("ties", "exact halves"):
            assert slopes <= {13, 38}, case.label
        if case.category in THROUGH_CENTRES:  # i = 0 or 50 and j = 25 in every column
            assert (slopes, distances) == ({50 if "45°" in case.category else 0}, {25}), case.label
        if case.category == HALF_OFF:
            assert distances == {50} and slopes <= {0, 50}, case.label
        if case.category == "horizontal or 45 degrees":
            assert slopes <= {0, 50}, case.label
        if case.category == "steep lines":
            assert {e.major for e in looked_up} == {"y"}, case.label


def test_grading_is_deterministic():
    cases = [*INDEX.public, *hidden_cases(INDEX, "det", 3)]
    for variant in INDEX.variants:
        first = [v.describe() for v in grade(INDEX, variant.source, cases)]
        assert first == [v.describe() for v in grade(INDEX, variant.source, cases)]


def test_a_float_index_is_an_error_of_the_run():
    answer = compile_answer("def table_index(m, dxy):\n    return 1.5, 2\n", "table_index")
    outcome = run_case(INDEX, answer, QUARTER)
    assert outcome.error == (
        "TypeError: step 'table_index' must return two ints; got (1.5, 2): 1.5 is a float"
    )


def test_post_table_lists_every_look_up():
    _, trace = _post(dict(TRIANGLE.inputs), True)
    lines = post_table(trace).splitlines()
    assert len(lines) == len(trace) == 28
    assert lines[0].startswith("segment 0  column ") and lines[-1].startswith("segment 2  row ")


def test_the_released_notebook_holds_the_stub_and_prints_the_look_ups():
    notebook = nbformat.read(FOLDER / notebook_name(INDEX), as_version=4)
    answers = [c for c in notebook.cells if c.source.startswith(ANSWER_MARKER)]
    assert [a.source for a in answers] == [answer_cell_source(INDEX, INDEX.stub)]
    assert "Wang 1989, ch. 4" in notebook.cells[0].source
    cell = notebook.cells[1].source.removeprefix("%matplotlib widget\n")
    namespace = {}
    exec(cell, namespace)  # noqa: S102 - the released cell, run headless on the first public case
    assert namespace["CASE"] == dict(QUARTER.inputs)
    assert len(namespace["trace"]) == 9


def test_the_released_notebook_grades_blank_zero_and_solved_full(tmp_path):
    from scanviz.exercises.grading import grade_submissions
    from scanviz.exercises.key import ExerciseKey, new_key

    for student, body in (("blank", "stub"), ("solved", "solution")):
        folder = tmp_path / "class" / student
        folder.mkdir(parents=True)
        notebook = nbformat.read(FOLDER / notebook_name(INDEX), as_version=4)
        for cell in notebook.cells:
            if cell.source.startswith(ANSWER_MARKER):
                cell.source = answer_cell_source(INDEX, getattr(INDEX, body))
        nbformat.write(notebook, folder / notebook_name(INDEX))
    key = dataclasses.replace(
        new_key(),
        secret="fixed secret of the table index exercise",
        exercises={INDEX.id: ExerciseKey(INDEX.points, 2)},
    )
    grades = {s.student: s for s in grade_submissions(tmp_path / "class", key, progress=False)}
    solved, blank = grades["solved"], grades["blank"]
    assert [(g.exercise, g.status) for g in solved.grades] == [(INDEX.id, "passed")]
    assert solved.score == solved.max_score == INDEX.points
    assert blank.score == 0 and {g.status for g in blank.grades} == {"error"}


def test_an_integer_valued_float_is_told_it_is_not_an_int():
    # Issue 22: (13.0, 25.0) scored 0 with numpy's "only integers ... are valid indices".
    floats = (
        "def table_index(m, dxy):\n"
        "    return float(int(abs(m) * 50 + 0.5)), float(int((dxy + 0.5) * 50 + 0.5))\n"
    )
    verdict = grade(INDEX, floats, INDEX.public[:1])[0]
    text = verdict.describe()
    assert "step 'table_index' must return two ints; got (13.0, 25.0): 13.0 is a float" in text
    assert "yours 13.0 (a float: an int is asked for), reference 13" in text

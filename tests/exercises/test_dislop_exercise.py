"""The DISLOP exercise (22): dislop_column, the per-column area formula of DISLOP_L, plugged into
the real traced line (dislop_line)."""

import dataclasses
import math
import re
from fractions import Fraction
from pathlib import Path

import nbformat
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import steps
from scanviz.antialias import dislop_line
from scanviz.antialias.columns import LINE_BRANCHES, band_row
from scanviz.antialias.line import middle_column
from scanviz.exercises.antialias import CATEGORIES, KINDS, THROUGH_CENTRES, middle_columns
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

COLUMN = get("dislop_column")
FOLDER = Path(__file__).parents[2] / "notebooks" / "exercises"
SHALLOW, STEEP, DIAGONAL, HORIZONTAL, FALLING, VERTICAL = COLUMN.public


def _draw(inputs, trace=None):
    return dislop_line(inputs["p0"], inputs["p1"], inputs["width"], inputs["height"], trace=trace)


def _middle(case):
    return middle_columns(reference_outcome(COLUMN, case).trace)


def test_the_exercise_has_its_number_and_step():
    assert (COLUMN.number, COLUMN.step, COLUMN.kind, COLUMN.rtol, COLUMN.points) == (
        22,
        "dislop_column",
        "step",
        1e-9,
        3,
    )
    assert steps.get("dislop_column") is middle_column
    assert "dislop_column" in {s.name for s in steps.table()}


def test_the_reference_plugged_in_gives_the_default_trace_and_the_compiled_image():
    for case in [*COLUMN.public, *hidden_cases(COLUMN, "test", 6)]:
        inputs = dict(case.inputs)
        default = Recorder(KINDS)
        traced = _draw(inputs, default)
        plugged = Recorder(KINDS)
        mine = COLUMN.call(COLUMN.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        compiled = _draw(inputs)  # no tracer, no step replaced: the numba kernel
        assert np.array_equal(mine, traced) and np.array_equal(compiled, traced), case.label
        assert not steps.replaced()


def test_a_replaced_step_reaches_the_untraced_entry_point():
    inputs = dict(HORIZONTAL.inputs)
    before = _draw(inputs)
    assert before[3, 2:8].tolist() == [0.25] * 6 and before[2, 2:8].tolist() == [0.75] * 6
    with steps.using(dislop_column=lambda m, dxy: (0.0, 0.0, 0.0)):
        emptied = _draw(inputs)  # the reference loop ran, with the step
    assert not emptied[:, 2:8].any()  # the middle columns 2..7 are empty
    assert np.array_equal(emptied[:, [0, 1, 8, 9]], before[:, [0, 1, 8, 9]])  # the caps are not
    with steps.using(dislop_column=middle_column):
        assert np.array_equal(_draw(inputs), before)  # the reference loop, same bits
    assert np.array_equal(_draw(inputs), before)


def test_the_step_is_called_once_a_middle_column_with_its_slope_and_dxy():
    for case in [*COLUMN.public, *practice_cases(COLUMN, 8, seed=3)]:
        seen = []

        def spy(m, dxy, seen=seen):
            seen.append((m, dxy))
            return middle_column(m, dxy)

        COLUMN.call(spy, dict(case.inputs), None)
        middle = _middle(case)
        assert seen == [(e.slope, e.dxy) for e in middle], case.label
        assert all(0 <= m <= 1 and -0.5 < dxy <= 0.5 for m, dxy in seen), case.label
        assert reference_outcome(COLUMN, case).calls == [
            tuple(middle_column(m, dxy)) for m, dxy in seen
        ], case.label


def test_the_public_cases_take_every_branch_of_the_formula():
    branches = [{e.branch for e in _middle(case)} for case in COLUMN.public]
    assert branches == [
        {"two", "three_triangle"},
        {"three", "three_triangle"},
        {"three"},
        {"flat"},
        {"two", "three_triangle"},
        {"flat"},
    ]
    assert set().union(*branches) == set(LINE_BRANCHES)


def test_the_public_cases_show_what_their_labels_say():
    slopes = [{e.slope for e in _middle(case)} for case in COLUMN.public]
    assert all(len(s) == 1 for s in slopes)  # one slope a line
    assert [round(min(s), 12) for s in slopes] == [0.3, 0.85, 1.0, 0.0, 1 / 16, 0.0]
    assert {e.major for e in _middle(STEEP)} == {"y"}  # x and y swap
    assert {e.major for e in _middle(SHALLOW)} == {"x"}
    diagonal, horizontal = _middle(DIAGONAL), _middle(HORIZONTAL)
    assert {e.dxy for e in diagonal} == {0.5} and {e.dxy for e in horizontal} == {0.25}
    assert {(e.up, e.mid, e.low) for e in horizontal} == {(0.25, 0.75, 0.0)}
    vertical = _middle(VERTICAL)
    assert {(e.major, e.dxy, e.up, e.mid, e.low) for e in vertical} == {("y", 0.0, 0.0, 1.0, 0.0)}
    # Falling at 1/16 a column: dxy steps by 1/16 through 0, on both sides of it.
    falling = [Fraction(e.dxy) for e in _middle(FALLING)]
    assert falling == [Fraction(k, 16) for k in range(-6, 7)]
    # Near both ends of (-1/2, 1/2] somewhere in the public middle columns.
    dxys = [e.dxy for case in COLUMN.public for e in _middle(case)]
    assert max(dxys) == 0.5 and min(dxys) <= -0.4


def test_past_slope_three_quarters_the_printed_formula_misses_the_fourth_pixel():
    # The reference is the printed formula: at m = 1, dxy = 1/2 the band's fourth pixel holds
    # 0.0214 (an exact oracle, band_row), which the formula credits to the pixel above.
    (diagonal,) = {(e.up, e.mid, e.low, e.spill) for e in _middle(DIAGONAL)}
    up, mid, low, spill = diagonal
    assert spill == 0.0 and math.isclose(up + mid + low, math.sqrt(2), rel_tol=1e-15)
    exact = [band_row(1.0, 0.5, r) for r in (-1, 0, 1, 2)]
    assert math.isclose(exact[3], 0.021447, abs_tol=1e-6)
    assert math.isclose(up, exact[2] + exact[3], rel_tol=1e-12)
    assert math.isclose(mid, exact[1], rel_tol=1e-12) and math.isclose(low, exact[0], rel_tol=1e-12)


@settings(max_examples=80, derandomize=True, deadline=None)
@given(m=st.floats(0.0, 0.75), dxy=st.floats(-0.5, 0.5, exclude_min=True))
def test_the_formula_is_the_exact_band_area_up_to_slope_three_quarters(m, dxy):
    up, mid, low = middle_column(m, dxy)
    exact = [band_row(m, dxy, r) for r in (-2, -1, 0, 1, 2)]
    assert exact[0] == exact[4] == 0.0 or max(exact[0], exact[4]) < 1e-12
    for mine, theirs in zip((low, mid, up), exact[1:4], strict=True):
        assert math.isclose(mine, theirs, abs_tol=1e-12), (m, dxy)


def test_solution_scores_full_marks_and_the_stub_none():
    cases = [*COLUMN.public, *hidden_cases(COLUMN, "test", 10)]
    verdicts = grade(COLUMN, COLUMN.solution, cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]
    assert score(COLUMN, verdicts) == COLUMN.points
    stub = grade(COLUMN, COLUMN.stub, COLUMN.public, variants=False)
    assert score(COLUMN, stub) == 0
    assert all(v.error.startswith("NotImplementedError (in ") for v in stub)


REARRANGED = """\
import math


def dislop_column(m, dxy):
    a = math.atan(m)
    ta = 1 / math.cos(a)  # the printed form of the thickness
    fcv = (m + ta - 1) / 2
    ad = -dxy if dxy < 0 else dxy
    scv = ad + (ta - 1) / 2
    sh = 1 / (2 * m) if m else 0.0
    if m == 0:
        above, below = ad, 0.0
    elif ad > fcv:
        above, below = scv, 0.0
    else:
        below = sh * (fcv - ad) * (fcv - ad)
        above = scv if scv > m / 2 else sh * (ad + fcv) * (ad + fcv)
    if dxy < 0:
        above, below = below, above
    return (above, ta - above - below, below)
"""


def test_another_arrangement_of_the_arithmetic_scores_full_marks():
    cases = [*COLUMN.public, *hidden_cases(COLUMN, "another", 6)]
    verdicts = grade(COLUMN, REARRANGED, cases)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]


EXACT_BAND = """\
import math


def dislop_column(m, dxy):
    # the exact band, not the printed formula: a fourth pixel's area is lost past m = 0.75
    half = 0.5 * math.sqrt(1 + m * m)

    def below(h):  # mean of clamp(h + m x, 0, 1) over the column
        lo, hi = h - m / 2, h + m / 2
        if hi <= 0:
            return 0.0
        if lo >= 1:
            return 1.0
        if m == 0:
            return min(max(h, 0.0), 1.0)
        a, b = max(lo, 0.0), min(hi, 1.0)
        return (0.5 * (b - a) * (b + a) + max(hi - 1, 0.0)) / m

    def row(r):
        return below(dxy + half - r + 0.5) - below(dxy - half - r + 0.5)

    return row(1), row(0), row(-1)
"""


def test_the_exact_band_passes_below_three_quarters_and_fails_above():
    # The exercise text says so: the reference is the printed formula, exact only up to 0.75.
    verdicts = grade(COLUMN, EXACT_BAND, COLUMN.public, variants=False)
    assert [v.passed for v in verdicts] == [True, False, False, True, True, True]
    assert "**The reference is the printed formula**" in COLUMN.idea


@pytest.mark.parametrize("variant", COLUMN.variants, ids=lambda v: v.name)
def test_every_variant_fails_a_public_case_and_is_named_there(variant):
    verdicts = grade(COLUMN, variant.source, COLUMN.public)
    assert score(COLUMN, verdicts) < COLUMN.points
    assert {v.variant.name for v in verdicts if v.variant is not None} == {variant.name}


def _describe(name, case):
    variant = known_variant(COLUMN, name)
    verdict = grade(COLUMN, variant.source, [case])[0]
    return verdict, verdict.describe()


def _places(events):
    return tuple(f"column {e.x} (middle pixel ({e.x}, {e.y}))" for e in events)


def test_no_triangle_is_wrong_exactly_in_the_three_triangle_columns():
    verdict, text = _describe("no_triangle", SHALLOW)
    triangles = [e for e in _middle(SHALLOW) if e.branch == "three_triangle"]
    assert (
        verdict.wrong_calls
        == _places(triangles)
        == (
            "column 4 (middle pixel (4, 2))",
            "column 8 (middle pixel (8, 3))",
        )
    )
    assert "first difference at event 5 of 13 -- dislop_column, pixel (4, 2)" in text
    assert "mid: yours 0.9133716469" in text and "reference 0.9120664102" in text
    assert text.endswith(known_variant(COLUMN, "no_triangle").hint)


def test_low_not_clipped_is_wrong_exactly_in_the_two_pixel_columns():
    verdict, text = _describe("low_not_clipped", SHALLOW)
    two = [e for e in _middle(SHALLOW) if e.branch == "two"]
    assert verdict.wrong_calls == _places(two) and len(two) == 7
    assert "first difference at event 3 of 13 -- dislop_column, pixel (2, 1)" in text
    assert verdict.result.path == "[0, 2]"  # a lower pixel the band misses gets an area
    assert text.endswith(known_variant(COLUMN, "low_not_clipped").hint)


def test_no_reflection_is_wrong_exactly_where_dxy_is_negative():
    verdict, text = _describe("no_reflection", FALLING)
    below = [e for e in _middle(FALLING) if e.dxy < 0]
    assert verdict.wrong_calls == _places(below) and len(below) == 6
    assert "first difference at event 3 of 17 -- dislop_column, pixel (2, 2)" in text
    assert "up: yours 0.37597561" in text and "reference 0.0" in text
    assert text.endswith(known_variant(COLUMN, "no_reflection").hint)


def test_up_low_swapped_shows_in_the_first_middle_column_of_the_horizontal_line():
    verdict, text = _describe("up_low_swapped", HORIZONTAL)
    assert "first difference at event 3 of 10 -- dislop_column, pixel (2, 2)" in text
    assert "up: yours 0.0, reference 0.25" in text
    assert len(verdict.wrong_calls) == verdict.calls_total == 6
    assert verdict.first_call.path == "[0]"


@pytest.mark.parametrize("name", ["fcv_sign", "mid_from_one"])
def test_wrong_critical_value_or_thickness_shows_in_the_middle_pixel_at_45_degrees(name):
    verdict, text = _describe(name, DIAGONAL)
    assert "first difference at event 3 of 12 -- dislop_column, pixel (2, 2)" in text
    assert "mid: yours " in text and "reference 0.68566017" in text
    assert verdict.wrong_calls == _places(_middle(DIAGONAL)) and len(verdict.wrong_calls) == 7
    assert text.endswith(known_variant(COLUMN, name).hint)


def test_no_flat_branch_divides_by_zero_only_through_the_pixel_centres():
    # Without the m == 0 branch a horizontal line off the centres still takes "two" (up = scv =
    # ad), but through them ad = fcv = 0 falls to the triangle formula and its 1 / 2m.
    variant = known_variant(COLUMN, "no_flat_branch")
    verdicts = grade(COLUMN, variant.source, COLUMN.public)
    assert [v.passed for v in verdicts] == [True, True, True, True, True, False]
    assert verdicts[-1].error.startswith("ZeroDivisionError: float division by zero (in ")
    assert verdicts[-1].variant == variant
    for student in ("", "ada"):
        hidden = hidden_cases(COLUMN, "features", 12, student)
        through = [c for c in hidden if c.category in THROUGH_CENTRES[:2]]
        failed = [v for v in grade(COLUMN, variant.source, through) if not v.passed]
        assert len(failed) == 2 and all(v.error.startswith("ZeroDivisionError") for v in failed)


def test_a_steep_line_names_its_calls_by_row():
    reference = reference_outcome(COLUMN, STEEP)
    places = [COLUMN.place(i, reference.trace) for i in range(len(reference.calls))]
    assert places and all(re.fullmatch(r"row \d+ \(middle pixel \(\d+, \d+\)\)", p) for p in places)
    assert [int(p.split()[1]) for p in places] == list(range(3, 12))  # walked bottom-up


def test_every_forced_call_is_placed_at_its_column():
    for case in [*COLUMN.public, *practice_cases(COLUMN, 6, seed=2)]:
        reference = reference_outcome(COLUMN, case)
        places = [COLUMN.place(i, reference.trace) for i in range(len(reference.calls))]
        pattern = r"(column|row) \d+ \(middle pixel \(-?\d+, -?\d+\)\)"
        assert places and all(re.fullmatch(pattern, p) for p in places), (case.label, places[:3])
        assert COLUMN.place(len(reference.calls), reference.trace).startswith("call ")


def test_hidden_cases_come_from_the_secret_and_call_the_step():
    first = hidden_cases(COLUMN, "secret one", 4)
    assert first == hidden_cases(COLUMN, "secret one", 4)
    assert first != hidden_cases(COLUMN, "secret two", 4)
    assert all(reference_outcome(COLUMN, case).calls for case in first)
    categories = {case.category for case in hidden_cases(COLUMN, "s", 25)}
    assert categories == set(CATEGORIES) | set(COLUMN.features)  # a feature's case names it


def test_generated_cases_are_what_their_category_names():
    octants = set()
    for case in practice_cases(COLUMN, 40, seed=6):
        middle = _middle(case)
        assert middle, case.label
        (slope,) = {e.slope for e in middle}
        (p0x, p0y), (p1x, p1y) = case.inputs["p0"], case.inputs["p1"]
        octants.add((abs(p1y - p0y) > abs(p1x - p0x), p1x > p0x, p1y > p0y))
        expected = {
            "shallow": 0.05 <= slope <= 0.5,
            "medium": 0.5 <= slope <= 0.75,
            "past 0.75": 0.75 < slope <= 1.0,
            "45 degrees": slope == 1.0 and len({e.dxy for e in middle}) == 1,
            "horizontal or vertical": slope == 0.0 and {e.branch for e in middle} == {"flat"},
            "flat": slope == 0.0,
            **{branch: branch in {e.branch for e in middle} for branch in ("two", "three")},
            "three_triangle": "three_triangle" in {e.branch for e in middle},
            THROUGH_CENTRES[0]: slope == 0.0 and p0y == p1y,
            THROUGH_CENTRES[1]: slope == 0.0 and p0x == p1x,
            THROUGH_CENTRES[2]: slope == 1.0,
        }
        assert expected[case.category], case.label
        if case.category in THROUGH_CENTRES:  # every column, not only one
            assert {e.dxy for e in middle} == {0.0}, case.label
    assert len(octants) >= 6  # the walk reflects every direction into the first octant


def test_grading_is_deterministic():
    cases = [*COLUMN.public, *hidden_cases(COLUMN, "det", 3)]
    for variant in COLUMN.variants:
        first = [v.describe() for v in grade(COLUMN, variant.source, cases)]
        assert first == [v.describe() for v in grade(COLUMN, variant.source, cases)]


def test_a_wrong_return_shape_is_an_error_of_the_run():
    answer = compile_answer("def dislop_column(m, dxy):\n    return 1.0, 0.0\n", "dislop_column")
    outcome = run_case(COLUMN, answer, SHALLOW)
    assert outcome.error is not None and outcome.error.startswith("ValueError")


def test_the_released_notebook_holds_the_stub_and_runs_the_dislop_stepper():
    notebook = nbformat.read(FOLDER / notebook_name(COLUMN), as_version=4)
    answers = [c for c in notebook.cells if c.source.startswith(ANSWER_MARKER)]
    assert [a.source for a in answers] == [answer_cell_source(COLUMN, COLUMN.stub)]
    assert "dislop_stepper(CASE['p0']" in notebook.cells[1].source
    assert "Wang 1989, ch. 4" in notebook.cells[0].source
    # The stepper cell runs headless on the first public case: one step per column.
    cell = notebook.cells[1].source.removeprefix("%matplotlib widget\n")
    namespace = {}
    exec(cell.replace("dislop_stepper(CASE", "stepper = dislop_stepper(CASE"), namespace)  # noqa: S102
    assert namespace["CASE"] == dict(SHALLOW.inputs)
    view = namespace["stepper"].views[0]
    assert [e.branch for e in view.steps] == [
        e.branch for e in reference_outcome(COLUMN, SHALLOW).trace
    ]


def test_the_released_notebook_grades_blank_zero_and_solved_full(tmp_path):
    from scanviz.exercises.grading import grade_submissions
    from scanviz.exercises.key import ExerciseKey, new_key

    for student, body in (("blank", "stub"), ("solved", "solution")):
        folder = tmp_path / "class" / student
        folder.mkdir(parents=True)
        notebook = nbformat.read(FOLDER / notebook_name(COLUMN), as_version=4)
        for cell in notebook.cells:
            if cell.source.startswith(ANSWER_MARKER):
                cell.source = answer_cell_source(COLUMN, getattr(COLUMN, body))
        nbformat.write(notebook, folder / notebook_name(COLUMN))
    key = dataclasses.replace(
        new_key(),
        secret="fixed secret of the DISLOP exercise",
        exercises={COLUMN.id: ExerciseKey(COLUMN.points, 2)},
    )
    grades = {s.student: s for s in grade_submissions(tmp_path / "class", key, progress=False)}
    solved, blank = grades["solved"], grades["blank"]
    assert [(g.exercise, g.status) for g in solved.grades] == [(COLUMN.id, "passed")]
    assert solved.score == solved.max_score == COLUMN.points
    assert blank.score == 0 and {g.status for g in blank.grades} == {"error"}

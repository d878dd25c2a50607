"""The notebook check: the answer cell run as grading runs it, plain words about hidden cases."""

import importlib

import pytest

from scanviz.exercises import check, get
from scanviz.exercises.check import answer_cell
from scanviz.widgets.exercise import TraceComparison

EXERCISE = get("span_rule")
MARKER = "# scanviz: answer span_rule\n"


def test_correct_answer_says_hidden_cases_come_later_never_all_passed():
    text = str(check("span_rule", source=MARKER + EXERCISE.solution))
    assert text.startswith("span_rule -- public cases 5 of 5 -- hidden cases are graded later")
    assert "all tests passed" not in text.lower()


def test_wrong_answer_shows_the_diagnostics_and_a_rerun_line():
    closed = next(v for v in EXERCISE.variants if v.name == "closed_span")
    report = check("span_rule", source=closed.source)
    text = str(report)
    assert report.passed < len(EXERCISE.public)
    assert f"public cases {report.passed} of {len(EXERCISE.public)}" in text
    assert "likely cause: " + closed.hint in text
    assert 'rerun just this case: check("span_rule", case=' in text


def test_an_import_made_in_another_cell_fails_here_as_in_grading():
    # The answer cell runs alone: `math` imported elsewhere in the notebook is not there.
    body = EXERCISE.solution.replace("import math\n", "")
    text = str(check("span_rule", source=MARKER + body))
    assert f"public cases 0 of {len(EXERCISE.public)}" in text
    assert "NameError: name 'math' is not defined (in span_rule, line" in text


def test_a_top_level_error_is_shown_with_its_line():
    report = check("span_rule", source=MARKER + "import math\nmath.nope\n" + EXERCISE.solution)
    assert report.status == "error"
    assert (
        "the answer cell raised AttributeError: module 'math' has no attribute 'nope' (line 3)"
        in (report.problem)
    )


def test_practice_cases_are_counted_separately():
    report = check("span_rule", practice=3, seed=7, source=EXERCISE.solution)
    assert "practice cases 3 of 3" in report.headline()


def test_missing_answer_is_said_plainly():
    text = str(check("span_rule"))  # no IPython here: no cell has run
    assert "no answer cell has run yet: run the cell whose first line is" in text


def test_the_answer_cell_is_the_last_one_run_with_the_marker():
    history = ["", MARKER + "old", "x = 1", MARKER + "new", "check('span_rule')"]
    assert answer_cell("span_rule", history) == MARKER + "new"
    assert answer_cell("aet_update", history) is None


def test_an_endless_loop_is_stopped(monkeypatch):
    monkeypatch.setattr(importlib.import_module("scanviz.exercises.check"), "CASE_SECONDS", 0.5)
    source = "def span_rule(crossings, rule):\n    while True:\n        pass\n"
    report = check("span_rule", case="triangle", source=source)
    assert report.status == "timeout"
    assert "the answer ran out of time (0.5 s) and was stopped" in str(report)


def test_unknown_case_and_bad_practice_are_errors():
    with pytest.raises(ValueError, match="'case' must be one of the public cases"):
        check("span_rule", case="nope", source=EXERCISE.solution)
    with pytest.raises(ValueError, match="'practice' must be an int in 0..1000"):
        check("span_rule", practice=-1)


def test_comparison_widget_opens_at_the_first_difference_and_steps_through_them():
    floor = next(v for v in EXERCISE.variants if v.name == "floor_for_ceil")
    report = check("span_rule", case="triangle", source=floor.source)
    case = report.cases[0]
    view = TraceComparison(case.yours, case.reference, case.verdict)
    assert view.slider.value == 3  # event 4: the span of row 1
    assert "row 1" in view.yours_pane.value and "#c62828" in view.yours_pane.value
    view.next_difference_button.click()
    assert view.slider.value == 5  # the span of row 2
    view.first_button.click()
    assert view.slider.value == 3

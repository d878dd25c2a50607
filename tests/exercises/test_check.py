"""The notebook check: public cases, plain words about hidden ones, the comparison widget."""

import importlib

import pytest

from scanviz.exercises import check, get
from scanviz.exercises.core import compile_answer
from scanviz.widgets.exercise import TraceComparison

EXERCISE = get("span_rule")


def _namespace(source):
    return {EXERCISE.answer: compile_answer(source, EXERCISE.answer)}


def test_correct_answer_says_hidden_cases_come_later_never_all_passed():
    report = check("span_rule", namespace=_namespace(EXERCISE.solution))
    text = str(report)
    assert text.startswith("span_rule -- public cases 4 of 4 -- hidden cases are graded later")
    assert "all tests passed" not in text.lower()


def test_wrong_answer_shows_the_diagnostics_and_a_rerun_line():
    closed = next(v for v in EXERCISE.variants if v.name == "closed_span")
    text = str(check("span_rule", namespace=_namespace(closed.source)))
    assert "public cases 0 of 4" in text or "public cases 1 of 4" in text
    assert "likely cause: " + closed.hint in text
    assert 'rerun just this case: check("span_rule", case=' in text


def test_practice_cases_are_counted_separately():
    report = check("span_rule", practice=3, seed=7, namespace=_namespace(EXERCISE.solution))
    assert "practice cases 3 of 3" in report.headline()


def test_missing_answer_is_said_plainly():
    text = str(check("span_rule", namespace={}))
    assert "no function 'span_rule' yet: run the answer cell first" in text


def test_an_endless_loop_is_stopped(monkeypatch):
    module = importlib.import_module("scanviz.exercises.check")
    monkeypatch.setattr(module, "CASE_SECONDS", 0.2)
    source = "def span_rule(crossings, rule):\n    while True:\n        pass\n"
    report = check("span_rule", case="triangle", namespace=_namespace(source))
    assert "CaseTimeout: stopped after 0.2 s" in str(report)


def test_unknown_case_and_bad_practice_are_errors():
    with pytest.raises(ValueError, match="'case' must be one of the public cases"):
        check("span_rule", case="nope", namespace=_namespace(EXERCISE.solution))
    with pytest.raises(ValueError, match="'practice' must be an int in 0..1000"):
        check("span_rule", practice=-1, namespace={})


def test_comparison_widget_opens_at_the_first_difference_and_steps_through_them():
    floor = next(v for v in EXERCISE.variants if v.name == "floor_for_ceil")
    report = check("span_rule", case="triangle", namespace=_namespace(floor.source))
    case = report.cases[0]
    view = TraceComparison(case.yours, case.reference, case.verdict)
    assert view.slider.value == 3  # event 4: the span of row 1
    assert "row 1" in view.yours_pane.value and "#c62828" in view.yours_pane.value
    view.next_difference_button.click()
    assert view.slider.value == 5  # the span of row 2
    view.first_button.click()
    assert view.slider.value == 3

"""The span_rule exercise, and the core's free and forced runs, verdicts and hidden cases on it."""

from scanviz.exercises import get

from .support import grade

EXERCISE = get("span_rule")


def test_floor_for_ceil_diagnostic_on_the_triangle():
    # Triangle (0,0), (6,0), (6,5): row 1 crosses the hypotenuse at x = 6/5, so ceil
    # starts the span at 2 and floor at 1; rows 1..4 all start one sample early.
    floor = next(v for v in EXERCISE.variants if v.name == "floor_for_ceil")
    verdict = grade(EXERCISE, floor.source, EXERCISE.public[:1])[0]
    text = verdict.describe()
    assert "first difference at event 4 of 10 -- span, row 1" in text
    assert "x_start: yours 1, reference 2" in text
    assert "yours differs at 4 of 5: row 1, row 2, row 3, row 4" in text  # rows 0-4 have an AET
    assert "samples: 16 matched (#), 4 extra (!), 0 missing (?)" in text
    assert text.endswith(floor.hint)


def test_forced_run_lists_every_wrong_call_not_only_the_first():
    wrong = "def span_rule(crossings, rule):\n    return []\n"
    verdict = grade(EXERCISE, wrong, EXERCISE.public[:1])[0]
    assert verdict.wrong_calls == ("row 0", "row 1", "row 2", "row 3", "row 4")

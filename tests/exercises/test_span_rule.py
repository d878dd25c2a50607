"""The span_rule exercise, and the core's free and forced runs, verdicts and hidden cases on it."""

import random

import pytest

from scanviz.exercises import get
from scanviz.exercises.core import reference_outcome

from .support import grade, known_variant

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


def test_the_statement_says_empty_runs_are_left_out():
    assert "(`ceil(x_in) == ceil(x_out)`) is not a span: leave it out" in EXERCISE.idea
    assert "a run holding no sample\n    (x_start == x_end) is left out" in EXERCISE.stub


def test_ceil_by_int_diagnostic_left_of_column_0():
    # The clockwise triangle (4, 8.5), (9.75, 2.5), (-2.5, 1.25) crosses column 0 on rows 2-4:
    # its edge 2 crosses them at x = -2.5 + 6.5 (y - 1.25) / 7.25 = -53/29, -27/29, -1/29, so
    # the runs start at ceil = -1, 0, 0 and int(x) + 1 = 0, 1, 1. Row 2's span is clipped to
    # column 0 either way; rows 3 and 4 lose their sample in column 0.
    variant = known_variant(EXERCISE, "ceil_by_int")
    case = next(c for c in EXERCISE.public if c.label.startswith("clockwise, crossing the left"))
    text = grade(EXERCISE, variant.source, [case])[0].describe()
    assert (
        "first difference at event 4 of 10 -- span, row 3\n    x_start: yours 1, reference 0"
        in text
    )
    assert (
        "yours differs at 3 of 5: row 2, row 3, row 4\n    first: [0][0]: yours 0, reference -1"
        in text
    )
    assert "samples: 31 matched (#), 0 extra (!), 2 missing (?)" in text
    assert text.endswith(variant.hint)


@pytest.mark.parametrize("feature", EXERCISE.features)
def test_every_features_case_is_built_to_have_it(feature):
    # The polygon, its place and the rule are chosen for the feature: (nearly) every draw has
    # it, so no hidden case waits on luck.
    rng = random.Random(11)
    cases = [EXERCISE.generate(rng, feature) for _ in range(20)]
    have = [feature in EXERCISE.exercised(c, reference_outcome(EXERCISE, c)) for c in cases]
    assert sum(have) >= 18

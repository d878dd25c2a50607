"""The midpoint exercises: midpoint_decision (the step) and midpoint_loop (the whole loop)."""

import random

import pytest

from scanviz import midpoint_line, steps
from scanviz.exercises import get
from scanviz.exercises.core import hidden_cases, reference_outcome
from scanviz.trace import Recorder

from .support import grade, known_variant

DECISION = get("midpoint_decision")
LOOP = get("midpoint_loop")
EXERCISES = [DECISION, LOOP]
VARIANTS = [(e, v) for e in EXERCISES for v in e.variants]


def test_hidden_cases_cover_every_octant_and_ties():
    categories = {c.category for c in hidden_cases(DECISION, "test", 60)}
    assert {f"octant {k}" for k in range(8)} <= {c.split(",")[0] for c in categories}
    assert any(c.endswith(", ties") for c in categories)


def test_the_reference_step_plugged_in_gives_the_default_trace():
    for case in [*DECISION.public, *hidden_cases(DECISION, "test", 10)]:
        plugged, default = Recorder(DECISION.kinds), Recorder(DECISION.kinds)
        with steps.using(midpoint_step=DECISION.reference):
            DECISION.call(DECISION.reference, dict(case.inputs), plugged)
        i = case.inputs
        midpoint_line(i["x0"], i["y0"], i["x1"], i["y1"], trace=default)
        assert plugged.trace() == default.trace()
        assert len(plugged.trace()) > 1


def test_the_loop_reference_is_scanvizs_midpoint_line():
    for case in LOOP.public:
        i = case.inputs
        mine, default = Recorder(LOOP.kinds), Recorder(LOOP.kinds)
        pixels = LOOP.reference(i["x0"], i["y0"], i["x1"], i["y1"], mine)
        xs, ys = midpoint_line(i["x0"], i["y0"], i["x1"], i["y1"], trace=default)
        assert pixels == list(zip(xs.tolist(), ys.tolist(), strict=True))
        assert mine.trace() == default.trace()


def test_tie_diagonal_diagnostic_on_the_line_through_midpoints():
    # (1, 1) to (9, 5): dx = 8, dy = 4, so d starts at 8 - 2 * 4 = 0 and alternates
    # 0, -8, 0, -8, ...: ties at the pixels (1, 1), (3, 2), (5, 3), (7, 4), where the
    # reference steps east (axial) and d <= 0 steps north-east.
    variant = known_variant(DECISION, "tie_diagonal")
    case = next(c for c in DECISION.public if c.label == "through a midpoint (tie)")
    text = grade(DECISION, variant.source, [case])[0].describe()
    assert "first difference at event 2 of 10 -- line_step, pixel (1, 1)" in text
    assert "choice: yours 'diagonal', reference 'axial'" in text
    assert "yours differs at 4 of 8: pixel (1, 1), pixel (3, 2), pixel (5, 3), pixel (7, 4)" in text
    assert "first: [0]: yours True, reference False" in text
    assert text.endswith(variant.hint)


def test_forgot_last_pixel_diagnostic_on_the_shallow_line():
    # (0, 0) to (11, 4): d starts at 11 - 8 = 3 and runs 3, -5, 9, 1, -7, 7, -1, 13, 5,
    # -3, 11, 3 (axial -8, diagonal +14): the last pixel (11, 4) has d = 3. Twelve pixels,
    # so the reference has 1 + 12 events and the variant stops one short.
    variant = known_variant(LOOP, "forgot_last_pixel")
    text = grade(LOOP, variant.source, LOOP.public[:1])[0].describe()
    assert "first difference at event 13 of 13 -- line_step, pixel (11, 4)" in text
    assert "missing in yours; reference has line_step(x=11, y=4, d=3, choice='last')" in text
    assert "samples: 11 matched (#), 0 extra (!), 1 missing (?)" in text


def test_not_doubled_keeps_the_pixels_and_shows_the_halved_d():
    # d = dx/2 - dy rounded down decides exactly as d = dx - 2 dy; only d itself differs:
    # on (0, 0) to (11, 4), 11 // 2 - 4 = 1 against 3.
    variant = known_variant(LOOP, "not_doubled")
    verdict = grade(LOOP, variant.source, LOOP.public[:1])[0]
    assert verdict.raster is None and verdict.result is None
    assert "d_start: yours 1, reference 3" in verdict.describe()


@pytest.mark.parametrize(
    ("exercise", "feature"),
    [(e, f) for e in EXERCISES for f in e.features],
    ids=[f"{e.id}-{f}" for e in EXERCISES for f in e.features],
)
def test_every_features_line_is_built_to_have_it(exercise, feature):
    # Extents, axis and signs are chosen for the feature, so every draw has it: none is luck.
    rng = random.Random(11)
    for _ in range(20):
        case = exercise.generate(rng, feature)
        assert feature in exercise.exercised(case, reference_outcome(exercise, case)), case.inputs


def test_octant_at_45_diagnostic_on_the_diagonal_line():
    # (1, 8) to (8, 1) points at 315 degrees, the first angle of octant 7 = [315, 360); taking
    # dy > dx for the upper half of a quadrant puts it in octant 6. The pixels are the same
    # (every step is diagonal, d = -7 throughout): only the setup differs, 1 + 8 events in all.
    variant = known_variant(LOOP, "octant_at_45")
    case = next(c for c in LOOP.public if c.label.startswith("45 degrees"))
    verdict = grade(LOOP, variant.source, [case])[0]
    text = verdict.describe()
    assert (
        "first difference at event 1 of 9 -- line_setup\n    octant: yours 6, reference 7" in text
    )
    assert verdict.raster is None
    assert text.endswith(variant.hint)

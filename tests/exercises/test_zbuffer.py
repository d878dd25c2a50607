"""The z-buffer depth-test exercise (10): depth_test plugged into the real render."""

import numpy as np

from scanviz import steps
from scanviz.exercises import get
from scanviz.exercises.core import (
    hidden_cases,
)
from scanviz.exercises.zbuffer import case_scene
from scanviz.pipeline import render
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder

from .support import grade

EXERCISE = get("zbuffer_depth")


def test_the_exercise_has_its_number_and_step():
    assert (EXERCISE.number, EXERCISE.step, EXERCISE.rtol) == (10, "depth_test", 0.0)


def test_the_reference_plugged_in_gives_the_default_trace():
    for case in [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 5)]:
        inputs = dict(case.inputs)
        default = Recorder(EXERCISE.kinds)
        render(case_scene(inputs), inputs["width"], inputs["height"], shading="flat", trace=default)
        plugged = Recorder(EXERCISE.kinds)
        EXERCISE.call(EXERCISE.reference, inputs, plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        assert not steps.replaced()


def test_the_case_scene_is_the_builtin_slide_scene():
    # The first public case is the UMBC slide: its scene renders exactly as the builtin one.
    inputs = dict(EXERCISE.public[0].inputs)
    mine = render(case_scene(inputs), inputs["width"], inputs["height"], shading="flat")
    slide = render(builtin_scene("umbc_zbuffer"), 12, 12, shading="flat")
    assert np.array_equal(mine.polygon, slide.polygon[:10]) and (mine.polygon >= 0).any()
    assert np.array_equal(mine.depth, slide.depth[:10])


def test_ties_to_later_diagnostic_on_the_two_squares():
    # Polygon 0 covers samples x, y in 1..4 (16 tests, all on empty samples); polygon 1 starts
    # at (3, 3), already held by polygon 0 at the same depth 8/16: a tie, which the earlier
    # polygon keeps. <= takes it, and the 3 other shared samples (4, 3), (3, 4), (4, 4).
    variant = next(v for v in EXERCISE.variants if v.name == "ties_to_later")
    text = grade(EXERCISE, variant.source, EXERCISE.public[1:2])[0].describe()
    assert "first difference at event 17 of 48 -- depth_test, polygon 1, pixel (3, 3)" in text
    assert "passed: yours True, reference False" in text
    assert (
        "yours differs at 4 of 48: polygon 1 at pixel (3, 3), polygon 1 at pixel (4, 3), "
        "polygon 1 at pixel (3, 4), polygon 1 at pixel (4, 4)"
    ) in text
    assert "result: [3][3]: yours 1, reference 0" in text
    assert text.endswith(variant.hint)

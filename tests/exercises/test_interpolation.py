"""The span_interpolation exercise (the step span_step of scanviz.raster.interpolate)."""

from scanviz.exercises import get
from scanviz.exercises.core import (
    Case,
    compile_answer,
    hidden_cases,
)
from scanviz.trace import Recorder
from scanviz.visibility.zbuffer import ScreenPolygons, zbuffer

from .support import grade, known_variant

EXERCISE = get("span_interpolation")


def test_the_reference_step_plugged_in_gives_the_default_trace():
    for case in [*EXERCISE.public, *hidden_cases(EXERCISE, "test", 6)]:
        plugged, default = Recorder(EXERCISE.kinds), Recorder(EXERCISE.kinds)
        EXERCISE.call(EXERCISE.reference, dict(case.inputs), plugged)
        i = case.inputs
        scene = ScreenPolygons.from_polygons(i["polygons"], i["colors"], i["inv_w"])
        zbuffer(scene, i["width"], i["height"], perspective=i["inv_w"] is not None, trace=default)
        assert plugged.trace() == default.trace()
        assert any(e.kind == "depth_test" for e in default.trace())


def test_a_replaced_step_runs_untraced_too():
    # zbuffer without a tracer runs the compiled kernel, unless a step is replaced.
    flat = compile_answer(known_variant(EXERCISE, "values_not_stepped").source, EXERCISE.answer)
    case = EXERCISE.public[0]
    reference = EXERCISE.call(EXERCISE.reference, dict(case.inputs), None)
    mine = EXERCISE.call(flat, dict(case.inputs), None)
    assert reference.stats.path == "reference"
    assert (mine.values != reference.values).any()


SQUARE = Case(
    "a red ramp on a square",
    {
        "polygons": [[[0, 0, 0.0], [4, 0, 2.0], [4, 4, 2.0], [0, 4, 0.0]]],
        "colors": [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]],
        "inv_w": None,
        "width": 5,
        "height": 5,
    },
)


def test_values_by_depth_slope_diagnostic_on_a_ramp():
    # z = x / 2 and red = x / 4 on the square [0, 4]^2: every span covers x = 0..3 and
    # steps dz/dx = 0.5, d(red)/dx = 0.25 (all exact in binary). Stepping the values by
    # dz/dx gives red = 0.5 at x = 1 instead of 0.25. The depth is right, so the trace
    # agrees; all 4 rows x 3 steps are wrong.
    variant = known_variant(EXERCISE, "values_by_depth_slope")
    text = grade(EXERCISE, variant.source, [SQUARE])[0].describe()
    assert "first difference at event" not in text
    assert (
        "yours differs at 12 of 12: pixel (1, 0), pixel (2, 0), pixel (3, 0), pixel (1, 1)" in text
    )
    assert "first: [2][0]: yours 0.5, reference 0.25" in text
    assert "result: [0, 1, 0]: yours 0.5, reference 0.25" in text
    assert text.endswith(variant.hint)

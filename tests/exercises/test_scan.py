"""The scan-conversion exercises: edge_table_entry and aet_update (steps), scan_loop (the loop)."""

import random

import numpy as np
import pytest

from scanviz import scan_convert, steps
from scanviz.exercises import get
from scanviz.exercises.core import compile_answer, hidden_cases, reference_outcome, run_case
from scanviz.trace import Recorder

from .support import grade, known_variant

ENTRY = get("edge_table_entry")
AET = get("aet_update")
LOOP = get("scan_loop")
EXERCISES = [ENTRY, AET, LOOP]
VARIANTS = [(e, v) for e in EXERCISES for v in e.variants]
STEPS = [ENTRY, AET]


def _public(exercise, label):
    return next(c for c in exercise.public if c.label == label)


def _default_trace(inputs):
    recorder = Recorder()
    scan_convert(
        inputs["polygon"], inputs["width"], inputs["height"], rule=inputs["rule"], trace=recorder
    )
    return recorder.trace()


@pytest.mark.parametrize("exercise", STEPS, ids=lambda e: e.id)
def test_the_reference_step_plugged_in_gives_the_default_trace(exercise):
    rows = []
    for case in [*exercise.public, *hidden_cases(exercise, "test", 10)]:
        plugged = Recorder()
        with steps.using(**{exercise.step: exercise.reference}):
            exercise.call(exercise.reference, dict(case.inputs), plugged)
        assert plugged.trace() == _default_trace(case.inputs)
        rows.append(len(plugged.trace().of_kind("aet_sorted")))
    assert min(rows[: len(exercise.public)]) >= 5 and sum(rows) > 50


def test_the_loop_reference_is_scanvizs_scan_conversion():
    for case in [*LOOP.public, *hidden_cases(LOOP, "test", 5)]:
        recorder = Recorder(LOOP.kinds)
        mask = LOOP.call(LOOP.reference, dict(case.inputs), recorder)
        default = _default_trace(case.inputs).of_kind(*LOOP.kinds)
        assert recorder.trace() == default
        i = case.inputs
        expected = scan_convert(i["polygon"], i["width"], i["height"], rule=i["rule"]).mask
        assert (mask == expected).all()


def test_floor_bucket_diagnostic_on_the_triangle_off_the_sample_rows():
    # (1, 1/2) -> (7, 9/4) -> (7/2, 27/4): every ymin (1/2, 9/4, 1/2) lies between two sample
    # rows, so floor and ceil differ for all 3 edges; edge 0's bucket is floor(1/2) = 0
    # against ceil(1/2) = 1, the first field of the edge table that differs.
    variant = known_variant(ENTRY, "floor_bucket")
    text = grade(ENTRY, variant.source, [_public(ENTRY, "triangle off the sample rows")])[
        0
    ].describe()
    assert "first difference at event 1 of " in text
    assert " -- edge_table_built\n    edges[0].bucket: yours 0, reference 1\n" in text
    assert (
        "yours differs at 3 of 3: edge 0 (1, 0.5)-(7, 2.25), edge 1 (7, 2.25)-(3.5, 6.75)" in text
    )
    assert text.endswith(variant.hint)


def test_float_accumulation_diagnostic_on_the_slide_polygon():
    # Edge 0 runs from (4, 1) up to (1, 11): dx/dy = -3/10. Row 1 (activation of edges 0 and 3,
    # the AET, one span) matches; on row 2 the float 4 + float(-3/10) rounds to float(37/10),
    # so x agrees and the first difference is x_exact, None for a float. Rows 2-10 step an
    # edge of non-dyadic slope (edge 0, and edge 1 with -4/3 from row 6): 9 of the 11 calls
    # (rows 1-11) differ; row 1 only adds edges and row 11 only retires them.
    variant = known_variant(AET, "float_accumulation")
    text = grade(AET, variant.source, [_public(AET, "the slide polygon (UMBC)")])[0].describe()
    assert "first difference at event 4 of 27 -- aet_sorted, row 2\n" in text
    assert "entries[0].x_exact: yours None, reference 37/10 (3 7/10 = 3.7)" in text
    assert "events 1-3 matched" in text
    assert "yours differs at 9 of 11: row 2, row 3, row 4, row 5, row 6, row 7, row 8" in text


def test_closed_spans_diagnostic_on_the_slide_polygon():
    # Row 1 has edges 0 (x = 4) and 3 (the vertical x = 12): the span is [4, 12), a closed one
    # ends at floor(12) + 1 = 13. The trace has 27 events: row 1 three (activated, AET, span),
    # rows 2-4 two each, row 5 four (activated, AET, two spans), rows 6-7 three each, row 8
    # three (retired, AET, span), rows 9-10 two each, row 11 one (retired).
    variant = known_variant(LOOP, "closed_spans")
    text = grade(LOOP, variant.source, [_public(LOOP, "the slide polygon (UMBC)")])[0].describe()
    assert (
        "first difference at event 3 of 27 -- span, row 1\n    x_end: yours 13, reference 12"
        in text
    )
    assert "samples: 59 matched (#), 8 extra (!), 0 missing (?)" in text
    assert text.endswith(variant.hint)


def test_activate_late_shows_the_missing_activation_first():
    # The late variant takes no edge on its bucket row: the first event, row 1's activation
    # of edges 0 and 3, is missing; both come in one row late, on row 2.
    variant = known_variant(AET, "activate_late")
    verdict = grade(AET, variant.source, [_public(AET, "the slide polygon (UMBC)")])[0]
    text = verdict.describe()
    assert "first difference at event 1 of 27 -- edges_activated, row 1" in text
    assert "missing in yours; reference has edges_activated(polygon=0, y=1, edges=[0, 3])" in text
    run = run_case(AET, compile_answer(variant.source, "aet_update"), AET.public[0])
    activated = [(e.y, list(e.edges)) for e in run.trace if e.kind == "edges_activated"]
    assert activated == [(2, [0, 3]), (6, [1, 2])]


@pytest.mark.parametrize(
    ("exercise", "feature"),
    [(e, f) for e in EXERCISES for f in e.features],
    ids=[f"{e.id}-{f}" for e in EXERCISES for f in e.features],
)
def test_every_features_case_is_built_to_have_it(exercise, feature):
    # The polygon and its place are chosen for the feature: (nearly) every draw has it, so no
    # hidden case waits on luck.
    rng = random.Random(11)
    cases = [exercise.generate(rng, feature) for _ in range(20)]
    have = [feature in exercise.exercised(c, reference_outcome(exercise, c)) for c in cases]
    assert sum(have) >= 18


BELOW_LABEL = "clockwise, crossing the bottom of the raster"


def test_ceil_by_int_diagnostic_below_row_0():
    # (0.5, -1.5), (2, 5.75), (6.5, 3), (5, -0.25): int(y) + 1 is ceil(y) for y > 0 only, so
    # the entries differ for the three edges with an end below row 0: edge 0 (bucket
    # ceil(-1.5) = -1, not 0), edge 2 (bucket ceil(-0.25) = 0, not 1) and edge 3 (both).
    variant = known_variant(ENTRY, "ceil_by_int")
    text = grade(ENTRY, variant.source, [_public(ENTRY, BELOW_LABEL)])[0].describe()
    assert "first difference at event 1 of 17 -- edge_table_built\n" in text
    assert "edges[0].bucket: yours 0, reference -1" in text
    assert "yours differs at 3 of 4: edge 0 (0.5, -1.5)-(2, 5.75), edge 2 " in text
    assert text.endswith(variant.hint)


def test_bucket_is_row_diagnostic_below_row_0():
    # Row 0 takes in edge 0 (bucket -1: it starts below the raster) and edge 2 (bucket 0);
    # taking only bucket == y, edge 0 never enters and no row has a span. Only row 0's call
    # differs: no other row has an edge from below the raster.
    variant = known_variant(AET, "bucket_is_row")
    case = _public(AET, BELOW_LABEL)
    text = grade(AET, variant.source, [case])[0].describe()
    assert "first difference at event 1 of 16 -- edges_activated, row 0\n" in text
    assert "edges[0]: yours 2, reference 0" in text
    assert "yours differs at 1 of 7: row 0\n" in text
    i = case.inputs
    inside = sum(
        _winding(i["polygon"], x, y) != 0 for x in range(i["width"]) for y in range(i["height"])
    )
    assert f"samples: 0 matched (#), 0 extra (!), {inside} missing (?)" in text


def test_rows_above_the_raster_diagnostic():
    # Edges 1 and 2 of (-2.5, 1.25), (9.75, 2.5), (4, 8.5) reach y = 8.5, above the 7 rows:
    # the reference's 13 events end on row 6 (rows 2-6; row 3 retires edge 0 and activates
    # edge 1); scanning on adds rows 7 and 8 and retires both edges on row 9.
    variant = known_variant(LOOP, "rows_above_the_raster")
    case = _public(LOOP, "crossing the left, right and top sides of the raster")
    text = grade(LOOP, variant.source, [case])[0].describe()
    assert "first difference at event 14 of 13 -- aet_sorted, row 7\n    extra in yours" in text
    assert "it also differs at: row 8, row 9 (2 places)" in text


def _winding(polygon, x, y):
    """The winding number at the sample (x, y): +1 for each downward edge crossing the row at or
    left of x, -1 for each upward one (an edge crosses the rows ymin <= y < ymax)."""
    winding = 0
    for (x0, y0), (x1, y1) in zip(polygon, polygon[1:] + polygon[:1], strict=True):
        if min(y0, y1) <= y < max(y0, y1) and x0 + (x1 - x0) * (y - y0) / (y1 - y0) <= x:
            winding += 1 if y1 < y0 else -1
    return winding


def test_winding_up_to_two_loses_exactly_the_samples_of_winding_3():
    variant = known_variant(LOOP, "winding_up_to_two")
    case = _public(LOOP, "{7/3} star: winding 3 at the centre")
    i = case.inputs
    verdict = grade(LOOP, variant.source, [case])[0]
    mine = LOOP.call(compile_answer(variant.source, LOOP.answer), dict(i), Recorder(LOOP.kinds))
    windings = np.array(
        [[_winding(i["polygon"], x, y) for x in range(i["width"])] for y in range(i["height"])]
    )
    assert (windings == 3).sum() == 5
    assert (mine == np.isin(windings, (1, 2))).all()
    assert verdict.describe().endswith(variant.hint)

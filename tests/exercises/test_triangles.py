"""The edge-function exercises: ownership_ties (owns_boundary) and edge_functions (edge_function)."""

import random

import pytest

from scanviz import triangle_samples
from scanviz.exercises import get
from scanviz.exercises.core import hidden_cases, reference_outcome
from scanviz.exercises.triangles import SIZE
from scanviz.trace import Recorder

from .support import grade, known_variant

OWNERSHIP = get("ownership_ties")
EDGES = get("edge_functions")
EXERCISES = [OWNERSHIP, EDGES]
VARIANTS = [(e, v) for e in EXERCISES for v in e.variants]


@pytest.mark.parametrize("exercise", EXERCISES, ids=lambda e: e.id)
def test_the_reference_step_plugged_in_gives_the_default_trace(exercise):
    for case in [*exercise.public, *hidden_cases(exercise, "test", 8)]:
        plugged, default = Recorder(exercise.kinds), Recorder(exercise.kinds)
        counts, _ = exercise.call(exercise.reference, dict(case.inputs), plugged)
        for index, triangle in enumerate(case.inputs["triangles"]):
            triangle_samples(
                triangle,
                case.inputs["width"],
                case.inputs["height"],
                sample=case.inputs["sample"],
                subpixel_bits=2,
                trace=default,
                polygon=index,
            )
        assert plugged.trace() == default.trace()
        assert counts.any()


def test_shared_edges_are_covered_once_in_every_hidden_case():
    for case in hidden_cases(OWNERSHIP, "test", 20):
        if case.category.startswith("shared edge"):
            counts, _ = OWNERSHIP.call(OWNERSHIP.reference, dict(case.inputs), None)
            assert counts.max() == 1


def test_closed_diagnostic_on_the_split_square():
    # Triangle 0 = (1,1), (7,1), (7,7) is counter-clockwise: its edge 1, from (7,1) up to
    # (7,7), has a = 1 - 7 < 0: a right edge, it owns nothing. Triangle 1 = (1,7), (7,7),
    # (1,1) is clockwise (orientation -1 flips the signs): its top edge 0 (a = 0, b = 6)
    # and the diagonal, edge 1 (a = 6), own nothing; its left edge 2 (a = -6) owns. Closed
    # owns all six edges, so the diagonal's samples, (1, 1) first, are drawn twice.
    variant = known_variant(OWNERSHIP, "closed")
    text = grade(OWNERSHIP, variant.source, OWNERSHIP.public[:1])[0].describe()
    assert "first difference at event 1 of 14 -- triangle_setup" in text
    assert "edges[1].owns_boundary: yours True, reference False" in text
    assert (
        "yours differs at 3 of 6: triangle 0, edge 1, triangle 1, edge 0, triangle 1, edge 1"
        in text
    )
    assert "result: [1, 1]: yours 2, reference 1" in text


def test_c_wrong_diagnostic_on_the_right_triangle():
    # (0,0), (6,0), (0,5) on a grid of 8 units per pixel: (0,0), (48,0), (0,40). Only
    # edge 1, (48,0) -> (0,40), has c != 0: x0 y1 - x1 y0 = 48 * 40 = 1920. With the sign
    # of c flipped, E_1 < 0 on every sample, so none of the 20 samples with
    # 5x + 6y < 30 (x, y >= 0) is covered.
    variant = known_variant(EDGES, "c_wrong")
    text = grade(EDGES, variant.source, EDGES.public[:1])[0].describe()
    assert "first difference at event 1 of 6 -- triangle_setup" in text
    assert "edges[1].c: yours -1920, reference 1920" in text
    assert "yours differs at 1 of 3: triangle 0, edge 1" in text
    assert "samples: 0 matched (#), 0 extra (!), 20 missing (?)" in text


@pytest.mark.parametrize(
    ("exercise", "feature"),
    [(e, f) for e in EXERCISES for f in e.features],
    ids=[f"{e.id}-{f}" for e in EXERCISES for f in e.features],
)
def test_every_features_triangles_are_built_to_have_it(exercise, feature):
    # Shape, orientation and place are chosen for the feature, so every draw has it: none is luck.
    rng = random.Random(11)
    for _ in range(20):
        case = exercise.generate(rng, feature)
        assert feature in exercise.exercised(case, reference_outcome(exercise, case)), case.inputs


def test_triangles_across_the_border_cover_samples_inside_and_reach_beyond():
    rng = random.Random(7)
    for _ in range(20):
        case = OWNERSHIP.generate(rng, "crosses the raster border")
        counts, _ = OWNERSHIP.call(OWNERSHIP.reference, dict(case.inputs), None)
        coordinates = [c for t in case.inputs["triangles"] for p in t for c in p]
        assert counts.any() and counts.max() == 1  # the shared edge is still covered once
        assert min(coordinates) <= -1 or max(coordinates) >= SIZE + 1

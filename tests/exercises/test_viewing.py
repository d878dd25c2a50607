"""The viewing-stage exercises: backface_cull (11), clip_plane (12), eye_from_world (13)."""

import pytest

from scanviz import steps
from scanviz.exercises import get
from scanviz.exercises.core import (
    hidden_cases,
)
from scanviz.exercises.viewing import case_camera
from scanviz.trace import Recorder
from scanviz.transform import clip_polygon, cull_faces, transform_vertices

from .support import grade

IDS = ("backface_cull", "clip_plane", "eye_from_world")
EXERCISES = [get(exercise_id) for exercise_id in IDS]
VARIANTS = [(e, v) for e in EXERCISES for v in e.variants]


def _variant(exercise_id, name):
    exercise = get(exercise_id)
    return exercise, next(v for v in exercise.variants if v.name == name)


def test_the_exercises_have_their_numbers_and_steps():
    assert [(e.number, e.step) for e in EXERCISES] == [
        (11, "back_face_test"),
        (12, "clip_against_plane"),
        (13, "viewing_matrix"),
    ]


# The entry points run without any step replaced, for the trace the exercise must reproduce.
DEFAULT_RUNS = {
    "backface_cull": lambda inputs, tracer: cull_faces(
        case_camera(inputs["camera"]), inputs["positions"], inputs["faces"], trace=tracer
    ),
    "clip_plane": lambda inputs, tracer: clip_polygon(
        inputs["polygon"], inputs["attributes"], trace=tracer
    ),
    "eye_from_world": lambda inputs, tracer: transform_vertices(
        case_camera(inputs["camera"]),
        inputs["points"],
        inputs["width"],
        inputs["height"],
        subpixel_bits=None,
        trace=tracer,
    ),
}


@pytest.mark.parametrize("exercise", EXERCISES, ids=IDS)
def test_the_reference_plugged_in_gives_the_default_trace(exercise):
    for case in [*exercise.public, *hidden_cases(exercise, "test", 5)]:
        default, plugged = Recorder(exercise.kinds), Recorder(exercise.kinds)
        DEFAULT_RUNS[exercise.id](dict(case.inputs), default)
        exercise.call(exercise.reference, dict(case.inputs), plugged)
        assert plugged.trace() == default.trace() and len(default.trace()), case.label
        assert not steps.replaced()


# Correct answers that round differently from the reference: rtol = 1e-9 must accept them.
OTHER_CORRECT = {
    "backface_cull": """\
import numpy as np

def back_face_test(normal, view):
    return bool(np.dot(view, normal) >= 0) and bool(np.any(normal))
""",
    "clip_plane": """\
def clip_against_plane(vertices, plane):
    def inside(v):
        return sum(c * x for c, x in zip(plane, v))

    out = []
    for i, p in enumerate(vertices):
        s = vertices[i - 1]
        ds, dp = inside(s), inside(p)
        if (ds < 0) != (dp < 0) and ds != 0 and dp != 0:
            t = dp / (dp - ds)  # from P towards S
            out.append(tuple(b + t * (a - b) for a, b in zip(s, p)))
        if dp >= 0:
            out.append(p)
    return out
""",
    "eye_from_world": """\
import numpy as np

def viewing_matrix(eye, look_at, up):
    forward = np.subtract(look_at, eye)
    forward = forward / np.linalg.norm(forward)
    right = np.cross(forward, up)
    right = right / np.linalg.norm(right)
    true_up = np.cross(right, forward)
    rotation = np.eye(4)
    rotation[:3, :3] = [right, true_up, -forward]
    translation = np.eye(4)
    translation[:3, 3] = np.negative(eye)
    return rotation @ translation
""",
}


@pytest.mark.parametrize("exercise", EXERCISES, ids=IDS)
def test_a_correct_answer_rounding_otherwise_passes(exercise):
    cases = [*exercise.public, *hidden_cases(exercise, "test", 20)]
    verdicts = grade(exercise, OTHER_CORRECT[exercise.id], cases, variants=False)
    assert all(v.passed for v in verdicts), [v.describe() for v in verdicts if not v.passed]


def test_sign_flipped_diagnostic_on_the_cube_from_a_corner():
    # Face 0 is the -x face: Newell normal (-8, 0, 0) (twice its area 4), centroid (-1, 0, 0);
    # from the eye (3, 4, 5), V = (-4, -4, -5) and V . N = 32 >= 0: culled. The flipped test
    # (V . N <= 0) keeps it. No face plane holds the eye, so all 6 verdicts flip.
    exercise, variant = _variant("backface_cull", "sign_flipped")
    text = grade(exercise, variant.source, exercise.public[:1])[0].describe()
    assert "first difference at event 1 of 6 -- face_culled" in text
    assert "culled: yours False, reference True" in text
    assert "yours differs at 6 of 6: face 0, face 1, face 2, face 3, face 4, face 5" in text
    assert text.endswith(variant.hint)


def test_wrong_parameter_diagnostic_on_the_triangle_out_of_x_equals_w():
    # Only vertex 1 = (3, 0, 0.5, 1) is outside the right plane (distance w - x = -2). The edge
    # from vertex 0 (distance 1) leaves at t = 1 / (1 + 2) = 1/3: x = 1. Using 1 - t = 2/3
    # puts the crossing at x = 2.
    exercise, variant = _variant("clip_plane", "wrong_parameter")
    text = grade(exercise, variant.source, exercise.public[:1])[0].describe()
    assert "first difference at event 1 of 1 -- polygon_clipped" in text
    assert "vertices[1][0]: yours 2.0, reference 1.0" in text
    assert "yours differs at 1 of 1: right plane x = w" in text


def test_translation_not_rotated_diagnostic_on_the_camera_on_x():
    # Eye (5, 0, 0) looking at the origin: w = (1, 0, 0), u = (0, 0, -1), v = (0, 1, 0), so
    # -R @ eye = (0, 0, -5); the unrotated column -eye = (-5, 0, 0) differs first in row 0,
    # entry 3 of the flat matrix of the "eye" stage (event 2, after the "world" stage).
    exercise, variant = _variant("eye_from_world", "translation_not_rotated")
    text = grade(exercise, variant.source, exercise.public[1:2])[0].describe()
    assert "first difference at event 2 of 6 -- vertices_transformed" in text
    assert "matrix[3]: yours -5.0, reference 0.0" in text
    assert "first: [0][3]: yours -5.0, reference 0.0" in text

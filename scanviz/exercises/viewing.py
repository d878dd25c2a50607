"""Exercises on the viewing stage (scanviz.transform): back-face culling, clipping, the look-at.

Clipping and the look-at matrix are float arithmetic: a correct answer may
round differently from the reference (another order of operations, the other
end of an edge to interpolate from, no snapping onto the plane), so their
values compare with ``rtol = 1e-9`` (relative, with the same absolute floor).
That is ~10^7 ulps of the values involved (all of order 1 to 100, and every
case keeps w >= 0.25, so the divide amplifies nothing much): any correct
formula passes, and every known-wrong variant is off by far more (a sign, a
factor, a vertex). The back-face test returns a bool and every float in its
events comes from the loop, the same in both runs: it compares exactly.
"""

from __future__ import annotations

import functools
import math
import random

import numpy as np

from ..scene import Camera, Mesh, Scene, SceneObject
from ..transform import clip_polygon, cull_faces, transform_vertices
from ..transform.clip import CLIP_PLANES, clip_against_plane
from ..transform.cull import back_face_test
from ..transform.viewing import viewing_matrix
from .cases import call_with_step, place_by_event
from .catalog import register
from .core import Case, Exercise, Variant, edited_variant, feature_tests

RTOL = 1e-9  # float steps: see the module docstring

CUBE = [[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_FACES = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]


def _variant(solution: str, name: str, hint: str, old: str, new: str) -> Variant:
    return edited_variant(solution, name, hint, (old, new))


def case_camera(spec: dict) -> Camera:
    """The `Camera` of a case's plain ``camera`` dict (eye, look_at, up; optional the rest)."""
    return Camera(**{k: tuple(v) if isinstance(v, list) else v for k, v in spec.items()})


def case_scene(inputs: dict) -> Scene:
    """The scene of a culling or viewing case: its mesh, seen by its camera (for the stepper)."""
    positions = inputs.get("positions", inputs.get("points"))
    mesh = Mesh(np.array(positions, float), tuple(inputs["faces"]), smooth=False, closed=True)
    return Scene((SceneObject(mesh),), case_camera(inputs["camera"]))


def _box(rng: random.Random, aligned: bool) -> list:
    """The 8 corners of a random box (order of `CUBE`), axis-aligned on quarter units or rotated."""
    center = [rng.randint(-4, 4) / 4 for _ in range(3)]
    half = [rng.randint(2, 8) / 4 for _ in range(3)]
    if aligned:
        return [
            [c + s * h for c, s, h in zip(center, corner, half, strict=True)] for corner in CUBE
        ]
    angle, axis = rng.uniform(0, 2 * math.pi), rng.randrange(3)
    cos, sin = math.cos(angle), math.sin(angle)
    i, j = [k for k in range(3) if k != axis]
    corners = []
    for corner in CUBE:
        local = [s * h for s, h in zip(corner, half, strict=True)]
        local[i], local[j] = cos * local[i] - sin * local[j], sin * local[i] + cos * local[j]
        corners.append([c + v for c, v in zip(center, local, strict=True)])
    return corners


def _eye(rng: random.Random, low: float, high: float) -> list:
    """A point at distance `low`..`high` from the origin, in a random direction."""
    direction = [rng.gauss(0, 1) for _ in range(3)]
    length = math.sqrt(sum(c * c for c in direction)) or 1.0
    distance = rng.uniform(low, high)
    return [c / length * distance for c in direction]


# --- 11: back-face culling -----------------------------------------------------------------


def _cull(inputs: dict, tracer):
    culled, _ = cull_faces(
        case_camera(inputs["camera"]), inputs["positions"], inputs["faces"], trace=tracer
    )
    return culled


_face_of_call = place_by_event("face_culled", lambda culled: f"face {culled.polygon}")


CULL_CATEGORIES = (
    "box, perspective",
    "box, orthographic",
    "eye in a face's plane",
    "degenerate face",
)
HAIR = 2.0**-30  # how far off a face's plane "nearly edge-on" puts the eye


def _cull_case(rng: random.Random, feature: str | None = None) -> Case:
    """A box seen by a camera; a `feature` of `CULL_FEATURES` places the eye (or adds a face)."""
    category = feature if feature in CULL_CATEGORIES else rng.choice(CULL_CATEGORIES)
    nearly = feature in ("nearly edge-on, toward the eye", "nearly edge-on, away")
    if nearly:
        category = "eye in a face's plane"
    positions = _box(rng, aligned=category != "box, perspective" or rng.random() < 0.3)
    faces = [list(f) for f in CUBE_FACES]
    eye = _eye(rng, 4, 9)
    projection = "orthographic" if category == "box, orthographic" else "perspective"
    if category == "eye in a face's plane":  # that face is seen exactly edge-on: V . N = 0
        axis, corner = rng.randrange(3), rng.randrange(8)
        eye[axis] = positions[corner][axis]
        if nearly:  # a hair off the plane: outside the box (toward) or inside it (away)
            outward = 1 if positions[corner][axis] >= sum(p[axis] for p in positions) / 8 else -1
            toward = feature == "nearly edge-on, toward the eye"
            eye[axis] += outward * HAIR * (1 if toward else -1)
    if category == "degenerate face":  # three collinear points: a zero normal
        a, b = positions[0], positions[7]
        positions = positions + [a, [(p + q) / 2 for p, q in zip(a, b, strict=True)], b]
        faces.append([8, 9, 10])
    camera = {"eye": eye, "look_at": [0.0, 0.0, 0.0], "up": [0.0, 1.0, 0.0]}
    if abs(eye[0]) + abs(eye[2]) < 1e-3:  # looking straight down y: another up
        camera["up"] = [1.0, 0.0, 0.0]
    camera["projection"] = projection
    label = feature or category
    return Case(label, {"camera": camera, "positions": positions, "faces": faces}, label)


def _dots(reference) -> list[tuple[float, bool]]:
    """(V . N, whether N is zero) of every face the reference tested."""
    return [
        (sum(n * v for n, v in zip(normal, view, strict=True)), not any(normal))
        for (normal, view), _ in reference.arguments
    ]


def _some_face(check):
    return lambda case, reference: any(check(dot, zero) for dot, zero in _dots(reference))


CULL_FEATURES = {
    "faces the eye": _some_face(lambda dot, zero: dot < 0 and not zero),
    "faces away": _some_face(lambda dot, zero: dot > 0 and not zero),
    "edge-on": _some_face(lambda dot, zero: dot == 0 and not zero),
    "nearly edge-on, toward the eye": _some_face(lambda dot, zero: -1e-6 < dot < 0),
    "nearly edge-on, away": _some_face(lambda dot, zero: 0 < dot < 1e-6),
    "zero normal": _some_face(lambda dot, zero: zero),
    "box, orthographic": lambda case, reference: (
        case.inputs["camera"].get("projection") == "orthographic"
    ),
    "box, perspective": lambda case, reference: (
        case.inputs["camera"].get("projection", "perspective") == "perspective"
    ),
}
"""Tests of the back-face test's features: each branch (toward, away, edge-on, a zero normal),
faces a hair off edge-on on either side (which a tolerance gets wrong), and both projections."""


BACK_FACE_SOLUTION = """\
def back_face_test(normal, view):
    dot = normal[0] * view[0] + normal[1] * view[1] + normal[2] * view[2]
    facing_away = dot >= 0
    has_area = normal[0] != 0 or normal[1] != 0 or normal[2] != 0
    return facing_away and has_area
"""


_cull_variant = functools.partial(_variant, BACK_FACE_SOLUTION)


register(
    Exercise(
        id="backface_cull",
        number=11,
        title="The back-face test",
        stage="viewing",
        kind="step",
        points=2,
        answer="back_face_test",
        idea=(
            "A closed mesh never shows the faces that turn away from the eye. With the faces "
            "counter-clockwise seen from outside, Newell's method gives each face an outward "
            "normal **N**. The viewing vector **V** goes from the eye to the face (its centroid) "
            "for a perspective camera, and is the view direction `look_at - eye` for an "
            "orthographic one. The face is **back-facing when V . N >= 0**: it points away, or "
            "is seen exactly edge-on and covers no area.\n\n"
            "Only the sign matters, so N need not be a unit vector. A face whose vertices are "
            "collinear has N = 0 and no back: it is never culled. The test runs in world space "
            "(the viewing transform is rigid, so the sign is the same in eye space)."
        ),
        stub=(
            "def back_face_test(normal, view):\n"
            '    """normal: (nx, ny, nz), the face\'s outward Newell normal (floats; not unit).\n'
            "    view: (vx, vy, vz), the viewing vector: eye to face centroid (perspective) or\n"
            "    the view direction look_at - eye (orthographic).\n"
            "    Return True if the face is culled: it turns away from the eye or is seen exactly\n"
            '    edge-on. A zero normal (collinear vertices) is never culled."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=BACK_FACE_SOLUTION,
        call=call_with_step("back_face_test", _cull),
        reference=back_face_test,
        public=(
            Case(
                "cube seen from a corner, perspective",
                {
                    "camera": {"eye": [3, 4, 5], "look_at": [0, 0, 0], "up": [0, 1, 0]},
                    "positions": CUBE,
                    "faces": CUBE_FACES,
                },
            ),
            Case(
                "cube head-on, orthographic",
                {
                    "camera": {
                        "eye": [0, 0, 5],
                        "look_at": [0, 0, 0],
                        "up": [0, 1, 0],
                        "projection": "orthographic",
                    },
                    "positions": CUBE,
                    "faces": CUBE_FACES,
                },
            ),
            Case(
                "cube, eye in the plane of the +y face, perspective",
                {
                    "camera": {"eye": [4, 1, 3], "look_at": [0, 0, 0], "up": [0, 1, 0]},
                    "positions": CUBE,
                    "faces": CUBE_FACES,
                },
            ),
            Case(
                "cube, eye a hair (2^-30) outside the plane of the +y face",
                {
                    "camera": {"eye": [4, 1 + 2**-30, 3], "look_at": [0, 0, 0], "up": [0, 1, 0]},
                    "positions": CUBE,
                    "faces": CUBE_FACES,
                },
            ),
            Case(
                "cube with a degenerate (collinear) face",
                {
                    "camera": {"eye": [0.5, 2, 6], "look_at": [0, 0, 0], "up": [0, 1, 0]},
                    "positions": CUBE + [[-1, -1, -1], [0, 0, 0], [1, 1, 1]],
                    "faces": CUBE_FACES + [[8, 9, 10]],
                },
            ),
        ),
        generate=_cull_case,
        **feature_tests(CULL_FEATURES),
        variants=(
            _cull_variant(
                "sign_flipped",
                "the sign is flipped: a face turns away when V . N >= 0 (V from the eye to the "
                "face, N outward); yours culls the faces that face the eye",
                "facing_away = dot >= 0",
                "facing_away = dot <= 0",
            ),
            _cull_variant(
                "normal_z_only",
                "testing only the normal's z works for an orthographic view down -z; in "
                "perspective each face has its own viewing vector: test V . N",
                "facing_away = dot >= 0",
                "facing_away = normal[2] <= 0",
            ),
            _cull_variant(
                "edge_on_kept",
                "a face seen exactly edge-on (V . N = 0) covers no area and is culled too: "
                "test V . N >= 0, not > 0",
                "facing_away = dot >= 0",
                "facing_away = dot > 0",
            ),
            _cull_variant(
                "tolerance",
                "a tolerance around 0: a face turned toward the eye by a hair is still seen; "
                "cull when V . N >= 0, exactly",
                "facing_away = dot >= 0",
                "facing_away = dot >= -1e-6",
            ),
            _cull_variant(
                "all_for_any",
                "a normal is zero only when all three components are: has_area is any "
                "component != 0, so an axis-aligned face (normal (0, 0, 1)) has area",
                "has_area = normal[0] != 0 or normal[1] != 0 or normal[2] != 0",
                "has_area = normal[0] != 0 and normal[1] != 0 and normal[2] != 0",
            ),
            _cull_variant(
                "zero_normal_culled",
                "a face with a zero normal (collinear vertices) has no back side: never cull it",
                "return facing_away and has_area",
                "return facing_away",
            ),
        ),
        kinds=("face_culled",),
        step="back_face_test",
        place=_face_of_call,
        result=lambda culled: [bool(c) for c in culled],
        stepper=(
            "from scanviz.exercises.viewing import case_scene\n"
            "from scanviz.widgets import viewing_stepper\n"
            "viewing_stepper(case_scene(CASE), 64, 64)"
        ),
    )
)


# --- 12: one Sutherland-Hodgman stage ---------------------------------------------------------

PLANE_EQUATIONS = ("z = 0", "z = w", "x = -w", "x = w", "y = -w", "y = w")


def _clip(inputs: dict, tracer):
    return clip_polygon(inputs["polygon"], inputs["attributes"], trace=tracer)


def _clipped(returned) -> dict:
    points, attributes = returned
    return {"vertices": points.tolist(), "attributes": attributes.tolist()}


def _plane_of_call(index: int, trace: list) -> str:
    """The plane of call `index`: the planes some vertex is outside of, while vertices remain."""
    event = next((e for e in trace if e.kind == "polygon_clipped"), None)
    if event is None:
        return f"call {index + 1}"
    outside = 0
    for code in event.outcodes:
        outside |= code
    before = [len(event.outcodes), *event.counts]
    planes = [p for p in range(len(event.counts)) if outside >> p & 1 and before[p]]
    if index >= len(planes):
        return f"call {index + 1}"
    plane = planes[index]
    return f"{CLIP_PLANES[plane]} plane {PLANE_EQUATIONS[plane]}"


CLIP_CATEGORIES = ("triangle", "polygon", "vertex on a plane", "mostly outside")


def _clip_case(rng: random.Random, feature: str | None = None) -> Case:
    """A polygon in clip space; a `feature` of `CLIP_FEATURES` shapes it to have it."""
    category = feature if feature in CLIP_CATEGORIES else rng.choice(CLIP_CATEGORIES)
    if feature == "on the plane":
        category = "vertex on a plane"
    count = 3 if category == "triangle" else rng.randint(4, 6)
    spread = 2.5 if category == "mostly outside" else 1.6
    center = [rng.uniform(-0.8, 0.8), rng.uniform(-0.8, 0.8)]
    polygon = []
    for k in sorted(rng.uniform(0, 2 * math.pi) for _ in range(count)):
        w = rng.uniform(0.5, 3.0)
        radius = rng.uniform(0.4, spread)
        x, y = center[0] + radius * math.cos(k), center[1] + radius * math.sin(k)
        polygon.append([x * w, y * w, rng.uniform(-0.3, 1.3) * w, w])
    if category == "vertex on a plane":  # exactly on x = w, y = -w or z = 0, the next one out
        k, axis = rng.randrange(count), rng.choice((0, 1, 2))
        vertex, after = polygon[k], polygon[(k + 1) % count]
        vertex[axis] = (vertex[3], -vertex[3], 0.0)[axis]
        after[axis] = (1.5 * after[3], -1.5 * after[3], -0.5 * after[3])[axis]
    attributes = [[rng.uniform(0, 1) for _ in range(2)] for _ in polygon]
    label = feature or category
    return Case(label, {"polygon": polygon, "attributes": attributes}, label)


def _distances(reference) -> list[list[float]]:
    """Each stage's signed distances of its vertices to its plane, in the reference's run."""
    return [
        [sum(a * b for a, b in zip(plane, v[:4], strict=True)) for v in vertices]
        for (vertices, plane), _ in reference.arguments
    ]


def _some_edge(check):
    """Whether an edge (S, P), S the previous vertex, of some stage passes `check(d_s, d_p)`."""
    return lambda case, reference: any(
        check(ds[k - 1], ds[k]) for ds in _distances(reference) for k in range(len(ds))
    )


CLIP_FEATURES = {
    "entering edge": _some_edge(lambda d_s, d_p: d_s < 0 < d_p),
    "leaving edge": _some_edge(lambda d_s, d_p: d_p < 0 < d_s),
    "edge inside": _some_edge(lambda d_s, d_p: d_s > 0 and d_p > 0),
    "on the plane": _some_edge(lambda d_s, d_p: d_p == 0),
    "perspective (w not 1)": lambda case, reference: any(v[3] != 1 for v in case.inputs["polygon"]),
}
"""Tests of a clipping stage's features: each branch of an edge (entering, leaving, inside, a
vertex exactly on the plane), and w other than 1 (a polygon wholly outside a plane is rejected
before any stage runs)."""


CLIP_SOLUTION = """\
def clip_against_plane(vertices, plane):
    def distance(v):
        return plane[0] * v[0] + plane[1] * v[1] + plane[2] * v[2] + plane[3] * v[3]

    clipped = []
    s = vertices[-1]
    for p in vertices:
        d_s, d_p = distance(s), distance(p)
        if d_s < 0 < d_p or d_p < 0 < d_s:
            t = d_s / (d_s - d_p)
            clipped.append(tuple(a + t * (b - a) for a, b in zip(s, p)))
        if d_p >= 0:
            clipped.append(p)
        s = p
    return clipped
"""


_clip_variant = functools.partial(_variant, CLIP_SOLUTION)


register(
    Exercise(
        id="clip_plane",
        number=12,
        title="One Sutherland-Hodgman clipping stage",
        stage="viewing",
        kind="step",
        points=4,
        answer="clip_against_plane",
        idea=(
            "Polygons are clipped in homogeneous clip space, before the divide, against six "
            "planes: -w <= x, y <= w and 0 <= z <= w. Each plane has a signed distance that is "
            "linear in (x, y, z, w), e.g. `w - x` for the right plane x = w; a vertex is "
            "inside when it is >= 0.\n\n"
            "**Sutherland-Hodgman** clips against one plane at a time. Walk the edges (S, P), S "
            "the previous vertex: if S and P are strictly on opposite sides, emit the crossing "
            "`S + t (P - S)` with `t = d_S / (d_S - d_P)` (attributes too, with the same t); "
            "then emit P if it is inside. The reference loops over the planes; you write one "
            "stage."
        ),
        stub=(
            "def clip_against_plane(vertices, plane):\n"
            '    """vertices: the polygon in order, each a tuple (x, y, z, w, a0, a1, ...) of\n'
            "    floats: clip-space coordinates, then attributes.\n"
            "    plane: (a, b, c, d); a vertex's signed distance is a*x + b*y + c*z + d*w, and\n"
            "    the inside is distance >= 0.\n"
            "    Return the clipped polygon: a list of tuples of the same length, in order. For\n"
            "    each edge (S, P) in turn, starting with (the last vertex, the first vertex):\n"
            "    if S and P are strictly on opposite sides (one distance < 0, the other > 0),\n"
            "    the crossing (every component interpolated with the same t); then P if its\n"
            '    distance is >= 0."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=CLIP_SOLUTION,
        call=call_with_step("clip_against_plane", _clip),
        reference=clip_against_plane,
        public=(
            Case(
                "triangle poking out of x = w",
                {
                    "polygon": [[0, 0, 0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]],
                    "attributes": [[0, 1], [3, 1], [0, 2]],
                },
            ),
            Case(
                "quad with a vertex on the near plane z = 0",
                {
                    "polygon": [
                        [0, 0, 0, 1],
                        [0.5, 0, -0.5, 1],
                        [0.5, 0.5, 0.5, 1],
                        [0, 0.5, 0.5, 1],
                    ],
                    "attributes": [[0, 0], [1, 0], [1, 1], [0, 1]],
                },
            ),
            Case(
                "perspective triangle across the left and top planes",
                {
                    "polygon": [[-3, 0.5, 1, 2], [1.5, -0.5, 1.5, 2.5], [0.5, 4, 2, 3]],
                    "attributes": [[1, 0], [0, 1], [0.5, 0.5]],
                },
            ),
        ),
        generate=_clip_case,
        **feature_tests(CLIP_FEATURES),
        variants=(
            _clip_variant(
                "keeps_outside",
                "the inside test is reversed: a vertex is kept when its distance is >= 0",
                "if d_p >= 0:",
                "if d_p <= 0:",
            ),
            _clip_variant(
                "no_entering_crossing",
                "an edge entering the inside (S outside, P inside) also crosses the plane: emit "
                "the crossing, then P",
                "if d_s < 0 < d_p or d_p < 0 < d_s:",
                "if d_p < 0 < d_s:",
            ),
            _clip_variant(
                "wrong_parameter",
                "t is measured from S: the crossing is S + t (P - S) with t = d_S / (d_S - d_P); "
                "yours uses 1 - t",
                "t = d_s / (d_s - d_p)",
                "t = d_p / (d_p - d_s)",
            ),
            _clip_variant(
                "attributes_not_interpolated",
                "the attributes after (x, y, z, w) are interpolated with the same t as the "
                "coordinates; yours copies them from S",
                "clipped.append(tuple(a + t * (b - a) for a, b in zip(s, p)))",
                "clipped.append(tuple(a + t * (b - a) for a, b in zip(s[:4], p[:4])) + s[4:])",
            ),
            edited_variant(
                CLIP_SOLUTION,
                "starts_one_later",
                "your vertices are right but start one edge later: walk the edges from (the last "
                "vertex, the first vertex), so the output starts with what that edge gives",
                (
                    "s = vertices[-1]\n    for p in vertices:",
                    "s = vertices[0]\n    for p in vertices[1:] + vertices[:1]:",
                ),
            ),
            _clip_variant(
                "on_plane_twice",
                "a vertex exactly on the plane is inside: an edge crosses only when its ends are "
                "strictly on opposite sides, else that vertex comes out twice",
                "if d_s < 0 < d_p or d_p < 0 < d_s:",
                "if d_s < 0 <= d_p or d_p < 0 <= d_s:",
            ),
        ),
        kinds=("polygon_clipped",),
        step="clip_against_plane",
        place=_plane_of_call,
        result=_clipped,
        rtol=RTOL,
        stepper=(
            "from scanviz.trace import Recorder\n"
            "from scanviz.transform import clip_polygon\n"
            "from scanviz.widgets import plot_clip\n\n"
            "recorder = Recorder()\n"
            "clipped, attributes = clip_polygon(CASE['polygon'], CASE['attributes'], "
            "trace=recorder)\n"
            "print('clipped vertices (x, y, z, w):', clipped.tolist())\n"
            "print('their attributes:', attributes.tolist())\n"
            "plot_clip(CASE['polygon'], recorder.trace()[0])"
        ),
    )
)


# --- 13: eye_from_world -------------------------------------------------------------------


def _view(inputs: dict, tracer):
    return transform_vertices(
        case_camera(inputs["camera"]),
        inputs["points"],
        inputs["width"],
        inputs["height"],
        subpixel_bits=None,  # no snapping: a last-bit difference never moves a grid point
        trace=tracer,
    )


VIEW_CATEGORIES = ("perspective", "orthographic", "tilted up vector", "long up vector")


def _view_case(rng: random.Random, feature: str | None = None) -> Case:
    """A rotated box and a camera; a `feature` of `VIEW_FEATURES` picks the camera that has it."""
    category = feature if feature in VIEW_CATEGORIES else rng.choice(VIEW_CATEGORIES)
    eye = _eye(rng, 8, 12)  # the box is within 5.2 of the origin: every point has w > 1
    up = [0.0, 1.0, 0.0]
    if category == "tilted up vector":
        up = [rng.uniform(-0.5, 0.5), 1.0, rng.uniform(-0.5, 0.5)]
    if category == "long up vector":
        up = [0.0, rng.choice((0.25, 2.0, 3.0)), 0.0]
    if abs(eye[0]) + abs(eye[2]) < 1.0:  # nearly straight down y: up along x instead
        up = [1.0, 0.0, 0.0]
    camera = {"eye": eye, "look_at": [rng.uniform(-0.5, 0.5) for _ in range(3)], "up": up}
    camera["projection"] = "orthographic" if category == "orthographic" else "perspective"
    camera["window"] = [-2.0, 2.0, -2.0, 2.0] if category == "orthographic" else [-1, 1, -1, 1]
    return Case(
        category,
        {
            "camera": camera,
            "points": _box(rng, aligned=False),
            "faces": CUBE_FACES,
            "width": rng.randint(8, 16),
            "height": rng.randint(8, 16),
        },
        category,
    )


def _camera_calls(reference) -> list[tuple]:
    return [args for args, _ in reference.arguments]


def _some_camera(check):
    return lambda case, reference: any(check(*args) for args in _camera_calls(reference))


def _backward(eye, look_at) -> list[float]:
    return [e - a for e, a in zip(eye, look_at, strict=True)]


VIEW_FEATURES = {
    "perspective": lambda case, reference: case.inputs["camera"]["projection"] == "perspective",
    "orthographic": lambda case, reference: case.inputs["camera"]["projection"] == "orthographic",
    "tilted up vector": _some_camera(
        lambda eye, look_at, up: (
            abs(sum(u * b for u, b in zip(up, _backward(eye, look_at), strict=True))) > 1e-9
        )
    ),
    "long up vector": _some_camera(
        lambda eye, look_at, up: abs(math.sqrt(sum(u * u for u in up)) - 1) > 1e-9
    ),
}
"""Tests of the viewing matrix's features: an up vector not perpendicular to the view (which must
be made so) or not of unit length (which must not scale), and both projections."""


VIEWING_SOLUTION = """\
import math

def viewing_matrix(eye, look_at, up):
    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

    def normalize(a):
        length = math.sqrt(dot(a, a))
        return [c / length for c in a]

    w = normalize([eye[k] - look_at[k] for k in range(3)])
    u = normalize(cross(up, w))
    v = cross(w, u)
    t = [-dot(u, eye), -dot(v, eye), -dot(w, eye)]
    return [
        [u[0], u[1], u[2], t[0]],
        [v[0], v[1], v[2], t[1]],
        [w[0], w[1], w[2], t[2]],
        [0.0, 0.0, 0.0, 1.0],
    ]
"""


_view_variant = functools.partial(_variant, VIEWING_SOLUTION)


CUBE_AT_ORIGIN = {"points": CUBE, "faces": CUBE_FACES, "width": 8, "height": 8}

register(
    Exercise(
        id="eye_from_world",
        number=13,
        title="The viewing matrix eye_from_world",
        stage="viewing",
        kind="step",
        points=3,
        answer="viewing_matrix",
        idea=(
            "Eye space puts the eye at the origin looking down **-z**, with y up, right-handed. "
            "From the camera's eye, look-at point and up vector build an orthonormal basis: "
            "`w` = unit vector from the look-at point to the eye (backward), `u = up x w` "
            "normalized (right), `v = w x u` (the true up, orthogonal to both).\n\n"
            "`eye_from_world = R @ T(-eye)`: first move the eye to the origin, then rotate; "
            "the rows of R are u, v, w, so the last column is `-R @ eye`. Matrices act on "
            "column vectors, `q = M @ p`."
        ),
        stub=(
            "def viewing_matrix(eye, look_at, up):\n"
            '    """eye, look_at, up: (x, y, z) tuples of floats (world space; up is any vector\n'
            "    not parallel to the view direction, not necessarily unit or orthogonal).\n"
            "    Return eye_from_world as a 4x4 nested list (or array) of floats: rows u, v, w of\n"
            '    the eye\'s basis, last column -R @ eye, last row (0, 0, 0, 1)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=VIEWING_SOLUTION,
        call=call_with_step("viewing_matrix", _view),
        reference=viewing_matrix,
        public=(
            Case(
                "default camera on +z",
                {"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "up": [0, 1, 0]}}
                | CUBE_AT_ORIGIN,
            ),
            Case(
                "camera on +x, up of length 2",
                {"camera": {"eye": [5, 0, 0], "look_at": [0, 0, 0], "up": [0, 2, 0]}}
                | CUBE_AT_ORIGIN,
            ),
            Case(
                "looking down at an angle",
                {"camera": {"eye": [3, 4, 5], "look_at": [0, 0.5, 0], "up": [0, 1, 0]}}
                | CUBE_AT_ORIGIN,
            ),
            Case(
                "orthographic, tilted up",
                {
                    "camera": {
                        "eye": [-4, 2, 6],
                        "look_at": [0.5, 0, 0],
                        "up": [0.5, 1, 0],
                        "projection": "orthographic",
                        "window": [-2, 2, -2, 2],
                    }
                }
                | CUBE_AT_ORIGIN,
            ),
        ),
        generate=_view_case,
        **feature_tests(VIEW_FEATURES),
        variants=(
            _view_variant(
                "left_handed",
                "u = w x up is the left-handed basis (the image comes out mirrored): the right "
                "axis is u = up x w",
                "u = normalize(cross(up, w))",
                "u = normalize(cross(w, up))",
            ),
            _view_variant(
                "u_not_normalized",
                "up x w has length |up| sin(angle): normalize u, or the rotation scales the scene",
                "u = normalize(cross(up, w))",
                "u = cross(up, w)",
            ),
            _view_variant(
                "translation_not_rotated",
                "eye_from_world = R @ T(-eye): the last column is -R @ eye (the eye in the "
                "rotated frame), not -eye",
                "t = [-dot(u, eye), -dot(v, eye), -dot(w, eye)]",
                "t = [-eye[0], -eye[1], -eye[2]]",
            ),
            _view_variant(
                "up_not_orthogonalized",
                "the given up vector is not orthogonal to w in general: use v = w x u, the true up",
                "v = cross(w, u)",
                "v = normalize(up)",
            ),
        ),
        kinds=("vertices_transformed",),
        step="viewing_matrix",
        place=lambda index, trace: "the viewing matrix",
        output=lambda args, kwargs, returned: np.asarray(returned, dtype=float).tolist(),
        rtol=RTOL,
        stepper=(
            "from scanviz.exercises.viewing import case_scene\n"
            "from scanviz.widgets import viewing_stepper\n"
            "viewing_stepper(case_scene(CASE), CASE['width'], CASE['height'])"
        ),
    )
)

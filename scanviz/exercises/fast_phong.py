"""Exercises on fast Phong shading (scanviz.shading.fast_phong; Wang 1989, ch. 3), through
`fast_phong_triangle` traced.

Two steps of the per-sample loop: ``specular_level``, the look-up of the
specular level in the table cos φ_1..cos φ_N by comparisons (a search at a
span's first sample, a walk from the previous level after), and
``forward_difference``, one step of a Taylor quadratic along a span (Q += dQ,
dQ += 2 T5). The real shader runs with the student's step; its
``fast_phong_pixel`` events (the differenced values, the level, the colour)
are graded, then the triangle's colours. Cases are small screen triangles
with a highlight, Phong and Blinn, expanded about vertex U or the centroid;
among them a narrow highlight whose level jumps by tens of entries between
neighbouring samples, a dull surface whose cosines land exactly on table
entries, cosines below the table (level 0) and samples past the terminator.
"""

from __future__ import annotations

import functools
import math
import random

from ..shading.fast_phong import ReflectionModel, fast_phong_triangle, forward_difference
from ..shading.lut import specular_level
from .cases import call_with_step, grid_value, place_by_event
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

KINDS = ("fast_phong_pixel",)
QUADRATICS = (  # the stepped quadratics, in the loop's order, named as the event's fields
    "cos_theta",
    "cos_specular",
    "ambient_diffuse[0]",
    "ambient_diffuse[1]",
    "ambient_diffuse[2]",
)
CATEGORIES = (
    "phong highlight",
    "blinn highlight",
    "narrow highlight",
    "highlight at vertex U",
    "past the terminator",
)
SPECULAR = {"phong highlight": "phong", "blinn highlight": "blinn"}  # the others draw one
SIZE = 12  # the raster of the hidden cases
STEPPER = (
    "from scanviz.exercises.fast_phong import case_model\n"
    "from scanviz.widgets.fast_phong import fast_phong_stepper\n"
    "fast_phong_stepper(CASE['vertices'], CASE['normals'], CASE['to_light'], "
    "CASE['to_viewer'], case_model(CASE),\n"
    "                   width=CASE['width'], height=CASE['height'], "
    "expansion=CASE['expansion'])"
)


def case_model(inputs: dict) -> ReflectionModel:
    """The reflection model of a case (its table included)."""
    return ReflectionModel(**inputs["model"])


def _shade(inputs: dict, tracer=None):
    return fast_phong_triangle(
        inputs["vertices"],
        inputs["normals"],
        inputs["to_light"],
        inputs["to_viewer"],
        case_model(inputs),
        width=inputs["width"],
        height=inputs["height"],
        expansion=inputs["expansion"],
        trace=tracer,
    )


def _pixels(trace: list) -> list:
    return [e for e in trace if e.kind == "fast_phong_pixel"]


def _sample(pixel) -> str:
    """The look-up runs once per covered sample, in the order the samples are traced."""
    return f"pixel ({pixel.x}, {pixel.y})" + (" (a span's first)" if pixel.direct else "")


def _quadratic_of_call(index: int, trace: list) -> str:
    """The step runs at every sample after a span's first, once per quadratic, in loop order."""
    stepped = [e for e in _pixels(trace) if not e.direct]
    sample, quadratic = divmod(index, len(QUADRATICS))
    if sample >= len(stepped):
        return f"call {index + 1}"
    return f"{QUADRATICS[quadratic]} at pixel ({stepped[sample].x}, {stepped[sample].y})"


def _model(n, ks=0.7, r_plus_r0=1.5, specular="phong", kd=(0.6, 0.6, 0.6), Ip=255.0) -> dict:
    """A `ReflectionModel`'s arguments: white ambient light at 0.1, light `Ip` levels."""
    return {
        "Ia": 255.0,
        "ka": 0.1,
        "Ip": Ip,
        "kd": list(kd),
        "ks": ks,
        "n": n,
        "r_plus_r0": r_plus_r0,
        "specular": specular,
    }


def _case(
    label, vertices, normals, to_light, to_viewer, model, width, height, expansion, category=""
):
    inputs = {
        "vertices": vertices,
        "normals": normals,
        "to_light": to_light,
        "to_viewer": to_viewer,
        "model": model,
        "expansion": expansion,
        "width": width,
        "height": height,
    }
    return Case(label, inputs, category)


Z = [0.0, 0.0, 1.0]
PUBLIC = (
    _case(
        "a highlight at vertex U (Phong, about U): cos φ = 1 there exactly, level N = 119",
        [[0.0, 0.0], [7.0, 0.0], [0.0, 7.0]],
        [Z, [0.25, 0.0, 1.0], [0.0, 0.25, 1.0]],
        Z,
        Z,
        _model(8),
        8,
        8,
        "vertex",
    ),
    _case(
        "a highlight inside the triangle (Blinn, about the centroid): levels rise, then fall",
        [[1.5, 0.5], [11.25, 3.5], [3.75, 10.25]],
        [[-0.3, -0.2, 1.0], [0.35, 0.0, 1.0], [0.0, 0.4, 1.0]],
        [0.3, 0.2, 1.0],
        Z,
        _model(24, specular="blinn", kd=[0.7, 0.5, 0.2]),
        12,
        12,
        "centroid",
    ),
    _case(
        "a narrow highlight (n = 60, N = 255): the level jumps by up to 51 entries a sample",
        [[0.5, 0.5], [13.5, 2.25], [4.25, 11.5]],
        [[-0.12, -0.05, 1.0], [0.15, 0.0, 1.0], [0.0, 0.14, 1.0]],
        Z,
        Z,
        _model(60, ks=1.0, r_plus_r0=1.0),
        14,
        12,
        "vertex",
    ),
    _case(
        "a grazing light: past the terminator (cos θ <= 0) and below the table (level 0)",
        [[0.5, 1.5], [13.5, 0.5], [7.25, 9.75]],
        [[-0.5, 0.0, 1.0], [0.9, 0.0, 1.0], [0.2, 0.3, 1.0]],
        [1.0, 0.0, 0.2],
        Z,
        _model(8, kd=[0.2, 0.6, 0.8]),
        14,
        10,
        "centroid",
    ),
    _case(
        "a dull surface (n = 1, N = 128): cos φ lands exactly on table entries",
        [[0.0, 0.0], [8.0, 0.0], [0.0, 8.0]],
        [Z, [0.25, 0.0, 1.0], [0.0, 0.25, 1.0]],
        Z,
        Z,
        _model(1, ks=1.0, r_plus_r0=1.0, Ip=128.0),
        9,
        9,
        "vertex",
    ),
)


def _round(values) -> list:
    return [round(v, 3) for v in values]


def _unit(vector) -> list:
    length = math.sqrt(sum(v * v for v in vector))
    return [v / length for v in vector]


def _triangle(rng: random.Random, corner: bool) -> list:
    """A triangle of 4 to 11 pixels across, vertices on a quarter-pixel grid, either winding.
    `corner`: U at an integer sample with a horizontal lower edge to its right (U is covered)."""
    while True:
        if corner:
            ux, uy = rng.randint(0, 3), rng.randint(0, 3)
            right = min(ux + rng.randint(4, 8), SIZE - 1)
            top = (grid_value(rng, ux, right), grid_value(rng, uy + 4, SIZE - 0.25))
            vertices = [[float(ux), float(uy)], [float(right), float(uy)], list(top)]
        else:
            vertices = [
                [grid_value(rng, 0, SIZE - 0.25), grid_value(rng, 0, SIZE - 0.25)] for _ in "uvw"
            ]
        (ax, ay), (bx, by), (cx, cy) = vertices
        if abs((bx - ax) * (cy - ay) - (cx - ax) * (by - ay)) / 2 >= 12:
            break
    if not corner and rng.random() < 0.5:
        vertices[1], vertices[2] = vertices[2], vertices[1]
    return vertices


def _normals_about(rng: random.Random, centre, tilt: float) -> list:
    """Three normals: `centre` tilted by up to `tilt` in x and y, rounded to 3 decimals."""
    return [
        _round(
            [centre[0] + rng.uniform(-tilt, tilt), centre[1] + rng.uniform(-tilt, tilt), centre[2]]
        )
        for _ in "uvw"
    ]


LEVEL_CATEGORIES = {  # a level feature: the category whose triangles have it
    "walk up": "narrow highlight",  # the level climbs by tens of entries toward the peak
    "walk down": "highlight at vertex U",  # from level N at U, falling along U's span
    "top of the table": "highlight at vertex U",  # cos φ = 1 exactly at U
    "below the table": "past the terminator",  # a normal turned from the light: cos φ < cos φ_1
    "level kept": "past the terminator",  # level 0 from sample to sample there
}


def _fast_phong_case(rng: random.Random, feature: str | None = None) -> Case:
    """A shaded screen triangle; a category `feature` is that category, a level feature one of
    `LEVEL_CATEGORIES`, another one is drawn until the feature test confirms it."""
    category = feature if feature in CATEGORIES else LEVEL_CATEGORIES.get(feature)
    category = category or rng.choice(CATEGORIES)
    if feature == "about the centroid":
        category = rng.choice(("phong highlight", "blinn highlight", "narrow highlight"))
    specular = SPECULAR.get(category) or rng.choice(("phong", "blinn"))
    n = rng.choice((6, 8, 16)) * (4 if specular == "blinn" else 1)
    ks, r_plus_r0 = rng.choice((0.5, 0.7, 1.0)), rng.choice((1.0, 1.2, 1.5))
    to_viewer = _round([rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 1.0])
    to_light = _round([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1.0])
    at_vertex = category == "highlight at vertex U"
    if at_vertex:  # N_U = L = V below: cos φ = 1 exactly at U
        to_light = to_viewer = [0.0, 0.0, 1.0]
    tilt = rng.uniform(0.15, 0.4)
    if category == "narrow highlight":
        n, ks, r_plus_r0, tilt = rng.choice((40, 60, 100)), 1.0, 1.0, rng.uniform(0.08, 0.16)
    if category == "past the terminator":
        angle, height = rng.uniform(0, 2 * math.pi), rng.uniform(0.1, 0.3)
        to_light = _round([math.cos(angle), math.sin(angle), height])
    halfway = _unit([a + b for a, b in zip(_unit(to_light), _unit(to_viewer), strict=True)])
    centre = [h / halfway[2] for h in halfway]  # the normal of the highlight's peak, z = 1
    normals = _normals_about(rng, centre, tilt)
    if category == "past the terminator":  # one normal turned away from the light: N·L < 0
        away = height + rng.uniform(0.5, 1.0)
        normals[rng.randrange(3)] = _round([-away * math.cos(angle), -away * math.sin(angle), 1.0])
    vertices = _triangle(rng, at_vertex)
    if at_vertex:
        normals[0] = [0.0, 0.0, 1.0]
    kd = _round([rng.uniform(0.2, 0.8) for _ in "rgb"])
    model = _model(n, ks, r_plus_r0, specular, kd=kd)
    expansion = "vertex" if at_vertex else rng.choice(("vertex", "centroid"))
    if feature == "about the centroid":
        expansion = "centroid"
    label = f"{category}: {specular}, n = {n}, about {expansion}"
    return _case(
        label, vertices, normals, to_light, to_viewer, model, SIZE, SIZE, expansion, category
    )


def _dot(a, b) -> float:
    return sum(x * y for x, y in zip(a, b, strict=True))


def _past_the_terminator(case: Case) -> bool:
    """Whether some vertex normal turns away from the light (N . L < 0)."""
    return any(_dot(n, case.inputs["to_light"]) < 0 for n in case.inputs["normals"])


CASE_FEATURES = {
    "phong highlight": lambda case, reference: case.inputs["model"]["specular"] == "phong",
    "blinn highlight": lambda case, reference: case.inputs["model"]["specular"] == "blinn",
    "narrow highlight": lambda case, reference: case.inputs["model"]["n"] >= 40,
    "highlight at vertex U": lambda case, reference: (
        case.inputs["to_light"] == case.inputs["to_viewer"] == case.inputs["normals"][0]
    ),
    "past the terminator": lambda case, reference: _past_the_terminator(case),
    "about the centroid": lambda case, reference: case.inputs["expansion"] == "centroid",
}
"""Tests of the fast Phong cases' kinds: both specular terms, a narrow highlight (a steep
table), cos φ = 1 exactly at vertex U, a normal past the terminator, either expansion point."""


def _level(table, cos_phi, start, level) -> set[str]:
    """How the search found `level` for `cos_phi` (which branch of the step)."""
    found = {"a span's first sample (search)"} if start is None else set()
    if start is not None:
        found.add("walk up" if level > start else "walk down" if level < start else "level kept")
    if level == 0:
        found.add("below the table")
    if level == len(table):
        found.add("top of the table")
    return found


LEVEL_FEATURES = {
    name: lambda case, reference, name=name: any(
        name in _level(*args, level)
        for (args, _), level in zip(reference.arguments, reference.calls, strict=True)
    )
    for name in (
        "a span's first sample (search)",
        "walk up",
        "walk down",
        "level kept",
        "below the table",
        "top of the table",
    )
}
"""Tests of the level search's features: each branch (a binary search at a span's start, a walk
up, down or none from the previous level) and both ends of the table."""


LEVEL_SOLUTION = """\
def specular_level(table, cos_phi, start):
    if start is None:
        low, high = 0, len(table)
        while low < high:
            middle = (low + high) // 2
            if table[middle] <= cos_phi:
                low = middle + 1
            else:
                high = middle
        return low
    level = start
    while level < len(table) and table[level] <= cos_phi:
        level += 1
    while level > 0 and cos_phi < table[level - 1]:
        level -= 1
    return level
"""


_level_variant = functools.partial(edited_variant, LEVEL_SOLUTION)


IDEA = (
    "**Fast Phong shading** (Bishop & Weimer 1986; Wang 1989, ch. 3) shades a screen triangle "
    "without a square root or a power per pixel. Per channel the model is I = Ia ka + Ip / "
    "(r + r0) (kd cos θ + ks cos^n φ). Over the triangle the normal is linear in the pixel, so "
    "cos θ and cos φ (R·V for Phong, N·H for Blinn) are smooth functions of (x, y); fast Phong "
    "replaces each by its second-order Taylor polynomial about vertex U or the centroid, "
    "Q = T5 x² + T4 xy + T3 y² + T2 x + T1 y + T0 (x, y in pixels from the expansion point), "
    "and steps five of them along each span: cos θ, cos φ and the ambient + diffuse of each "
    "channel.\n\n"
    "The specular term ks Ip cos^n φ / (r + r0), in integer levels, is found in a **table** "
    "built once per surface: cos φ_j = (j / N)^(1/n) for j = 1..N, N = floor(Ip ks / "
    "(r + r0)), `table[j - 1]` = cos φ_j. The level is j when cos φ_j <= cos φ < cos φ_{j+1}: "
    "**the number of entries <= cos φ**, 0 below cos φ_1 and N from cos φ_N = 1 up (an "
    "approximated cos φ can overshoot 1). A sample's colour is clip(max(ambient + diffuse, "
    "Ia ka) + (level if cos θ > 0 else 0), 0, 255): past the terminator there is no "
    "highlight. Every covered sample emits a `fast_phong_pixel` event (the values and their "
    "differences, the level, the colour); scanviz: y up, pixel (x, y) sampled at its "
    "lower-left corner (x, y)."
)

register(
    Exercise(
        id="specular_level",
        number=20,
        title="The specular level by comparisons",
        stage="fast shading",
        kind="step",
        points=3,
        answer="specular_level",
        idea=IDEA
        + (
            "\n\nYour step is the look-up, once per sample. At a span's first sample (`start` "
            "is None) nothing is known: search the table, in ceil(log2(N + 1)) comparisons by "
            "bisection. Along a span cos φ changes little, so from the previous sample's level "
            "`start` walk up while the next entry is <= cos φ, or down while cos φ is below the "
            "current level's entry: usually 0 or 1 steps, but a narrow highlight moves the "
            "level by tens of entries between neighbours. The event's `comparisons` is the "
            "count the textbook search makes to reach your level; `level` and `color` are "
            "graded, then the triangle's colours."
        ),
        stub=(
            "def specular_level(table, cos_phi, start):\n"
            '    """table: cos φ_1..cos φ_N, a nondecreasing numpy float64 array of N entries\n'
            "    (N >= 0), table[j - 1] = cos φ_j, the last one 1.0; cos_phi: a sample's cos φ (a\n"
            "    float, possibly below cos φ_1, negative or above 1); start: the level of the\n"
            "    previous sample on this span (an int, 0 <= start <= N), or None at a span's\n"
            "    first sample.\n"
            "    Return the level, an int (119, not 119.0): the number of entries <= cos_phi\n"
            "    (0 <= level <= N), by a search when start is None, else by walking from\n"
            '    start."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=LEVEL_SOLUTION,
        call=call_with_step("specular_level", _shade),
        reference=specular_level,
        public=PUBLIC,
        generate=_fast_phong_case,
        **feature_tests({**CASE_FEATURES, **LEVEL_FEATURES}),
        variants=(
            _level_variant(
                "strict",
                "the level counts the entries <= cos φ: where cos φ equals cos φ_j exactly the "
                "level is j (cos φ = 1 is the top level N); counting entries < cos φ gives one "
                "less there",
                ("if table[middle] <= cos_phi:", "if table[middle] < cos_phi:"),
                ("and table[level] <= cos_phi:", "and table[level] < cos_phi:"),
                ("cos_phi < table[level - 1]:", "cos_phi <= table[level - 1]:"),
            ),
            _level_variant(
                "bisection_drops_entry",
                "when table[middle] > cos φ, middle may be the first entry above cos φ: keep it "
                "in the range (high = middle), so that table[:low] <= cos φ < table[high:] "
                "holds until low == high",
                ("                high = middle\n", "                high = middle - 1\n"),
            ),
            _level_variant(
                "walks_up_only",
                "past the highlight cos φ falls along the span: walk down too, while cos φ is "
                "below the current level's entry (cos φ < table[level - 1])",
                ("    while level > 0 and cos_phi < table[level - 1]:\n        level -= 1\n", ""),
            ),
            _level_variant(
                "one_entry_a_sample",
                "the level can move by more than one entry between neighbouring samples (a "
                "narrow highlight moves it by tens): keep walking until "
                "table[level - 1] <= cos φ < table[level]",
                ("    while level < len(table) and", "    if level < len(table) and"),
                ("    while level > 0 and", "    elif level > 0 and"),
            ),
        ),
        kinds=KINDS,
        step="specular_level",
        place=place_by_event("fast_phong_pixel", _sample),
        result=lambda shaded: shaded.colors,
        stepper=STEPPER,
    )
)


DIFFERENCE_SOLUTION = """\
def forward_difference(q, dq, t5):
    q_next = q + dq
    dq_next = dq + 2 * t5
    return q_next, dq_next
"""


_difference_variant = functools.partial(edited_variant, DIFFERENCE_SOLUTION)


register(
    Exercise(
        id="forward_difference",
        number=21,
        title="Forward differences along a span",
        stage="fast shading",
        kind="step",
        points=2,
        answer="forward_difference",
        idea=IDEA
        + (
            "\n\nYour step moves one quadratic one sample right. Its difference to the next "
            "sample, dQ(x) = Q(x + 1) - Q(x) = T5 (2x + 1) + T4 y + T2, is linear in x and "
            "grows by 2 T5 per sample, so Q(x + 1) = Q(x) + dQ(x) and dQ(x + 1) = dQ(x) + 2 T5: "
            "two additions per quadratic per sample. A span's first sample gets Q and dQ from "
            "the coefficients; after that only your step runs, five times a sample (cos θ, "
            "cos φ, then red, green and blue). Floats are compared to the bit: use exactly "
            "these two additions (2 T5 is exact), as the compiled kernel does."
        ),
        stub=(
            "def forward_difference(q, dq, t5):\n"
            '    """q: a quadratic Q = T5 x² + T4 xy + T3 y² + T2 x + T1 y + T0 at the current\n'
            "    sample; dq: its difference Q(x + 1) - Q(x) to the next sample; t5: its x²\n"
            "    coefficient T5 (three floats).\n"
            '    Return (q, dq) at the next sample: Q + dQ, and dQ + 2 T5."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=DIFFERENCE_SOLUTION,
        call=call_with_step("forward_difference", _shade),
        reference=forward_difference,
        public=PUBLIC,
        generate=_fast_phong_case,
        **feature_tests(CASE_FEATURES),
        variants=(
            _difference_variant(
                "difference_first",
                "Q(x + 1) = Q(x) + dQ(x) takes the difference of the current sample: add dQ to "
                "Q before stepping dQ by 2 T5, not after",
                (
                    "    q_next = q + dq\n    dq_next = dq + 2 * t5\n",
                    "    dq_next = dq + 2 * t5\n    q_next = q + dq_next\n",
                ),
            ),
            _difference_variant(
                "no_second_difference",
                "dQ is not constant: it is linear in x, T5 (2x + 1) + T4 y + T2, so it grows by "
                "2 T5 per sample (the second difference); without it Q is stepped as a line",
                ("dq_next = dq + 2 * t5", "dq_next = dq"),
            ),
            _difference_variant(
                "t5_once",
                "the second difference of T5 x² is T5 ((x + 2)² - 2 (x + 1)² + x²) = 2 T5: "
                "dQ grows by 2 T5 per sample, not T5",
                ("dq_next = dq + 2 * t5", "dq_next = dq + t5"),
            ),
        ),
        kinds=KINDS,
        step="forward_difference",
        place=_quadratic_of_call,
        result=lambda shaded: shaded.colors,
        rtol=0.0,  # the two additions are prescribed, so a right answer has the reference's bits
        stepper=STEPPER,
    )
)

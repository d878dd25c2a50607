"""Exercises on edge-function triangle rasterization (scanviz.raster.edgefn): ties, edge functions."""

from __future__ import annotations

import math
import random

import numpy as np

from ..raster.edgefn import edge_function, owns_boundary, triangle_samples
from .cases import call_with_step, grid_value
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

SIZE = 12  # the raster of the hidden cases
BITS = 2  # sub-pixel bits: a grid of 8 units per pixel keeps quarter-pixel inputs exact


def _cover(inputs, tracer) -> tuple[np.ndarray, list[np.ndarray]]:
    """Rasterize each triangle in order: (coverage counts (H, W), barycentric weights per triangle)."""
    width, height = inputs["width"], inputs["height"]
    counts = np.zeros((height, width), dtype=np.int64)
    weights = []
    for index, triangle in enumerate(inputs["triangles"]):
        found = triangle_samples(
            triangle,
            width,
            height,
            sample=inputs["sample"],
            subpixel_bits=BITS,
            trace=tracer,
            polygon=index,
        )
        counts[found.ys, found.xs] += 1
        weights.append(found.barycentric)
    return counts, weights


def _edge_of_call(index: int, trace: list) -> str:
    """Call k is edge k % 3 of the (k // 3)-th triangle set up."""
    setups = [e for e in trace if e.kind == "triangle_setup"]
    if index // 3 < len(setups):
        return f"triangle {setups[index // 3].polygon}, edge {index % 3}"
    return f"call {index + 1}"


def _case(label: str, triangles: list, width: int, height: int, sample: str = "corner") -> Case:
    return Case(label, {"triangles": triangles, "width": width, "height": height, "sample": sample})


def _lattice_point(rng: random.Random) -> list[int]:
    return [rng.randint(0, SIZE - 1), rng.randint(0, SIZE - 1)]


def _area2(triangle: list) -> float:
    (x0, y0), (x1, y1), (x2, y2) = triangle
    return (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)


FEATURES = (
    "shared edge",
    "horizontal edges",
    "integer vertices",
    "pixel centers",
    "quarter pixels",
)


def _triangles(rng: random.Random, feature: str) -> tuple[list, str]:
    """(triangles, sample) for one hidden case: shapes with many samples exactly on edges."""
    if feature == "shared edge":  # a quad split on its diagonal, in either winding
        x0, y0 = rng.randint(0, 3), rng.randint(0, 3)
        x1, y1 = x0 + rng.randint(3, 8), y0 + rng.randint(3, 8)
        quad = [[x0, y0], [x1, y0 + rng.randint(-1, 1)], [x1, y1], [x0 + rng.randint(-1, 1), y1]]
        if rng.random() < 0.5:
            quad.reverse()
        return [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]], "corner"
    if feature == "horizontal edges":
        x0, x1 = sorted(rng.sample(range(SIZE), 2))
        y0, y1 = sorted(rng.sample(range(SIZE), 2))
        apex = rng.randint(0, SIZE - 1)
        bottom_up = [[x0, y0], [x1, y0], [apex, y1]]
        top_down = [[x1, y1], [x0, y1], [apex, y0]]
        triangles = [bottom_up, top_down]
        return [t[::-1] if rng.random() < 0.5 else t for t in triangles], "corner"
    if feature == "integer vertices":
        return [[_lattice_point(rng) for _ in range(3)] for _ in range(rng.randint(1, 2))], "corner"
    if feature == "pixel centers":
        return [
            [[rng.randint(0, SIZE - 1) + 0.5, rng.randint(0, SIZE - 1) + 0.5] for _ in range(3)]
        ], "center"
    return [[[grid_value(rng, 0, SIZE), grid_value(rng, 0, SIZE)] for _ in range(3)]], rng.choice(
        ("corner", "center")
    )


_SHAPES = {  # the shapes of `_triangles` a feature is drawn from (others: any)
    "horizontal edge through samples": "horizontal edges",
    "vertical edge through samples": "horizontal edges",
    "shared edge": "shared edge",
    "sample at pixel centers": "pixel centers",
    "crosses the raster border": "shared edge",  # a quad big enough to cover samples across it
}


def _triangles_case(rng: random.Random, feature: str | None = None) -> Case:
    shape = _SHAPES.get(feature) or rng.choice(FEATURES)
    while True:
        triangles, sample = _triangles(rng, shape)
        if all(_area2(t) != 0 for t in triangles):
            break
    if feature == "vertical edge through samples":  # the horizontal edges' shapes, transposed
        triangles = [[[y, x] for x, y in t] for t in triangles]
    if feature in ("counter-clockwise", "clockwise"):  # the first triangle turned that way
        if (_area2(triangles[0]) > 0) != (feature == "counter-clockwise"):
            triangles[0] = triangles[0][::-1]
    if feature == "crosses the raster border":
        triangles = _across(rng, triangles)
    windings = {"counter-clockwise" if _area2(t) > 0 else "clockwise" for t in triangles}
    category = feature or f"{shape}, {' and '.join(sorted(windings))}"
    inputs = {"triangles": triangles, "width": SIZE, "height": SIZE, "sample": sample}
    return Case(category, inputs, category)


def _across(rng: random.Random, triangles: list) -> list:
    """`triangles` moved across one side of the raster by whole pixels: the farthest vertex
    1 pixel to half their extent beyond it."""
    axis, outward = rng.choice((0, 1)), rng.choice((-1, 1))
    values = [p[axis] for t in triangles for p in t]
    beyond = rng.randint(1, max(1, math.floor((max(values) - min(values)) / 2)))
    shift = -beyond - min(values) if outward < 0 else SIZE + beyond - max(values)
    return [
        [[c + shift if k == axis else c for k, c in enumerate(p)] for p in t] for t in triangles
    ]


def _edges(case: Case) -> list:
    return [(t[k], t[(k + 1) % 3]) for t in case.inputs["triangles"] for k in range(3)]


def _covered(case: Case, reference) -> bool:
    return reference.raster is not None and bool(np.asarray(reference.raster).any())


def _through_samples(case: Case, axis: int) -> bool:
    """Whether an edge along x (`axis` 1: horizontal) or y (0: vertical) lies on samples."""
    offset = 0.5 if case.inputs["sample"] == "center" else 0
    return any(
        a[axis] == b[axis]
        and (a[axis] - offset) % 1 == 0
        and math.ceil(min(a[1 - axis], b[1 - axis]) - offset)
        <= max(a[1 - axis], b[1 - axis]) - offset
        for a, b in _edges(case)
    )


def _shares_an_edge(case: Case) -> bool:
    edges = [frozenset(map(tuple, e)) for e in _edges(case)]
    return len(set(edges)) < len(edges)


TRIANGLE_FEATURES = {
    "counter-clockwise": lambda case, reference: any(
        _area2(t) > 0 for t in case.inputs["triangles"]
    ),
    "clockwise": lambda case, reference: any(_area2(t) < 0 for t in case.inputs["triangles"]),
    "horizontal edge through samples": lambda case, reference: _through_samples(case, 1),
    "vertical edge through samples": lambda case, reference: _through_samples(case, 0),
    "shared edge": lambda case, reference: _shares_an_edge(case) and _covered(case, reference),
    "sample at pixel centers": lambda case, reference: case.inputs["sample"] == "center",
    "crosses the raster border": lambda case, reference: (
        _covered(case, reference)
        and any(not 0 <= v <= SIZE for t in case.inputs["triangles"] for p in t for v in p)
    ),
}
"""Tests of the triangle exercises' features: both orientations (the sign of the edge functions
and of the ownership test), horizontal and vertical edges with samples on them (where the
ownership rule reads b, not a, and where a alone decides), an edge two triangles share (covered
once), the other sampling, and triangles across a side of the raster."""


CONVENTIONS = (
    "scanviz: y up; pixel (x, y) is sampled at its lower-left corner (x, y) (or its center "
    "with `sample='center'`); vertices are snapped to a sub-pixel grid of integers "
    "(here 8 units per pixel), so every test is exact."
)
STEPPER = (
    "from scanviz.widgets import scan_conversion_stepper\n"
    "# the same triangle scan-converted row by row: the same samples, the same ownership rule\n"
    "scan_conversion_stepper(CASE['triangles'][0], CASE['width'], CASE['height'], "
    "sample=CASE['sample'])"
)

# --- 6: the ownership rule on ties ---------------------------------------------------------

OWNERSHIP_SOLUTION = """\
def owns_boundary(a, b, orientation):
    leading = a if a != 0 else b
    return orientation * leading > 0
"""

OWNERSHIP_CASES = (
    _case(
        "square split on its diagonal, the second half clockwise",
        [[[1, 1], [7, 1], [7, 7]], [[1, 7], [7, 7], [1, 1]]],
        9,
        9,
    ),
    _case(
        "horizontal top edge clockwise, horizontal bottom edge counter-clockwise",
        [[[1, 6], [7, 6], [4, 0]], [[8, 1], [14, 1], [11, 7]]],
        15,
        8,
    ),
    _case(
        "two triangles sharing a vertical edge",
        [[[1, 1], [4, 1], [4, 7]], [[4, 1], [8, 4], [4, 7]]],
        9,
        8,
    ),
    _case(
        "pixel centers, center sampling",
        [[[0.5, 0.5], [6.5, 0.5], [0.5, 6.5]], [[6.5, 0.5], [6.5, 6.5], [0.5, 6.5]]],
        8,
        8,
        "center",
    ),
)

register(
    Exercise(
        id="ownership_ties",
        number=6,
        title="Who owns a sample on an edge",
        stage="edge functions",
        kind="step",
        points=3,
        answer="owns_boundary",
        idea=(
            "A sample p is inside a triangle when every edge function, signed so that the inner "
            "side is positive (times the orientation: +1 counter-clockwise, -1 clockwise), is "
            "positive. A sample exactly **on** an edge (E = 0) needs a tie rule, or triangles "
            "sharing that edge would both draw it (or neither would).\n\n"
            "scanviz decides p as the point `p + (eps, eps**2)` for an infinitesimal eps > 0: "
            "`E(p + (eps, eps**2)) = a eps + b eps**2` has the sign of `a`, or of `b` when "
            "`a == 0` (a horizontal edge). The sample is in when that sign is the inner side's: "
            "a pixel owns its **left** and **lower** borders (Direct3D's top-left rule, y "
            "flipped). " + CONVENTIONS
        ),
        stub=(
            "def owns_boundary(a, b, orientation):\n"
            '    """a, b: the coefficients of an edge function E(p) = a*px + b*py + c (ints);\n'
            "    orientation: +1 if the triangle is counter-clockwise, -1 if clockwise.\n"
            "    Return True if a sample exactly on this edge (E = 0) is inside the triangle\n"
            '    (scanviz: decide it as the sample moved to (px + eps, py + eps**2))."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=OWNERSHIP_SOLUTION,
        call=call_with_step("owns_boundary", _cover),
        reference=owns_boundary,
        public=OWNERSHIP_CASES,
        generate=_triangles_case,
        **feature_tests(TRIANGLE_FEATURES),
        variants=(
            edited_variant(
                OWNERSHIP_SOLUTION,
                "flipped",
                "the right and top edges are owned instead: a pixel owns its left and lower "
                "borders, i.e. the edges whose (a, b) leans to the inner side",
                ("orientation * leading > 0", "orientation * leading < 0"),
            ),
            edited_variant(
                OWNERSHIP_SOLUTION,
                "closed",
                "every boundary sample is inside: then two triangles sharing an edge both draw "
                "its samples; only the left and lower edges own theirs",
                ("return orientation * leading > 0", "return True"),
            ),
            edited_variant(
                OWNERSHIP_SOLUTION,
                "open",
                "no boundary sample is inside: then a sample on an edge shared by two triangles "
                "is drawn by neither (a crack); the left and lower edges own theirs",
                ("return orientation * leading > 0", "return False"),
            ),
            edited_variant(
                OWNERSHIP_SOLUTION,
                "ignores_orientation",
                "the orientation is ignored: for a clockwise triangle the inner side is where "
                "E < 0, so multiply by the orientation",
                ("orientation * leading > 0", "leading > 0"),
            ),
            edited_variant(
                OWNERSHIP_SOLUTION,
                "horizontal_never",
                "horizontal edges (a == 0) are never owned: the sample moves by eps**2 in y "
                "too, so a lower horizontal edge owns its samples (the sign of b decides)",
                ("leading = a if a != 0 else b", "leading = a"),
            ),
            edited_variant(
                OWNERSHIP_SOLUTION,
                "y_first",
                "b decides before a: the sample moves by eps in x and only eps**2 in y, so a "
                "decides and b only breaks the tie of a horizontal edge",
                ("leading = a if a != 0 else b", "leading = b if b != 0 else a"),
            ),
        ),
        kinds=("triangle_setup", "edge_function_row"),
        step="owns_boundary",
        place=_edge_of_call,
        result=lambda returned: returned[0],
        raster=lambda returned: returned[0] > 0,
        stepper=STEPPER,
    )
)

# --- 8: edge functions ---------------------------------------------------------------------

EDGE_SOLUTION = """\
def edge_function(start, end):
    (x0, y0), (x1, y1) = start, end
    a = y0 - y1
    b = x1 - x0
    c = x0 * y1 - x1 * y0
    return a, b, c
"""

EDGE_CASES = (
    _case("right triangle", [[[0, 0], [6, 0], [0, 5]]], 8, 7),
    _case("clockwise triangle", [[[1, 1], [2.5, 6.25], [7, 3.5]]], 9, 8),
    _case(
        "two triangles sharing an edge",
        [[[0.5, 0.25], [7.75, 1.5], [3.25, 6.5]], [[7.75, 1.5], [8.5, 7.25], [3.25, 6.5]]],
        10,
        8,
    ),
)

register(
    Exercise(
        id="edge_functions",
        number=8,
        title="Edge functions of a triangle",
        stage="edge functions",
        kind="step",
        points=3,
        answer="edge_function",
        idea=(
            "The directed edge from (x0, y0) to (x1, y1) has the **edge function** "
            "`E(p) = (x1 - x0)(py - y0) - (y1 - y0)(px - x0)`, twice the signed area of the "
            "triangle (start, end, p): positive left of the edge, zero on it, negative right "
            "of it. Written as `a px + b py + c`, it is evaluated incrementally: one sample "
            "right adds a, one row up adds b.\n\n"
            "A triangle's three edge functions sum to its doubled signed area, so the weight "
            "of vertex i is E of its opposite edge over that area: the **barycentric weights** "
            "come for free. " + CONVENTIONS
        ),
        stub=(
            "def edge_function(start, end):\n"
            '    """start = (x0, y0), end = (x1, y1): the edge\'s ends, ints on the sub-pixel grid.\n'
            "    Return (a, b, c), ints, with E(p) = a*px + b*py + c positive left of the edge\n"
            '    (seen from start toward end) and zero on it."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=EDGE_SOLUTION,
        call=call_with_step("edge_function", _cover),
        reference=edge_function,
        public=EDGE_CASES,
        generate=_triangles_case,
        **feature_tests(TRIANGLE_FEATURES),
        variants=(
            edited_variant(
                EDGE_SOLUTION,
                "sign_swapped",
                "E is negated (positive right of the edge): a = y0 - y1 and b = x1 - x0 make "
                "it positive on the left, where a counter-clockwise triangle's inside is",
                ("a = y0 - y1", "a = y1 - y0"),
                ("b = x1 - x0", "b = x0 - x1"),
                ("c = x0 * y1 - x1 * y0", "c = x1 * y0 - x0 * y1"),
            ),
            edited_variant(
                EDGE_SOLUTION,
                "c_wrong",
                "c has the wrong sign: E(start) must be 0, so c = -(a x0 + b y0) = x0 y1 - x1 y0",
                ("c = x0 * y1 - x1 * y0", "c = x1 * y0 - x0 * y1"),
            ),
            edited_variant(
                EDGE_SOLUTION,
                "a_b_swapped",
                "a and b are swapped: a multiplies px and is y0 - y1, b multiplies py and is "
                "x1 - x0 (the edge's direction turned by 90 degrees)",
                ("a = y0 - y1", "a = x1 - x0"),
                ("b = x1 - x0", "b = y0 - y1"),
            ),
        ),
        kinds=("triangle_setup", "edge_function_row"),
        step="edge_function",
        place=_edge_of_call,
        result=lambda returned: returned[1],
        raster=lambda returned: returned[0] > 0,
        stepper=STEPPER,
    )
)

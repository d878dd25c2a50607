"""Exercise on the z-buffer's depth test (scanviz.visibility.zbuffer), through `render`.

The cases are flat polygons in the UMBC slides' coordinates (x, y in pixels,
z a depth, smaller = nearer) seen 1:1 by an orthographic camera, as the
builtin ``umbc_zbuffer`` scene: display x, y are the case's x, y and the
depth the z-buffer compares is z / 16, exact in binary, so ties are exact.
"""

from __future__ import annotations

import random

import numpy as np

from ..pipeline import render
from ..scene import Scene
from ..scene.builtin import slide_scene
from ..visibility.zbuffer import depth_test
from .cases import call_with_step, grid_value, place_by_event, polygon
from .catalog import register
from .core import Case, Exercise, Variant, edited_variant, feature_tests

COLORS = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (1.0, 1.0, 0.0), (0.0, 1.0, 1.0))


def case_scene(inputs: dict) -> Scene:
    """The scene of a case: its polygons of (x, y, z) as flat colors, seen 1:1 from the front."""
    polygons = [np.array(vertices, float) for vertices in inputs["polygons"]]
    return slide_scene(polygons, inputs["width"], inputs["height"], colors=COLORS)


def _case(label: str, polygons: list, width: int, height: int, category: str = "") -> Case:
    return Case(label, {"polygons": polygons, "width": width, "height": height}, category)


def _rectangle(x0: float, y0: float, x1: float, y1: float, z: float) -> list:
    """The rectangle [x0, x1] x [y0, y1] at depth z, counter-clockwise from (x0, y0)."""
    return [[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]


def _render(inputs: dict, tracer):
    return render(
        case_scene(inputs), inputs["width"], inputs["height"], shading="flat", trace=tracer
    )


_pixel_of_call = place_by_event(
    "depth_test", lambda test: f"polygon {test.polygon} at pixel ({test.x}, {test.y})"
)


def _depths(rng: random.Random, vertices: list, flat: bool) -> list:
    """(x, y, z) of a polygon: constant depth on quarter units (ties, 0) or a gentle slope."""
    if flat:
        z = grid_value(rng, 0, 12)
        return [[x, y, z] for x, y in vertices]
    z0, dx, dy = grid_value(rng, 4, 8), rng.uniform(-0.4, 0.4), rng.uniform(-0.4, 0.4)
    return [[x, y, min(max(z0 + dx * x + dy * y, 0.0), 15.0)] for x, y in vertices]


CATEGORIES = ("flat, ties", "sloped, piercing", "mixed", "nearest first")
NEAR = 2.0**-24  # "near-equal depths": apart by this, exact in binary, far below a pixel's step


def _zbuffer_case(rng: random.Random, feature: str | None = None) -> Case:
    """2-4 polygons; a `feature` of `ZBUFFER_FEATURES` shapes their depths (or place) to have it."""
    width, height = rng.randint(6, 12), rng.randint(6, 12)
    category = feature if feature in CATEGORIES else rng.choice(CATEGORIES)
    if feature in ("tie", "empty sample"):
        category = "flat, ties"
    shapes = [polygon(rng, width, height) for _ in range(rng.randint(2, 4))]
    polygons = []
    for k, (_, vertices) in enumerate(shapes):
        flat = category in ("flat, ties", "nearest first") or (category == "mixed" and k % 2 == 0)
        polygons.append(_depths(rng, vertices, flat and category != "sloped, piercing"))
    if category == "flat, ties":  # some polygons at exactly the same depth
        for later in polygons[1:]:
            if rng.random() < 0.5:
                for vertex in later:
                    vertex[2] = polygons[0][0][2]
    if category == "nearest first":  # the first polygon on the near plane, z = 0
        for vertex in polygons[0]:
            vertex[2] = 0.0
    if feature == "near-equal depths":  # flat, each a hair nearer than the one drawn before ...
        z = grid_value(rng, 4, 8)
        polygons = [[[x, y, z - k * NEAR] for x, y, _ in p] for k, p in enumerate(polygons)]
        polygons[-1] = [[x, y, z + 1] for x, y, _ in polygons[-1]]  # ... but the last, behind
    if feature == "crosses the raster border":
        dx = rng.choice((-1, 1)) * round(width * rng.uniform(0.3, 0.6))
        polygons = [[[x + dx, y, z] for x, y, z in p] for p in polygons]
    shapes_seen = ", ".join(sorted({shape for shape, _ in shapes}))
    return _case(
        f"{feature or category}: {shapes_seen}", polygons, width, height, feature or category
    )


def _tests(reference) -> list[tuple[float, float | None]]:
    """(z, stored) of every depth test the reference made."""
    return [args for args, _ in reference.arguments]


def _some_test(check):
    return lambda case, reference: any(check(z, stored) for z, stored in _tests(reference))


ZBUFFER_FEATURES = {
    "empty sample": _some_test(lambda z, stored: stored is None),
    "nearer fragment": _some_test(lambda z, stored: stored is not None and z < stored),
    "farther fragment": _some_test(lambda z, stored: stored is not None and z > stored),
    "tie": _some_test(lambda z, stored: z == stored),
    "near-equal depths": _some_test(lambda z, stored: stored is not None and 0 < stored - z < 1e-6),
    "nearest first": _some_test(lambda z, stored: stored == 0.0 and z > 0),
    "crosses the raster border": lambda case, reference: (
        any(not 0 <= v[0] <= case.inputs["width"] for p in case.inputs["polygons"] for v in p)
        and bool(_tests(reference))
    ),
}
"""Tests of the depth test's features: each of its branches (an empty sample, a nearer, a farther
fragment, a tie), depths a hair apart (which a tolerance gets wrong), a stored depth of 0 (which
`not stored` takes for empty), and polygons across the raster's side."""


DEPTH_TEST_SOLUTION = """\
def depth_test(z, stored):
    if stored is None:
        return True
    return z < stored
"""


def _depth_variant(name: str, hint: str, old: str, new: str) -> Variant:
    return edited_variant(DEPTH_TEST_SOLUTION, name, hint, (old, new))


register(
    Exercise(
        id="zbuffer_depth",
        number=10,
        title="The z-buffer's depth test",
        stage="visibility",
        kind="step",
        points=2,
        answer="depth_test",
        idea=(
            "The z-buffer (Catmull) draws the polygons in any order and keeps, per sample, the "
            "nearest fragment so far. Each polygon's depth is interpolated along its spans; at "
            "every sample it covers, the **depth test** compares the fragment's depth z with "
            "the depth stored there and writes the fragment only if it is nearer.\n\n"
            "In scanviz **smaller z is nearer**. The buffer starts empty (+inf: here `stored` "
            "is None) and any fragment wins an empty sample. On a **tie** the stored fragment "
            "stays: the earlier polygon keeps the sample."
        ),
        stub=(
            "def depth_test(z, stored):\n"
            '    """z: the incoming fragment\'s depth (float, smaller is nearer).\n'
            "    stored: the depth stored at that sample (float), or None if nothing was drawn\n"
            "    there yet.\n"
            "    Return True if the fragment is written (it is nearer than the stored one, or the\n"
            '    sample is empty), False if it is hidden; on a tie the stored fragment stays."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=DEPTH_TEST_SOLUTION,
        call=call_with_step("depth_test", _render),
        reference=depth_test,
        public=(
            _case(
                "the UMBC slide: a triangle piercing another",
                [
                    [[1, 1, 5], [7, 7, 5], [1, 7, 5]],
                    _rectangle(3, 5, 10, 9, 9),
                    [[2, 6, 3], [2, 3, 8], [7, 3, 3]],
                ],
                12,
                10,
            ),
            _case(
                "two overlapping squares at the same depth, a third behind",
                [_rectangle(1, 1, 5, 5, 8), _rectangle(3, 3, 7, 7, 8), _rectangle(2, 2, 6, 6, 12)],
                8,
                8,
            ),
            _case(
                "a square on the near plane z = 0, then squares behind and before the next",
                [
                    _rectangle(1, 1, 4, 4, 0),
                    _rectangle(3, 3, 7, 7, 4),
                    _rectangle(6, 1, 8, 5, 6),
                    _rectangle(4, 6, 6, 8, 2),
                ],
                8,
                8,
            ),
            _case(
                "a square a hair (2^-24) nearer than the one drawn before it, a third behind",
                [
                    _rectangle(1, 1, 6, 6, 6),
                    _rectangle(3, 2, 8, 7, 6 - 2**-24),
                    _rectangle(2, 4, 7, 7.5, 9),
                ],
                9,
                8,
            ),
        ),
        generate=_zbuffer_case,
        **feature_tests(ZBUFFER_FEATURES),
        variants=(
            _depth_variant(
                "no_depth_test",
                "every fragment is written, so the last polygon drawn wins (the painter's order): "
                "write only if z < stored",
                "    return z < stored\n",
                "    return True\n",
            ),
            _depth_variant(
                "swapped_comparison",
                "smaller z is nearer in scanviz: write when z < stored, not z > stored",
                "return z < stored",
                "return z > stored",
            ),
            _depth_variant(
                "ties_to_later",
                "on a tie the stored fragment stays (the earlier polygon keeps the sample): "
                "z < stored, not z <= stored",
                "return z < stored",
                "return z <= stored",
            ),
            _depth_variant(
                "empty_never_written",
                "an empty sample (stored None, the buffer's +inf) takes any fragment: return True",
                "    if stored is None:\n        return True\n",
                "    if stored is None:\n        return False\n",
            ),
            _depth_variant(
                "tolerance",
                "a tolerance: a fragment nearer by less than it is still nearer (depths a hair "
                "apart are two surfaces); compare z < stored exactly",
                "return z < stored",
                "return z < stored - 1e-6",
            ),
            _depth_variant(
                "zero_depth_as_empty",
                "`not stored` is also true for a stored depth of 0.0 (the near plane): test "
                "`stored is None` for an empty sample",
                "if stored is None:",
                "if not stored:",
            ),
        ),
        kinds=("depth_test",),
        step="depth_test",
        place=_pixel_of_call,
        result=lambda result: result.polygon.tolist(),
        raster=lambda result: result.polygon >= 0,
        stepper=(
            "from scanviz.exercises.zbuffer import case_scene\n"
            "from scanviz.widgets import zbuffer_stepper\n"
            "zbuffer_stepper(case_scene(CASE), CASE['width'], CASE['height'], shading='flat')"
        ),
    )
)

"""Exercise on incremental interpolation along a span (scanviz.raster.interpolate)."""

from __future__ import annotations

import functools
import math
import random

from ..raster.interpolate import span_step
from ..visibility.zbuffer import ScreenPolygons, zbuffer
from .cases import call_with_step, grid_value
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

SIZE = 16  # the raster of the hidden cases


def _render(inputs, tracer):
    scene = ScreenPolygons.from_polygons(inputs["polygons"], inputs["colors"], inputs["inv_w"])
    return zbuffer(
        scene,
        inputs["width"],
        inputs["height"],
        perspective=inputs["inv_w"] is not None,
        trace=tracer,
    )


def _sample_of_call(index: int, trace: list) -> str:
    """Call k computes the k-th sample after the first of a span, in the order spans were traced."""
    for span in (e for e in trace if e.kind == "span_values"):
        stepped = span.x_end - span.x_start - 1
        if index < stepped:
            polygon = f"polygon {span.polygon}, " if span.polygon else ""
            return f"{polygon}pixel ({span.x_start + 1 + index}, {span.y})"
        index -= stepped
    return f"call {index + 1}"


def _case(label: str, polygons: list, colors: list, width: int, height: int, inv_w=None) -> Case:
    inputs = {
        "polygons": polygons,
        "colors": colors,
        "inv_w": inv_w,
        "width": width,
        "height": height,
    }
    return Case(label, inputs)


def _polygon(rng: random.Random, wide: bool) -> list:
    """A triangle or a quad (convex, either winding) with depths in [0, 1]; `wide` spans the raster."""
    if wide:
        y0 = grid_value(rng, 0, SIZE / 2)
        top = (grid_value(rng, 0, SIZE), grid_value(rng, y0 + 2, SIZE))
        corners = [(0.25, y0), (SIZE - 0.25, y0 + grid_value(rng, 0, 2)), top]
    else:
        cx, cy, radius = rng.uniform(5, SIZE - 5), rng.uniform(5, SIZE - 5), rng.uniform(3, 5)
        angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(rng.choice((3, 4))))
        corners = [
            (round((cx + radius * math.cos(a)) * 4) / 4, round((cy + radius * math.sin(a)) * 4) / 4)
            for a in angles
        ]
    if rng.random() < 0.5:
        corners.reverse()
    return [[x, y, round(rng.uniform(0, 1), 3)] for x, y in corners]


def _color(rng: random.Random) -> list[float]:
    return [round(rng.uniform(0, 1), 3) for _ in range(3)]


CATEGORIES = ("one polygon", "overlapping polygons", "wide spans", "perspective-correct")


def _interpolation_case(rng: random.Random, feature: str | None = None) -> Case:
    """One or two polygons; a `feature` of `INTERPOLATION_FEATURES` picks the kind that has it."""
    category = feature if feature in CATEGORIES else rng.choice(CATEGORIES)
    count = 2 if category == "overlapping polygons" else 1
    polygons = [_polygon(rng, category == "wide spans") for _ in range(count)]
    if feature == "crosses the raster border":
        dx = rng.choice((-1, 1)) * round(SIZE * rng.uniform(0.3, 0.5))
        polygons = [[[x + dx, y, z] for x, y, z in p] for p in polygons]
    colors = [[_color(rng) for _ in polygon] for polygon in polygons]
    inv_w = None
    if category == "perspective-correct":
        inv_w = [[round(rng.uniform(0.2, 1), 3) for _ in polygon] for polygon in polygons]
    inputs = {
        "polygons": polygons,
        "colors": colors,
        "inv_w": inv_w,
        "width": SIZE,
        "height": SIZE,
    }
    return Case(feature or category, inputs, feature or category)


def _steps(reference) -> list[tuple]:
    return [args for args, _ in reference.arguments]


INTERPOLATION_FEATURES = {
    "wide spans": lambda case, reference: any(
        e.x_end - e.x_start > SIZE // 2 for e in reference.trace if e.kind == "span_values"
    ),
    "overlapping polygons": lambda case, reference: len(case.inputs["polygons"]) > 1,
    "perspective-correct": lambda case, reference: case.inputs["inv_w"] is not None,
    "a rounding error carried": lambda case, reference: any(
        carry != 0 for _, carry, *_ in _steps(reference)
    ),
    "crosses the raster border": lambda case, reference: (
        bool(_steps(reference))
        and any(not 0 <= v[0] <= SIZE for p in case.inputs["polygons"] for v in p)
    ),
}
"""Tests of the span step's features: long spans (where an uncompensated sum drifts), a carry
that is not 0, two polygons, 1/w channels, and polygons across the raster's side."""


SOLUTION = """\
def span_step(z, carry, values, dzdx, dvdx):
    corrected = dzdx - carry
    new_z = z + corrected
    carry = (new_z - z) - corrected
    return new_z, carry, tuple(v + d for v, d in zip(values, dvdx))
"""


_variant = functools.partial(edited_variant, SOLUTION)


RED, GREEN, BLUE = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]

register(
    Exercise(
        id="span_interpolation",
        number=9,
        title="Incremental interpolation along a span",
        stage="interpolation",
        kind="step",
        points=3,
        answer="span_step",
        idea=(
            "Along a span, depth and vertex values (here colors) are linear in x, so the next "
            "sample's value is the current one plus its **d/dx**: `v += dv/dx`, one addition "
            "per value per sample. The span's first sample gets its values from the two edge "
            "crossings; after that only the step runs.\n\n"
            "Each float addition rounds, and n of them drift by up to n ulps of z: too much for "
            "depths packed near 1. scanviz steps the depth with **Kahan's compensated sum**: it "
            "keeps the rounding error of each addition in a `carry` and subtracts it from the "
            "next step (`corrected = dzdx - carry`, `new_z = z + corrected`, `carry = (new_z - "
            "z) - corrected`); the values use plain additions. Floats are compared to the bit: "
            "the same operations in the same order give the same bits. scanviz: y up, pixel "
            "(x, y) sampled at its lower-left corner (x, y)."
        ),
        stub=(
            "def span_step(z, carry, values, dzdx, dvdx):\n"
            '    """One sample to the right along a span. z: the depth at the current sample;\n'
            "    carry: the rounding error kept from the previous depth step (0.0 at the span's\n"
            "    start); values: the current sample's values, a tuple of floats; dzdx, dvdx:\n"
            "    their steps per pixel (a float, and a tuple of floats like values).\n"
            "    Return (z, carry, values) at the next sample: z by Kahan's compensated sum,\n"
            '    each value by a plain addition of its step."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=SOLUTION,
        call=call_with_step("span_step", _render),
        reference=span_step,
        public=(
            _case(
                "Gouraud triangle",
                [[[0.5, 0.5, 0.2], [9.5, 1.25, 0.9], [3.25, 8.5, 0.55]]],
                [[RED, GREEN, BLUE]],
                11,
                10,
            ),
            _case(
                "a wide span, depth near 1",
                [[[0.25, 0.5, 0.999], [15.75, 1.0, 0.9137], [8.25, 3.5, 0.95]]],
                [[RED, GREEN, BLUE]],
                16,
                4,
            ),
            _case(
                "two overlapping triangles",
                [
                    [[0.5, 0.5, 0.3], [11.5, 2.25, 0.7], [4.25, 9.5, 0.4]],
                    [[1.5, 8.5, 0.1], [3.75, 1.25, 0.9], [11.25, 7.75, 0.35]],
                ],
                [[RED, GREEN, BLUE], [[0.9, 0.8, 0.1], [0.2, 0.3, 0.4], [0.6, 0.1, 0.7]]],
                12,
                10,
            ),
            _case(
                "perspective-correct triangle",
                [[[0.5, 0.5, 0.25], [10.25, 2.5, 0.75], [2.75, 9.25, 0.5]]],
                [[RED, GREEN, BLUE]],
                11,
                10,
                inv_w=[[1.0, 0.25, 0.6]],
            ),
        ),
        generate=_interpolation_case,
        **feature_tests(INTERPOLATION_FEATURES),
        variants=(
            _variant(
                "uncompensated",
                "the depth is stepped by a plain z + dzdx: its rounding errors pile up along "
                "the span; keep each step's error in the carry and subtract it from the next",
                (
                    "    corrected = dzdx - carry\n    new_z = z + corrected\n"
                    "    carry = (new_z - z) - corrected\n",
                    "    new_z = z + dzdx\n    carry = 0.0\n",
                ),
            ),
            _variant(
                "carry_added",
                "the carry is added back instead of subtracted: it is the part of the last step "
                "that was rounded in too much, so corrected = dzdx - carry",
                ("corrected = dzdx - carry", "corrected = dzdx + carry"),
            ),
            _variant(
                "values_by_depth_slope",
                "the values are stepped by the depth's slope dz/dx: each value has its own "
                "step, dvdx[k]",
                ("tuple(v + d for v, d in zip(values, dvdx))", "tuple(v + dzdx for v in values)"),
            ),
            _variant(
                "values_not_stepped",
                "the values are not stepped: they stay at the span's first sample; add each "
                "value's d/dx at every sample",
                ("tuple(v + d for v, d in zip(values, dvdx))", "tuple(values)"),
            ),
        ),
        kinds=("span_values", "depth_test"),
        step="span_step",
        place=_sample_of_call,
        result=lambda returned: returned.values,
        rtol=0.0,  # the operations are prescribed, so a right answer has the reference's bits
        stepper=(
            "from scanviz.trace import Recorder\n"
            "from scanviz.visibility.zbuffer import ScreenPolygons, zbuffer\n"
            "from scanviz.widgets import InterpolationView, Stepper\n"
            "scene = ScreenPolygons.from_polygons(CASE['polygons'], CASE['colors'], CASE['inv_w'])\n"
            "kinds = ['polygon_setup', 'edge_values', 'span_values']\n"
            "result = zbuffer(scene, CASE['width'], CASE['height'], "
            "perspective=CASE['inv_w'] is not None, trace=Recorder(kinds))\n"
            "Stepper(result.trace, [InterpolationView(result.trace, result.values.clip(0, 1))])"
        ),
    )
)

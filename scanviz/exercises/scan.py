"""Exercises on polygon scan conversion (scanviz.raster.scanline): ET, AET, spans."""

from __future__ import annotations

import random

from ..raster import scan_convert
from ..raster.scanline import span_rule
from .cases import polygon
from .catalog import register
from .core import Case, Exercise, Variant


def _scan_with_span_rule(fn, inputs, tracer):
    from .. import steps

    with steps.using(span_rule=fn):
        return scan_convert(
            inputs["polygon"], inputs["width"], inputs["height"], rule=inputs["rule"], trace=tracer
        )


def _row_of_call(index: int, trace: list) -> str:
    rows = [e.y for e in trace if e.kind == "aet_sorted"]
    return f"row {rows[index]}" if index < len(rows) else f"call {index + 1}"


def _span_case(rng: random.Random) -> Case:
    width, height = rng.randint(6, 12), rng.randint(6, 12)
    feature, vertices = polygon(rng, width, height)
    rule = rng.choice(("nonzero", "evenodd"))
    return Case(
        f"{feature}, {rule}",
        {"polygon": vertices, "width": width, "height": height, "rule": rule},
        f"{feature}, {rule}",
    )


SPAN_RULE_SOLUTION = '''\
import math

def span_rule(crossings, rule):
    spans = []
    winding = 0
    for (x_in, step), (x_out, _) in zip(crossings, crossings[1:]):
        winding += step
        inside = winding % 2 == 1 if rule == "evenodd" else winding != 0
        start, end = math.ceil(x_in), math.ceil(x_out)
        if inside and start < end:
            spans.append((start, end, winding))
    return spans
'''


def _span_variant(name: str, hint: str, old: str, new: str) -> Variant:
    assert old in SPAN_RULE_SOLUTION, old
    return Variant(name, hint, SPAN_RULE_SOLUTION.replace(old, new))


register(
    Exercise(
        id="span_rule",
        number=5,
        title="The span rule with winding numbers",
        stage="scan conversion",
        kind="step",
        points=4,
        answer="span_rule",
        idea=(
            "After the AET of a row is sorted, walk it left to right keeping a **winding count**: "
            "each crossing adds its edge's winding (+1 or -1). Between two consecutive crossings "
            "the row is inside when the count is nonzero (`nonzero` rule) or odd (`evenodd`).\n\n"
            "A sample at integer x belongs to the span when `x_in <= x < x_out`: the span is "
            "the half-open `[ceil(x_in), ceil(x_out))`, so two polygons sharing an edge never "
            "both own a sample on it."
        ),
        stub=(
            "def span_rule(crossings, rule):\n"
            '    """crossings: [(x, winding), ...] sorted by x (x is a Fraction); rule: "nonzero"'
            ' or "evenodd".\n'
            '    Return [(x_start, x_end, winding), ...]: the inside runs, half-open, in order."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=SPAN_RULE_SOLUTION,
        call=_scan_with_span_rule,
        reference=span_rule,
        public=(
            Case(
                "triangle",
                {"polygon": [[0, 0], [6, 0], [6, 5]], "width": 8, "height": 6, "rule": "nonzero"},
            ),
            Case(
                "pentagram, nonzero",
                {
                    "polygon": [[4, 0], [6.5, 7.5], [0, 2.75], [8, 2.75], [1.5, 7.5]],
                    "width": 9, "height": 8, "rule": "nonzero",
                },
            ),
            Case(
                "pentagram, evenodd",
                {
                    "polygon": [[4, 0], [6.5, 7.5], [0, 2.75], [8, 2.75], [1.5, 7.5]],
                    "width": 9, "height": 8, "rule": "evenodd",
                },
            ),
            Case(
                "clockwise square on pixel centers",
                {"polygon": [[1.5, 1.5], [1.5, 5.5], [5.5, 5.5], [5.5, 1.5]],
                 "width": 7, "height": 7, "rule": "nonzero"},
            ),
        ),
        generate=_span_case,
        variants=(
            _span_variant(
                "floor_for_ceil",
                "floor instead of ceil: a span starts at the first sample x >= x_in, i.e. ceil(x_in)",
                "start, end = math.ceil(x_in), math.ceil(x_out)",
                "start, end = math.floor(x_in), math.floor(x_out)",
            ),
            _span_variant(
                "closed_span",
                "a closed span [x_in, x_out]: the right end is exclusive, x_end = ceil(x_out)",
                "start, end = math.ceil(x_in), math.ceil(x_out)",
                "start, end = math.ceil(x_in), math.floor(x_out) + 1",
            ),
            _span_variant(
                "round_for_ceil",
                "rounding to the nearest integer: a sample is inside only if x_in <= x, so use ceil",
                "start, end = math.ceil(x_in), math.ceil(x_out)",
                "start, end = round(x_in), round(x_out)",
            ),
            _span_variant(
                "positive_winding_only",
                "inside only when the count is positive: clockwise polygons have negative "
                "winding numbers; the nonzero rule tests winding != 0",
                'else winding != 0',
                'else winding > 0',
            ),
            _span_variant(
                "parity_always",
                "the even-odd test used for both rules: under 'nonzero' an overlap with "
                "winding 2 is inside",
                'inside = winding % 2 == 1 if rule == "evenodd" else winding != 0',
                "inside = winding % 2 == 1",
            ),
            _span_variant(
                "pairs_only",
                "taking crossings in pairs (0-1, 2-3, ...) ignores the winding count; "
                "walk every consecutive pair and keep the count",
                "for (x_in, step), (x_out, _) in zip(crossings, crossings[1:]):",
                "for (x_in, step), (x_out, _) in zip(crossings[::2], crossings[1::2]):",
            ),
        ),
        kinds=("aet_sorted", "span"),
        step="span_rule",
        place=_row_of_call,
        raster=lambda result: result.mask,
        stepper=(
            "from scanviz.widgets import scan_conversion_stepper\n"
            "scan_conversion_stepper(CASE['polygon'], CASE['width'], CASE['height'], rule=CASE['rule'])"
        ),
        banned=("scanviz.raster.scanline", "span_rule"),
    )
)

"""Exercises on polygon scan conversion (scanviz.raster.scanline): ET, AET, spans, the loop.

A student's ``edge_table_entry`` or ``aet_update`` is installed with `steps.using`
and so reaches the reference loop through its check (`.scan_checks`).
"""

from __future__ import annotations

import functools
import json
import math
import random
from fractions import Fraction

import numpy as np

from ..raster import scan_convert
from ..raster.scanline import EdgeEntry, aet_update, edge_table_entry, span_rule
from ..trace import Recorder
from .cases import call_with_step, place_by_event, polygon, star
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

IDEA_CONVENTIONS = (
    "scanviz: y up, pixel (x, y) is the unit square sampled at its lower-left corner (x, y), "
    "so sample rows are the integer y; an edge crosses row y when ymin <= y < ymax (half-open)."
)


def _scan(inputs: dict, tracer):
    """The scan conversion of the case's polygon."""
    return scan_convert(
        inputs["polygon"], inputs["width"], inputs["height"], rule=inputs["rule"], trace=tracer
    )


def _case(label: str, vertices: list, width: int, height: int, rule: str = "nonzero") -> Case:
    return Case(label, {"polygon": vertices, "width": width, "height": height, "rule": rule})


UMBC = _case("the slide polygon (UMBC)", [[4, 1], [1, 11], [9, 5], [12, 8], [12, 1]], 14, 13)
OFF_GRID = _case(
    "triangle off the sample rows", [[1, 0.5], [7, 2.25], [3.5, 6.75]], 8, 8, "evenodd"
)
PENTAGRAM = _case(
    "pentagram, nonzero", [[4, 0], [6.5, 7.5], [0, 2.75], [8, 2.75], [1.5, 7.5]], 9, 8
)
BELOW = _case(
    "clockwise, crossing the bottom of the raster",
    [[0.5, -1.5], [2, 5.75], [6.5, 3], [5, -0.25]],
    8,
    7,
)
BESIDE = _case(
    "crossing the left, right and top sides of the raster",
    [[-2.5, 1.25], [9.75, 2.5], [4, 8.5]],
    8,
    7,
    "evenodd",
)
STAR_7_3 = _case(
    "{7/3} star: winding 3 at the centre",
    [[11.5, 6.0], [1.0, 8.5], [9.5, 1.75], [4.75, 11.25], [4.75, 0.75], [9.5, 10.25], [1.0, 3.5]],
    12,
    12,
)

STEPPER = (
    "from scanviz.widgets import scan_conversion_stepper\n"
    "scan_conversion_stepper(CASE['polygon'], CASE['width'], CASE['height'], rule=CASE['rule'])"
)

# --- the hidden cases of every scan exercise ----------------------------------------------

LARGE = ("convex", "concave")  # shapes wide and tall enough for a side of the raster to cut
_KINDS = {  # (kinds, grid step) of the polygon a feature's case is drawn from; others: any
    "left of column 0": (LARGE, 0.25),
    "crosses the raster border": (LARGE, 0.25),
    "below row 0": (LARGE, 0.25),
    "above the top row": (LARGE, 0.25),
    "clockwise, nonzero": (LARGE, 0.25),
    "vertex between rows": (LARGE, 0.25),
    "overlap, nonzero": (("concave",), 0.25),
    "overlap, evenodd": (("concave",), 0.25),
    "empty run": (("concave",), 0.25),
    "edges cross": (("concave",), 0.25),
    "crossing on a sample": (LARGE, 1),  # vertices on samples: edges start on them
    "equal x in the AET": (LARGE, 1),
    "edge ends on a row": (LARGE, 1),
    "horizontal edge on a row": (("horizontal edges",), 1),
}
_SIDES = {  # the raster sides a feature's polygon is moved across
    "left of column 0": ("left",),
    "crosses the raster border": ("left", "right"),
    "below row 0": ("bottom",),
    "above the top row": ("top",),
}
_RULES = {
    "winding 3 or more": "nonzero",
    "clockwise, nonzero": "nonzero",
    "overlap, nonzero": "nonzero",
    "overlap, evenodd": "evenodd",
}


def _span_case(rng: random.Random, feature: str | None = None) -> Case:
    """A polygon, a raster and a rule; a `feature` of `SCAN_FEATURES` shapes them to have it."""
    width, height = rng.randint(6, 12), rng.randint(6, 12)
    rule = _RULES.get(feature) or rng.choice(("nonzero", "evenodd"))
    if feature == "winding 3 or more":
        center = (
            rng.randint(width // 2 - 1, width // 2 + 1),
            rng.randint(height // 2 - 1, height // 2 + 1),
        )
        radius = min(width, height) / 2 * rng.uniform(0.7, 0.95)  # the centre sample: winding 3
        shape, vertices = "{7/3} star", star(rng, center, radius, 7, turn=3)
    elif feature == "slope not a binary fraction":
        shape, vertices = "triangle", _tall_triangle(rng, width, height)
    elif feature in _KINDS:
        kinds, step = _KINDS[feature]
        shape, vertices = polygon(rng, width, height, rng.choice(kinds), step)
        while kinds == LARGE and _extent(vertices) < 3:  # random angles can bunch up
            shape, vertices = polygon(rng, width, height, rng.choice(kinds), step)
    else:
        shape, vertices = polygon(rng, width, height)
    if feature == "equal x in the AET":
        vertices = _one_lowest(vertices)
    if feature == "clockwise, nonzero" or rng.random() < 0.3:
        vertices = vertices[::-1]
    if feature in _SIDES:
        vertices = _across(rng, vertices, rng.choice(_SIDES[feature]), width, height)
    elif feature is None and rng.random() < 0.2:
        side = rng.choice(("left", "right", "bottom", "top"))
        vertices = _across(rng, vertices, side, width, height)
    category = feature or f"{shape}, {rule}"
    inputs = {"polygon": vertices, "width": width, "height": height, "rule": rule}
    return Case(category, inputs, category)


def _across(rng: random.Random, vertices: list, side: str, width: int, height: int) -> list:
    """`vertices` moved by quarter pixels across one side of the raster, partly inside.

    "left" or "right": the widest first (last) inside run of a row starts a sample or more
    left of column 0 (ends right of column width - 1), holding samples on both sides;
    "bottom" or "top": the edge spanning most rows crosses row 0 from a row or more below it,
    between two rows (crosses the top row from a row inside).
    """
    if side in ("left", "right"):
        ys = [y for _, y in vertices]
        rows = [_crossings(vertices, y) for y in range(math.ceil(min(ys)), math.ceil(max(ys)))]
        rows = [xs for xs in rows if len(xs) > 1] or [sorted(x for x, _ in vertices)]  # no row
        if side == "left":
            xs = max(rows, key=lambda xs: xs[1] - xs[0])
            shift = -(rng.randint(1, max(1, math.floor(xs[1] - xs[0] - 0.5))) + 0.5) - xs[0]
        else:
            xs = max(rows, key=lambda xs: xs[-1] - xs[-2])
            shift = width + rng.randint(0, max(0, math.floor(xs[-1] - xs[-2] - 2))) + 0.5 - xs[-1]
        return [[x + round(shift * 4) / 4, y] for x, y in vertices]
    edges = zip(vertices, vertices[1:] + vertices[:1], strict=True)
    low, high = max((sorted((a[1], b[1])) for a, b in edges), key=lambda e: e[1] - e[0])
    half = math.floor((high - low) / 2)
    rows = rng.randint(1, max(1, half)) if side == "bottom" else rng.randint(0, max(0, half - 1))
    beyond = rows + rng.choice((0.25, 0.5, 0.75))
    shift = -beyond - low if side == "bottom" else height + beyond - high
    return [[x, y + shift] for x, y in vertices]


def _tall_triangle(rng: random.Random, width: int, height: int) -> list:
    """A triangle on samples with an edge 3 or 5 rows tall and not a multiple of that across:
    its x steps by thirds or fifths, which no binary fraction holds."""
    rise = rng.choice((3, 5))
    run = rng.choice([d for d in range(-5, 6) if d % rise])
    x0, y0 = rng.randint(max(0, -run), width - 1 - max(0, run)), rng.randint(0, height - 1 - rise)
    t = rng.randint(0, rise)  # the third vertex 2 to 4 samples beside the edge's row t
    third = [x0 + round(run * t / rise) + rng.choice((-1, 1)) * rng.randint(2, 4), y0 + t]
    return [[x0, y0], [x0 + run, y0 + rise], third]


def _one_lowest(vertices: list) -> list:
    """`vertices` with the first lowest one alone on its row (the others there one row up):
    the two edges from it enter the AET at the same x."""
    low = min(y for _, y in vertices)
    first = next(k for k, (_, y) in enumerate(vertices) if y == low)
    return [[x, y + (y == low and k != first)] for k, (x, y) in enumerate(vertices)]


def _extent(vertices: list) -> float:
    """The smaller of the polygon's width and height."""
    xs, ys = zip(*vertices, strict=True)
    return min(max(xs) - min(xs), max(ys) - min(ys))


def _crossings(vertices: list, y: float) -> list[float]:
    """The sorted x where the polygon's edges cross the line y (each edge for ymin <= y < ymax)."""
    xs = [
        x0 + (x1 - x0) * (y - y0) / (y1 - y0)
        for (x0, y0), (x1, y1) in zip(vertices, vertices[1:] + vertices[:1], strict=True)
        if min(y0, y1) <= y < max(y0, y1)
    ]
    return sorted(xs)


@functools.lru_cache(maxsize=1024)
def _traced(key: str) -> tuple:
    """Every event of the reference's scan conversion of a case (its inputs as JSON)."""
    inputs = json.loads(key)
    recorder = Recorder()
    _scan(inputs, recorder)
    return tuple(recorder.trace())


def _events(case: Case, kind: str) -> list:
    return [e for e in _traced(json.dumps(dict(case.inputs), sort_keys=True)) if e.kind == kind]


def _intervals(case: Case) -> list[tuple[Fraction, Fraction, int]]:
    """(x_in, x_out, winding) between consecutive crossings of every row's AET."""
    runs = []
    for row in _events(case, "aet_sorted"):
        winding = 0
        for left, right in zip(row.entries, row.entries[1:], strict=False):
            winding += left.winding
            runs.append((left.x_exact, right.x_exact, winding))
    return runs


def _inside(case: Case, winding: int) -> bool:
    return winding % 2 == 1 if case.inputs["rule"] == "evenodd" else winding != 0


def _spans(case: Case) -> list[tuple[Fraction, Fraction, int]]:
    """(x_in, x_out, winding) of the inside runs that hold a sample, before they are clipped."""
    return [
        (a, b, winding)
        for a, b, winding in _intervals(case)
        if _inside(case, winding) and math.ceil(a) < math.ceil(b)
    ]


def _crosses_a_side(case: Case, reference) -> bool:
    width = case.inputs["width"]
    beyond = any(math.ceil(a) < 0 or math.ceil(b) > width for a, b, _ in _spans(case))
    return beyond and bool(_events(case, "span"))


def _edges(case: Case) -> list:
    return [e for t in _events(case, "edge_table_built") for e in t.edges]


def _rule(rule: str, test):
    return lambda case, reference: case.inputs["rule"] == rule and test(case)


SCAN_FEATURES = {
    "left of column 0": lambda case, reference: (
        bool(_events(case, "span")) and any(a < 0 and a % 1 for a, _, _ in _spans(case))
    ),
    "crosses the raster border": _crosses_a_side,
    "below row 0": lambda case, reference: (
        bool(_events(case, "span"))
        and any(not e.horizontal and e.bucket < 0 < e.row_end and e.ymin % 1 for e in _edges(case))
    ),
    "above the top row": lambda case, reference: (
        bool(_events(case, "span"))
        and any(
            not e.horizontal and e.bucket < case.inputs["height"] < e.row_end for e in _edges(case)
        )
    ),
    "winding 3 or more": lambda case, reference: any(
        abs(w) >= 3 and max(math.ceil(a), 0) < min(math.ceil(b), case.inputs["width"])
        for a, b, w in _spans(case)
    ),
    "clockwise, nonzero": _rule("nonzero", lambda c: any(w < 0 for _, _, w in _intervals(c))),
    "overlap, nonzero": _rule("nonzero", lambda c: any(abs(w) == 2 for _, _, w in _intervals(c))),
    "overlap, evenodd": _rule("evenodd", lambda c: any(abs(w) == 2 for _, _, w in _intervals(c))),
    "empty run": lambda case, reference: any(
        _inside(case, w) and math.ceil(a) == math.ceil(b) for a, b, w in _intervals(case)
    ),
    "crossing on a sample": lambda case, reference: any(
        e.x_exact.denominator == 1 for row in _events(case, "aet_sorted") for e in row.entries
    ),
    "horizontal edge on a row": lambda case, reference: any(
        e.horizontal and e.ymin % 1 == 0 and 0 <= e.ymin < case.inputs["height"]
        for e in _edges(case)
    ),
    "vertex between rows": lambda case, reference: any(
        not e.horizontal and e.ymin % 1 for e in _edges(case)
    ),
    "edge ends on a row": lambda case, reference: any(
        not e.horizontal and e.ymax % 1 == 0 and e.row_end > e.bucket for e in _edges(case)
    ),
    "edges cross": lambda case, reference: any(
        row.swaps for row in _events(case, "aet_sorted")[1:]
    ),
    "equal x in the AET": lambda case, reference: any(
        a.x_exact == b.x_exact
        for row in _events(case, "aet_sorted")
        for a, b in zip(row.entries, row.entries[1:], strict=False)
    ),
    "slope not a binary fraction": lambda case, reference: any(
        e.dxdy_exact is not None and e.dxdy_exact.denominator & (e.dxdy_exact.denominator - 1)
        for e in _edges(case)
    ),
}
"""Tests of the scan exercises' features: the inputs that broke real students' code (a polygon
crossing the raster's sides, below row 0 or above the top row, winding 3, edges and crossings on
sample rows and samples), each branch of the span rule (the rules, negative windings, overlaps,
empty runs), of the edge-table entry (horizontal edges, ends between and on rows) and of the AET
update (crossing edges, ties, inexact slopes)."""


def _scan_features(*names: str) -> dict:
    return feature_tests({name: SCAN_FEATURES[name] for name in names})


# --- 5: the span rule ------------------------------------------------------------------------


_row_of_call = place_by_event("aet_sorted", lambda row: f"row {row.y}")


SPAN_RULE_SOLUTION = """\
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
"""


def _span_variant(name: str, hint: str, bounds: str):
    """The variant of the span rule whose span bounds are `bounds` instead of ceil, ceil."""
    return edited_variant(
        SPAN_RULE_SOLUTION, name, hint, ("start, end = math.ceil(x_in), math.ceil(x_out)", bounds)
    )


WINDING_UP_TO_TWO = (
    "inside only for winding +-1 and +-2: under the nonzero rule every winding but 0 is inside "
    "(a {7/3} star has winding 3 at its centre)"
)


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
            "both own a sample on it. A run between two crossings that holds no sample "
            "(`ceil(x_in) == ceil(x_out)`) is not a span: leave it out."
        ),
        stub=(
            "def span_rule(crossings, rule):\n"
            '    """crossings: [(x, winding), ...] sorted by x (x is a Fraction); rule: "nonzero"'
            ' or "evenodd".\n'
            "    Return [(x_start, x_end, winding), ...]: the inside runs in order, half-open\n"
            "    [ceil(x_in), ceil(x_out)), winding the count inside; a run holding no sample\n"
            '    (x_start == x_end) is left out."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=SPAN_RULE_SOLUTION,
        call=call_with_step("span_rule", _scan),
        reference=span_rule,
        public=(
            _case("triangle", [[0, 0], [6, 0], [6, 5]], 8, 6),
            PENTAGRAM,
            _case("pentagram, evenodd", PENTAGRAM.inputs["polygon"], 9, 8, "evenodd"),
            STAR_7_3,
            _case(
                "clockwise, crossing the left, right and top sides of the raster",
                BESIDE.inputs["polygon"][::-1],
                8,
                7,
            ),
        ),
        generate=_span_case,
        **_scan_features(
            "left of column 0",
            "winding 3 or more",
            "clockwise, nonzero",
            "overlap, nonzero",
            "overlap, evenodd",
            "empty run",
            "crossing on a sample",
        ),
        variants=(
            _span_variant(
                "floor_for_ceil",
                "floor instead of ceil: a span starts at the first sample x >= x_in, i.e. ceil(x_in)",
                "start, end = math.floor(x_in), math.floor(x_out)",
            ),
            _span_variant(
                "closed_span",
                "a closed span [x_in, x_out]: the right end is exclusive, x_end = ceil(x_out)",
                "start, end = math.ceil(x_in), math.floor(x_out) + 1",
            ),
            _span_variant(
                "round_for_ceil",
                "rounding to the nearest integer: a sample is inside only if x_in <= x, so use ceil",
                "start, end = round(x_in), round(x_out)",
            ),
            _span_variant(
                "ceil_by_int",
                "int() rounds toward zero, so int(x) + 1 is ceil(x) only for x > 0: left of "
                "column 0 (x < 0) it is one sample too far right; use math.ceil",
                "start = int(x_in) + (x_in != int(x_in))\n"
                "        end = int(x_out) + (x_out != int(x_out))",
            ),
            edited_variant(
                SPAN_RULE_SOLUTION,
                "positive_winding_only",
                "inside only when the count is positive: clockwise polygons have negative "
                "winding numbers; the nonzero rule tests winding != 0",
                ("else winding != 0", "else winding > 0"),
            ),
            edited_variant(
                SPAN_RULE_SOLUTION,
                "parity_always",
                "the even-odd test used for both rules: under 'nonzero' an overlap with "
                "winding 2 is inside",
                (
                    'inside = winding % 2 == 1 if rule == "evenodd" else winding != 0',
                    "inside = winding % 2 == 1",
                ),
            ),
            edited_variant(
                SPAN_RULE_SOLUTION,
                "winding_up_to_two",
                WINDING_UP_TO_TWO,
                ("else winding != 0", "else winding in (1, -1, 2, -2)"),
            ),
            edited_variant(
                SPAN_RULE_SOLUTION,
                "pairs_only",
                "taking crossings in pairs (0-1, 2-3, ...) ignores the winding count; "
                "walk every consecutive pair and keep the count",
                (
                    "for (x_in, step), (x_out, _) in zip(crossings, crossings[1:]):",
                    "for (x_in, step), (x_out, _) in zip(crossings[::2], crossings[1::2]):",
                ),
            ),
        ),
        kinds=("aet_sorted", "span"),
        step="span_rule",
        place=_row_of_call,
        raster=lambda result: result.mask,
        stepper=STEPPER,
    )
)


# --- 3: the edge-table entry ---------------------------------------------------------------


def _edge_of_call(index: int, trace: list) -> str:
    tables = [e for e in trace if e.kind == "edge_table_built"]
    if not tables or index >= len(tables[0].edges):
        return f"call {index + 1}"
    e = tables[0].edges[index]
    return f"edge {index} ({e.x0:g}, {e.y0:g})-({e.x1:g}, {e.y1:g})"


def _entry_output(args, kwargs, returned):
    """A returned entry as an `EdgeEntry`, whether the answer built a plain tuple or not."""
    if isinstance(returned, tuple | list) and len(returned) == len(EdgeEntry._fields):
        return EdgeEntry(*returned)
    return returned


ENTRY_SOLUTION = """\
import math

def edge_table_entry(start, end):
    if start[1] == end[1]:
        return None  # horizontal: it crosses no sample row
    lower, upper = (start, end) if start[1] < end[1] else (end, start)
    winding = 1 if end[1] < start[1] else -1
    return lower, upper, winding, math.ceil(lower[1]), math.ceil(upper[1])
"""

register(
    Exercise(
        id="edge_table_entry",
        number=3,
        title="Edge-table entries",
        stage="scan conversion",
        kind="step",
        points=3,
        answer="edge_table_entry",
        idea=(
            "The **edge table** (ET) holds each polygon edge in the bucket of the first sample "
            "row it crosses. An edge from `start` to `end` is stored by its **lower** and "
            "**upper** ends; it crosses the rows `ymin <= y < ymax`, i.e. it goes into bucket "
            "`ceil(ymin)` and leaves the active edge table on row `ceil(ymax)`. A **horizontal** "
            "edge crosses no sample row: it is not in the table (return `None`), though the "
            "polygon keeps it for its topology. Each edge also carries its **winding**: +1 if "
            "it runs downward from `start` to `end`, -1 if upward (a counter-clockwise polygon "
            "then has winding +1 inside).\n\n" + IDEA_CONVENTIONS
        ),
        stub=(
            "def edge_table_entry(start, end):\n"
            '    """start, end: the edge\'s endpoints in contour order, (x, y) pairs of Fractions\n'
            "    in pixels. Return None for a horizontal edge, else the tuple\n"
            "    (lower, upper, winding, bucket, row_end): lower and upper the endpoints with the\n"
            "    smaller and the larger y; winding +1 if the edge runs downward (end below\n"
            '    start), else -1; the edge is active for the rows bucket <= y < row_end (ints)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=ENTRY_SOLUTION,
        call=call_with_step("edge_table_entry", _scan),
        reference=edge_table_entry,
        public=(UMBC, OFF_GRID, PENTAGRAM, BELOW),
        generate=_span_case,
        **_scan_features(
            "below row 0",
            "horizontal edge on a row",
            "vertex between rows",
            "edge ends on a row",
        ),
        variants=(
            edited_variant(
                ENTRY_SOLUTION,
                "floor_bucket",
                "floor instead of ceil for the bucket: an edge starts on the first sample row "
                "at or above ymin, ceil(ymin)",
                (
                    "math.ceil(lower[1]), math.ceil(upper[1])",
                    "math.floor(lower[1]), math.ceil(upper[1])",
                ),
            ),
            edited_variant(
                ENTRY_SOLUTION,
                "ceil_by_int",
                "int() rounds toward zero, so int(y) + 1 is ceil(y) only for y > 0: below row 0 "
                "(y < 0) it is one row too high; use math.ceil",
                (
                    "math.ceil(lower[1]), math.ceil(upper[1])",
                    "int(lower[1]) + (lower[1] != int(lower[1])), "
                    "int(upper[1]) + (upper[1] != int(upper[1]))",
                ),
            ),
            edited_variant(
                ENTRY_SOLUTION,
                "horizontal_in_table",
                "a horizontal edge in the table: it crosses no sample row and has no winding; "
                "return None for it",
                (
                    "    if start[1] == end[1]:\n        return None  # horizontal: it crosses no sample row\n",
                    "",
                ),
            ),
            edited_variant(
                ENTRY_SOLUTION,
                "winding_flipped",
                "the winding's sign is flipped: an edge running downward (end below start) has "
                "winding +1",
                (
                    "winding = 1 if end[1] < start[1] else -1",
                    "winding = -1 if end[1] < start[1] else 1",
                ),
            ),
            edited_variant(
                ENTRY_SOLUTION,
                "inclusive_top",
                "the top row is included: an edge crosses the rows y < ymax, so row_end = "
                "ceil(ymax), not floor(ymax) + 1",
                ("math.ceil(upper[1])", "math.floor(upper[1]) + 1"),
            ),
            edited_variant(
                ENTRY_SOLUTION,
                "unsorted_ends",
                "the ends are not ordered by y: lower is the end with the smaller y, whichever "
                "comes first in the contour",
                (
                    "lower, upper = (start, end) if start[1] < end[1] else (end, start)",
                    "lower, upper = start, end",
                ),
            ),
        ),
        kinds=("edge_table_built", "edges_activated", "edges_retired", "aet_sorted", "span"),
        step="edge_table_entry",
        place=_edge_of_call,
        output=_entry_output,
        raster=lambda result: result.mask,
        stepper=STEPPER,
    )
)

# --- 4: the per-row AET update --------------------------------------------------------------


def _scanned_row_of_call(index: int, trace: list) -> str:
    rows = sorted({e.y for e in trace if e.kind in ("aet_sorted", "edges_retired")})
    return f"row {rows[index]}" if index < len(rows) else f"call {index + 1}"


AET_SOLUTION = """\
def aet_update(active, y, entering):
    retired = [e for e in active if e.row_end <= y]
    aet = [e for e in active if e.row_end > y]
    for e in aet:
        e.x += e.dxdy
    aet += [e for e in entering if e.bucket <= y]
    for i in range(1, len(aet)):
        j = i
        while j > 0 and aet[j].x < aet[j - 1].x:
            aet[j - 1], aet[j] = aet[j], aet[j - 1]
            j -= 1
    return retired, aet
"""

register(
    Exercise(
        id="aet_update",
        number=4,
        title="The active edge table, row by row",
        stage="scan conversion",
        kind="step",
        points=4,
        answer="aet_update",
        idea=(
            "The **active edge table** (AET) holds the edges that cross the current sample row, "
            "sorted by where they cross it. Going from row y - 1 to row y: **retire** the edges "
            "whose last row has passed (`row_end <= y`), **step** the x of the others by their "
            "`dx/dy` (exactly, with Fractions: no drift), **add** the edges of row y's bucket "
            "(their x is already where they cross row y), and **re-sort** by x. The table is "
            "almost sorted, so an insertion sort does little work; edges with equal x keep "
            "their order (the active ones first, then the entering ones as given).\n\n"
            + IDEA_CONVENTIONS
        ),
        stub=(
            "def aet_update(active, y, entering):\n"
            '    """active: the AET after row y - 1, sorted by x; entering: the edges of row y\'s\n'
            "    bucket, with x where they cross row y (an edge you leave out comes again on the\n"
            "    next row). Each item has .edge (its id), .x and .dxdy (Fractions), .bucket and\n"
            "    .row_end (it is active for the rows bucket <= y < row_end) and .winding; change\n"
            "    only .x. Return (retired, aet): the active items with row_end <= y, in their\n"
            "    order, and row y's AET: the other active items with x stepped by dxdy, then the\n"
            '    entering ones, insertion-sorted by x (equal x keep that order)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=AET_SOLUTION,
        call=call_with_step("aet_update", _scan),
        reference=aet_update,
        public=(UMBC, PENTAGRAM, OFF_GRID, BELOW),
        generate=_span_case,
        **_scan_features(
            "below row 0",
            "winding 3 or more",
            "edges cross",
            "equal x in the AET",
            "slope not a binary fraction",
            "edge ends on a row",
            "horizontal edge on a row",
        ),
        variants=(
            edited_variant(
                AET_SOLUTION,
                "activate_late",
                "the entering edges join one row late: an edge is active from its bucket row "
                "itself (bucket <= y)",
                ("e.bucket <= y", "e.bucket < y"),
            ),
            edited_variant(
                AET_SOLUTION,
                "bucket_is_row",
                "only edges whose bucket is this row enter: an edge starting below the raster "
                "(bucket < 0) enters on row 0, so take every entering edge with bucket <= y",
                ("e.bucket <= y", "e.bucket == y"),
            ),
            edited_variant(
                AET_SOLUTION,
                "retire_late",
                "an edge is retired one row late: it is active for the rows y < row_end, so "
                "retire it when row_end <= y",
                ("e.row_end <= y", "e.row_end < y"),
                ("e.row_end > y", "e.row_end >= y"),
            ),
            edited_variant(
                AET_SOLUTION,
                "no_resort",
                "the AET is not re-sorted: entering edges and edges that cross each other must "
                "be put back in x order every row",
                (
                    "    for i in range(1, len(aet)):\n        j = i\n"
                    "        while j > 0 and aet[j].x < aet[j - 1].x:\n"
                    "            aet[j - 1], aet[j] = aet[j], aet[j - 1]\n            j -= 1\n",
                    "",
                ),
            ),
            edited_variant(
                AET_SOLUTION,
                "ties_swapped",
                "edges with equal x are swapped: the insertion sort moves an edge left only "
                "past a strictly larger x (<, not <=), so ties keep their order",
                ("aet[j].x < aet[j - 1].x", "aet[j].x <= aet[j - 1].x"),
            ),
            edited_variant(
                AET_SOLUTION,
                "float_accumulation",
                "float accumulation: x += float(dx/dy) drifts and loses the exact crossing; "
                "step x by the exact Fraction dx/dy",
                ("e.x += e.dxdy", "e.x += float(e.dxdy)"),
            ),
            edited_variant(
                AET_SOLUTION,
                "step_entering",
                "the entering edges are stepped too: their x is already where they cross row y; "
                "step only the edges that were active on the row before",
                (
                    "    for e in aet:\n        e.x += e.dxdy\n"
                    "    aet += [e for e in entering if e.bucket <= y]\n",
                    "    aet += [e for e in entering if e.bucket <= y]\n"
                    "    for e in aet:\n        e.x += e.dxdy\n",
                ),
            ),
        ),
        kinds=("edges_activated", "edges_retired", "aet_sorted", "span"),
        step="aet_update",
        place=_scanned_row_of_call,
        raster=lambda result: result.mask,
        stepper=STEPPER,
    )
)

# --- 7: the whole ET/AET loop ---------------------------------------------------------------


def _scan_loop(fn, inputs, tracer):
    vertices = [(Fraction(x), Fraction(y)) for x, y in inputs["polygon"]]
    fn(vertices, inputs["width"], inputs["height"], inputs["rule"], tracer)
    return _span_mask(tracer, inputs["width"], inputs["height"])


def _span_mask(tracer, width: int, height: int) -> np.ndarray:
    """The (height, width) bool samples the recorded ``span`` events cover."""
    mask = np.zeros((height, width), dtype=bool)
    for event in tracer.trace() if isinstance(tracer, Recorder) else ():
        if event.kind == "span" and 0 <= event.y < height:
            mask[event.y, max(event.x_start, 0) : max(min(event.x_end, width), 0)] = True
    return mask


def reference_scan_loop(polygon, width, height, rule, tracer):
    """The reference of `scan_loop`: scanviz's ET/AET scan conversion, emitting to `tracer`."""
    scan_convert([[float(x), float(y)] for x, y in polygon], width, height, rule=rule, trace=tracer)


LOOP_SOLUTION = """\
import math
from scanviz.trace.events import AetEntry, AetSorted, EdgesActivated, EdgesRetired, Span

def scan_loop(polygon, width, height, rule, tracer):
    table = {}  # the edge table: first raster row -> the edges entering there
    for i, ((x0, y0), (x1, y1)) in enumerate(zip(polygon, polygon[1:] + polygon[:1])):
        if y0 == y1:
            continue  # horizontal: it crosses no sample row
        (xl, yl), (xu, yu) = ((x0, y0), (x1, y1)) if y0 < y1 else ((x1, y1), (x0, y0))
        bucket, row_end = max(math.ceil(yl), 0), math.ceil(yu)
        if bucket < min(row_end, height):
            dxdy = (xu - xl) / (yu - yl)
            table.setdefault(bucket, []).append({
                "edge": i, "x": xl + dxdy * (bucket - yl), "dxdy": dxdy, "ymax": yu,
                "row_end": row_end, "winding": 1 if y1 < y0 else -1,
            })
    aet = []
    y = min(table, default=height)
    while y < height and (aet or y in table):
        retired = [e for e in aet if e["row_end"] <= y]
        aet = [e for e in aet if e["row_end"] > y]
        for e in aet:
            e["x"] += e["dxdy"]
        entering = table.get(y, [])
        aet += entering
        swaps = 0
        for k in range(1, len(aet)):
            j = k
            while j > 0 and aet[j]["x"] < aet[j - 1]["x"]:
                aet[j - 1], aet[j] = aet[j], aet[j - 1]
                swaps += 1
                j -= 1
        if retired:
            tracer.emit(EdgesRetired(0, y, tuple(e["edge"] for e in retired)))
        if entering:
            tracer.emit(EdgesActivated(0, y, tuple(e["edge"] for e in entering)))
        if aet:
            entries = tuple(
                AetEntry(e["edge"], float(e["x"]), e["x"], float(e["dxdy"]), e["dxdy"],
                         float(e["ymax"]), e["winding"])
                for e in aet
            )
            tracer.emit(AetSorted(0, y, entries, swaps))
        winding = 0
        for left, right in zip(aet, aet[1:]):
            winding += left["winding"]
            inside = winding % 2 == 1 if rule == "evenodd" else winding != 0
            start, end = max(math.ceil(left["x"]), 0), min(math.ceil(right["x"]), width)
            if inside and start < end:
                tracer.emit(Span(0, y, start, end, winding))
        y += 1
"""

register(
    Exercise(
        id="scan_loop",
        number=7,
        title="The whole ET/AET scan conversion",
        stage="scan conversion",
        kind="loop",
        points=5,
        answer="scan_loop",
        idea=(
            "Put it together: build the **edge table** (every non-horizontal edge in the bucket "
            "of its first sample row, `ceil(ymin)`), then for each row from the lowest bucket "
            "up: retire the edges with `ceil(ymax) <= y`, step the others' x by `dx/dy`, add "
            "the row's bucket, insertion-sort by x, and fill the spans "
            "`[ceil(x_in), ceil(x_out))` where the winding count says inside. Rows and "
            "columns outside the raster are never drawn: an edge starting below row 0 enters "
            "at row 0, and spans are clipped to `[0, width)`. Every step is an event the "
            "tracer records, compared with scanviz's own loop event by event.\n\n"
            + IDEA_CONVENTIONS
        ),
        stub=(
            "from scanviz.trace.events import AetEntry, AetSorted, EdgesActivated, "
            "EdgesRetired, Span\n\n"
            "def scan_loop(polygon, width, height, rule, tracer):\n"
            '    """polygon: one contour [(x, y), ...] of Fractions in pixels; edge i runs from\n'
            '    polygon[i] to polygon[i + 1] (the last one back to polygon[0]); rule: "nonzero"\n'
            '    or "evenodd". Horizontal edges are not in the edge table. An edge enters on row\n'
            "    max(ceil(ymin), 0), with x where it crosses that row, if that row is below\n"
            "    min(ceil(ymax), height); it is retired on row ceil(ymax). Its winding is +1 if it\n"
            "    runs downward, else -1. Scan rows y from the lowest bucket while y < height and\n"
            "    edges are active or entering. On each row: retire, step x by dx/dy, append the\n"
            "    row's bucket in edge order, insertion-sort by x (equal x keep their order), then\n"
            "    tracer.emit, with polygon 0 and in this order:\n"
            "      EdgesRetired(0, y, edge ids in AET order), if any were retired;\n"
            "      EdgesActivated(0, y, edge ids in edge order), if any entered;\n"
            "      AetSorted(0, y, entries, swaps), if the AET is not empty: entries in AET order,\n"
            "        AetEntry(edge, x=float(x), x_exact=x, dxdy=float(dxdy), dxdy_exact=dxdy,\n"
            "        ymax=float(ymax), winding), swaps the exchanges the insertion sort made;\n"
            "      Span(0, y, x_start, x_end, winding) for each inside run [ceil(x_in),\n"
            "        ceil(x_out)) clipped to [0, width), if not empty; winding: the count inside.\n"
            '    Return nothing."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=LOOP_SOLUTION,
        call=_scan_loop,
        reference=reference_scan_loop,
        public=(UMBC, OFF_GRID, PENTAGRAM, BELOW, BESIDE, STAR_7_3),
        generate=_span_case,
        **_scan_features(
            "crosses the raster border",
            "below row 0",
            "above the top row",
            "winding 3 or more",
            "clockwise, nonzero",
            "overlap, evenodd",
            "horizontal edge on a row",
            "crossing on a sample",
            "edges cross",
            "vertex between rows",
            "edge ends on a row",
        ),
        variants=(
            edited_variant(
                LOOP_SOLUTION,
                "closed_spans",
                "closed spans [x_in, x_out]: a span is half-open, its end is ceil(x_out)",
                ('min(math.ceil(right["x"]), width)', 'min(math.floor(right["x"]) + 1, width)'),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "spans_not_clipped",
                "spans run past the raster's sides: clip each to [0, width) (a span starts at "
                "max(ceil(x_in), 0) and ends at min(ceil(x_out), width))",
                (
                    'max(math.ceil(left["x"]), 0), min(math.ceil(right["x"]), width)',
                    'math.ceil(left["x"]), math.ceil(right["x"])',
                ),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "rows_below_the_raster",
                "rows below the raster are scanned: an edge that starts below row 0 enters the "
                "AET on row max(ceil(ymin), 0), with x where it crosses row 0",
                (
                    "bucket, row_end = max(math.ceil(yl), 0), math.ceil(yu)",
                    "bucket, row_end = math.ceil(yl), math.ceil(yu)",
                ),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "no_resort",
                "the AET is not re-sorted: entering edges and edges that cross each other must "
                "be put back in x order every row",
                (
                    '            while j > 0 and aet[j]["x"] < aet[j - 1]["x"]:',
                    "            while False:",
                ),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "retire_late",
                "an edge is retired one row late: it is active for the rows y < ceil(ymax), so "
                "retire it when ceil(ymax) <= y",
                ('e["row_end"] <= y', 'e["row_end"] < y'),
                ('e["row_end"] > y', 'e["row_end"] >= y'),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "rows_above_the_raster",
                "rows at and above the raster's top are scanned: the raster's rows are 0 to "
                "height - 1, so scan while y < height and enter only edges starting below height",
                ("while y < height and (aet or y in table):", "while aet or y in table:"),
                ("if bucket < min(row_end, height):", "if bucket < row_end:"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "winding_up_to_two",
                WINDING_UP_TO_TWO,
                ("else winding != 0", "else winding in (1, -1, 2, -2)"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "floor_bucket",
                "floor instead of ceil for the bucket: an edge starts on the first sample row "
                "at or above ymin, ceil(ymin)",
                ("max(math.ceil(yl), 0)", "max(math.floor(yl), 0)"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "step_entering",
                "the entering edges are stepped too: their x is already where they cross row y; "
                "step only the edges that were active on the row before",
                (
                    '        for e in aet:\n            e["x"] += e["dxdy"]\n'
                    "        entering = table.get(y, [])\n        aet += entering\n",
                    "        entering = table.get(y, [])\n        aet += entering\n"
                    '        for e in aet:\n            e["x"] += e["dxdy"]\n',
                ),
            ),
        ),
        kinds=("edges_activated", "edges_retired", "aet_sorted", "span"),
        raster=lambda mask: mask,
        stepper=STEPPER,
    )
)

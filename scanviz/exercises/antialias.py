"""Exercises on area-sampling anti-aliasing (scanviz.antialias; Wang 1989, ch. 4), through
`dislop_line` and `post_antialias` traced.

``dislop_column`` is the per-column area formula of DISLOP_L (Fig 4-2, spec
§3.2): from the first-octant slope m and the offset dxy of the line from the
middle pixel's centre, the areas of the pixels above, at and below it. The
real DISLOP_L runs with the student's formula in every middle column (the
three columns at each end are clipped exactly and do not call it); its
``dislop_column`` events (the middle pixel, m, dxy, the critical values, the
branch, the areas) are graded, then the coverage image. Cases are single
lines in several octants (the walk reflects them into 0 <= m <= 1): shallow
ones, whose columns take two and three pixels, slopes past 0.75, where the
printed formula misses a fourth pixel (it is the reference all the same),
45° lines with dxy = 1/2 or 0 in every column, and horizontal and vertical
lines (m = 0).

``table_index`` is the index arithmetic of post-anti-aliasing (§4.8, spec
§3.8): the slope and distance indices (i, j) of the 51 x 51 x 3 table, found
in every table column of every segment. `post_antialias` runs with the
student's step; its ``post_column`` events (the middle pixel, dxy, i, j, the
areas read) are graded, then the image. Cases are lines and polygon edges on
a black image, among them slopes and distances on exact halves (m·50 = 12.5:
the C cast rounds up, Python's round() to even) and Fig 5-1's line.
"""

from __future__ import annotations

import functools
import math
import random

import numpy as np

from ..antialias.columns import LINE_BRANCHES
from ..antialias.line import dislop_line, middle_column
from ..antialias.post import post_antialias
from ..antialias.tables import table_indices
from .cases import call_with_step, place_by_event
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

KINDS = ("dislop_column",)
CATEGORIES = ("shallow", "medium", "past 0.75", "45 degrees", "horizontal or vertical")
SIZE = 16  # the raster of the hidden cases


def _draw(inputs: dict, tracer):
    return dislop_line(inputs["p0"], inputs["p1"], inputs["width"], inputs["height"], trace=tracer)


def middle_columns(trace: list) -> list:
    """The ``dislop_column`` events of the middle columns: the ones the formula runs in."""
    return [e for e in trace if e.kind == "dislop_column" and e.branch in LINE_BRANCHES]


def _middle_column(event) -> str:
    """Where a column event of a line is: the column (or row) it walks and its middle pixel."""
    walked = f"column {event.x}" if event.major == "x" else f"row {event.y}"
    return f"{walked} (middle pixel ({event.x}, {event.y}))"


def _column_of_call(index: int, trace: list) -> str:
    """The formula runs once per middle column, in the order the columns are traced."""
    middle = middle_columns(trace)
    return _middle_column(middle[index]) if index < len(middle) else f"call {index + 1}"


def _case(label, p0, p1, width, height, category=""):
    inputs = {"p0": list(p0), "p1": list(p1), "width": width, "height": height}
    return Case(label, inputs, category)


PUBLIC = (
    _case(
        "a shallow line (m = 0.3): two pixels a column, and three where |dxy| is small",
        (0.5, 1.2),
        (12.5, 4.8),
        13,
        7,
    ),
    _case(
        "a steep line running down and left (x and y swap, m = 0.85 > 0.75)",
        (11.9, 13.5),
        (1.7, 1.5),
        13,
        15,
    ),
    _case(
        "a 45° line half a pixel above the centres: m = 1 and dxy = 1/2 in every column",
        (0.5, 1.0),
        (10.5, 11.0),
        12,
        12,
    ),
    _case(
        "a horizontal line (m = 0) a quarter pixel above the centres: up = |dxy| = 1/4",
        (0.5, 2.75),
        (9.5, 2.75),
        10,
        5,
    ),
    _case(
        "a nearly horizontal line falling to the right (m = 1/16): dxy steps from -3/8 to 3/8",
        (0.5, 3.0),
        (16.5, 2.0),
        17,
        5,
    ),
    _case(
        "a vertical line through the pixel centres (m = 0, dxy = 0): mid = 1, up = low = 0",
        (2.5, 0.5),
        (2.5, 11.5),
        5,
        12,
    ),
)


def _sixteenth(rng: random.Random, low: float, high: float) -> float:
    return round(rng.uniform(low, high) * 16) / 16


THROUGH_CENTRES = (
    "horizontal through pixel centres",
    "vertical through pixel centres",
    "45° through pixel centres",
)
_SHAPES = {  # feature: (the categories its line may be in, dxy at its middle column)
    "flat": (("horizontal or vertical",), None),
    "two": (("shallow",), 0.5),  # ad = 1/2 > fcv while m <= 1/2
    "three": (("past 0.75", "45 degrees"), 0.5),  # ad = 1/2 <= fcv and scv > m/2 from m = 13/16
    "three_triangle": (("shallow", "medium", "past 0.75", "45 degrees"), 0.0),  # scv = dw/2 < m/2
    "horizontal through pixel centres": (("horizontal or vertical",), 0.0),
    "vertical through pixel centres": (("horizontal or vertical",), 0.0),
    "45° through pixel centres": (("45 degrees",), 0.0),
}
_SLOPES = {  # category: the range of its first-octant slopes, in sixteenths
    "shallow": (0.05, 0.5),
    "medium": (0.5, 0.75),
    "past 0.75": (0.79, 0.96),  # 13/16 to 15/16: neither 0.75 nor 1
    "45 degrees": (1.0, 1.0),
    "horizontal or vertical": (0.0, 0.0),
}


def _dislop_case(rng: random.Random, feature: str | None = None) -> Case:
    """A line of 8 to 14 pixels along its major axis on a 16² raster, in any octant.

    A `feature` of `DISLOP_FEATURES` picks the category and the offset dxy of the middle
    column halfway along the line that give it (dxy is the same in every column of a
    horizontal, vertical or 45° line); the walk's reflections keep |dxy| (the fall mirrors
    the raster, pixel centres onto pixel centres).
    """
    categories, dxy = _SHAPES.get(
        feature, ((feature,) if feature in CATEGORIES else CATEGORIES, None)
    )
    category = rng.choice(categories)
    length = rng.randint(8, 14)
    m = _sixteenth(rng, *_SLOPES[category])
    if dxy is None:  # any; a 45° line has it in every column: 1/2, 0 or 1/16 - 1/2
        dxy = rng.choice((0.5, 0.0, 1 / 16 - 0.5)) if m == 1 else _sixteenth(rng, -0.45, 0.5)
    x0 = _sixteenth(rng, 0.0, SIZE - 1 - length)
    column = math.floor(x0) + length // 2  # at least 4 columns from either end: a middle one
    run = column + 0.5 - x0  # from the start to the middle column's centre
    row = math.floor(_sixteenth(rng, 0.0, SIZE - 1 - m * length) + m * run)
    y0 = row + 0.5 + dxy - m * run  # the line is dxy above the middle pixel's centre there
    if not 0 <= y0 <= SIZE - 1 - m * length:  # a row up or down keeps it on the raster
        y0 += 1 if y0 < 0 else -1
    start, end = [x0, y0], [x0 + length, y0 + m * length]
    if rng.random() < 0.5:  # fall instead of rise: the walk negates v
        start[1], end[1] = SIZE - 1 - start[1], SIZE - 1 - end[1]
    if rng.random() < 0.5:  # run right to left: the walk reverses the segment
        start, end = end, start
    if feature in THROUGH_CENTRES[:2]:
        steep = feature == THROUGH_CENTRES[1]
    else:
        steep = rng.random() < 0.5
    if steep:  # steep on the screen: the walk swaps x and y
        start, end = start[::-1], end[::-1]
    label = f"{feature or category}: ({start[0]}, {start[1]}) to ({end[0]}, {end[1]})"
    return _case(label, start, end, SIZE, SIZE, feature or category)


def _columns(reference) -> list[tuple[float, float]]:
    """(m, dxy) of every column the reference called the step in."""
    return [tuple(args) for args, _ in reference.arguments]


def _slopes(low: float, high: float):
    return lambda case, reference: any(low <= m <= high for m, _ in _columns(reference))


def _branch(name: str):
    return lambda case, reference: any(
        e.kind == "dislop_column" and e.branch == name for e in reference.trace
    )


def _through_centres(axis: int | None, m: float):
    """A segment along `axis` (0: horizontal, 1: vertical, None: either) and a call of the step
    at slope `m` in a column through the pixel centres (dxy = 0); of a line or of post's
    segments."""

    def test(case, reference):
        segments = case.inputs.get("segments") or [(case.inputs["p0"], case.inputs["p1"])]
        along = axis is None or any(p0[1 - axis] == p1[1 - axis] for p0, p1 in segments)
        return along and (m, 0.0) in _columns(reference)

    return test


DISLOP_FEATURES = {
    "shallow": _slopes(0.05, 0.5),
    "medium": _slopes(0.5, 0.75),
    "past 0.75": lambda case, reference: any(0.75 < m < 1 for m, _ in _columns(reference)),
    "45 degrees": _slopes(1, 1),
    "horizontal or vertical": _slopes(0, 0),
    THROUGH_CENTRES[0]: _through_centres(0, 0.0),
    THROUGH_CENTRES[1]: _through_centres(1, 0.0),
    THROUGH_CENTRES[2]: _through_centres(None, 1.0),
    **{branch: _branch(branch) for branch in ("flat", "two", "three", "three_triangle")},
}
"""Tests of the column areas' features: slopes in each range (past 0.75 the printed formula is
not exact), horizontal, vertical and 45° lines through the pixel centres (dxy = 0, where
ad = fcv = 0 for m = 0), and each branch of the formula (Fig 4-2)."""


SOLUTION = """\
import math


def dislop_column(m, dxy):
    thickness = math.sqrt(1.0 + m * m)
    dw = thickness - 1.0
    fcv = 0.5 * (m + dw)
    ad = abs(dxy)
    scv = ad + 0.5 * dw
    if m == 0:
        up, low = ad, 0.0
    elif ad > fcv:
        up, low = scv, 0.0
    elif scv > 0.5 * m:
        up, low = scv, (fcv - ad) ** 2 / (2 * m)
    else:
        up, low = (ad + fcv) ** 2 / (2 * m), (fcv - ad) ** 2 / (2 * m)
    if dxy < 0:
        up, low = low, up
    return up, thickness - up - low, low
"""


_variant = functools.partial(edited_variant, SOLUTION)


IDEA = (
    "**DISLOP_L** (Wang 1989, ch. 4, §4.2, Figs 4-1 and 4-2) draws a line 1 pixel wide, "
    "measured across the line, and gives every pixel the area of its unit square inside the "
    "band: exact area sampling, column by column. Every direction is reflected into the first "
    "octant, 0 <= m <= 1 (swap x and y if the line is steep, negate y if it falls), so one "
    "formula serves all lines. In a column x ∈ [-1/2, 1/2] the middle pixel is the one whose "
    "row holds the line at the column centre; relative to its centre the band is "
    "dxy + m x - Ta/2 <= y <= dxy + m x + Ta/2, with -1/2 < dxy <= 1/2 and Ta = sqrt(1 + m²) "
    "= 1 / cos a, the band's vertical thickness: every column holds exactly Ta, so the "
    "intensity per unit length is the same at every slope.\n\n"
    "Wang's (1989) formula: dw = Ta - 1, the first critical value fcv = (m + dw) / 2 "
    "(for |dxy| > fcv the band misses the lower pixel), ad = |dxy|, the second critical value "
    "scv = ad + dw / 2 (the band's mean overhang above the middle pixel). Then\n\n"
    "| branch | when | up | low |\n|---|---|---|---|\n"
    "| flat | m = 0 | ad | 0 |\n"
    "| two | ad > fcv | scv | 0 |\n"
    "| three | scv > m / 2: the overhang above is a trapezoid | scv | (fcv - ad)² / 2m |\n"
    "| three_triangle | otherwise: both overhangs are triangles | (ad + fcv)² / 2m | "
    "(fcv - ad)² / 2m |\n\n"
    "written for dxy >= 0; for dxy < 0 the column is the mirror image about the middle "
    "pixel's centre, so up and low swap. The middle pixel gets the rest, mid = Ta - up - low. "
    "The formula is exact up to m = 0.75; above, the band can reach a fourth pixel, whose area "
    "(at most 0.021, at m = 1 and dxy = ±1/2) the formula credits to up or low. **The "
    "reference is the printed formula**, since it is what the grading compares with: do not "
    "add the fourth pixel. Every column emits a `dislop_column` event (the middle pixel, m, "
    "dxy, fcv, scv, the branch, the areas); scanviz: y up, pixel (x, y) is the square "
    "[x, x+1] × [y, y+1].\n\n"
    "Your step is the formula, called once per middle column. The three columns at each end "
    "are clipped exactly by the loop (branch `cap`) and do not call it. Floats compare to a "
    "relative 1e-9, so any arrangement of the arithmetic passes."
)

register(
    Exercise(
        id="dislop_column",
        number=22,
        title="The areas of a DISLOP line's column",
        stage="anti-aliasing",
        kind="step",
        points=3,
        answer="dislop_column",
        idea=IDEA,
        stub=(
            "def dislop_column(m, dxy):\n"
            '    """m: the first-octant slope of the line (a float, 0 <= m <= 1); dxy: its offset\n'
            "    from the middle pixel's centre at the column centre (a float, -1/2 < dxy <= 1/2),\n"
            "    positive above.\n"
            "    Return (up, mid, low): the areas of the pixels above, at and below the middle one\n"
            '    inside the 1-wide band, by Wang\'s (1989) formula (Fig. 4-2)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=SOLUTION,
        call=call_with_step("dislop_column", _draw),
        reference=middle_column,
        public=PUBLIC,
        generate=_dislop_case,
        **feature_tests(DISLOP_FEATURES),
        variants=(
            _variant(
                "no_flat_branch",
                "a horizontal or vertical line (m = 0) needs its own branch, up = |dxy| and "
                "low = 0: through the pixel centres ad = fcv = scv = 0, so neither ad > fcv nor "
                "scv > m / 2 holds and the triangle formula divides by 2m = 0",
                (
                    "    if m == 0:\n        up, low = ad, 0.0\n    elif ad > fcv:\n",
                    "    if ad > fcv:\n",
                ),
            ),
            _variant(
                "up_low_swapped",
                "up is the pixel above the middle one (y > 1/2): for dxy > 0 the line leans "
                "that way and up is the larger overhang; return (up, mid, low) in that order",
                (
                    "    return up, thickness - up - low, low\n",
                    "    return low, thickness - up - low, up\n",
                ),
            ),
            _variant(
                "no_reflection",
                "the formula is written for dxy >= 0; for dxy < 0 the column is its mirror image "
                "about the middle pixel's centre: swap up and low",
                ("    if dxy < 0:\n        up, low = low, up\n", ""),
            ),
            _variant(
                "no_triangle",
                "when scv <= m / 2 the band's top edge crosses y = 1/2 inside the column: the "
                "overhang above is a triangle, (ad + fcv)² / 2m, not a trapezoid of mean "
                "height scv (branch three_triangle)",
                ("    elif scv > 0.5 * m:\n", "    else:\n"),
                (
                    "    else:\n        up, low = (ad + fcv) ** 2 / (2 * m), (fcv - ad) ** 2 / (2 * m)\n",
                    "",
                ),
            ),
            _variant(
                "fcv_sign",
                "the band's lower edge at the column's low end is at ad - m/2 - Ta/2, below "
                "y = -1/2 while ad < (m + Ta - 1) / 2: fcv = (m + dw) / 2, with + dw",
                ("fcv = 0.5 * (m + dw)", "fcv = 0.5 * (m - dw)"),
            ),
            _variant(
                "low_not_clipped",
                "past the first critical value (ad > fcv) the band misses the lower pixel: low "
                "is 0 there; (fcv - ad)² / 2m is a triangle only while fcv - ad > 0 (squaring "
                "a negative length gives a positive area that is not there)",
                (
                    "    elif ad > fcv:\n        up, low = scv, 0.0\n",
                    "    elif ad > fcv:\n        up, low = scv, (fcv - ad) ** 2 / (2 * m)\n",
                ),
            ),
            _variant(
                "mid_from_one",
                "a column holds Ta = sqrt(1 + m²) of the band (its vertical thickness), not 1: "
                "mid = Ta - up - low, so that the intensity per unit length is the same at "
                "every slope",
                (
                    "    return up, thickness - up - low, low\n",
                    "    return up, 1.0 - up - low, low\n",
                ),
            ),
        ),
        kinds=KINDS,
        step="dislop_column",
        place=_column_of_call,
        result=lambda image: image,
        rtol=1e-9,
        stepper=(
            "from scanviz.widgets import dislop_stepper\n"
            "dislop_stepper(CASE['p0'], CASE['p1'], CASE['width'], CASE['height'])"
        ),
    )
)


POST_KINDS = ("post_column",)
POST_CATEGORIES = ("lines", "ties", "horizontal or 45 degrees", "steep lines", "polygon edges")


def _post(inputs: dict, tracer):
    return post_antialias(
        np.zeros((inputs["height"], inputs["width"])),
        inputs["segments"],
        kind=inputs["kind"],
        flags=inputs["flags"],
        trace=tracer,
    )


def _look_up(event) -> str:
    """The indices are found once per table column (the dxy recurrence), in trace order."""
    return f"segment {event.segment}, {_middle_column(event)}"


def post_table(trace) -> str:
    """The table look-ups as text, one line each: segment, where, dxy, i, j, the areas read.

    >>> _, trace = post_antialias(np.zeros((4, 9)), [((0.5, 1.0), (8.5, 3.0))], trace=True)
    >>> print(post_table(trace).splitlines()[0])
    segment 0  column 2   pixel ( 2,  1)  dxy  0.0000  i 13  j 25  up 0.0413  mid 0.9506  low 0.0413
    """
    lines = []
    for e in trace:
        if e.kind != "post_column":
            continue
        walked = f"column {e.x:<3}" if e.major == "x" else f"row {e.y:<6}"
        lines.append(
            f"segment {e.segment}  {walked} pixel ({e.x:2d}, {e.y:2d})  dxy {e.dxy:7.4f}  "
            f"i {e.i:2d}  j {e.j:2d}  up {e.up:.4f}  mid {e.mid:.4f}  low {e.low:.4f}"
        )
    return "\n".join(lines)


def _post_case(label, segments, width, height, kind="line", flags=None, category=""):
    inputs = {
        "segments": [[list(p0), list(p1)] for p0, p1 in segments],
        "kind": kind,
        "flags": flags,
        "width": width,
        "height": height,
    }
    return Case(label, inputs, category)


POST_PUBLIC = (
    _post_case(
        "a line of slope 1/4: m·50 = 12.5 gives i = 13, and dxy = ±1/4 gives the ties j = 13, 38",
        [((0.5, 1.0), (12.5, 4.0))],
        13,
        6,
    ),
    _post_case(
        "Fig 5-1's line, moved by (-98, -148): m = 0.6747, i = 34, j = 42, 26, 10, 44, 27, 11",
        [((2.8, 2.7), (11.1, 8.3))],
        13,
        11,
    ),
    _post_case(
        "an 85° line leaning left (x and y swap, m = 0.0875): i = 4 from 4.875",
        [((4.55, 0.5), (3.5, 12.5))],
        7,
        14,
    ),
    _post_case(
        "a horizontal line and a 45° one, half a pixel above the centres: i = 0 and 50, j = 50",
        [((0.5, 2.0), (10.5, 2.0)), ((0.5, 4.0), (8.5, 12.0))],
        12,
        14,
    ),
    _post_case(
        "a triangle's three edges (kind edge, flags 0, 1, 0): the columns between their ends",
        [((1.5, 1.5), (13.5, 4.5)), ((13.5, 4.5), (5.5, 12.5)), ((5.5, 12.5), (1.5, 1.5))],
        15,
        14,
        "edge",
        [0, 1, 0],
    ),
)


def _post_segment(rng: random.Random, category: str) -> list:
    """A segment of 5 to 14 pixels along its major axis on the 16² raster, in any octant."""
    length = rng.randint(5, 14)
    grid = 4 if category in ("ties", "horizontal or 45 degrees") else 16
    if category == "ties":  # m·50 = 12.5 or 37.5, and dxy on quarters: j ties at dxy = ±1/4
        rise = rng.choice((0.25, 0.75)) * length
    elif category == "horizontal or 45 degrees":
        rise = rng.choice((0.0, 1.0)) * length
    else:
        rise = _sixteenth(rng, 0.0, 1.0) * length
    x0 = round(rng.uniform(0.0, SIZE - 1 - length) * grid) / grid
    y0 = round(rng.uniform(0.0, SIZE - 1 - rise) * grid) / grid
    start, end = [x0, y0], [x0 + length, y0 + rise]
    if rng.random() < 0.5:
        start[1], end[1] = end[1], start[1]
    if rng.random() < 0.5:
        start, end = end, start
    if category == "steep lines" or rng.random() < 0.3:
        start, end = start[::-1], end[::-1]
    return [start, end]


HALF_OFF = "half a pixel off the centres"
_DIRECTIONS = dict(zip(THROUGH_CENTRES, ("horizontal", "vertical", "45°"), strict=True))


def _grid_segment(rng: random.Random, direction: str, offset: float) -> list:
    """A horizontal, vertical or 45° segment of 5 to 14 pixels on the 16² raster whose every
    column is `offset` from the pixel centres (dxy = `offset`; 1/2: between two rows)."""
    length = rng.randint(5, 14)
    x0 = _sixteenth(rng, 0.0, SIZE - 1 - length)
    if direction == "45°":  # y = x + c: at a column centre x = k + 1/2, y = k + c + 1/2
        c = rng.randint(math.ceil(-x0 - offset), math.floor(SIZE - 1 - length - x0 - offset))
        y0, rise = x0 + c + offset, length
    else:
        y0, rise = rng.randint(0, SIZE - 2) + 0.5 + offset, 0
    start, end = [x0, y0], [x0 + length, y0 + rise]
    if rng.random() < 0.5:  # fall: the raster's mirror keeps pixel centres on pixel centres
        start[1], end[1] = SIZE - 1 - start[1], SIZE - 1 - end[1]
    if rng.random() < 0.5:
        start, end = end, start
    if direction == "vertical":
        start, end = start[::-1], end[::-1]
    return [start, end]


def _table_index_case(rng: random.Random, feature: str | None = None) -> Case:
    """1-3 segments on a 16² raster; a category `feature` is that category, a line through the
    pixel centres or half a pixel off them is built so, "exact halves" are ties."""
    if feature in THROUGH_CENTRES or feature == HALF_OFF:
        offset = 0.5 if feature == HALF_OFF else 0.0
        direction = _DIRECTIONS.get(feature) or rng.choice(list(_DIRECTIONS.values()))
        segments = [_grid_segment(rng, direction, offset) for _ in range(rng.randint(1, 3))]
        label = f"{feature}: {len(segments)} segment{'s' if len(segments) > 1 else ''}"
        return _post_case(label, segments, SIZE, SIZE, "line", None, feature)
    category = feature if feature in POST_CATEGORIES else rng.choice(POST_CATEGORIES)
    if feature == "exact halves":
        category = "ties"
    segments = [_post_segment(rng, category) for _ in range(rng.randint(1, 3))]
    edge = category == "polygon edges"
    flags = [rng.randint(0, 1) for _ in segments] if edge else None
    label = f"{feature or category}: {len(segments)} segment{'s' if len(segments) > 1 else ''}"
    kind = "edge" if edge else "line"
    return _post_case(label, segments, SIZE, SIZE, kind, flags, feature or category)


def _half(value: float) -> bool:
    return (value * 50) % 1 == 0.5


INDEX_FEATURES = {
    "lines": lambda case, reference: case.inputs["kind"] == "line",
    "polygon edges": lambda case, reference: case.inputs["kind"] == "edge",
    "steep lines": lambda case, reference: any(
        abs(y1 - y0) > abs(x1 - x0) for (x0, y0), (x1, y1) in case.inputs["segments"]
    ),
    "exact halves": lambda case, reference: any(
        _half(abs(m)) or _half(dxy + 0.5) for (m, dxy), _ in reference.arguments
    ),
    THROUGH_CENTRES[0]: _through_centres(0, 0.0),
    THROUGH_CENTRES[1]: _through_centres(1, 0.0),
    THROUGH_CENTRES[2]: _through_centres(None, 1.0),
    HALF_OFF: lambda case, reference: any(dxy == 0.5 for (_, dxy), _ in reference.arguments),
}
"""Tests of the table index's features: lines and edges, steep segments, an index exactly half way
(the C cast rounds it up, Python's round() to even), horizontal, vertical and 45° lines through
the pixel centres (i = 0 or 50, j = 25) and a line half a pixel off them (j = 50)."""


INDEX_SOLUTION = """\
def table_index(m, dxy):
    i = int(abs(m) * 50 + 0.5)
    j = int((dxy + 0.5) * 50 + 0.5)
    return i, j
"""


_index_variant = functools.partial(edited_variant, INDEX_SOLUTION)


POST_IDEA = (
    "**Post-anti-aliasing** (Wang 1989, ch. 4, §4.8) anti-aliases an image that is already "
    "rendered: every visible line or polygon edge is walked column by column in its "
    "first-octant frame, and in each column the areas of the three pixels it cuts are read "
    "from a table instead of computed (DISLOP_L for lines, DISLOP_E for edges) and blended "
    "over the image. The slope range [0, 1] is divided into 50: m_i = i / 50, each with an "
    "exact period 50 / gcd(i, 50), so one table of 51 × 51 × 3 areas serves every slope: "
    "`[i, j, (upper, middle, lower)]` with dxy_j = -1/2 + j / 50 (j = 0 and j = 50 are the "
    "same configuration, one row apart).\n\n"
    "The indices are those of Wang's (1989) C code: i = (int)(|m| * 50 + 0.5), j = (int)((dxy + 0.5) "
    "* 50 + 0.5), the nearest division, halves rounded up (m = 0.080 gives i = 4 from 4.5, "
    "m = 0.6747 gives i = 34). Each traced column emits a `post_column` event (the segment, "
    "the middle pixel, dxy, i, j and the areas read); scanviz: y up, pixel (x, y) is the "
    "square [x, x+1] × [y, y+1].\n\n"
    "Your step is the index arithmetic, called once per table column with the segment's "
    "first-octant slope m (0 <= m <= 1) and the column's dxy (-1/2 < dxy <= 1/2, stepped by m "
    "from column to column). Lines keep the three columns at each end for the exact caps, "
    "edges their two end columns for the polygon's other edges: those do not call it."
)

register(
    Exercise(
        id="table_index",
        number=23,
        title="The table indices of post-anti-aliasing",
        stage="anti-aliasing",
        kind="step",
        points=2,
        answer="table_index",
        idea=POST_IDEA,
        stub=(
            "def table_index(m, dxy):\n"
            '    """m: a first-octant slope (a float, 0 <= m <= 1); dxy: a column\'s distance from\n'
            "    its middle pixel's centre (a float, -1/2 <= dxy <= 1/2).\n"
            "    Return (i, j), two ints: the slope and distance indices of the 51 x 51 x 3\n"
            '    table, each the nearest of the 50 divisions, halves rounded up."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=INDEX_SOLUTION,
        call=call_with_step("table_index", _post),
        reference=table_indices,
        public=POST_PUBLIC,
        generate=_table_index_case,
        **feature_tests(INDEX_FEATURES),
        variants=(
            _index_variant(
                "round_half_even",
                "(int)(x + 0.5) rounds halves up; Python's round() rounds them to even: "
                "m·50 = 12.5 gives 12, the table's index is 13",
                ("int(abs(m) * 50 + 0.5)", "round(abs(m) * 50)"),
                ("int((dxy + 0.5) * 50 + 0.5)", "round((dxy + 0.5) * 50)"),
            ),
            _index_variant(
                "truncated",
                "(int) truncates: add 1/2 first, so that the index is the nearest division, "
                "not the one below (m = 0.6747 is 33.7 divisions: i = 34, not 33)",
                ("int(abs(m) * 50 + 0.5)", "int(abs(m) * 50)"),
                ("int((dxy + 0.5) * 50 + 0.5)", "int((dxy + 0.5) * 50)"),
            ),
            _index_variant(
                "dxy_not_shifted",
                "the table's rows run from dxy = -1/2 (j = 0) to dxy = 1/2 (j = 50): shift "
                "dxy by 1/2 before scaling, j = (int)((dxy + 0.5) * 50 + 0.5)",
                ("int((dxy + 0.5) * 50 + 0.5)", "int(dxy * 50 + 0.5)"),
            ),
            _index_variant(
                "fifty_one",
                "the table has 51 rows but 50 divisions: m_i = i / 50 and dxy_j = -1/2 + j / 50, "
                "so scale by 50, not 51",
                ("int(abs(m) * 50 + 0.5)", "int(abs(m) * 51 + 0.5)"),
                ("int((dxy + 0.5) * 50 + 0.5)", "int((dxy + 0.5) * 51 + 0.5)"),
            ),
            _index_variant(
                "j_wraps",
                "j runs from 0 to 50: dxy = 1/2, the line half a pixel above the middle pixel's "
                "centre, reads the table's last row, j = 50. j = 0 is dxy = -1/2, the line half "
                "a pixel below its middle pixel's centre: the areas of other pixels. Do not wrap "
                "j to 0 (no % 50)",
                ("int((dxy + 0.5) * 50 + 0.5)", "int((dxy + 0.5) * 50 + 0.5) % 50"),
            ),
            _index_variant(
                "swapped",
                "the first index is the slope's (i), the second the distance's (j): return (i, j)",
                ("    return i, j\n", "    return j, i\n"),
            ),
        ),
        kinds=POST_KINDS,
        step="table_index",
        place=place_by_event("post_column", _look_up),
        result=lambda image: image[:, :, 0],
        stepper=(
            "import numpy as np\n"
            "from scanviz.antialias.post import post_antialias\n"
            "from scanviz.exercises.antialias import post_table\n"
            "image, trace = post_antialias(np.zeros((CASE['height'], CASE['width'])), "
            "CASE['segments'],\n"
            "                              kind=CASE['kind'], flags=CASE['flags'], trace=True)\n"
            "print(post_table(trace))"
        ),
    )
)

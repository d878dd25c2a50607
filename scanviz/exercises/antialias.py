"""Exercises on area-sampling anti-aliasing (scanviz.antialias; Wang 1989, ch. 4), through
`dislop_line` traced.

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
"""

from __future__ import annotations

import random

from .. import steps
from ..antialias.columns import LINE_BRANCHES
from ..antialias.line import dislop_line, middle_column
from .catalog import register
from .core import Case, Exercise, Variant, edited_variant

KINDS = ("dislop_column",)
CATEGORIES = ("shallow", "medium", "past 0.75", "45 degrees", "horizontal or vertical")
SIZE = 16  # the raster of the hidden cases


def _draw_with(step: str):
    def call(fn, inputs, tracer):
        with steps.using(**{step: fn}):
            return dislop_line(
                inputs["p0"], inputs["p1"], inputs["width"], inputs["height"], trace=tracer
            )

    return call


def middle_columns(trace: list) -> list:
    """The ``dislop_column`` events of the middle columns: the ones the formula runs in."""
    return [e for e in trace if e.kind == "dislop_column" and e.branch in LINE_BRANCHES]


def _column_of_call(index: int, trace: list) -> str:
    """The formula runs once per middle column, in the order the columns are traced."""
    middle = middle_columns(trace)
    if index >= len(middle):
        return f"call {index + 1}"
    event = middle[index]
    walked = f"column {event.x}" if event.major == "x" else f"row {event.y}"
    return f"{walked} (middle pixel ({event.x}, {event.y}))"


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
)


def _sixteenth(rng: random.Random, low: float, high: float) -> float:
    return round(rng.uniform(low, high) * 16) / 16


def _dislop_case(rng: random.Random) -> Case:
    """A line of 6 to 14 pixels along its major axis on a 16² raster, in any octant."""
    category = rng.choice(CATEGORIES)
    length = rng.randint(6, 14)
    if category == "shallow":
        rise = _sixteenth(rng, 0.05, 0.5) * length
    elif category == "medium":
        rise = _sixteenth(rng, 0.5, 0.75) * length
    elif category == "past 0.75":
        rise = _sixteenth(rng, 0.76, 1.0) * length
    elif category == "45 degrees":
        rise = float(length)
    else:
        rise = 0.0
    start = [_sixteenth(rng, 0.0, SIZE - 1 - length), _sixteenth(rng, 0.0, SIZE - 1 - rise)]
    if category == "45 degrees":  # the same dxy in every column: 1/2, 0 or 1/16 - 1/2
        offset = rng.choice((0.5, 0.0, 1 / 16 - 0.5))
        start[1] = start[0] + offset + round(start[1] - start[0] - offset)
    end = [start[0] + length, start[1] + rise]
    if rng.random() < 0.5:  # fall instead of rise: the walk negates v
        start[1], end[1] = end[1], start[1]
    if rng.random() < 0.5:  # run right to left: the walk reverses the segment
        start, end = end, start
    if rng.random() < 0.5:  # steep on the screen: the walk swaps x and y
        start, end = start[::-1], end[::-1]
    label = f"{category}: ({start[0]}, {start[1]}) to ({end[0]}, {end[1]})"
    return _case(label, start, end, SIZE, SIZE, category)


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


def _variant(name: str, hint: str, *edits: tuple[str, str]) -> Variant:
    return edited_variant(SOLUTION, name, hint, *edits)


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
    "The dissertation's formula: dw = Ta - 1, the first critical value fcv = (m + dw) / 2 "
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
            '    inside the 1-wide band, by the dissertation\'s formula (Fig 4-2)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=SOLUTION,
        call=_draw_with("dislop_column"),
        reference=middle_column,
        public=PUBLIC,
        generate=_dislop_case,
        variants=(
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
        banned=("scanviz.antialias", "line_column", "line_column_compiled", "middle_column"),
    )
)

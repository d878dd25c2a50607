"""Exercises on the midpoint line (scanviz.raster.lines): the decision step, then the whole loop."""

from __future__ import annotations

import random

import numpy as np

from ..raster.lines import midpoint_line, midpoint_step, octant
from ..trace import Recorder
from .cases import call_with_step
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

SIZE = 16  # lines of the hidden cases fit a SIZE x SIZE raster
STEPPER = (
    "from scanviz.widgets import line_stepper\n"
    "line_stepper(CASE['x0'], CASE['y0'], CASE['x1'], CASE['y1'])"
)


def _pixels(xs: np.ndarray, ys: np.ndarray) -> list[tuple[int, int]]:
    return list(zip(xs.tolist(), ys.tolist(), strict=True))


def _painted(returned) -> np.ndarray:
    """The (height, width) bool raster of a run's pixels; pixels off the raster are left out."""
    pixels, width, height = returned
    image = np.zeros((height, width), dtype=bool)
    for pixel in pixels:
        x, y = pixel
        if 0 <= x < width and 0 <= y < height:
            image[y, x] = True
    return image


def _ends(inputs) -> tuple[int, int, int, int]:
    return inputs["x0"], inputs["y0"], inputs["x1"], inputs["y1"]


def _midpoint_line(inputs: dict, tracer):
    xs, ys = midpoint_line(*_ends(inputs), trace=tracer)
    return _pixels(xs, ys), inputs["width"], inputs["height"]


def _line_loop(fn, inputs, tracer):
    return list(fn(*_ends(inputs), tracer)), inputs["width"], inputs["height"]


def reference_line(x0, y0, x1, y1, tracer):
    """The reference of `midpoint_loop`: scanviz's midpoint line, emitting to `tracer`."""
    return _pixels(*midpoint_line(x0, y0, x1, y1, trace=tracer))


def _pixel_of_call(index: int, trace: list) -> str:
    decided = [e for e in trace if e.kind == "line_step" and e.choice != "last"]
    if index < len(decided):
        return f"pixel ({decided[index].x}, {decided[index].y})"
    return f"call {index + 1}"


# (major, minor) extents of lines through midpoints: d == 0 on some step
TIES = ((2, 1), (4, 1), (4, 3), (6, 1), (6, 5))
_EXTENTS = {  # the (major, minor) extents of a feature's line, before scaling
    "tie, minor step +1": TIES,
    "tie, minor step -1": TIES,
    "horizontal or vertical": ((1, 0),),
    "45 degrees": ((1, 1),),
}


def _line_case(rng: random.Random, feature: str | None = None) -> Case:
    """A line inside a SIZE x SIZE raster in any octant; a third run exactly through midpoints.

    A `feature` of `LINE_FEATURES` picks extents, axis and directions that give the line it:
    a tie direction with the minor step's sign, a steep line, a line along the grid.
    """
    extents = _EXTENTS.get(feature)
    if extents is None and rng.random() < 1 / 3:
        extents = TIES
    if extents is not None:
        major, minor = rng.choice(extents)
        scale = rng.randint(1, (SIZE - 1) // major)
        major, minor = major * scale, minor * scale
    else:
        major = rng.randint(0 if feature is None else 1, SIZE - 1)  # 0: a single pixel
        low = 1 if feature == "diagonal step" else 0  # a diagonal step needs minor > 0
        high = major - 1 if feature in ("axial step", "steep") else major  # these minor < major
        minor = rng.randint(low, high)
    steep = feature == "steep" or (feature != "45 degrees" and rng.random() < 0.5)
    minor_step = {"tie, minor step +1": 1, "tie, minor step -1": -1}.get(feature)
    minor *= minor_step or rng.choice((1, -1))
    major *= rng.choice((1, -1))
    dx, dy = (minor, major) if steep else (major, minor)
    x0 = rng.randint(max(0, -dx), SIZE - 1 - max(0, dx))
    y0 = rng.randint(max(0, -dy), SIZE - 1 - max(0, dy))
    x1, y1 = x0 + dx, y0 + dy
    inputs = {"x0": x0, "y0": y0, "x1": x1, "y1": y1, "width": SIZE, "height": SIZE}
    return Case(f"({x0}, {y0}) to ({x1}, {y1})", inputs, feature or _category(x0, y0, x1, y1))


def _setup(reference) -> object:
    return next(e for e in reference.trace if e.kind == "line_setup")


def _ties(reference, tie_steps: bool) -> bool:
    steps = [e for e in reference.trace if e.kind == "line_step" and e.choice != "last"]
    return _setup(reference).tie_steps == tie_steps and any(e.d == 0 for e in steps)


def _choice(choice: str):
    return lambda case, reference: any(
        e.kind == "line_step" and e.choice == choice for e in reference.trace
    )


def _extents(case) -> tuple[int, int]:
    i = case.inputs
    return abs(i["x1"] - i["x0"]), abs(i["y1"] - i["y0"])


LINE_FEATURES = {
    "diagonal step": _choice("diagonal"),
    "axial step": _choice("axial"),
    "tie, minor step +1": lambda case, reference: _ties(reference, False),
    "tie, minor step -1": lambda case, reference: _ties(reference, True),
    "steep": lambda case, reference: _setup(reference).major == "y",
    "horizontal or vertical": lambda case, reference: (
        min(_extents(case)) == 0 < max(_extents(case))
    ),
    "45 degrees": lambda case, reference: len(set(_extents(case))) == 1 and _extents(case)[0] > 0,
}
"""The features of the lines' hidden cases: each branch of the decision (diagonal, axial, a tie
each way), a steep line, and lines along the grid: horizontal, vertical and 45 degrees, where d
never changes sign or sits on a tie at every step."""


def _category(x0: int, y0: int, x1: int, y1: int) -> str:
    """``octant 3`` or ``octant 3, ties``: what a hidden case is shown as."""
    recorder = Recorder(["line_step"])
    midpoint_line(x0, y0, x1, y1, trace=recorder)
    ties = any(e.d == 0 and e.choice != "last" for e in recorder.trace())
    return f"octant {octant(x1 - x0, y1 - y0)}{', ties' if ties else ''}"


def _line(label: str, x0: int, y0: int, x1: int, y1: int, width: int, height: int) -> Case:
    return Case(label, {"x0": x0, "y0": y0, "x1": x1, "y1": y1, "width": width, "height": height})


IDEA_CONVENTIONS = (
    "scanviz: y up, pixel (x, y) is the unit square with its sample at the lower-left corner "
    "(x, y); both endpoints are drawn."
)

SHALLOW = _line("shallow line (octant 0)", 0, 0, 11, 4, 12, 5)
TIE = _line("through a midpoint (tie)", 1, 1, 9, 5, 10, 6)
DOWN_TIES = _line("down to the right, ties (octant 7)", 1, 5, 9, 1, 10, 6)

# --- 1: the decision step ----------------------------------------------------------------

DECISION_SOLUTION = """\
def midpoint_step(d, dx, dy):
    if d < 0:
        return True, d + 2 * (dx - dy)
    return False, d - 2 * dy
"""

DECISION_CASES = (SHALLOW, TIE, _line("steep line (octant 1)", 2, 1, 6, 12, 8, 13), DOWN_TIES)

register(
    Exercise(
        id="midpoint_decision",
        number=1,
        title="The midpoint decision variable",
        stage="lines",
        kind="step",
        points=2,
        answer="midpoint_step",
        idea=(
            "For a line of slope 0..1 from (x0, y0) to (x1, y1), the implicit function "
            "`f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0` is positive above the line. "
            "After drawing (x, y), test the **midpoint** (x + 1, y + 1/2) between the two "
            "candidates: if `f < 0` there, the line passes above it and the next pixel is "
            "north-east (*diagonal*), else east (*axial*).\n\n"
            "The decision variable `d = 2 f(midpoint)` stays an integer: it starts at "
            "`dx - 2 dy` and changes by `2 (dx - dy)` after a diagonal step, by `-2 dy` after an "
            "axial one. A tie (`d == 0`: the line through the midpoint) steps east. The loop maps "
            "the other seven octants to this one (dx is the major extent, dy the minor); "
            + IDEA_CONVENTIONS
        ),
        stub=(
            "def midpoint_step(d, dx, dy):\n"
            '    """d: the decision variable 2 f(midpoint), an int; dx >= dy >= 0: the line\'s\n'
            "    extents along its major and minor axes (ints, first-octant frame).\n"
            "    Return (diagonal, d_next): diagonal is True for the diagonal (NE) step, False\n"
            '    for the axial (E) one; d_next is d at the next midpoint (an int)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=DECISION_SOLUTION,
        call=call_with_step("midpoint_step", _midpoint_line),
        reference=midpoint_step,
        public=DECISION_CASES,
        generate=_line_case,
        **feature_tests(LINE_FEATURES),
        variants=(
            edited_variant(
                DECISION_SOLUTION,
                "tie_diagonal",
                "a tie (d == 0) takes the diagonal step: the line through the midpoint keeps "
                "the smaller y, so test d < 0, not d <= 0",
                ("if d < 0:", "if d <= 0:"),
            ),
            edited_variant(
                DECISION_SOLUTION,
                "not_doubled",
                "the increments of f, not of d = 2 f: d grows by 2 (dx - dy) after a diagonal "
                "step and by -2 dy after an axial one",
                ("d + 2 * (dx - dy)", "d + (dx - dy)"),
                ("d - 2 * dy", "d - dy"),
            ),
            edited_variant(
                DECISION_SOLUTION,
                "swapped_increments",
                "the increments are swapped: a diagonal step adds 2 (dx - dy), an axial one -2 dy",
                (
                    "return True, d + 2 * (dx - dy)\n    return False, d - 2 * dy",
                    "return True, d - 2 * dy\n    return False, d + 2 * (dx - dy)",
                ),
            ),
            edited_variant(
                DECISION_SOLUTION,
                "sign_flipped",
                "the test is reversed: d < 0 means the midpoint is below the line, so the line "
                "passes above it and the next pixel is the diagonal one",
                ("if d < 0:", "if d > 0:"),
            ),
        ),
        kinds=("line_setup", "line_step"),
        step="midpoint_step",
        place=_pixel_of_call,
        result=lambda returned: returned[0],
        raster=_painted,
        stepper=STEPPER,
    )
)

# --- 2: the whole loop, all octants --------------------------------------------------------

LOOP_SOLUTION = """\
from scanviz.trace.events import LineSetup, LineStep

def octant(dx, dy):
    if dx == 0 and dy == 0:
        return 0
    quadrant = 0
    while not (dx > 0 and dy >= 0):  # rotate by -90 degrees until in [0, 90)
        dx, dy = dy, -dx
        quadrant += 1
    return 2 * quadrant + (dy >= dx)

def midpoint_line(x0, y0, x1, y1, tracer):
    step_x = 1 if x1 >= x0 else -1
    step_y = 1 if y1 >= y0 else -1
    steep = abs(y1 - y0) > abs(x1 - x0)
    major = max(abs(x1 - x0), abs(y1 - y0))
    minor = min(abs(x1 - x0), abs(y1 - y0))
    d = major - 2 * minor
    d_axial, d_diagonal = -2 * minor, 2 * (major - minor)
    tie_steps = (step_x if steep else step_y) < 0
    tracer.emit(LineSetup(
        x0=x0, y0=y0, x1=x1, y1=y1, octant=octant(x1 - x0, y1 - y0),
        major="y" if steep else "x", step_x=step_x, step_y=step_y,
        d_start=d, d_axial=d_axial, d_diagonal=d_diagonal, tie_steps=tie_steps,
    ))
    pixels = []
    x, y = x0, y0
    for i in range(major + 1):
        pixels.append((x, y))
        if i == major:
            tracer.emit(LineStep(x, y, d, "last"))
            break
        diagonal = d < 0 or (d == 0 and tie_steps)
        tracer.emit(LineStep(x, y, d, "diagonal" if diagonal else "axial"))
        if steep:
            y += step_y
        else:
            x += step_x
        if diagonal:
            if steep:
                x += step_x
            else:
                y += step_y
            d += d_diagonal
        else:
            d += d_axial
    return pixels
"""

LOOP_CASES = (
    SHALLOW,
    TIE,
    DOWN_TIES,
    _line("steep, down to the left (octant 5)", 6, 12, 2, 1, 8, 13),
    _line("one pixel", 3, 2, 3, 2, 5, 4),
    _line("45 degrees, down to the right (octant 7)", 1, 8, 8, 1, 10, 10),
)

register(
    Exercise(
        id="midpoint_loop",
        number=2,
        title="The midpoint line in all eight octants",
        stage="lines",
        kind="loop",
        points=4,
        answer="midpoint_line",
        idea=(
            "Write the whole midpoint line. The axis with the larger extent is the **major** "
            "one: it steps once per pixel, the other (**minor**) one only on diagonal steps, "
            "each in the direction of its sign. With `dx` the major extent and `dy` the minor "
            "one, `d = 2 f(midpoint)` starts at `dx - 2 dy`, steps by `2 (dx - dy)` after a "
            "diagonal step and by `-2 dy` after an axial one; `d < 0` takes the diagonal step.\n\n"
            "Ties (`d == 0`) take the pixel with the **smaller minor coordinate**: axial where "
            "the minor axis points up (or right), diagonal where it points down (or left). Then "
            "reversing the endpoints gives the same pixels. " + IDEA_CONVENTIONS
        ),
        stub=(
            "from scanviz.trace.events import LineSetup, LineStep\n\n"
            "def midpoint_line(x0, y0, x1, y1, tracer):\n"
            '    """Draw the line from (x0, y0) to (x1, y1) (ints); return its pixels [(x, y), ...]\n'
            "    in drawing order, both endpoints included (one pixel per major step).\n\n"
            "    First emit tracer.emit(LineSetup(x0=, y0=, x1=, y1=, octant=, major=, step_x=,\n"
            "    step_y=, d_start=, d_axial=, d_diagonal=, tie_steps=)):\n"
            "      octant: k in 0..7 with the angle of (x1 - x0, y1 - y0), counter-clockwise\n"
            "        from +x, in [45k, 45(k + 1)) degrees (0 for a single pixel);\n"
            '      major: "x" if |x1 - x0| >= |y1 - y0|, else "y";\n'
            "      step_x, step_y: +1 if x1 >= x0 (y1 >= y0), else -1;\n"
            "      d_start, d_axial, d_diagonal: d at the first midpoint and its changes (ints);\n"
            "      tie_steps: whether d == 0 takes the diagonal step (the minor step is -1).\n"
            "    Then for each pixel, tracer.emit(LineStep(x, y, d, choice)): d before the\n"
            '    decision, choice "axial", "diagonal", or "last" for the last pixel."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=LOOP_SOLUTION,
        call=_line_loop,
        reference=reference_line,
        public=LOOP_CASES,
        generate=_line_case,
        **feature_tests(LINE_FEATURES),
        variants=(
            edited_variant(
                LOOP_SOLUTION,
                "tie_always_diagonal",
                "every tie takes the diagonal step: a tie keeps the smaller minor coordinate, "
                "diagonal only where the minor step is -1 (d < 0 or d == 0 and tie_steps)",
                ("diagonal = d < 0 or (d == 0 and tie_steps)", "diagonal = d <= 0"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "tie_ignores_direction",
                "every tie takes the axial step: where the minor axis points down a tie must "
                "go diagonal, or the pixels depend on which endpoint comes first",
                ("diagonal = d < 0 or (d == 0 and tie_steps)", "diagonal = d < 0"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "not_doubled",
                "d is f at the midpoint, not 2 f: doubling it, d starts at dx - 2 dy and changes "
                "by 2 (dx - dy) or -2 dy, all integers (no halves)",
                ("d = major - 2 * minor", "d = major // 2 - minor"),
                (
                    "d_axial, d_diagonal = -2 * minor, 2 * (major - minor)",
                    "d_axial, d_diagonal = -minor, major - minor",
                ),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "swapped_increments",
                "the increments are swapped: d changes by 2 (dx - dy) after a diagonal step "
                "and by -2 dy after an axial one",
                (
                    "d_axial, d_diagonal = -2 * minor, 2 * (major - minor)",
                    "d_diagonal, d_axial = -2 * minor, 2 * (major - minor)",
                ),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "strict_step_sign",
                "the steps' signs are +1 only for x1 > x0 (y1 > y0): a horizontal or vertical "
                "line, or one pixel, has step +1 along the axis it does not move on "
                "(x1 >= x0, y1 >= y0)",
                ("step_x = 1 if x1 >= x0 else -1", "step_x = 1 if x1 > x0 else -1"),
                ("step_y = 1 if y1 >= y0 else -1", "step_y = 1 if y1 > y0 else -1"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "octant_at_45",
                "a diagonal line (|dx| == |dy|) is put in the octant below its angle: octant k "
                "holds the angles [45k, 45(k + 1)), so a line at 45k degrees is in octant k "
                "(dy >= dx once turned into the first quadrant, not dy > dx)",
                ("return 2 * quadrant + (dy >= dx)", "return 2 * quadrant + (dy > dx)"),
            ),
            edited_variant(
                LOOP_SOLUTION,
                "forgot_last_pixel",
                "the last pixel is missing: a line has max(|dx|, |dy|) + 1 pixels, both "
                "endpoints included",
                ("for i in range(major + 1):", "for i in range(major):"),
            ),
        ),
        kinds=("line_setup", "line_step"),
        result=lambda returned: returned[0],
        raster=_painted,
        stepper=STEPPER,
    )
)

"""Exercises on the Floating Perimeter Algorithm (scanviz.surfaces.perimeter), through
`floating_perimeter` in lines mode.

Two steps of Fig. 2-4 (Wang 1989, ch. 2): ``perimeter_test``, whether a raster
point of an edge is hidden by the perimeter the facets before it left, and
``perimeter_merge``, how a facet's visible points (Bbuf) widen the
perimeter after all its edges. The real FPA runs with the student's step;
its per-edge points, flags and segments (``perimeter_edge``) and its
perimeter updates (``perimeter_update``) are graded, then the hidden-line
raster. Cases are small grid surfaces with a viewpoint in each kind of
viewing case, parallel views among them, and one where the perimeter test
hides points that no earlier facet covers (a hole): the reference is the
Wang's (1989) test, not the z-buffer's truth.
"""

from __future__ import annotations

import functools
import math
import random

from ..surfaces import GridSurface, View, floating_perimeter
from ..surfaces.perimeter import perimeter_merge, perimeter_test
from .cases import call_with_step, place_by_event
from .catalog import register
from .core import Case, Exercise, edited_variant, feature_tests

KINDS = ("perimeter_edge", "perimeter_update")
VIEWINGS = ("face-on", "edge-on", "corner-on", "parallel")
ARRAYS = ("top", "bottom", "right", "left")
STEPPER = (
    "from scanviz.exercises.perimeter import case_surface, case_view\n"
    "from scanviz.widgets.surfaces import perimeter_stepper\n"
    "perimeter_stepper(case_surface(CASE), case_view(CASE), CASE['width'], CASE['height'])"
)


def case_surface(inputs: dict) -> GridSurface:
    """The grid surface of a case: its planes x, y and heights z[row][column]."""
    return GridSurface(inputs["x"], inputs["y"], inputs["z"])


def case_view(inputs: dict) -> View:
    """The view of a case: viewpoint, viewing direction and projection."""
    return View(tuple(inputs["point"]), tuple(inputs["direction"]), inputs["projection"])


def _floating_perimeter(inputs: dict, tracer):
    return floating_perimeter(
        case_surface(inputs),
        case_view(inputs),
        inputs["width"],
        inputs["height"],
        "lines",
        trace=tracer,
    )


def _point_of_call(index: int, trace: list) -> str:
    """Which raster point call `index` tested: every point of every edge, in processing order
    (the cases' grids are fitted to the raster, so every point is on it and is tested)."""
    for event in trace:
        if event.kind != "perimeter_edge":
            continue
        if index < len(event.points):
            x, y = event.points[index]
            return f"point ({x}, {y}) of facet {event.facet}"
        index -= len(event.points)
    return f"call {index + 1}"


_facet_of_call = place_by_event("perimeter_update", lambda update: f"facet {update.facet}")


def _merged(args: tuple, kwargs: dict, returned: object) -> dict:
    """What a merge produced: the four arrays after the call (it changes them in place)."""
    return {name: list(map(int, array)) for name, array in zip(ARRAYS, args[:4], strict=True)}


def _case(x, y, z, point, direction, width, height, projection="perspective") -> dict:
    return {
        "x": x,
        "y": y,
        "z": z,
        "point": point,
        "direction": direction,
        "projection": projection,
        "width": width,
        "height": height,
    }


def _heights(f, x: list, y: list) -> list:
    return [[round(f(xi, yj), 2) for xi in x] for yj in y]


AXIS_5 = [-2.0, -1.0, 0.0, 1.0, 2.0]
PUBLIC = (
    Case(
        "a hill seen from a corner (case 9)",
        _case(
            AXIS_5,
            AXIS_5,
            _heights(lambda x, y: math.exp(-x * x - y * y), AXIS_5, AXIS_5),
            [3.0, 4.0, 1.2],
            [-3.0, -4.0, -0.9],
            32,
            20,
        ),
    ),
    Case(
        "a ridge seen edge-on (case 2): the valley behind it is partly hidden",
        _case(
            [0.0, 1.0, 2.0, 3.0],
            [0.0, 1.0, 2.0, 3.0, 4.0],
            [
                [0.0, 0.0, 0.0, 0.0],
                [0.2, 0.3, 0.2, 0.1],
                [1.0, 1.2, 1.1, 0.9],
                [0.3, 0.2, 0.4, 0.3],
                [0.5, 0.6, 0.8, 0.7],
            ],
            [1.5, -4.0, 1.0],
            [0.0, 1.0, -0.1],
            36,
            18,
        ),
    ),
    Case(
        "a tall peak seen from above the grid (case 1): its far side is hidden",
        _case(
            AXIS_5,
            AXIS_5,
            _heights(
                lambda x, y: 3 * math.exp(-2 * ((x - 0.5) ** 2 + (y - 0.5) ** 2)), AXIS_5, AXIS_5
            ),
            [-1.5, -1.9, 2.5],
            [0.8, 1.0, -0.8],
            32,
            32,
        ),
    ),
    Case(
        "a saddle in parallel projection from the lower right (case 8)",
        _case(
            [-1.5, -0.5, 0.5, 1.5],
            [-1.5, -0.75, 0.0, 0.75, 1.5],
            _heights(
                lambda x, y: 0.4 * (x * x - y * y),
                [-1.5, -0.5, 0.5, 1.5],
                [-1.5, -0.75, 0.0, 0.75, 1.5],
            ),
            [0.0, 0.0, 5.0],
            [-1.0, 0.2, -0.3],
            40,
            24,
            "parallel",
        ),
    ),
    Case(
        # Found by compare_with_zbuffer on GridSurface.random(3, 3, seed=275), heights doubled.
        "a hole: facet 4's left edge is hidden at (11, 16) and (12, 18), where no earlier "
        "facet is (the z-buffer shows them)",
        _case(
            [0.0, 1.0, 2.0],
            [0.0, 1.0, 2.0],
            [[1.85, 1.6, 0.06], [0.08, 1.77, 1.6], [0.89, 0.54, 0.29]],
            [3.4, -2.8, 2.6],
            [-2.4, 3.8, -2.1],
            32,
            32,
        ),
    ),
)


def _axis(rng: random.Random, n: int) -> list:
    """n increasing grid planes from 0, uniform or with steps of 0.5, 1 or 1.5 (non-uniform)."""
    if rng.random() < 0.5:
        return [float(i) for i in range(n)]
    planes = [0.0]
    for _ in range(n - 1):
        planes.append(planes[-1] + rng.choice((0.5, 1.0, 1.5)))
    return planes


def _surface_heights(rng: random.Random, x: list, y: list) -> list:
    """Random heights in [0, 2), or a bump of random height, place and width."""
    if rng.random() < 0.5:
        return [[round(rng.uniform(0, 2), 2) for _ in x] for _ in y]
    cx, cy = rng.uniform(x[0], x[-1]), rng.uniform(y[0], y[-1])
    peak, spread = rng.uniform(0.5, 2.5), rng.uniform(0.5, 2.0)
    return _heights(lambda u, v: peak * math.exp(-((u - cx) ** 2 + (v - cy) ** 2) / spread), x, y)


def _outside(rng: random.Random, low: float, high: float) -> float:
    """A coordinate beyond one end of [low, high], by 1 to 4 units."""
    away = rng.uniform(1, 4)
    return low - away if rng.random() < 0.5 else high + away


def _viewpoint(rng: random.Random, viewing: str, x: list, y: list, top: float) -> tuple:
    """(point, direction, projection) of a view of the `viewing` kind toward the grid's centre,
    low enough that the surface mostly hides some of itself."""
    (x0, x1), (y0, y1) = (x[0], x[-1]), (y[0], y[-1])
    centre = ((x0 + x1) / 2, (y0 + y1) / 2)
    if viewing == "parallel":
        direction = (rng.uniform(-1, 1), rng.uniform(-1, 1), -rng.uniform(0.15, 0.6))
        return (*centre, top + 5), direction, "parallel"
    if viewing == "face-on":  # over the grid near one side, looking across it
        near, across = rng.choice((0.1, 0.9)) + rng.uniform(-0.1, 0.1), rng.random()
        fx, fy = (near, across) if rng.random() < 0.5 else (across, near)
        vx, vy = x0 + fx * (x1 - x0), y0 + fy * (y1 - y0)
    elif viewing == "edge-on":
        vx, vy = rng.uniform(x0, x1), rng.uniform(y0, y1)
        if rng.random() < 0.5:
            vx = _outside(rng, x0, x1)
        else:
            vy = _outside(rng, y0, y1)
    else:
        vx, vy = _outside(rng, x0, x1), _outside(rng, y0, y1)
    vz = top + rng.uniform(0.2, 1.5)
    steep = rng.uniform(0.5, 1.2) if viewing == "face-on" else rng.uniform(0.3, 1.0)
    return (vx, vy, vz), (centre[0] - vx, centre[1] - vy, -steep * vz), "perspective"


def _perimeter_case(rng: random.Random, feature: str | None = None) -> Case:
    """A grid surface, a view and a raster; a viewing `feature` is that viewing."""
    viewing = feature if feature in VIEWINGS else rng.choice(VIEWINGS)
    while True:  # a perspective view must have every grid point in front of it
        nx, ny = rng.randint(3, 6), rng.randint(3, 6)
        x, y = _axis(rng, nx), _axis(rng, ny)
        z = _surface_heights(rng, x, y)
        point, direction, projection = _viewpoint(rng, viewing, x, y, max(map(max, z)))
        inputs = _case(
            x,
            y,
            z,
            [round(v, 2) for v in point],
            [round(v, 2) for v in direction],
            rng.randint(24, 48),
            rng.randint(24, 48),
            projection,
        )
        try:
            case_view(inputs).screen_from_world(case_surface(inputs).points(), 2, 2)
        except ValueError:
            continue
        break
    return Case(
        f"{viewing}: {nx}x{ny} grid, {inputs['width']}x{inputs['height']} raster",
        inputs,
        viewing,
    )


def _viewing(name: str):
    return lambda case, reference: _kind_of_view(case) == name


def _kind_of_view(case: Case) -> str:
    """The viewing of a case from its inputs: parallel, else by where the eye is (over the grid:
    face-on; beside one side: edge-on; beside a corner: corner-on)."""
    if case.inputs["projection"] == "parallel":
        return "parallel"
    x, y = case.inputs["x"], case.inputs["y"]
    px, py, _ = case.inputs["point"]
    beside = (not x[0] <= px <= x[-1]) + (not y[0] <= py <= y[-1])
    return ("face-on", "edge-on", "corner-on")[beside]


def _tests(reference) -> list[tuple]:
    """(top, bottom, right, left, x, y) of every perimeter test the reference made."""
    return [args for args, _ in reference.arguments]


def _where(top, bottom, right, left, x, y) -> set[str]:
    """How the perimeter test decides the point (x, y): by which of its two comparisons, and
    whether the point is on the perimeter."""
    in_column, in_row = bottom[x] < y < top[x], left[y] < x < right[y]
    if not in_column:
        ways = {"outside the column"}
    else:
        ways = {"hidden" if in_row else "in the column, not inside the row"}
    on_column = y in (bottom[x], top[x]) and left[y] <= x <= right[y]
    on_row = x in (left[y], right[y]) and bottom[x] <= y <= top[x]
    return ways | ({"on the perimeter"} if on_column or on_row else set())


TEST_FEATURES = {
    where: lambda case, reference, where=where: any(
        where in _where(*args) for args in _tests(reference)
    )
    for where in (
        "hidden",
        "outside the column",
        "in the column, not inside the row",
        "on the perimeter",
    )
}
"""Tests of the perimeter test's features: each way a point is decided (hidden strictly inside,
outside its column, inside the column but not strictly inside its row), and a point on the
perimeter."""


def _widens(top, bottom, right, left, bbuf) -> set[str]:
    """Which of the perimeter's arrays a merge of `bbuf` changes ("inside already" if a point
    changes none)."""
    changes = set()
    for x, y in bbuf:
        changed = {
            "raises top": y > top[x],
            "lowers bottom": y < bottom[x],
            "raises right": x > right[y],
            "lowers left": x < left[y],
        }
        changes |= {name for name, yes in changed.items() if yes}
        if not any(changed.values()):
            changes.add("inside already")
    return changes


MERGE_FEATURES = {
    name: lambda case, reference, name=name: any(
        name in _widens(*args) for args, _ in reference.arguments
    )
    for name in ("raises top", "lowers bottom", "raises right", "lowers left", "inside already")
}
"""Tests of the merge's features: a point that widens each of the four arrays, and one the
perimeter holds already (which must change nothing)."""


TEST_SOLUTION = """\
def perimeter_test(top, bottom, right, left, x, y):
    inside_column = bottom[x] < y < top[x]
    inside_row = left[y] < x < right[y]
    return inside_column and inside_row
"""


_test_variant = functools.partial(edited_variant, TEST_SOLUTION)


IDEA = (
    "The **Floating Perimeter Algorithm** (Wang 1989, ch. 2, Fig. 2-4) draws the "
    "hidden lines of a grid surface z = f(x, y). Its facets are taken **nearest first** (the "
    "enumeration of the viewing case), so what hides a facet's edge has been drawn already. "
    "What the facets so far cover on the screen is kept only as its **floating perimeter**, "
    "four 1-D arrays over the W x H raster (screen y up, row 0 at the bottom):\n\n"
    "- `top[x]`, `bottom[x]`: the highest and lowest visible point so far in column x "
    "(at first 0 and H: nothing);\n"
    "- `right[y]`, `left[y]`: the rightmost and leftmost visible point so far in row y "
    "(at first 0 and W).\n\n"
    "Each edge a facet processes is rasterised into points (x, y); each point is tested "
    "against the perimeter the facets before it left: **hidden iff strictly inside it both "
    "ways**, `bottom[x] < y < top[x]` and `left[y] < x < right[y]`; on the perimeter counts "
    "as visible (that keeps the vertex an edge shares with a visible edge drawn). The visible "
    "runs of each edge are drawn. After **all** of a facet's edges, its visible points (Bbuf) "
    "widen the perimeter: `top[x] = max(top[x], y)`, `bottom[x] = min(bottom[x], y)`, "
    "`right[y] = max(right[y], x)`, `left[y] = min(left[y], x)`.\n\n"
    "The test is Wang's (1989), not the truth: where the facets so far leave a notch "
    "inside their row and column spans (a *hole*), it hides points no earlier facet covers. "
    "The last public case has one; the reference hides those points, and so must you "
    '(see it in the stepper with `CASE = public_inputs("{id}", 4)`).'
)

EXERCISE_TEST = register(
    Exercise(
        id="perimeter_test",
        number=18,
        title="The floating perimeter's visibility test",
        stage="grid surfaces",
        kind="step",
        points=2,
        answer="perimeter_test",
        idea=IDEA.format(id="perimeter_test")
        + (
            "\n\nYour step is the test of one point. It is called for every raster point of "
            "every edge, with the arrays as the facets before the edge's own left them (a "
            "facet's points widen the perimeter only after all its edges)."
        ),
        stub=(
            "def perimeter_test(top, bottom, right, left, x, y):\n"
            '    """top, bottom: the perimeter\'s highest and lowest y in each column (numpy\n'
            "    int64, W entries); right, left: its rightmost and leftmost x in each row (H\n"
            "    entries). x, y: a raster point of an edge (ints, 0 <= x < W, 0 <= y < H).\n"
            "    Return True if the point is hidden: strictly inside the perimeter, both in\n"
            '    its column and in its row; False if it is visible (outside or on it)."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=TEST_SOLUTION,
        call=call_with_step("perimeter_test", _floating_perimeter),
        reference=perimeter_test,
        public=PUBLIC,
        generate=_perimeter_case,
        **feature_tests({**{v: _viewing(v) for v in VIEWINGS}, **TEST_FEATURES}),
        variants=(
            _test_variant(
                "on_perimeter_hidden",
                "a point on the perimeter (y == top[x], x == left[y], ...) is visible: hidden "
                "only strictly inside, bottom[x] < y < top[x] and left[y] < x < right[y] (that "
                "keeps the vertex a hidden edge shares with a visible one drawn)",
                ("bottom[x] < y < top[x]", "bottom[x] <= y <= top[x]"),
                ("left[y] < x < right[y]", "left[y] <= x <= right[y]"),
            ),
            _test_variant(
                "columns_only",
                "the column span alone hides points beside what was drawn: a point is hidden "
                "only if it is also strictly inside its row's span, left[y] < x < right[y]",
                ("return inside_column and inside_row", "return inside_column"),
            ),
            _test_variant(
                "or_for_and",
                "hidden needs both spans: strictly inside the column's (bottom[x] < y < top[x]) "
                "and the row's (left[y] < x < right[y]); either one alone is not enough",
                ("return inside_column and inside_row", "return inside_column or inside_row"),
            ),
            _test_variant(
                "swapped_axes",
                "top and bottom are per column: indexed by x, they bound y (bottom[x] < y < "
                "top[x]); right and left are per row: indexed by y, they bound x",
                ("bottom[x] < y < top[x]", "bottom[y] < x < top[y]"),
                ("left[y] < x < right[y]", "left[x] < y < right[x]"),
            ),
        ),
        kinds=KINDS,
        step="perimeter_test",
        place=_point_of_call,
        raster=lambda result: result.lines,
        stepper=STEPPER,
    )
)


MERGE_UPDATES = """\
        top[x] = max(top[x], y)
        bottom[x] = min(bottom[x], y)
        right[y] = max(right[y], x)
        left[y] = min(left[y], x)
"""

MERGE_SOLUTION = (
    "def perimeter_merge(top, bottom, right, left, bbuf):\n    for x, y in bbuf:\n" + MERGE_UPDATES
)

OVERWRITTEN = """\
        top[x] = y
        bottom[x] = y
        right[y] = x
        left[y] = x
"""
AXES_SWAPPED = """\
        top[y] = max(top[y], x)
        bottom[y] = min(bottom[y], x)
        right[x] = max(right[x], y)
        left[x] = min(left[x], y)
"""
MIN_MAX_SWAPPED = """\
        top[x] = min(top[x], y)
        bottom[x] = max(bottom[x], y)
        right[y] = min(right[y], x)
        left[y] = max(left[y], x)
"""


_merge_variant = functools.partial(edited_variant, MERGE_SOLUTION)


EXERCISE_MERGE = register(
    Exercise(
        id="perimeter_merge",
        number=19,
        title="Widening the floating perimeter",
        stage="grid surfaces",
        kind="step",
        points=2,
        answer="perimeter_merge",
        idea=IDEA.format(id="perimeter_merge")
        + "\n\nYour step is the merge, once per facet: it is given the facet's visible points "
        "and changes the four arrays **in place** (the algorithm keeps using the same arrays). "
        "A wrong merge shows first in the facet's `perimeter_update`, then in the edges of the "
        "later facets, tested against your perimeter.",
        stub=(
            "def perimeter_merge(top, bottom, right, left, bbuf):\n"
            '    """top, bottom: the perimeter\'s highest and lowest y in each column (numpy\n'
            "    int64, W entries); right, left: its rightmost and leftmost x in each row (H\n"
            "    entries). bbuf: the facet's visible raster points, a list of (x, y) on the\n"
            "    raster, after all its edges were tested.\n"
            "    Widen the perimeter to every point, changing the four arrays in place:\n"
            "    raise top[x] and right[y], lower bottom[x] and left[y] to reach (x, y).\n"
            '    Return None."""\n'
            "    raise NotImplementedError\n"
        ),
        solution=MERGE_SOLUTION,
        call=call_with_step("perimeter_merge", _floating_perimeter),
        reference=perimeter_merge,
        public=PUBLIC,
        generate=_perimeter_case,
        **feature_tests({**{v: _viewing(v) for v in VIEWINGS}, **MERGE_FEATURES}),
        variants=(
            _merge_variant(
                "reset_each_facet",
                "the perimeter accumulates: it bounds every facet drawn so far, so each merge "
                "widens the stored arrays; do not start them afresh (0, H, 0, W) for each facet",
                (
                    "    for x, y in bbuf:\n",
                    "    top[:], bottom[:] = 0, len(right)\n"
                    "    right[:], left[:] = 0, len(top)\n"
                    "    for x, y in bbuf:\n",
                ),
            ),
            _merge_variant(
                "overwrites",
                "widen, do not overwrite: top[x] = max(top[x], y) (and min for bottom and "
                "left): with top[x] = y the last point of Bbuf in the column decides",
                (MERGE_UPDATES, OVERWRITTEN),
            ),
            _merge_variant(
                "top_only",
                "all four arrays widen at every visible point: top[x] and right[y] are raised, "
                "bottom[x] and left[y] lowered; with one of them left alone nothing is strictly "
                "inside the perimeter",
                (MERGE_UPDATES, "        top[x] = max(top[x], y)\n"),
            ),
            _merge_variant(
                "swapped_axes",
                "top and bottom are per column: index them by x and store y (top[x] = max(top[x], "
                "y)); right and left are per row: index them by y and store x",
                (MERGE_UPDATES, AXES_SWAPPED),
            ),
            _merge_variant(
                "min_max_swapped",
                "top[x] is the highest y seen in column x: raise it with max(top[x], y), as "
                "right[y]; lower bottom[x] and left[y] with min. With min and max swapped the "
                "perimeter never grows and nothing is ever hidden",
                (MERGE_UPDATES, MIN_MAX_SWAPPED),
            ),
        ),
        kinds=KINDS,
        step="perimeter_merge",
        place=_facet_of_call,
        output=_merged,
        raster=lambda result: result.lines,
        stepper=STEPPER,
    )
)

"""Random inputs for hidden and practice cases (the shapes that break textbook code), and the
pieces the exercise modules share to declare an exercise.

Every generator takes a `random.Random` (seeded by the grader from the course
secret, or locally for practice) and returns plain values, so a case crosses
the sandbox boundary as JSON. `call_with_step` and `place_by_event` build an
exercise's ``call`` and ``place``; `case_polygons` and `polygon_lists` turn the
polygons of a visibility case into `ScreenPolygons` and back.
"""

from __future__ import annotations

import math
import random
from collections.abc import Callable

import numpy as np

from .. import steps
from ..visibility import ScreenPolygons

FEATURES = ("convex", "concave", "horizontal edges", "shared vertex", "sliver", "on pixel centers")


def plane_polygon(
    rng: random.Random, width: int, height: int, *, depth: tuple[float, float], slope: float
) -> list:
    """A triangle or convex quad of [x, y, z] with a random depth plane, either way round.

    Its depth at its centre is in `depth`, its steps dz/dx and dz/dy within
    +-`slope`; half of them are clockwise (seen from the back).
    """
    n, cx, cy = rng.choice((3, 4)), rng.uniform(1, width - 1), rng.uniform(1, height - 1)
    radius = rng.uniform(2, max(width, height) / 2)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(n))
    z0, dzdx, dzdy = rng.uniform(*depth), rng.uniform(-slope, slope), rng.uniform(-slope, slope)
    points = []
    for a in angles:
        x, y = cx + radius * math.cos(a), cy + radius * math.sin(a)
        points.append([round(x, 3), round(y, 3), round(z0 + dzdx * (x - cx) + dzdy * (y - cy), 4)])
    return points[::-1] if rng.random() < 0.5 else points


def grid_value(rng: random.Random, low: float, high: float, step: float = 0.25) -> float:
    """A value in [low, high] on a grid of `step` (quarter pixels by default: ties happen)."""
    return round(rng.uniform(low, high) / step) * step


def star(
    rng: random.Random,
    center: tuple[float, float],
    radius: float,
    points: int,
    turn: int = 0,
    step: float = 0.25,
) -> list:
    """A star polygon {points/turn} on a grid of `step`: each vertex `turn` points on from the last
    (default 2 for an odd count, whose centre has winding 2; {7/3} has winding 3 there)."""
    cx, cy = center
    turn = turn or (2 if points % 2 else 1)
    return [
        [
            _on_grid(cx + radius * math.cos(2 * math.pi * k * turn / points), step),
            _on_grid(cy + radius * math.sin(2 * math.pi * k * turn / points), step),
        ]
        for k in range(points)
    ]


def polygon(
    rng: random.Random, width: int, height: int, kind: str | None = None, step: float = 0.25
) -> tuple[str, list]:
    """(kind, vertices) of a random polygon inside a width x height raster.

    The kind is `kind` or one of `FEATURES` at random (the category a hidden
    case is shown as); the vertices lie on a grid of `step` pixels (the
    shapes made of pixel centres, or of offsets from one vertex, on their
    own grid); the polygon always has at least 3 distinct vertices.
    """
    while True:
        name = kind or rng.choice(FEATURES)
        vertices = _polygon(rng, name, width, height, step)
        if len({tuple(v) for v in vertices}) >= 3:
            return name, vertices


def _on_grid(value: float, step: float) -> float:
    return round(value / step) * step


def _polygon(rng: random.Random, kind: str, width: int, height: int, step: float) -> list:
    if kind == "horizontal edges":
        x0, x1 = sorted(grid_value(rng, 0, width, step) for _ in range(2))
        y0, y1 = sorted(grid_value(rng, 0, height, step) for _ in range(2))
        x1, y1 = x1 + 1, y1 + 1
        return [[x0, y0], [x1, y0], [x1, y1], [(x0 + x1) / 2, y1 + 0.5], [x0, y1]]
    if kind == "shared vertex":
        cx, cy = grid_value(rng, 1, width - 1, 1), grid_value(rng, 1, height - 1, 1)
        return [
            [cx, cy],
            [cx - 1.5, cy - 1.75],
            [cx + 1.25, cy - 2],
            [cx, cy],
            [cx + 2, cy + 1.5],
            [cx - 1, cy + 2],
        ]
    if kind == "sliver":
        x0, y0 = grid_value(rng, 0, width, step), grid_value(rng, 0, height, step)
        x1, y1 = grid_value(rng, 0, width, step), grid_value(rng, 0, height, step)
        return [[x0, y0], [x1, y1], [x1 + 0.25, y1 + 0.5]]
    if kind == "on pixel centers":
        return [[grid_value(rng, 0, width, 0.5), grid_value(rng, 0, height, 0.5)] for _ in range(3)]
    points = rng.randint(3, 6) if kind == "convex" else rng.choice((5, 7))
    center = (width / 2 + rng.uniform(-1, 1), height / 2 + rng.uniform(-1, 1))
    radius = min(width, height) / 2 * rng.uniform(0.6, 0.95)
    if kind == "concave":
        return star(rng, center, radius, points, step=step)
    angles = sorted(rng.uniform(0, 2 * math.pi) for _ in range(points))
    return [
        [
            _on_grid(center[0] + radius * math.cos(a), step),
            _on_grid(center[1] + radius * math.sin(a), step),
        ]
        for a in angles
    ]


# --- declaring an exercise ---------------------------------------------------------------


def case_polygons(inputs: dict) -> ScreenPolygons:
    """The screen polygons of a case, each vertex's value its polygon's index."""
    polygons = [[tuple(map(float, v)) for v in vertices] for vertices in inputs["polygons"]]
    values = [np.full((len(p), 1), float(i)) for i, p in enumerate(polygons)]
    return ScreenPolygons.from_polygons(polygons, values)


def polygon_lists(polygons: ScreenPolygons) -> list:
    """The [x, y, z] vertices of each of `polygons`, as a case holds them (`case_polygons`)."""
    offsets = polygons.offsets.tolist()
    vertices = np.column_stack([polygons.xy, polygons.z]).tolist()
    return [vertices[a:b] for a, b in zip(offsets, offsets[1:], strict=False)]


def call_with_step(step: str, run: Callable[[dict, object], object]) -> Callable:
    """An exercise's ``call``: ``run(inputs, tracer)`` with `step` of the step table replaced
    by the student's function (`scanviz.steps.using`)."""

    def call(fn, inputs: dict, tracer):
        with steps.using(**{step: fn}):
            return run(inputs, tracer)

    return call


def place_by_event(kind: str, describe: Callable[[object], str]) -> Callable[[int, list], str]:
    """An exercise's ``place`` when call k of its step is made at the k-th `kind` event of the
    reference's trace: that event as `describe` says, ``call k + 1`` past the last one."""

    def place(index: int, trace: list) -> str:
        events = [e for e in trace if e.kind == kind]
        return describe(events[index]) if index < len(events) else f"call {index + 1}"

    return place

"""Events of edge-function triangle rasterization (`scanviz.raster.edgefn`), with its
`EdgeFunction` record (one definition: the rasterizer imports it from here)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event, Record


@dataclass(frozen=True)
class EdgeFunction(Record):
    """E(p) = a * px + b * py + c on the grid, and whether E = 0 counts as inside.

    Edge i of a triangle runs from vertex i to vertex i+1 mod 3 (its place in
    `TriangleSetup.edges`). ``owns_boundary`` says whether a sample exactly on
    the edge (E = 0) is inside: true for left-facing edges and the lower
    horizontal edge (DESIGN §2).
    """

    a: int
    b: int
    c: int
    owns_boundary: bool

    def at(self, px: int, py: int) -> int:
        return self.a * px + self.b * py + self.c


@dataclass(frozen=True)
class TriangleSetup(Event):
    """A triangle ready for edge-function tests, on the integer grid of `scanviz.raster.fixed`.

    ``units`` are the snapped vertices in grid units (``scale`` per pixel, the
    sample of pixel (x, y) at (x * scale, y * scale)); ``vertices`` are the
    same points in pixels, caller's frame. ``area2`` is the doubled signed
    area (E_0 at vertex 2), ``orientation`` its sign (+1 counter-clockwise).
    ``bbox`` = (x_start, y_start, x_end, y_end): the half-open range of
    samples tested, clipped to the raster (empty for a zero-area triangle).
    """

    kind: ClassVar[str] = "triangle_setup"
    polygon: int
    vertices: tuple[tuple[float, float], ...]
    units: tuple[tuple[int, int], ...]
    scale: int
    edges: tuple[EdgeFunction, ...]  # edge i: vertex i to vertex i+1 mod 3
    area2: int
    orientation: int
    bbox: tuple[int, int, int, int]


@dataclass(frozen=True)
class EdgeFunctionRow(Event):
    """Samples ``x_start <= x < x_end`` of row `y` tested; ``covered_start <= x < covered_end`` in.

    ``values`` are (E_0, E_1, E_2) at the first tested sample; each grows by
    ``a * scale`` per sample to the right (a from the `TriangleSetup`).
    """

    kind: ClassVar[str] = "edge_function_row"
    polygon: int
    y: int
    x_start: int
    x_end: int
    values: tuple[int, ...]
    covered_start: int
    covered_end: int

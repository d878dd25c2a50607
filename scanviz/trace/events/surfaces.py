"""Events of grid surfaces: the floating horizon and the floating perimeter (`scanviz.surfaces`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event, Record


@dataclass(frozen=True)
class HorizonCurve(Event):
    """Floating horizon: curve `curve` of the grid family, the `step`-th processed (0: nearest).

    ``points`` is its screen polyline in grid order; ``pieces`` the (first,
    last) sample index of each x-monotone piece it was split into.
    """

    kind: ClassVar[str] = "horizon_curve"
    curve: int
    step: int
    family: str
    points: tuple[tuple[float, float], ...]
    pieces: tuple[tuple[int, int], ...]


@dataclass(frozen=True)
class HorizonColumn(Event):
    """Floating horizon: the curve at screen column `x`, height `y`, against the horizons.

    ``up`` and ``low`` are the horizons at `x` before this curve; ``flag`` is
    +1 (y >= up), -1 (y <= low) or 0 (hidden); ``previous_flag`` the flag at
    column x - 1 of the same piece (None at a piece's first column).
    ``drawn`` holds the visible parts (x0, y0, x1, y1) of the segment from
    column x - 1 to x.
    """

    kind: ClassVar[str] = "horizon_column"
    curve: int
    x: int
    y: float
    previous_flag: int | None
    flag: int
    up: float
    low: float
    drawn: tuple[tuple[float, float, float, float], ...]


@dataclass(frozen=True)
class GridEdge(Record):
    """A grid edge: ``kind`` "h" (along x, from (column, row) to (column + 1, row)) or "v"
    (along y, from (column, row) to (column, row + 1))."""

    kind: str
    row: int
    column: int


@dataclass(frozen=True)
class FacetsEnumerated(Event):
    """Floating perimeter, Steps II-IV: the viewing case and the facet enumeration.

    ``order[row][column]`` is the facet number (1 first) and ``classes[row][column]``
    its region class 1-9, rows from the bottom (smaller y) up; ``vp_cell`` is
    the viewpoint's (column, row), -1 or N - 1 outside the grid.
    """

    kind: ClassVar[str] = "facets_enumerated"
    case: int
    vp_cell: tuple[int, int]
    order: tuple[tuple[int, ...], ...]
    classes: tuple[tuple[int, ...], ...]


@dataclass(frozen=True)
class PerimeterFacet(Event):
    """Floating perimeter: facet `number` (grid element `row`, `column`) and the edges it processes.

    ``sides`` names them (T, B, L, R: larger y, smaller y, smaller x, larger x)
    and ``edges`` holds each as a `GridEdge`.
    """

    kind: ClassVar[str] = "perimeter_facet"
    number: int
    row: int
    column: int
    region_class: int
    sides: str
    edges: tuple[GridEdge, ...]


@dataclass(frozen=True)
class PerimeterEdge(Event):
    """Floating perimeter: one edge rasterised and tested against the perimeter (Fig. 2-4).

    ``points`` are its raster points in order and ``visible`` their flags (vifg);
    ``segments`` the visible runs (x0, y0, x1, y1), first and last point of
    each; ``verdict`` "visible" (tvifg), "hidden" (tivfg) or "partial".
    """

    kind: ClassVar[str] = "perimeter_edge"
    facet: int
    edge: GridEdge
    points: tuple[tuple[int, int], ...]
    visible: tuple[bool, ...]
    segments: tuple[tuple[int, int, int, int], ...]
    verdict: str


@dataclass(frozen=True)
class PerimeterUpdate(Event):
    """Floating perimeter: the facet's visible points (Bbuf, `points` = Tvp) merged into the perimeter.

    ``columns`` holds (x, top[x], bottom[x]) and ``rows`` (y, right[y],
    left[y]) after the update, for every entry that changed.
    """

    kind: ClassVar[str] = "perimeter_update"
    facet: int
    points: int
    columns: tuple[tuple[int, int, int], ...]
    rows: tuple[tuple[int, int, int], ...]

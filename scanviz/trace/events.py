"""Trace events: small frozen records named after the algorithm step that emits them.

Every event class sets a class-level ``kind`` and registers itself, so a trace
can be written to JSON and read back exactly (see `scanviz.trace.codec`).
Fields that filters understand: ``polygon`` (which input polygon), ``y`` (the
scanline or pixel row), and an x-extent given by ``x`` or ``x_start``/``x_end``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

EVENT_TYPES: dict[str, type[Event]] = {}


@dataclass(frozen=True)
class Event:
    """Base of all trace events; subclasses set ``kind`` and are registered by it."""

    kind: ClassVar[str] = "event"

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        if cls.kind in EVENT_TYPES:
            raise TypeError(f"event kind {cls.kind!r} is registered twice")
        EVENT_TYPES[cls.kind] = cls


# --- scan conversion (scanviz.raster.scanline) -------------------------------------------


@dataclass(frozen=True)
class EdgeRecord:
    """One polygon edge as the edge table holds it (pixel coordinates, caller's frame).

    ``bucket`` is the first sample row the edge crosses, ceil(ymin); the edge
    is active for rows ``bucket <= y < row_end`` (half-open). ``x`` is where it
    crosses row ``bucket``. Edges that cross no sample row (horizontal ones,
    and short ones between two rows) are kept for topology only.
    """

    edge: int
    contour: int
    x0: float
    y0: float
    x1: float
    y1: float
    ymin: float
    ymax: float
    bucket: int
    row_end: int
    x: float
    x_exact: Fraction | None
    dxdy: float
    dxdy_exact: Fraction | None
    winding: int
    horizontal: bool
    kept_for_topology: bool


@dataclass(frozen=True)
class AetEntry:
    """One active edge on the current row: its x there, dx/dy, top y and winding."""

    edge: int
    x: float
    x_exact: Fraction | None
    dxdy: float
    dxdy_exact: Fraction | None
    ymax: float
    winding: int


@dataclass(frozen=True)
class EdgeTableBuilt(Event):
    kind: ClassVar[str] = "edge_table_built"
    polygon: int
    edges: tuple[EdgeRecord, ...]


@dataclass(frozen=True)
class EdgesActivated(Event):
    kind: ClassVar[str] = "edges_activated"
    polygon: int
    y: int
    edges: tuple[int, ...]


@dataclass(frozen=True)
class EdgesRetired(Event):
    kind: ClassVar[str] = "edges_retired"
    polygon: int
    y: int
    edges: tuple[int, ...]


@dataclass(frozen=True)
class AetSorted(Event):
    """The active edge table on row `y` after the x update and re-sort (`swaps` exchanges)."""

    kind: ClassVar[str] = "aet_sorted"
    polygon: int
    y: int
    entries: tuple[AetEntry, ...]
    swaps: int


@dataclass(frozen=True)
class Span(Event):
    """Pixels ``x_start <= x < x_end`` of row `y`, inside with this winding count."""

    kind: ClassVar[str] = "span"
    polygon: int
    y: int
    x_start: int
    x_end: int
    winding: int


# --- edge-function triangles (scanviz.raster.edgefn) -------------------------------------


@dataclass(frozen=True)
class EdgeFunctionRecord:
    """Edge ``edge`` (vertex i to vertex i+1 mod 3): E(p) = a*px + b*py + c in grid units.

    ``owns_boundary`` says whether a sample exactly on the edge (E = 0) is inside:
    true for left-facing edges and the lower horizontal edge (DESIGN §2).
    """

    edge: int
    a: int
    b: int
    c: int
    owns_boundary: bool


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
    edges: tuple[EdgeFunctionRecord, ...]
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


# --- midpoint lines (scanviz.raster.lines) -----------------------------------------------


@dataclass(frozen=True)
class LineSetup(Event):
    """A line ready for the midpoint algorithm.

    ``octant`` 0..7 counts 45-degree sectors of the direction counter-clockwise
    from +x (octant 0 is the slides' case 0 <= slope < 1). ``major`` is the axis
    stepped once per pixel; ``step_x``, ``step_y`` the direction signs. The
    decision variable is d = 2 f(midpoint): it starts at ``d_start`` and grows
    by ``d_axial`` after an axial step, by ``d_diagonal`` after a diagonal one.
    ``tie_steps`` says whether d == 0 takes the diagonal step.
    """

    kind: ClassVar[str] = "line_setup"
    x0: int
    y0: int
    x1: int
    y1: int
    octant: int
    major: str
    step_x: int
    step_y: int
    d_start: int
    d_axial: int
    d_diagonal: int
    tie_steps: bool


@dataclass(frozen=True)
class LineStep(Event):
    """Pixel (x, y) drawn; `d` before the decision; `choice` "axial", "diagonal" or "last"."""

    kind: ClassVar[str] = "line_step"
    x: int
    y: int
    d: int
    choice: str

"""Events of scan conversion with the edge table and the active edge table
(`scanviz.raster.scanline`)."""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

from .base import Event, Record


@dataclass(frozen=True)
class EdgeRecord(Record):
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
class AetEntry(Record):
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

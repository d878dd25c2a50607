"""The painter's algorithm: sort the polygons by depth, farthest first, and paint them in order.

As on the UMBC slides: sort the list on depth (the largest z first: smaller
z is nearer in scanviz), then for each polygon, for each pixel it covers,
write its intensity. There is no test at all, so it is wrong wherever the
order of the farthest points is not the order of visibility: cyclic
overlaps, interpenetrating polygons, a long polygon behind a short one
whose far end is farther. Those failures are left in, for depth sort to
fix (`scanviz.visibility.depth_sort`).

``key`` chooses the sort key: "zmin" (the nearest vertex: the slides' "sort
polygon list on minimum z, largest z-value first"; default), "zmax" (the
farthest vertex, the order depth sort starts from) or "centroid" (the mean
vertex depth, as many games did). Ties keep the input order (a stable sort).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..conventions import check_choice
from ..trace.display import RichDisplay
from ..trace.events import PolygonsSorted
from .interface import Decision, Visibility, piece_record, register
from .screen_polygons import Piece, Surfaces

KEYS = ("zmin", "zmax", "centroid")


@dataclass
class PainterStats(RichDisplay):
    """polygons: sorted and painted (edge-on and off-raster ones are left out)."""

    polygons: int = 0
    left_out: int = 0


def sort_key(piece: Piece, key: str) -> float:
    """The depth a piece is sorted on (larger: painted earlier)."""
    z = piece.vertices[:, 2]
    return float(z.max() if key == "zmax" else z.min() if key == "zmin" else z.mean())


def depth_order(pieces: list[Piece], key: str = "zmax") -> list[Piece]:
    """Pieces sorted farthest first on `key`; ties keep their order."""
    return sorted(pieces, key=lambda piece: -sort_key(piece, key))


@register
@dataclass(frozen=True)
class Painter(Visibility):
    """The painter's algorithm (options: ``key`` = "zmin" | "zmax" | "centroid")."""

    name: ClassVar[str] = "painter"
    key: str = "zmin"

    def __post_init__(self) -> None:
        check_choice("key", self.key, KEYS)

    def decide(self, surfaces: Surfaces, tracer) -> Decision:
        order = depth_order(surfaces.pieces(), self.key)
        if tracer is not None and tracer.wants("polygons_sorted"):
            tracer.emit(PolygonsSorted(self.key, tuple(map(piece_record, order))))
        stats = PainterStats(len(order), surfaces.count - len(order))
        return Decision(stats, tuple(order), "over")

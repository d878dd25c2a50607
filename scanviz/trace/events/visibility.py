"""Events of the list-priority and image-space visibility algorithms (`scanviz.visibility`),
with the `Cut` record of a piece (one definition: `scanviz.visibility` imports it)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event, Record

# Pieces are named by label: the polygon's index, then "a" (in front of) or "b" (behind)
# per cutting plane, as the slides name 5a and 5b (`scanviz.visibility.screen_polygons`).


@dataclass(frozen=True)
class PixelPainted(Event):
    """Piece `piece` of polygon `polygon` at pixel (x, y), depth `z`, over what was there.

    ``previous`` is the polygon painted there before (-1: none). ``painted``
    is False where the mode's test kept the sample: painting under (front to
    back) a sample already painted, a polygon not the one decided visible, or
    a sample outside the piece's cuts.
    """

    kind: ClassVar[str] = "pixel_painted"
    polygon: int
    piece: str
    x: int
    y: int
    z: float
    previous: int
    painted: bool


@dataclass(frozen=True)
class Cut(Record):
    """Keep the samples where z_polygon - z_other > 0 (``behind``) or <= 0 (not ``behind``).

    A piece's cuts (`scanviz.visibility.Piece`) say which side of each cutting
    polygon `other`'s plane it keeps.
    """

    other: int
    behind: bool


@dataclass(frozen=True)
class PieceRecord(Record):
    """A piece as the traces show it: label, polygon, vertices (x, y, z) and cuts."""

    label: str
    polygon: int
    vertices: tuple[tuple[float, float, float], ...]
    cuts: tuple[Cut, ...]
    zmin: float
    zmax: float


@dataclass(frozen=True)
class PaintOrder(Event):
    """The order the pieces are painted in: back to front ("over") or front to back ("under")."""

    kind: ClassVar[str] = "paint_order"
    algorithm: str
    mode: str
    pieces: tuple[PieceRecord, ...]


@dataclass(frozen=True)
class PolygonsSorted(Event):
    """The list sorted on `key` ("zmax" descending: the farthest first), before any test.

    Depth sort emits it again after each split: the list re-sorted with the two new pieces.
    """

    kind: ClassVar[str] = "polygons_sorted"
    key: str
    pieces: tuple[PieceRecord, ...]


@dataclass(frozen=True)
class AmbiguityTest(Record):
    """One test of a pair in depth sort: its name and whether it settled the order."""

    name: str
    passed: bool


@dataclass(frozen=True)
class PairTested(Event):
    """Depth sort: piece `piece` (S, at the far end of the list) against `other` (S').

    ``tests`` are the tests run in order, up to the one that settled the
    pair (minimax, x_extent, y_extent, s_behind_plane, other_in_front,
    no_overlap; then the same with S and S' exchanged when the first round
    fails). ``outcome`` is "no_overlap" (the minimax test: S' is wholly
    nearer), "order_ok" (S may be painted before S'), "swap" (S' goes to
    the far end), "split" (a cycle: S is cut by the plane of S'), or
    "no_shared_sample" (no split can break it, but the two cover no common
    sample -- pieces cut along one line touch there -- so either order paints
    the same; kept in list order) or "unresolved" (no split can break it and
    they share samples: the split budget is spent, or a cycle has no member
    straddling another's plane; kept in list order, no depth promise).
    """

    kind: ClassVar[str] = "pair_tested"
    polygon: int
    piece: str
    other: str
    tests: tuple[AmbiguityTest, ...]
    settled_by: str | None
    outcome: str


@dataclass(frozen=True)
class PiecesSwapped(Event):
    """Depth sort: `moved` goes to the far end of the list ahead of `piece`; the new order."""

    kind: ClassVar[str] = "pieces_swapped"
    piece: str
    moved: str
    order: tuple[str, ...]


@dataclass(frozen=True)
class PolygonSplit(Event):
    """A piece cut by the plane of polygon `by`: its part in front and its part behind.

    ``why`` is "cycle" or "interpenetration" (depth sort) or "straddles" (BSP).
    """

    kind: ClassVar[str] = "polygon_split"
    polygon: int
    piece: str
    by: int
    why: str
    front: PieceRecord
    behind: PieceRecord


@dataclass(frozen=True)
class BspCandidate(Record):
    """A root candidate of a BSP node and the splits choosing it would make."""

    label: str
    splits: int


@dataclass(frozen=True)
class BspNode(Event):
    """A BSP node: its root piece, the pieces in front of and behind its plane (and on it).

    ``node`` numbers nodes in the order they are built (depth first, front
    subtree first); ``parent`` is -1 at the root and ``side`` "front" or
    "back" of the parent ("root" at the root). ``candidates`` are the roots considered (one for
    rule "first" and "random").
    """

    kind: ClassVar[str] = "bsp_node"
    node: int
    parent: int
    side: str
    depth: int
    polygon: int
    piece: str
    front: tuple[str, ...]
    back: tuple[str, ...]
    coplanar: tuple[str, ...]
    candidates: tuple[BspCandidate, ...]


@dataclass(frozen=True)
class BspVisited(Event):
    """Display: node `node` reached; the viewer in front of its plane or not, so which side first."""

    kind: ClassVar[str] = "bsp_visited"
    node: int
    piece: str
    viewer_in_front: bool
    first: str


@dataclass(frozen=True)
class SurfaceRecord(Record):
    """A polygon in the scanline algorithm's sorted surface table: its rows [y_start, y_end)."""

    polygon: int
    y_start: int
    y_end: int


@dataclass(frozen=True)
class SurfaceTableBuilt(Event):
    """The sorted surface table (SST): polygons by their first sample row."""

    kind: ClassVar[str] = "surface_table_built"
    surfaces: tuple[SurfaceRecord, ...]


@dataclass(frozen=True)
class ActiveSurfaces(Event):
    """Row `y`: the active surface table (AST) after polygons entered and were exhausted."""

    kind: ClassVar[str] = "active_surfaces"
    y: int
    entered: tuple[int, ...]
    exhausted: tuple[int, ...]
    active: tuple[int, ...]


@dataclass(frozen=True)
class VisibleSpan(Event):
    """Span [x_start, x_end) of row `y`: the surfaces over it and the visible one (-1: background).

    One event per span, or per piece of a span split by interpenetration.

    ``depths`` are the surfaces' depths at the span's first sample, in the
    order of ``surfaces``. ``reused`` is True when the row below had the same
    span with the same surfaces, so its decision was reused (coherence).
    ``split_at``, on each piece after the first, is where its plane crosses the
    previous piece's (between x_start - 1 and x_start); None otherwise.
    """

    kind: ClassVar[str] = "visible_span"
    y: int
    x_start: int
    x_end: int
    surfaces: tuple[int, ...]
    depths: tuple[float, ...]
    visible: int
    reused: bool
    split_at: float | None


@dataclass(frozen=True)
class AreaClassified(Event):
    """Warnock: the area [x_start, x_end) x [y_start, y_end) at quadtree `level` and its case.

    ``case`` is "empty" (no polygon), "surrounding" (one polygon, or the
    nearest of those, covers it all and is in front of every other),
    "single" (one polygon meets it, the rest is background), "subdivide"
    or "pixel" (one pixel: decided by depth at its sample). ``visible`` is the
    polygon shown over the area (-1: background or subdivided);
    ``polygons`` the polygons that meet it.
    """

    kind: ClassVar[str] = "area_classified"
    level: int
    x_start: int
    x_end: int
    y_start: int
    y_end: int
    case: str
    visible: int
    polygons: tuple[int, ...]

"""Trace events: small frozen records named after the algorithm step that emits them.

Every event class sets a class-level ``kind`` and registers itself, so a trace
can be written to JSON and read back exactly (see `scanviz.trace.codec`).
Fields that filters understand: ``polygon`` (which input polygon), ``y`` (the
scanline or pixel row), and an x-extent given by ``x`` or ``x_start``/``x_end``.
Every record checks its field types against its annotations when built
(`scanviz.trace.schema`): a wrong type raises TypeError naming the field.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

from .display import RichDisplay  # tables in Jupyter, readable print
from .schema import validate

EVENT_TYPES: dict[str, type[Event]] = {}


class Record(RichDisplay):
    """Base of trace records and events: field types are checked against the annotations.

    Jupyter shows a record as a table of its fields (`scanviz.trace.display`).

    >>> Span(polygon="x", y=0, x_start=0, x_end=1, winding=1)
    Traceback (most recent call last):
    ...
    TypeError: Span field 'polygon' must be int; got 'x' (str)
    """

    __slots__ = ()
    __post_init__ = validate  # called by the dataclass __init__ (a plain function: one frame less)


@dataclass(frozen=True)
class Event(Record):
    """Base of all trace events; subclasses set ``kind`` and are registered by it."""

    kind: ClassVar[str] = "event"

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        if cls.kind in EVENT_TYPES:
            raise TypeError(f"event kind {cls.kind!r} is registered twice")
        EVENT_TYPES[cls.kind] = cls


# --- scan conversion (scanviz.raster.scanline) -------------------------------------------


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


# --- edge-function triangles (scanviz.raster.edgefn) -------------------------------------


@dataclass(frozen=True)
class EdgeFunctionRecord(Record):
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


# --- illumination (scanviz.shading.illumination) -----------------------------------------


@dataclass(frozen=True)
class LightTerm(Record):
    """One light's share of the color of an illuminated point (world space).

    ``to_light`` is L, the unit vector from the point toward the light (zero if
    the point is at a point light). ``n_dot_l`` and ``r_dot_v`` are the cosines
    N.L and R.V with R = 2(N.L)N - L; ``attenuation`` is f_att. ``diffuse`` is
    kd * Od * max(N.L, 0) (RGB), ``specular`` ks * max(R.V, 0)^n where N.L > 0,
    else 0 (white), and ``contribution`` = f_att * Il * (diffuse + specular).
    """

    light: int
    to_light: tuple[float, float, float]
    n_dot_l: float
    r_dot_v: float
    attenuation: float
    diffuse: tuple[float, float, float]
    specular: float
    contribution: tuple[float, float, float]


@dataclass(frozen=True)
class Illumination(Event):
    """The Phong illumination model evaluated at one point, shown at pixel (x, y).

    ``normal`` is the unit normal used: renormalized, and reversed (``flipped``)
    if the surface is seen from behind; zero for a zero normal. ``to_viewer`` is
    V. ``ambient`` is ka * Ia * Od; ``color`` = clip(ambient + sum of the
    lights' contributions, 0, 1), exactly what the untraced shader returns.
    """

    kind: ClassVar[str] = "illumination"
    x: int
    y: int
    polygon: int | None
    position: tuple[float, float, float]
    normal: tuple[float, float, float]
    flipped: bool
    to_viewer: tuple[float, float, float]
    ambient: tuple[float, float, float]
    lights: tuple[LightTerm, ...]
    color: tuple[float, float, float]


# --- viewing, clipping, culling (scanviz.transform) --------------------------------------


@dataclass(frozen=True)
class VerticesTransformed(Event):
    """The vertices of object `object` at pipeline stage `stage` (see `scanviz.transform`).

    ``stage`` is "world", "eye", "clip", "ndc", "display" or "image";
    ``matrix`` is the 4x4 matrix that produced the stage from the previous one,
    row-major (16 floats), or None where no matrix is used (the input "world",
    the divide "ndc", the snap "image"). ``vertices`` has one row per vertex;
    a row is None where the stage is undefined: NDC and later for vertices
    with w <= 0 (at or behind the eye), which only clipping can bring back.
    """

    kind: ClassVar[str] = "vertices_transformed"
    object: int
    stage: str
    matrix: tuple[float, ...] | None
    vertices: tuple[tuple[float, ...] | None, ...]


@dataclass(frozen=True)
class PolygonClipped(Event):
    """Polygon `polygon` against the view volume -w <= x, y <= w, 0 <= z <= w.

    ``verdict`` is "accepted" (every vertex inside: passed unchanged),
    "rejected" (all vertices outside one plane, or fewer than 3 vertices
    left) or "clipped". ``outcodes`` are the input vertices' outcodes;
    ``counts[i]`` the vertex count after plane i of
    `scanviz.transform.clip.CLIP_PLANES`, empty when the clipper did not run.
    ``vertices`` are the output clip-space vertices (x, y, z, w).
    """

    kind: ClassVar[str] = "polygon_clipped"
    polygon: int
    verdict: str
    outcodes: tuple[int, ...]
    counts: tuple[int, ...]
    vertices: tuple[tuple[float, float, float, float], ...]


@dataclass(frozen=True)
class FaceCulled(Event):
    """The back-face test of polygon `polygon`: culled iff dot(normal, view) >= 0.

    ``normal`` is the face's Newell normal (length twice the area for a planar
    face), ``view`` the vector from the eye to the face centroid (perspective)
    or the view direction (orthographic). A face with a zero normal is never
    culled.
    """

    kind: ClassVar[str] = "face_culled"
    polygon: int
    normal: tuple[float, float, float]
    view: tuple[float, float, float]
    dot: float
    culled: bool


@dataclass(frozen=True)
class PolygonsTransformed(Event):
    """The whole scene at stop `stage` of the viewing pipeline (`scanviz.pipeline.viewing`).

    ``stage`` is "world", "eye", "clip", "ndc" or "display"; ``matrix`` the
    4x4 matrix that took the previous stop here, row-major (16 floats), or
    None (the input "world", the divide "ndc"). ``objects[k]`` is the scene
    object of polygon k and ``polygons[k]`` its vertices in this space: every
    input polygon up to "clip"; in "ndc" and "display" the polygons as clipped,
    empty for those culled or clipped away. ``volume`` holds the view
    volume's 8 corners here (near face, then far face, each counter-clockwise
    from left-bottom); ``eye`` the eye's position, None where it has none.
    """

    kind: ClassVar[str] = "polygons_transformed"
    stage: str
    matrix: tuple[float, ...] | None
    objects: tuple[int, ...]
    polygons: tuple[tuple[tuple[float, ...], ...], ...]
    volume: tuple[tuple[float, ...], ...]
    eye: tuple[float, float, float] | None


# --- interpolation and the z-buffer (scanviz.raster.interpolate, scanviz.visibility) -----


@dataclass(frozen=True)
class PolygonSetup(Event):
    """Polygon `polygon` ready for interpolation: its snapped vertices and depth plane.

    ``vertices`` are (x, y, z): x, y snapped, in pixels, caller's frame; z as
    given. ``plane`` is (A, B, C, D) by Newell's method, A x + B y + C z + D = 0
    in the same frame; ``dzdx`` = -A/C and ``dzdy`` = -B/C are the depth steps
    per pixel and per row, None when C == 0 (seen edge-on: drawn nowhere).
    ``values`` are the per-vertex quantities interpolated along edges and
    spans: the attributes, or with ``perspective`` each attribute times 1/w
    followed by 1/w itself.
    """

    kind: ClassVar[str] = "polygon_setup"
    polygon: int
    vertices: tuple[tuple[float, float, float], ...]
    plane: tuple[float, float, float, float]
    dzdx: float | None
    dzdy: float | None
    values: tuple[tuple[float, ...], ...]
    perspective: bool


@dataclass(frozen=True)
class EdgeValueEntry(Record):
    """One active edge on the current row: its crossing x and its values there, with d/dy."""

    edge: int
    x: float
    values: tuple[float, ...]
    dvdy: tuple[float, ...]


@dataclass(frozen=True)
class EdgeValues(Event):
    """Row `y` of a polygon: depth ``z_row`` at the sample of pixel 0, and the AET with values.

    ``entries`` are in AET order (as `aet_sorted`); each edge's values were
    computed at its first row from its lower end, then stepped by d/dy per row.
    ``z_row`` is computed from the plane on the first row, then stepped by dz/dy.
    """

    kind: ClassVar[str] = "edge_values"
    polygon: int
    y: int
    z_row: float
    entries: tuple[EdgeValueEntry, ...]


@dataclass(frozen=True)
class SpanValues(Event):
    """Span [x_start, x_end) of row `y` between crossings ``x_left`` and ``x_right``.

    ``z`` is the depth at sample x_start (z_row + dzdx * x_start), stepped by
    ``dzdx`` per pixel; ``values`` are the values at x_start and ``dvdx`` their
    steps, (v_right - v_left) / (x_right - x_left).
    """

    kind: ClassVar[str] = "span_values"
    polygon: int
    y: int
    x_start: int
    x_end: int
    x_left: float
    x_right: float
    z: float
    dzdx: float
    values: tuple[float, ...]
    dvdx: tuple[float, ...]


@dataclass(frozen=True)
class DepthTest(Event):
    """Fragment of `polygon` at pixel (x, y) with depth `z` against the stored depth.

    ``stored`` is None where nothing was drawn yet (+inf). ``passed`` iff
    z < stored (strictly: ties keep the earlier polygon).
    """

    kind: ClassVar[str] = "depth_test"
    polygon: int
    x: int
    y: int
    z: float
    stored: float | None
    passed: bool


# --- pixel masks and the mask buffer (scanviz.abuffer.masks) -----------------------------


@dataclass(frozen=True)
class EdgeMaskEntry(Record):
    """Edge `edge` in one pixel: the bits at or right of its crossings, and its winding."""

    edge: int
    winding: int
    mask: int


@dataclass(frozen=True)
class MaskBufferPixel(Record):
    """A pixel of the mask buffer that some active edge crosses.

    ``carry`` is the winding entering the pixel from the left on each
    sub-row, bottom first; each bit's winding is its sub-row's carry plus the
    windings of the ``edges`` whose mask has the bit. ``mask`` is the result
    under the fill rule (for a convex corner: the "and" of the edge masks).
    """

    x: int
    carry: tuple[int, ...]
    edges: tuple[EdgeMaskEntry, ...]
    mask: int


@dataclass(frozen=True)
class MaskRun(Record):
    """Pixels ``x_start <= x < x_end`` that no edge crosses, all with mask `mask` (from the carry)."""

    x_start: int
    x_end: int
    mask: int


@dataclass(frozen=True)
class MaskBufferRow(Event):
    """The mask buffer of pixel row `y` after every active edge was scanned into it.

    ``active`` are the ids of the edges whose y-extent covers a sub-row of the
    row (ids as in `edge_table_built`); ``pixels`` the crossed pixels,
    ``runs`` the uncrossed pixels with a nonzero mask. Masks are ints whose
    bit j * cols + i is sub-sample (i, j) of the `layout` ("8x8", ...).
    """

    kind: ClassVar[str] = "mask_buffer_row"
    polygon: int
    y: int
    layout: str
    active: tuple[int, ...]
    pixels: tuple[MaskBufferPixel, ...]
    runs: tuple[MaskRun, ...]


@dataclass(frozen=True)
class EdgeMask(Event):
    """Edge `edge` scanned into pixel (x, y): its exact crossings and its edge mask.

    ``crossings[j]`` is where the edge crosses sub-row j (bottom first), in
    pixels, caller's frame, or None where it does not cross it inside this
    pixel. ``mask`` has the sub-samples at or right of each crossing.
    """

    kind: ClassVar[str] = "edge_mask"
    polygon: int
    y: int
    x: int
    edge: int
    winding: int
    crossings: tuple[Fraction | None, ...]
    mask: int


# --- the a-buffer (scanviz.abuffer) -------------------------------------------------------


@dataclass(frozen=True)
class FragmentRecord(Record):
    """One fragment as a pixelstruct holds it (thesis Fig. 6.6, without the link).

    ``z`` and ``zmax`` are its depth range (smaller is nearer); ``area`` the
    exact area of the pixel it covers; ``mask`` its sub-sample bits (bit
    j * cols + i); ``opacity`` = 1 - transparency; ``object`` its object id.
    A simple pixelstruct is one record with a full mask and opacity 1.
    """

    z: float
    zmax: float
    area: float
    mask: int
    color: tuple[float, ...]
    opacity: float
    object: int


@dataclass(frozen=True)
class FragmentInserted(Event):
    """Fragment ``index`` (of `polygon`) inserted into pixel (x, y)'s pixelstruct.

    ``case`` is one of the six of thesis §6.3.4: "complete_empty",
    "complete_simple", "complete_list", "partial_empty", "partial_simple",
    "partial_list" (incoming mask full or not x pixelstruct before).
    ``before`` and ``after`` are the fragment lists, nearest first, with their
    kinds ("empty", "simple", "list"); ``after`` is after merging and discarding.
    """

    kind: ClassVar[str] = "fragment_inserted"
    x: int
    y: int
    polygon: int
    index: int
    fragment: FragmentRecord
    case: str
    before_kind: str
    before: tuple[FragmentRecord, ...]
    after_kind: str
    after: tuple[FragmentRecord, ...]


@dataclass(frozen=True)
class FragmentsMerged(Event):
    """A stored fragment and the incoming one (same object and color, masks together full)."""

    kind: ClassVar[str] = "fragments_merged"
    x: int
    y: int
    polygon: int
    stored: FragmentRecord
    incoming: FragmentRecord
    merged: FragmentRecord


@dataclass(frozen=True)
class FragmentsDiscarded(Event):
    """Fragments thrown away behind ``front``, a fully covered opaque fragment."""

    kind: ClassVar[str] = "fragments_discarded"
    x: int
    y: int
    polygon: int
    front: FragmentRecord
    discarded: tuple[FragmentRecord, ...]


@dataclass(frozen=True)
class PackStep(Record):
    """One level of the fragment packer (thesis eqs. 6.4-6.6) on one region of the pixel.

    The region ``region`` (bits, M_Q(i+1)) of weight ``weight`` (Q_{i+1}) is
    what is still visible in front of fragment ``level`` (0 = nearest).
    ``branch`` names the region: the covered ("c") or uncovered ("u") side
    taken under each transparent fragment in front ("" under opaque ones only).
    ``mask_a`` = M_Q(i+1) AND M_i, weight ``a`` (A_i); ``mask_q`` = M_Q(i+1)
    AND NOT M_i, weight ``q`` (Q_i). ``color`` is the region's color times its
    weight: P_i A_i + T_i Q_i (opaque) or eq. 6.5 (transparent).
    """

    level: int
    branch: str
    fragment: FragmentRecord
    region: int
    weight: float
    mask_a: int
    a: float
    mask_q: int
    q: float
    color: tuple[float, ...]


@dataclass(frozen=True)
class PixelPacked(Event):
    """The packer collapsed pixel (x, y)'s fragment list into ``color`` and coverage ``alpha``.

    ``steps`` are in the order the recursion finishes them (deepest first);
    ``alpha`` is 1 - the background's share of the pixel.
    """

    kind: ClassVar[str] = "pixel_packed"
    x: int
    y: int
    weights: str
    steps: tuple[PackStep, ...]
    color: tuple[float, ...]
    alpha: float


@dataclass(frozen=True)
class CoverageBlended(Event):
    """The flawed z-buffer (thesis §6.3): color = new * coverage + old * (1 - coverage).

    ``passed`` iff z < stored (None: nothing drawn yet); only then is ``color``
    the blend of ``incoming`` over ``old``, else the old color stays.
    """

    kind: ClassVar[str] = "coverage_blended"
    x: int
    y: int
    polygon: int
    z: float
    stored: float | None
    passed: bool
    coverage: float
    incoming: tuple[float, ...]
    old: tuple[float, ...]
    color: tuple[float, ...]


# --- the list-priority and image-space visibility algorithms (scanviz.visibility) --------
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
class CutRecord(Record):
    """A cut of a piece: keep the samples behind (``behind``) or not behind polygon `other`'s plane."""

    other: int
    behind: bool


@dataclass(frozen=True)
class PieceRecord(Record):
    """A piece as the traces show it: label, polygon, vertices (x, y, z) and cuts."""

    label: str
    polygon: int
    vertices: tuple[tuple[float, float, float], ...]
    cuts: tuple[CutRecord, ...]
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
    "unresolved" (no split can break it: the split budget is spent, or a cycle
    has no member straddling another's plane; the pair is kept in list order).
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


# --- grid surfaces (scanviz.surfaces) ---------------------------------------------------


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


# --- fast Phong (scanviz.shading.fast_phong) ----------------------------------------------


@dataclass(frozen=True)
class RationalFormsRecord(Record):
    """The scalars of the exact rational forms over one triangle (dissertation §3.2).

    With N(x, y) = A x + B y + C (x, y from the expansion point):
    a, b, c = L·A, L·B, L·C; aa, bb, cc = V·A, V·B, V·C; |N|² = d x² + e xy +
    f y² + g x + h y + i; l, m, o, p, q, w the numerator of 2 (N·L)(N·V);
    k_lv = L·V; ha, hb, hc = H·A, H·B, H·C (L, V, H unit).
    """

    a: float
    b: float
    c: float
    aa: float
    bb: float
    cc: float
    d: float
    e: float
    f: float
    g: float
    h: float
    i: float
    l: float  # noqa: E741 -- the dissertation's name
    m: float
    o: float
    p: float
    q: float
    w: float
    k_lv: float
    ha: float
    hb: float
    hc: float


@dataclass(frozen=True)
class FastPhongSetup(Event):
    """Fast Phong over triangle `polygon`: the expansion and every coefficient, before any pixel.

    ``vertices`` are the snapped screen vertices, ``origin`` the expansion
    point (``expansion`` "vertex": vertex 0, or "centroid"); ``plane`` is
    (A, B, C) with N(x, y) = A x + B y + C in pixels from the origin.
    ``cos_theta``, ``cos_specular`` and each of ``ambient_diffuse`` (r, g, b)
    hold a quadratic's (x², xy, y², x, y, 1) coefficients: T5..T0, T55..T00
    (``specular`` "phong") or the N·H ones ("blinn"), W5..W0. ``table`` is
    the specular look-up table cos φ_1..cos φ_N.
    """

    kind: ClassVar[str] = "fast_phong_setup"
    polygon: int
    vertices: tuple[tuple[float, float], ...]
    normals: tuple[tuple[float, float, float], ...]
    expansion: str
    origin: tuple[float, float]
    plane: tuple[tuple[float, float, float], ...]
    to_light: tuple[float, float, float]
    to_viewer: tuple[float, float, float]
    halfway: tuple[float, float, float]
    forms: RationalFormsRecord
    specular: str
    cos_theta: tuple[float, float, float, float, float, float]
    cos_specular: tuple[float, float, float, float, float, float]
    ambient_diffuse: tuple[tuple[float, float, float, float, float, float], ...]
    table: tuple[float, ...]


@dataclass(frozen=True)
class FastPhongPixel(Event):
    """Fast Phong at sample (x, y): the quadratics' values there and their steps to x + 1.

    ``direct`` is True at a span's first sample (values evaluated from the
    coefficients) and False where they came from one forward-difference step.
    Each ``*_step`` is the difference to the next sample. ``level`` is the
    table index of ``cos_specular`` (``comparisons`` made to find it);
    ``lit`` says whether cos θ > 0 (else no highlight); ``color`` is
    clip(max(ambient_diffuse, Ia ka) + (level if lit else 0), 0, 255).
    """

    kind: ClassVar[str] = "fast_phong_pixel"
    polygon: int
    x: int
    y: int
    direct: bool
    cos_theta: float
    cos_theta_step: float
    cos_specular: float
    cos_specular_step: float
    ambient_diffuse: tuple[float, float, float]
    ambient_diffuse_step: tuple[float, float, float]
    level: int
    comparisons: int
    lit: bool
    color: tuple[float, float, float]


# --- area-sampling anti-aliasing (scanviz.antialias) ---


@dataclass(frozen=True)
class DislopColumn(Event):
    """One column (or row, ``major == "y"``) of a DISLOP line, ring or disk.

    ``x``, ``y`` is the middle pixel (raster coordinates), the one whose row
    (column) holds the line at the column (row) centre. In the first-octant
    frame the line there is ``y = dxy + slope * x`` relative to that pixel's
    centre, with ``0 <= slope`` and ``-1/2 < dxy <= 1/2``. ``fcv`` and ``scv``
    are the first and second critical values of Fig 4-2 (for an edge column,
    its critical value cv and the corner area AA of Fig 4-5). ``branch`` is
    the formula taken: "flat", "two", "three", "three_triangle" (DISLOP_L),
    "one_pixel", "two_pixel" (DISLOP_E), "cap" (an end column, clipped
    exactly) or "exact" (the exact band, up to four pixels). ``up``, ``mid``, ``low`` are the
    areas of the pixels above, at and below the middle one, in the first-octant
    frame (right, middle, left for a steep line); ``spill`` is the area of the
    fourth pixel, two beyond the middle on the side of ``dxy`` (0 in the
    dissertation's formula).
    """

    kind: ClassVar[str] = "dislop_column"
    x: int
    y: int
    major: str
    slope: float
    dxy: float
    fcv: float
    scv: float
    branch: str
    up: float
    mid: float
    low: float
    spill: float


@dataclass(frozen=True)
class PostColumn(Event):
    """One table look-up of post-anti-aliasing: a column (row, ``major == "y"``) of a segment.

    ``segment`` indexes the input segments; ``x``, ``y`` is the middle pixel
    (raster coordinates); ``i``, ``j`` the slope and distance indices;
    ``dxy`` the distance they came from (the table's dxy_j with the simple
    recurrence); ``up``, ``mid``, ``low`` the coverages read and blended
    (quantised to levels with the intensity table), first-octant frame.
    """

    kind: ClassVar[str] = "post_column"
    segment: int
    x: int
    y: int
    major: str
    i: int
    j: int
    dxy: float
    up: float
    mid: float
    low: float

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


# --- illumination (scanviz.shading.illumination) -----------------------------------------


@dataclass(frozen=True)
class LightTerm:
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
class EdgeValueEntry:
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

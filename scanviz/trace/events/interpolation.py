"""Events of interpolation along edges and spans and of the z-buffer
(`scanviz.raster.interpolate`, `scanviz.visibility.zbuffer`)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import ClassVar

from .base import Event, Record


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
class InterpolatedSpan(Record):
    """Samples [x_start, x_end) of row `y` between crossings ``x_left`` and ``x_right``.

    ``z`` is the depth at sample x_start (z_row + dzdx * x_start), stepped by
    ``dzdx`` per pixel; ``values`` are the values at x_start and ``dvdx`` their
    steps, (v_right - v_left) / (x_right - x_left). `scanviz.raster.interpolate`
    builds them in its sample frame and walks them with `span_samples`.
    """

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
class SpanValues(InterpolatedSpan, Event):
    """An `InterpolatedSpan` of polygon `polygon`, in the caller's frame."""

    kind: ClassVar[str] = "span_values"
    polygon: int

    @classmethod
    def of(cls, polygon: int, span: InterpolatedSpan) -> SpanValues:
        """The event of `span`, a span of `polygon`."""
        return cls(polygon=polygon, **{f.name: getattr(span, f.name) for f in fields(span)})


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

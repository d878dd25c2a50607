"""Events of viewing, clipping and culling (`scanviz.transform`, `scanviz.pipeline.viewing`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event


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

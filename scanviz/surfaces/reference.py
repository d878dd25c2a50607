"""The Floating Perimeter Algorithm checked against scanviz's own z-buffer, point by point.

Wang (1989) claims the FPA is exact without proof; spec §1.6.5 found where
the perimeter test is not (a hole in the union of processed facets). This
module measures it (``docs/surfaces-fpa.md``, "Exactness").

Hidden lines
    Each raster point the FPA tests (`PerimeterResult.points`) is also
    decided by the z-buffer of `GridSurface.scene`, rendered with
    ``sample="center"`` so that pixel (x, y) is sampled at screen (x, y), the
    point itself. The point is visible to the z-buffer iff its sample is
    empty, or the facet seen there is one of the (one or two) facets that
    share the edge, or the edge's own depth at the point (display z, linear
    along the projected edge; the point projected onto it) is no farther than
    the depth of the plane of the triangle seen there, evaluated at that
    edge point (so both depths are taken at the same screen position). Every
    disagreement is counted, in both directions.
Holes
    A point the FPA hides although no facet processed before its own covers
    its sample (the coverage of the front-to-back mask render, same
    sampling) is a *hole*: strictly inside the perimeter's row and column
    spans but outside the union of what was processed. A hole is
    *structural* if the point also lies strictly inside the exact row and
    column spans of that union (the earlier facets' triangles, unrounded):
    the failure spec §1.6.5 warns of, which no raster can remove. Otherwise
    it is the raster's: the perimeter holds rounded points, up to half a
    pixel outside the union. The other disagreements are the raster's too (a
    point half a pixel off its edge, a vertex shared by facets, a point on
    the perimeter counted visible).
Hidden surfaces
    The FPA's facet per pixel (front to back with the coverage mask) against
    ``render(surface.scene(view, w, h), w, h).polygon // 2``, same default sampling.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..transform.viewing import vertex_tables
from .grid import GridSurface
from .perimeter import PerimeterResult, edge_endpoints, floating_perimeter
from .view import View


@dataclass(frozen=True)
class ZBufferComparison:
    """The FPA against the z-buffer on one surface, view and raster.

    Attributes
    ----------
    case : int
        The viewing case.
    points : int
        Raster points the FPA tested (lines mode).
    false_hidden, false_visible : int
        Points the FPA hides that the z-buffer shows, and the reverse.
    on_perimeter : int
        Of the false visible points, those the FPA shows only because they lie
        on the perimeter (its ``>=`` and ``<=``), not strictly outside it.
    holes : int
        Of the false hidden points, those no earlier facet covers.
    structural_holes : int
        Of the holes, those inside the exact spans of the earlier facets (module notes).
    pixels : int
        Pixels where either hidden-surface picture shows a facet.
    facet_mismatch : int
        Pixels where the FPA's facet (coverage mask) differs from the z-buffer's.
    fpa : PerimeterResult
        The lines-mode result compared.
    zbuffer_visible : (P,) ndarray of bool
        The z-buffer's decision for each of ``fpa.points``.
    hole : (P,) ndarray of bool
        Which points are holes.
    structural : (P,) ndarray of bool
        Which holes are structural.
    """

    case: int
    points: int
    false_hidden: int
    false_visible: int
    on_perimeter: int
    holes: int
    structural_holes: int
    pixels: int
    facet_mismatch: int
    fpa: PerimeterResult
    zbuffer_visible: np.ndarray
    hole: np.ndarray
    structural: np.ndarray

    @property
    def exact(self) -> bool:
        """No point and no pixel decided differently."""
        return self.false_hidden == self.false_visible == self.facet_mismatch == 0


def compare_with_zbuffer(
    surface: GridSurface, view: View, width: int, height: int
) -> ZBufferComparison:
    """Run the FPA (both modes) and the z-buffer on the same surface and count every disagreement.

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
        Raster size, each at least 2.

    Returns
    -------
    ZBufferComparison

    Examples
    --------
    A plane seen from above hides nothing, and the two agree everywhere:

    >>> plane = GridSurface.from_function(lambda x, y: 0 * x, (0, 1), (0, 1), 4, 4)
    >>> c = compare_with_zbuffer(plane, View((0.5, -2, 3), (0, 1, -1.5)), 24, 24)
    >>> c.exact, c.points > 0, c.holes
    (True, True, 0)
    """
    from ..pipeline import render  # the pipeline imports the visibility package; import it late

    fpa = floating_perimeter(surface, view, width, height, "lines")
    scene = surface.scene(view, width, height)
    centred = render(scene, width, height, shading="flat", sample="center")
    visible = _zbuffer_visible(surface, view, width, height, fpa, scene.camera, centred)
    mask = floating_perimeter(surface, view, width, height, "surface", shading="flat", sample="center")  # fmt: skip
    hole = ~fpa.visible & ~_covered_before(fpa, mask.facet) & visible
    structural = _inside_exact_spans(surface, view, width, height, fpa, hole)
    z = render(scene, width, height, shading="flat")
    zfacet = np.where(z.polygon >= 0, z.polygon // 2, -1)
    fpa_facet = floating_perimeter(surface, view, width, height, "surface", shading="flat").facet
    return ZBufferComparison(
        case=fpa.case,
        points=len(fpa.points),
        false_hidden=int((~fpa.visible & visible).sum()),
        false_visible=int((fpa.visible & ~visible).sum()),
        on_perimeter=int((fpa.on_perimeter & ~visible).sum()),
        holes=int(hole.sum()),
        structural_holes=int(structural.sum()),
        pixels=int(((zfacet >= 0) | (fpa_facet >= 0)).sum()),
        facet_mismatch=int((zfacet != fpa_facet).sum()),
        fpa=fpa,
        zbuffer_visible=visible,
        hole=hole,
        structural=structural,
    )


def edge_facets(edges: np.ndarray, nx: int, ny: int) -> np.ndarray:
    """(E, 2) int64: the grid elements k = r (Nx - 1) + c on either side of each edge, -1 past the boundary.

    >>> edge_facets(np.array([[0, 1, 0], [1, 0, 0]]), 3, 3).tolist()
    [[0, 2], [-1, 0]]
    """
    edges = np.asarray(edges, np.int64).reshape(-1, 3)
    kind, row, column = edges.T
    columns = nx - 1
    along_x = kind == 0
    # "h" edges: the facets below (row - 1) and above (row); "v": left (column - 1) and right.
    first_row = np.where(along_x, row - 1, row)
    first_column = np.where(along_x, column, column - 1)
    first = np.where((first_row >= 0) & (first_column >= 0), first_row * columns + first_column, -1)
    second_ok = np.where(along_x, row < ny - 1, column < nx - 1)
    second = np.where(second_ok, row * columns + column, -1)
    return np.stack([first, second], axis=1)


def _zbuffer_visible(surface, view, width, height, fpa, camera, centred) -> np.ndarray:
    """The z-buffer's decision for each FPA raster point (module notes)."""
    points, point_edge = fpa.points, fpa.point_edge
    screen = view.screen_from_world(surface.points(), width, height)[0]
    tables = vertex_tables(camera, surface.points(), width, height, subpixel_bits=None)
    depth = tables["display"][:, 2]
    starts, ends = edge_endpoints(fpa.edges.edges, surface.nx)
    a, b = screen[starts][point_edge], screen[ends][point_edge]
    ab = b - a
    length = np.maximum((ab * ab).sum(axis=1), 1e-300)
    t = np.clip(((points - a) * ab).sum(axis=1) / length, 0.0, 1.0)
    on_edge = a + t[:, None] * ab  # the edge point the raster point stands for
    z_edge = depth[starts][point_edge] + t * (depth[ends][point_edge] - depth[starts][point_edge])
    x, y = points[:, 0], points[:, 1]
    seen = centred.polygon[y, x]
    facet = np.where(seen >= 0, seen // 2, -1)
    sharing = edge_facets(fpa.edges.edges, surface.nx, surface.ny)[point_edge]
    own = (facet[:, None] == sharing).any(axis=1) & (facet >= 0)
    # The seen triangle's plane (display z affine in screen x, y), at the edge point.
    faces = np.array(surface.to_mesh().faces)[np.maximum(seen, 0)]
    corners = np.concatenate([screen[faces], depth[faces][..., None]], axis=-1)
    z_seen = _plane_at(corners, on_edge)
    nearer = z_seen < z_edge - 1e-9 * np.maximum(1.0, np.abs(z_edge))
    return (seen < 0) | own | ~nearer


def _plane_at(corners: np.ndarray, at: np.ndarray) -> np.ndarray:
    """z of the plane through each triangle's corners (T, 3, 3: x, y, z) at the points `at` (T, 2).

    A triangle edge-on to the screen has no such plane: its vertex depth nearest
    the point stands in (it is seen only along a line).
    """
    p0, p1, p2 = corners[:, 0], corners[:, 1], corners[:, 2]
    u, v = p1 - p0, p2 - p0
    normal = np.cross(u, v)
    flat = np.abs(normal[:, 2]) <= 1e-12 * np.maximum(1.0, np.abs(normal).max(axis=1))
    nz = np.where(flat, 1.0, normal[:, 2])
    z = (
        p0[:, 2]
        - (normal[:, 0] * (at[:, 0] - p0[:, 0]) + normal[:, 1] * (at[:, 1] - p0[:, 1])) / nz
    )
    nearest = np.argmin(((corners[:, :, :2] - at[:, None]) ** 2).sum(axis=-1), axis=1)
    return np.where(flat, corners[np.arange(len(at)), nearest, 2], z)


def _inside_exact_spans(surface, view, width, height, fpa, hole) -> np.ndarray:
    """Whether each hole lies strictly inside the exact row and column spans of the earlier facets."""
    structural = np.zeros(len(fpa.points), bool)
    if not hole.any():
        return structural
    screen = view.screen_from_world(surface.points(), width, height)[0]
    triangles = screen[np.array(surface.to_mesh().faces)]  # (2F, 3, 2)
    number = np.repeat(fpa.enumeration.order.reshape(-1), 2)  # each triangle's facet number
    for i in np.flatnonzero(hole):
        earlier = triangles[number < fpa.edges.facet[fpa.point_edge[i]]]
        x, y = fpa.points[i]
        low_x, high_x = _line_extent(earlier, 1, y)
        low_y, high_y = _line_extent(earlier, 0, x)
        structural[i] = low_x < x < high_x and low_y < y < high_y
    return structural


def _line_extent(triangles: np.ndarray, axis: int, at: float) -> tuple[float, float]:
    """(min, max) of the other coordinate where the line coordinate[axis] = at meets the triangles."""
    a, b = triangles, np.roll(triangles, -1, axis=1)  # the three edges a -> b of each triangle
    da, db = a[..., axis] - at, b[..., axis] - at
    crosses = (da * db <= 0) & (da != db)
    t = np.where(crosses, da / np.where(da != db, da - db, 1.0), 0.0)
    other = 1 - axis
    values = (a[..., other] + t * (b[..., other] - a[..., other]))[crosses]
    return (values.min(), values.max()) if values.size else (np.inf, -np.inf)


def _covered_before(fpa: PerimeterResult, facet: np.ndarray) -> np.ndarray:
    """Whether each FPA point's sample is covered by a facet numbered before the point's own."""
    number = np.concatenate([fpa.enumeration.order.reshape(-1), [np.iinfo(np.int64).max]])
    first = number[facet]  # facet -1 (nothing covers the sample) picks the sentinel
    points = fpa.points
    return first[points[:, 1], points[:, 0]] < fpa.edges.facet[fpa.point_edge]


@dataclass(frozen=True)
class SurfaceResults:
    """One grid surface by every method: what `plot_results` draws.

    Attributes
    ----------
    lines : PerimeterResult
        The FPA's hidden lines.
    horizon : HorizonResult
        The floating horizon's curves of one family.
    shaded : PerimeterResult
        The FPA's hidden surfaces.
    zbuffer : RenderResult
        The z-buffer's render of ``surface.scene(view, width, height)``.
    facets_differ : int
        Pixels where the FPA's visible facet is not the z-buffer's.
    """

    lines: PerimeterResult
    horizon: object
    shaded: PerimeterResult
    zbuffer: object
    facets_differ: int


def surface_results(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    family: str = "x",
    shading: str = "phong",
) -> SurfaceResults:
    """The FPA (lines and surfaces), the floating horizon of `family` and the z-buffer, on one view.

    Examples
    --------
    >>> from scanviz.surfaces import gaussian
    >>> results = surface_results(gaussian(5), View((3, 4, 3), (-3, -4, -3)), 24, 24)
    >>> results.facets_differ
    0
    """
    from ..pipeline import render
    from .horizon import floating_horizon

    lines = floating_perimeter(surface, view, width, height)
    horizon = floating_horizon(surface, view, width, height, family=family)
    shaded = floating_perimeter(surface, view, width, height, "surface", shading=shading)
    zbuffer = render(surface.scene(view, width, height), width, height, shading=shading)
    facet = np.where(zbuffer.polygon >= 0, zbuffer.polygon // 2, -1)  # two triangles per facet
    return SurfaceResults(lines, horizon, shaded, zbuffer, int((facet != shaded.facet).sum()))

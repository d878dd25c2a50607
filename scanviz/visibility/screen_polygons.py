"""The common input of the visibility algorithms: snapped screen polygons with their depth planes.

Every algorithm but the z-buffer decides in *screen space*: x, y in the
sample frame (the sample of pixel (x, y) is the point (x, y), see
`scanviz.raster.fixed`) and z the depth after the viewing transform. The
perspective map takes planes to planes and keeps, for points in front of
the eye, the side of a plane each point is on, so a polygon is a plane
z = z_p(x, y) here and the viewer is at z = -inf looking along +z: "behind"
means larger z. The planes are the z-buffer's own (Newell's method on the
snapped vertices, `scanviz.raster.interpolate.depth_plane`), so a decision
here and a depth test there compare the same numbers.

A *piece* is a polygon, or the part of one that one or more cuts leave.
Cutting polygon p by the plane of polygon q splits p's samples by the sign
of z_p(x, y) - z_q(x, y) (the depth difference of the two planes), taken
exactly (`scanviz.visibility.cut_side`): the piece "behind q" keeps the
samples where it is > 0, the piece "in front" those where it is < 0, and a
sample on the line goes to the piece on its +x side (+y for a line
parallel to x), as the fill rule gives border samples. Both pieces
evaluate the same exact sign, so they partition p's samples: painting them
covers each sample of p once, with p's own depth and values, as the
z-buffer draws p. The piece's vertices are p's clipped at that line (in
floating point, from the exact depth differences at p's vertices); they
serve the algorithms' geometric tests and bound the rows painting visits,
never decide a sample.

A polygon here is its plane: the z-buffer draws polygon p with the depth
z_p of its plane (Newell's, fitted to its vertices), so the z of its
vertices are those of the plane at their x, y (a quad whose corners are not
coplanar is drawn, and decided on, flat).

Classification against a plane uses `PLANE_TOLERANCE`: a vertex within
tolerance = PLANE_TOLERANCE * max(1, max |z|) of the plane in depth counts as
on it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..raster.fixed import exact_bits, snap_units
from ..raster.interpolate import depth_plane, plane_depth, reaches_raster, vertex_channels
from ..trace.events import Cut  # the trace's record is the domain record
from . import cut_side, zbuffer_compiled
from .zbuffer import ScreenPolygons

PLANE_TOLERANCE = 1e-9  # relative to the scene's depth magnitude (at least 1)
BEHIND, FRONT, ON, STRADDLES = "behind", "front", "on", "straddles"


@dataclass(frozen=True)
class Piece:
    """A polygon or a part of one: what the list-priority algorithms order and paint.

    ``label`` names it as the slides do: the polygon's index, then one letter
    per split, "a" for the part in front of the cutting plane and "b" for the
    part behind it ("5a", "5b", "5ba"). ``vertices`` (n, 3) are x, y (sample
    frame) and z, for the geometric tests.
    """

    polygon: int
    label: str
    vertices: np.ndarray = field(repr=False, compare=False)
    cuts: tuple[Cut, ...] = ()

    @property
    def zmin(self) -> float:
        return float(self.vertices[:, 2].min())

    @property
    def zmax(self) -> float:
        return float(self.vertices[:, 2].max())

    def rows(self) -> tuple[int, int]:
        """The sample rows [low, high) painting visits: all for a whole polygon, else its extent.

        A piece's vertices are a float clip of its samples' region, so the
        extent is widened by a row each way; the cuts decide each sample.
        """
        if not self.cuts or not len(self.vertices):
            return (
                -zbuffer_compiled.WHOLE,
                zbuffer_compiled.WHOLE,
            )  # an empty clip leaves it to the cuts
        ys = self.vertices[:, 1]
        return int(np.floor(ys.min())) - 1, int(np.ceil(ys.max())) + 2

    def extent(self) -> tuple[float, float, float, float]:
        """(x_min, x_max, y_min, y_max) of its vertices, sample frame."""
        xs, ys = self.vertices[:, 0], self.vertices[:, 1]
        return float(xs.min()), float(xs.max()), float(ys.min()), float(ys.max())


@dataclass(frozen=True)
class Surfaces:
    """The polygons of a scene as the visibility algorithms take them, validated once.

    Build with `Surfaces.of(polygons, width, height, ...)`. ``planes[p]`` is
    (x_first, y_first, z_first, dzdx, dzdy) for `plane_depth`; ``normals[p]``
    Newell's (a, b, c), c > 0 for a polygon counter-clockwise on the screen
    (front-facing); ``drawn[p]`` is False for polygons the z-buffer never
    scans (seen edge-on, c == 0, or wholly off the raster): the algorithms
    leave them out.
    """

    polygons: ScreenPolygons
    width: int
    height: int
    sample: str
    bits: int
    perspective: bool
    units: np.ndarray
    positions: np.ndarray
    channels: np.ndarray
    planes: np.ndarray
    normals: np.ndarray
    drawn: np.ndarray
    tolerance: float

    @classmethod
    def of(
        cls,
        polygons: ScreenPolygons,
        width: int,
        height: int,
        *,
        sample: str = "corner",
        subpixel_bits: int | None = 8,
        perspective: bool = False,
    ) -> Surfaces:
        bits = exact_bits(polygons.xy) if subpixel_bits is None else subpixel_bits
        units = snap_units(polygons.xy, sample, bits)
        scale = 2 ** (bits + 1)
        if units.dtype == np.int64:  # exact: every unit is below 2**53
            positions = units / scale
            planes, normals, drawn = zbuffer_compiled.polygon_planes(
                units, positions, polygons.z, polygons.offsets, scale, width, height
            )
        else:
            positions, planes, normals, drawn = _exact_planes(polygons, units, scale, width, height)
        magnitude = float(np.abs(polygons.z).max()) if len(polygons.z) else 1.0
        return cls(
            polygons=polygons,
            width=width,
            height=height,
            sample=sample,
            bits=bits,
            perspective=perspective,
            units=units,
            positions=positions,
            channels=vertex_channels(polygons.values, polygons.inv_w, perspective),
            planes=planes,
            normals=normals,
            drawn=drawn,
            tolerance=PLANE_TOLERANCE * max(1.0, magnitude),
        )

    @property
    def count(self) -> int:
        return self.polygons.count

    @property
    def scale(self) -> int:
        return 2 ** (self.bits + 1)

    @cached_property
    def xyz(self) -> np.ndarray:
        """(M, 3) x, y (sample frame, snapped) and z of every vertex, z on its polygon's plane; read-only."""
        xyz = np.column_stack([self.positions, self.polygons.z])
        owners = np.repeat(np.arange(self.count), np.diff(self.polygons.offsets))
        on_plane = self.drawn[owners]
        x, y = xyz[on_plane, 0], xyz[on_plane, 1]
        xyz[on_plane, 2] = plane_depth(*self.planes[owners[on_plane]].T, x, y)
        xyz.setflags(write=False)
        return xyz

    def vertices(self, p: int) -> np.ndarray:
        """(n, 3) x, y (sample frame, snapped) and z of polygon p's vertices."""
        return self.xyz[self.polygons.offsets[p] : self.polygons.offsets[p + 1]]

    def pieces(self) -> list[Piece]:
        """One whole piece per drawn polygon, in input order."""
        return [Piece(p, str(p), self.vertices(p)) for p in np.flatnonzero(self.drawn).tolist()]

    def depth(self, p: int, x, y):
        """z_p(x, y): the depth of polygon p's plane (scalars or arrays)."""
        return plane_depth(*self.planes[p], x, y)

    def front_facing(self, p: int) -> bool:
        """Counter-clockwise on the screen (c > 0): the viewer is on the front side of its plane."""
        return bool(self.normals[p, 2] > 0)

    def gaps(self, piece: Piece, q: int) -> np.ndarray:
        """Per vertex of `piece`, z of its plane minus z of q's plane there, exactly signed (> 0: behind q's plane)."""
        return self.vertex_gaps(piece.vertices, np.full(len(piece.vertices), piece.polygon), q)

    def vertex_gaps(self, vertices: np.ndarray, owners: np.ndarray, q: int) -> np.ndarray:
        """`gaps` of many vertices at once: vertices (n, 3) of the polygons `owners` (n,)."""
        owns = self.planes[owners]
        return cut_side.gaps(owns, self.planes[q], vertices[:, 0].copy(), vertices[:, 1].copy())

    def classify(self, piece: Piece, q: int) -> str:
        """BEHIND, FRONT (of q's plane, in depth: the viewer's side), ON (coplanar) or STRADDLES."""
        d = self.gaps(piece, q)
        far, near = bool((d > self.tolerance).any()), bool((d < -self.tolerance).any())
        if far and near:
            return STRADDLES
        return BEHIND if far else FRONT if near else ON

    def split(self, piece: Piece, q: int) -> tuple[Piece, Piece]:
        """(front, behind): `piece` cut by q's plane, exactly as a partition of its samples.

        The vertices of each part are the piece clipped at the line where the
        two planes meet (the part nearer than q's plane, and the part beyond
        it), placed by the exact depth differences at the piece's vertices.
        """
        d = self.gaps(piece, q)
        v = piece.vertices
        near, far = [], []
        for i in range(len(v)):
            j = (i + 1) % len(v)
            (far if d[i] > 0 else near).append(v[i])
            if (d[i] > 0) != (d[j] > 0):
                t = d[i] / (d[i] - d[j])
                point = v[i] + t * (v[j] - v[i])
                near.append(point)
                far.append(point)
        front = Piece(piece.polygon, piece.label + "a", _rows(near), (*piece.cuts, Cut(q, False)))
        back = Piece(piece.polygon, piece.label + "b", _rows(far), (*piece.cuts, Cut(q, True)))
        return front, back

    def cut_rows(self, piece: Piece) -> np.ndarray:
        """(k, 11) rows of `piece`'s cuts for the compiled painter (`zbuffer_compiled.keeps`)."""
        rows = np.zeros((len(piece.cuts), 11))
        for i, cut in enumerate(piece.cuts):
            rows[i, :5], rows[i, 5:10] = self.planes[piece.polygon], self.planes[cut.other]
            rows[i, 10] = 1.0 if cut.behind else 0.0
        return rows

    def keeps(self, piece: Piece, x: int, y: int) -> bool:
        """Whether sample (x, y) of piece's polygon is in the piece (the compiled painter's test)."""
        return not piece.cuts or bool(cut_side.keeps(self.cut_rows(piece), x, y))


def _exact_planes(polygons, units, scale, width, height):
    """`zbuffer_compiled.polygon_planes` for units beyond int64 (subpixel_bits=None), in Python."""
    positions = np.array([[int(u) / scale for u in row] for row in units]).reshape(-1, 2)
    count = polygons.count
    planes, normals, drawn = np.zeros((count, 5)), np.zeros((count, 3)), np.zeros(count, bool)
    for p in range(count):
        rows = slice(polygons.offsets[p], polygons.offsets[p + 1])
        xs, ys, zs = positions[rows, 0], positions[rows, 1], polygons.z[rows]
        a, b, c, dzdx, dzdy, z_first = depth_plane(xs.tolist(), ys.tolist(), zs.tolist())
        planes[p] = xs[0], ys[0], z_first, dzdx, dzdy
        normals[p] = a, b, c
        u = units[rows]
        drawn[p] = c != 0.0 and reaches_raster(
            int(u[:, 0].min()), int(u[:, 0].max()), int(u[:, 1].min()), int(u[:, 1].max()),
            scale, width, height,
        )  # fmt: skip
    return positions, planes, normals, drawn


def _rows(points: list) -> np.ndarray:
    return np.array(points, dtype=np.float64).reshape(-1, 3)

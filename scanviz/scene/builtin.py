"""Built-in scenes and the mesh generators they are made of.

The scenes are the worked examples of the seed course notes (the UMBC CMSC 435
z-buffer and painter's slides, in the slides' own coordinates) and a few
classic test scenes, each sized for the raster it lists. Every scene is built
fresh and deterministically; none downloads anything.

Attributes
----------
BUILTIN_SCENES : Mapping[str, BuiltinScene]
    Every built-in scene by name, read-only, in the order of the table below.
    ``load_scene("builtin:NAME")`` (`scanviz.io`) gives the same scenes.
BUILTIN_MESHES : Mapping[str, callable]
    The mesh generators `box`, `icosphere`, `terrain`, `torus` and
    `uv_sphere` by name, as JSON scenes refer to them. `function_surface_mesh`
    takes a Python function, so it is not among them. Every generator
    estimates its memory from its parameters first (about 400 bytes per face
    and 150 per vertex) and raises `scanviz.limits.ResourceLimitError` (a
    ValueError) over the memory limit, before allocating anything.

Notes
-----
================  =======  ==========  =================================================
name              raster   triangles   what it shows
================  =======  ==========  =================================================
umbc_zbuffer      12x12    4           the CMSC 435 z-buffer slide: three flat polygons,
                                       the third piercing the first
painter           16x12    5           the CMSC 435 painter's-algorithm slide
sphere            256x256  1,280       smooth icosphere, a point and a directional light
function_surface  256x256  3,200       z = exp(-x^2 - y^2) over [-2, 2]^2, seen from (6, 8, 3)
transparent_cube  256x256  1,292       opaque sphere behind a cube of transparency 0.5
terrain           256x256  51,200      diamond-square fractal terrain, 2 n^2 triangles
================  =======  ==========  =================================================

**The slide scenes** (``umbc_zbuffer``, ``painter``) keep the slides'
numbers: each polygon's mesh positions are the slide's (x, y, z), with x, y
in pixels and z a depth, smaller = nearer. Those coordinates are left-handed
(x right, y up, z into the screen), so ``world_from_model`` mirrors z,
diag(1, 1, -1, 1), into the right-handed world. The camera is orthographic at
the origin looking down -z with y up, window (0, W, 0, H) and near = 0,
far = 16. Rendered at W x H pixels, then:

* display x, y = the slide's x, y (pixel = coordinate, y up), and
* the depth along the view direction = the slide's z, so the slides' depth
  order holds; display depth z_ndc = z / 16 (exact in binary).

The polygons are unlit flat colors (ambient 1, diffuse 0, specular 0 under a
white ambient light and no lights), so every shading model shows exactly red,
green and blue, in the slides' order. They are not closed: nothing is culled.

**Height fields** (``function_surface``, ``terrain``) are z = f(x, y) with
z up; their cameras say ``up = (0, 0, 1)``. All other meshes are y up.

Examples
--------
>>> scene = builtin_scene("umbc_zbuffer")
>>> [o.mesh.positions.tolist() for o in scene.objects][2]
[[2.0, 6.0, 3.0], [2.0, 3.0, 8.0], [7.0, 3.0, 3.0]]
>>> BUILTIN_SCENES["painter"].width, BUILTIN_SCENES["painter"].height
(16, 12)
>>> builtin_scene("terrain", n=10).triangle_count()
200
"""

from __future__ import annotations

import inspect
import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np

from ..limits import check_memory
from ..vectors import unit_vectors
from .model import WORLD_LIMIT, Camera, Light, Material, Mesh, Scene, SceneObject

# --- argument checks ---------------------------------------------------------------------


def _count(name: str, value: object, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name!r} must be an int; got {value!r}")
    if not low <= value <= high:
        raise ValueError(f"{name!r} must be in {low}..{high}; got {value}")
    return int(value)


def _positive(name: str, value: object, high: float = math.inf) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name!r} must be a number; got {value!r}")
    if not (math.isfinite(value) and 0 < value <= high):
        rule = "finite and > 0" if high == math.inf else f"> 0 and <= {high:g}"
        raise ValueError(f"{name!r} must be {rule}; got {value}")
    return float(value)


# Peak bytes while a generator builds its Mesh, measured with tracemalloc (torus, uv_sphere,
# terrain, icosphere at ~100,000 faces: 440-520 B per face with as many vertices as faces).
_BYTES_PER_FACE = 400  # the per-face index arrays (one numpy array each) and the flat corners
_BYTES_PER_VERTEX = 150  # positions, normals and the generator's temporaries


def _check_mesh_memory(generator: str, vertices: int, faces: int) -> None:
    """Refuse, before allocating, a mesh whose estimated size is over the memory limit."""
    check_memory(
        _BYTES_PER_FACE * faces + _BYTES_PER_VERTEX * vertices,
        f"{generator} with {vertices:,} vertices and {faces:,} faces",
    )


def _grid_faces(rows: int, columns: int, *, wrap_columns: bool = False) -> np.ndarray:
    """Quads (a, b, c, d) of a rows x columns vertex grid, counter-clockwise in (column, row)."""
    r, c = np.meshgrid(
        np.arange(rows - 1), np.arange(columns if wrap_columns else columns - 1), indexing="ij"
    )
    r, c = r.ravel(), c.ravel()
    right = (c + 1) % columns
    return np.stack(
        [r * columns + c, r * columns + right, (r + 1) * columns + right, (r + 1) * columns + c],
        axis=1,
    )


def _triangulate(quads: np.ndarray) -> np.ndarray:
    """Split each quad (a, b, c, d) along a-c into (a, b, c) and (a, c, d)."""
    return np.stack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]], axis=1).reshape(-1, 3)


# --- mesh generators ---------------------------------------------------------------------


def uv_sphere(n_lat: int = 16, n_lon: int = 32) -> Mesh:
    """A unit sphere tessellated by latitude and longitude, poles on the y axis.

    Parameters
    ----------
    n_lat : int
        Bands from pole to pole, >= 2.
    n_lon : int
        Segments around the axis, >= 3.

    Returns
    -------
    Mesh
        Triangles at the poles, planar quads (isosceles trapezoids) between;
        ``2 * n_lon * (n_lat - 1)`` triangles. Unit outward normals, smooth, closed.

    Examples
    --------
    >>> mesh = uv_sphere(2, 4)
    >>> mesh.positions.tolist()[:3]
    [[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]]
    >>> mesh.face_count, mesh.triangle_count()
    (8, 8)
    """
    n_lat = _count("n_lat", n_lat, 2, 4096)
    n_lon = _count("n_lon", n_lon, 3, 4096)
    _check_mesh_memory("uv_sphere", (n_lat - 1) * n_lon + 2, n_lat * n_lon)
    polar = np.pi * np.arange(1, n_lat) / n_lat  # angle from +y, rings only
    azimuth = 2 * np.pi * np.arange(n_lon) / n_lon  # counter-clockwise seen from +y
    ring_radius = np.sin(polar)[:, None]
    rings = np.stack(
        [
            ring_radius * np.cos(azimuth),
            np.broadcast_to(np.cos(polar)[:, None], (n_lat - 1, n_lon)),
            -ring_radius * np.sin(azimuth),
        ],
        axis=-1,
    ).reshape(-1, 3)
    positions = np.concatenate([[[0.0, 1.0, 0.0]], rings, [[0.0, -1.0, 0.0]]])
    ring = np.arange(n_lon)
    following = (ring + 1) % n_lon
    last_ring = 1 + (n_lat - 2) * n_lon
    north = np.stack([np.zeros(n_lon, np.int64), 1 + ring, 1 + following], axis=1)
    bands = 1 + _grid_faces(n_lat - 1, n_lon, wrap_columns=True)[:, ::-1]
    south = np.stack(
        [np.full(n_lon, len(positions) - 1), last_ring + following, last_ring + ring], axis=1
    )
    faces = (*north, *bands, *south)
    return Mesh(positions, faces, normals=positions, smooth=True, closed=True)


_PHI = (1 + math.sqrt(5)) / 2
_ICOSAHEDRON_POSITIONS = np.array(
    [
        (-1, _PHI, 0), (1, _PHI, 0), (-1, -_PHI, 0), (1, -_PHI, 0),
        (0, -1, _PHI), (0, 1, _PHI), (0, -1, -_PHI), (0, 1, -_PHI),
        (_PHI, 0, -1), (_PHI, 0, 1), (-_PHI, 0, -1), (-_PHI, 0, 1),
    ]
)  # fmt: skip
_ICOSAHEDRON_FACES = np.array(
    [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
)  # fmt: skip


def icosphere(level: int = 3) -> Mesh:
    """A unit sphere made by subdividing an icosahedron `level` times.

    Each level splits every triangle into four at its edge midpoints and
    pushes the new vertices out onto the sphere, so triangles stay nearly
    equal in size (no crowding at poles, unlike `uv_sphere`).

    Parameters
    ----------
    level : int
        Subdivisions, 0..8; ``20 * 4**level`` triangles.

    Returns
    -------
    Mesh
        Unit outward normals, smooth, closed.

    Examples
    --------
    >>> [icosphere(level).triangle_count() for level in range(4)]
    [20, 80, 320, 1280]
    >>> bool(np.allclose(np.linalg.norm(icosphere(2).positions, axis=1), 1.0))
    True
    """
    level = _count("level", level, 0, 8)
    _check_mesh_memory("icosphere", 10 * 4**level + 2, 20 * 4**level)
    positions = unit_vectors(_ICOSAHEDRON_POSITIONS)
    faces = _ICOSAHEDRON_FACES
    for _ in range(level):
        edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        midpoints = unit_vectors(positions[unique].sum(axis=1))
        ab, bc, ca = (len(positions) + inverse.reshape(-1, 3)).T
        a, b, c = faces.T
        faces = np.array([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]])
        faces = faces.transpose(2, 0, 1).reshape(-1, 3)  # (4 children, 3 corners, F) -> rows
        positions = np.concatenate([positions, midpoints])
    return Mesh(positions, tuple(faces), normals=positions, smooth=True, closed=True)


def box(size: float | tuple[float, float, float] = 2.0) -> Mesh:
    """An axis-aligned box centred at the origin: 8 vertices, 6 quads.

    Parameters
    ----------
    size : float or (3,) tuple of float
        Edge length, or the lengths along x, y, z; each > 0 and <= 2e99, so the
        corners stay within the world coordinate limit (`scanviz.scene.model.WORLD_LIMIT`).

    Returns
    -------
    Mesh
        Faceted (``smooth=False``: each face keeps its own normal), closed.

    Examples
    --------
    >>> mesh = box((2, 4, 6))
    >>> mesh.positions.max(axis=0).tolist(), mesh.face_count
    ([1.0, 2.0, 3.0], 6)
    """
    sizes = size if isinstance(size, tuple | list) else (size, size, size)
    if len(sizes) != 3:
        raise ValueError(f"'size' must be a number or 3 numbers; got {size!r}")
    half = np.array([_positive("size", s, 2 * WORLD_LIMIT) for s in sizes]) / 2
    corners = np.array([(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)], float)
    faces = (
        (0, 2, 3, 1),  # -z
        (4, 5, 7, 6),  # +z
        (0, 4, 6, 2),  # -x
        (1, 3, 7, 5),  # +x
        (0, 1, 5, 4),  # -y
        (2, 6, 7, 3),  # +y
    )
    return Mesh(corners * half, faces, smooth=False, closed=True)


def torus(
    major_radius: float = 1.0, minor_radius: float = 0.35, n_major: int = 48, n_minor: int = 24
) -> Mesh:
    """A torus around the y axis: a tube of `minor_radius` along a circle of `major_radius`.

    Parameters
    ----------
    major_radius, minor_radius : float
        Radii of the centre circle and of the tube, both > 0 and <= 5e98 (so the
        torus stays within the world coordinate limit).
    n_major, n_minor : int
        Segments around the centre circle and around the tube, each >= 3.

    Returns
    -------
    Mesh
        Planar quads (isosceles trapezoids), ``2 * n_major * n_minor``
        triangles; analytic unit outward normals, smooth, closed.

    Examples
    --------
    >>> mesh = torus(2.0, 0.5, 8, 4)
    >>> mesh.face_count, float(mesh.positions[:, 0].max())
    (32, 2.5)
    """
    major_radius = _positive("major_radius", major_radius, WORLD_LIMIT / 2)
    minor_radius = _positive("minor_radius", minor_radius, WORLD_LIMIT / 2)
    n_major = _count("n_major", n_major, 3, 4096)
    n_minor = _count("n_minor", n_minor, 3, 4096)
    _check_mesh_memory("torus", n_major * n_minor, n_major * n_minor)
    around = 2 * np.pi * np.arange(n_major) / n_major  # counter-clockwise seen from +y
    tube = 2 * np.pi * np.arange(n_minor) / n_minor
    u, v = np.meshgrid(around, tube)  # rows: tube angle, columns: around the axis
    radial = np.stack([np.cos(u), np.zeros_like(u), -np.sin(u)], axis=-1)
    normals = np.cos(v)[..., None] * radial + np.sin(v)[..., None] * np.array([0.0, 1.0, 0.0])
    positions = major_radius * radial + minor_radius * normals
    quads = _grid_faces(n_minor + 1, n_major, wrap_columns=True) % (n_minor * n_major)
    return Mesh(
        positions.reshape(-1, 3),
        tuple(quads),
        normals=normals.reshape(-1, 3),
        smooth=True,
        closed=True,
    )


def function_surface_mesh(
    func: Callable[[np.ndarray, np.ndarray], np.ndarray],
    xrange: tuple[float, float] = (-2.0, 2.0),
    yrange: tuple[float, float] = (-2.0, 2.0),
    n: int = 40,
) -> Mesh:
    """The height field z = func(x, y) sampled on an n x n grid of cells.

    Parameters
    ----------
    func : callable
        Vectorized: ``func(x, y)`` takes two (n+1, n+1) float64 arrays and
        returns heights of the same shape, all finite.
    xrange, yrange : (2,) tuple of float
        The domain, low < high.
    n : int
        Cells per side, 1..4096; each cell is split into two triangles
        (a curved quad is not planar), ``2 * n**2`` triangles.

    Returns
    -------
    Mesh
        Vertex (i, j) = row i (y), column j (x) is vertex ``i * (n + 1) + j``.
        Faces are counter-clockwise seen from +z; normals are left to the
        renderer (``smooth=True``); open (``closed=False``).

    Examples
    --------
    >>> mesh = function_surface_mesh(lambda x, y: x * y, (0, 1), (0, 2), n=2)
    >>> mesh.positions[-1].tolist(), mesh.triangle_count()
    ([1.0, 2.0, 2.0], 8)
    """
    if not callable(func):
        raise TypeError(f"'func' must be callable; got {func!r}")
    n = _count("n", n, 1, 4096)
    _check_mesh_memory("function_surface_mesh", (n + 1) ** 2, 2 * n * n)
    axes = []
    for name, (low, high) in (("xrange", xrange), ("yrange", yrange)):
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ValueError(f"{name!r} must be finite with low < high; got {(low, high)}")
        axes.append(np.linspace(low, high, n + 1))
    x, y = np.meshgrid(*axes)
    z = np.asarray(func(x, y), dtype=np.float64)
    if z.shape != x.shape:
        raise ValueError(f"'func' must return an array of shape {x.shape}; got {z.shape}")
    if not np.isfinite(z).all():
        raise ValueError("'func' returned non-finite heights")
    positions = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    faces = _triangulate(_grid_faces(n + 1, n + 1))
    return Mesh(positions, tuple(faces), smooth=True, closed=False)


def _diamond_square(size_log2: int, roughness: float, rng: np.random.Generator) -> np.ndarray:
    """Heights on a (2**k + 1)^2 grid by the diamond-square algorithm (Fournier et al. 1982)."""
    size = 2**size_log2 + 1
    heights = np.zeros((size, size))
    heights[:: size - 1, :: size - 1] = rng.uniform(-1, 1, (2, 2))
    step, amplitude = size - 1, 1.0
    index = np.arange(size)
    while step > 1:
        half = step // 2
        # Square step: each square's centre is its corners' mean plus noise.
        corners = heights[:-1:step, :-1:step] + heights[step::step, :-1:step]
        corners = corners + heights[:-1:step, step::step] + heights[step::step, step::step]
        heights[half::step, half::step] = corners / 4 + amplitude * rng.uniform(
            -1, 1, corners.shape
        )
        # Diamond step: each edge midpoint is its 3 or 4 neighbours' mean plus noise.
        for rows, columns in (
            (index[::step], index[half::step]),
            (index[half::step], index[::step]),
        ):
            r, c = np.meshgrid(rows, columns, indexing="ij")
            total, count = np.zeros(r.shape), np.zeros(r.shape)
            for dr, dc in ((-half, 0), (half, 0), (0, -half), (0, half)):
                inside = (0 <= r + dr) & (r + dr < size) & (0 <= c + dc) & (c + dc < size)
                total += np.where(inside, heights[(r + dr) % size, (c + dc) % size], 0.0)
                count += inside
            heights[r, c] = total / count + amplitude * rng.uniform(-1, 1, r.shape)
        step, amplitude = half, amplitude * roughness
    return heights


_TERRAIN_MATERIALS = (
    Material(color=(0.16, 0.32, 0.62), specular=0.6, exponent=64.0),  # water
    Material(color=(0.30, 0.52, 0.22), specular=0.05),  # grass
    Material(color=(0.47, 0.42, 0.36), specular=0.1),  # rock
    Material(color=(0.95, 0.95, 0.97), specular=0.4, exponent=16.0),  # snow
)


def terrain(n: int = 160, seed: int = 0, roughness: float = 0.5) -> Mesh:
    """A fractal landscape over [-1, 1]^2 by diamond-square midpoint displacement.

    Heights come from the diamond-square algorithm on the smallest
    (2**k + 1)^2 grid holding (n + 1)^2 points, cropped, scaled to a relief
    of 0.5 and flooded: the lowest quarter becomes a flat lake.

    Parameters
    ----------
    n : int
        Cells per side, 1..2048: ``2 * n**2`` triangles (160: 51,200).
    seed : int
        Seed of `numpy.random.default_rng`; the same seed gives the same mesh.
    roughness : float
        Noise amplitude ratio from one level to the next, in (0, 1]; larger is rougher.

    Returns
    -------
    Mesh
        Height field z = h(x, y), vertex ``i * (n + 1) + j`` at row i (y),
        column j (x); per-vertex materials by height (water, grass, rock,
        snow) in ``materials``; normals left to the renderer, open.

    Examples
    --------
    >>> mesh = terrain(8, seed=1)
    >>> mesh.triangle_count(), float(np.ptp(mesh.positions[:, 2]))
    (128, 0.5)
    >>> bool((terrain(8, seed=1).positions == mesh.positions).all())
    True
    """
    n = _count("n", n, 1, 2048)
    grid = 2 ** max(1, math.ceil(math.log2(n))) + 1  # diamond-square works on a (2**k + 1)^2 grid
    _check_mesh_memory("terrain", max((n + 1) ** 2, grid**2), 2 * n * n)
    seed = _count("seed", seed, 0, 2**63 - 1)
    roughness = _positive("roughness", roughness)
    if roughness > 1:
        raise ValueError(f"'roughness' must be in (0, 1]; got {roughness}")
    heights = _diamond_square(
        max(1, math.ceil(math.log2(n))), roughness, np.random.default_rng(seed)
    )
    heights = heights[: n + 1, : n + 1]
    heights = np.maximum(heights, np.quantile(heights, 0.25))
    heights = 0.5 * (heights - heights.min()) / max(np.ptp(heights), 1e-300)
    limits = [1e-12, 0.3, 0.42]  # water | grass | rock | snow
    bands = np.searchsorted(limits, heights.ravel(), side="right")
    x, y = np.meshgrid(np.linspace(-1, 1, n + 1), np.linspace(-1, 1, n + 1))
    faces = tuple(_triangulate(_grid_faces(n + 1, n + 1)))
    # Polygons get the band of their mean height, so flat shading shows the bands too.
    mean_heights = heights.ravel()[np.array(faces)].mean(axis=1)
    return Mesh(
        np.stack([x, y, heights], axis=-1).reshape(-1, 3),
        faces,
        smooth=True,
        closed=False,
        face_materials=np.searchsorted(limits, mean_heights, side="right"),
        vertex_materials=bands,
        materials=_TERRAIN_MATERIALS,
    )


BUILTIN_MESHES: Mapping[str, Callable[..., Mesh]] = MappingProxyType(
    {"box": box, "icosphere": icosphere, "terrain": terrain, "torus": torus, "uv_sphere": uv_sphere}
)
"""The mesh generators a JSON scene can name as ``{"builtin_mesh": NAME, ...parameters}``."""


# --- scenes ------------------------------------------------------------------------------

SLIDE_COLORS = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
SLIDE_DEPTH = 16.0  # the far plane: slide depths z in [0, 16) are z / 16 in the buffer, exactly
_SLIDE_MIRROR = np.diag([1.0, 1.0, -1.0, 1.0])  # the slides' left-handed screen space -> world


def slide_scene(
    polygons, width: int, height: int, *, colors=SLIDE_COLORS, names=None, name: str = ""
) -> Scene:
    """Flat-colored polygons in slide coordinates, seen 1:1 by an orthographic camera.

    Slide coordinates are the UMBC slides': x, y in pixels, z a depth into the
    screen (smaller = nearer), in [0, `SLIDE_DEPTH`). Polygon k gets
    ``colors[k % len(colors)]`` and the name ``names[k]`` (default "polygon k").
    """
    objects = tuple(
        SceneObject(
            Mesh(polygon, (tuple(range(len(polygon))),), smooth=False, closed=False),
            Material(color=colors[k % len(colors)], ambient=1.0, diffuse=0.0, specular=0.0),
            _SLIDE_MIRROR,
            names[k] if names is not None else f"polygon {k}",
        )
        for k, polygon in enumerate(polygons)
    )
    camera = Camera(
        eye=(0, 0, 0),
        look_at=(0, 0, -1),
        up=(0, 1, 0),
        window=(0, width, 0, height),
        near=0.0,
        far=SLIDE_DEPTH,
        projection="orthographic",
    )
    return Scene(objects, camera, lights=(), ambient=(1, 1, 1), name=name)


_ORDINALS = ("first polygon", "second polygon", "third polygon")


def _umbc_zbuffer() -> Scene:
    return slide_scene(
        (
            ((1, 1, 5), (7, 7, 5), (1, 7, 5)),
            ((3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)),
            ((2, 6, 3), (2, 3, 8), (7, 3, 3)),
        ),
        12,
        12,
        names=_ORDINALS,
        name="umbc_zbuffer",
    )


def _painter() -> Scene:
    return slide_scene(
        (
            ((6, 3, 10), (11, 5, 10), (2, 2, 10)),
            ((1, 2, 8), (12, 2, 8), (12, 6, 8), (1, 6, 8)),
            ((6, 5, 5), (14, 5, 5), (14, 10, 5), (6, 10, 5)),
        ),
        16,
        12,
        names=_ORDINALS,
        name="painter",
    )


_KEY_LIGHT = Light("point", color=(0.85, 0.85, 0.8), position=(4.0, 5.0, 6.0))
_FILL_LIGHT = Light("directional", color=(0.25, 0.27, 0.35), direction=(1.0, 0.2, -1.0))
_BACKGROUND = (0.08, 0.08, 0.1)


def _sphere(level: int = 3) -> Scene:
    return Scene(
        (
            SceneObject(
                icosphere(level),
                Material(color=(0.85, 0.3, 0.2), specular=0.5, exponent=40.0),
                name="sphere",
            ),
        ),
        Camera(eye=(0, 0, 4), window=(-0.3, 0.3, -0.3, 0.3), near=1.0, far=10.0),
        lights=(_KEY_LIGHT, _FILL_LIGHT),
        ambient=(1, 1, 1),
        background=_BACKGROUND,
        name="sphere",
    )


def _function_surface(n: int = 40) -> Scene:
    mesh = function_surface_mesh(lambda x, y: np.exp(-(x**2) - y**2), (-2, 2), (-2, 2), n)
    return Scene(
        (SceneObject(mesh, Material(color=(0.25, 0.6, 0.85), specular=0.4), name="exp(-x^2-y^2)"),),
        Camera(eye=(6, 8, 3), up=(0, 0, 1), window=(-1.2, 1.2, -1.2, 1.2), near=4.0, far=20.0),
        lights=(
            Light("point", color=(0.85, 0.85, 0.8), position=(2.0, 6.0, 8.0)),
            Light("directional", color=(0.25, 0.25, 0.3), direction=(1.0, -0.5, -1.0)),
        ),
        background=_BACKGROUND,
        name="function_surface",
    )


def _transparent_cube() -> Scene:
    sphere_from_model = np.diag([1.2, 1.2, 1.2, 1.0])
    sphere_from_model[:3, 3] = (-0.6, -0.3, -2.7)  # behind the cube, peeking out at its top right
    return Scene(
        (
            SceneObject(
                icosphere(3),
                Material(color=(0.85, 0.3, 0.2), specular=0.5, exponent=40.0),
                sphere_from_model,
                "opaque sphere",
            ),
            SceneObject(
                replace(box(1.6), closed=False),  # not culled: its back faces show through
                Material(color=(0.3, 0.6, 0.95), specular=0.3, transparency=0.5),
                name="transparent cube",
            ),
        ),
        Camera(eye=(3, 2.5, 6), window=(-0.25, 0.25, -0.25, 0.25), near=1.0, far=20.0),
        lights=(_KEY_LIGHT, _FILL_LIGHT),
        background=(0.9, 0.9, 0.88),
        name="transparent_cube",
    )


def _terrain(n: int = 160, seed: int = 0) -> Scene:
    return Scene(
        (SceneObject(terrain(n, seed), Material(), name="terrain"),),
        Camera(
            eye=(2.3, -2.3, 2.3),
            look_at=(0.0, 0.0, 0.1),
            up=(0, 0, 1),
            window=(-0.4, 0.4, -0.4, 0.4),
            near=1.0,
            far=10.0,
        ),
        lights=(
            Light("directional", color=(0.9, 0.85, 0.75), direction=(-1.0, 0.6, -0.8)),
            Light("directional", color=(0.2, 0.22, 0.3), direction=(1.0, 1.0, -0.5)),
        ),
        background=(0.55, 0.7, 0.9),
        name="terrain",
    )


@dataclass(frozen=True)
class BuiltinScene:
    """A built-in scene: its description, the raster it is made for, and its builder.

    Attributes
    ----------
    name : str
        Key in `BUILTIN_SCENES`.
    description : str
        One line.
    width, height : int
        The raster the camera window is chosen for.
    build : callable
        Returns a new `Scene`; keyword parameters as `builtin_scene` documents.
    """

    name: str
    description: str
    width: int
    height: int
    build: Callable[..., Scene]


BUILTIN_SCENES: Mapping[str, BuiltinScene] = MappingProxyType(
    {
        scene.name: scene
        for scene in (
            BuiltinScene(
                "umbc_zbuffer", "CMSC 435 z-buffer slide, slide coordinates", 12, 12, _umbc_zbuffer
            ),
            BuiltinScene(
                "painter", "CMSC 435 painter's slide, slide coordinates", 16, 12, _painter
            ),
            BuiltinScene(
                "sphere", "smooth icosphere, point + directional light", 256, 256, _sphere
            ),
            BuiltinScene(
                "function_surface", "z = exp(-x^2 - y^2) on [-2, 2]^2", 256, 256, _function_surface
            ),
            BuiltinScene(
                "transparent_cube",
                "opaque sphere behind a cube of transparency 0.5",
                256,
                256,
                _transparent_cube,
            ),
            BuiltinScene("terrain", "diamond-square fractal terrain", 256, 256, _terrain),
        )
    }
)


def builtin_scene(name: str, **params: object) -> Scene:
    """Build the built-in scene `name` (see `BUILTIN_SCENES`).

    Parameters
    ----------
    name : str
        One of `BUILTIN_SCENES`.
    **params
        Passed to the scene's builder: ``sphere(level=3)`` (icosphere
        subdivisions), ``function_surface(n=40)`` (cells per side),
        ``terrain(n=160, seed=0)`` (cells per side, random seed). The slide
        scenes and ``transparent_cube`` take none.

    Returns
    -------
    Scene

    Raises
    ------
    ValueError
        If `name` is unknown or a parameter is not one the scene takes.

    Examples
    --------
    >>> builtin_scene("sphere").triangle_count()
    1280
    >>> builtin_scene("sphere", level=1).triangle_count()
    80
    >>> builtin_scene("cube")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: unknown built-in scene 'cube'; known: umbc_zbuffer, painter, sphere, ...
    """
    if name not in BUILTIN_SCENES:
        raise ValueError(f"unknown built-in scene {name!r}; known: {', '.join(BUILTIN_SCENES)}")
    build = BUILTIN_SCENES[name].build
    allowed = tuple(inspect.signature(build).parameters)
    unknown = sorted(set(params) - set(allowed))
    if unknown:
        raise ValueError(
            f"built-in scene {name!r} takes parameters ({', '.join(allowed)}); got {', '.join(unknown)}"
        )
    return build(**params)

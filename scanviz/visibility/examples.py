"""The scenes the visibility lessons use: the UMBC slides' examples and the painter's failures.

Every function returns `ScreenPolygons` in display coordinates (pixels,
y up; depth z, smaller nearer) with one value per vertex: the polygon's
index, so a Gouraud-style image of ``values`` shows which polygon is where.
Sizes are chosen for a 16 x 12 raster unless a function says otherwise.

- `slides_painter`: the three polygons of the slides' painter's algorithm
  example (depths 10, 8, 5: painted in that order).
- `slides_zbuffer`: the three polygons of the slides' z-buffer example (the
  sloped triangle crosses the other two).
- `cyclic_overlap`: three long bars, each over the next and under the
  previous: no order of whole polygons is right (painter's fails).
- `interpenetrating`: two polygons passing through each other.
- `long_behind_short`: a long slanted polygon behind a short one over its far
  end: sorting on the nearest vertex (the painter's default) paints the short
  one first and the long one over it, which is wrong; sorting on the farthest
  vertex happens to be right here.
- `slides_bsp`: the slides' BSP example from viewpoint C (32 x 24, a
  reconstruction; `BSP(sequence=BSP_SEQUENCE)` gives the slides' tree).
- `split_hole`: two polygons whose split once left samples empty (a
  regression scene, 32 x 32).
- `random_scene(kind, seed, size)`: seeded random scenes of the kinds that
  stress splitting (`RANDOM_KINDS`), for the agreement campaign.
"""

from __future__ import annotations

import numpy as np

from .zbuffer import ScreenPolygons


def _scene(polygons) -> ScreenPolygons:
    values = [np.full((len(p), 1), float(i)) for i, p in enumerate(polygons)]
    return ScreenPolygons.from_polygons(polygons, values)


def slides_painter() -> ScreenPolygons:
    """The slides' painter example: a triangle at z = 10, a rectangle at 8, a square at 5 (16 x 12)."""
    return _scene(
        [
            [(6, 3, 10), (11, 5, 10), (2, 2, 10)],
            [(1, 2, 8), (12, 2, 8), (12, 6, 8), (1, 6, 8)],
            [(6, 5, 5), (14, 5, 5), (14, 10, 5), (6, 10, 5)],
        ]
    )


def slides_zbuffer() -> ScreenPolygons:
    """The slides' z-buffer example (10 x 9): a triangle at 5, a square at 9, a sloped triangle."""
    return _scene(
        [
            [(1, 1, 5), (7, 7, 5), (1, 7, 5)],
            [(3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)],
            [(2, 6, 3), (2, 3, 8), (7, 3, 3)],
        ]
    )


def cyclic_overlap(size: int = 24) -> ScreenPolygons:
    """Three bars in a cycle (size x size): A over B over C over A, each sloped in depth.

    Each bar's depth falls along its length, so it is nearer than the next bar
    where they cross and farther than the previous one: there is no painting
    order of whole bars, and depth sort must split one.
    """
    s = size / 24
    bars = []
    for k in range(3):
        angle = 2 * np.pi * k / 3
        c, d = np.cos(angle), np.sin(angle)
        # A bar from near the centre outwards, 4 wide; depth from 0.2 (its start) to 0.8.
        corners = [(-9, -2), (9, -2), (9, 2), (-9, 2)]
        offset = (4 * -d, 4 * c)
        polygon = []
        for u, v in corners:
            x = 12 * s + s * (u * c - v * d + offset[0])
            y = 12 * s + s * (u * d + v * c + offset[1])
            polygon.append((x, y, 0.5 + 0.3 * u / 9))
        bars.append(polygon)
    return _scene(bars)


def interpenetrating() -> ScreenPolygons:
    """Two rectangles passing through each other (16 x 12): each is in front over half the other."""
    return _scene(
        [
            [(1, 2, 0.2), (13, 2, 0.8), (13, 10, 0.8), (1, 10, 0.2)],
            [(3, 1, 0.7), (15, 1, 0.3), (15, 9, 0.3), (3, 9, 0.7)],
        ]
    )


def long_behind_short() -> ScreenPolygons:
    """A long slanted polygon behind a short one (16 x 12) that sorting on zmin paints wrongly."""
    return _scene(
        [
            [(1, 3, 0.3), (15, 3, 0.9), (15, 8, 0.9), (1, 8, 0.3)],  # long: from 0.3 to 0.9
            [
                (10, 2, 0.5),
                (14, 2, 0.5),
                (14, 10, 0.5),
                (10, 10, 0.5),
            ],  # short: at 0.5, over the far end
        ]
    )


# The slides' BSP example, top view (u right, v away from the viewpoint C at the origin): each
# wall (number, start, end, bottom, top) runs from start to end with its front side on the right.
BSP_WALLS = (
    (1, (-3.0, 3.0), (-1.0, 3.0), -1.0, 1.5),
    (2, (4.0, 2.5), (1.0, 3.0), -1.0, 0.5),
    (3, (-4.0, 6.0), (2.0, 6.0), -1.0, 0.5),
    (4, (5.0, 9.0), (-5.0, 9.0), -1.0, 3.0),
    (5, (3.0, 4.0), (3.0, 8.0), -1.0, 3.0),
)
BSP_SEQUENCE = (3, 2, 4, 5, 1)  # the list MakeBSP takes on the slides: pgon 3 first


def slides_bsp() -> ScreenPolygons:
    """The slides' BSP example seen from viewpoint C (32 x 24): five walls, numbered as there.

    The slides' figure is lost; this is a reconstruction (`BSP_WALLS`, a top
    view) with the tree the slides build from pgon 3: 3 at the root, whose
    plane splits 5 into 5a (in front) and 5b (behind); 2 the root of the
    front list (5a in front of it, 1 behind), 4 of the back list (5b behind).
    From C, the viewer is in front of 3 and 1 and behind 2, 4 and 5. Polygon
    i is the slides' pgon i: polygon 0 is a placeholder off the raster, which
    every algorithm leaves out. Build with ``BSP(sequence=BSP_SEQUENCE)`` for
    the slides' list order. Each wall is projected from C (focal length 10,
    C at pixel (12, 10)) with depth z = 1 - 1/v, a projective map: planes stay
    planes and sides stay sides.
    """
    walls = [[(-10.0, -10.0, 0.5), (-9.0, -10.0, 0.5), (-10.0, -9.0, 0.5)]]
    for _, (u0, v0), (u1, v1), bottom, top in BSP_WALLS:
        corners = [(u0, v0, bottom), (u1, v1, bottom), (u1, v1, top), (u0, v0, top)]
        walls.append([(12 + 10 * u / v, 10 + 10 * h / v, 1 - 1 / v) for u, v, h in corners])
    return _scene(walls)


def split_hole() -> ScreenPolygons:
    """Two quads (32 x 32) whose BSP split left 9 samples empty when a piece's rows came from
    its corners' own depths rather than its plane's (corners not coplanar)."""
    return ScreenPolygons.from_polygons(
        [
            [[34.25, 53.75, 0.49524753217059897], [32.5, 54.5, 0.4884976242681647],
             [0.0, 13.75, 0.4724993346515287], [6.25, 7.0, 0.504749005731651]],
            [[-2.9050833466952337, 46.4032270246079, 0.39847807124131474],
             [-14.837687936407182, 41.5759466890838, 0.37233538819589335],
             [-17.65522605249134, 27.44248192010425, 0.3921498379869859],
             [2.7598726438833863, 19.425047285111837, 0.4694290280618343]],
        ]
    )  # fmt: skip


RANDOM_KINDS = (
    "quads", "triangles", "near_coplanar", "interpenetrating", "cyclic", "slivers", "steep", "grid",
)  # fmt: skip
_SLOPES = {"steep": 5.0, "interpenetrating": 1.0}  # depth change across the raster, else 0.05


def random_scene(kind: str, seed: int, size: int = 32) -> ScreenPolygons:
    """A seeded random scene of 2-8 polygons over a size x size raster, of one of `RANDOM_KINDS`.

    "quads": convex 3-6-gons with random corner depths (not coplanar);
    "triangles": slanted triangles; "near_coplanar": polygons within about
    1e-9 of one plane; "interpenetrating": steep planes that cross inside
    the overlaps; "cyclic": three bars in a cycle; "slivers": triangles with
    a corner near the opposite edge; "steep": planes rising 5 per raster;
    "grid": integer corners and depths in 64ths (lines through samples).

    >>> random_scene("cyclic", 0).count
    3
    """
    rng = np.random.default_rng(seed)
    if kind == "cyclic":
        return _cyclic_bars(rng, size)
    if kind not in RANDOM_KINDS:
        raise ValueError(f"'kind' must be one of {RANDOM_KINDS}; got {kind!r}")
    origin, slope, level = (
        rng.uniform(0, size, 2),
        rng.normal(size=2) * 0.02 / size,
        rng.uniform(0.3, 0.7),
    )
    polygons = []
    for k in range(int(rng.integers(2, 9))):
        corners = 3 if kind in ("triangles", "slivers") else int(rng.integers(3, 7))
        center = rng.uniform(0, size, 2)
        angles = np.sort(rng.uniform(0, 2 * np.pi, corners))
        xy = center + rng.uniform(3, 0.7 * size) * np.column_stack([np.cos(angles), np.sin(angles)])
        if kind == "slivers":
            xy[2] = xy[0] + (xy[1] - xy[0]) * rng.uniform() + rng.normal(size=2) * 0.05
        if kind == "grid":
            xy = np.round(xy)
        if kind == "quads":
            z = rng.uniform(0.3, 0.6, corners)
        elif kind == "near_coplanar":
            tilt = slope + rng.normal(size=2) * 1e-10
            z = level + (xy - origin) @ tilt + rng.normal() * 1e-9 * (k > 0)
        else:
            z = rng.uniform(0.3, 0.7) + (xy - center) @ (
                rng.normal(size=2) * _SLOPES.get(kind, 0.05) / size
            )
        if kind == "grid":
            z = np.round(z * 64) / 64
        polygons.append(np.column_stack([xy, z]).tolist())
    return ScreenPolygons.from_polygons(polygons)


def _cyclic_bars(rng: np.random.Generator, size: int) -> ScreenPolygons:
    """Three jittered bars through the middle, each sloped in depth along its length."""
    bars = []
    for k in range(3):
        angle = 2 * np.pi * k / 3 + rng.normal() * 0.1
        along = np.array([np.cos(angle), np.sin(angle)])
        across = np.array([-along[1], along[0]])
        center = size / 2 + rng.normal(size=2)
        ends = (center - 0.6 * size * along, center + 0.6 * size * along)
        xy = np.array(
            [ends[0] - 3 * across, ends[1] - 3 * across, ends[1] + 3 * across, ends[0] + 3 * across]
        )
        z = 0.5 + ((xy - center) @ along) * 0.01 * rng.uniform(0.5, 1.5)
        bars.append(np.column_stack([xy, z]).tolist())
    return ScreenPolygons.from_polygons(bars)

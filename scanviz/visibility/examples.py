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

"""A catalog of named test shapes: canonical, tricky and degenerate polygons.

Tests, notebooks and benchmarks draw from the same shapes, so a case found
once (a vertex on a sample, a hole, a self-intersection) is reused everywhere.
Each `Shape` names the raster it is drawn for; coordinates are pixels, y up.

Attributes
----------
SHAPES : Mapping[str, Shape]
    Every shape by name, read-only, in the order of the table below.

Notes
-----
=============================  ==================================================
convex                         regular hexagon, float vertices
concave                        chevron (arrowhead) with one reflex vertex
pentagram                      self-intersecting star: centre in for nonzero only
bow_tie                        self-intersecting quad: lobes of opposite winding
square_with_hole               outer square and a reversed inner contour
two_squares_overlapping        two contours, same orientation: overlap winds twice
horizontal_and_vertical_edges  rectilinear L-shape on integer coordinates
vertices_on_samples            diamond whose vertices and edges hit sample points
umbc_example                   the UMBC CMSC 435 scanline-fill slide polygon
comb                           zig-zag top edge: many local extremes, busy AET
repeated_vertices              square with repeated vertices (zero-length edges)
sliver                         long quad thinner than a pixel
subpixel                       triangle inside one pixel, around its centre
huge                           triangle with vertices near +-2**20
tiny                           triangle of size ~1e-6 around a sample point
collinear                      zero area: vertices on one line through samples
repeated_collinear             zero area: collinear with repeated vertices
zero_area_bow_tie              bow tie whose lobes collapsed to segments
sliver_between_rows            thin strip between sample rows in both modes
=============================  ==================================================

`Shape.degenerate` is True when the shape can cover no sample in any mode
(zero area, or too thin to reach a sample row): it must render nothing.
Every other shape covers at least one sample of its raster in some mode
(sample point and sub-pixel bits); `tiny`, for one, does so only unsnapped.

Examples
--------
>>> from scanviz import scan_convert
>>> shape = get("umbc_example")
>>> shape.polygon.contours[0].tolist()
[[4.0, 1.0], [1.0, 11.0], [9.0, 5.0], [12.0, 8.0], [12.0, 1.0]]
>>> int(scan_convert(shape.polygon, shape.width, shape.height).mask.sum())
59
>>> get("circle")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
KeyError: "unknown shape 'circle'; known shapes: convex, concave, ...
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from .geometry import Polygon


@dataclass(frozen=True)
class Shape:
    """A named polygon with a one-line description and the raster it is drawn for.

    Attributes
    ----------
    name : str
        Key in `SHAPES`.
    polygon : Polygon
        The shape itself.
    description : str
        One line saying what the shape tests.
    degenerate : bool
        True if it covers no sample in any mode (must render nothing).
    width, height : int
        The raster the shape is sized for.
    """

    name: str
    polygon: Polygon
    description: str
    degenerate: bool = False
    width: int = 32
    height: int = 32


def _circle(count: int, radius: float, step: int = 1, turn: float = 0.1) -> list[tuple]:
    """`count` points on a circle about (16, 16), taken `step` at a time (counter-clockwise)."""
    angles = (turn + 2 * math.pi * (i * step % count) / count for i in range(count))
    return [(16 + radius * math.cos(a), 16 + radius * math.sin(a)) for a in angles]


def _comb(teeth: int) -> list[tuple]:
    """A base strip with a zig-zag top: `teeth` peaks at y 26.5 over valleys at y 8.25."""
    top = [
        (30.5 - 4.5 * i - 2.25 * (j % 2), 26.5 if j % 2 == 0 else 8.25)
        for i in range(teeth)
        for j in range(2)
    ]
    return [(1.5, 2.5), (30.5, 2.5), *top, (1.5, 26.5)]


def _shape(
    name: str,
    contours: object,
    description: str,
    *,
    degenerate: bool = False,
    size: tuple[int, int] = (32, 32),
) -> Shape:
    """A `Shape` from raw contours; `size` is (width, height)."""
    return Shape(name, Polygon(contours), description, degenerate, *size)


_SQUARE = [(5.5, 5.5), (20.5, 5.5), (20.5, 20.5), (5.5, 20.5)]

_SHAPES = [
    _shape("convex", _circle(6, 12.5), "regular hexagon, float vertices"),
    _shape(
        "concave",
        [(2.5, 2.25), (21.5, 12.5), (2.5, 22.75), (9.25, 12.5)],
        "chevron (arrowhead) with one reflex vertex",
        size=(24, 24),
    ),
    _shape(
        "pentagram",
        _circle(5, 14.5, step=2),
        "self-intersecting star: the centre winds twice (in for nonzero, out for evenodd)",
    ),
    _shape(
        "bow_tie",
        [(3.5, 3.25), (28.5, 20.75), (28.5, 3.25), (3.5, 20.75)],
        "self-intersecting quad whose two lobes wind in opposite directions",
        size=(32, 24),
    ),
    _shape(
        "square_with_hole",
        [
            [(3.5, 3.5), (28.5, 3.5), (28.5, 28.5), (3.5, 28.5)],
            [(11.25, 11.25), (11.25, 20.75), (20.75, 20.75), (20.75, 11.25)],
        ],
        "outer square and a hole given as a reversed inner contour",
    ),
    _shape(
        "two_squares_overlapping",
        [[(4, 4), (20, 4), (20, 20), (4, 20)], [(12, 12), (28, 12), (28, 28), (12, 28)]],
        "two counter-clockwise squares: the overlap winds twice (out for evenodd)",
    ),
    _shape(
        "horizontal_and_vertical_edges",
        [(4, 4), (24, 4), (24, 10), (10, 10), (10, 26), (4, 26)],
        "rectilinear L-shape on integer coordinates: horizontal edges on sample rows",
    ),
    _shape(
        "vertices_on_samples",
        [(16, 4), (28, 16), (16, 28), (4, 16)],
        "diamond whose vertices are samples and whose edges pass through samples",
    ),
    _shape(
        "umbc_example",
        [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)],
        "the scanline-fill example polygon of the UMBC CMSC 435 slides",
        size=(16, 16),
    ),
    _shape(
        "comb",
        _comb(6),
        "strip with a zig-zag top: many local minima and maxima, a busy active edge table",
    ),
    _shape(
        "repeated_vertices",
        [_SQUARE[0], _SQUARE[0], _SQUARE[1], _SQUARE[2], _SQUARE[2], _SQUARE[3], _SQUARE[0]],
        "square with repeated vertices (zero-length edges): same pixels as the plain square",
        size=(24, 24),
    ),
    _shape(
        "sliver",
        [(1.25, 2.4), (30.5, 14.2), (30.5, 14.6), (1.25, 2.8)],
        "long quad 0.4 pixel tall: covers a sample only here and there",
        size=(32, 16),
    ),
    _shape(
        "subpixel",
        [(5.25, 5.25), (5.875, 5.375), (5.5, 5.875)],
        "triangle inside pixel (5, 5) around its centre: covered by center sampling only",
        size=(8, 8),
    ),
    _shape(
        "huge",
        [(-(2**20) + 0.5, -(2**20) + 0.25), (2**20 - 0.75, -(2**20) + 1.5), (3.3, 2**20 - 1)],
        "triangle with vertices near +-2**20 covering the whole raster: very long edges",
        size=(64, 64),
    ),
    _shape(
        "tiny",
        [(8 - 1e-6, 8 - 1e-6), (8 + 2e-6, 8 - 0.5e-6), (8 - 0.5e-6, 8 + 2e-6)],
        "triangle ~1e-6 across around sample (8, 8): covers it only without snapping",
        size=(16, 16),
    ),
    _shape(
        "collinear",
        [(2, 3), (10, 7), (26, 15), (18, 11)],
        "zero area: vertices on the line y = x/2 + 2, which passes through samples",
        degenerate=True,
    ),
    _shape(
        "repeated_collinear",
        [(4, 4), (4, 4), (12, 12), (12, 12), (8, 8)],
        "zero area: repeated vertices on the diagonal y = x",
        degenerate=True,
        size=(16, 16),
    ),
    _shape(
        "zero_area_bow_tie",
        [(2, 2), (8, 14), (14, 2), (8, 14)],
        "bow tie whose lobes collapsed to segments: each edge is retraced",
        degenerate=True,
        size=(16, 16),
    ),
    _shape(
        "sliver_between_rows",
        [(1.5, 5.125), (30.5, 5.25), (30.5, 5.375), (1.5, 5.375)],
        "strip between sample rows y = 5 and y = 5.5: no row of either sample mode crosses it",
        degenerate=True,
        size=(32, 8),
    ),
]

SHAPES: Mapping[str, Shape] = MappingProxyType({shape.name: shape for shape in _SHAPES})


def get(name: str) -> Shape:
    """The shape called `name`; a KeyError lists the known names.

    >>> get("pentagram").polygon.vertex_count
    5
    """
    try:
        return SHAPES[name]
    except KeyError:
        raise KeyError(f"unknown shape {name!r}; known shapes: {', '.join(SHAPES)}") from None

"""Fill variants of the UMBC slides: solid, pattern, colour wash and vertex colours.

The slides' scan-line fill writes one colour between each pair of crossings
(``for x in [x1, x2): framebuffer[x, y] = c``) and then varies what is
written:

* **Pattern fill**: a tile repeated over the plane. The slides' checker is
  ``c1 if (x + y) % 2 else c2``; any (h, w, 3) tile works. It is anchored to
  the screen (tile pixel (x mod w, y mod h)), or to the polygon (the tile's
  origin at the pixel of its lower-left bounding corner, so the pattern moves
  with the polygon).
* **Colour wash**: colour linear across the polygon, ``C0 + dC (x - x1)``
  along a span, from one colour at the polygon's extreme vertex in a
  direction to another at the opposite extreme. "For efficiency carry C and
  dC in AET and calculate color incrementally."
* **Vertex colours**: a colour per vertex, carried along the edges as Cy and
  dCy in the AET, with dCx computed at the start of each span.

Solid and pattern fills colour the samples `scan_convert` covers (any
contours, either fill rule). The wash and the vertex colours are the
incremental scheme of `scanviz.raster.interpolate`: every active edge
carries its colour on the current row and steps it by dC/dy, every span
steps by dC/dx. They run through the z-buffer (`scanviz.visibility.zbuffer`)
with the colours as its interpolated values, so they take one contour and
its samples are the z-buffer's (the nonzero rule; nothing when the snapped
signed area is 0). A wash is vertex colours that are a linear function of
position, so the incremental scheme reproduces it to rounding.

Without a tracer the compiled kernels run; with one, the traced references
(``edge_table_built`` ... ``span`` for solid and pattern; ``polygon_setup``,
``edge_values``, ``span_values`` for the others). Both give the same image,
bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..conventions import check_choice, check_raster_size, short_repr
from ..geometry import Polygon
from ..limits import check_memory
from ..raster.api import as_tracer, scan_convert
from ..trace import Recorder, Trace

ANCHORS = ("screen", "polygon")
# Bytes per pixel fill_polygon holds at its peak, estimated before any is allocated.
IMAGE_PIXEL_BYTES = 1 + 3 * 8  # the bool mask and the (H, W, 3) float64 image
PATTERN_PIXEL_BYTES = 7 * 8  # row and column indices, their remainders, the gathered tile colours
WASH_PIXEL_BYTES = 8 * (2 + 3)  # the z-buffer's depth, ids and three colour channels


def _colour(name: str, value: object) -> tuple[float, float, float]:
    try:
        colour = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        colour = np.zeros(0)
    if (
        colour.shape != (3,)
        or not np.isfinite(colour).all()
        or (colour < 0).any()
        or (colour > 1).any()
    ):
        raise ValueError(f"{name!r} must be an RGB triple in [0, 1]; got {short_repr(value)}")
    return tuple(colour.tolist())


def _colours(name: str, value: object) -> np.ndarray:
    try:
        colours = np.array(value, dtype=np.float64)
    except (TypeError, ValueError):
        colours = np.zeros(0)
    if colours.ndim != 2 or colours.shape[1:] != (3,) or not colours.size:
        raise ValueError(
            f"{name!r} must be an (N, 3) array of RGB colours; got {short_repr(value)}"
        )
    if not np.isfinite(colours).all() or (colours < 0).any() or (colours > 1).any():
        raise ValueError(f"{name!r} must hold colours in [0, 1]")
    colours.setflags(write=False)
    return colours


@dataclass(frozen=True)
class Solid:
    """One colour between every pair of crossings."""

    color: tuple[float, float, float] = (1.0, 1.0, 1.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "color", _colour("color", self.color))


@dataclass(frozen=True, eq=False)
class Pattern:
    """A tile repeated over the plane, anchored to the screen or to the polygon.

    ``tile`` is (h, w, 3) RGB in [0, 1], row 0 at the bottom (y up, as images).
    `Pattern.checker` is the slides' two-colour checker.
    """

    tile: np.ndarray
    anchor: str = "screen"

    def __post_init__(self) -> None:
        try:
            tile = np.array(self.tile, dtype=np.float64)
        except (TypeError, ValueError):
            tile = np.zeros(0)
        if tile.ndim != 3 or tile.shape[2] != 3 or not tile.size:
            raise ValueError(f"'tile' must be an (h, w, 3) RGB array; got {short_repr(self.tile)}")
        if not np.isfinite(tile).all() or (tile < 0).any() or (tile > 1).any():
            raise ValueError("'tile' must hold colours in [0, 1]")
        tile.setflags(write=False)
        object.__setattr__(self, "tile", tile)
        check_choice("anchor", self.anchor, ANCHORS)

    @classmethod
    def checker(cls, c1=(1.0, 1.0, 1.0), c2=(0.0, 0.0, 0.0), anchor: str = "screen") -> Pattern:
        """The slides' pattern: ``c1 if (x + y) % 2 else c2``.

        >>> Pattern.checker((1, 0, 0), (0, 0, 1)).tile[..., 0].tolist()
        [[0.0, 1.0], [1.0, 0.0]]
        """
        c1, c2 = np.array(_colour("c1", c1)), np.array(_colour("c2", c2))
        odd = (np.add.outer(np.arange(2), np.arange(2)) % 2).astype(bool)
        return cls(np.where(odd[..., None], c1, c2), anchor)


@dataclass(frozen=True)
class ColourWash:
    """``start`` at the polygon's extreme vertex against ``direction``, ``end`` at the other extreme.

    The colour is linear in position: C(p) = start + t (end - start), t the
    position of p along `direction` from 0 (the lowest vertex) to 1 (the
    highest). Default: left to right, red to blue as on the slides.
    """

    start: tuple[float, float, float] = (1.0, 0.0, 0.0)
    end: tuple[float, float, float] = (0.0, 0.0, 1.0)
    direction: tuple[float, float] = (1.0, 0.0)

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", _colour("start", self.start))
        object.__setattr__(self, "end", _colour("end", self.end))
        direction = np.asarray(self.direction, dtype=np.float64)
        if direction.shape != (2,) or not np.isfinite(direction).all() or not direction.any():
            raise ValueError(f"'direction' must be a nonzero finite (dx, dy); got {short_repr(self.direction)}")  # fmt: skip
        object.__setattr__(self, "direction", tuple(direction.tolist()))

    def vertex_colours(self, vertices: np.ndarray) -> np.ndarray:
        """The wash's colour at each vertex (N, 2): the values the AET carries."""
        along = vertices @ np.array(self.direction)
        extent = along.max() - along.min()
        t = (along - along.min()) / extent if extent > 0 else np.zeros(len(vertices))
        return np.array(self.start) + t[:, None] * (np.array(self.end) - np.array(self.start))


@dataclass(frozen=True, eq=False)
class VertexColours:
    """One RGB colour per vertex, interpolated along the edges, then along the spans."""

    colors: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "colors", _colours("colors", self.colors))


FILLS = (Solid, Pattern, ColourWash, VertexColours)


@dataclass(frozen=True)
class FillResult:
    """image (H, W, 3) float64, row 0 at the bottom; mask (H, W) bool: the samples filled."""

    image: np.ndarray
    mask: np.ndarray
    trace: Trace | None = field(default=None)


def fill_polygon(
    polygon: object,
    width: int,
    height: int,
    fill: object = None,
    *,
    background: tuple[float, float, float] = (0.0, 0.0, 0.0),
    sample: str = "corner",
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
    trace: object = None,
) -> FillResult:
    """Fill a polygon with one of the slides' fill variants.

    Parameters
    ----------
    polygon : Polygon or array_like
        As `scan_convert`; one contour for `ColourWash` and `VertexColours`.
    width, height : int
        Raster size.
    fill : Solid, Pattern, ColourWash or VertexColours
        Default `Solid()` (white).
    background : RGB in [0, 1]
        The samples not filled.
    sample, rule, subpixel_bits
        As `scan_convert` (`rule` applies to solid and pattern fills only).
    trace : None, True or Tracer
        None runs the compiled kernels; a tracer, the traced references.

    Returns
    -------
    FillResult

    Raises
    ------
    TypeError
        If `fill` is not a fill variant.
    ValueError
        As `scan_convert`; or a colour outside [0, 1]; `VertexColours` whose
        count is not the vertex count; a wash or vertex colours on a polygon of
        several contours.
    scanviz.limits.ResourceLimitError
        If the image, its mask and the fill's buffers (25 bytes a pixel, 81
        for a pattern, 65 for a wash or vertex colours) would exceed the memory
        limit, refused before any is allocated.

    Examples
    --------
    The slides' checker on a 4 x 2 rectangle:

    >>> result = fill_polygon([(0, 0), (4, 0), (4, 2), (0, 2)], 4, 2, Pattern.checker())
    >>> result.image[..., 0].astype(int)[::-1].tolist()  # top row first
    [[1, 0, 1, 0], [0, 1, 0, 1]]
    """
    fill = Solid() if fill is None else fill
    if not isinstance(fill, FILLS):
        raise TypeError(
            f"'fill' must be a Solid, Pattern, ColourWash or VertexColours; got {short_repr(fill)}"
        )
    background = np.array(_colour("background", background))
    tracer = as_tracer(trace)
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    extra = {Solid: 0, Pattern: PATTERN_PIXEL_BYTES}.get(type(fill), WASH_PIXEL_BYTES)
    check_memory(
        (IMAGE_PIXEL_BYTES + extra) * width * height,
        f"fill_polygon: a {width}x{height} RGB image with its mask and {type(fill).__name__} fill",
    )
    if isinstance(fill, Solid | Pattern):
        scanned = scan_convert(
            polygon,
            width,
            height,
            sample=sample,
            rule=rule,
            subpixel_bits=subpixel_bits,
            trace=tracer,
        )
        mask = scanned.mask
        colours = _solid_or_pattern(fill, polygon, mask)
    else:
        mask, colours = _interpolated(fill, polygon, width, height, sample, subpixel_bits, tracer)
    image = np.where(mask[..., None], colours, background)
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return FillResult(image, mask, recorded)


def _solid_or_pattern(fill, polygon: Polygon, mask: np.ndarray) -> np.ndarray:
    height, width = mask.shape
    if isinstance(fill, Solid):
        return np.broadcast_to(np.array(fill.color), (height, width, 3))
    tile = fill.tile
    origin_x = origin_y = 0
    if fill.anchor == "polygon":  # the tile's origin at the pixel of the lower-left bounding corner
        x_min, y_min = polygon.vertices.min(axis=0)
        origin_x, origin_y = int(np.floor(x_min)), int(np.floor(y_min))
    ys, xs = np.mgrid[0:height, 0:width]
    return tile[(ys - origin_y) % tile.shape[0], (xs - origin_x) % tile.shape[1]]


def _interpolated(fill, polygon: Polygon, width, height, sample, bits, tracer):
    from ..visibility.zbuffer import ScreenPolygons, zbuffer  # visibility builds on raster

    if polygon.contour_count != 1:
        raise ValueError(
            f"a {type(fill).__name__} fill takes a polygon of one contour; got {polygon.contour_count}"
        )
    vertices = polygon.contours[0]
    if isinstance(fill, VertexColours):
        if len(fill.colors) != len(vertices):
            raise ValueError(
                f"'colors' must hold one colour per vertex: {len(vertices)}; got {len(fill.colors)}"
            )
        colours = fill.colors
    else:
        colours = fill.vertex_colours(vertices)
    flat = np.column_stack([vertices, np.zeros(len(vertices))])
    screen = ScreenPolygons.from_polygons([flat], [colours])
    z = zbuffer(screen, width, height, sample=sample, subpixel_bits=bits, trace=tracer)
    return z.polygon >= 0, z.values

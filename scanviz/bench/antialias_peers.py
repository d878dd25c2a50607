"""Other libraries' anti-aliasers, drawn into scanviz's coverage convention for `bench antialias`.

Each function draws one shape anti-aliased with full intensity into an 8-bit
single-channel image and returns it as a (height, width) float64 coverage in
[0, 1] with scanviz's convention: row 0 at the bottom, pixel (x, y) the unit
square [x, x+1] x [y, y+1] (DESIGN §2). The libraries are y-down, so a point
(x, y) is drawn at (x, height - y) and the rows are flipped back.

* skia-python: its pixel (i, j) is the square [i, i+1] x [j, j+1] (samples
  at +1/2, like ours), so the point goes in as (x, height - y). A line is a
  stroke of width 1 with butt caps; polygons and disks are anti-aliased fills.
* OpenCV: pixel (i, j) is centred on the integer point (i, j), and sub-pixel
  positions are integers with `shift` fractional bits, so the point goes in as
  round(((x - 1/2), (height - y - 1/2)) * 2**SHIFT). ``cv2.line`` with
  ``LINE_AA`` and thickness 1 draws its own Wu-style line (its ends are not
  flat caps); ``fillPoly`` and ``circle`` (thickness -1) with ``LINE_AA``
  fill with an anti-aliased border.
* cairo is not included: pycairo needs the system cairo library to build.

`PEERS` maps each installed library to its functions; a missing library is
absent, and the benchmark says "not available".
"""

from __future__ import annotations

import numpy as np

from ..antialias._inputs import check_point, check_radius, new_raster
from ..geometry import Polygon
from . import optional_module

SHIFT = 8  # OpenCV fractional bits, as scanviz snaps to 1/256 pixel
FULL = 255.0


def _skia_draw(width: int, height: int, draw) -> np.ndarray:
    """Run `draw(canvas)` on a zeroed A8 surface; the alpha as coverage, row 0 at the bottom."""
    skia = optional_module("skia")
    image = new_raster(width, height, "skia")
    if image.size == 0:
        return image
    surface = skia.Surface.MakeRaster(skia.ImageInfo.MakeA8(image.shape[1], image.shape[0]))
    draw(surface.getCanvas())
    alpha = surface.makeImageSnapshot().toarray(colorType=skia.kAlpha_8_ColorType)
    return alpha[::-1, :, 0] / FULL if alpha.ndim == 3 else alpha[::-1] / FULL


def skia_line(p0: object, p1: object, width: int, height: int) -> np.ndarray:
    """The 1-pixel-wide segment as a skia stroke (width 1, butt caps, anti-aliased).

    >>> skia_line((0, 1.5), (4, 1.5), 4, 3)[::-1]  # top row first
    array([[0., 0., 0., 0.],
           [1., 1., 1., 1.],
           [0., 0., 0., 0.]])
    """
    skia = optional_module("skia")
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    paint = skia.Paint(
        AntiAlias=True,
        Style=skia.Paint.kStroke_Style,
        StrokeWidth=1.0,
        StrokeCap=skia.Paint.kButt_Cap,
    )
    return _skia_draw(width, height, lambda c: c.drawLine(x0, height - y0, x1, height - y1, paint))


def skia_polygon(polygon: object, width: int, height: int) -> np.ndarray:
    """A polygon (nonzero winding) as a skia anti-aliased path fill."""
    skia = optional_module("skia")
    contours = Polygon(polygon).contours
    path = skia.Path()
    for contour in contours:
        path.addPoly([skia.Point(x, height - y) for x, y in contour.tolist()], True)
    path.setFillType(skia.PathFillType.kWinding)
    paint = skia.Paint(AntiAlias=True)
    return _skia_draw(width, height, lambda c: c.drawPath(path, paint))


def skia_disk(center: object, radius: float, width: int, height: int) -> np.ndarray:
    """A disk as skia's anti-aliased ``drawCircle`` fill."""
    skia = optional_module("skia")
    (cx, cy), radius = check_point("center", center), check_radius(radius)
    paint = skia.Paint(AntiAlias=True)
    return _skia_draw(width, height, lambda c: c.drawCircle(cx, height - cy, radius, paint))


def _cv2_point(x: float, y: float, height: int) -> tuple[int, int]:
    """scanviz (x, y) as OpenCV's fixed-point pixel-centred y-down point."""
    scale = 2.0**SHIFT
    return int(np.rint((x - 0.5) * scale)), int(np.rint((height - y - 0.5) * scale))


def _cv2_draw(width: int, height: int, draw) -> np.ndarray:
    image = new_raster(width, height, "opencv")
    if image.size == 0:
        return image
    canvas = np.zeros(image.shape, dtype=np.uint8)
    draw(canvas)
    return canvas[::-1] / FULL


def opencv_line(p0: object, p1: object, width: int, height: int) -> np.ndarray:
    """The segment as ``cv2.line(..., thickness=1, lineType=LINE_AA, shift=SHIFT)``.

    >>> opencv_line((0, 10.5), (20, 10.5), 20, 20).sum(axis=1).argmax()  # the row at y = 10.5
    np.int64(10)
    """
    cv2 = optional_module("cv2")
    (x0, y0), (x1, y1) = check_point("p0", p0), check_point("p1", p1)
    a, b = _cv2_point(x0, y0, height), _cv2_point(x1, y1, height)
    return _cv2_draw(width, height, lambda c: cv2.line(c, a, b, 255, 1, cv2.LINE_AA, SHIFT))


def opencv_polygon(polygon: object, width: int, height: int) -> np.ndarray:
    """A polygon as ``cv2.fillPoly(..., lineType=LINE_AA, shift=SHIFT)``."""
    cv2 = optional_module("cv2")
    contours = [
        np.array([_cv2_point(x, y, height) for x, y in c.tolist()], dtype=np.int32)
        for c in Polygon(polygon).contours
    ]
    return _cv2_draw(width, height, lambda c: cv2.fillPoly(c, contours, 255, cv2.LINE_AA, SHIFT))


def opencv_disk(center: object, radius: float, width: int, height: int) -> np.ndarray:
    """A disk as ``cv2.circle(..., thickness=-1, lineType=LINE_AA, shift=SHIFT)``."""
    cv2 = optional_module("cv2")
    (cx, cy), radius = check_point("center", center), check_radius(radius)
    middle, r = _cv2_point(cx, cy, height), int(np.rint(radius * 2.0**SHIFT))
    return _cv2_draw(width, height, lambda c: cv2.circle(c, middle, r, 255, -1, cv2.LINE_AA, SHIFT))


def _installed() -> dict[str, dict[str, object]]:
    peers = {}
    if optional_module("skia") is not None:
        peers["skia"] = {"line": skia_line, "edge": skia_polygon, "disk": skia_disk}
    if optional_module("cv2") is not None:
        peers["OpenCV LINE_AA"] = {"line": opencv_line, "edge": opencv_polygon, "disk": opencv_disk}
    return peers


PEERS = _installed()
"""{library: {"line" | "edge" | "disk": function}} for the installed libraries."""
LIBRARIES = ("skia", "OpenCV LINE_AA", "cairo")
"""Every library the benchmark knows; those missing from `PEERS` print as "not available"."""

"""Visibility: the z-buffer, and the classic algorithms behind one interface.

`solve(name, polygons, width, height)` runs any of `ALGORITHMS` on screen
polygons; `render(scene, w, h, visibility=name)` runs it in the pipeline.
The list-priority algorithms (painter's, depth sort, BSP) decide an order
of pieces to paint; the image-space ones (scanline, Warnock) the visible
polygon per sample; all paint with the z-buffer's scan conversion
(`scanviz.visibility.draw_decisions`), so where they decide as the z-buffer does,
the pixels are the z-buffer's to the bit.
"""

from .bsp import BSP, BspStats, BspTree, BspTreeNode
from .depth_sort import DepthSort, DepthSortStats
from .interface import ALGORITHMS, Decision, Visibility, VisibilityResult, ZBuffer, algorithm, solve
from .painter import Painter
from .scanline_visibility import Scanline, ScanlineStats
from .screen_polygons import PLANE_TOLERANCE, Cut, Piece, Surfaces
from .warnock import Quadtree, Warnock, WarnockStats
from .zbuffer import ScreenPolygons, ZBufferResult, ZBufferStats, zbuffer

__all__ = [
    "ALGORITHMS",
    "BSP",
    "BspStats",
    "BspTree",
    "BspTreeNode",
    "PLANE_TOLERANCE",
    "Quadtree",
    "Cut",
    "Decision",
    "DepthSort",
    "DepthSortStats",
    "Painter",
    "Piece",
    "Scanline",
    "ScanlineStats",
    "ScreenPolygons",
    "Surfaces",
    "Visibility",
    "VisibilityResult",
    "Warnock",
    "WarnockStats",
    "ZBuffer",
    "ZBufferResult",
    "ZBufferStats",
    "algorithm",
    "solve",
    "zbuffer",
]

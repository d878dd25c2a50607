"""Rasterization: ET/AET scan conversion, fill variants, edge functions, midpoint lines, compiled kernels."""

from .api import ScanResult, fill_polygons, rasterize_triangles, scan_convert
from .edgefn import TriangleSamples, triangle_samples
from .fill import ColourWash, FillResult, Pattern, Solid, VertexColours, fill_polygon
from .lines import midpoint_line, paint_lines

__all__ = [
    "ColourWash",
    "FillResult",
    "Pattern",
    "ScanResult",
    "Solid",
    "VertexColours",
    "fill_polygon",
    "TriangleSamples",
    "fill_polygons",
    "midpoint_line",
    "paint_lines",
    "rasterize_triangles",
    "scan_convert",
    "triangle_samples",
]

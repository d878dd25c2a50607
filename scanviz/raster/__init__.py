"""Rasterization: ET/AET scan conversion, edge functions, midpoint lines, compiled kernels."""

from .api import ScanResult, fill_polygons, rasterize_triangles, scan_convert
from .edgefn import TriangleSamples, triangle_samples
from .lines import midpoint_line, paint_lines

__all__ = [
    "ScanResult",
    "TriangleSamples",
    "fill_polygons",
    "midpoint_line",
    "paint_lines",
    "rasterize_triangles",
    "scan_convert",
    "triangle_samples",
]

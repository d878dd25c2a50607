"""scanviz: step through the classic polygon rendering pipeline, exactly and fast.

The conventions (y up, pixel = unit square, lower-left corner sampling, the
ownership rule for boundary samples) are in `scanviz.conventions`.
"""

from .abuffer import area_coverage
from .geometry import Polygon
from .io import load_scene
from .pipeline import RenderResult, render
from .progress import announce_compiling
from .raster import (
    ScanResult,
    TriangleSamples,
    fill_polygons,
    midpoint_line,
    rasterize_triangles,
    scan_convert,
    triangle_samples,
)
from .trace import Recorder, Trace, Tracer

announce_compiling()  # a one-line note, not silence, when a kernel compiles

__all__ = [
    "Polygon",
    "Recorder",
    "RenderResult",
    "ScanResult",
    "Trace",
    "Tracer",
    "TriangleSamples",
    "area_coverage",
    "fill_polygons",
    "load_scene",
    "midpoint_line",
    "rasterize_triangles",
    "render",
    "scan_convert",
    "triangle_samples",
]
__version__ = "0.1.0"

"""scanviz: step through the classic polygon rendering pipeline, exactly and fast.

See ``DESIGN`` conventions in `scanviz.conventions`.
"""

from .geometry import Polygon
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

__all__ = [
    "Polygon",
    "Recorder",
    "ScanResult",
    "Trace",
    "Tracer",
    "TriangleSamples",
    "fill_polygons",
    "midpoint_line",
    "rasterize_triangles",
    "scan_convert",
    "triangle_samples",
]
__version__ = "0.1.0"

"""scanviz: step through the classic polygon rendering pipeline, exactly and fast.

See ``DESIGN`` conventions in `scanviz.conventions`.
"""

from .geometry import Polygon
from .raster import ScanResult, scan_convert
from .trace import Recorder, Trace, Tracer

__all__ = ["Polygon", "Recorder", "ScanResult", "Trace", "Tracer", "scan_convert"]
__version__ = "0.1.0"

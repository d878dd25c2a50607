"""The pipeline: scene -> cull -> transform -> clip -> attributes -> visibility -> shade -> image.

`render` (`scanviz.pipeline.render`) runs it; `prepare` makes the screen
polygons; the a-buffer path, the shading of visible pixels and the feature
edges live in their own modules.
"""

from .antialiased import PROGRESS_POLYGONS
from .feature_lines import PROGRESS_EDGES
from .prepare import ATTRIBUTES, prepare
from .render import ANTIALIASED, RELIGHTABLE, SHADINGS, VISIBILITIES, render
from .result import PixelRecord, RenderPlan, RenderResult, RenderStats, Stage

__all__ = [
    "ANTIALIASED",
    "ATTRIBUTES",
    "PROGRESS_EDGES",
    "PROGRESS_POLYGONS",
    "RELIGHTABLE",
    "SHADINGS",
    "VISIBILITIES",
    "PixelRecord",
    "RenderPlan",
    "RenderResult",
    "RenderStats",
    "Stage",
    "prepare",
    "render",
]

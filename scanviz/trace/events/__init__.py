"""Trace events: small frozen records named after the algorithm step that emits them.

One module per stage of the pipeline holds that stage's events and the
records they carry; `base` holds `Record`, `Event` and the registry
`EVENT_TYPES` (every event class registers its ``kind`` there, so a trace
can be written to JSON and read back exactly, see `scanviz.trace.codec`).
A new algorithm adds its events beside the others of its stage.

Fields that filters understand: ``polygon`` (which input polygon), ``y``
(the scanline or pixel row), and an x-extent given by ``x`` or
``x_start``/``x_end``. Records check nothing when built; their types are
checked where data enters (`scanviz.trace.schema.validate`: the JSON
reader, the jail's wire decoder).

It imports nothing of scanviz but `scanviz.trace.display`: the grading
jail ships it, with `display` and `schema`, as its whole scanviz
(`scanviz.exercises.jail.launch`).
"""

# ruff: noqa: F401 -- the imports below are the re-exports; `__all__` lists them all

from .abuffer import (
    CoverageBlended,
    EdgeMask,
    EdgeMaskEntry,
    FragmentInserted,
    FragmentRecord,
    FragmentsDiscarded,
    FragmentsMerged,
    MaskBufferPixel,
    MaskBufferRow,
    MaskRun,
    PackStep,
    PixelPacked,
)
from .antialias import DislopColumn, PostColumn
from .base import EVENT_TYPES, Event, Record
from .interpolation import (
    DepthTest,
    EdgeValueEntry,
    EdgeValues,
    InterpolatedSpan,
    PolygonSetup,
    SpanValues,
)
from .lines import LineSetup, LineStep
from .scan import (
    AetEntry,
    AetSorted,
    EdgeRecord,
    EdgesActivated,
    EdgesRetired,
    EdgeTableBuilt,
    Span,
)
from .shading import FastPhongPixel, FastPhongSetup, Illumination, LightTerm, RationalForms
from .surfaces import (
    FacetsEnumerated,
    GridEdge,
    HorizonColumn,
    HorizonCurve,
    PerimeterEdge,
    PerimeterFacet,
    PerimeterUpdate,
)
from .triangles import EdgeFunction, EdgeFunctionRow, TriangleSetup
from .viewing import FaceCulled, PolygonClipped, PolygonsTransformed, VerticesTransformed
from .visibility import (
    ActiveSurfaces,
    AmbiguityTest,
    AreaClassified,
    BspCandidate,
    BspNode,
    BspVisited,
    Cut,
    PaintOrder,
    PairTested,
    PieceRecord,
    PiecesSwapped,
    PixelPainted,
    PolygonSplit,
    PolygonsSorted,
    SurfaceRecord,
    SurfaceTableBuilt,
    VisibleSpan,
)

# Every record and event class above, and the registry: what `scanviz.trace` re-exports.
__all__ = [
    "EVENT_TYPES",
    *sorted(
        name
        for name, value in dict(vars()).items()
        if isinstance(value, type) and issubclass(value, Record)
    ),
]

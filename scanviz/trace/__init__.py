"""Step traces: events, the Tracer protocol, a filtering Recorder, the Trace and its JSON."""

from .events import (
    EVENT_TYPES,
    AetEntry,
    AetSorted,
    EdgeFunctionRecord,
    EdgeFunctionRow,
    EdgeRecord,
    EdgesActivated,
    EdgesRetired,
    EdgeTableBuilt,
    Event,
    LineSetup,
    LineStep,
    Span,
    TriangleSetup,
)
from .recorder import Filter, Recorder, Trace, Tracer

__all__ = [
    "EVENT_TYPES",
    "AetEntry",
    "AetSorted",
    "EdgeFunctionRecord",
    "EdgeFunctionRow",
    "EdgeRecord",
    "EdgeTableBuilt",
    "EdgesActivated",
    "EdgesRetired",
    "Event",
    "Filter",
    "LineSetup",
    "LineStep",
    "Recorder",
    "Span",
    "Trace",
    "Tracer",
    "TriangleSetup",
]

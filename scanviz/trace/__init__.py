"""Step traces: events, the Tracer protocol, a filtering Recorder, the Trace and its JSON."""

from .events import (
    EVENT_TYPES,
    AetEntry,
    AetSorted,
    EdgeRecord,
    EdgesActivated,
    EdgesRetired,
    EdgeTableBuilt,
    Event,
    Span,
)
from .recorder import Filter, Recorder, Trace, Tracer

__all__ = [
    "EVENT_TYPES",
    "AetEntry",
    "AetSorted",
    "EdgeRecord",
    "EdgeTableBuilt",
    "EdgesActivated",
    "EdgesRetired",
    "Event",
    "Span",
    "Filter",
    "Recorder",
    "Trace",
    "Tracer",
]

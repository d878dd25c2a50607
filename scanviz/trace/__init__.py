"""Step traces: events, the Tracer protocol, a filtering Recorder, the Trace and its JSON."""

from . import events
from .events import *  # noqa: F403 -- every record and event class, as `events.__all__` lists them
from .recorder import Filter, Recorder, Trace, Tracer

__all__ = [*events.__all__, "Filter", "Recorder", "Trace", "Tracer"]

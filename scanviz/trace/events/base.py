"""The base of every trace record and event, and the registry of event kinds.

A record is a small frozen dataclass; an event is a record with a
class-level ``kind``, registered in `EVENT_TYPES` so that a trace can be
written to JSON and read back exactly (`scanviz.trace.codec`). Building a
record checks nothing: the reference loops build them in hot traced loops
from values they made. Types are checked where data enters instead
(`scanviz.trace.schema.validate`): the JSON reader and the jail's wire
decoder, which raise naming the field.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from ..display import RichDisplay  # tables in Jupyter, readable print

EVENT_TYPES: dict[str, type[Event]] = {}


class Record(RichDisplay):
    """Base of trace records and events: frozen dataclasses whose annotations are their schema.

    Jupyter shows a record as a table of its fields (`scanviz.trace.display`).
    """

    __slots__ = ()


@dataclass(frozen=True)
class Event(Record):
    """Base of all trace events; subclasses set ``kind`` and are registered by it."""

    kind: ClassVar[str] = "event"

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        if cls.kind in EVENT_TYPES:
            raise TypeError(f"event kind {cls.kind!r} is registered twice")
        EVENT_TYPES[cls.kind] = cls

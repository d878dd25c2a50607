"""The Tracer protocol, a filtering recorder, and the Trace it produces."""

from __future__ import annotations

import difflib
import operator
from collections.abc import Iterable, Iterator, Sequence
from typing import Protocol, runtime_checkable

import numpy as np

from ..conventions import check_raster_size
from ..limits import check_memory
from .codec import events_from_json, events_to_json
from .display import trace_html
from .events import EVENT_TYPES, Event
from .schema import shown


@runtime_checkable
class Tracer(Protocol):
    """What a traced algorithm talks to. ``trace=None`` means no tracer at all.

    `wants` lets the algorithm skip building an event nobody will keep;
    `emit` receives the events that are built.
    """

    def wants(self, kind: str, *, polygon: int | None = None, y: int | None = None) -> bool: ...

    def emit(self, event: Event) -> None: ...


def _int(name: str, value: object) -> int:
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an int; got {shown(value)}")
    try:
        return operator.index(value)  # type: ignore[arg-type]
    except TypeError:
        raise TypeError(f"{name} must be an int; got {shown(value)}") from None


def _ints(name: str, value: object, rule: str, length: int | None = None) -> tuple[int, ...] | None:
    """`value` as a tuple of ints (exactly `length` of them if given), or None if None."""
    if value is None:
        return None
    if isinstance(value, str | bytes) or not isinstance(value, Iterable):
        raise TypeError(f"{name!r} must be {rule}; got {shown(value)}")
    values = tuple(_int(f"{name!r}[{i}]", v) for i, v in enumerate(value))
    if length is not None and len(values) != length:
        raise ValueError(f"{name!r} must be {rule}; got {len(values)} values: {shown(value)}")
    return values


def _kinds(kinds: object) -> frozenset[str] | None:
    """`kinds` (None, one kind, or an iterable of kinds) as a set of known event kinds."""
    if kinds is None:
        return None
    if isinstance(kinds, str):
        kinds = [kinds]
    if not isinstance(kinds, Iterable):
        raise TypeError(
            f"'kinds' must be an event kind (str) or an iterable of them; got {shown(kinds)}"
        )
    kinds = list(kinds)
    for index, kind in enumerate(kinds):
        if not isinstance(kind, str):
            raise TypeError(f"'kinds'[{index}] must be a str; got {shown(kind)}")
    unknown = sorted(set(kinds) - EVENT_TYPES.keys())
    if unknown:
        close = [(k, difflib.get_close_matches(k, EVENT_TYPES, n=1)) for k in unknown]
        hint = ", ".join(f"{m[0]!r} for {k!r}" for k, m in close if m)
        raise ValueError(
            f"'kinds' has unknown event kinds {unknown}"
            + (f" (did you mean {hint}?)" if hint else "")
            + f"; known: {sorted(EVENT_TYPES)}"
        )
    return frozenset(kinds)


class Filter:
    """Which events to keep: by kind, polygon, row range and pixel region (half-open ranges)."""

    def __init__(
        self,
        kinds: Iterable[str] | None = None,
        *,
        rows: tuple[int, int] | None = None,
        polygons: Iterable[int] | None = None,
        region: tuple[int, int, int, int] | None = None,
    ) -> None:
        self.kinds = _kinds(kinds)
        self.rows = _ints("rows", rows, "a (start, stop) pair of ints", 2)
        polygons = _ints("polygons", polygons, "an iterable of polygon indices (ints)")
        self.polygons = None if polygons is None else frozenset(polygons)
        self.region = _ints("region", region, "(x_start, y_start, x_end, y_end), 4 ints", 4)

    def wants(self, kind: str, *, polygon: int | None = None, y: int | None = None) -> bool:
        if self.kinds is not None and kind not in self.kinds:
            return False
        if polygon is not None and self.polygons is not None and polygon not in self.polygons:
            return False
        if y is not None:
            for bounds in (self.rows, self.region and (self.region[1], self.region[3])):
                if bounds is not None and not bounds[0] <= y < bounds[1]:
                    return False
        return True

    def keeps(self, event: Event) -> bool:
        if not self.wants(
            event.kind, polygon=getattr(event, "polygon", None), y=getattr(event, "y", None)
        ):
            return False
        if self.region is None:
            return True
        if hasattr(event, "x_start"):
            return event.x_start < self.region[2] and event.x_end > self.region[0]
        x = getattr(event, "x", None)
        return not isinstance(x, int) or self.region[0] <= x < self.region[2]


class Recorder(Filter):
    """A tracer that records the events its filter keeps.

    Examples
    --------
    >>> from scanviz import Polygon, scan_convert
    >>> recorder = Recorder(kinds=["span"], rows=(2, 4))
    >>> _ = scan_convert(Polygon([(0, 0), (4, 0), (4, 4)]), 4, 4, trace=recorder)
    >>> [(e.y, e.x_start, e.x_end) for e in recorder.trace()]
    [(2, 2, 4), (3, 3, 4)]
    """

    def __init__(self, kinds: Iterable[str] | None = None, **filters: object) -> None:
        super().__init__(kinds, **filters)  # type: ignore[arg-type]
        self.events: list[Event] = []

    def emit(self, event: Event) -> None:
        if self.keeps(event):
            self.events.append(event)

    def trace(self) -> Trace:
        """The recorded events as an immutable `Trace`."""
        return Trace(self.events)


class Trace(Sequence[Event]):
    """An immutable sequence of events with step indexing, filtering and JSON."""

    def __init__(self, events: Iterable[Event] = ()) -> None:
        if not isinstance(events, Iterable):
            raise TypeError(f"'events' must be an iterable of Events; got {shown(events)}")
        self._events = tuple(events)
        for index, event in enumerate(self._events):
            if not isinstance(event, Event):
                raise TypeError(f"'events'[{index}] must be an Event; got {shown(event)}")

    def __getitem__(self, index):  # type: ignore[override]
        if isinstance(index, slice):
            return Trace(self._events[index])
        return self._events[index]

    def __len__(self) -> int:
        return len(self._events)

    def __iter__(self) -> Iterator[Event]:
        return iter(self._events)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Trace) and self._events == other._events

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        counts: dict[str, int] = {}
        for event in self._events:
            counts[event.kind] = counts.get(event.kind, 0) + 1
        return f"Trace({len(self)} events: {counts})"

    def _repr_html_(self) -> str:
        """Jupyter's view: the events per kind and the first few (`display.trace_html`)."""
        return trace_html(self)

    def of_kind(self, *kinds: str) -> Trace:
        return self.filter(kinds)

    def filter(self, kinds: Iterable[str] | None = None, **filters: object) -> Trace:
        """A new Trace of the events a `Filter(kinds, **filters)` keeps."""
        keep = Filter(kinds, **filters)  # type: ignore[arg-type]
        return Trace(e for e in self._events if keep.keeps(e))

    def image_at(self, step: int, width: int, height: int):
        """Coverage counts painted by the ``span`` events among the first `step` events.

        Returns a (height, width) ndarray of int32, row 0 at the bottom.
        """
        width, height = check_raster_size(width, height)
        step = _int("'step'", step)
        if step < 0:
            raise ValueError(f"'step' must be >= 0 (a count of events); got {step}")
        check_memory(4 * width * height, f"a {width}x{height} step image")
        image = np.zeros((height, width), dtype=np.int32)
        for event in self._events[:step]:
            if event.kind == "span" and 0 <= event.y < height:
                image[event.y, max(event.x_start, 0) : min(event.x_end, width)] += 1
        return image

    def to_json(self, **dumps_options: object) -> str:
        return events_to_json(self, **dumps_options)

    @classmethod
    def from_json(cls, text: str) -> Trace:
        """Read a trace from JSON text; malformed text raises a ValueError naming the JSON path.

        See `scanviz.trace.codec.events_from_json` and docs/trace-format.md.
        """
        return cls(events_from_json(text))

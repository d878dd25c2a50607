"""JSON form of a trace: ``{"events": [{"kind": ..., field: value, ...}, ...]}``.

Values map as: int, float, bool, str and None as themselves (floats keep every
bit: JSON numbers are written with `repr`); `fractions.Fraction` as the string
``"p/q"``; tuples as lists; nested records as objects. Reading uses each
event class's type hints, so ``Trace.from_json(t.to_json()) == t`` exactly.
"""

from __future__ import annotations

import dataclasses
import json
import types
import typing
from fractions import Fraction
from functools import cache

from .events import EVENT_TYPES, Event


def encode(value: object) -> object:
    """A JSON-ready form of an event, record, or field value."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: encode(getattr(value, f.name)) for f in dataclasses.fields(value)}
        return {"kind": value.kind, **fields} if isinstance(value, Event) else fields
    if isinstance(value, tuple | list):
        return [encode(v) for v in value]
    if isinstance(value, Fraction):
        return f"{value.numerator}/{value.denominator}"
    return value


@cache
def _hints(cls: type) -> dict[str, object]:
    return typing.get_type_hints(cls)


def decode(hint: object, data: object) -> object:
    """Rebuild a value of type `hint` from its JSON form."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        options = typing.get_args(hint)
        if data is None and type(None) in options:
            return None
        return decode(next(o for o in options if o is not type(None)), data)
    if origin is tuple:
        item = typing.get_args(hint)[0]
        return tuple(decode(item, v) for v in data)  # type: ignore[union-attr]
    if hint is Fraction:
        return Fraction(data)  # type: ignore[arg-type]
    if hint is float:
        return float(data)  # type: ignore[arg-type]
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        hints = _hints(hint)
        return hint(
            **{f.name: decode(hints[f.name], data[f.name]) for f in dataclasses.fields(hint)}
        )  # type: ignore[index]
    return data


def event_from_dict(data: dict) -> Event:
    kind = data.get("kind")
    if kind not in EVENT_TYPES:
        raise ValueError(f"unknown event kind {kind!r}; known: {sorted(EVENT_TYPES)}")
    return decode(EVENT_TYPES[kind], data)  # type: ignore[return-value]


def trace_to_json(trace: typing.Iterable[Event], **dumps_options: object) -> str:
    return json.dumps({"events": [encode(e) for e in trace]}, **dumps_options)  # type: ignore[arg-type]


def trace_from_json(text: str):
    from .recorder import Trace

    data = json.loads(text)
    if not isinstance(data, dict) or not isinstance(data.get("events"), list):
        raise ValueError("trace JSON must be an object with an 'events' list")
    return Trace(event_from_dict(e) for e in data["events"])

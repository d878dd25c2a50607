"""Plain JSON values for what crosses the sandbox boundary: case inputs, step outputs, results.

A student's answer runs in a separate process, and only data comes back --
never pickles, which would run code in the grader. `to_plain` turns the
values a step can return (numbers, exact fractions, tuples, named tuples,
dataclass records, numpy arrays, trace events) into JSON-able values, and
`from_plain` reads them back as Python values to compare and to show.
Anything else comes back as its (shortened) repr, which compares unequal to
every reference value.
"""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import numpy as np

from ..trace.codec import encode, event_from_dict
from ..trace.events import Event
from ..trace.schema import Invalid

REPR_LIMIT = 200  # characters of an unknown value's repr that are kept
ARRAY_KINDS = "biuf"  # the array dtypes that cross the boundary (others come back as repr)


@dataclasses.dataclass(frozen=True)
class Record:
    """A named record read back from plain form (a named tuple or dataclass of the step)."""

    type: str
    fields: dict

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Record) and self.fields == other.fields

    __hash__ = None  # type: ignore[assignment]


@dataclasses.dataclass(frozen=True)
class Opaque:
    """A value that has no plain form: kept only as its repr, equal to nothing but itself."""

    repr: str


def _number(value: float) -> object:
    return value if math.isfinite(value) else {"$float": repr(value)}


def to_plain(value: object, depth: int = 0) -> object:
    """`value` as JSON-able data (see the module docstring)."""
    if depth > 32:
        return {"$repr": "<nested too deeply>"}
    if value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, int | np.integer) and not isinstance(value, np.bool_):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, float | np.floating):
        return _number(float(value))
    if isinstance(value, Fraction):
        return {"$fraction": [value.numerator, value.denominator]}
    if isinstance(value, Event):
        return {"$event": encode(value)}
    if isinstance(value, Record):  # read back from plain form already: keep its own form
        return _record(value.type, value.fields, depth)
    if isinstance(value, Opaque):
        return {"$repr": value.repr}
    if isinstance(value, np.ndarray) and value.dtype.kind in ARRAY_KINDS:
        return {"$array": to_plain(value.tolist(), depth + 1), "dtype": str(value.dtype)}
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return _record(type(value).__name__, value._asdict(), depth)
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
        return _record(type(value).__name__, fields, depth)
    if isinstance(value, list | tuple):
        return [to_plain(item, depth + 1) for item in value]
    if isinstance(value, dict) and all(isinstance(k, str) for k in value):
        return {"$dict": {k: to_plain(v, depth + 1) for k, v in value.items()}}
    return {"$repr": _short_repr(value)}


def _record(name: str, fields: dict, depth: int) -> dict:
    return {"$record": name, "fields": {k: to_plain(v, depth + 1) for k, v in fields.items()}}


def _short_repr(value: object) -> str:
    try:
        text = repr(value)
    except Exception as error:  # a student's __repr__ may raise
        text = f"<unprintable {type(value).__name__}: {error!r}>"
    return text if len(text) <= REPR_LIMIT else text[: REPR_LIMIT - 3] + "..."


def from_plain(data: object) -> object:
    """The Python value of plain `data`; malformed data raises ValueError."""
    try:
        return _from_plain(data)
    except Invalid as error:
        raise ValueError(f"not a plain event: {error.rule}") from None
    except (TypeError, KeyError, AttributeError, ZeroDivisionError) as error:
        raise ValueError(f"not a plain value: {type(error).__name__}: {error}") from None


def _from_plain(data: object) -> object:
    if data is None or isinstance(data, bool | int | float | str):
        return data
    if isinstance(data, list):
        return [_from_plain(item) for item in data]
    if not isinstance(data, dict) or len(data) == 0:
        raise ValueError(f"not a plain value: {_short_repr(data)}")
    if "$fraction" in data:
        numerator, denominator = data["$fraction"]
        return Fraction(int(numerator), int(denominator))
    if "$float" in data:
        return float(data["$float"])
    if "$event" in data:
        return event_from_dict(data["$event"])
    if "$array" in data:
        dtype = np.dtype(str(data["dtype"]))
        if dtype.kind not in ARRAY_KINDS:
            raise ValueError(f"not a plain array: dtype {dtype} is not bool, int or float")
        return np.array(_from_plain(data["$array"]), dtype=dtype)
    if "$record" in data:
        return Record(
            str(data["$record"]), {str(k): _from_plain(v) for k, v in data["fields"].items()}
        )
    if "$dict" in data:
        return {str(k): _from_plain(v) for k, v in data["$dict"].items()}
    if "$repr" in data:
        return Opaque(str(data["$repr"]))
    raise ValueError(f"not a plain value: {_short_repr(data)}")

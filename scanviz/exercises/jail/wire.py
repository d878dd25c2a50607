"""Plain JSON values: the only form in which anything crosses the jail's boundary.

Both sides use this file: the grader (``scanviz.exercises.jail.wire``) and the
runner inside the jail (``wire``, next to ``runner.py``), so it imports
nothing of scanviz but the trace events and their schema, which the jail has
too. A value is:

- ``null``, ``true``, ``false``, an int, a finite float, a string;
- ``{"$f": "nan" | "inf" | "-inf"}``: a float that is not finite;
- ``{"$q": [numerator, denominator]}``: a `fractions.Fraction`;
- ``{"$t": [...]}``: a tuple; ``[...]`` or ``{"$l": [...]}``: a list;
- ``{"$d": [[key, value], ...]}``: a dict;
- ``{"$a": [element, ...], "dtype": "int64", "shape": [...]}``: a numpy array
  of bools, ints or floats; ``{"$s": value, "dtype": ...}`` a numpy scalar;
- ``{"$rec": "AetItem", "form": F, "fields": [[name, value], ...]}``: a
  record, F one of ``"dataclass"``, ``"frozen"`` (a frozen dataclass) and
  ``"namedtuple"``;
- ``{"$r": "..."}``: anything else, as its shortened repr (it equals nothing);
- ``{"$arg": k}`` (replies only): object ``k`` of the request.

In a request, every mutable object (list, dict, array, non-frozen dataclass)
carries ``"$id": k``, and a second occurrence of it is ``{"$ref": k}``. The
reply refers back to those objects with ``{"$arg": k}`` and sends the state
of each one the answer changed, so an answer that changes its arguments in
place (``e.x += e.dxdy``) changes the grader's objects, as a call in one
process would.

`Decoder` checks everything it reads: the grammar, and limits on size
(`MAX_NODES` values, `MAX_INT_BITS`, `MAX_TEXT`, `MAX_DEPTH`), so no reply
can make the grader work or allocate without bound. Records decode to the
class of the same name where the decoder knows one (the trace events and
records, and on the grader's side the classes it sent), else to a `Fields`
(a dataclass by another name) or a plain tuple (a named tuple). A trace
record is checked against its annotations as it is built
(`scanviz.trace.schema.validate`): records built in Python check nothing,
so this is where an answer's events and records are checked.
"""

from __future__ import annotations

import collections
import dataclasses
import math
from fractions import Fraction

from scanviz.trace import events
from scanviz.trace.schema import validate

MAX_NODES = 2_000_000  # values in one message
MAX_INT_BITS = 4096  # an int's (or a fraction's term's) size
MAX_TEXT = 100_000  # characters of one string
MAX_DEPTH = 64  # nesting of containers and records
REPR_LIMIT = 300  # characters kept of an unknown value's repr
ARRAY_KINDS = "biuf"  # numpy dtypes that cross: bool, int, unsigned, float
FORMS = ("dataclass", "frozen", "namedtuple")

TRACE_RECORDS: dict[str, type] = {
    name: value
    for name in events.__all__
    if isinstance(value := getattr(events, name), type) and dataclasses.is_dataclass(value)
}
"""Every trace event and record class, by name: both sides build these for real (and check them)."""


class WireError(ValueError):
    """A message that breaks the grammar or a limit (the text says which)."""


@dataclasses.dataclass(frozen=True)
class Opaque:
    """A value with no plain form, kept as its repr: it equals nothing but itself."""

    repr: str


class Fields:
    """A record of a class the decoder does not know: its name and its fields, read as attributes.

    Two compare equal when their fields do (the name is only shown).
    """

    def __init__(self, name: str, fields: dict) -> None:
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_fields", dict(fields))

    def __getattr__(self, name: str) -> object:
        if name.startswith("__") or name in ("_name", "_fields"):
            raise AttributeError(name)
        try:
            return self._fields[name]
        except KeyError:
            raise AttributeError(f"{self._name} has no field {name!r}") from None

    def __setattr__(self, name: str, value: object) -> None:
        self._fields[name] = value

    def __reduce__(self) -> tuple:
        return Fields, (self._name, self._fields)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Fields) and self._fields == other._fields

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self._fields.items())
        return f"{self._name}({inner})"


def record_fields(value: object) -> dict | None:
    """The fields of a record-like value (dataclass, named tuple, `Fields`) by name, else None."""
    if isinstance(value, Fields):
        return value._fields
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return value._asdict()
    return None


def record_name(value: object) -> str:
    return value._name if isinstance(value, Fields) else type(value).__name__


def _numpy():
    import numpy  # imported when an array first crosses: the jail starts faster without it

    return numpy


def _short_repr(value: object) -> str:
    try:
        text = repr(value)
    except Exception as error:  # a student's __repr__ may raise
        text = f"<unprintable {type(value).__name__}: {type(error).__name__}>"
    return text if len(text) <= REPR_LIMIT else text[: REPR_LIMIT - 3] + "..."


def _float(value: float) -> object:
    return value if math.isfinite(value) else {"$f": repr(value)}


# --- writing ----------------------------------------------------------------------------------


class Encoder:
    """Plain form of Python values.

    With ``identify``, mutable objects get ids (``$id``; `objects` maps each id
    to its object): what a request does. With ``arguments`` (``id(object) ->
    k``), those objects are written as ``{"$arg": k}``: what a reply does.
    """

    def __init__(self, *, identify: bool = False, arguments: dict[int, int] | None = None) -> None:
        self.identify = identify
        self.arguments = arguments or {}
        self.objects: dict[int, object] = {}
        self.classes: dict[str, type] = {}  # the record classes written, by name
        self._ids: dict[int, int] = {}

    def encode(self, value: object, depth: int = 0) -> object:
        if depth > MAX_DEPTH:
            return {"$r": "<nested too deeply>"}
        if value is None or isinstance(value, bool | str):
            return value
        if type(value) is int:
            return value
        if type(value) is float:
            return _float(value)
        if id(value) in self.arguments:
            return {"$arg": self.arguments[id(value)]}
        if self.identify and id(value) in self._ids:
            return {"$ref": self._ids[id(value)]}
        if isinstance(value, Fraction):
            return {"$q": [value.numerator, value.denominator]}
        if type(value).__module__ == "numpy":
            return self._numpy(value, depth + 1)
        if isinstance(value, int | float):  # other subclasses of int and float
            return int(value) if isinstance(value, int) else _float(float(value))
        return self._container(value, depth)

    def _identified(self, value: object, plain: dict) -> dict:
        if self.identify:
            k = len(self._ids)
            self._ids[id(value)] = k
            self.objects[k] = value
            plain["$id"] = k
        return plain

    def state(self, value: object, depth: int = 0) -> object:
        """The contents of a mutable object (its state), never the object itself as ``$arg``."""
        saved = self.arguments
        self.arguments = {k: v for k, v in saved.items() if k != id(value)}
        try:
            if type(value).__module__ == "numpy":
                return self._numpy(value, depth + 1)
            return self._container(value, depth)
        finally:
            self.arguments = saved

    def _container(self, value: object, depth: int) -> object:
        inner = depth + 1
        fields = record_fields(value)
        if isinstance(value, events.Event | events.Record) or fields is not None:
            return self._record(value, fields or {}, inner)
        if isinstance(value, list):
            if not self.identify:
                return [self.encode(item, inner) for item in value]
            plain = self._identified(value, {"$l": None})
            plain["$l"] = [self.encode(item, inner) for item in value]
            return plain
        if isinstance(value, tuple):
            return {"$t": [self.encode(item, inner) for item in value]}
        if isinstance(value, dict):
            plain = self._identified(value, {"$d": None})
            plain["$d"] = [[self.encode(k, inner), self.encode(v, inner)] for k, v in value.items()]
            return plain
        return {"$r": _short_repr(value)}

    def _record(self, value: object, fields: dict, depth: int) -> dict:
        if isinstance(value, tuple):
            form = "namedtuple"
        elif dataclasses.is_dataclass(value) and value.__dataclass_params__.frozen:
            form = "frozen"
        else:
            form = "dataclass"
        if not isinstance(value, Fields):
            self.classes[type(value).__name__] = type(value)
        plain = {"$rec": record_name(value), "form": form, "fields": None}
        if form == "dataclass":
            plain = self._identified(value, plain)
        plain["fields"] = [[name, self.encode(v, depth)] for name, v in fields.items()]
        return plain

    def _numpy(self, value: object, depth: int) -> object:
        numpy = _numpy()
        if isinstance(value, numpy.ndarray) and value.dtype.kind in ARRAY_KINDS:
            flat = value.ravel().tolist()
            if value.dtype.kind == "f" and not numpy.isfinite(value).all():
                flat = [_float(item) for item in flat]
            plain = {"$a": flat, "dtype": value.dtype.str, "shape": list(value.shape)}
            return self._identified(value, plain)
        if isinstance(value, numpy.generic) and value.dtype.kind in ARRAY_KINDS:
            return {"$s": self.encode(value.item(), depth), "dtype": value.dtype.str}
        return {"$r": _short_repr(value)}


def encode(value: object) -> object:
    """`value` in plain form (no ids, no references): for events, results and case inputs."""
    return Encoder().encode(value)


# --- reading ----------------------------------------------------------------------------------


class Decoder:
    """Python values from plain form, checked against the grammar and the limits.

    `classes` maps record names to the classes built for real (default: the
    trace records); `make_record(name, form, names)` gives the class of any
    other record (default: `Fields`, or a plain tuple for a named tuple).
    `arguments` maps the ids of a request's objects back to them (``$arg``).
    After reading a request, `objects` maps each id to the object made for it
    and `states` to its state as a reply would write it (to tell what changed).
    """

    def __init__(
        self,
        *,
        classes: dict[str, type] | None = None,
        make_record=None,
        arguments: dict[int, object] | None = None,
    ) -> None:
        self.classes = TRACE_RECORDS if classes is None else classes
        self.make_record = make_record
        self.arguments = arguments or {}
        self.objects: dict[int, object] = {}
        self.states: dict[int, object] = {}
        self.nodes = 0

    def decode(self, data: object) -> object:
        try:
            return self._decode(data, 0)[0]
        except WireError:
            raise
        except (
            TypeError,
            ValueError,
            KeyError,
            IndexError,
            AttributeError,
            ArithmeticError,
        ) as error:
            raise WireError(f"{type(error).__name__}: {error}") from None
        except RecursionError:
            raise WireError("nested too deeply") from None

    def _count(self, depth: int) -> None:
        self.nodes += 1
        if self.nodes > MAX_NODES:
            raise WireError(f"more than {MAX_NODES} values in one message")
        if depth > MAX_DEPTH:
            raise WireError(f"nested more than {MAX_DEPTH} levels")

    def _decode(self, data: object, depth: int) -> tuple[object, object]:
        """(the value, its state form: nested request objects as ``$arg`` references)."""
        self._count(depth)
        if data is None or isinstance(data, bool):
            return data, data
        if isinstance(data, int):
            _check_int(data)
            return data, data
        if isinstance(data, float):
            if not math.isfinite(data):
                raise WireError("a float that is not finite must be written {'$f': ...}")
            return data, data
        if isinstance(data, str):
            if len(data) > MAX_TEXT:
                raise WireError(f"a string longer than {MAX_TEXT} characters")
            return data, data
        if isinstance(data, list):
            return self._list(data, depth, None)
        if not isinstance(data, dict) or not data:
            raise WireError(f"not a plain value: {_short_repr(data)}")
        tag = next(iter(data))
        reader = _READERS.get(tag)
        if reader is None:
            raise WireError(f"unknown tag {_short_repr(tag)}")
        return reader(self, data, depth)

    def _items(self, data: object, depth: int) -> tuple[list, list]:
        if not isinstance(data, list):
            raise WireError(f"expected a list; got {_short_repr(data)}")
        pairs = [self._decode(item, depth + 1) for item in data]
        return [p[0] for p in pairs], [p[1] for p in pairs]

    def _keep(self, data: dict, value: object, state: object) -> tuple[object, object]:
        """Register a request's mutable object: its id now names `value`."""
        if "$id" not in data:
            return value, state
        k = data["$id"]
        if not isinstance(k, int) or isinstance(k, bool) or k in self.objects:
            raise WireError(f"bad object id {_short_repr(k)}")
        self.objects[k] = value
        self.states[k] = state
        return value, {"$arg": k}

    def _list(self, data: list, depth: int, source: dict | None) -> tuple[object, object]:
        value: list = []
        if source is not None:
            value, reference = self._keep(source, value, None)
        values, states = self._items(data, depth)
        value.extend(values)
        if source is not None and "$id" in source:
            self.states[source["$id"]] = states
            return value, reference
        return value, states

    def _tuple(self, data: dict, depth: int) -> tuple[object, object]:
        values, states = self._items(data["$t"], depth)
        return tuple(values), {"$t": states}

    def _fraction(self, data: dict, depth: int) -> tuple[object, object]:
        numerator, denominator = data["$q"]
        for term in (numerator, denominator):
            if not isinstance(term, int) or isinstance(term, bool):
                raise WireError("a fraction's terms must be ints")
            _check_int(term)
        value = Fraction(numerator, denominator)
        return value, {"$q": [value.numerator, value.denominator]}

    def _nonfinite(self, data: dict, depth: int) -> tuple[object, object]:
        if data["$f"] not in ("nan", "inf", "-inf"):
            raise WireError(f"'$f' must be 'nan', 'inf' or '-inf'; got {_short_repr(data['$f'])}")
        return float(data["$f"]), data

    def _dict(self, data: dict, depth: int) -> tuple[object, object]:
        value: dict = {}
        value, reference = self._keep(data, value, None)
        pairs = data["$d"]
        if not isinstance(pairs, list):
            raise WireError("'$d' must be a list of [key, value] pairs")
        states = []
        for pair in pairs:
            if not isinstance(pair, list) or len(pair) != 2:
                raise WireError("'$d' must be a list of [key, value] pairs")
            (key, key_state), (item, item_state) = (
                self._decode(pair[0], depth + 1),
                self._decode(pair[1], depth + 1),
            )
            value[key] = item  # an unhashable key raises TypeError: a WireError
            states.append([key_state, item_state])
        if "$id" in data:
            self.states[data["$id"]] = {"$d": states}
            return value, reference
        return value, {"$d": states}

    def _record(self, data: dict, depth: int) -> tuple[object, object]:
        name, form, fields = data["$rec"], data.get("form"), data.get("fields")
        if not isinstance(name, str) or not name.isidentifier() or len(name) > 100:
            raise WireError(f"a record's name must be an identifier; got {_short_repr(name)}")
        if form not in FORMS:
            raise WireError(f"a record's form must be one of {FORMS}; got {_short_repr(form)}")
        if not isinstance(fields, list) or not all(
            isinstance(f, list) and len(f) == 2 and isinstance(f[0], str) and f[0].isidentifier()
            for f in fields
        ):
            raise WireError(f"record {name}: 'fields' must be a list of [name, value] pairs")
        names = [f[0] for f in fields]
        if len(set(names)) != len(names):
            raise WireError(f"record {name}: a field is given twice")
        values, states = self._items([f[1] for f in fields], depth)
        state = {
            "$rec": name,
            "form": form,
            "fields": [list(p) for p in zip(names, states, strict=True)],
        }
        value = self._build(name, form, dict(zip(names, values, strict=True)))
        if form == "dataclass":
            kept, reference = self._keep(data, value, state)
            return kept, reference if "$id" in data else state
        return value, state

    def _build(self, name: str, form: str, fields: dict) -> object:
        cls = self.classes.get(name)
        if cls is None and self.make_record is not None:
            cls = self.make_record(name, form, tuple(fields))
        if cls is None:
            return tuple(fields.values()) if form == "namedtuple" else Fields(name, fields)
        try:
            if issubclass(cls, tuple):
                return cls(*fields.values())
            record = cls(**fields)
            if isinstance(record, events.Record):
                validate(record)  # where a trace record enters: it is checked here, not when built
            return record
        except Exception as error:  # a missing or unknown field, or a trace record's wrong type
            raise WireError(f"not a valid {name}: {error}") from None

    def _array(self, data: dict, depth: int) -> tuple[object, object]:
        numpy = _numpy()
        try:
            dtype = numpy.dtype(str(data["dtype"]))
        except TypeError:
            raise WireError(f"unknown dtype {_short_repr(data['dtype'])}") from None
        if dtype.kind not in ARRAY_KINDS:
            raise WireError(f"an array's dtype must be bool, int or float; got {dtype}")
        shape = data.get("shape")
        if not isinstance(shape, list) or not all(
            isinstance(n, int) and not isinstance(n, bool) and n >= 0 for n in shape
        ):
            raise WireError("an array's 'shape' must be a list of ints >= 0")
        flat = data["$a"]
        if not isinstance(flat, list):
            raise WireError("'$a' must be a list")
        if all(type(v) in _EXACT or (type(v) is float and math.isfinite(v)) for v in flat):
            self.nodes += len(flat)
            self._count(depth)
            values, states = flat, flat
        else:
            values, states = self._items(flat, depth)
        if math.prod(shape) != len(values):
            raise WireError(f"an array of shape {tuple(shape)} needs {math.prod(shape)} values")
        if not all(type(v) in (bool, int, float) for v in values):
            raise WireError("an array's values must be numbers")
        value = numpy.array(values, dtype=dtype).reshape(shape)
        state = {"$a": states, "dtype": dtype.str, "shape": shape}
        kept, reference = self._keep(data, value, state)
        return kept, reference if "$id" in data else state

    def _scalar(self, data: dict, depth: int) -> tuple[object, object]:
        numpy = _numpy()
        dtype = numpy.dtype(str(data["dtype"]))
        if dtype.kind not in ARRAY_KINDS:
            raise WireError(f"a scalar's dtype must be bool, int or float; got {dtype}")
        value, _ = self._decode(data["$s"], depth + 1)
        if type(value) not in (bool, int, float):
            raise WireError("a numpy scalar's value must be a number")
        return dtype.type(value), {"$s": value, "dtype": dtype.str}

    def _opaque(self, data: dict, depth: int) -> tuple[object, object]:
        text = data["$r"]
        if not isinstance(text, str) or len(text) > MAX_TEXT:
            raise WireError("'$r' must be a short string")
        return Opaque(text), data

    def _argument(self, data: dict, depth: int) -> tuple[object, object]:
        k = data["$arg"]
        if isinstance(k, bool) or k not in self.arguments:
            raise WireError(f"'$arg' names no object of the request: {_short_repr(k)}")
        return self.arguments[k], data

    def _reference(self, data: dict, depth: int) -> tuple[object, object]:
        k = data["$ref"]
        if isinstance(k, bool) or k not in self.objects:
            raise WireError(f"'$ref' names no earlier object: {_short_repr(k)}")
        return self.objects[k], {"$arg": k}

    def _wrapped_list(self, data: dict, depth: int) -> tuple[object, object]:
        if not isinstance(data["$l"], list):
            raise WireError("'$l' must be a list")
        return self._list(data["$l"], depth, data)


_EXACT = (bool, int)  # with finite floats, what an array's fast path takes as it is


def _check_int(value: int) -> None:
    if value.bit_length() > MAX_INT_BITS:
        raise WireError(f"an int of more than {MAX_INT_BITS} bits")


_READERS = {
    "$t": Decoder._tuple,
    "$l": Decoder._wrapped_list,
    "$q": Decoder._fraction,
    "$f": Decoder._nonfinite,
    "$d": Decoder._dict,
    "$rec": Decoder._record,
    "$a": Decoder._array,
    "$s": Decoder._scalar,
    "$r": Decoder._opaque,
    "$arg": Decoder._argument,
    "$ref": Decoder._reference,
}


def decode(data: object, classes: dict[str, type] | None = None) -> object:
    """The value of plain `data` (see `Decoder`); malformed data raises `WireError`."""
    return Decoder(classes=classes).decode(data)


def apply_state(target: object, state: object) -> None:
    """Make the mutable object `target` hold `state` (decoded: a list, dict, array or field dict).

    Raises WireError if the state does not fit the object (another shape,
    another record's fields).
    """
    if isinstance(target, list):
        if not isinstance(state, list):
            raise WireError(f"a list's state must be a list; got {_short_repr(state)}")
        target[:] = state
    elif isinstance(target, dict):
        if not isinstance(state, dict):
            raise WireError(f"a dict's state must be a dict; got {_short_repr(state)}")
        target.clear()
        target.update(state)
    elif type(target).__module__ == "numpy":
        numpy = _numpy()
        if not isinstance(state, numpy.ndarray) or state.shape != target.shape:
            raise WireError(f"an array of shape {target.shape} cannot take {_short_repr(state)}")
        target[...] = state
    else:
        fields = record_fields(state)
        names = [f.name for f in dataclasses.fields(target)]
        if fields is None or list(fields) != names:
            raise WireError(f"a {type(target).__name__}'s state must have the fields {names}")
        for name, value in fields.items():
            setattr(target, name, value)


_MADE: dict[tuple, type] = {}


def jail_record_class(name: str, form: str, names: tuple[str, ...]) -> type:
    """Inside the jail: a class for a record the jail has no module for (``AetItem``, ...).

    A mutable or frozen dataclass, or a named tuple, with the same name and
    fields, made once per shape.
    """
    key = (name, form, names)
    if key not in _MADE:
        if form == "namedtuple":
            _MADE[key] = collections.namedtuple(name, names)
        else:
            _MADE[key] = dataclasses.make_dataclass(name, names, frozen=form == "frozen")
    return _MADE[key]

"""Field types of trace records, read from their annotations: check Python values, decode JSON.

One small node per annotation form the events use: ``int``, ``float``,
``bool``, ``str``, ``Fraction``, ``X | None``, ``tuple[X, ...]``, fixed
``tuple[X, X, ...]`` and nested records. `validate` checks a record built in
Python, nested records included (its fast test is one type lookup per scalar
field); `Node.decode` rebuilds a value from its JSON form, checking it as it
goes. Both raise `Invalid`, which collects the path to the bad part on its
way out. Records check nothing when they are built: these are the checks of
the places where data enters (the JSON reader, `scanviz.trace.codec`; the
jail's wire decoder, `scanviz.exercises.jail.wire`).

Non-finite floats travel as the strings ``"inf"``, ``"-inf"`` and ``"nan"``
(strict JSON has no literal for them); exact fractions as ``"p/q"``.
"""

from __future__ import annotations

import dataclasses
import math
import re
import reprlib
import types
import typing
from fractions import Fraction

DIGITS = 4300  # most digits in a JSON number or a fraction's terms: Python's own limit for int(str)
_BEYOND_FLOAT = 2**1024 - 2**970  # ints from here on round to 2**1024: float() overflows
NON_FINITE = {"inf": math.inf, "-inf": -math.inf, "nan": math.nan}
_SHORT = reprlib.Repr()
_SHORT.maxstring = _SHORT.maxother = 60
_FRACTION = re.compile(rf"(-?\d{{1,{DIGITS}}})/(\d{{1,{DIGITS}}})")


class Invalid(Exception):
    """A value that breaks its field's rule; `where` holds the path parts, innermost first."""

    def __init__(self, rule: str) -> None:
        super().__init__(rule)
        self.rule = rule
        self.where: list[str] = []

    def at(self, part: str) -> Invalid:
        self.where.append(part)
        return self

    def path(self) -> str:
        return "".join(reversed(self.where))


def shown(value: object) -> str:
    """A short repr of a value and its type for an error message."""
    try:
        text = _SHORT.repr(value)
    except ValueError:  # an int beyond Python's digit limit for str()
        text = f"an int of {value.bit_length()} bits"  # type: ignore[attr-defined]
    return f"{text} ({type(value).__name__})"


class Node:
    """The type of one field.

    `fits` is the fast test (exact types, tested in C where possible); `check`
    the thorough one, which also accepts the rarer forms (an int for a float,
    subclasses) and raises `Invalid` saying what is wrong and where. `exact`
    is the set of types a scalar node accepts at a glance (None for the others).
    """

    expected = "?"
    exact: frozenset[type] | None = None
    depth = 0  # JSON nesting levels a value of this type needs

    def fits(self, value: object) -> bool:
        return type(value) in self.exact  # type: ignore[operator]

    def accepts(self, value: object) -> bool:
        return self.fits(value)

    def check(self, value: object) -> None:
        if not self.accepts(value):
            raise Invalid(f"must be {self.expected}; got {shown(value)}")

    def decode(self, data: object) -> object:
        self.check(data)
        return data


class Scalar(Node):
    """int, bool or str (a bool is not an int here)."""

    def __init__(self, kind: type) -> None:
        self.kind = kind
        self.expected = kind.__name__
        self.exact = frozenset({kind})

    def accepts(self, value: object) -> bool:
        return isinstance(value, self.kind) and (self.kind is bool or not isinstance(value, bool))


class Float(Node):
    """A float; an int within the float64 range is accepted too (it compares equal)."""

    expected = 'a float within +-1.8e308 (in JSON: a number, or "inf", "-inf", "nan")'
    exact = frozenset({float})

    def accepts(self, value: object) -> bool:
        if isinstance(value, float):
            return True
        return isinstance(value, int) and not isinstance(value, bool) and abs(value) < _BEYOND_FLOAT

    def decode(self, data: object) -> float:
        if isinstance(data, str) and data in NON_FINITE:
            return NON_FINITE[data]
        if isinstance(data, float) and math.isinf(data):  # a literal such as 1e400
            raise Invalid("must be within the float64 range (+-1.8e308); got a number beyond it")
        self.check(data)
        return float(data)  # type: ignore[arg-type]


class Exact(Node):
    """A `fractions.Fraction`; in JSON the string "p/q" (q > 0)."""

    expected = f'a Fraction (in JSON: the string "p/q", integers of at most {DIGITS} digits, q > 0)'
    exact = frozenset({Fraction})

    def accepts(self, value: object) -> bool:
        return isinstance(value, Fraction)

    def decode(self, data: object) -> Fraction:
        match = _FRACTION.fullmatch(data) if isinstance(data, str) else None
        if match is None:
            raise Invalid(f"must be {self.expected}; got {shown(data)}")
        if not match.group(2).strip("0"):
            raise Invalid(f'must be a Fraction "p/q" with q > 0; got {data!r}, a zero denominator')
        return Fraction(int(match.group(1)), int(match.group(2)))


class OrNone(Node):
    """X or None (JSON null)."""

    def __init__(self, inner: Node) -> None:
        self.inner = inner
        self.expected = f"{inner.expected} or None"
        self.exact = None if inner.exact is None else inner.exact | {type(None)}
        self.depth = inner.depth

    def fits(self, value: object) -> bool:
        return value is None or self.inner.fits(value)

    def check(self, value: object) -> None:
        if value is None:
            return
        if self.exact is None:  # a tuple or record: its own check says which part is wrong
            self.inner.check(value)
        elif not self.inner.accepts(value):
            raise Invalid(f"must be {self.expected}; got {shown(value)}")

    def decode(self, data: object) -> object:
        return None if data is None else self.inner.decode(data)


class Nested(Node):
    """A nested record (a dataclass); in JSON an object with exactly its fields."""

    def __init__(self, cls: type) -> None:
        self.cls = cls
        self.expected = cls.__name__
        self.fields = fields_of(cls)
        self.names = frozenset(name for name, _ in self.fields)
        self.depth = 1 + max((node.depth for _, node in self.fields), default=0)

    def fits(self, value: object) -> bool:
        return isinstance(value, self.cls) and fits_record(value)

    def check(self, value: object) -> None:
        if not isinstance(value, self.cls):
            raise Invalid(f"must be {self.expected}; got {shown(value)}")
        _check_fields(value)

    def decode(self, data: object, ignore: frozenset[str] = frozenset()) -> object:
        if not isinstance(data, dict):
            raise Invalid(f"must be an object ({self.expected}); got {shown(data)}")
        for key in data:
            if key not in self.names and key not in ignore:
                raise Invalid(
                    f"is not a field of {self.expected}; fields: {sorted(self.names)}"
                ).at(f".{key}")
        values = {}
        for name, node in self.fields:
            if name not in data:
                raise Invalid(f"is missing field {name!r} of {self.expected}")
            try:
                values[name] = node.decode(data[name])
            except Invalid as error:
                raise error.at(f".{name}") from None
        return self.cls(**values)


class TupleOf(Node):
    """tuple[X, ...] (any length) or tuple[X, X, ...] (that length); in JSON a list."""

    def __init__(self, item: Node, length: int | None) -> None:
        self.item, self.length = item, length
        self.depth = 1 + item.depth
        count = "" if length is None else f"{length} "
        self.expected = f"a tuple of {count}{item.expected}"

    def fits(self, value: object) -> bool:
        if type(value) is not tuple or (self.length is not None and len(value) != self.length):
            return False
        exact = self.item.exact
        if exact is not None:  # plain loops: faster than all(map(...)) on short tuples
            for item in value:
                if type(item) not in exact:
                    return False
            return True
        return all(map(self.item.fits, value))

    def _items(self, values: list | tuple) -> typing.Iterator[tuple[int, object]]:
        if self.length is not None and len(values) != self.length:
            raise Invalid(f"must have {self.length} items; got {len(values)}")
        return enumerate(values)

    def check(self, value: object) -> None:
        if not isinstance(value, tuple):
            raise Invalid(f"must be {self.expected}; got {shown(value)}")
        for index, item in self._items(value):
            try:
                self.item.check(item)
            except Invalid as error:
                raise error.at(f"[{index}]") from None

    def decode(self, data: object) -> tuple:
        if not isinstance(data, list):
            raise Invalid(f"must be a list ({self.expected}); got {shown(data)}")
        values = []
        for index, item in self._items(data):
            try:
                values.append(self.item.decode(item))
            except Invalid as error:
                raise error.at(f"[{index}]") from None
        return tuple(values)


_SCALARS: dict[object, Node] = {
    int: Scalar(int),
    bool: Scalar(bool),
    str: Scalar(str),
    float: Float(),
    Fraction: Exact(),
}
_FIELDS: dict[type, tuple[tuple[str, Node], ...]] = {}
_PLANS: dict[type, tuple] = {}


def node_of(hint: object) -> Node:
    """The node checking and decoding values annotated `hint`."""
    if hint in _SCALARS:
        return _SCALARS[hint]
    origin, args = typing.get_origin(hint), typing.get_args(hint)
    if origin in (typing.Union, types.UnionType) and len(args) == 2 and type(None) in args:
        return OrNone(node_of(next(a for a in args if a is not type(None))))
    if origin is tuple and args and len(set(args) - {Ellipsis}) == 1:
        return TupleOf(node_of(args[0]), None if args[-1] is Ellipsis else len(args))
    if isinstance(hint, type) and dataclasses.is_dataclass(hint):
        return Nested(hint)
    raise TypeError(f"trace records cannot hold fields annotated {hint!r}")


def fields_of(cls: type) -> tuple[tuple[str, Node], ...]:
    """(name, node) of each field of a record class, from its annotations (cached)."""
    fields = _FIELDS.get(cls)
    if fields is None:
        hints = typing.get_type_hints(cls)
        fields = tuple((f.name, node_of(hints[f.name])) for f in dataclasses.fields(cls))
        _FIELDS[cls] = fields
    return fields


def _plan(cls: type) -> tuple[tuple, tuple]:
    """The fast test of a record class: (name, exact types) per scalar field, (name, fits) per other."""
    fields = fields_of(cls)
    plan = _PLANS[cls] = (
        tuple((name, node.exact) for name, node in fields if node.exact is not None),
        tuple((name, node.fits) for name, node in fields if node.exact is None),
    )
    return plan


def fits_record(record: object) -> bool:
    """The fast test: every field has its exact type (False may still be valid: an int for a float)."""
    scalars, others = _PLANS.get(type(record)) or _plan(type(record))
    values = record.__dict__
    for name, exact in scalars:
        if type(values[name]) not in exact:
            return False
    for name, fits in others:
        if not fits(values[name]):
            return False
    return True


def validate(record: object) -> None:
    """Raise TypeError naming the field, the position inside it and the type expected.

    Nested records are checked too. A record passing the fast test is valid;
    one failing it is checked field by field (it may still be valid: an int
    where a float is due).

    Examples
    --------
    >>> from scanviz.trace.events import Span
    >>> validate(Span(polygon=0, y=1, x_start=2, x_end=5, winding=1))
    >>> validate(Span(polygon="x", y=1, x_start=2, x_end=5, winding=1))
    Traceback (most recent call last):
    ...
    TypeError: Span field 'polygon' must be int; got 'x' (str)
    """
    if fits_record(record):
        return
    try:
        _check_fields(record)
    except Invalid as error:
        field, inside = error.where[-1], "".join(reversed(error.where[:-1]))
        raise TypeError(
            f"{type(record).__name__} field {field[1:]!r}{inside} {error.rule}"
        ) from None


def _check_fields(record: object) -> None:
    """Raise `Invalid` at the first field that breaks its rule (the path starts at the field)."""
    for name, node in fields_of(type(record)):
        try:
            node.check(getattr(record, name))
        except Invalid as error:
            raise error.at(f".{name}") from None

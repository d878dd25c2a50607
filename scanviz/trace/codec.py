"""JSON form of a trace: ``{"version": 2, "events": [{"kind": ..., field: value, ...}, ...]}``.

Values map as: int, bool, str and None as themselves; finite floats as JSON
numbers with every bit kept (`repr`), non-finite ones as the strings
``"inf"``, ``"-inf"``, ``"nan"`` (the output is strict JSON); a
`fractions.Fraction` as the string ``"p/q"``; tuples as lists; nested
records as objects. Reading is driven by each event class's annotations
(`scanviz.trace.schema`), so ``Trace.from_json(t.to_json()) == t``
exactly, and malformed text raises a ValueError naming the JSON path and
the rule, before anything large is built: text over the file limit, or
nested deeper than `MAX_DEPTH`, or holding a number of more than `DIGITS`
digits, is refused unparsed. Reading is also where an event's field types
are checked (events built in Python check nothing).

`FORMAT_VERSION` is written; every version in `READABLE` is read, each to
today's event classes. Version 1 (before issue 24) had no ``"version"`` key,
and each edge of a ``triangle_setup`` carried its index ``"edge"``, which
today is its place in ``edges`` (`_from_version_1` drops it, checking it).
"""

from __future__ import annotations

import dataclasses
import difflib
import json
import math
import re
import typing
from fractions import Fraction

from ..limits import (
    FILE_ENV,
    JSON_STRING,
    ResourceLimitError,
    check_memory,
    current_file_limit,
    format_size,
    json_nesting,
)
from .events import EVENT_TYPES, Event
from .schema import DIGITS, Invalid, Nested, shown

FORMAT_VERSION = 2
"""The version `events_to_json` writes: 2 added the ``"version"`` key; its events carry the
stages' own records (a triangle's edges are `EdgeFunction`s, without an index)."""

READABLE = (1, 2)
"""The versions `events_from_json` reads; a file without ``"version"`` is version 1."""

_EVENT_NODES = {kind: Nested(cls) for kind, cls in EVENT_TYPES.items()}
MAX_DEPTH = 2 + max(node.depth for node in _EVENT_NODES.values())
"""Deepest nesting of arrays and objects a trace can need (the root object is level 1)."""

BYTES_PER_CHARACTER = 32
"""Peak memory of parsing, per character of JSON text (measured worst case: ``[{},{},...]``)."""

_KIND = frozenset({"kind"})
_NON_FINITE_TEXT = {math.inf: "inf", -math.inf: "-inf"}
_CONSTANTS = {"Infinity": "inf", "-Infinity": "-inf", "NaN": "nan"}  # non-standard literals
_LONG_NUMBER = re.compile(rf"(?<!\d)\d{{{DIGITS + 1}}}")  # starts only at a run: linear time
_TOKENS = re.compile(rf"{JSON_STRING}|[\[\]{{}},:]|{_LONG_NUMBER.pattern}", re.DOTALL)


def encode(value: object) -> object:
    """A JSON-ready form of an event, record, or field value (strict JSON: no NaN literals)."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = {f.name: encode(getattr(value, f.name)) for f in dataclasses.fields(value)}
        return {"kind": value.kind, **fields} if isinstance(value, Event) else fields
    if isinstance(value, tuple | list):
        return [encode(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return _NON_FINITE_TEXT.get(value, "nan")
    if isinstance(value, Fraction):
        return f"{value.numerator}/{value.denominator}"
    return value


def events_to_json(events: typing.Iterable[Event], **dumps_options: object) -> str:
    """The JSON text of a sequence of events; `dumps_options` go to `json.dumps`."""
    data = {"version": FORMAT_VERSION, "events": [encode(e) for e in events]}
    return json.dumps(data, **dumps_options)  # type: ignore[arg-type]


def _close_kind(kind: str) -> str:
    close = difflib.get_close_matches(kind, EVENT_TYPES, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _from_version_1(data: dict) -> dict:
    """A version-1 event object in today's shape: a triangle's edges lose their index ``edge``."""
    edges = data.get("edges")
    if data["kind"] != "triangle_setup" or not isinstance(edges, list):
        return data
    today = []
    for index, edge in enumerate(edges):
        if isinstance(edge, dict):
            if "edge" not in edge:
                raise Invalid("is missing field 'edge' (version 1)").at(f".edges[{index}]")
            if type(edge["edge"]) is not int or edge["edge"] != index:
                raise Invalid(
                    f"must be {index}, the edge's place in 'edges' (version 1); "
                    f"got {shown(edge['edge'])}"
                ).at(f".edges[{index}].edge")
            edge = {key: value for key, value in edge.items() if key != "edge"}
        today.append(edge)
    return {**data, "edges": today}


def event_from_dict(data: object, version: int = FORMAT_VERSION) -> Event:
    """The event of one decoded JSON object of format `version`; raises `schema.Invalid` with
    the path inside it."""
    if not isinstance(data, dict):
        raise Invalid(f"must be an event object with a 'kind'; got {shown(data)}")
    if "kind" not in data:
        raise Invalid("has no 'kind' naming its event type")
    kind = data["kind"]
    if not isinstance(kind, str):
        raise Invalid(f"must be a str naming an event kind; got {shown(kind)}").at(".kind")
    if kind not in EVENT_TYPES:
        raise Invalid(
            f"is an unknown event kind {kind!r}{_close_kind(kind)}; known: {sorted(EVENT_TYPES)}"
        ).at(".kind")
    if version == 1:
        data = _from_version_1(data)
    return _EVENT_NODES[kind].decode(data, ignore=_KIND)  # type: ignore[return-value]


def _first_problem(text: str) -> str | None:
    """The "path: rule" of the first container deeper than `MAX_DEPTH` or number over `DIGITS` digits.

    Iterative on purpose: a recursive parser is what deep text breaks.
    """
    stack: list[list] = []  # per open container: [is_object, current key or index]
    key = None
    for match in _TOKENS.finditer(text):
        token = match.group()
        if token in "[{":
            if len(stack) == MAX_DEPTH:
                return (
                    f"{_path(stack)}: nests deeper than {MAX_DEPTH} levels of arrays and "
                    "objects, the most a trace needs"
                )
            stack.append([token == "{", None if token == "{" else 0])
        elif token in "]}":
            if not stack:
                return None  # unbalanced: json.loads reports where
            stack.pop()
        elif token == ",":
            if stack and not stack[-1][0]:
                stack[-1][1] += 1
        elif token == ":":
            if stack and key is not None:
                stack[-1][1] = key
        elif token[0] == '"':
            key = token
        else:
            return f"{_path(stack)}: is a number of more than {DIGITS} digits"
    return None


def _key(token: str) -> str:
    try:
        return json.loads(token)
    except ValueError:  # a bad escape, or the string runs to the end of the text
        return token.strip('"')


def _path(stack: list[list]) -> str:
    parts = [
        (f".{_key(step)}" if step is not None else "") if is_object else f"[{step}]"
        for is_object, step in stack
    ]
    return "".join(parts).lstrip(".") or "the top level"


def check_structure(text: str) -> None:
    """Raise ValueError naming the path if `text` nests too deep or holds a too long number.

    The test runs at C speed on the text without its strings; only text that
    fails it is walked token by token to name the path.
    """
    depth, outside_strings = json_nesting(text)
    if depth > MAX_DEPTH or _LONG_NUMBER.search(outside_strings):
        problem = _first_problem(text)
        if problem is not None:
            raise ValueError(f"trace JSON at {problem}")


def check_size(text: str) -> None:
    """Refuse text larger than the file limit, or whose parse would pass the memory limit."""
    limit = current_file_limit()
    if len(text) > limit:
        raise ResourceLimitError(
            f"trace JSON of {len(text)} characters is larger than the file limit of "
            f"{format_size(limit)} (raise it with scanviz.limits.file_limit(...) or {FILE_ENV})"
        )
    check_memory(len(text) * BYTES_PER_CHARACTER, f"parsing {len(text)} characters of trace JSON")


def parse(text: object) -> object:
    """The JSON value of `text`, refused unparsed if too large, too deep or with too long numbers."""
    if not isinstance(text, str):
        raise TypeError(f"'text' must be a str of trace JSON; got {shown(text)}")
    check_size(text)
    check_structure(text)
    try:
        return json.loads(text.removeprefix("\ufeff"), parse_constant=_CONSTANTS.__getitem__)
    except ValueError as error:  # JSONDecodeError, or Python's limit on integer digits
        raise ValueError(f"trace JSON is not valid JSON: {error}") from None


def events_from_json(text: str) -> list[Event]:
    """The events of a trace's JSON text (`Trace.from_json`).

    Every outcome is the list of events or a ValueError naming the JSON path and the
    rule broken (TypeError if `text` is not a str).

    Examples
    --------
    >>> events_from_json('{"version": 2, "events": [{"kind": "span", "polygon": 0, "y": 1, "x_start": 2, "x_end": 5, "winding": 1}]}')
    [Span(polygon=0, y=1, x_start=2, x_end=5, winding=1)]
    >>> events_from_json('{"events": []}')  # version 1: no "version" key
    []
    >>> events_from_json('{"events": [{"kind": "span", "polygon": 0, "y": 1.5, "x_start": 2, "x_end": 5, "winding": 1}]}')
    Traceback (most recent call last):
    ...
    ValueError: trace JSON at events[0].y: must be int; got 1.5 (float)
    """
    data = parse(text)
    if not isinstance(data, dict) or not isinstance(data.get("events"), list):
        raise ValueError(
            f"trace JSON must be an object with an 'events' list; got {type(data).__name__}"
            + (f" with keys {sorted(data)[:10]}" if isinstance(data, dict) else "")
        )
    extra = sorted(data.keys() - {"version", "events"})
    if extra:
        raise ValueError(
            f"trace JSON has unknown top-level keys {extra}; only 'version' and 'events' are allowed"
        )
    version = data.get("version", 1)
    if type(version) is not int or version not in READABLE:
        raise ValueError(
            f"trace JSON at version: must be one of the versions this scanviz reads, {READABLE} "
            f"(a file without 'version' is version 1); got {shown(version)}"
        )
    events = []
    for index, item in enumerate(data["events"]):
        try:
            events.append(event_from_dict(item, version))
        except Invalid as error:
            raise ValueError(f"trace JSON at events[{index}]{error.path()}: {error.rule}") from None
    return events

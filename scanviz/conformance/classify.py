"""How the suite and the fuzz campaign judge an exception: a clear error, or anything else.

A **clear error** is a `ValueError` or `TypeError` (or an `OSError`, where the
entry point reads or writes files) whose message is one non-empty line of at
most 1,000 characters that names what was wrong. It names it when it holds
at least one of:

* a quoted name: ``'width'``, ``"kind"``;
* a JSON path or an indexed name: ``objects[2].material``, ``camera.near``, ``'polygons'[3]``;
* a command-line option: ``--width``;
* a subject at the start: ``ambient must be an array``;
* a word for a part of the input: contour, vertex, row, line, polygon,
  triangle, edge, event, camera, light, material, mesh, scene, file, ...

numpy's or Python's own words for an unchecked input (`INTERNAL_PHRASES`:
"could not convert", "setting an array element", ...) name nothing: only the
part of the message before them is judged, so ``'triangle' must be a (3, 2)
array of numbers: could not convert ...`` counts and ``could not convert
string to float: 'abc'`` does not. A message whose quoted names are all internal arrays (``'clip_points'``,
``'inv_w'``, ...) does not count: the user never passed those. A
`scanviz.limits.ResourceLimitError` always counts (it names the request, the
estimate and the limit). Every other
exception (AttributeError, KeyError, OverflowError, RecursionError,
ZeroDivisionError, MemoryError, ...) is "anything else".

>>> clear_error(ValueError("contour 0 vertex 2 is not finite: [nan, 0.0]"))
True
>>> clear_error(ValueError("need at least one array to concatenate"))
False
>>> clear_error(OverflowError("int too large to convert to float"))
False
>>> clear_error(ValueError("'inv_w'[45] = 1e-120 is not in [1e-100, 1e+100]"))
False
"""

from __future__ import annotations

import re

from ..limits import ResourceLimitError

PART_WORDS = (
    "contour", "vertex", "vertices", "row", "column", "line", "polygon", "triangle", "edge",
    "event", "events", "kind", "field", "scene", "camera", "light", "material", "mesh", "object",
    "face", "position", "normal", "file", "width", "height", "argument", "raster",
)  # fmt: skip
INTERNAL_NAMES = frozenset({"clip_points", "inv_w", "values", "xy", "z", "units", "breaks"})
_QUOTED = re.compile(r"'([^'\n]+)'|\"([^\"\n]+)\"")
_PATH = re.compile(r"\b[A-Za-z_]\w*(\[\d+\])+|\b[A-Za-z_]\w*\.[A-Za-z_]\w*|(^|\s)--[a-z][\w-]*")
_WORDS = re.compile(r"\b(" + "|".join(PART_WORDS) + r")s?\b", re.IGNORECASE)
_SUBJECT = re.compile(r"^[A-Za-z_][\w.\[\]-]* (must|is|has|needs)\b")  # "ambient must be ..."
INTERNAL_PHRASES = (
    "could not convert", "setting an array element", "only supports up to", "need at least one",
    "zero-size array", "invalid literal for", "exceeds the limit", "cannot fit", "object of type",
    "unsupported operand", "not subscriptable", "has no attribute",
)  # fmt: skip
MAX_MESSAGE = 1000


def names_something(message: str) -> bool:
    """Whether a message names the argument, field or part of the input it is about."""
    lowered = message.lower()
    found = [lowered.find(p) for p in INTERNAL_PHRASES if p in lowered]
    if found:  # numpy's or Python's own words: only what the library said before them counts
        message = message[: min(found)]
    if _SUBJECT.match(message):
        return True
    quoted = {a or b for a, b in _QUOTED.findall(message)}
    if quoted:
        return bool(quoted - INTERNAL_NAMES)  # about internal arrays only: not the user's input
    unquoted = _QUOTED.sub("", message)
    return bool(_PATH.search(unquoted) or _WORDS.search(unquoted))


def clear_error(error: BaseException, *, files: bool = False) -> bool:
    """Whether `error` is a clear error by the rule of this module (OSError too if `files`)."""
    if isinstance(error, ResourceLimitError):
        return True  # names what was asked for, the estimate and the limit, by construction
    kinds = (ValueError, TypeError, OSError) if files else (ValueError, TypeError)
    if not isinstance(error, kinds) or isinstance(error, RecursionError | MemoryError):
        return False
    message = str(error)
    if not message.strip() or "\n" in message.strip() or len(message) > MAX_MESSAGE:
        return False
    return names_something(message)


def short_repr(value: object, limit: int = 240) -> str:
    """A one-line repr of an input, long digit runs shortened, cut to `limit` characters.

    >>> short_repr(10**400)
    '<401 digits>'
    """
    text = re.sub(r"\d{30,}", lambda m: f"<{len(m.group())} digits>", repr(value))
    return text if len(text) <= limit else f"{text[: limit - 20]}...({len(text)} chars)"


def one_line(error: BaseException, limit: int = 200) -> str:
    """``Type: message`` on one line, cut to `limit` characters."""
    text = " ".join(str(error).split())
    if len(text) > limit:
        text = text[:limit] + "..."
    return f"{type(error).__name__}: {text}"

"""Comparing a student's run with the reference's, in the algorithm's own terms.

Values compare structurally: lists element by element (a tuple equals a list
with the same items), records and events field by field, arrays by shape and
elements. Integers and fractions compare exactly; floats compare exactly
unless the exercise declares a relative tolerance. A difference is reported
as a path into the value (``entries[2].x``), the student's value and the
reference's, with fractions written as the slides write them:
``17/5 (3 2/5 = 3.4)``.
"""

from __future__ import annotations

import math
from collections import defaultdict, deque
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from ..trace.events import Event, GridEdge
from .jail.wire import Opaque, record_fields, record_name


class _Missing:
    """A list item or field that one side lacks (one object, also after pickling)."""

    def __repr__(self) -> str:
        return "MISSING"

    def __reduce__(self) -> str:
        return "MISSING"


MISSING = _Missing()


@dataclass(frozen=True)
class Difference:
    """Where two values first differ: the path into them and both values there."""

    path: str
    yours: object
    reference: object

    def describe(self) -> str:
        """One line: ``entries[2].x: yours 17/5 (3.4), reference 37/10 (3.7)``.

        Coverage masks (fields named ``*mask*`` or ``region``) are shown in hex too.
        """
        where = f"{self.path}: " if self.path else ""
        if self.yours is MISSING:
            return f"{where}missing in yours; reference has {show(self.reference)}"
        if self.reference is MISSING:
            return f"{where}extra in yours ({show(self.yours)}); the reference has none"
        mine = self._show(self.yours)
        if isinstance(self.yours, float) and isinstance(self.reference, Fraction):
            mine += " (a float: the reference is exact)"
        elif (
            isinstance(self.yours, float)
            and isinstance(self.reference, int)
            and not isinstance(self.reference, bool)
        ):
            mine += " (a float: an int is asked for)"
        return f"{where}yours {mine}, reference {self._show(self.reference)}"

    def _show(self, value: object) -> str:
        field = self.path.rsplit(".", 1)[-1].split("[", 1)[0]
        if ("mask" in field or field == "region") and isinstance(value, int) and value >= 0:
            return f"{value} ({value:#x})"
        return show(value)


def first_places(places: Sequence[str], more: str = " ...", most: int = 12) -> str:
    """The first `most` of `places` joined with commas, then `more` if there are others.

    >>> first_places(["a", "b", "c"], most=2)
    'a, b ...'
    """
    return ", ".join(places[:most]) + (more if len(places) > most else "")


def show(value: object, limit: int = 160, *, nested: bool = False) -> str:
    """A value as a student reads it: exact fractions with their mixed form and decimal.

    Inside records and lists (`nested`) a fraction is just ``17/5``.
    """
    if isinstance(value, np.generic):
        value = value.item()  # np.True_ reads as True
    if isinstance(value, Fraction):
        if value.denominator == 1:
            return str(value.numerator)
        if nested:
            return str(value)
        whole = int(value)
        mixed = f"{whole} {abs(value - whole)} = " if whole else ""
        return f"{value} ({mixed}{float(value):.6g})"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, Opaque):
        return value.repr
    fields = _items(value)
    if isinstance(value, Event):
        inner = ", ".join(f"{k}={show(v, limit, nested=True)}" for k, v in fields.items())
        text = f"{value.kind}({inner})"
    elif fields is not None:
        name = record_name(value)
        inner = ", ".join(f"{k}={show(v, limit, nested=True)}" for k, v in fields.items())
        text = f"{name}({inner})"
    elif isinstance(value, list | tuple):
        text = "[" + ", ".join(show(v, limit, nested=True) for v in value) + "]"
    elif isinstance(value, np.ndarray):
        text = np.array2string(value, threshold=20, separator=", ")
    else:
        text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


_items = record_fields  # the named fields of a record-like value, else None


def _number(value: object) -> bool:
    """Numbers and truth values (`numbers_equal` keeps bools apart from ints)."""
    return isinstance(value, int | float | Fraction | np.integer | np.floating | np.bool_)


def numbers_equal(yours: object, reference: object, rtol: float) -> bool:
    """Exact equality, or within `rtol` (relative, with an absolute floor of `rtol`) for floats."""
    if isinstance(yours, bool | np.bool_) or isinstance(reference, bool | np.bool_):
        both = isinstance(yours, bool | np.bool_) and isinstance(reference, bool | np.bool_)
        return both and bool(yours) == bool(reference)
    if isinstance(reference, int | np.integer) and isinstance(yours, float | np.floating):
        return False  # an int is prescribed: 13.0 is not 13 (`Difference.describe` says so)
    if yours == reference:
        return True
    if isinstance(yours, float) and isinstance(reference, float) and math.isnan(yours):
        return math.isnan(reference)
    if rtol == 0 or not (isinstance(yours, float) or isinstance(reference, float)):
        return False
    a, b = float(yours), float(reference)
    return math.isfinite(a) and math.isfinite(b) and abs(a - b) <= rtol * max(1.0, abs(b))


def first_difference(
    yours: object, reference: object, rtol: float = 0.0, path: str = ""
) -> Difference | None:
    """The first place `yours` and `reference` differ, or None if they agree."""
    if _number(yours) and _number(reference):
        return None if numbers_equal(yours, reference, rtol) else Difference(path, yours, reference)
    if isinstance(yours, Event) and isinstance(reference, Event) and yours.kind != reference.kind:
        return Difference(f"{path}.kind" if path else "kind", yours.kind, reference.kind)
    named_yours, named_reference = _items(yours), _items(reference)
    if named_yours is not None and named_reference is not None:
        for name in named_reference:
            inner = f"{path}.{name}" if path else name
            difference = first_difference(
                named_yours.get(name, MISSING), named_reference[name], rtol, inner
            )
            if difference is not None:
                return difference
        return None
    if isinstance(yours, np.ndarray) or isinstance(reference, np.ndarray):
        return _array_difference(yours, reference, rtol, path)
    if _sequence(yours) and _sequence(reference):
        for index in range(max(len(yours), len(reference))):
            item_yours = yours[index] if index < len(yours) else MISSING
            item_reference = reference[index] if index < len(reference) else MISSING
            inner = f"{path}[{index}]{_edge_label(item_reference, index)}"
            difference = first_difference(item_yours, item_reference, rtol, inner)
            if difference is not None:
                return difference
        return None
    if isinstance(yours, dict) and isinstance(reference, dict):
        for key in sorted(set(yours) | set(reference)):
            difference = first_difference(
                yours.get(key, MISSING), reference.get(key, MISSING), rtol, f"{path}[{key!r}]"
            )
            if difference is not None:
                return difference
        return None
    if yours is MISSING or reference is MISSING or type(yours) is not type(reference):
        return Difference(path, yours, reference)
    return None if yours == reference else Difference(path, yours, reference)


def _edge_label(item: object, index: int) -> str:
    """`` (e3)`` for entry `index` of a table sorted otherwise than by edge (the AET), so
    paths read ``entries[0] (e3).x``; empty where the index is the edge or there is none."""
    fields = _items(item)
    edge = fields.get("edge") if fields else None
    named = isinstance(edge, int) and not isinstance(edge, bool) and edge != index
    return f" (e{edge})" if named else ""


def _sequence(value: object) -> bool:
    return isinstance(value, list | tuple) and not hasattr(value, "_fields")


def _array_difference(yours, reference, rtol: float, path: str) -> Difference | None:
    try:
        a, b = np.asarray(yours), np.asarray(reference)
    except (TypeError, ValueError):
        return Difference(path, yours, reference)
    if a.shape != b.shape:
        return Difference(f"{path} shape" if path else "shape", a.shape, b.shape)
    if a.dtype == object or b.dtype == object:
        return first_difference(a.tolist(), b.tolist(), rtol, path)
    if rtol == 0 or not (a.dtype.kind == "f" or b.dtype.kind == "f"):
        same = (a == b) | (np.isnan(a) & np.isnan(b)) if a.dtype.kind == "f" else a == b
    else:
        same = np.isclose(a, b, rtol=rtol, atol=rtol, equal_nan=True)
    if np.all(same):
        return None
    index = tuple(int(i) for i in np.argwhere(~same)[0])
    return Difference(f"{path}{list(index)}", a[index].item(), b[index].item())


def where(event: Event) -> str:
    """Where an event happened, in the algorithm's terms: ``row 5``, ``pixel (3, 2)``, ..."""
    parts = []
    polygon = getattr(event, "polygon", None)
    if isinstance(polygon, int) and polygon:
        parts.append(f"polygon {polygon}")
    x, y = getattr(event, "x", None), getattr(event, "y", None)
    if isinstance(x, int) and isinstance(y, int):
        parts.append(f"pixel ({x}, {y})")
    elif isinstance(y, int):
        parts.append(f"row {y}")
    step = getattr(event, "step", None)
    if isinstance(step, int):
        parts.append(f"step {step}")
    facet, edge = getattr(event, "facet", None), getattr(event, "edge", None)
    if isinstance(facet, int) and not isinstance(facet, bool):  # the floating perimeter's events
        on = f" edge {edge.kind}({edge.row}, {edge.column})" if isinstance(edge, GridEdge) else ""
        parts.append(f"facet {facet}{on}")
    return ", ".join(parts)


@dataclass(frozen=True)
class TraceDifference:
    """The first diverging event of two traces, and every diverging place after it."""

    index: int  # 0-based position of the first diverging event
    length: int  # events in the reference
    kind: str
    place: str
    difference: Difference
    matched: int  # events before it that agree
    later: tuple[str, ...]  # places of the later diverging events (rows, pixels), in order

    def describe(self) -> str:
        place = f", {self.place}" if self.place else ""
        lines = [
            f"first difference at event {self.index + 1} of {self.length} -- {self.kind}{place}",
            f"  {self.difference.describe()}",
            f"  events 1-{self.matched} matched"
            if self.matched
            else "  no event matched before it",
        ]
        if self.later:
            lines.append(
                f"  it also differs at: {first_places(self.later)} ({len(self.later)} places)"
            )
        return "\n".join(lines)


def _key(event: object) -> tuple[str, str]:
    return (getattr(event, "kind", "?"), where(event) if isinstance(event, Event) else "")


def aligned(yours: Sequence, reference: Sequence) -> Iterator[tuple[int, object, object]]:
    """(reference index, yours, reference) pairs of two traces, in linear time.

    Events are paired by kind and place (``span``, ``row 5``) walking both
    traces together. Where the next two differ, the walk skips ahead on the
    side whose skip is shorter to the next event of the other's key (an
    event only one side has is paired with MISSING, so one extra event does
    not make every later event differ); where neither key comes again, each
    is a step the other lacks. Each trace's positions per key are visited
    once, so the cost is linear in the two lengths.
    """
    keys_yours, keys_reference = [_key(e) for e in yours], [_key(e) for e in reference]
    ahead_yours, ahead_reference = _positions(keys_yours), _positions(keys_reference)
    i = j = 0
    while i < len(yours) and j < len(reference):
        if keys_yours[i] == keys_reference[j]:
            yield j, yours[i], reference[j]
            i, j = i + 1, j + 1
            continue
        next_in_yours = _next(ahead_yours[keys_reference[j]], i)
        next_in_reference = _next(ahead_reference[keys_yours[i]], j)
        if next_in_yours is None and next_in_reference is None:  # two steps the other lacks
            yield j, MISSING, reference[j]
            yield j + 1, yours[i], MISSING
            i, j = i + 1, j + 1
        elif next_in_reference is None or (
            next_in_yours is not None and next_in_yours - i <= next_in_reference - j
        ):
            yield from ((j, yours[k], MISSING) for k in range(i, next_in_yours))
            i = next_in_yours
        else:
            yield from ((k, MISSING, reference[k]) for k in range(j, next_in_reference))
            j = next_in_reference
    yield from ((len(reference), yours[k], MISSING) for k in range(i, len(yours)))
    yield from ((k, MISSING, reference[k]) for k in range(j, len(reference)))


def _positions(keys: list) -> defaultdict:
    positions: defaultdict = defaultdict(deque)
    for index, key in enumerate(keys):
        positions[key].append(index)
    return positions


def _next(positions: deque, start: int) -> int | None:
    """The first position >= `start` (earlier ones are dropped: the walk never goes back)."""
    while positions and positions[0] < start:
        positions.popleft()
    return positions[0] if positions else None


def traces_equal(yours: Sequence, reference: Sequence, rtol: float = 0.0) -> bool:
    """Whether two traces agree event by event (within `rtol` for floats)."""
    return len(yours) == len(reference) and all(
        a == b or first_difference(a, b, rtol) is None
        for a, b in zip(yours, reference, strict=True)
    )


def trace_difference(
    yours: Sequence[Event], reference: Sequence[Event], rtol: float = 0.0
) -> TraceDifference | None:
    """Compare two event sequences event by event; None if they agree. Linear in their lengths."""
    if len(yours) == len(reference) and all(a == b for a, b in zip(yours, reference, strict=True)):
        return None  # the common case, without aligning
    first = None
    later: dict[str, None] = {}  # places in order, each once
    for index, mine, theirs in aligned(yours, reference):
        difference = first_difference(mine, theirs, rtol)
        if difference is None:
            continue
        event = theirs if theirs is not MISSING else mine
        place = where(event) if isinstance(event, Event) else ""
        if first is None:
            first = (index, getattr(event, "kind", type(event).__name__), place, difference)
        elif place and place != first[2]:
            later.setdefault(place)
    if first is None:
        return None
    index, kind, place, difference = first
    return TraceDifference(index, len(reference), kind, place, difference, index, tuple(later))


@dataclass(frozen=True)
class RasterDifference:
    """Matched, missing and extra samples of a student's raster against the reference."""

    yours: np.ndarray  # (H, W) bool, row 0 at the bottom
    reference: np.ndarray

    @property
    def matched(self) -> int:
        return int(np.count_nonzero(self.yours & self.reference))

    @property
    def missing(self) -> int:
        return int(np.count_nonzero(self.reference & ~self.yours))

    @property
    def extra(self) -> int:
        return int(np.count_nonzero(self.yours & ~self.reference))

    def art(self, limit: int = 64) -> str:
        """Scotty3D's legend, y up: ``#`` matched, ``!`` extra, ``?`` missing, ``.`` empty."""
        rows, cols = self.reference.shape
        if rows > limit or cols > limit:
            return f"(a {cols}x{rows} raster: too large to print; see the image)"
        glyphs = np.full(self.reference.shape, ".", dtype="<U1")
        glyphs[self.yours & self.reference] = "#"
        glyphs[self.yours & ~self.reference] = "!"
        glyphs[self.reference & ~self.yours] = "?"
        return "\n".join("".join(row) for row in glyphs[::-1])

    def describe(self) -> str:
        return (
            f"samples: {self.matched} matched (#), {self.extra} extra (!), "
            f"{self.missing} missing (?)\n{self.art()}"
        )

    def image(self) -> np.ndarray:
        """An (H, W, 3) float image, row 0 at the top: grey matched, red extra, blue missing."""
        image = np.ones(self.reference.shape + (3,))
        image[self.yours & self.reference] = (0.55, 0.55, 0.55)
        image[self.yours & ~self.reference] = (0.85, 0.15, 0.15)
        image[self.reference & ~self.yours] = (0.15, 0.35, 0.9)
        return image[::-1]


def raster_difference(yours: object, reference: np.ndarray) -> RasterDifference | None:
    """The sample diff of two (H, W) bool rasters, or None if they agree.

    A student raster of the wrong shape or type counts as empty.
    """
    reference = np.asarray(reference, dtype=bool)
    try:
        mine = np.asarray(yours, dtype=bool)
    except (TypeError, ValueError):
        mine = np.zeros_like(reference)
    if mine.shape != reference.shape:
        mine = np.zeros_like(reference)
    if np.array_equal(mine, reference):
        return None
    return RasterDifference(mine, reference)

"""Screen-space polygons: one or more contours of (x, y) vertices, validated once.

A `Polygon` holds read-only float64 contours. Holes and self-intersecting
contours are allowed; which points are inside is decided later by a fill rule
(nonzero winding or even-odd).

`as_coordinates` is the one gate every raster entry point sends its
coordinates through (DESIGN §6): each coordinate must be a real number (a
Python or numpy int or float, or another `numbers.Real`; not a bool, str,
complex or other object), finite, and within +-2**20 pixels; a ragged input
is reported at the item whose length is wrong.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Iterator, Sequence

import numpy as np

from .conventions import COORD_LIMIT, short_repr

LIMIT_TEXT = f"+-2**20 = {COORD_LIMIT} pixels"
_NOT_FINITE, _BEYOND, _NOT_REAL = 1, 2, 3
_NUMERIC_KINDS = "iuf"  # integer, unsigned, float dtypes; bool, complex, str, object are not
_MAX_NESTING = 8  # deeper than any coordinate array (numpy iterates at most 32 dimensions)


def nested_array(value: object) -> np.ndarray | None:
    """`value` as an ndarray, Python objects kept as they are (so bools stay bools).

    An ndarray is returned as it is; anything else becomes an object array.
    None when the nesting is too ragged or too deep (numpy holds 32 dimensions) for numpy to hold,
    or when a list holds masked arrays (whose masks numpy would drop).
    """
    if isinstance(value, np.ndarray):
        return value
    if isinstance(value, (list, tuple)) and any(isinstance(v, np.ma.MaskedArray) for v in value):
        return None  # np.array would drop the masks; `plain_array` checks such items one by one
    if isinstance(value, (list, tuple)) and _numeric_arrays(value):
        try:
            return np.array(value)  # fast: numeric arrays keep their values exactly
        except ValueError:
            pass  # ragged: the object array below names the misfit
    try:
        array = np.array(value, dtype=object)
    except (ValueError, RuntimeError, RecursionError):
        return None
    return array if array.ndim <= _MAX_NESTING else None


def _numeric_arrays(items: list | tuple) -> bool:
    """True when every item is an ndarray of an int or float dtype (no bools to hide)."""
    return bool(items) and all(
        type(item) is np.ndarray and item.dtype.kind in _NUMERIC_KINDS for item in items
    )


def _is_sequence(value: object) -> bool:
    if isinstance(value, np.ndarray):
        return value.ndim > 0
    return isinstance(value, Sequence) and not isinstance(value, (str, bytes))


def _shape_text(shape: tuple[int | str, ...]) -> str:
    text = f"({', '.join(map(str, shape))})"
    return f"{'an' if shape[0] == 'N' else 'a'} {text} array"


def _label(name: str, index: tuple[int, ...]) -> str:
    """How messages name an item: the vertex of a contour, of a triangle, ..."""
    if not index:
        return name
    return name + "".join(f"[{i}]" for i in index[:-1]) + f" vertex {index[-1]}"


def _misfit(value: object, shape: tuple[int | str, ...], index: tuple[int, ...] = ()):
    """(index, problem) of the first item of nested `value` that does not fit `shape`, or None."""
    if not shape:
        return (
            (index[:-1], "holds a sequence where a number belongs") if _is_sequence(value) else None
        )
    if not _is_sequence(value):
        return index, "is not a sequence"
    if isinstance(shape[0], int) and len(value) != shape[0]:
        what = "coordinates; a vertex is (x, y)" if len(shape) == 1 else f"items; want {shape[0]}"
        return index, f"has {len(value)} {what}"
    for i, item in enumerate(value):
        found = _misfit(item, shape[1:], (*index, i))
        if found:
            return found
    return None


def _check_shape(raw, value, name: str, shape: tuple[int | str, ...]) -> np.ndarray:
    """`raw` if it has `shape` (a str is a free length); else a ValueError naming the misfit."""
    if raw is not None and raw.shape == (0,) and isinstance(shape[0], str):
        return raw.reshape(0, *(0 if isinstance(n, str) else n for n in shape[1:]))
    fits = raw is not None and raw.ndim == len(shape)
    if fits and all(isinstance(n, str) or n == m for n, m in zip(shape, raw.shape, strict=True)):
        return raw
    ragged = raw is None or (raw.dtype == object and any(map(_is_sequence, raw.flat)))
    found = _misfit(value, shape) if ragged else None
    if found:
        index, problem = found
        label = _label(name, index) if len(index) == len(shape) - 1 else _item_label(name, index)
        raise ValueError(f"{name} must be {_shape_text(shape)}; {label} {problem}")
    raise ValueError(f"{name} must be {_shape_text(shape)}; got shape {raw.shape}")


def _item_label(name: str, index: tuple[int, ...]) -> str:
    return name + "".join(f"[{i}]" for i in index) if index else name


def _fault(value: object) -> int:
    """0 for a valid coordinate, else why not: _NOT_REAL, _NOT_FINITE or _BEYOND."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        return _NOT_REAL
    if isinstance(value, numbers.Integral):
        return 0 if -COORD_LIMIT <= value <= COORD_LIMIT else _BEYOND  # exact, any size
    if math.isnan(value) or math.isinf(value):
        return _NOT_FINITE
    return 0 if -COORD_LIMIT <= value <= COORD_LIMIT else _BEYOND


_PLAIN_TYPES = (float, int, np.float64, np.float32, np.int64, np.int32)


def _plain_numbers(raw: np.ndarray) -> np.ndarray | None:
    """An object array of plain ints and floats as float64 (vectorized), or None for the rest.

    Exact types only, so bools (a subclass of int) take the element-wise path;
    ints beyond float64 (OverflowError) do too. An int that rounds to a
    float keeps its side of +-2**20, since ints near the limit are exact.
    """
    types = np.frompyfunc(type, 1, 1)(raw)
    if not np.isin(types, _PLAIN_TYPES).all():
        return None
    try:
        return raw.astype(np.float64)
    except OverflowError:
        return None


def _faults(raw: np.ndarray) -> np.ndarray:
    """Per-coordinate `_fault` codes of `raw` (vectorized for numeric dtypes)."""
    if raw.dtype.kind == "f":
        finite = np.isfinite(raw)
        beyond = np.abs(np.where(finite, raw, 0)) > COORD_LIMIT
        return np.where(~finite, _NOT_FINITE, np.where(beyond, _BEYOND, 0))
    if raw.dtype.kind in "iu":  # compared as integers: no abs() overflow at -2**63
        return np.where((raw < -COORD_LIMIT) | (raw > COORD_LIMIT), _BEYOND, 0)
    if raw.dtype == object:
        plain = _plain_numbers(raw)
        if plain is not None:
            return _faults(plain)
        codes = np.fromiter(map(_fault, raw.flat), dtype=np.int8, count=raw.size)
        return codes.reshape(raw.shape)
    return np.full(raw.shape, _NOT_REAL)


def _within_limit(raw: np.ndarray) -> bool:
    """True when numeric `raw` is all finite and within +-2**20: two reductions, no codes.

    A NaN makes min and max NaN, which compares False; ints compare exactly.
    """
    if raw.dtype.kind not in _NUMERIC_KINDS or not raw.size:
        return False
    return bool(raw.min() >= -COORD_LIMIT) and bool(raw.max() <= COORD_LIMIT)


_KIND_NAMES = {
    "b": "bool",
    "c": "complex",
    "m": "timedelta",
    "M": "datetime",
    "O": "Python objects",
    "S": "bytes",
    "U": "str",
    "V": "structured",
}
NOT_REAL_KINDS = "".join(_KIND_NAMES)
"""numpy dtype kinds that are not real numbers, for `plain_array`'s `refused`."""


def plain_array(value: object, name: str, refused: str = "") -> object:
    """`value` with ndarray subclasses undone, its rows too; a masked array only if none is masked.

    ``np.matrix`` and other subclasses become plain ndarrays (a matrix's
    indexing and ``*`` differ from an array's); a masked array becomes its
    data when nothing is masked, else a ValueError says to fill it first, so
    no masked value is read as a number. An ndarray whose dtype kind is in
    `refused` (numpy's kind letters) raises a TypeError naming `name` and the
    dtype. The items of a list or tuple (rows, contours) are checked the same
    way; anything else is returned as it is.

    >>> plain_array(np.ma.masked_array([1.0, 2.0], mask=[0, 1]), "'points'")
    Traceback (most recent call last):
    ...
    ValueError: 'points' is a masked array with 1 masked value; fill the masked values first (np.ma.filled(array, value)) or leave them out
    """
    if isinstance(value, np.ma.MaskedArray):
        masked = int(np.ma.count_masked(value))
        if masked:
            raise ValueError(
                f"{name} is a masked array with {masked} masked value{'s' * (masked > 1)}; "
                "fill the masked values first (np.ma.filled(array, value)) or leave them out"
            )
        value = np.ma.getdata(value)
    if isinstance(value, np.ndarray):
        value = np.asarray(value)  # a plain ndarray, sharing the data
        if value.dtype.kind in refused:
            raise TypeError(
                f"{name} must hold real numbers (int or float); got dtype {value.dtype} "
                f"({_KIND_NAMES[value.dtype.kind]})"
            )
        return value
    if isinstance(value, (list, tuple)) and any(isinstance(item, np.ndarray) for item in value):
        return [plain_array(item, f"{name}[{i}]", refused) for i, item in enumerate(value)]
    return value


def as_coordinates(value: object, name: str, shape: tuple[int | str, ...]) -> np.ndarray:
    """`value` as a new float64 array of `shape` whose every coordinate is valid (DESIGN §6).

    Parameters
    ----------
    value : array_like
        Nested sequences or an array; its last axis holds (x, y).
    name : str
        How messages name `value`: ``"contour 0"``, ``"'triangles'"``.
    shape : tuple of int or str
        The shape wanted, a str for a free length: ``("N", 2)``, ``("T", 3, 2)``.
        An empty sequence is taken as zero items when the first length is free.

    Returns
    -------
    ndarray of float64
        A writable copy.

    Raises
    ------
    TypeError
        If a coordinate is not a real number (bool, str, complex, None, an
        object, or an array of such a dtype); the message names the vertex.
    ValueError
        If `value` does not have `shape` (a ragged input names the first item
        of the wrong length), or a coordinate is not finite or lies beyond
        +-2**20 pixels (any Python int is compared exactly).

    Examples
    --------
    >>> as_coordinates([(0, 1), (2.5, 3)], "'points'", ("N", 2)).tolist()
    [[0.0, 1.0], [2.5, 3.0]]
    >>> as_coordinates([(0, 0), (1, 0, 5)], "contour 0", ("N", 2))
    Traceback (most recent call last):
    ...
    ValueError: contour 0 must be an (N, 2) array; contour 0 vertex 1 has 3 coordinates; a vertex is (x, y)
    >>> as_coordinates([(0, 0), (10**400, 0)], "contour 0", ("N", 2))
    Traceback (most recent call last):
    ...
    ValueError: contour 0 vertex 1 = [<an int of 1329 bits>, 0] is beyond the coordinate limit of +-2**20 = 1048576 pixels
    """
    value = plain_array(value, name)
    raw = _check_shape(nested_array(value), value, name, shape)
    if raw.dtype.kind not in _NUMERIC_KINDS + "O":
        raise TypeError(
            f"{name} must be {_shape_text(shape)} of numbers (real: int or float); "
            f"got dtype {raw.dtype}"
        )
    if _within_limit(raw):
        return raw.astype(np.float64)
    codes = _faults(raw)
    bad = np.flatnonzero(codes)
    if bad.size:
        *vertex, _ = index = np.unravel_index(bad[0], raw.shape)
        vertex = tuple(int(i) for i in vertex)
        label, shown = _label(name, vertex), ", ".join(map(short_repr, raw[vertex].tolist()))
        code = codes[index]
        if code == _NOT_REAL:
            culprit = raw[index]
            raise TypeError(
                f"{name} must be {_shape_text(shape)} of numbers (real: int or float; not bool, "
                f"str, complex or None): {label} holds {short_repr(culprit)} of type "
                f"{type(culprit).__name__}"
            )
        if code == _NOT_FINITE:
            raise ValueError(f"{label} is not finite: [{shown}]")
        raise ValueError(f"{label} = [{shown}] is beyond the coordinate limit of {LIMIT_TEXT}")
    return raw.astype(np.float64)


def _contour_parts(contours: object) -> list:
    """The contours of `contours`: one (N, 2) contour, or a sequence of them."""
    if isinstance(contours, np.ndarray):
        if contours.ndim == 2:
            return [contours]
        if contours.ndim == 3:
            return list(contours)
        raise ValueError(
            f"'contours' must be an (N, 2) array or a list of them; got shape {contours.shape}"
        )
    if isinstance(contours, (str, bytes)) or not isinstance(contours, Iterable):
        raise TypeError(
            f"'contours' must be an (N, 2) array or a list of them; got {contours!r:.60}"
        )
    parts = list(contours)
    # A vertex (a sequence of numbers) first means one contour; a sequence of sequences, several.
    is_vertex = parts and not (_is_sequence(parts[0]) and any(map(_is_sequence, parts[0])))
    return [parts] if is_vertex else parts


def check_three_distinct(vertices: np.ndarray, label: str) -> None:
    """Raise a ValueError, naming `label`, unless (N, 2) `vertices` hold 3 distinct points."""
    distinct = len(np.unique(vertices, axis=0))
    if distinct < 3:
        raise ValueError(f"{label} has {distinct} distinct vertices; a contour needs at least 3")


def _as_contour(points: object, index: int) -> np.ndarray:
    array = as_coordinates(points, f"contour {index}", ("N", 2))
    check_three_distinct(array, f"contour {index}")
    array.setflags(write=False)
    return array


class Polygon:
    """A screen-space polygon made of one or more closed contours.

    Parameters
    ----------
    contours : (N, 2) array_like, or sequence of (N_i, 2) array_like
        One contour, or a list of contours (holes and self-intersections are
        allowed). Each contour is closed implicitly: its last vertex joins its
        first. Coordinates are pixels, y up, within +-2**20.

    Raises
    ------
    ValueError
        If a contour has the wrong shape (a ragged one names the vertex of the
        wrong length), a non-finite coordinate, a coordinate beyond +-2**20
        (Python ints of any size are compared exactly), or fewer than 3
        distinct vertices.
    TypeError
        If a coordinate is not a real number: bools, strings, complex numbers
        and other objects are refused, never converted.

    Examples
    --------
    >>> square_with_hole = Polygon([[(0, 0), (4, 0), (4, 4), (0, 4)],
    ...                             [(1, 1), (1, 3), (3, 3), (3, 1)]])
    >>> square_with_hole.contour_count, square_with_hole.vertex_count
    (2, 8)
    >>> Polygon([(0, 0), (1, 1)])
    Traceback (most recent call last):
    ...
    ValueError: contour 0 has 2 distinct vertices; a contour needs at least 3
    """

    __slots__ = ("_contours",)

    def __init__(self, contours: object) -> None:
        if isinstance(contours, Polygon):
            self._contours = contours._contours
            return
        parts = _contour_parts(contours)
        if not parts:
            raise ValueError("'contours' must hold at least one contour")
        self._contours = tuple(_as_contour(part, i) for i, part in enumerate(parts))

    @property
    def contours(self) -> tuple[np.ndarray, ...]:
        """The contours, each a read-only (N, 2) ndarray of float64."""
        return self._contours

    @property
    def contour_count(self) -> int:
        return len(self._contours)

    @property
    def vertex_count(self) -> int:
        return sum(len(c) for c in self._contours)

    @property
    def vertices(self) -> np.ndarray:
        """All vertices, contour after contour: (M, 2) ndarray of float64."""
        return np.concatenate(self._contours)

    @property
    def offsets(self) -> np.ndarray:
        """Start of each contour in `vertices`, plus the total: (C + 1,) ndarray of int64."""
        return np.concatenate([[0], np.cumsum([len(c) for c in self._contours])]).astype(np.int64)

    def edges(self) -> Iterator[tuple[int, int, np.ndarray, np.ndarray]]:
        """Yield (contour, index, start, end) for every edge, closing each contour."""
        for c, contour in enumerate(self._contours):
            for i in range(len(contour)):
                yield c, i, contour[i], contour[(i + 1) % len(contour)]

    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) of all vertices."""
        v = self.vertices
        return (*v.min(axis=0).tolist(), *v.max(axis=0).tolist())

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Polygon):
            return NotImplemented
        return len(self._contours) == len(other._contours) and all(
            np.array_equal(a, b) for a, b in zip(self._contours, other._contours, strict=True)
        )

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        inner = ", ".join(repr(c.tolist()) for c in self._contours)
        return f"Polygon([{inner}])"

"""Screen-space polygons: one or more contours of (x, y) vertices, validated once.

A `Polygon` holds read-only float64 contours. Holes and self-intersecting
contours are allowed; which points are inside is decided later by a fill rule
(nonzero winding or even-odd).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from .conventions import COORD_LIMIT


def _as_contour(points: object, index: int) -> np.ndarray:
    try:
        array = np.array(points, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise TypeError(f"contour {index} must be an (N, 2) array of numbers: {error}") from None
    if array.ndim != 2 or array.shape[1] != 2:
        raise ValueError(f"contour {index} must be an (N, 2) array; got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array).all(axis=1))
    if bad.size:
        raise ValueError(f"contour {index} vertex {bad[0]} is not finite: {array[bad[0]].tolist()}")
    far = np.flatnonzero((np.abs(array) > COORD_LIMIT).any(axis=1))
    if far.size:
        raise ValueError(
            f"contour {index} vertex {far[0]} = {array[far[0]].tolist()} is beyond the "
            f"coordinate limit of +-{COORD_LIMIT} pixels"
        )
    distinct = len(np.unique(array, axis=0))
    if distinct < 3:
        raise ValueError(
            f"contour {index} has {distinct} distinct vertices; a contour needs at least 3"
        )
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
        If a contour has the wrong shape, a non-finite coordinate, a
        coordinate beyond the limit, or fewer than 3 distinct vertices.

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
        try:
            array = np.asarray(contours, dtype=np.float64)
        except (TypeError, ValueError):
            array = None  # ragged: a list of contours of different lengths
        if array is not None and array.ndim == 2:
            parts = [contours]
        elif array is not None and array.ndim not in (1, 3):
            raise ValueError(
                f"'contours' must be an (N, 2) array or a list of them; got shape {array.shape}"
            )
        else:
            parts = list(contours)  # type: ignore[call-overload]
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

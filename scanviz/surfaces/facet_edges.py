"""Which edges each facet processes in the Floating Perimeter Algorithm (Step V).

Wang (1989, §2.3, Step V): every edge of the grid must be processed once, and
only once; facet 1 processes all four of its edges, and in viewing case 1 a
facet of class 2-5 processes three and one of class 6-9 two (Fig. 2-3, whose
glyphs the OCR lost). The rule that gives those counts in case 1 and stays
right in cases 2-9, reconstructed in spec §1.6.4: **a facet processes an edge
unless the facet across that edge exists and has a smaller number.** Why it
is the right rule, and the class table it reproduces, are in
``docs/surfaces-fpa-edges.md``.

Edges
-----
An edge is named by its direction and the grid point it starts from, in
index space (indices as in `scanviz.surfaces.enumeration`):

``("h", row, column)``
    along x, from grid point (column, row) to (column + 1, row);
    row in 0..Ny-1, column in 0..Nx-2.
``("v", row, column)``
    along y, from grid point (column, row) to (column, row + 1);
    row in 0..Ny-2, column in 0..Nx-1.

Facet (row, column) has sides T = ("h", row + 1, column), B = ("h", row,
column), L = ("v", row, column) and R = ("v", row, column + 1); it lists the
edges it processes in the order T, B, L, R, the column order of the spec's
class table. The grid has Nx(Ny-1) + Ny(Nx-1) edges (spec §1.1).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .enumeration import Enumeration

SIDES = "TBLR"
KINDS = "hv"  # edge kind code 0 is "h" (along x), 1 is "v" (along y)


@dataclass(frozen=True)
class FacetEdges:
    """The edges each facet processes, in processing order (Step V).

    Attributes
    ----------
    edges : (E, 3) ndarray of int64, read-only
        Every edge of the grid once, in processing order, as (kind, row,
        column) with kind 0 for "h" and 1 for "v".
    facet : (E,) ndarray of int64, read-only
        The number 1..F of the facet that processes each edge.
    taken : (F, 4) ndarray of bool, read-only
        ``taken[n - 1]`` marks the sides T, B, L, R facet number n processes.
    per_facet : tuple of tuples of (str, int, int)
        ``per_facet[n - 1]`` holds the edges facet number n processes, each
        ``("h" | "v", row, column)``, in the order T, B, L, R (built on first use).
    sides : tuple of str
        ``sides[n - 1]`` names the sides facet n processes, e.g. ``"TLR"`` (built on first use).
    """

    edges: np.ndarray
    facet: np.ndarray
    taken: np.ndarray

    @cached_property
    def per_facet(self) -> tuple[tuple[tuple[str, int, int], ...], ...]:
        counts = self.taken.sum(axis=1)
        return tuple(
            tuple((KINDS[kind], int(row), int(column)) for kind, row, column in block.tolist())
            for block in np.split(self.edges, np.cumsum(counts)[:-1])
        )

    @cached_property
    def sides(self) -> tuple[str, ...]:
        return tuple("".join(SIDES[i] for i in np.flatnonzero(facet)) for facet in self.taken)


def _check_enumeration(enumeration: object) -> Enumeration:
    if not isinstance(enumeration, Enumeration):
        raise TypeError(
            "'enumeration' must be a scanviz.surfaces.Enumeration (from enumerate_facets); "
            f"got {type(enumeration).__name__}"
        )
    order, sequence = np.asarray(enumeration.order), np.asarray(enumeration.sequence)
    if order.ndim != 2 or order.size == 0 or not np.issubdtype(order.dtype, np.integer):
        raise ValueError(
            "'enumeration.order' must be a non-empty 2-D integer array; "
            f"got shape {order.shape} of {order.dtype}"
        )
    count = order.size
    if not np.array_equal(np.sort(order, axis=None), np.arange(1, count + 1)):
        raise ValueError(f"'enumeration.order' must number the facets 1..{count}, each once")
    rows, columns = np.indices(order.shape)
    expected = np.empty((count, 2), dtype=np.int64)
    expected[order.ravel() - 1] = np.stack([rows.ravel(), columns.ravel()], axis=1)
    if not np.array_equal(sequence, expected):
        raise ValueError(
            "'enumeration.sequence' must list (row, column) of facets 1..F in the order "
            "'enumeration.order' gives"
        )
    return enumeration


def processed_sides(order: np.ndarray) -> np.ndarray:
    """Whether each facet processes its T, B, L and R edge, by the neighbour rule.

    Parameters
    ----------
    order : (Ny - 1, Nx - 1) ndarray of int64
        Facet numbers 1..F, indexed [row, column] (`Enumeration.order`).

    Returns
    -------
    (Ny - 1, Nx - 1, 4) ndarray of bool
        ``[row, column, side]`` for sides T, B, L, R.

    Examples
    --------
    >>> processed_sides(np.array([[1, 2]])).astype(int)  # one row: facet 2 skips its L edge
    array([[[1, 1, 1, 1],
            [1, 1, 0, 1]]])
    """
    # A missing neighbour counts as later: no other facet has that edge, so this one must take it.
    padded = np.pad(order, 1, constant_values=order.size + 1)
    across = (padded[2:, 1:-1], padded[:-2, 1:-1], padded[1:-1, :-2], padded[1:-1, 2:])
    return np.stack([neighbour > order for neighbour in across], axis=-1)


def side_edges(rows: int, columns: int) -> np.ndarray:
    """The edge (kind, row, column) on each side T, B, L, R of every facet.

    Returns
    -------
    (rows, columns, 4, 3) ndarray of int64

    Examples
    --------
    >>> side_edges(1, 1)[0, 0].tolist()  # T, B, L, R of the only facet
    [[0, 1, 0], [0, 0, 0], [1, 0, 0], [1, 0, 1]]
    """
    row, column = np.indices((rows, columns))
    horizontal, vertical = np.zeros_like(row), np.ones_like(row)
    sides = [
        (horizontal, row + 1, column),
        (horizontal, row, column),
        (vertical, row, column),
        (vertical, row, column + 1),
    ]
    return np.stack([np.stack(side, axis=-1) for side in sides], axis=-2)


def _read_only(array: np.ndarray) -> np.ndarray:
    array.flags.writeable = False
    return array


def facet_edges(enumeration: Enumeration) -> FacetEdges:
    """The edges each facet processes, facet by facet in processing order (Step V).

    A facet processes an edge unless the facet across it exists and has a
    smaller number, so every edge is processed exactly once, by the first of
    its (one or two) facets to be processed.

    Parameters
    ----------
    enumeration : Enumeration
        From `enumerate_facets`: its `order` and `sequence` are used.

    Returns
    -------
    FacetEdges

    Raises
    ------
    TypeError
        If `enumeration` is not an Enumeration.
    ValueError
        If its `order` is not a 2-D array numbering the facets 1..F once each,
        or its `sequence` disagrees with `order`.

    Examples
    --------
    A 2 x 2-facet grid seen from beyond its upper-right corner (case 9):

    >>> from scanviz.surfaces import View, enumerate_facets
    >>> grid = enumerate_facets([0, 1, 2], [0, 1, 2], View((3, 3, 2), (-1, -1, -1)))
    >>> grid.order[::-1]  # top row first
    array([[3, 1],
           [4, 2]])
    >>> edges = facet_edges(grid)
    >>> edges.sides
    ('TBLR', 'BLR', 'TBL', 'BL')
    >>> edges.per_facet[1]  # facet 2, the lower right: its T edge is facet 1's
    (('h', 0, 1), ('v', 0, 1), ('v', 0, 2))
    >>> edges.edges.shape, edges.facet.tolist()
    ((12, 3), [1, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4])
    """
    enumeration = _check_enumeration(enumeration)
    order, sequence = np.asarray(enumeration.order), np.asarray(enumeration.sequence)
    rows, columns = sequence[:, 0], sequence[:, 1]
    taken = processed_sides(order)[rows, columns]  # (F, 4), facets in processing order
    edges = side_edges(*order.shape)[rows, columns][taken]
    counts = taken.sum(axis=1)
    return FacetEdges(
        edges=_read_only(edges.astype(np.int64)),
        facet=_read_only(np.repeat(np.arange(1, order.size + 1, dtype=np.int64), counts)),
        taken=_read_only(taken),
    )

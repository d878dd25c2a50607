"""The nine viewing cases and the facet enumeration of the Floating Perimeter Algorithm.

Steps II-IV of Wang (1989, §2.3): the viewing case is the region of the XY
plane that holds the viewpoint; facets are numbered by the XY nearness of
their grid element to the viewpoint (z is ignored) and each gets a region
class 1-9 relative to the viewpoint's cell. The rule, reconstructed so that it
reproduces all nine grids of the dissertation's Fig. 2-2 (spec §1.6.2-1.6.3),
and why it is a valid front-to-back order are in
``docs/surfaces-fpa-enumeration.md``.

Indices
-------
A grid has Nx x-planes ``x`` and Ny y-planes ``y``; facet (row, column) is the
grid element ``[x[column], x[column+1]] x [y[row], y[row+1]]``, rows counted
upward in y. Facet arrays have shape (Ny - 1, Nx - 1) and are indexed
``[row, column]`` with row 0 at the bottom, like scanviz images.

Viewing cases and region classes (dc = column - vp column, dr = row - vp row)::

    case  viewpoint (x, y)          classes      class  dc    dr
    1     inside    inside          1..9         1      0     0
    2     inside    below ymin      2, 6, 8      2      0     > 0
    3     inside    above ymax      3, 7, 9      3      0     < 0
    4     left      inside          4, 6, 7      4      > 0   0
    5     right     inside          5, 8, 9      5      < 0   0
    6     left      below           6            6      > 0   > 0
    7     left      above           7            7      > 0   < 0
    8     right     below           8            8      < 0   > 0
    9     right     above           9            9      < 0   < 0
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from .view import View

# Case of each (x side, y side) of the viewpoint: -1 below the domain, 0 inside, +1 above.
_CASES = {
    (0, 0): 1,
    (0, -1): 2,
    (0, 1): 3,
    (-1, 0): 4,
    (1, 0): 5,
    (-1, -1): 6,
    (-1, 1): 7,
    (1, -1): 8,
    (1, 1): 9,
}
# Region class of each (sign dc, sign dr), as in the module table.
_CLASSES = np.array([[9, 5, 8], [3, 1, 2], [7, 4, 6]])  # [sign dc + 1, sign dr + 1]


def _check_view(view: object) -> View:
    if not isinstance(view, View):
        raise TypeError(f"'view' must be a scanviz.surfaces.View; got {type(view).__name__}")
    return view


def _check_domain(domain: object) -> tuple[float, float, float, float]:
    try:
        values = tuple(float(v) for v in domain)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise TypeError(
            f"'domain' must be 4 numbers (xmin, xmax, ymin, ymax); got {domain!r}"
        ) from None
    if len(values) != 4 or not all(math.isfinite(v) for v in values):
        raise ValueError(
            f"'domain' must be 4 finite numbers (xmin, xmax, ymin, ymax); got {domain!r}"
        )
    xmin, xmax, ymin, ymax = values
    if not (xmin < xmax and ymin < ymax):
        raise ValueError(f"'domain' must have xmin < xmax and ymin < ymax; got {values}")
    return values


def _check_planes(name: str, planes: object) -> np.ndarray:
    try:
        planes = np.asarray(planes, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name!r} must be a 1-D array of numbers") from None
    if planes.ndim != 1 or planes.size < 2:
        raise ValueError(
            f"{name!r} must be a 1-D array of at least 2 planes; got shape {planes.shape}"
        )
    if not np.isfinite(planes).all():
        raise ValueError(
            f"{name!r} must be finite; entry {np.flatnonzero(~np.isfinite(planes))[0]} is not"
        )
    steps = np.flatnonzero(~(np.diff(planes) > 0))
    if steps.size:
        i = steps[0]
        raise ValueError(
            f"{name!r} must be strictly increasing; entries {i} and {i + 1} are "
            f"{planes[i]} and {planes[i + 1]}"
        )
    return planes


def _side(low: float, high: float, position: float, direction: float, parallel: bool) -> int:
    """-1, 0 or +1: the viewpoint is below, inside (ties included) or above [low, high]."""
    if parallel:  # the viewpoint is at infinity along -direction
        return int(np.sign(-direction))
    return -1 if position < low else (1 if position > high else 0)


def viewing_case(domain: object, view: View) -> int:
    """The viewing case 1-9: the region of the XY plane holding the viewpoint (Step II).

    Parameters
    ----------
    domain : (xmin, xmax, ymin, ymax) floats
        The grid's rectangle, xmin < xmax and ymin < ymax.
    view : View
        Perspective: the viewpoint's x and y decide; a viewpoint on a limit
        line counts as inside. Parallel: the viewpoint is at infinity along
        -direction, so the signs of -dx and -dy decide and a zero component
        counts as inside.

    Returns
    -------
    int
        1 (face-on), 2-5 (edge-on) or 6-9 (corner-on), as in the module table.

    Raises
    ------
    TypeError, ValueError
        If `domain` is not 4 finite numbers with xmin < xmax and ymin < ymax,
        or `view` is not a View.

    Examples
    --------
    The setup of the dissertation's Tables 2-2 and 2-3:

    >>> viewing_case((-2, 2, -2, 2), View(point=(6, 8, 3), direction=(-6, -8, -3)))
    9
    >>> viewing_case((-2, 2, -2, 2), View((0, 0, 9), (1, 0, -1), projection="parallel"))
    4
    """
    xmin, xmax, ymin, ymax = _check_domain(domain)
    view = _check_view(view)
    parallel = view.projection == "parallel"
    (px, py, _), (dx, dy, _) = view.point, view.direction
    sides = (_side(xmin, xmax, px, dx, parallel), _side(ymin, ymax, py, dy, parallel))
    return _CASES[sides]


def _axis_cell(planes: np.ndarray, position: float, direction: float, parallel: bool) -> int:
    """The cell index along one axis: -1 or len(planes) - 1 outside, ties to the upper cell."""
    cells = planes.size - 1
    if parallel and direction != 0.0:
        return -1 if direction > 0.0 else cells
    if parallel:  # no lateral occlusion: any cell serves, so take the one nearest the point
        position = min(max(position, planes[0]), planes[-1])
    if position < planes[0]:
        return -1
    if position > planes[-1]:
        return cells
    # A cell owns its lower plane (as a pixel owns its left and lower borders); the last owns both.
    return min(int(np.searchsorted(planes, position, side="right")) - 1, cells - 1)


def vp_cell(x: object, y: object, view: View) -> tuple[int, int]:
    """The (column, row) of the facet whose grid element holds the viewpoint's (x, y).

    Parameters
    ----------
    x : (Nx,) array_like of float
        The x-planes, strictly increasing, at least 2 (a non-uniform grid is fine).
    y : (Ny,) array_like of float
        The y-planes, likewise.
    view : View

    Returns
    -------
    (int, int)
        Column in -1..Nx-1 and row in -1..Ny-1: -1 below the first plane and
        Nx - 1 (resp. Ny - 1) beyond the last are virtual cells outside the
        grid. A viewpoint on an interior plane belongs to the cell above it
        (larger index); on the last plane, to the last cell. Parallel views:
        an axis the direction moves along gives the virtual cell at infinity
        behind the viewer; an axis it does not move along gives the cell of
        the point's coordinate clamped into the grid (any cell would serve:
        nothing occludes across that axis).

    Raises
    ------
    TypeError, ValueError
        If `x` or `y` is not a finite, strictly increasing 1-D array of at
        least 2 planes, or `view` is not a View.

    Examples
    --------
    >>> vp_cell([0, 1, 2, 3], [0, 1, 2], View((1.5, -4, 2), (0, 1, -0.5)))
    (1, -1)
    >>> vp_cell([0, 1, 2, 3], [0, 1, 2], View((1.0, 2.0, 2), (0, 1, -0.5)))  # ties
    (1, 1)
    """
    x, y = _check_planes("x", x), _check_planes("y", y)
    view = _check_view(view)
    parallel = view.projection == "parallel"
    (px, py, _), (dx, dy, _) = view.point, view.direction
    return _axis_cell(x, px, dx, parallel), _axis_cell(y, py, dy, parallel)


@dataclass(frozen=True)
class Enumeration:
    """The facet order and region classes of one grid and viewpoint (Steps III-IV).

    Attributes
    ----------
    order : (Ny - 1, Nx - 1) ndarray of int64
        Facet number 1..F (F = (Nx-1)(Ny-1)) of facet [row, column]; 1 is
        processed first, and no facet is numbered before one that can hide it.
    classes : (Ny - 1, Nx - 1) ndarray of int64
        Region class 1-9 of each facet relative to the viewpoint cell.
    case : int
        The viewing case 1-9.
    vp_cell : (int, int)
        (column, row) of the viewpoint, virtual -1 or N - 1 outside (`vp_cell`).
    sequence : (F, 2) ndarray of int64
        (row, column) of each facet in processing order: ``sequence[n - 1]``
        is facet number n.
    """

    order: np.ndarray
    classes: np.ndarray
    case: int
    vp_cell: tuple[int, int]
    sequence: np.ndarray


def _check_cells(columns: object, rows: object, cell: object) -> tuple[int, int, tuple[int, int]]:
    for name, value in (("columns", columns), ("rows", rows)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise TypeError(f"{name!r} must be an int; got {value!r}")
        if value < 1:
            raise ValueError(f"{name!r} must be >= 1; got {value!r}")
    try:
        column, row = cell  # type: ignore[misc]
    except (TypeError, ValueError):
        raise TypeError(f"'cell' must be a (column, row) pair of ints; got {cell!r}") from None
    if not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in cell):
        raise TypeError(f"'cell' must be a (column, row) pair of ints; got {cell!r}")
    if not (-1 <= column <= columns and -1 <= row <= rows):
        raise ValueError(
            f"'cell' must lie in -1..columns and -1..rows (virtual cells outside); got {cell!r} "
            f"for {columns} x {rows} facets"
        )
    return int(columns), int(rows), (int(column), int(row))


def region_classes(columns: int, rows: int, cell: tuple[int, int]) -> np.ndarray:
    """Region class 1-9 of every facet of a rows x columns grid, from the viewpoint cell.

    `cell` is (column, row) as `vp_cell` gives it: -1 or columns (resp. rows)
    is a virtual cell outside the grid.

    Examples
    --------
    >>> region_classes(5, 4, (2, 2))  # Fig. 2-2, case 1; row 0 (bottom) first
    array([[9, 9, 3, 7, 7],
           [9, 9, 3, 7, 7],
           [5, 5, 1, 4, 4],
           [8, 8, 2, 6, 6]])
    """
    columns, rows, cell = _check_cells(columns, rows, cell)
    row, column = np.indices((rows, columns))
    return _CLASSES[np.sign(column - cell[0]) + 1, np.sign(row - cell[1]) + 1]


def facet_sequence(columns: int, rows: int, cell: tuple[int, int]) -> np.ndarray:
    """(row, column) of every facet in processing order, from the viewpoint cell (Step III).

    The sort key, which reproduces Fig. 2-2: the ring max(abs(dc), abs(dr)); then
    the region class; then, with D the depth axis (x when the viewpoint is
    left or right of the grid in y-range, y otherwise) and T the other, the
    facets with abs(dD) = ring by increasing abs(dT), then those with abs(dT) = ring by
    increasing abs(dD).

    Examples
    --------
    >>> facet_sequence(3, 2, (-1, 0)).tolist()  # viewpoint left of row 0
    [[0, 0], [1, 0], [0, 1], [1, 1], [0, 2], [1, 2]]
    """
    columns, rows, cell = _check_cells(columns, rows, cell)
    row, column = (axis.ravel() for axis in np.indices((rows, columns)))
    dc, dr = np.abs(column - cell[0]), np.abs(row - cell[1])
    ring = np.maximum(dc, dr)
    edge_on_in_x = not 0 <= cell[0] < columns and 0 <= cell[1] < rows  # cases 4 and 5
    depth, lateral = (dc, dr) if edge_on_in_x else (dr, dc)
    first = (depth == ring) & (lateral < ring)  # the ring's far side, then its lateral side
    within = np.where(first, lateral, depth)
    classes = region_classes(columns, rows, cell).ravel()
    ranked = np.lexsort((within, ~first, classes, ring))  # last key is the primary one
    return np.stack([row[ranked], column[ranked]], axis=1)


def enumerate_facets(x: object, y: object, view: View) -> Enumeration:
    """Number the facets of a grid nearest-first in XY and give each its region class.

    Parameters
    ----------
    x : (Nx,) array_like of float
        The x-planes, strictly increasing, at least 2 (uniform or not: the
        order uses cell indices only).
    y : (Ny,) array_like of float
        The y-planes, likewise.
    view : View

    Returns
    -------
    Enumeration

    Raises
    ------
    TypeError, ValueError
        As `vp_cell`.

    Examples
    --------
    Fig. 2-2, case 9: a 5 x 4-facet grid seen from beyond its upper-right
    corner (top row first, as printed):

    >>> grid = enumerate_facets(range(6), range(5), View((7, 6, 3), (-1, -1, -1)))
    >>> grid.case, grid.vp_cell
    (9, (5, 4))
    >>> grid.order[::-1]
    array([[17, 13,  7,  3,  1],
           [18, 14,  8,  4,  2],
           [19, 15,  9,  6,  5],
           [20, 16, 12, 11, 10]])
    """
    x, y = _check_planes("x", x), _check_planes("y", y)
    view = _check_view(view)
    cell = vp_cell(x, y, view)
    columns, rows = x.size - 1, y.size - 1
    sequence = facet_sequence(columns, rows, cell)
    order = np.empty((rows, columns), dtype=np.int64)
    order[sequence[:, 0], sequence[:, 1]] = np.arange(1, sequence.shape[0] + 1)
    return Enumeration(
        order=order,
        classes=region_classes(columns, rows, cell),
        case=viewing_case((x[0], x[-1], y[0], y[-1]), view),
        vp_cell=cell,
        sequence=sequence,
    )

"""Look-up tables of DISLOP areas and intensities (Wang 1989, §4.7 periodicity, §4.8 post-AA).

Two kinds of table, both filled from the per-column formulas of
`scanviz.antialias.columns` (the geometry is not written again here):

* **periodic tables** (§4.7, Tables 4-1..4-6): one slope m, the p + 1 distances
  ``dxy_j = -1/2 + j/p`` of a period p, i.e. a column count with m·p close to
  an integer n, so that a long line reuses the table column after column.
  The printed periods of Tables 4-2 (16 levels), 4-4 (64) and 4-3 (256) are
  shipped as data (`PRINTED_PERIODS`); other slopes get `period_rule`.
* **the 51 x 51 x 3 tables** of post-anti-aliasing (§4.8, Tables 4-7..4-9):
  50 divisions of the slope range, ``m_i = i/50``, each with the exact period
  ``50/gcd(i, 50)``, so one rectangular table serves every slope:
  ``[i, j, (upper, middle, lower)]`` with ``dxy_j = -1/2 + j/50``; the line
  table and the two edge tables (flag 0: inside above, flag 1: inside below).

Indices follow the dissertation's C (L16068-16073, OCR-fixed in the spec):
``i = (int)(|m| * 50 + 0.5)``, ``j = (int)((dxy + 0.5) * 50 + 0.5)``; j = 0 and
j = 50 are the same configuration, one row apart. `column_indices` walks a
segment column by column with the dxy recurrence of Fig 5-2 (or the "simpler"
``j = (j + i) mod 50``), whose steps `first_column` and `next_column` also
drive `post_antialias`. Derivations and measurements: docs/antialiasing.md.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import cache

import numpy as np
from numba import njit

from .. import steps
from ..conventions import check_choice, check_int, short_repr
from . import columns
from ._inputs import check_point
from .line import canonical

DIVISIONS = 50  # slope divisions of [0, 1] (§4.8): m_i = i / 50, every period divides 50
LEVELS = (16, 64, 256)  # the intensity levels of §4.7
DISSERTATION_PI = 3.14156  # the tables of §4.7 were computed with this pi (spec §0, by fitting)
DRIFT_COLUMNS = 60  # `period_rule`: the drift over this many columns stays below one level
MAX_PERIOD = 2**16  # `period_rule` searches periods 1..MAX_PERIOD
KINDS = ("line", "edge")  # the tables of DISLOP_L and of DISLOP_E
RECURRENCES = ("exact", "simple")  # the dxy recurrence of Fig 5-2, or j = (j + i) mod 50

# Tables 4-2 (16 levels), 4-4 (64) and 4-3 (256): the printed period for 0..45 degrees.
PRINTED_PERIODS = {
    16: (1, 55, 29, 19, 43, 23, 19, 49, 50, 19, 17, 36, 33, 13, 52, 41, 56, 36, 37, 29, 11, 52, 47,
         33, 54, 15, 39, 51, 32, 56, 26, 50, 8, 20, 40, 10, 51, 57, 32, 21, 31, 23, 10, 59, 29, 1),
    64: (1, 57, 57, 57, 57, 57, 57, 57, 57, 82, 17, 36, 80, 13, 349, 56, 129, 72, 40, 61, 228, 86,
         52, 66, 128, 148, 41, 51, 79, 83, 71, 218, 8, 57, 43, 50, 106, 69, 32, 63, 56, 107, 221,
         74, 29, 1),
    256: (1, 172, 86, 229, 143, 80, 314, 57, 185, 101, 380, 391, 207, 758, 365, 209, 136, 157,
          277, 61, 272, 99, 99, 139, 146, 178, 285, 210, 205, 175, 97, 233, 877, 77, 255, 487, 128,
          142, 32, 184, 87, 153, 251, 163, 204, 1),
}  # fmt: skip


def degree_slope(degree: float) -> float:
    """The slope of `degree` as the dissertation's tables have it: tan(degree * 3.14156 / 180).

    >>> round(degree_slope(5), 4)
    0.0875
    """
    return math.tan(degree * DISSERTATION_PI / 180.0)


def _check_slope(m: object, name: str = "m") -> float:
    if isinstance(m, bool) or not isinstance(m, numbers.Real):
        raise TypeError(f"{name!r} must be a real number; got {short_repr(m)}")
    m = abs(float(m))
    if not m <= 1.0:  # also catches nan
        raise ValueError(f"{name!r} must be a first-octant slope, |m| <= 1; got {short_repr(m)}")
    return m


def check_levels(levels: object) -> int:
    """`levels` as an int in 2..256: the intensities are uint8."""
    return check_int("levels", levels, 2, 256)


def slope_index(m: float) -> int:
    """The slope index i = (int)(|m| * 50 + 0.5) of a first-octant slope |m| <= 1.

    >>> slope_index(0.080), slope_index(0.0875), slope_index(0.6747)
    (4, 4, 34)
    """
    return int(_check_slope(m) * DIVISIONS + 0.5)


def distance_index(dxy: float) -> int:
    """The distance index j = (int)((dxy + 0.5) * 50 + 0.5) of a distance dxy in [-1/2, 1/2].

    >>> distance_index(-0.0024), distance_index(-0.3277), distance_index(0.5)
    (25, 9, 50)
    """
    if isinstance(dxy, bool) or not isinstance(dxy, numbers.Real):
        raise TypeError(f"'dxy' must be a real number; got {short_repr(dxy)}")
    if not -0.5 <= dxy <= 0.5:
        raise ValueError(f"'dxy' must be in -1/2..1/2; got {short_repr(dxy)}")
    return int((float(dxy) + 0.5) * DIVISIONS + 0.5)


@steps.step(
    "table_index",
    takes="a first-octant slope m (|m| <= 1) and a column's distance dxy (-1/2 <= dxy <= 1/2)",
    returns="(i, j): the indices of the 51 x 51 x 3 tables, i = int(|m| * 50 + 0.5) and "
    "j = int((dxy + 0.5) * 50 + 0.5)",
)
def table_indices(m: float, dxy: float) -> tuple[int, int]:
    """The table indices (i, j) of a column: `slope_index` and `distance_index`.

    >>> table_indices(0.080, -0.0024), table_indices(0.25, 0.25)
    ((4, 25), (13, 38))
    """
    return slope_index(m), distance_index(dxy)


def _fill(rows: int, m_values, dxy_values, formula) -> np.ndarray:
    table = np.empty((len(m_values), rows, 3))
    for i, m in enumerate(m_values):
        for j, dxy in enumerate(dxy_values):
            table[i, j] = formula(m, dxy)[:3]
    return table


@cache
def _line_table() -> np.ndarray:
    grid = [k / DIVISIONS for k in range(DIVISIONS + 1)]
    table = _fill(DIVISIONS + 1, grid, [k - 0.5 for k in grid], columns.line_column)
    table.flags.writeable = False
    return table


@cache
def _edge_tables() -> np.ndarray:
    grid = [k / DIVISIONS for k in range(DIVISIONS + 1)]
    tables = np.stack(
        [
            _fill(DIVISIONS + 1, grid, [k - 0.5 for k in grid], _edge_formula(flag))
            for flag in (0, 1)
        ]
    )
    tables.flags.writeable = False
    return tables


def _edge_formula(flag: int):
    return lambda m, dxy: columns.edge_column(m, dxy, flag)


def line_table() -> np.ndarray:
    """The post-AA line table: DISLOP_L areas at m_i = i/50, dxy_j = -1/2 + j/50.

    Returns
    -------
    (51, 51, 3) ndarray of float64
        ``[i, j, (upper, middle, lower)]``, read-only (built once).

    >>> [round(float(a), 4) for a in line_table()[4, 25]]  # Table 4-8, j = 25
    [0.0108, 0.9816, 0.0108]
    """
    return _line_table()


def edge_tables() -> np.ndarray:
    """The post-AA edge tables: DISLOP_E areas for flag 0 (inside above) and 1 (inside below).

    Returns
    -------
    (2, 51, 51, 3) ndarray of float64
        ``[flag, i, j, (upper, middle, lower)]``, read-only. Only the pixels the
        edge cuts are non-zero (the polygon fill covers the others).

    >>> [round(float(a), 4) for a in edge_tables()[1, 42, 0]]  # Table 4-9, j = 0
    [0.0, 0.105, 0.895]
    """
    return _edge_tables()


def intensities(areas: object, levels: int = 64) -> np.ndarray:
    """Areas quantised to `levels` intensity levels: floor(A * (levels - 1) + 0.5), as uint8.

    >>> intensities([0.0119, 0.98, 0.0119], 256).tolist()
    [3, 250, 3]
    """
    levels = check_levels(levels)
    areas = np.asarray(areas, dtype=np.float64)
    if not np.all((areas >= 0.0) & (areas <= 1.0)):
        raise ValueError("'areas' must be finite and in 0..1")
    return np.floor(areas * (levels - 1) + 0.5).astype(np.uint8)


@dataclass(frozen=True)
class PeriodicTable:
    """A per-slope table of §4.7: the p + 1 distances ``dxy_j = -1/2 + j/p`` of one period.

    Attributes
    ----------
    m : float
        The slope, 0..1.
    levels : int
        Intensity levels L.
    period : int
        p, the column count after which dxy nearly repeats.
    value : float
        m·p ("Value" in Tables 4-2..4-4).
    n : int
        The integer closest to m·p.
    residual : float
        ``|m·p - n|``, the precision in area: how far dxy drifts per period.
    precision : float
        The precision in intensity, residual × L (the tables multiply by L, not L - 1).
    dxy : (p + 1,) ndarray of float64
    areas : (p + 1, 3) ndarray of float64
        (upper, middle, lower) of each distance (DISLOP_L, or DISLOP_E with the flag).
    intensities : (p + 1, 3) ndarray of uint8
    """

    m: float
    levels: int
    period: int
    value: float
    n: int
    residual: float
    precision: float
    dxy: np.ndarray
    areas: np.ndarray
    intensities: np.ndarray


def period_rule(m: float, levels: int) -> int:
    """scanviz's period for slope m: the smallest p with |m·p - n| < 1/L and drift over 60 columns < 1/L.

    n = round(m·p) must be >= 1 for m > 0, and the drift ``|m·p - n| * 60 / p``
    is how far dxy moves when the table is reused for a 60-column line. At
    256 levels this reproduces all 44 non-trivial printed periods of Table
    4-3; at 16 and 64 levels, see docs/antialiasing.md (the dissertation does
    not state its rule).

    >>> period_rule(degree_slope(5), 256), period_rule(degree_slope(40), 256)
    (80, 87)
    """
    m, levels = _check_slope(m), check_levels(levels)
    if m == 0.0 or m == 1.0:
        return 1
    p = np.arange(1, MAX_PERIOD + 1, dtype=np.float64)
    n = np.rint(m * p)
    residual = np.abs(m * p - n)
    ok = (n >= 1) & (residual < 1.0 / levels) & (residual * DRIFT_COLUMNS / p < 1.0 / levels)
    if not ok.any():
        raise ValueError(f"'m' = {m!r} has no period up to {MAX_PERIOD}; pass 'period'")
    return int(np.argmax(ok)) + 1


def printed_period(m: float, levels: int) -> int | None:
    """The period Tables 4-2..4-4 print for m = tan(degree) (dissertation pi or exact), else None.

    >>> printed_period(degree_slope(5), 64), printed_period(0.3, 64)
    (57, None)
    """
    m, levels = _check_slope(m), check_levels(levels)
    if levels not in PRINTED_PERIODS:
        return None
    for degree, period in enumerate(PRINTED_PERIODS[levels]):
        if min(abs(m - degree_slope(degree)), abs(m - math.tan(math.radians(degree)))) < 1e-9:
            return period
    return None


def periodic_table(
    m: float, levels: int, period: int | None = None, *, kind: str = "line", flag: int = 1
) -> PeriodicTable:
    """The §4.7 table of slope m over one period, areas and `levels`-level intensities.

    Parameters
    ----------
    m : float
        First-octant slope, |m| <= 1.
    levels : int
        Intensity levels, 2..256 (the dissertation: 16, 64, 256).
    period : int, optional
        p >= 1; default the printed period of Tables 4-2..4-4 if m is a whole
        degree there (`printed_period`), otherwise `period_rule`.
    kind : {"line", "edge"}
        DISLOP_L areas, or DISLOP_E areas with `flag` (1: inside below, Table 4-6).
    flag : {0, 1}
        The edge flag; ignored for lines.

    Returns
    -------
    PeriodicTable

    Examples
    --------
    >>> t = periodic_table(degree_slope(5), 64)  # Table 4-5
    >>> t.period, round(t.value, 4), t.n, t.intensities[28].tolist()
    (57, 4.9868, 5, [0, 62, 1])
    """
    m, levels = _check_slope(m), check_levels(levels)
    check_choice("kind", kind, KINDS)
    if flag not in (0, 1) or isinstance(flag, bool):
        raise ValueError(f"'flag' must be 0 or 1; got {short_repr(flag)}")
    if period is None:
        period = printed_period(m, levels) or period_rule(m, levels)
    period = check_int("period", period, 1, MAX_PERIOD)
    value = m * period
    n = round(value)
    dxy = -0.5 + np.arange(period + 1) / period
    formula = columns.line_column if kind == "line" else _edge_formula(flag)
    areas = np.array([formula(m, float(d))[:3] for d in dxy])
    residual = abs(value - n)
    return PeriodicTable(
        m, levels, period, value, n, residual, residual * levels, dxy, areas,
        intensities(np.clip(areas, 0.0, 1.0), levels),
    )  # fmt: skip


@dataclass(frozen=True)
class ColumnIndices:
    """The table indices of a segment, column by column, in its first-octant frame (Fig 5-2).

    Attributes
    ----------
    x : (K,) ndarray of int64
        The columns ixs..ixe (the frame's major axis: raster y if `steep`).
    iy : (K,) ndarray of int64
        The middle pixel's row in each column (negated raster row if `flip`).
    dxy : (K,) ndarray of float64
        The distance of the centre line from the middle pixel's centre; with the
        "simple" recurrence the table's dxy_j = -1/2 + j/50.
    i : int
        The slope index.
    j : (K,) ndarray of int64
        The distance index.
    m : float
        The first-octant slope.
    steep, flip : bool
        How the frame reflects the raster (`scanviz.antialias.line.canonical`).
    """

    x: np.ndarray
    iy: np.ndarray
    dxy: np.ndarray
    i: int
    j: np.ndarray
    m: float
    steep: bool
    flip: bool


def column_indices(p0: object, p1: object, recurrence: str = "exact") -> ColumnIndices:
    """Slope and distance indices of segment p0-p1 in every column ixs..ixe (Fig 5-2).

    ``X0 = ixs``, ``Y0`` the centre line at its centre, ``iy = round(Y0)``,
    ``dxy = Y0 - iy``; then per column ``dxy += m`` (minus 1, iy + 1, past
    1/2) and j from `distance_index` ("exact"), or ``j = (j + i) mod 50``
    with iy + 1 when it wraps ("simple", less accurate: §4.1).

    Parameters
    ----------
    p0, p1 : (2,) array_like of float
        Endpoints in scanviz pixel coordinates (the dissertation's plus 1/2).
    recurrence : {"exact", "simple"}

    Examples
    --------
    >>> column_indices((100.8, 150.7), (109.1, 156.3)).j[:9].tolist()
    [25, 9, 42, 26, 10, 44, 27, 11, 45]
    >>> column_indices((100.8, 150.7), (109.1, 156.3), "simple").j[:9].tolist()
    [25, 9, 43, 27, 11, 45, 29, 13, 47]
    """
    p0, p1 = check_point("p0", p0), check_point("p1", p1)
    simple = check_choice("recurrence", recurrence, RECURRENCES) == "simple"
    u0, v0, u1, v1, steep, flip = canonical(p0, p1)
    m = (v1 - v0) / (u1 - u0) if u1 > u0 else 0.0
    i = int(m * DIVISIONS + 0.5)
    start, end = math.floor(u0 + 0.5), math.floor(u1 + 0.5)
    count = end - start + 1
    x, iy, j = (np.empty(count, dtype=np.int64) for _ in range(3))
    dxy = np.empty(count)
    row, d, index = first_column(u0, v0, m, start)
    for k in range(count):
        if k > 0:
            row, d, index = next_column(row, d, i, index, m, simple)
        x[k], iy[k], j[k] = start + k, row, index
        dxy[k] = -0.5 + index / DIVISIONS if simple else d
    return ColumnIndices(x, iy, dxy, i, j, m, steep, flip)


def first_column(u0: float, v0: float, m: float, column: int) -> tuple[int, float, int]:
    """The recurrence's start X0 = `column`: the middle pixel's row, dxy and j there (Fig 5-2).

    >>> first_column(0.0, 0.25, 0.5, 1)
    (1, -0.25, 13)
    """
    centre = v0 + (column - u0) * m  # Y0: the centre line at the column's centre
    row = math.ceil(centre - 0.5)
    dxy = centre - row
    return row, dxy, int((dxy + 0.5) * DIVISIONS + 0.5)


def next_column(
    row: int, dxy: float, i: int, j: int, m: float, simple: bool
) -> tuple[int, float, int]:
    """One column of Fig 5-2's recurrence: the next column's (row, dxy, j).

    Exact: ``dxy += m`` (minus 1, row + 1, past 1/2) and j from dxy, as
    `distance_index`; simple: ``j = (j + i) mod 50`` (row + 1 when it wraps)
    and dxy = -1/2 + j/50, the table's distance.

    >>> next_column(3, 0.375, 13, 12, 0.25, False), next_column(3, 0.375, 13, 12, 0.25, True)
    ((4, -0.375, 6), (3, 0.0, 25))
    """
    if simple:
        row += 1 if j + i >= DIVISIONS else 0
        j = (j + i) % DIVISIONS
        return row, -0.5 + j / DIVISIONS, j
    dxy += m
    if dxy > 0.5:
        row, dxy = row + 1, dxy - 1.0
    return row, dxy, int((dxy + 0.5) * DIVISIONS + 0.5)


first_column_compiled = njit(cache=True)(first_column)
next_column_compiled = njit(cache=True)(next_column)

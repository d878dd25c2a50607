"""The specular look-up table: (cos φ)^n by comparisons instead of a power (Wang 1989, §3.3).

The specular term of the dissertation's model is Isr·cos(φ)^n with the
constant Isr = Ip·ks/(r + r0). Quantised to integer levels it is
floor(N·cos(φ)^n) with N = floor(Isr), and that level is j exactly when

    cos φ_j <= cos φ < cos φ_{j+1},    cos φ_j = (j/N)^(1/n),  j = 1..N.

So the table cos φ_1..cos φ_N is built once per surface and each pixel finds
its level by comparisons: a binary search (ceil(log2(N+1)) comparisons, 8
for N = 255), or a linear step from the previous pixel's level, which along
a span usually moves by 0 or 1. The level is the number of entries <= cos φ;
below cos φ_1 (negative, or NaN) it is 0, from cos φ_N = 1 up it is N.
See docs/shading-lut.md.
"""

from __future__ import annotations

import math
import numbers
from fractions import Fraction

import numpy as np
from numba import njit

from .. import steps
from ..conventions import finite_real
from ..limits import check_memory

_BYTES_PER_ENTRY = 8  # float64, built in place


def _decimal(value: float) -> Fraction:
    # the shortest decimal that rounds to `value`: what the user wrote, so 100 * 0.29 is 29
    return Fraction(repr(value))


def table_size(Ip: float, ks: float, r_plus_r0: float) -> int:
    """N = floor(Ip·ks/(r + r0)), the number of specular levels, computed exactly.

    The product is taken over the parameters' decimal values (their shortest
    ``repr``), not in floating point, so a level count that is an integer on
    paper is not lost to rounding (100·0.29 is 28.999999999999996 in float64).

    >>> table_size(255, 1, 1), table_size(255, 0.5, 1.2), table_size(255, 0.7, 1.5)
    (255, 106, 119)
    >>> table_size(100, 0.29, 1), math.floor(100 * 0.29)
    (29, 28)
    """
    Ip = finite_real("Ip", Ip)
    ks = finite_real("ks", ks)
    r_plus_r0 = finite_real("r_plus_r0", r_plus_r0)
    if Ip <= 0:
        raise ValueError(f"'Ip' (the light intensity) must be > 0; got {Ip}")
    if ks < 0:
        raise ValueError(f"'ks' (the specular coefficient) must be >= 0; got {ks}")
    if r_plus_r0 < 1:
        raise ValueError(f"'r_plus_r0' (the distance term r + r0) must be >= 1; got {r_plus_r0}")
    return math.floor(_decimal(Ip) * _decimal(ks) / _decimal(r_plus_r0))


def _exponent(n: object) -> float:
    n = finite_real("n", n)
    if n <= 0:
        raise ValueError(f"'n' (the specular exponent) must be > 0; got {n}")
    return n


def _count(entries: int) -> str:
    digits = str(entries)
    return digits if len(digits) <= 15 else f"about 10^{len(digits) - 1}"


def specular_lut(
    Ip: float, ks: float, r_plus_r0: float, n: float, *, top: int | None = None
) -> np.ndarray:
    """The table cos φ_j = (j/N)^(1/n), j = 1..N, with N = floor(Ip·ks/(r + r0)).

    Parameters
    ----------
    Ip : float
        Light-source intensity, > 0 (255 in the dissertation).
    ks : float
        Specular coefficient, >= 0 (the same for every channel).
    r_plus_r0 : float
        The distance term r + r0, >= 1, taken constant over the surface.
    n : float
        Specular exponent, > 0.
    top : int, optional
        Keep only the entries j = 1..min(N, top), so a look-up gives
        min(level, top). Fast Phong clips each colour at 255 levels, so past
        ``top=255`` no entry can change a pixel: `render` builds its tables so,
        and a bright light (Ip·ks of 10^8) costs 2 KiB instead of gigabytes.

    Returns
    -------
    (min(N, top),) ndarray of float64
        Read-only, nondecreasing, positive, ending at 1.0 when it is whole. Entry
        ``j - 1`` is cos φ_j. Empty when N = 0 (e.g. ks = 0): every look-up then gives level 0.

    Raises
    ------
    ValueError
        A parameter out of its range (naming it and the rule), or a table
        over the memory limit (`scanviz.limits.ResourceLimitError`).

    Notes
    -----
    N is truncated, not rounded: Table 3-3 (Ip = 255, ks = 0.5, r + r0 = 1.2)
    prints cos φ_1 = 0.4597 = (1/106)^(1/6), where Isr = 106.25 would give 0.4595.

    Examples
    --------
    >>> table = specular_lut(255, 0.5, 1.2, 6)        # Table 3-3
    >>> len(table), table[:2].round(4).tolist(), float(table[-1])
    (106, [0.4597, 0.516], 1.0)
    >>> specular_lut(255, 0, 1, 6).shape
    (0,)
    >>> bright = specular_lut(255e8, 1, 1, 6, top=255)     # the same first 255 entries as N's
    >>> len(bright), float(bright[0]) == (1 / 255e8) ** (1 / 6)
    (255, True)
    """
    levels = table_size(Ip, ks, r_plus_r0)
    n = _exponent(n)
    if top is not None:
        if isinstance(top, bool) or not isinstance(top, numbers.Integral) or top < 0:
            raise ValueError(f"'top' (the highest level kept) must be an int >= 0; got {top!r}")
    entries = levels if top is None else min(levels, int(top))
    nbytes = float(_BYTES_PER_ENTRY * entries) if entries < 2**1000 else math.inf
    check_memory(nbytes, f"a specular look-up table of N = {_count(entries)} entries")
    table = np.arange(1, entries + 1, dtype=np.float64)
    if levels < 2**1000:
        table /= levels
        np.power(table, 1.0 / n, out=table)
    else:  # j/N underflows in float64: take (j/N)^(1/n) through logarithms (exact N's log)
        np.log(table, out=table)
        table -= math.log(levels)
        table /= n
        np.exp(table, out=table)
    # for n < 1 small entries underflow; the true value is > 0, so cos φ <= 0 must stay level 0
    np.maximum(table, np.finfo(np.float64).smallest_subnormal, out=table)
    table.flags.writeable = False
    return table


def _table(table: object) -> np.ndarray:
    # O(1) checks only: a look-up must stay at its few comparisons
    if not isinstance(table, np.ndarray) or table.ndim != 1 or table.dtype != np.float64:
        raise TypeError(f"'table' must be a 1-D float64 array from specular_lut; got {table!r}")
    return table


def _cosine(cos_phi: object) -> float:
    if isinstance(cos_phi, bool) or not isinstance(cos_phi, numbers.Real):
        raise TypeError(f"'cos_phi' must be a real number; got {cos_phi!r}")
    return float(cos_phi)


def lut_level(table: np.ndarray, cos_phi: float, *, count: bool = False) -> int | tuple[int, int]:
    """The level j with cos φ_j <= cos φ < cos φ_{j+1}, by binary search.

    Parameters
    ----------
    table : (N,) ndarray of float64
        From `specular_lut`.
    cos_phi : float
        Below cos φ_1 (negative, or NaN) gives 0; at or above cos φ_N = 1 gives N.
    count : bool
        Also return the number of comparisons of cos φ with table entries.

    Returns
    -------
    int, or (int, int) if `count`
        The level, the number of entries <= cos φ; and the comparisons made,
        at most ceil(log2(N + 1)): 8 for N = 255, 0 for an empty table.

    Examples
    --------
    >>> table = specular_lut(255, 1, 1, 6)            # Table 3-1
    >>> lut_level(table, 0.7000, count=True), lut_level(table, 0.6999), lut_level(table, 1.0)
    ((30, 8), 29, 255)
    """
    table = _table(table)
    cos_phi = _cosine(cos_phi)
    low, high = 0, len(table)  # table[:low] <= cos φ < table[high:]
    comparisons = 0
    while low < high:
        middle = (low + high) // 2
        comparisons += 1
        if table[middle] <= cos_phi:  # False for NaN: NaN sinks to level 0
            low = middle + 1
        else:
            high = middle
    return (low, comparisons) if count else low


def lut_level_coherent(
    table: np.ndarray, cos_phi: float, start: int, *, count: bool = False
) -> int | tuple[int, int]:
    """The same level as `lut_level`, stepping one entry at a time from level `start`.

    Along a span cos φ changes little from pixel to pixel, so starting from
    the previous pixel's level the answer is usually 0 or 1 steps away.

    Parameters
    ----------
    table : (N,) ndarray of float64
        From `specular_lut`.
    cos_phi : float
        As for `lut_level`.
    start : int
        The previous level, 0 <= start <= N.
    count : bool
        Also return the number of comparisons of cos φ with table entries:
        abs(level - start) + 1 when moving up, abs(level - start) + 2 when moving
        down or staying (both neighbours are checked), fewer at the ends.

    Returns
    -------
    int, or (int, int) if `count`

    Examples
    --------
    >>> table = specular_lut(255, 1, 1, 6)
    >>> lut_level_coherent(table, 0.7000, 28, count=True), lut_level_coherent(table, 0.6999, 30)
    ((30, 3), 29)
    """
    table = _table(table)
    cos_phi = _cosine(cos_phi)
    if isinstance(start, bool) or not isinstance(start, numbers.Integral):
        raise TypeError(f"'start' must be an int level; got {start!r}")
    if not 0 <= start <= len(table):
        raise ValueError(f"'start' must be a level in [0, N = {len(table)}]; got {start}")
    level, comparisons = int(start), 0
    while level < len(table):  # up while cos φ_{level+1} <= cos φ
        comparisons += 1
        if not table[level] <= cos_phi:
            break
        level += 1
    if level == start:
        while level > 0:  # down while cos φ < cos φ_level (NaN included)
            comparisons += 1
            if table[level - 1] <= cos_phi:
                break
            level -= 1
    return (level, comparisons) if count else level


@steps.step(
    "specular_level",
    takes="the table cos φ_1..cos φ_N (nondecreasing float64), a sample's cos φ and start: the "
    "previous sample's level on the span (None at a span's first sample)",
    returns="the level: the number of entries <= cos φ (a binary search at a span's start, a walk "
    "from start after)",
)
def specular_level(table: np.ndarray, cos_phi: float, start: int | None) -> int:
    """The level of `cos_phi` as fast Phong finds it: `lut_level` at a span's first sample, else
    `lut_level_coherent` from the previous sample's level `start`.

    >>> table = specular_lut(255, 1, 1, 6)
    >>> specular_level(table, 0.7, None), specular_level(table, 0.7, 28), specular_level(table, 0.7, 31)
    (30, 30, 30)
    """
    return lut_level(table, cos_phi) if start is None else lut_level_coherent(table, cos_phi, start)


def level_comparisons(size: int, level: int, start: int | None = None) -> int:
    """The comparisons `specular_level` makes on a table of `size` entries when it finds `level`.

    Both searches branch only on whether an entry is <= cos φ, true for the first `level`
    entries, so they make the same comparisons over the ranks 0..size-1 for level - 1/2.
    A level or start outside [0, size] (from a replaced step) counts as the nearest end.

    >>> table = specular_lut(255, 1, 1, 6)
    >>> lut_level(table, 0.7, count=True), level_comparisons(255, 30)
    ((30, 8), 8)
    >>> lut_level_coherent(table, 0.7, 28, count=True), level_comparisons(255, 30, 28)
    ((30, 3), 3)
    """
    ranks = np.arange(size, dtype=np.float64)
    rank = min(max(int(level), 0), size) - 0.5
    if start is None:
        return lut_level(ranks, rank, count=True)[1]
    return lut_level_coherent(ranks, rank, min(max(int(start), 0), size), count=True)[1]


@njit(cache=True)
def lut_level_compiled(table: np.ndarray, cos_phi: float) -> int:
    """`lut_level` compiled: the same comparisons, callable from other numba kernels.

    >>> lut_level_compiled(specular_lut(255, 1, 1, 6), 0.7)
    30
    """
    low, high = 0, len(table)
    while low < high:
        middle = (low + high) // 2
        if table[middle] <= cos_phi:
            low = middle + 1
        else:
            high = middle
    return low


@njit(cache=True)
def _levels(table: np.ndarray, cosines: np.ndarray, out: np.ndarray) -> None:
    for i in range(len(cosines)):
        out[i] = lut_level_compiled(table, cosines[i])


def lut_levels(table: np.ndarray, cos_phis: object) -> np.ndarray:
    """`lut_level` over an array of cosines, compiled; equal to it everywhere, ties included.

    Parameters
    ----------
    table : (N,) ndarray of float64
        From `specular_lut`.
    cos_phis : array_like of float
        Any shape; NaN gives level 0 as in `lut_level`.

    Returns
    -------
    ndarray of int64, the shape of `cos_phis`

    Examples
    --------
    >>> table = specular_lut(255, 0.7, 1.5, 8)        # Table 3-4, N = 119
    >>> lut_levels(table, [-1.0, 0.5502, 0.5503, 0.9180, 2.0, np.nan]).tolist()
    [0, 0, 1, 60, 119, 0]
    """
    table = _table(table)
    cosines = np.asarray(cos_phis, dtype=np.float64)
    out = np.empty(cosines.shape, dtype=np.int64)
    _levels(table, np.ascontiguousarray(cosines).ravel(), out.ravel())
    return out


def specular_levels_exact(N: int, n: float, cos_phis: object) -> np.ndarray:
    """The oracle: floor(N·c^n) with c = cos φ clipped to [0, 1] (NaN counts as 0).

    Clipping at 1 matches the table's top level N for cos φ >= 1 (an
    approximated cos φ can overshoot); at 0 it matches level 0 for a
    highlight facing away.

    Parameters
    ----------
    N : int
        The number of levels, >= 0 (`table_size`).
    n : float
        Specular exponent, > 0.
    cos_phis : array_like of float

    Returns
    -------
    ndarray of int64, the shape of `cos_phis`

    Examples
    --------
    >>> specular_levels_exact(255, 6, [0.7, 0.6999, 1.0, 1.5, -0.5]).tolist()
    [30, 29, 255, 255, 0]
    """
    if isinstance(N, bool) or not isinstance(N, numbers.Integral):
        raise TypeError(f"'N' must be an int number of levels; got {N!r}")
    if N < 0:
        raise ValueError(f"'N' (the number of levels) must be >= 0; got {N}")
    n = _exponent(n)
    cosines = np.clip(np.fmax(np.asarray(cos_phis, dtype=np.float64), 0.0), 0.0, 1.0)
    return np.floor(N * cosines**n).astype(np.int64)

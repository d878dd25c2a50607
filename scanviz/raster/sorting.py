"""Counting the exchanges a stable insertion sort would make, in O(n log n).

The edge-table walks report how much their active edge tables were
reordered (an insertion sort's swaps, `scanviz.raster.scanline`), and the
area sweep bounds its work by the same count (`scanviz.abuffer.area`). Both
are the inversions of a sequence: pairs out of order, counted while a
bottom-up merge sort merges them (Knuth, TAOCP vol. 3, section 5.1.1).
"""

from __future__ import annotations

from numba import njit


@njit(cache=True)
def inversions(values, scratch):
    """Pairs i < j with values[i] > values[j], by a bottom-up merge sort that overwrites both arrays."""
    n = len(values)
    count = 0
    run = 1
    while run < n:
        for lo in range(0, n, 2 * run):
            mid, hi = min(lo + run, n), min(lo + 2 * run, n)
            i, j = lo, mid
            for k in range(lo, hi):
                if j < hi and (i == mid or values[j] < values[i]):
                    scratch[k] = values[j]
                    count += mid - i  # values[j] is below every value left in [i, mid)
                    j += 1
                else:
                    scratch[k] = values[i]
                    i += 1
        values, scratch = scratch, values
        run *= 2
    return count

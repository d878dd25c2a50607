"""Per-render buffers in ordinary pages: no transparent huge pages, whose faults can cost more.

numpy advises the kernel to back every array of 4 MiB or more with huge
pages (``madvise(MADV_HUGEPAGE)``). Where the kernel then compacts memory to
find them (``/sys/kernel/mm/transparent_hugepage/defrag`` set to
``madvise``), the first write to each 2 MiB of a fresh array waits for it: a
1024² RGB image took 26 ms to fill on one machine, 5 ms in ordinary pages.
A render allocates its buffers afresh (they are returned to the caller), so
`empty` and `zeros` here ask numpy not to advise huge pages for them. Where
numpy offers no such switch they are plain `np.empty` and `np.zeros`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np

try:
    from numpy._core.multiarray import _set_madvise_hugepage
except ImportError:  # numpy < 2 spells the module numpy.core
    try:
        from numpy.core.multiarray import _set_madvise_hugepage
    except ImportError:
        _set_madvise_hugepage = None


@contextlib.contextmanager
def ordinary_pages() -> Iterator[None]:
    """Arrays made inside are not advised into huge pages (the setting is restored after)."""
    if _set_madvise_hugepage is None:
        yield
        return
    before = _set_madvise_hugepage(False)
    try:
        yield
    finally:
        _set_madvise_hugepage(before)


def empty(shape, dtype=np.float64) -> np.ndarray:
    """`np.empty` in ordinary pages."""
    with ordinary_pages():
        return np.empty(shape, dtype)


def zeros(shape, dtype=np.float64) -> np.ndarray:
    """`np.zeros` in ordinary pages: pages never written are never touched (calloc)."""
    with ordinary_pages():
        return np.zeros(shape, dtype)

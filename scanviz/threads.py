"""When a compiled kernel shares its work among numba's threads, and when it stays on one.

Starting numba's threads costs tens of microseconds on an idle machine and
milliseconds on a loaded one (OpenMP's workers spin), so each parallel
kernel has a twin for one thread. The twins are separately named functions
sharing one inlined body: numba's cache cannot tell two compilations of one
function apart. With one numba thread (the grading sandbox sets
``NUMBA_NUM_THREADS=1``) the parallel twin is never used, so it is never
compiled there.
"""

from __future__ import annotations

import numba


def use_threads(work: int, least: int) -> bool:
    """Whether `work` units go to numba's threads: more than `least` of them, more than one thread.

    >>> use_threads(10, 100)
    False
    """
    return work > least and numba.get_num_threads() > 1

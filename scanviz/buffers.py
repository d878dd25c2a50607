"""Per-render buffers: numpy's own `empty` and `zeros`, in the pages numpy chooses.

numpy advises the kernel to back arrays of 4 MiB or more with transparent
huge pages (``madvise(MADV_HUGEPAGE)``), and a render's first write to its
fresh buffers then takes one fault per 2 MiB instead of one per 4 KiB: a
2048² render ran in 250 ms, 410 ms in ordinary pages (docs/performance.md).
Where huge pages cost more (the kernel compacting memory to find them), the
public switch is the environment variable ``NUMPY_MADVISE_HUGEPAGE=0``, read
once when numpy is imported: set it before Python starts.
"""

from __future__ import annotations

import numpy as np

empty = np.empty
zeros = np.zeros

"""Progress for long runs: a tqdm bar when the work is large, nothing when it is small.

`progress(total, desc)` returns a tqdm bar (``tqdm.auto``: a widget in
Jupyter, text on a terminal) when ``total`` work units exceed
``threshold``, and a no-op otherwise, so small renders print nothing.
Loops that update it run in Python between compiled chunks, so Ctrl-C or a
Jupyter kernel interrupt stops them at the next chunk with
``KeyboardInterrupt`` and no partial result.
"""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator


class _Silent:
    def update(self, n: int = 1) -> None:
        pass

    def write(self, text: str) -> None:  # as tqdm.write: a line above the bar
        print(text)


@contextlib.contextmanager
def progress(total: int, desc: str, *, threshold: int = 0, enabled: bool | None = None) -> Iterator:
    """A progress bar over `total` units, shown when `enabled` (default: when total > threshold).

    >>> with progress(10, "polygons", threshold=100) as bar:
    ...     bar.update(10)
    """
    show = total > threshold if enabled is None else enabled
    if not show:
        yield _Silent()
        return
    from tqdm.auto import tqdm

    with tqdm(total=total, desc=desc, unit="", leave=False, mininterval=0.5) as bar:
        yield bar


NOTE = "scanviz: compiling kernels (first run only; `python -m scanviz warmup` does it ahead)"
_announced = False


def announce_compiling() -> None:
    """Print `NOTE` once, the first time numba compiles a kernel in this process."""
    from numba.core import event

    class Listener(event.Listener):
        def on_start(self, event_: object) -> None:
            global _announced
            if not _announced:
                _announced = True
                stream = sys.stdout if "ipykernel" in sys.modules else sys.stderr
                print(NOTE, file=stream, flush=True)

        def on_end(self, event_: object) -> None:
            pass

    event.register("numba:compile", Listener())

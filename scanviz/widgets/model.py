"""The state of a stepper: a trace and how many of its events have happened. No widgets here."""

from __future__ import annotations

import numbers
from collections.abc import Callable

from ..trace import Trace


class StepModel:
    """Which step of a `Trace` is shown: the state after the first `step` events.

    Widgets drive it with `set_step`; views `observe` it. It knows nothing of
    widgets, so it is tested (and usable) without a frontend.

    Parameters
    ----------
    trace : Trace

    Attributes
    ----------
    trace : Trace
    step : int
        0 (nothing happened yet) to ``len(trace)`` (every event happened).

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> model = StepModel(scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3, trace=True).trace)
    >>> seen = []
    >>> model.observe(seen.append)
    >>> model.set_step(3)
    >>> model.set_step(3)  # no change, no call
    >>> model.step, len(model), seen
    (3, 8, [3])
    """

    def __init__(self, trace: Trace) -> None:
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        self.trace = trace
        self.step = 0
        self._observers: list[Callable[[int], None]] = []

    def __len__(self) -> int:
        return len(self.trace)

    def set_step(self, step: int) -> None:
        """Go to `step` (0..len) and tell every observer; nothing happens if it is the current one."""
        if isinstance(step, bool) or not isinstance(step, numbers.Integral):
            raise TypeError(f"'step' must be an int; got {step!r}")
        if not 0 <= step <= len(self):
            raise ValueError(f"'step' must be in 0..{len(self)}; got {step}")
        if step == self.step:
            return
        self.step = int(step)
        for callback in self._observers:
            callback(self.step)

    def observe(self, callback: Callable[[int], None]) -> None:
        """Call ``callback(step)`` after every change of step."""
        self._observers.append(callback)

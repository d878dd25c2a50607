"""Events of the midpoint line algorithm (`scanviz.raster.lines`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event


@dataclass(frozen=True)
class LineSetup(Event):
    """A line ready for the midpoint algorithm.

    ``octant`` 0..7 counts 45-degree sectors of the direction counter-clockwise
    from +x (octant 0 is the slides' case 0 <= slope < 1). ``major`` is the axis
    stepped once per pixel; ``step_x``, ``step_y`` the direction signs. The
    decision variable is d = 2 f(midpoint): it starts at ``d_start`` and grows
    by ``d_axial`` after an axial step, by ``d_diagonal`` after a diagonal one.
    ``tie_steps`` says whether d == 0 takes the diagonal step.
    """

    kind: ClassVar[str] = "line_setup"
    x0: int
    y0: int
    x1: int
    y1: int
    octant: int
    major: str
    step_x: int
    step_y: int
    d_start: int
    d_axial: int
    d_diagonal: int
    tie_steps: bool


@dataclass(frozen=True)
class LineStep(Event):
    """Pixel (x, y) drawn; `d` before the decision; `choice` "axial", "diagonal" or "last"."""

    kind: ClassVar[str] = "line_step"
    x: int
    y: int
    d: int
    choice: str

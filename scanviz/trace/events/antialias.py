"""Events of area-sampling anti-aliasing: DISLOP and post-anti-aliasing (`scanviz.antialias`)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import Event


@dataclass(frozen=True)
class DislopColumn(Event):
    """One column (or row, ``major == "y"``) of a DISLOP line, ring or disk.

    ``x``, ``y`` is the middle pixel (raster coordinates), the one whose row
    (column) holds the line at the column (row) centre. In the first-octant
    frame the line there is ``y = dxy + slope * x`` relative to that pixel's
    centre, with ``0 <= slope`` and ``-1/2 < dxy <= 1/2``. ``fcv`` and ``scv``
    are the first and second critical values of Fig 4-2 (for an edge column,
    its critical value cv and the corner area AA of Fig 4-5). ``branch`` is
    the formula taken: "flat", "two", "three", "three_triangle" (DISLOP_L),
    "one_pixel", "two_pixel" (DISLOP_E), "cap" (an end column, clipped
    exactly) or "exact" (the exact band, up to four pixels). ``up``, ``mid``, ``low`` are the
    areas of the pixels above, at and below the middle one, in the first-octant
    frame (right, middle, left for a steep line); ``spill`` is the area of the
    fourth pixel, two beyond the middle on the side of ``dxy`` (0 in the
    dissertation's formula).
    """

    kind: ClassVar[str] = "dislop_column"
    x: int
    y: int
    major: str
    slope: float
    dxy: float
    fcv: float
    scv: float
    branch: str
    up: float
    mid: float
    low: float
    spill: float


@dataclass(frozen=True)
class PostColumn(Event):
    """One table look-up of post-anti-aliasing: a column (row, ``major == "y"``) of a segment.

    ``segment`` indexes the input segments; ``x``, ``y`` is the middle pixel
    (raster coordinates); ``i``, ``j`` the slope and distance indices;
    ``dxy`` the distance they came from (the table's dxy_j with the simple
    recurrence); ``up``, ``mid``, ``low`` the coverages read and blended
    (quantised to levels with the intensity table), first-octant frame.
    """

    kind: ClassVar[str] = "post_column"
    segment: int
    x: int
    y: int
    major: str
    i: int
    j: int
    dxy: float
    up: float
    mid: float
    low: float

"""Events of the a-buffer: pixel masks and the mask buffer (`scanviz.abuffer.masks`),
fragment lists and the packer (`scanviz.abuffer`)."""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import ClassVar

from .base import Event, Record

# --- pixel masks and the mask buffer (scanviz.abuffer.masks) -----------------------------


@dataclass(frozen=True)
class EdgeMaskEntry(Record):
    """Edge `edge` in one pixel: the bits at or right of its crossings, and its winding."""

    edge: int
    winding: int
    mask: int


@dataclass(frozen=True)
class MaskBufferPixel(Record):
    """A pixel of the mask buffer that some active edge crosses.

    ``carry`` is the winding entering the pixel from the left on each
    sub-row, bottom first; each bit's winding is its sub-row's carry plus the
    windings of the ``edges`` whose mask has the bit. ``mask`` is the result
    under the fill rule (for a convex corner: the "and" of the edge masks).
    """

    x: int
    carry: tuple[int, ...]
    edges: tuple[EdgeMaskEntry, ...]
    mask: int


@dataclass(frozen=True)
class MaskRun(Record):
    """Pixels ``x_start <= x < x_end`` that no edge crosses, all with mask `mask` (from the carry)."""

    x_start: int
    x_end: int
    mask: int


@dataclass(frozen=True)
class MaskBufferRow(Event):
    """The mask buffer of pixel row `y` after every active edge was scanned into it.

    ``active`` are the ids of the edges whose y-extent covers a sub-row of the
    row (ids as in `edge_table_built`); ``pixels`` the crossed pixels,
    ``runs`` the uncrossed pixels with a nonzero mask. Masks are ints whose
    bit j * cols + i is sub-sample (i, j) of the `layout` ("8x8", ...).
    """

    kind: ClassVar[str] = "mask_buffer_row"
    polygon: int
    y: int
    layout: str
    active: tuple[int, ...]
    pixels: tuple[MaskBufferPixel, ...]
    runs: tuple[MaskRun, ...]


@dataclass(frozen=True)
class EdgeMask(Event):
    """Edge `edge` scanned into pixel (x, y): its exact crossings and its edge mask.

    ``crossings[j]`` is where the edge crosses sub-row j (bottom first), in
    pixels, caller's frame, or None where it does not cross it inside this
    pixel. ``mask`` has the sub-samples at or right of each crossing.
    """

    kind: ClassVar[str] = "edge_mask"
    polygon: int
    y: int
    x: int
    edge: int
    winding: int
    crossings: tuple[Fraction | None, ...]
    mask: int


# --- the a-buffer (scanviz.abuffer) -------------------------------------------------------


@dataclass(frozen=True)
class FragmentRecord(Record):
    """One fragment as a pixelstruct holds it (thesis Fig. 6.6, without the link).

    ``z`` and ``zmax`` are its depth range (smaller is nearer); ``area`` the
    exact area of the pixel it covers; ``mask`` its sub-sample bits (bit
    j * cols + i); ``opacity`` = 1 - transparency; ``object`` its object id.
    A simple pixelstruct is one record with a full mask and opacity 1.
    """

    z: float
    zmax: float
    area: float
    mask: int
    color: tuple[float, ...]
    opacity: float
    object: int


@dataclass(frozen=True)
class FragmentInserted(Event):
    """Fragment ``index`` (of `polygon`) inserted into pixel (x, y)'s pixelstruct.

    ``case`` is one of the six of thesis §6.3.4: "complete_empty",
    "complete_simple", "complete_list", "partial_empty", "partial_simple",
    "partial_list" (incoming mask full or not x pixelstruct before).
    ``before`` and ``after`` are the fragment lists, nearest first, with their
    kinds ("empty", "simple", "list"); ``after`` is after merging and discarding.
    """

    kind: ClassVar[str] = "fragment_inserted"
    x: int
    y: int
    polygon: int
    index: int
    fragment: FragmentRecord
    case: str
    before_kind: str
    before: tuple[FragmentRecord, ...]
    after_kind: str
    after: tuple[FragmentRecord, ...]


@dataclass(frozen=True)
class FragmentsMerged(Event):
    """A stored fragment and the incoming one (same object and color, masks together full)."""

    kind: ClassVar[str] = "fragments_merged"
    x: int
    y: int
    polygon: int
    stored: FragmentRecord
    incoming: FragmentRecord
    merged: FragmentRecord


@dataclass(frozen=True)
class FragmentsDiscarded(Event):
    """Fragments thrown away behind ``front``, a fully covered opaque fragment."""

    kind: ClassVar[str] = "fragments_discarded"
    x: int
    y: int
    polygon: int
    front: FragmentRecord
    discarded: tuple[FragmentRecord, ...]


@dataclass(frozen=True)
class PackStep(Record):
    """One level of the fragment packer (thesis eqs. 6.4-6.6) on one region of the pixel.

    The region ``region`` (bits, M_Q(i+1)) of weight ``weight`` (Q_{i+1}) is
    what is still visible in front of fragment ``level`` (0 = nearest).
    ``branch`` names the region: the covered ("c") or uncovered ("u") side
    taken under each transparent fragment in front ("" under opaque ones only).
    ``mask_a`` = M_Q(i+1) AND M_i, weight ``a`` (A_i); ``mask_q`` = M_Q(i+1)
    AND NOT M_i, weight ``q`` (Q_i). ``color`` is the region's color times its
    weight: P_i A_i + T_i Q_i (opaque) or eq. 6.5 (transparent).
    """

    level: int
    branch: str
    fragment: FragmentRecord
    region: int
    weight: float
    mask_a: int
    a: float
    mask_q: int
    q: float
    color: tuple[float, ...]


@dataclass(frozen=True)
class PixelPacked(Event):
    """The packer collapsed pixel (x, y)'s fragment list into ``color`` and coverage ``alpha``.

    ``steps`` are in the order the recursion finishes them (deepest first);
    ``alpha`` is 1 - the background's share of the pixel.
    """

    kind: ClassVar[str] = "pixel_packed"
    x: int
    y: int
    weights: str
    steps: tuple[PackStep, ...]
    color: tuple[float, ...]
    alpha: float


@dataclass(frozen=True)
class CoverageBlended(Event):
    """The flawed z-buffer (thesis §6.3): color = new * coverage + old * (1 - coverage).

    ``passed`` iff z < stored (None: nothing drawn yet); only then is ``color``
    the blend of ``incoming`` over ``old``, else the old color stays.
    """

    kind: ClassVar[str] = "coverage_blended"
    x: int
    y: int
    polygon: int
    z: float
    stored: float | None
    passed: bool
    coverage: float
    incoming: tuple[float, ...]
    old: tuple[float, ...]
    color: tuple[float, ...]

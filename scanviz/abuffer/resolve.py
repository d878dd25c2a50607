"""Resolve a-buffer fragments into an anti-aliased image (thesis §6.3, Carpenter 1984).

Fragments arrive in drawing order, one per polygon per pixel. Each is
inserted into its pixel's pixelstruct (empty, simple or a fragment list;
the six cases of §6.3.4), kept sorted in z, combined with a fragment of the
same surface when their masks together cover the pixel, and everything behind
a fully covered opaque fragment is thrown away (§6.3.5). After the last
fragment, the packer collapses each fragment list into a color and a coverage
(§6.3.6, eqs. 6.4-6.6). ``mode="flawed"`` runs instead the coverage-blending
z-buffer the thesis opens §6.3 with, which leaves seams between polygons.

Without a tracer the compiled twin (`scanviz.abuffer.pixelstruct_compiled`) runs; with one,
or while a step of `scanviz.steps` is replaced, the traced reference
(`scanviz.abuffer.pixelstruct`). They give the same
fragment lists and stats, and images equal to 1e-12. See docs/abuffer.md.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from .. import steps
from ..conventions import check_choice, check_raster_size, check_rows
from ..limits import check_memory
from ..raster.api import as_tracer
from ..trace import Recorder, Trace
from ..trace.events import FragmentRecord
from . import pixelstruct, pixelstruct_compiled
from .merge import MERGES, merge_by_object
from .pixelstruct import ABufferStats, FragmentTable

__all__ = ["ABufferResult", "ABufferStats", "FragmentRecord", "Fragments", "resolve"]

WEIGHTS = ("area", "mask")
MODES = ("abuffer", "flawed")
MAX_MASK_BITS = 64
RESOLVE_PIXEL_BYTES = 8 * 11  # image (3), alpha, list head, the treaps' roots, hider and length
# Per fragment: the compiled path's copy of the fields (grouped by pixel), the links, and the
# two treaps (keys, insertion times, children, priorities, walk buffers).
RESOLVE_FRAGMENT_BYTES = 8 * 24


@dataclass(frozen=True)
class Fragments:
    """Fragments in drawing order: one row per polygon's part of one pixel, validated once.

    Attributes
    ----------
    x, y : (F,) ndarray of int64
        The pixel, inside the raster given to `resolve`.
    polygon, object : (F,) ndarray of int64
        The polygon the fragment comes from, and its object (for combining).
    mask : (F,) ndarray of uint64
        Sub-sample bits, bit j * cols + i for sub-sample (i, j) of the layout.
    area : (F,) ndarray of float64
        Exact area of polygon ∩ pixel, in [0, 1].
    zmin, zmax : (F,) ndarray of float64
        Depth range over the pixel, zmin <= zmax; smaller is nearer.
    color : (F, 3) ndarray of float64
        RGB of the fragment (finite).
    opacity : (F,) ndarray of float64
        1 - transparency, in [0, 1].

    All arrays are copied and made read-only.

    Raises
    ------
    ValueError
        On a wrong shape or an entry out of range, naming the array and row.
    TypeError
        If an array does not hold numbers of the right kind.

    Examples
    --------
    >>> f = Fragments.from_rows([dict(x=0, y=0, mask=0xF, area=0.25, z=0.5, color=(1, 0, 0))])
    >>> f.count, int(f.mask[0]), f.color.shape
    (1, 15, (1, 3))
    >>> Fragments.from_rows([dict(x=0, y=0, mask=1, area=1.5, z=0.5, color=(1, 0, 0))])
    Traceback (most recent call last):
    ...
    ValueError: 'area'[0] = 1.5 is not in [0, 1]
    """

    x: np.ndarray
    y: np.ndarray
    polygon: np.ndarray
    object: np.ndarray
    mask: np.ndarray
    area: np.ndarray
    zmin: np.ndarray
    zmax: np.ndarray
    color: np.ndarray
    opacity: np.ndarray

    def __post_init__(self) -> None:
        arrays = {name: _integer_array(name, getattr(self, name)) for name in _INTEGER_FIELDS}
        arrays["mask"] = _mask_array(self.mask)
        for name in ("area", "zmin", "zmax", "opacity", "color"):
            arrays[name] = _float_array(name, getattr(self, name))
        count = len(arrays["x"])
        for name, array in arrays.items():
            shape = (count, 3) if name == "color" else (count,)
            if array.shape != shape:
                wanted = "(F, 3)" if name == "color" else "(F,)"
                raise ValueError(
                    f"{name!r} must be an {wanted} array with F = {count} (the length of 'x'); "
                    f"got shape {array.shape}"
                )
        for name in ("area", "opacity"):
            broken = (arrays[name] < 0) | (arrays[name] > 1)
            check_rows(name, arrays[name], broken, "is not in [0, 1]")
        check_rows("zmax", arrays["zmax"], arrays["zmax"] < arrays["zmin"], "is below 'zmin'")
        for name, array in arrays.items():
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    @property
    def count(self) -> int:
        """The number of fragments, F."""
        return len(self.x)

    @classmethod
    def from_rows(cls, rows: list[dict]) -> Fragments:
        """Pack dicts with x, y, mask, area, z (or zmin/zmax), color, and optional
        polygon (default: the row index), object (default 0) and opacity (default 1)."""
        columns: dict[str, list] = {name: [] for name in cls.__dataclass_fields__}
        for i, row in enumerate(rows):
            z = row.get("z")
            columns["x"].append(row["x"])
            columns["y"].append(row["y"])
            columns["polygon"].append(row.get("polygon", i))
            columns["object"].append(row.get("object", 0))
            columns["mask"].append(int(row["mask"]))
            columns["area"].append(row["area"])
            columns["zmin"].append(row.get("zmin", z))
            columns["zmax"].append(row.get("zmax", row.get("zmin", z)))
            columns["color"].append(row["color"])
            columns["opacity"].append(row.get("opacity", 1.0))
        columns["mask"] = np.array(columns["mask"], dtype=np.uint64)
        columns["color"] = np.array(columns["color"], dtype=np.float64).reshape(-1, 3)
        return cls(**columns)


_INTEGER_FIELDS = ("x", "y", "polygon", "object")


def _integer_array(name: str, value: object) -> np.ndarray:
    array = np.array(value)
    if array.size and not np.issubdtype(array.dtype, np.integer):
        raise TypeError(f"{name!r} must hold integers; got dtype {array.dtype}")
    return array.astype(np.int64)


def _mask_array(value: object) -> np.ndarray:
    array = np.array(value)
    if array.size and not np.issubdtype(array.dtype, np.integer):
        raise TypeError(f"'mask' must hold unsigned integers; got dtype {array.dtype}")
    if array.size and array.dtype.kind == "i" and (array < 0).any():
        row = int(np.flatnonzero(array.ravel() < 0)[0])
        raise ValueError(f"'mask'[{row}] = {array.ravel()[row]} is negative")
    return array.astype(np.uint64)


def _float_array(name: str, value: object) -> np.ndarray:
    try:
        array = np.array(value, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name!r} must be an array of numbers: {error}") from None
    check_rows(name, array, ~np.isfinite(array), "is not finite")
    return array


def check_layout(layout: object) -> tuple[int, int]:
    """(cols, rows) from a pair of positive ints or a string "CxR", at most 64 sub-samples."""
    if isinstance(layout, str):
        try:
            layout = tuple(int(v) for v in layout.lower().split("x"))
        except ValueError:
            raise ValueError(f"'layout' must be (cols, rows) or 'CxR'; got {layout!r}") from None
    if (
        not isinstance(layout, tuple | list)
        or len(layout) != 2
        or not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in layout)
    ):
        raise ValueError(f"'layout' must be (cols, rows) or 'CxR'; got {layout!r}")
    cols, rows = int(layout[0]), int(layout[1])
    if cols < 1 or rows < 1 or cols * rows > MAX_MASK_BITS:
        raise ValueError(f"'layout' must have 1..{MAX_MASK_BITS} sub-samples; got {cols}x{rows}")
    return cols, rows


@dataclass(frozen=True)
class ABufferResult:
    """The result of `resolve`.

    Attributes
    ----------
    image : (height, width, 3) ndarray of float64
        The packed colors, the background mixed in.
    alpha : (height, width) ndarray of float64
        Packed coverage: 1 - the background's share of each pixel.
    stats : ABufferStats
        Counts of what ran, and which path.
    table : FragmentTable
        The fragment lists after the last insertion (empty in flawed mode).
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    image: np.ndarray
    alpha: np.ndarray
    stats: ABufferStats
    table: FragmentTable
    trace: Trace | None = None

    def pixel(self, x: int, y: int) -> tuple[FragmentRecord, ...]:
        """Pixel (x, y)'s fragment list, nearest first (a simple pixelstruct: one record)."""
        height, width = self.alpha.shape
        if not (0 <= x < width and 0 <= y < height):
            raise ValueError(f"pixel ({x}, {y}) is outside the {width}x{height} raster")
        return self.table.pixel(x, y)


def resolve(
    fragments: Fragments,
    width: int,
    height: int,
    *,
    layout: object = (8, 8),
    weights: str = "area",
    background: object = (0.0, 0.0, 0.0),
    mode: str = "abuffer",
    merge: str = "none",
    trace: object = None,
) -> ABufferResult:
    """Insert fragments into the a-buffer in drawing order and pack every pixel.

    Parameters
    ----------
    fragments : Fragments
        The fragments, in drawing order.
    width, height : int
        Raster size in pixels; every fragment's pixel must lie inside.
    layout : (cols, rows) or "CxR"
        The sub-sample grid of the masks, at most 64 bits.
    weights : {"area", "mask"}
        How the packer measures covered regions: the thesis' bit counts, or
        the exact areas where a fragment is unobscured (see Notes).
    background : (3,) float
        The color behind everything.
    mode : {"abuffer", "flawed"}
        The a-buffer, or the coverage-blending z-buffer of thesis §6.3.
    merge : {"none", "object"}
        "object" first merges, in each pixel, the fragments of one object
        whose depth ranges overlap or abut (Carpenter's per-object merge:
        masks or-ed, areas summed, colors weighted by area; `merge_by_object`),
        which keeps lists short on smooth meshes; "none" (default) inserts
        every fragment as given. Counted in ``stats.fragments_object_merged``.
    trace : None, True, or Tracer
        None runs the compiled kernel (the reference while `scanviz.steps`
        has a replaced step); a tracer (True for a new `Recorder`)
        runs the traced reference: ``fragment_inserted``, ``fragments_merged``,
        ``fragments_discarded`` and ``pixel_packed`` (or ``coverage_blended``).

    Returns
    -------
    ABufferResult

    Notes
    -----
    A fragment is complete when its mask is full. Fragments combine when they
    come from the same object, have the same color and opacity (within 1e-12),
    neither is complete and their masks together are full. The packer recurses
    over each list, nearest first, on regions (mask M_Q, weight Q) starting at
    (full, 1): M_A = M_Q AND M_i, next M_Q = M_Q AND NOT M_i. With
    ``weights="mask"`` A = popcount(M_A) / n. With ``weights="area"``:
    A = Q for a complete fragment; A = min(area_i, Q) when the fragment is
    unobscured (M_i within M_Q, or M_i empty and M_Q full); else
    A = Q * popcount(M_A) / popcount(M_Q) (0 if M_Q is empty); next Q = Q - A.
    So one fragment covers exactly its area, and polygons sharing an edge
    pack to coverage 1 with no seam. Derivation in docs/abuffer.md.

    Examples
    --------
    Thesis Fig. 6.7: red covers the left half in front, green the bottom half
    behind, on blue: 50% red, 25% green, 25% blue.

    >>> left, bottom = 0x0F0F0F0F0F0F0F0F, 0x00000000FFFFFFFF
    >>> f = Fragments.from_rows([
    ...     dict(x=0, y=0, mask=left, area=0.5, z=0.1, color=(1, 0, 0)),
    ...     dict(x=0, y=0, mask=bottom, area=0.5, z=0.2, color=(0, 1, 0)),
    ... ])
    >>> result = resolve(f, 1, 1, background=(0, 0, 1))
    >>> result.image[0, 0].tolist(), float(result.alpha[0, 0])
    ([0.5, 0.25, 0.25], 0.75)
    >>> result.stats.pixels_list, [r.z for r in result.pixel(0, 0)]
    (1, [0.1, 0.2])
    """
    if not isinstance(fragments, Fragments):
        raise TypeError(f"'fragments' must be a Fragments; got {type(fragments).__name__}")
    width, height = check_raster_size(width, height)
    cols, rows = check_layout(layout)
    check_choice("weights", weights, WEIGHTS)
    check_choice("mode", mode, MODES)
    check_choice("merge", merge, MERGES)
    background = _float_array("background", background)
    if background.shape != (3,):
        raise ValueError(f"'background' must be an (r, g, b) triple; got shape {background.shape}")
    tracer = as_tracer(trace)
    full = (1 << (cols * rows)) - 1
    _check_fragments_fit(fragments, width, height, full)
    check_memory(
        width * height * RESOLVE_PIXEL_BYTES + fragments.count * RESOLVE_FRAGMENT_BYTES,
        f"resolving {fragments.count} fragments on a {width}x{height} a-buffer",
    )
    object_merged = 0
    if merge == "object":
        fragments, object_merged = merge_by_object(fragments, width, height, full)
    if tracer is None and not steps.replaced():  # the kernel has no step table
        result = pixelstruct_compiled.resolve_compiled(
            fragments, width, height, full, cols * rows, weights, background, mode
        )
    else:
        result = pixelstruct.resolve_reference(
            fragments, width, height, full, cols * rows, weights, background, mode, tracer
        )
    stats = result.stats
    stats.pixels = width * height
    stats.mode, stats.weights = mode, weights
    stats.fragments_object_merged = object_merged
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return ABufferResult(result.image, result.alpha, stats, result.table, recorded)


def _check_fragments_fit(fragments: Fragments, width: int, height: int, full: int) -> None:
    for name, size in (("x", width), ("y", height)):
        array = getattr(fragments, name)
        check_rows(
            name, array, (array < 0) | (array >= size), f"is not in 0..{size - 1} (the raster)"
        )
    outside = fragments.mask & ~np.uint64(full)
    check_rows("mask", fragments.mask, outside != 0, f"has bits outside the layout's {full:#x}")

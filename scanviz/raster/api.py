"""Public entry points of the raster stage: validate once, then run the reference or the kernel."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import steps
from ..conventions import (
    ARITHMETICS,
    MAX_SUBPIXEL_BITS,
    RULES,
    SAMPLE_MODES,
    check_choice,
    check_raster_size,
    check_subpixel_bits,
    short_repr,
)
from ..geometry import Polygon, as_coordinates, check_three_distinct, nested_array
from ..limits import check_memory, current_memory_limit
from ..trace import Recorder, Trace, Tracer
from . import fill_batched, scan_compiled
from .fixed import SnappedPolygon, exact_bits, snap, snap_units
from .scanline import ScanStats, scan_reference

COUNT_BYTES = 4  # an int32 coverage count
SPAN_BYTES = 3 * 8  # a (y, x_start, x_end) row of int64
# A compiled scan holds its span buffer, the doubled copy while it grows, then the result.
SPAN_BUFFER_BYTES = 3 * SPAN_BYTES
VERTEX_BYTES = 20 * 8  # per vertex: snapped units, the edge table, the active edge table
# Active-edge steps (an edge on a scanned row) `scan_convert` takes before it refuses: the
# walk costs O(rows x active edges) (plus a sort of each row's AET), which the output need not
# bound (edges left or right of the raster are walked all the same). About 5 s compiled.
MAX_CROSSINGS = 2**31


@dataclass(frozen=True)
class ScanResult:
    """The result of `scan_convert`.

    Attributes
    ----------
    mask : (height, width) ndarray of bool
        Covered samples, row 0 at the bottom.
    spans : (K, 3) ndarray of int64
        Rows (y, x_start, x_end), half-open in x, sorted by y then x_start.
    stats : ScanStats
        What ran: rows scanned, spans, edges, sort swaps, which path.
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    mask: np.ndarray
    spans: np.ndarray
    stats: ScanStats
    trace: Trace | None


def as_tracer(trace: object) -> Tracer | None:
    """`trace` as a Tracer: None stays None, True makes a Recorder that keeps everything."""
    if trace is None or trace is False:
        return None
    if trace is True:
        return Recorder()
    if not isinstance(trace, Tracer):
        raise TypeError(
            f"'trace' must be None, True or a Tracer (wants/emit); got {short_repr(trace)}"
        )
    return trace


def paint_spans(spans: np.ndarray, width: int, height: int) -> np.ndarray:
    """The (height, width) bool mask of a (K, 3) span array."""
    return scan_compiled.paint_mask(np.asarray(spans, dtype=np.int64).reshape(-1, 3), width, height)


def scan_snapped(
    snapped: SnappedPolygon,
    width: int,
    height: int,
    *,
    rule: str = "nonzero",
    arithmetic: str = "exact",
    trace: Tracer | None = None,
    reserved: int = 0,
) -> tuple[np.ndarray, ScanStats]:
    """Spans and stats of a snapped polygon: the kernel when untraced and int64, else the reference.

    The compiled path counts every `ScanStats` field but `swaps`, which stays 0:
    it sorts the active edges by ceil(x), which gives the same spans with other swaps.
    Its span buffer grows as needed within the memory limit less `reserved`
    bytes (what the caller will allocate next to the spans); past that it
    raises `scanviz.limits.ResourceLimitError`.
    """
    if trace is not None or not snapped.compilable or steps.replaced():
        return scan_reference(snapped, width, height, rule=rule, arithmetic=arithmetic, trace=trace)
    max_spans = max(current_memory_limit() - reserved, 0) // SPAN_BUFFER_BYTES
    spans, (edges, kept, rows, max_active), refused = scan_compiled.scan_spans(
        np.array(snapped.units),  # a writable copy: one compiled signature for every caller
        snapped.offsets,
        snapped.scale,
        width,
        height,
        rule == "evenodd",
        arithmetic == "exact",
        np.float32 if arithmetic == "float32" else np.float64,
        max_spans,
    )
    if refused:
        check_memory(
            refused * SPAN_BUFFER_BYTES + reserved,
            f"scan conversion: at least {refused} spans on a {width}x{height} raster",
        )
    stats = ScanStats(
        edges=edges,
        kept_for_topology=kept,
        rows_scanned=rows,
        spans=len(spans),
        max_active=max_active,
        path="compiled",
    )
    return spans, stats


def scan_convert(
    polygon: object,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
    arithmetic: str = "exact",
    trace: object = None,
) -> ScanResult:
    """Scan-convert a polygon with an edge table and active edge table.

    Parameters
    ----------
    polygon : Polygon or array_like
        Anything `Polygon` accepts: one (N, 2) contour or a list of contours.
    width, height : int
        Raster size in pixels; rows and columns outside it are never scanned.
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    rule : {"nonzero", "evenodd"}
        Fill rule.
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None decides the float64 input exactly.
    arithmetic : {"exact", "float32", "float64"}
        Exact integer DDA, or the textbook ``x += dx/dy`` in floating point.
    trace : None, True, or Tracer
        None runs the compiled kernel and records nothing; a tracer (True for
        a new `Recorder`) runs the traced reference.

    Returns
    -------
    ScanResult
        ``stats.path`` is "compiled" or "reference". The compiled kernel (used
        without a tracer whenever the grid fits int64, i.e. ``subpixel_bits``
        is not None or the input needs at most 16 bits) gives the reference's
        spans and stats, except ``stats.swaps``, which it leaves at 0.

    Raises
    ------
    TypeError
        If a coordinate is not a real number (bool, str, complex, object), or
        an option has the wrong type.
    ValueError
        If `polygon` is malformed (see `Polygon`: shape, non-finite values,
        coordinates beyond +-2**20, fewer than 3 distinct vertices), or an
        option is unknown or out of range; or, on the compiled path, if the
        edges cross more than `MAX_CROSSINGS` (2**31) sample rows in all
        (`active_crossings`), refused before the walk.
    scanviz.limits.ResourceLimitError
        (a ValueError) If the mask (width * height bytes) and the spans (24
        bytes each) would exceed the memory limit (`scanviz.limits`).

    Examples
    --------
    >>> result = scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3)
    >>> result.mask.astype(int)[::-1]  # top row first
    array([[0, 0, 0, 1, 0],
           [0, 0, 1, 1, 0],
           [1, 1, 1, 1, 0]])
    >>> result.spans.tolist(), result.stats.path
    ([[0, 0, 4], [1, 2, 4], [2, 3, 4]], 'compiled')
    """
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    check_choice("rule", rule, RULES)
    check_choice("arithmetic", arithmetic, ARITHMETICS)
    tracer = as_tracer(trace)
    mask_bytes = width * height
    check_memory(
        mask_bytes + VERTEX_BYTES * polygon.vertex_count,
        f"scan_convert: a {width}x{height} bool mask",
    )
    snapped = snap(polygon, sample, subpixel_bits)
    if snapped.compilable:
        check_crossings(snapped, width, height)
    spans, stats = scan_snapped(
        snapped, width, height, rule=rule, arithmetic=arithmetic, trace=tracer, reserved=mask_bytes
    )
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return ScanResult(paint_spans(spans, width, height), spans, stats, recorded)


def active_crossings(snapped: SnappedPolygon, height: int) -> int:
    """The active-edge steps of the ET/AET walk: per edge, the raster rows it crosses (O(n)).

    >>> from scanviz.raster.fixed import snap
    >>> active_crossings(snap(Polygon([(0, 0), (4, 0), (4, 3), (0, 3)])), 10)  # 2 edges, 3 rows
    6
    """
    units, scale = np.asarray(snapped.units, np.int64), snapped.scale
    following = np.empty_like(units)
    for start, stop in zip(snapped.offsets[:-1], snapped.offsets[1:], strict=True):
        following[start:stop] = np.roll(units[start:stop], -1, axis=0)
    low = np.minimum(units[:, 1], following[:, 1])
    high = np.maximum(units[:, 1], following[:, 1])
    rows = np.clip(-(-high // scale), 0, height) - np.clip(-(-low // scale), 0, height)
    return int(rows.sum())


def check_crossings(snapped: SnappedPolygon, width: int, height: int) -> None:
    """Refuse, with the figure and the limit, a walk of over `MAX_CROSSINGS` active-edge steps."""
    crossings = active_crossings(snapped, height)
    if crossings > MAX_CROSSINGS:
        raise ValueError(
            f"scan_convert: the polygon's {len(snapped.units)} edges cross {crossings:.3g} "
            f"sample rows of the {width}x{height} raster (limit {MAX_CROSSINGS}): the scan "
            "steps every active edge on every row, also edges off the raster's sides; "
            "use fewer vertices or fewer rows"
        )


def _as_batch(polygons: object) -> np.ndarray | None:
    """`polygons` as a checked (P, N, 2) float64 array if it is one block of N >= 3 vertices each."""
    raw = nested_array(polygons)
    if raw is None or raw.ndim != 3 or raw.shape[1] < 3 or raw.shape[2] != 2:
        return None
    return as_coordinates(raw, "'polygons'", ("P", "N", 2))


def _snap_batch(batch: np.ndarray, sample: str, bits: int | None) -> tuple[np.ndarray, int] | None:
    """(units, scale) of a (T, N, 2) batch snapped as `fixed.snap` does; None if int64 cannot hold it."""
    if bits is None:
        bits = exact_bits(batch)
        if bits > MAX_SUBPIXEL_BITS:
            return None
    units = snap_units(batch, sample, bits)
    return units, 2 ** (bits + 1)


def _as_polygon(polygon: object, index: int) -> Polygon:
    try:
        return Polygon(polygon)
    except (TypeError, ValueError) as error:
        raise type(error)(f"'polygons'[{index}]: {error}") from None


def _pack(snapped: list[SnappedPolygon]) -> tuple[np.ndarray, ...]:
    """Polygons as flat arrays for `fill_batched.fill_polygons`.

    Returns (units, contour_offsets, polygon_contours, scales): all vertices,
    all contour starts plus the end, and polygon p owning the contours
    contour_offsets[polygon_contours[p] : polygon_contours[p + 1] + 1].
    """
    offsets, polygon_contours, base = [], [0], 0
    for s in snapped:
        offsets.append(s.offsets[:-1] + base)
        polygon_contours.append(polygon_contours[-1] + len(s.offsets) - 1)
        base += len(s.units)
    return (
        np.concatenate([np.zeros((0, 2), np.int64)] + [s.units for s in snapped]),
        np.concatenate(offsets + [[base]]).astype(np.int64),
        np.array(polygon_contours, dtype=np.int64),
        np.array([s.scale for s in snapped], dtype=np.int64),
    )


def fill_polygons(
    polygons: object,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    rule: str = "nonzero",
    subpixel_bits: int | None = 8,
) -> np.ndarray:
    """Count how many polygons cover each sample, all in one compiled pass.

    Parameters
    ----------
    polygons : iterable of Polygon or array_like
        Each item is anything `Polygon` accepts (a (P, N, 2) array gives P
        polygons).
    width, height : int
        Raster size in pixels.
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    rule : {"nonzero", "evenodd"}
        Fill rule, per polygon.
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None decides the float64 input
        exactly (polygons needing more than 16 bits go through the reference).

    Returns
    -------
    (height, width) ndarray of int32
        The number of polygons covering each sample: the sum of their
        `scan_convert` masks (exact arithmetic), row 0 at the bottom.

    Raises
    ------
    TypeError
        If `polygons` is not iterable, an item is not a polygon, a coordinate
        is not a real number, or an option has the wrong type.
    ValueError
        If an item is not a valid `Polygon` (the message names it as
        ``'polygons'[i]``), or an option is unknown or out of range.
    scanviz.limits.ResourceLimitError
        (a ValueError) If the (height, width) int32 raster and the working
        memory would exceed the memory limit (`scanviz.limits`).

    Examples
    --------
    >>> square = [(0, 0), (3, 0), (3, 2), (0, 2)]
    >>> fill_polygons([square, [(1, 0), (4, 0), (4, 1), (1, 1)]], 4, 2)[::-1]
    array([[1, 1, 1, 0],
           [1, 2, 2, 1]], dtype=int32)
    """
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    check_choice("rule", rule, RULES)
    bits = check_subpixel_bits(subpixel_bits)
    what = f"fill_polygons: a {width}x{height} int32 coverage raster"
    check_memory(COUNT_BYTES * width * height, what)
    batch = _as_batch(polygons)
    if batch is not None:  # P one-contour polygons: validate at once
        check_memory(_batch_bytes(batch, width, height), what)
        few = np.flatnonzero(~scan_compiled.three_distinct(batch))
        if few.size:
            check_three_distinct(batch[few[0]], f"'polygons'[{few[0]}]: contour 0")
        snapped_batch = _snap_batch(batch, sample, bits)
        if snapped_batch is not None:
            (count, size, _), (units, scale) = batch.shape, snapped_batch
            return fill_batched.fill_polygons(
                units.reshape(-1, 2),
                np.arange(0, count * size + 1, size),
                np.arange(count + 1),
                np.full(count, scale),
                width,
                height,
                rule == "evenodd",
            )
    try:
        items = list(polygons)  # type: ignore[call-overload]
    except TypeError:
        raise TypeError(
            f"'polygons' must be an iterable of polygons; got {short_repr(polygons)}"
        ) from None
    snapped = [snap(_as_polygon(p, i), sample, bits) for i, p in enumerate(items)]
    rasters = 1 + any(not s.compilable for s in snapped)  # the reference's spans get their own
    check_memory(COUNT_BYTES * width * height * rasters + 16 * height, what)
    image = fill_batched.fill_polygons(
        *_pack([s for s in snapped if s.compilable]), width, height, rule == "evenodd"
    )
    # A grid finer than int64 takes needs the reference's Python ints.
    spans = [scan_reference(s, width, height, rule=rule)[0] for s in snapped if not s.compilable]
    if spans:
        image += scan_compiled.count_spans(np.concatenate(spans), width, height)
    return image


def _batch_bytes(batch: np.ndarray, width: int, height: int) -> int:
    """Memory of counting a (T, N, 2) batch: the int32 raster, row marks, snapped copies."""
    return COUNT_BYTES * width * height + 16 * height + 3 * batch.nbytes


def rasterize_triangles(
    triangles: object,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    subpixel_bits: int | None = 8,
) -> np.ndarray:
    """Count how many triangles cover each sample, all in one compiled pass.

    Each triangle covers exactly the samples `scan_convert` covers for it
    (both fill rules agree on a triangle), so shared edges are covered once.

    Parameters
    ----------
    triangles : (T, 3, 2) array_like of float
        Vertices in pixels, y up, within +-2**20. Any orientation; zero-area
        triangles cover nothing.
    width, height : int
        Raster size in pixels.
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None decides the float64 input
        exactly (through the reference when that needs more than 16 bits).

    Returns
    -------
    (height, width) ndarray of int32
        The number of triangles covering each sample, row 0 at the bottom.

    Raises
    ------
    TypeError
        If a coordinate is not a real number (bool, str, complex, object), or
        an option has the wrong type.
    ValueError
        If `triangles` is not (T, 3, 2) (a ragged one names the first item of
        the wrong length), or has a non-finite coordinate or one beyond
        +-2**20 (the message names the first such triangle and vertex).
    scanviz.limits.ResourceLimitError
        (a ValueError) If the (height, width) int32 raster and the working
        memory would exceed the memory limit (`scanviz.limits`).

    Examples
    --------
    >>> halves = [[(0, 0), (4, 0), (4, 3)], [(0, 0), (4, 3), (0, 3)]]
    >>> rasterize_triangles(halves, 5, 3)[::-1]
    array([[1, 1, 1, 1, 0],
           [1, 1, 1, 1, 0],
           [1, 1, 1, 1, 0]], dtype=int32)
    """
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    bits = check_subpixel_bits(subpixel_bits)
    what = f"rasterize_triangles: a {width}x{height} int32 coverage raster"
    check_memory(COUNT_BYTES * width * height, what)
    vertices = as_coordinates(triangles, "'triangles'", ("T", 3, 2))
    check_memory(_batch_bytes(vertices, width, height), what)
    snapped = _snap_batch(vertices, sample, bits)
    if snapped is None:  # a grid finer than int64 takes: the reference, triangle by triangle
        spans = [
            scan_reference(snap(Polygon(triangle), sample, None), width, height)[0]
            for triangle in vertices[
                scan_compiled.three_distinct(vertices)
            ]  # the others have no area
        ]
        return scan_compiled.count_spans(
            np.concatenate(spans + [np.zeros((0, 3), np.int64)]), width, height
        )
    return scan_compiled.rasterize_triangles(*snapped, width, height)

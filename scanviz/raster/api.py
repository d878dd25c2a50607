"""Public entry points of the raster stage: validate once, then run the reference or the kernel."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..conventions import ARITHMETICS, RULES, SAMPLE_MODES, check_choice, check_raster_size
from ..geometry import Polygon
from ..trace import Recorder, Trace, Tracer
from .fixed import snap
from .scanline import ScanStats, scan_reference


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
        raise TypeError(f"'trace' must be None, True or a Tracer (wants/emit); got {trace!r}")
    return trace


def paint_spans(spans: np.ndarray, width: int, height: int) -> np.ndarray:
    """The (height, width) bool mask of a (K, 3) span array."""
    mask = np.zeros((height, width), dtype=bool)
    for y, start, end in spans.tolist():
        mask[y, start:end] = True
    return mask


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

    Examples
    --------
    >>> result = scan_convert([(0, 0), (4, 0), (4, 3)], 5, 3)
    >>> result.mask.astype(int)[::-1]  # top row first
    array([[0, 0, 0, 1, 0],
           [0, 0, 1, 1, 0],
           [1, 1, 1, 1, 0]])
    >>> result.spans.tolist()
    [[0, 0, 4], [1, 2, 4], [2, 3, 4]]
    """
    polygon = Polygon(polygon)
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    check_choice("rule", rule, RULES)
    check_choice("arithmetic", arithmetic, ARITHMETICS)
    tracer = as_tracer(trace)
    snapped = snap(polygon, sample, subpixel_bits)
    spans, stats = scan_reference(
        snapped, width, height, rule=rule, arithmetic=arithmetic, trace=tracer
    )
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return ScanResult(paint_spans(spans, width, height), spans, stats, recorded)

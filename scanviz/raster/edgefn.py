"""Triangle rasterization with edge functions (Pineda 1988; tinyrenderer lesson 2).

Edge i runs from vertex i to vertex i + 1 (mod 3) and has the edge function

    E_i(p) = (X1 - X0) * (py - Y0) - (Y1 - Y0) * (px - X0) = a * px + b * py + c,
    a = Y0 - Y1,  b = X1 - X0,  c = X0 * Y1 - X1 * Y0,

which is the slides' implicit line f(x, y): positive left of the edge, zero on
it. E_0 + E_1 + E_2 is the doubled signed area everywhere, so vertex i has the
barycentric weight E of its opposite edge over the doubled area.

A sample is covered when it lies on the inner side of all three edges. A
sample exactly on an edge (E = 0) is decided as the point p + (eps, eps**2)
(DESIGN §2), whose E has the sign of the first nonzero of (E(p), a, b): with
the inner side counted positive, an edge owns its samples when (a, b) starts
positive -- the left edges and the lower horizontal edge. So a sample is in
iff ``orientation * E_i >= bias_i`` for every edge, bias 0 for an owning edge
and 1 otherwise. All coordinates are integers on the grid of
`scanviz.raster.fixed`, so every decision is exact.

The edge function of one edge and its ownership rule are the replaceable
steps ``edge_function`` and ``owns_boundary`` (`scanviz.steps`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import steps
from ..conventions import (
    SAMPLE_MODES,
    check_choice,
    check_index,
    check_raster_size,
    check_subpixel_bits,
)
from ..geometry import Polygon, as_coordinates
from ..limits import check_memory
from ..trace import Recorder, Trace
from ..trace.events import EdgeFunction, EdgeFunctionRow, TriangleSetup
from .api import as_tracer
from .fixed import snap

INT64_LIMIT = 2**63
BLOCK_SAMPLES = 2**16  # samples evaluated per numpy block, to bound memory
SAMPLE_BYTES = 2 * (8 + 8 + 3 * 8)  # ys, xs, barycentric of a covered sample; once more joined


@dataclass(frozen=True)
class TriangleSamples:
    """The samples a triangle covers (`triangle_samples`).

    Attributes
    ----------
    ys, xs : (K,) ndarray of int64
        Pixel coordinates of the covered samples, sorted by y then x.
    barycentric : (K, 3) ndarray of float64
        Weights of the three snapped vertices at each sample; they sum to 1.
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    ys: np.ndarray
    xs: np.ndarray
    barycentric: np.ndarray
    trace: Trace | None


@steps.step(
    "edge_function",
    takes="an edge's start (x0, y0) and end (x1, y1), ints on the sub-pixel grid",
    returns="(a, b, c) with E(p) = a px + b py + c: a = y0 - y1, b = x1 - x0, c = x0 y1 - x1 y0",
)
def edge_function(start: tuple[int, int], end: tuple[int, int]) -> tuple[int, int, int]:
    """The edge function of the directed edge start -> end: positive on its left, zero on it.

    >>> a, b, c = edge_function((0, 0), (4, 0))
    >>> (a, b, c), a * 1 + b * 2 + c  # (1, 2) lies left of the edge
    ((0, 4, 0), 8)
    """
    (x0, y0), (x1, y1) = start, end
    return y0 - y1, x1 - x0, x0 * y1 - x1 * y0


@steps.step(
    "owns_boundary",
    takes="an edge's (a, b) and the triangle's orientation (+1 counter-clockwise, -1 clockwise)",
    returns="whether a sample on the edge (E = 0) is inside: orientation * (a if a else b) > 0",
)
def owns_boundary(a: int, b: int, orientation: int) -> bool:
    """The tie rule: the sample p on the edge is decided as p + (eps, eps**2), eps > 0 infinitesimal.

    E(p + (eps, eps**2)) = a eps + b eps**2 has the sign of a, or of b on a
    horizontal edge (a = 0); the sample is in iff that sign is the inner side's.

    >>> owns_boundary(4, 0, 1), owns_boundary(0, 4, 1), owns_boundary(-4, -4, 1)  # left, bottom, right
    (True, True, False)
    """
    return orientation * (a if a else b) > 0


def _edge_function(start: tuple[int, int], end: tuple[int, int], orientation: int) -> EdgeFunction:
    a, b, c = steps.get("edge_function")(start, end)
    return EdgeFunction(a, b, c, steps.get("owns_boundary")(a, b, orientation))


def _sample_range(values: list[int], scale: int, size: int) -> tuple[int, int]:
    """Pixels [start, stop) whose samples lie in [min(values), max(values)), clipped to 0..size."""
    start = min(max(-(-min(values) // scale), 0), size)
    return start, max(min(-(-max(values) // scale), size), start)


def _exact_dtype(edges: list[EdgeFunction], bbox: tuple[int, int, int, int], scale: int):
    """int64 when nothing evaluated over the bbox can overflow it, else Python ints (object).

    Numpy sees E at the first sample of a row, the per-sample steps a * scale
    and b * scale, their multiples across the box, and sums of these. E is
    affine, so its extremes over the box are at the corners, and
    |corner E| + |a * scale| * width + |b * scale| * height bounds them all.
    """
    x_lo, y_lo, x_hi, y_hi = bbox
    corners = [(x * scale, y * scale) for x in (x_lo, x_hi - 1) for y in (y_lo, y_hi - 1)]
    largest = max(
        max(abs(e.at(*p)) for p in corners)
        + abs(e.a * scale) * (x_hi - x_lo)
        + abs(e.b * scale) * (y_hi - y_lo)
        for e in edges
    )
    return np.int64 if largest < INT64_LIMIT else object


def triangle_samples(
    triangle: object,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    trace: object = None,
    polygon: int = 0,
) -> TriangleSamples:
    """The samples a triangle covers, found by testing its three edge functions.

    Parameters
    ----------
    triangle : (3, 2) array_like
        Vertices in pixels, y up, within +-2**20; either winding.
    width, height : int
        Raster size; only samples of the triangle's bounding box inside it are tested.
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None decides the float64 input exactly.
    trace : None, True, or Tracer
        Receives ``triangle_setup`` and one ``edge_function_row`` per tested row
        (True records them into ``result.trace``).
    polygon : int
        Index recorded in the events (for scenes of many triangles).

    Returns
    -------
    TriangleSamples
        Covered samples as ``ys``, ``xs`` and their ``barycentric`` weights.
        Zero-area triangles cover nothing; one with a repeated vertex records no events.

    Raises
    ------
    TypeError
        If a coordinate is not a real number (bool, str, complex, object), or
        `width`, `height`, `subpixel_bits`, `polygon` or `trace` has the wrong type.
    ValueError
        If `triangle` is not (3, 2), has a non-finite coordinate or one beyond
        +-2**20, or an option is unknown or out of range (`polygon` < 0).
    scanviz.limits.ResourceLimitError
        (a ValueError) If the covered samples could need more than the memory
        limit (`scanviz.limits`): 80 bytes a sample, up to the triangle's area
        plus half its perimeter plus one, within its clipped bounding box.

    Notes
    -----
    Agrees sample for sample with `scan_convert` on the same triangle: both
    apply the ownership rule of DESIGN §2 to the same snapped integers.

    With a tracer, or while a step of `scanviz.steps` is replaced, every
    sample of the clipped bounding box is tested, as the textbook does, and a
    tracer receives each row's edge function values. Otherwise the fast path
    skips the samples outside each row's exact x-range: the integer solution
    of ``orientation * E_i >= bias_i`` for the three edges at that row. It evaluates the same integers at the samples it keeps,
    so it returns the same samples and bit-identical weights, in time and
    memory proportional to the covered samples (a sliver across a 65536²
    box: milliseconds rather than minutes).

    Examples
    --------
    >>> cover = triangle_samples([(0, 0), (4, 0), (0, 3)], 5, 4)
    >>> image = np.zeros((4, 5), dtype=int)
    >>> image[cover.ys, cover.xs] = 1
    >>> image[::-1]  # top row first
    array([[0, 0, 0, 0, 0],
           [1, 1, 0, 0, 0],
           [1, 1, 1, 0, 0],
           [1, 1, 1, 1, 0]])
    >>> cover.barycentric[(cover.xs == 2) & (cover.ys == 0)]  # halfway along edge 0
    array([[0.5, 0.5, 0. ]])
    """
    vertices = as_coordinates(triangle, "'triangle'", (3, 2))
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    check_subpixel_bits(subpixel_bits)
    polygon = check_index("polygon", polygon)
    tracer = as_tracer(trace)
    if len(np.unique(vertices, axis=0)) == 3:
        snapped = snap(Polygon(vertices), sample, subpixel_bits)
        ys, xs, weights = _scan_bbox(snapped, width, height, tracer, polygon)
    else:  # a point or a segment: zero area, nothing to set up
        ys, xs, weights = _no_samples()
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return TriangleSamples(ys, xs, weights, recorded)


def _scan_bbox(snapped, width, height, tracer, polygon):
    """Set up the edge functions and find the samples of the clipped bounding box they cover."""
    scale = snapped.scale
    units = [(int(x), int(y)) for x, y in snapped.units]
    (x0, y0), (x1, y1), (x2, y2) = units
    area2 = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)  # E_0 at vertex 2
    orientation = (area2 > 0) - (area2 < 0)
    edges = [_edge_function(units[i], units[(i + 1) % 3], orientation) for i in range(3)]
    # Samples from the lowest vertex up to, not including, the highest: one there is outside.
    x_lo, x_hi = _sample_range([u[0] for u in units], scale, width)
    y_lo, y_hi = _sample_range([u[1] for u in units], scale, height)
    if orientation == 0 or x_lo == x_hi or y_lo == y_hi:
        x_hi, y_hi = x_lo, y_lo  # nothing to test
    bbox = (x_lo, y_lo, x_hi, y_hi)
    check_memory(
        SAMPLE_BYTES * _most_samples(units, area2, scale, bbox),
        f"triangle_samples: the samples of a triangle on a {width}x{height} raster",
    )
    if tracer is not None and tracer.wants("triangle_setup", polygon=polygon):
        tracer.emit(_setup_event(snapped, units, edges, area2, orientation, bbox, polygon))
    if x_lo == x_hi:
        return _no_samples()
    dtype = _exact_dtype(edges, bbox, scale)
    biases = [0 if e.owns_boundary else 1 for e in edges]
    if tracer is None and not steps.replaced():
        found = _scan_row_ranges(edges, biases, orientation, scale, bbox, dtype, area2)
    else:
        found = _scan_blocks(edges, biases, orientation, scale, bbox, dtype, area2, tracer, polygon)
    return tuple(np.concatenate(part) for part in zip(*found, strict=True))


def _scan_blocks(edges, biases, orientation, scale, bbox, dtype, area2, tracer, polygon):
    """The textbook traversal: test every sample of the box, a block of rows at a time."""
    x_lo, y_lo, x_hi, y_hi = bbox
    columns = np.arange(x_hi - x_lo, dtype=dtype)[None, :]
    rows_per_block = max(1, BLOCK_SAMPLES // (x_hi - x_lo))
    found = []
    for row in range(y_lo, y_hi, rows_per_block):
        rows = np.arange(min(rows_per_block, y_hi - row), dtype=dtype)[:, None]
        # E at the block's first sample, plus a * scale per sample right, b * scale per row up.
        values = [
            e.at(x_lo * scale, row * scale) + e.a * scale * columns + e.b * scale * rows
            for e in edges
        ]
        # Inside iff each edge function, signed to the inner side, reaches its bias.
        inside = np.logical_and.reduce(
            [orientation * v >= bias for v, bias in zip(values, biases, strict=True)]
        )
        _emit_rows(tracer, polygon, row, x_lo, x_hi, values, inside)
        ys, xs = np.nonzero(inside)
        selected = [v[inside] for v in values]
        found.append((ys + row, xs + x_lo, _weights(selected, area2)))
    return found


def _scan_row_ranges(edges, biases, orientation, scale, bbox, dtype, area2):
    """Evaluate only the samples between each row's exact first and last inside sample.

    The ranges of a block of rows come from the edge functions at the rows'
    first samples; their samples are then evaluated about BLOCK_SAMPLES at a
    time, so memory is bounded by the output.
    """
    x_lo, y_lo, x_hi, y_hi = bbox
    found = []
    for row in range(y_lo, y_hi, BLOCK_SAMPLES):
        rows = np.arange(row - y_lo, min(row + BLOCK_SAMPLES, y_hi) - y_lo, dtype=dtype)
        # Each edge function at the rows' first samples, signed to the inner side, less its bias.
        margins = [
            orientation * (e.at(x_lo * scale, y_lo * scale) + e.b * scale * rows) - bias
            for e, bias in zip(edges, biases, strict=True)
        ]
        starts, counts = _inside_columns(edges, orientation, scale, margins, x_hi - x_lo)
        ends = np.cumsum(counts)
        cuts = np.searchsorted(ends, np.arange(BLOCK_SAMPLES, ends[-1], BLOCK_SAMPLES))
        for first, last in zip(np.r_[0, cuts], np.r_[cuts, len(rows)], strict=True):
            part = slice(first, last)
            found.append(
                _row_samples(
                    edges, scale, bbox, dtype, area2, rows[part], starts[part], counts[part]
                )
            )
    return found


def _inside_columns(edges, orientation, scale, margins, columns):
    """Per row, the first column k in 0..columns with margin + step * k >= 0 for all edges, and how many."""
    starts = np.zeros(len(margins[0]), np.int64)
    stops = np.full(len(margins[0]), columns, np.int64)
    for e, margin in zip(edges, margins, strict=True):
        step = orientation * e.a * scale  # the signed E's change per sample to the right
        if step > 0:  # inside from ceil(-margin / step) on
            starts = np.maximum(starts, np.clip(-(margin // step), 0, columns).astype(np.int64))
        elif step < 0:  # inside up to floor(margin / -step)
            stops = np.minimum(stops, np.clip(margin // -step + 1, 0, columns).astype(np.int64))
        else:  # parallel to the rows: the whole row or nothing
            stops = np.where(margin >= 0, stops, 0)
    return starts, np.maximum(stops - starts, 0)


def _row_samples(edges, scale, bbox, dtype, area2, rows, starts, counts):
    """The samples of `counts` columns from `starts` on each of `rows` (offsets in the box)."""
    x_lo, y_lo = bbox[:2]
    ys = np.repeat(rows, counts)
    xs = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts - starts, counts)
    values = [
        e.at(x_lo * scale, y_lo * scale) + e.a * scale * xs.astype(dtype) + e.b * scale * ys
        for e in edges
    ]
    return ys.astype(np.int64) + y_lo, xs + x_lo, _weights(values, area2)


def _most_samples(units, area2: int, scale: int, bbox: tuple[int, int, int, int]) -> int:
    """An upper bound on the samples a triangle covers within `bbox`.

    A closed convex region of area A and perimeter P holds at most
    A + P/2 + 1 lattice points; the clipped bounding box bounds them too.
    """
    x_lo, y_lo, x_hi, y_hi = bbox
    pixels = [(x / scale, y / scale) for x, y in units]  # int / int: no overflow on fine grids
    perimeter = sum(math.dist(pixels[i], pixels[(i + 1) % 3]) for i in range(3))
    lattice = abs(area2) / (2 * scale * scale) + perimeter / 2 + 1
    return int(min((x_hi - x_lo) * (y_hi - y_lo), math.ceil(lattice)))


def _weights(values: list[np.ndarray], area2: int) -> np.ndarray:
    """Barycentric weights from the edge functions at the samples: vertex i's is E_{i+1} / area2."""
    return _ratio(np.stack([values[1], values[2], values[0]], axis=1), area2)


def _ratio(numerators: np.ndarray, denominator: int) -> np.ndarray:
    """numerators / denominator as float64; Python ints are divided exactly (they may exceed floats)."""
    if numerators.dtype == object:
        return (numerators / denominator).astype(np.float64)
    return numerators.astype(np.float64) / float(denominator)  # |denominator| <= 3 * 2**63


def _no_samples() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return np.empty(0, np.int64), np.empty(0, np.int64), np.empty((0, 3))


def _setup_event(snapped, units, edges, area2, orientation, bbox, polygon) -> TriangleSetup:
    return TriangleSetup(
        polygon=polygon,
        vertices=tuple(
            (float(snapped.to_pixels(x)), float(snapped.to_pixels(y))) for x, y in units
        ),
        units=tuple(units),
        scale=snapped.scale,
        edges=tuple(edges),
        area2=area2,
        orientation=orientation,
        bbox=bbox,
    )


def _emit_rows(tracer, polygon, row, x_lo, x_hi, values, inside) -> None:
    if tracer is None:  # untraced, with a step replaced: the textbook traversal, no events
        return
    for r, covered in enumerate(inside):
        y = row + r
        if not tracer.wants("edge_function_row", polygon=polygon, y=y):
            continue
        cols = np.flatnonzero(covered)  # a triangle's row is one run of samples
        start, end = (x_lo + int(cols[0]), x_lo + int(cols[-1]) + 1) if cols.size else (x_lo, x_lo)
        row_values = tuple(int(v[r, 0]) for v in values)
        tracer.emit(EdgeFunctionRow(polygon, y, x_lo, x_hi, row_values, start, end))

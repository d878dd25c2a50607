"""The z-buffer (Catmull): polygons drawn in order, each sample keeps its nearest fragment.

The UMBC CMSC 435 slides' algorithm: a depth buffer starts at +inf; for each
polygon, for each sample it covers, compute the depth z of the polygon there;
if z < stored depth, store z, the polygon's index and its interpolated
values. Ties keep the earlier polygon. Coverage is exactly `scan_convert`'s
(nonzero rule), and depth and values are interpolated as in
`scanviz.raster.interpolate`. Only the visible fragment's values are kept:
shading runs afterwards on the final buffers (deferred shading).

Without a tracer the compiled kernel (`scanviz.visibility.zbuffer_compiled`) runs;
with one, or while a step of `scanviz.steps` is replaced, the traced
reference below, which takes its depth test from the step ``depth_test``.
They give identical depths and ids, and identical values (the same
formulas, compiled from the same source).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import steps
from ..conventions import (
    COORD_LIMIT,
    SAMPLE_MODES,
    check_choice,
    check_raster_size,
    check_rows,
    check_subpixel_bits,
)
from ..geometry import NOT_REAL_KINDS, plain_array
from ..limits import check_memory
from ..raster.api import as_tracer
from ..raster.fixed import SnappedPolygon, exact_bits, snap_units
from ..raster.interpolate import (
    emit_polygon_setup,
    interpolate_rows,
    perspective_divide,
    polygon_plane,
    polygon_reaches_raster,
    span_samples,
    vertex_channels,
)
from ..trace import Recorder, Trace
from ..trace.display import RichDisplay
from ..trace.events import DepthTest
from . import zbuffer_compiled

VALUE_LIMIT = 1e100  # bound on |z|, |values| and 1/w (and 1/w >= 1/VALUE_LIMIT): no overflow


def _float_array(name: str, value: object, ndim: int) -> np.ndarray:
    try:
        array = np.array(value, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{name!r} must be an array of numbers: {error}") from None
    if array.ndim != ndim:
        shape = "(M, 2)" if name == "xy" else ("(M,)" if ndim == 1 else "(M, K)")
        raise ValueError(f"{name!r} must be an {shape} array; got shape {array.shape}")
    return array


def _check_range(name: str, array: np.ndarray, low: float, high: float, rule: str) -> None:
    """Raise naming the first row of `array` not finite or outside [low, high]."""
    check_rows(name, array, ~np.isfinite(array), "is not finite")
    check_rows(name, array, (array < low) | (array > high), rule)


@dataclass(frozen=True)
class ScreenPolygons:
    """Screen-space polygons with depth and attributes, packed in arrays, validated once.

    Attributes
    ----------
    xy : (M, 2) ndarray of float64
        Display coordinates of all vertices, pixels, y up, within +-2**20.
    z : (M,) ndarray of float64
        Depth per vertex, smaller is nearer (NDC z in [0, 1] usually).
    inv_w : (M,) ndarray of float64
        1/w_clip per vertex, positive (all 1.0 for orthographic views).
    values : (M, K) ndarray of float64
        Attributes per vertex to interpolate (K may be 0).
    offsets : (P + 1,) ndarray of int64
        Polygon p is rows offsets[p]:offsets[p+1] (one contour, >= 3 vertices).

    |z|, |values| and 1/w are at most 1e100 (and 1/w at least 1e-100). All
    arrays are copied and made read-only. A polygon with fewer than 3 distinct
    vertices once snapped is valid: it renders nothing.

    Raises
    ------
    ValueError
        On a wrong shape, a non-finite or out-of-range entry (naming the
        array and the row), or bad offsets.
    TypeError
        If an array does not hold numbers, or `offsets` not integers.

    Examples
    --------
    >>> scene = ScreenPolygons.from_polygons([[(0, 0, 0.5), (4, 0, 0.5), (0, 4, 0.5)]])
    >>> scene.count, scene.values.shape, scene.offsets.tolist()
    (1, (3, 0), [0, 3])
    >>> ScreenPolygons.from_polygons([[(0, 0, 0.5), (4, 0, 0.5)]])
    Traceback (most recent call last):
    ...
    ValueError: 'offsets': polygon 0 has 2 vertices; a polygon needs at least 3
    """

    xy: np.ndarray
    z: np.ndarray
    inv_w: np.ndarray
    values: np.ndarray
    offsets: np.ndarray

    def __post_init__(self) -> None:
        xy = _float_array("xy", self.xy, 2)
        if xy.shape[1:] != (2,):
            raise ValueError(f"'xy' must be an (M, 2) array; got shape {xy.shape}")
        count = len(xy)
        arrays = {"xy": xy}
        for name, ndim in (("z", 1), ("inv_w", 1), ("values", 2)):
            array = _float_array(name, getattr(self, name), ndim)
            if len(array) != count:
                raise ValueError(
                    f"{name!r} must have one row per vertex of 'xy' ({count}); got {len(array)}"
                )
            arrays[name] = array
        _check_range("xy", xy, -COORD_LIMIT, COORD_LIMIT, f"is beyond +-{COORD_LIMIT} pixels")
        limit = f"is beyond +-{VALUE_LIMIT:g}"
        _check_range("z", arrays["z"], -VALUE_LIMIT, VALUE_LIMIT, limit)
        _check_range("values", arrays["values"], -VALUE_LIMIT, VALUE_LIMIT, limit)
        _check_range(
            "inv_w",
            arrays["inv_w"],
            1 / VALUE_LIMIT,
            VALUE_LIMIT,
            f"is not in [{1 / VALUE_LIMIT:g}, {VALUE_LIMIT:g}] (1/w of a vertex in front of the eye)",
        )
        arrays["offsets"] = _check_offsets(self.offsets, count)
        for name, array in arrays.items():
            array.setflags(write=False)
            object.__setattr__(self, name, array)

    @classmethod
    def checked(cls, xy, z, inv_w, values, offsets) -> ScreenPolygons:
        """Screen polygons from arrays their maker has already checked against every rule above.

        For `scanviz.pipeline.prepare`, which checks each field where it comes
        from (to name the object and the field in an error): the arrays are
        taken as they are when C-ordered float64 / int64 (else as such
        copies) and made read-only, not checked again.
        """
        polygons = object.__new__(cls)
        for name, array, dtype in (
            ("xy", xy, np.float64), ("z", z, np.float64), ("inv_w", inv_w, np.float64),
            ("values", values, np.float64), ("offsets", offsets, np.int64),
        ):  # fmt: skip
            array = np.ascontiguousarray(array, dtype=dtype)
            array.setflags(write=False)
            object.__setattr__(polygons, name, array)
        return polygons

    @property
    def count(self) -> int:
        """The number of polygons, P."""
        return len(self.offsets) - 1

    @property
    def value_count(self) -> int:
        """The number of attributes per vertex, K."""
        return self.values.shape[1]

    @classmethod
    def from_polygons(
        cls, polygons: object, values: object = None, inv_w: object = None
    ) -> ScreenPolygons:
        """Pack a list of (n_i, 3) arrays of (x, y, z), with optional (n_i, K) values and (n_i,) 1/w.

        Missing values give K = 0; missing 1/w gives 1.0 (orthographic).
        """
        vertices = [
            np.asarray(plain_array(p, f"polygon {k}", NOT_REAL_KINDS), dtype=np.float64).reshape(
                -1, 3
            )
            for k, p in enumerate(polygons)
        ]
        sizes = [len(v) for v in vertices]
        stacked = np.concatenate([np.zeros((0, 3)), *vertices])
        count = len(stacked)
        packed_values = np.zeros((count, 0))
        if values is not None:
            rows = [
                np.asarray(plain_array(v, f"values {k}", NOT_REAL_KINDS), np.float64).reshape(n, -1)
                for k, (v, n) in enumerate(zip(values, sizes, strict=True))
            ]
            packed_values = np.concatenate([np.zeros((0, rows[0].shape[1] if rows else 0)), *rows])
        packed_inv_w = np.ones(count)
        if inv_w is not None:
            packed_inv_w = np.concatenate(
                [np.zeros(0)]
                + [
                    np.asarray(plain_array(w, f"inv_w {k}", NOT_REAL_KINDS), np.float64).ravel()
                    for k, w in enumerate(inv_w)
                ]
            )
        return cls(
            xy=stacked[:, :2],
            z=stacked[:, 2],
            inv_w=packed_inv_w,
            values=packed_values,
            offsets=np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
        )


def _check_offsets(offsets: object, count: int) -> np.ndarray:
    array = np.array(offsets)
    if array.ndim != 1 or len(array) == 0:
        raise ValueError(f"'offsets' must be a (P + 1,) array; got shape {array.shape}")
    if not np.issubdtype(array.dtype, np.integer):
        raise TypeError(f"'offsets' must hold integers; got dtype {array.dtype}")
    array = array.astype(np.int64)
    if array[0] != 0 or array[-1] != count:
        raise ValueError(
            f"'offsets' must start at 0 and end at the vertex count {count}; "
            f"got {array[0]} ... {array[-1]}"
        )
    sizes = np.diff(array)
    if (sizes < 3).any():
        p = int(np.flatnonzero(sizes < 3)[0])
        raise ValueError(
            f"'offsets': polygon {p} has {sizes[p]} vertices; a polygon needs at least 3"
        )
    return array


@dataclass
class ZBufferStats(RichDisplay):
    """What one z-buffer pass did.

    ``polygons_drawn`` covered at least one sample; ``polygons_skipped`` were
    never scanned (seen edge-on, C == 0, or wholly off the raster).
    ``fragments`` = ``depth_passed`` + ``depth_failed``: the samples covered.
    """

    polygons: int = 0
    polygons_drawn: int = 0
    polygons_skipped: int = 0
    rows_scanned: int = 0
    spans: int = 0
    fragments: int = 0
    depth_passed: int = 0
    depth_failed: int = 0
    path: str = "reference"

    @classmethod
    def from_counts(cls, counts, polygons: int, path: str) -> ZBufferStats:
        """The stats of a compiled pass from its (7,) counts (`zbuffer_compiled.ROWS`, ...)."""
        return cls(
            polygons=polygons,
            polygons_drawn=int(counts[zbuffer_compiled.DRAWN]),
            polygons_skipped=int(counts[zbuffer_compiled.SKIPPED]),
            rows_scanned=int(counts[zbuffer_compiled.ROWS]),
            spans=int(counts[zbuffer_compiled.SPANS]),
            fragments=int(counts[zbuffer_compiled.FRAGMENTS]),
            depth_passed=int(counts[zbuffer_compiled.PASSED]),
            depth_failed=int(counts[zbuffer_compiled.FAILED]),
            path=path,
        )


@dataclass(frozen=True)
class ZBufferResult:
    """The result of `zbuffer`.

    Attributes
    ----------
    depth : (height, width) ndarray of float64
        Depth of the visible fragment, +inf where nothing was drawn.
    polygon : (height, width) ndarray of int64
        Index of the visible polygon, -1 where none.
    values : (height, width, K) ndarray of float64
        Interpolated attributes of the visible fragment, 0 where none.
    stats : ZBufferStats
        Counts of what ran, and which path.
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    depth: np.ndarray
    polygon: np.ndarray
    values: np.ndarray
    stats: ZBufferStats
    trace: Trace | None = None


def zbuffer(
    polygons: ScreenPolygons,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    perspective: bool = False,
    trace: object = None,
) -> ZBufferResult:
    """Draw polygons in order through a z-buffer, interpolating depth and attributes.

    A fragment passes iff its depth is below the stored one (strictly: ties
    keep the earlier polygon). Each polygon covers exactly the samples
    `scan_convert` covers for it (nonzero rule), so polygons sharing an edge
    cover each sample once; one whose snapped vertices have zero signed area
    (seen edge-on, C == 0 in its plane) draws nothing.

    Parameters
    ----------
    polygons : ScreenPolygons
        The polygons, in drawing order.
    width, height : int
        Raster size in pixels.
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    subpixel_bits : int in 0..16, or None
        Snap vertices to 1/2**bits pixel; None keeps them exact (through the
        reference when that needs more than 16 bits).
    perspective : bool
        Interpolate attributes perspective-correctly (value/w and 1/w, divided
        per sample) instead of affinely in screen space. Depth is affine in
        screen space either way.
    trace : None, True, or Tracer
        None runs the compiled kernel (the traced reference while a step of
        `scanviz.steps` is replaced); a tracer (True for a new `Recorder`)
        runs the traced reference, which emits `polygon_setup`, the scan
        events, `edge_values`, `span_values` and `depth_test`.

    Returns
    -------
    ZBufferResult

    Notes
    -----
    Depth is the plane (Newell's method) of the snapped vertices, z_row
    stepped by dz/dy between rows and z by dz/dx along spans; attributes are
    interpolated along edges, then spans (thesis §6.2). See docs/interpolation.md.

    Examples
    --------
    The UMBC slides' example: a triangle at depth 5, a square behind it at 9,
    and a sloped triangle crossing both.

    >>> scene = ScreenPolygons.from_polygons([
    ...     [(1, 1, 5), (7, 7, 5), (1, 7, 5)],
    ...     [(3, 5, 9), (10, 5, 9), (10, 9, 9), (3, 9, 9)],
    ...     [(2, 6, 3), (2, 3, 8), (7, 3, 3)],
    ... ])
    >>> result = zbuffer(scene, 10, 9)
    >>> result.polygon[::-1] + 1  # top row first; 0 = empty
    array([[0, 0, 0, 2, 2, 2, 2, 2, 2, 2],
           [0, 0, 0, 2, 2, 2, 2, 2, 2, 2],
           [0, 1, 1, 1, 1, 1, 2, 2, 2, 2],
           [0, 1, 3, 3, 1, 2, 2, 2, 2, 2],
           [0, 1, 1, 1, 3, 3, 0, 0, 0, 0],
           [0, 1, 1, 3, 3, 3, 3, 0, 0, 0],
           [0, 1, 0, 0, 0, 0, 0, 0, 0, 0],
           [0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
           [0, 0, 0, 0, 0, 0, 0, 0, 0, 0]])
    >>> float(result.depth[3, 3]), result.stats.path  # z = 15 - x - 5y/3 there
    (7.0, 'compiled')
    """
    width, height, bits = check_arguments(
        polygons, width, height, sample, subpixel_bits, perspective
    )
    tracer = as_tracer(trace)
    check_memory(
        width * height * 8 * (2 + polygons.value_count),
        f"a {width}x{height} z-buffer with {polygons.value_count} attributes per pixel",
    )
    if bits is None:
        bits = exact_bits(polygons.xy)
    units = snap_units(polygons.xy, sample, bits)
    channels = vertex_channels(polygons.values, polygons.inv_w, bool(perspective))
    if tracer is None and units.dtype == np.int64 and not steps.replaced():
        scale = 2 ** (bits + 1)
        if polygons.value_count == 0:  # nothing to divide by 1/w: leave it out
            channels = channels[:, :0]
        depth, ids, values, counts = zbuffer_compiled.zbuffer_polygons(
            units, units / scale, polygons.z, channels, polygons.offsets, scale,
            width, height, polygons.value_count,
        )  # fmt: skip
        stats = ZBufferStats.from_counts(counts, polygons.count, "compiled")
        return ZBufferResult(depth, ids, values, stats)
    result = zbuffer_reference(
        polygons, units, bits, sample, channels, width, height, bool(perspective), tracer
    )
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return ZBufferResult(result.depth, result.polygon, result.values, result.stats, recorded)


def check_arguments(polygons, width, height, sample, subpixel_bits, perspective):
    """(width, height, bits) once the arguments `zbuffer` and `solve` share are checked."""
    if not isinstance(polygons, ScreenPolygons):
        raise TypeError(f"'polygons' must be a ScreenPolygons; got {type(polygons).__name__}")
    width, height = check_raster_size(width, height)
    check_choice("sample", sample, SAMPLE_MODES)
    bits = check_subpixel_bits(subpixel_bits)
    if not isinstance(perspective, bool | np.bool_):
        raise TypeError(f"'perspective' must be a bool; got {perspective!r}")
    return width, height, bits


def zbuffer_reference(
    polygons: ScreenPolygons,
    units: np.ndarray,
    bits: int,
    sample: str,
    channels: np.ndarray,
    width: int,
    height: int,
    perspective: bool,
    trace=None,
) -> ZBufferResult:
    """The traced z-buffer on snapped `units` (any grid): `zbuffer` after validation."""
    depth = np.full((height, width), np.inf)
    ids = np.full((height, width), -1, np.int64)
    values = np.zeros((height, width, polygons.value_count))
    stats = ZBufferStats(polygons=polygons.count)
    offsets = polygons.offsets.tolist()
    nearer = steps.get("depth_test")
    for p, (first, stop) in enumerate(zip(offsets, offsets[1:], strict=False)):
        snapped = SnappedPolygon(units[first:stop], np.array([0, stop - first]), bits, sample)
        z, polygon_channels = polygons.z[first:stop], channels[first:stop]
        plane = polygon_plane(snapped, z)
        emit_polygon_setup(trace, p, snapped, z, plane, polygon_channels, perspective)
        if plane.edge_on or not polygon_reaches_raster(snapped, width, height):
            stats.polygons_skipped += 1  # seen edge-on, or off the raster: never scanned
            continue
        fragments = stats.fragments
        for y, spans in interpolate_rows(
            snapped, plane, polygon_channels, width, height, trace=trace, polygon=p
        ):
            stats.rows_scanned += 1
            stats.spans += len(spans)
            traced = trace is not None and trace.wants("depth_test", polygon=p, y=y)
            for span in spans:
                for x, z_sample, channel_values in span_samples(span):
                    stored = _stored(depth[y, x])
                    passed = bool(nearer(z_sample, stored))
                    if traced:
                        trace.emit(DepthTest(p, x, y, z_sample, stored, passed))
                    if passed:
                        depth[y, x], ids[y, x] = z_sample, p
                        values[y, x] = _attributes(channel_values, perspective)
                    stats.fragments += 1
                    stats.depth_passed += passed
                    stats.depth_failed += not passed
        stats.polygons_drawn += stats.fragments > fragments
    return ZBufferResult(depth, ids, values, stats)


@steps.step(
    "depth_test",
    takes="a fragment's depth z and the depth stored at its pixel (None: nothing drawn yet)",
    returns="True if the fragment is nearer and is written (z < stored; ties keep the stored one)",
)
def depth_test(z: float, stored: float | None) -> bool:
    """The z-buffer test: smaller z is nearer; an empty pixel takes any fragment.

    Examples
    --------
    >>> depth_test(0.25, None), depth_test(0.25, 0.5), depth_test(0.5, 0.5)
    (True, True, False)
    """
    return stored is None or z < stored


def _stored(depth: float) -> float | None:
    return None if depth == np.inf else float(depth)


def _attributes(channel_values: tuple[float, ...], perspective: bool) -> list[float]:
    """The attributes of a sample: the channels, or value/w over 1/w (the last channel)."""
    if not perspective:
        return list(channel_values)
    *over_w, one_over_w = channel_values
    return [perspective_divide(v, one_over_w) for v in over_w]

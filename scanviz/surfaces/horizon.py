"""The Floating Horizon Algorithm: hidden lines of one family of grid curves (Rogers 1985, ch. 4).

Wang (1989, §2.2) cites the FHA as the classic way to draw a surface
z = f(x, y) cut by parallel planes; scanviz follows the normative steps of
spec §1.4 [EXT]. Derivations and choices: ``docs/surfaces-horizon.md``.

1. The curves of one family (``family="x"``: the curves y = y_j, each a
   polyline over the x_i; ``"y"``: the curves x = x_i over the y_j) are
   projected with `View.screen_from_world`, fitted to all grid points, and
   processed nearest first: by the distance in XY of the curve's cutting
   plane from the viewpoint, |y_j - VPy| (family "x") or |x_i - VPx|
   (family "y"), ties by index.
2. ``up[x] = -inf`` and ``low[x] = +inf`` for every screen column x.
3. Each curve is split into x-monotone pieces (where its screen x reverses)
   and each piece is scanned left to right over the integer columns it spans,
   its height linearly interpolated between projected samples. A column's flag
   is +1 if y >= up[x], else -1 if y <= low[x], else 0 (hidden).
4. Between columns x - 1 and x with flags (P, C): P == C != 0 draws the
   segment, P == C == 0 nothing; otherwise the segment is cut where it meets
   the horizon of each nonzero flag (the horizons linear between the two
   columns), and the part at a visible end is drawn; (+1, -1) and (-1, +1)
   need both intersections.
5. After each curve, ``up = max(up, curve)`` and ``low = min(low, curve)``.

All pieces of one curve are tested against the horizons left by the curves
before it, so a curve never hides itself (a limitation of the FHA: it assumes
x-monotone curves). Screen coordinates are y up, row 0 at the bottom.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..conventions import check_raster_size, short_repr
from ..limits import check_memory
from ..raster.api import as_tracer
from ..raster.lines import paint_lines
from ..trace import Recorder, Trace
from ..trace.display import RichDisplay
from ..trace.events import HorizonColumn, HorizonCurve
from .grid import GridSurface
from .view import View

FAMILIES = ("x", "y")
LINE_IMAGE_PIXEL_BYTES = 1 + 8 + 3 * 8  # the bool lines, the gray image, its RGB copy
FLAG_PAIRS = tuple((p, c) for p in (1, 0, -1) for c in (1, 0, -1))
"""The nine (previous, current) flag combinations, in the order `HorizonStats` counts them."""


@dataclass(frozen=True)
class HorizonStats(RichDisplay):
    """What the floating horizon did.

    ``curves`` and ``pieces`` processed, screen ``columns`` visited (over all
    pieces), ``segments`` drawn (visible parts), and ``intersections``: per
    (previous, current) flag pair, the intersections with a horizon computed.
    """

    curves: int
    pieces: int
    columns: int
    segments: int
    intersections: dict[tuple[int, int], int]


@dataclass(frozen=True)
class HorizonResult:
    """The floating horizon's picture and state.

    Attributes
    ----------
    lines : (H, W) ndarray of bool
        The visible parts, rasterised (row 0 at the bottom).
    image : (H, W, 3) ndarray of float64
        Black lines on white.
    segments : (K, 4) ndarray of float64
        The visible parts (x0, y0, x1, y1) in screen pixels, in drawing order.
    up, low : (W,) ndarray of float64
        The final upper and lower horizons (-inf / +inf where no curve reached).
    order : tuple of int
        The curves in processing order (nearest first).
    stats : HorizonStats
    trace : Trace or None
        The recorded events when a recording tracer (or True) was given.
    """

    lines: np.ndarray
    image: np.ndarray
    segments: np.ndarray
    up: np.ndarray
    low: np.ndarray
    order: tuple[int, ...]
    stats: HorizonStats
    trace: Trace | None = field(default=None)


def floating_horizon(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    family: str = "x",
    trace: object = None,
) -> HorizonResult:
    """Hidden-line drawing of one family of grid curves by the floating horizon.

    Parameters
    ----------
    surface : GridSurface
    view : View
        The viewpoint, direction and projection; the grid is fitted to the raster.
    width, height : int
        Raster size, each at least 1.
    family : {"x", "y"}
        "x": the curves y = y_j (polylines along x); "y": the curves x = x_i.
    trace : None, True or Tracer
        Receives one ``horizon_curve`` per curve and one ``horizon_column``
        per column of each piece (True: a new Recorder; see the module notes).

    Returns
    -------
    HorizonResult

    Raises
    ------
    TypeError
        If `surface` is not a GridSurface, `view` not a View, `trace` not a
        tracer, or width/height not an int.
    ValueError
        If width or height is < 1 or `family` is unknown; the View's own
        error if a grid point is not in front of a perspective viewpoint.
    scanviz.limits.ResourceLimitError
        If the line raster and its image (33 bytes a pixel) would exceed the
        memory limit, refused before any is allocated.

    Examples
    --------
    A flat plane seen from the front and above: its three curves y = 0, 1, 2 are
    fully visible, the nearest (widest, in perspective) at the bottom.

    >>> plane = GridSurface([0.0, 1.0], [0.0, 1.0, 2.0], [[0, 0], [0, 0], [0, 0]])
    >>> result = floating_horizon(plane, View((0.5, -4, 3), (0, 1, -1)), 5, 5)
    >>> result.lines[::-1].astype(int)  # top row first
    array([[0, 1, 1, 1, 0],
           [0, 0, 0, 0, 0],
           [0, 1, 1, 1, 0],
           [0, 0, 0, 0, 0],
           [1, 1, 1, 1, 1]])
    >>> result.order, result.stats.segments
    ((0, 1, 2), 8)
    """
    width, height = _check(surface, view, width, height, family)
    tracer = as_tracer(trace)
    check_memory(
        LINE_IMAGE_PIXEL_BYTES * width * height + 16 * width + 40 * surface.nx * surface.ny,
        f"floating_horizon: a {width}x{height} line image of a {surface.nx}x{surface.ny} grid",
    )
    grid = np.stack(np.meshgrid(surface.x, surface.y), axis=-1)  # (Ny, Nx, 2)
    points = np.concatenate([grid, surface.z[..., None]], axis=-1).reshape(-1, 3)
    screen = view.screen_from_world(points, width, height)[0].reshape(surface.ny, surface.nx, 2)
    curves, planes, viewpoint = (
        (screen, surface.y, view.point[1])
        if family == "x"
        else (screen.transpose(1, 0, 2), surface.x, view.point[0])
    )
    order = tuple(int(k) for k in np.argsort(np.abs(planes - viewpoint), kind="stable"))
    up, low = np.full(width, -np.inf), np.full(width, np.inf)
    if tracer is None:
        polylines = np.ascontiguousarray(curves[list(order)], dtype=np.float64)
        segments, tally = _horizon_pass(polylines, up, low)
        counts = Counter(dict(zip(("pieces", "columns", *FLAG_PAIRS), tally.tolist(), strict=True)))
    else:
        drawn: list[tuple[float, float, float, float]] = []
        counts = Counter()
        for step, curve in enumerate(order):
            _process_curve(curve, step, family, curves[curve], up, low, drawn, counts, tracer)
        segments = np.array(drawn, dtype=np.float64).reshape(-1, 4)
    lines = paint_segments(segments, width, height)
    image = np.repeat(np.where(lines, 0.0, 1.0)[..., None], 3, axis=-1)
    stats = HorizonStats(
        curves=len(order),
        pieces=counts.pop("pieces", 0),
        columns=counts.pop("columns", 0),
        segments=len(segments),
        intersections={pair: counts[pair] for pair in FLAG_PAIRS},
    )
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return HorizonResult(lines, image, segments, up, low, order, stats, recorded)


def _check(surface: object, view: object, width: object, height: object, family: object):
    if not isinstance(surface, GridSurface):
        raise TypeError(f"'surface' must be a GridSurface; got {short_repr(surface)}")
    if not isinstance(view, View):
        raise TypeError(f"'view' must be a View; got {short_repr(view)}")
    width, height = check_raster_size(width, height)
    if width < 1 or height < 1:
        raise ValueError(f"'width' and 'height' must be at least 1; got {width} x {height}")
    if not isinstance(family, str) or family not in FAMILIES:
        raise ValueError(f"'family' must be 'x' or 'y'; got {short_repr(family)}")
    return width, height


def monotone_pieces(xs: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) sample indices of the maximal pieces of a polyline monotone in x.

    A piece ends where x reverses; the turning sample belongs to both pieces.
    Steps with no change in x never end a piece.

    >>> monotone_pieces(np.array([0.0, 1.0, 1.0, 3.0, 2.0, 0.0, 4.0]))
    [(0, 3), (3, 5), (5, 6)]
    """
    signs = np.sign(np.diff(xs))
    pieces, first, direction = [], 0, 0.0
    for k, sign in enumerate(signs):
        if sign and direction and sign != direction:  # x reverses at sample k
            pieces.append((first, k))
            first = k
        direction = sign or direction
    pieces.append((first, len(xs) - 1))
    return pieces


def column_heights(piece: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
    """The integer columns a monotone piece spans (clipped to the raster) and its heights there.

    >>> column_heights(np.array([[2.5, 0.0], [0.5, 4.0]]), 10)
    (array([1, 2]), array([3., 1.]))
    """
    if piece[-1, 0] < piece[0, 0]:
        piece = piece[::-1]  # scan left to right
    start = max(int(np.ceil(piece[0, 0])), 0)
    stop = min(int(np.floor(piece[-1, 0])), width - 1)
    columns = np.arange(start, stop + 1)
    return columns, np.interp(columns, piece[:, 0], piece[:, 1])


@njit(cache=True)
def flag(y: float, up: float, low: float) -> int:  # pragma: no cover - compiled
    """+1 on or above the upper horizon, -1 on or below the lower one, 0 hidden (step 3).

    Compiled, so the traced loop and `_horizon_pass` run this one definition.
    """
    if y >= up:
        return 1
    return -1 if y <= low else 0


def crossing(start: tuple, end: tuple, horizon: tuple) -> tuple[float, float]:
    """Where the segment start-end meets the horizon, linear between the same two columns.

    An infinite horizon end (no curve reached that column) puts the crossing at that end.

    >>> crossing((0.0, 0.0), (1.0, 2.0), (1.0, 1.0))
    (0.5, 1.0)
    """
    return _cut(
        float(start[0]), float(start[1]), float(end[0]), float(end[1]),
        float(horizon[0]), float(horizon[1]),
    )  # fmt: skip


def visible_parts(start, end, previous_flag, current_flag, up, low):
    """The visible parts of the segment between two columns, and the crossings computed (step 4).

    `up` and `low` are the horizons (at start, at end). A nonzero flag makes
    its end visible up to the crossing with its own horizon.

    >>> visible_parts((0.0, 2.0), (1.0, 0.0), 1, 0, (1.0, 1.0), (0.0, 0.0))
    ([(0.0, 2.0, 0.5, 1.0)], 1)
    >>> visible_parts((0.0, 2.0), (1.0, -2.0), 1, -1, (1.0, 1.0), (-1.0, -1.0))
    ([(0.0, 2.0, 0.25, 1.0), (0.75, -1.0, 1.0, -2.0)], 2)
    """
    if previous_flag == current_flag:
        return ([(*start, *end)] if current_flag else []), 0
    horizon = {1: up, -1: low}
    parts = []
    if previous_flag:
        parts.append((*start, *crossing(start, end, horizon[previous_flag])))
    if current_flag:
        parts.append((*crossing(start, end, horizon[current_flag]), *end))
    return parts, len(parts)


def _process_curve(curve, step, family, polyline, up, low, drawn, counts, tracer) -> None:
    """Steps 3-5 for one curve: scan each monotone piece, then raise and lower the horizons."""
    pieces = monotone_pieces(polyline[:, 0])
    if tracer is not None and tracer.wants("horizon_curve"):
        points = tuple((float(x), float(y)) for x, y in polyline)
        tracer.emit(
            HorizonCurve(curve=curve, step=step, family=family, points=points, pieces=tuple(pieces))
        )
    heights = []
    for first, last in pieces:
        columns, ys = column_heights(polyline[first : last + 1], len(up))
        _scan_piece(curve, columns, ys, up, low, drawn, counts, tracer)
        heights.append((columns, ys))
    counts["pieces"] += len(pieces)
    for columns, ys in heights:  # step 5, after the whole curve
        up[columns] = np.maximum(up[columns], ys)
        low[columns] = np.minimum(low[columns], ys)


def _scan_piece(curve, columns, ys, up, low, drawn, counts, tracer) -> None:
    """Flags and visible parts of one monotone piece, column by column (steps 3 and 4)."""
    previous = None
    for x, y in zip(columns.tolist(), ys.tolist(), strict=True):
        current = flag(y, up[x], low[x])
        parts = []
        if previous is not None:
            parts, cuts = visible_parts(
                (x - 1.0, previous[0]),
                (float(x), y),
                previous[1],
                current,
                (up[x - 1], up[x]),
                (low[x - 1], low[x]),
            )
            counts[previous[1], current] += cuts
            drawn.extend(parts)
        if tracer is not None and tracer.wants("horizon_column"):
            tracer.emit(
                HorizonColumn(
                    curve=curve,
                    x=x,
                    y=y,
                    previous_flag=None if previous is None else previous[1],
                    flag=current,
                    up=float(up[x]),
                    low=float(low[x]),
                    drawn=tuple(tuple(float(v) for v in part) for part in parts),
                )
            )
        previous = (y, current)
    counts["columns"] += len(columns)


@njit(cache=True)
def _cut(x0, y0, x1, y1, h0, h1):  # pragma: no cover - compiled; `crossing` and the pass
    """`crossing` on scalars. An equal difference at both ends is 0 at both: on the horizon."""
    above_start, above_end = y0 - h0, y1 - h1
    if not np.isfinite(above_start):
        t = 0.0
    elif not np.isfinite(above_end):
        t = 1.0
    else:
        t = above_start / (above_start - above_end) if above_start != above_end else 0.0
    return x0 + t * (x1 - x0), y0 + t * (y1 - y0)


@njit(cache=True)
def _horizon_pass(curves, up, low):  # pragma: no cover - compiled
    """Steps 3-5 over every curve (nearest first), as `_process_curve` does, without events.

    Returns the drawn segments (K, 4) and the counts: pieces, columns, then the
    intersections of each flag pair in `FLAG_PAIRS` order.
    """
    width = up.shape[0]
    drawn = []
    tally = np.zeros(11, np.int64)
    for c in range(curves.shape[0]):
        xs, ys = curves[c, :, 0], curves[c, :, 1]
        new_up, new_low = up.copy(), low.copy()
        first, direction = 0, 0.0
        n = xs.shape[0]
        for k in range(n):
            sign = np.sign(xs[k + 1] - xs[k]) if k < n - 1 else 0.0
            reverses = k < n - 1 and sign != 0.0 and direction != 0.0 and sign != direction
            if not (reverses or k == n - 1):
                direction = sign if sign != 0.0 else direction
                continue
            last = k  # the piece first..last (the turning sample is in both pieces)
            px, py = xs[first : last + 1], ys[first : last + 1]
            if px[-1] < px[0]:
                px, py = px[::-1].copy(), py[::-1].copy()
            start = max(int(np.ceil(px[0])), 0)
            stop = min(int(np.floor(px[-1])), width - 1)
            tally[0] += 1
            previous_flag, previous_y = 2, 0.0  # 2: no previous column in this piece
            for x in range(start, stop + 1):
                y = np.interp(float(x), px, py)
                flag_now = flag(y, up[x], low[x])
                if previous_flag != 2:
                    if previous_flag == flag_now:
                        if flag_now != 0:
                            drawn.append((x - 1.0, previous_y, float(x), y))
                    else:
                        pair = (1 - previous_flag) * 3 + (1 - flag_now)
                        if previous_flag != 0:
                            h0 = up[x - 1] if previous_flag == 1 else low[x - 1]
                            h1 = up[x] if previous_flag == 1 else low[x]
                            cx, cy = _cut(x - 1.0, previous_y, float(x), y, h0, h1)
                            drawn.append((x - 1.0, previous_y, cx, cy))
                            tally[2 + pair] += 1
                        if flag_now != 0:
                            h0 = up[x - 1] if flag_now == 1 else low[x - 1]
                            h1 = up[x] if flag_now == 1 else low[x]
                            cx, cy = _cut(x - 1.0, previous_y, float(x), y, h0, h1)
                            drawn.append((cx, cy, float(x), y))
                            tally[2 + pair] += 1
                previous_flag, previous_y = flag_now, y
                new_up[x] = max(new_up[x], y)
                new_low[x] = min(new_low[x], y)
            tally[1] += max(stop - start + 1, 0)
            first = k
            direction = sign if sign != 0.0 else direction
        up[:] = new_up  # step 5, after the whole curve
        low[:] = new_low
    segments = np.empty((len(drawn), 4))
    for i in range(len(drawn)):
        segments[i, 0], segments[i, 1], segments[i, 2], segments[i, 3] = drawn[i]
    return segments, tally


def paint_segments(segments: np.ndarray, width: int, height: int) -> np.ndarray:
    """The (height, width) bool raster of segments, endpoints rounded, by the midpoint line.

    >>> paint_segments(np.array([[0.0, 0.0, 2.0, 1.2]]), 3, 2).astype(int)[::-1]
    array([[0, 0, 1],
           [1, 1, 0]])
    """
    return paint_lines(np.rint(segments).astype(np.int64).reshape(-1, 4), width, height)

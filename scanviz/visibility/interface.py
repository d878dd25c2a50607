"""One interface for every visibility algorithm: screen polygons and a tracer in, visible surfaces out.

An algorithm is a small frozen dataclass of its options with a ``name``
(the string `render(visibility=...)` takes) and a method
``decide(surfaces, tracer) -> Decision``: either an order of pieces to
paint (list priority: painter's, depth sort, BSP) or the visible polygon per
sample (image space: scanline, Warnock). `solve` runs the decision and
paints it with the z-buffer's scan conversion (`scanviz.visibility.draw_decisions`);
the z-buffer itself is the algorithm that decides while it paints.

    >>> from scanviz.visibility import ScreenPolygons, solve
    >>> scene = ScreenPolygons.from_polygons([
    ...     [(0, 0, 9), (8, 0, 9), (0, 8, 9)],  # far
    ...     [(2, 2, 1), (8, 2, 1), (2, 8, 1)],  # near
    ... ])
    >>> result = solve("painter", scene, 8, 8)
    >>> [piece.label for piece in result.order], int(result.polygon[3, 3])
    (['0', '1'], 1)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..conventions import check_choice
from ..limits import ResourceLimitError, check_memory
from ..raster.api import as_tracer
from ..trace import Recorder, Trace
from ..trace.events import PaintOrder, PieceRecord
from .draw_decisions import paint
from .screen_polygons import Piece, Surfaces
from .zbuffer import ScreenPolygons, ZBufferStats, check_arguments, zbuffer


@dataclass(frozen=True)
class Decision:
    """What an algorithm decided: pieces to paint in order (``mode`` "over"/"under") or ``target`` ids.

    ``stats`` are the algorithm's own counts (a dataclass); ``detail`` is its
    structure for widgets and tests (the BSP tree, the quadtree, ...).
    """

    stats: object
    pieces: tuple[Piece, ...] = ()
    mode: str = "over"
    target: np.ndarray | None = None
    detail: object = None


@dataclass(frozen=True)
class VisibilityResult:
    """The visible surface per sample, as `ZBufferResult`, and what the algorithm decided.

    ``depth`` (H, W) float64 (+inf: empty), ``polygon`` (H, W) int64 (-1:
    background), ``values`` (H, W, K); ``stats`` the painting counts (a
    `ZBufferStats`: fragments painted and kept), ``algorithm`` the
    algorithm's own stats, ``order`` the pieces painted (list-priority
    algorithms), ``detail`` its structure, ``trace`` the recorded events;
    ``depth_slack`` the algorithm's promise (`Visibility.depth_slack`): at
    every sample the polygon shown is at most this much farther than the
    nearest one covering it (None: no promise).
    """

    name: str
    depth: np.ndarray
    polygon: np.ndarray
    values: np.ndarray
    stats: ZBufferStats
    algorithm: object = None
    order: tuple[Piece, ...] = ()
    detail: object = None
    trace: Trace | None = field(default=None)
    depth_slack: float | None = None


class Visibility:
    """Base of the visibility algorithms: a name, options as dataclass fields, and `decide`."""

    name: ClassVar[str] = ""

    def decide(self, surfaces: Surfaces, tracer) -> Decision:  # pragma: no cover - abstract
        raise NotImplementedError

    def depth_slack(self, surfaces: Surfaces, stats: object) -> float | None:
        """How much farther than the nearest covering polygon the one shown may be, at any
        sample, by the algorithm's own rule (docs/visibility.md); None: no promise."""
        return None


@dataclass(frozen=True)
class ZBuffer(Visibility):
    """The z-buffer (`scanviz.visibility.zbuffer`): it decides while it paints."""

    name: ClassVar[str] = "zbuffer"


ALGORITHMS: dict[str, type[Visibility]] = {"zbuffer": ZBuffer}


def register(cls: type[Visibility]) -> type[Visibility]:
    """Class decorator: make `cls` available by its ``name`` to `solve` and `render`."""
    if not cls.name or cls.name in ALGORITHMS:
        raise TypeError(f"visibility algorithm name {cls.name!r} is empty or taken")
    ALGORITHMS[cls.name] = cls
    return cls


def algorithm(visibility: object) -> Visibility:
    """A `Visibility` from a name in `ALGORITHMS` or an instance (its options), checked."""
    if isinstance(visibility, Visibility):
        return visibility
    if isinstance(visibility, str):
        check_choice("visibility", visibility, tuple(ALGORITHMS))
        return ALGORITHMS[visibility]()
    raise TypeError(
        "'visibility' must be a name of scanviz.visibility.ALGORITHMS or a Visibility; "
        f"got {type(visibility).__name__}"
    )


def solve(
    visibility: object,
    polygons: ScreenPolygons,
    width: int,
    height: int,
    *,
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    perspective: bool = False,
    trace: object = None,
) -> VisibilityResult:
    """Decide what is visible with `visibility` (a name or an algorithm) and paint it.

    The arguments after `visibility` are those of `scanviz.visibility.zbuffer`.
    Polygons the z-buffer never scans (edge-on, off the raster) take no part.
    A tracer records the algorithm's events, then `paint_order` and one
    `pixel_painted` per sample painted.
    """
    chosen = algorithm(visibility)
    width, height, _ = check_arguments(polygons, width, height, sample, subpixel_bits, perspective)
    tracer = as_tracer(trace)
    options = {"sample": sample, "subpixel_bits": subpixel_bits, "perspective": bool(perspective)}
    if isinstance(chosen, ZBuffer):
        z = zbuffer(polygons, width, height, **options, trace=tracer)
        return VisibilityResult("zbuffer", z.depth, z.polygon, z.values, z.stats, z.stats, trace=z.trace, depth_slack=0.0)  # fmt: skip
    check_memory(
        width * height * 8 * (3 + polygons.value_count),
        f"a {width}x{height} {chosen.name} render with {polygons.value_count} attributes per pixel",
    )
    surfaces = Surfaces.of(polygons, width, height, **options)
    decision = chosen.decide(surfaces, tracer)
    if decision.target is None and tracer is not None and tracer.wants("paint_order"):
        tracer.emit(
            PaintOrder(chosen.name, decision.mode, tuple(map(piece_record, decision.pieces)))
        )
    if decision.target is not None:
        painted = paint(surfaces, surfaces.pieces(), "target", target=decision.target, trace=tracer)
    else:
        painted = paint(surfaces, list(decision.pieces), decision.mode, trace=tracer)
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return VisibilityResult(
        chosen.name,
        painted.depth,
        painted.polygon,
        painted.values,
        painted.stats,
        decision.stats,
        decision.pieces,
        decision.detail,
        recorded,
        chosen.depth_slack(surfaces, decision.stats),
    )


def check_budget(name: str, value: object, least: int) -> None:
    """Check a work-budget option: None (the algorithm's default) or an int >= `least`."""
    if value is not None and (
        not isinstance(value, int | np.integer) or isinstance(value, bool) or value < least
    ):
        raise ValueError(f"{name!r} must be None or an int >= {least}; got {value!r}")


def budget(option: int | None, per_polygon: int, spare: int, polygons: int) -> int:
    """A work budget: the option, or `per_polygon` per polygon plus `spare` when it is None."""
    return per_polygon * polygons + spare if option is None else int(option)


def over_budget(work: str, limit: int, option: str, advice: str) -> ResourceLimitError:
    """The one-line refusal of an algorithm whose work passed its budget `option`."""
    return ResourceLimitError(
        f"{work} passed {limit:,} ({option}): {advice}; use visibility='zbuffer', or raise {option}"
    )


def piece_record(piece: Piece) -> PieceRecord:
    """A piece as trace events carry it."""
    return PieceRecord(
        piece.label,
        piece.polygon,
        tuple((float(x), float(y), float(z)) for x, y, z in piece.vertices),
        piece.cuts,
        piece.zmin,
        piece.zmax,
    )

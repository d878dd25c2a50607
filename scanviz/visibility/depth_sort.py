"""Depth sort (Newell, Newell and Sancha): the painter's order, checked pair by pair and repaired.

The list starts sorted on each piece's farthest vertex (the largest zmax
first: smaller z is nearer in scanviz). S, the piece at the far end, may be
painted first unless it can hide some S' still in the list. S can hide S'
only if some point of S is nearer than some point of S', so only the S'
with S'.zmax > S.zmin are tested (the **minimax test** settles the others:
S' lies wholly at or nearer than S's nearest point). For each such S' the
slides' ambiguity tests run in order (step ``depth_order_test``), and the
first that passes settles the pair -- painting S before S' is right:

1. ``x_extent``: the x extents do not overlap (touching counts as apart: a
   polygon owns no sample on its right border, `scanviz.conventions`);
2. ``y_extent``: the y extents do not overlap (same rule for the top border);
3. ``s_behind_plane``: no vertex of S is in front of the plane of S' by more
   than the tolerance (`Surfaces.classify` is "behind" or "on");
4. ``other_in_front``: no vertex of S' is behind the plane of S;
5. ``no_overlap``: the projections do not overlap, decided exactly
   (`projections_overlap`: touching is not overlapping).

If none passes, the same step runs with S and S' exchanged: S' entirely
behind S's plane (``other_behind_plane``) or S entirely in front of S''s
(``s_in_front``) means S' must be painted first: S' moves to the far end of
the list, is marked, and the scan restarts with it as S. A marked S' that
would move again closes a cycle (``why`` "cycle"); a pair whose reversed
tests fail too crosses in depth ("interpenetration"). Either is broken by
a split: S cut by the plane of S' when S straddles it, else S' by S's; in
a cycle where neither straddles the other, the first member of the cycle
that straddles another member's plane. The two pieces replace the piece in
the list where its zmax sorts them, and the scan restarts; the pieces that
were moved ahead of a piece that is cut go back to the sorted list unmarked
(the reason they moved is gone).

Termination: a split only cuts a piece that straddles the plane by more
than the tolerance, so no piece is ever cut twice by one plane; a piece is
moved at most once while it lives; painting removes the far end. At most
``max_splits`` splits are made (default `SPLITS_PER_POLYGON` per polygon
plus `SPLITS_SPARE`); past it, or when no member of a cycle straddles
another's plane, the pair is accepted in list order. If the two pieces
cover no common sample (pieces cut along the same line meet only there:
their outlines touch, their samples do not), the order cannot matter and
the pair is counted in ``settled["no_shared_sample"]``; otherwise (or past
`SAMPLE_CHECKS` such checks) it is counted ``unresolved``.

Work: every split and swap restarts the scan, so a scene where polygons
cover and cut each other everywhere costs about splits x pieces pair tests.
The pairs that pass none of the four cheap tests (each a call of the step)
and all the pairs tested (most settled by the vectorised tests) are
counted, and past ``max_hard_pairs`` or ``max_pairs`` (defaults
`HARD_PER_POLYGON` and `PAIRS_PER_POLYGON` per polygon plus a spare;
ordinary scenes use a few hard pairs and under 100 pairs per polygon) the
sort raises `scanviz.limits.ResourceLimitError` rather than run for minutes.

The promise (`DepthSort.depth_slack`): when nothing is unresolved, every
sample shows a polygon at most the tolerance farther than the nearest. The
piece painted last at a sample was, when each earlier one there was
painted, still in the list and settled against it by a test that puts it
no farther than the tolerance behind (minimax, the plane tests) or shows
they share no sample (extents, projections, ``no_shared_sample``).

Traced: ``polygons_sorted`` (the list at the start and after each split),
one ``pair_tested`` per pair examined (every test run and the one that
settled it), ``pieces_swapped`` per move, ``polygon_split`` per split.
Untraced, the pairs are pruned with numpy: the minimax window is a binary
search in the sorted list, and the extent and plane tests run on the whole
window at once with the step's own floating-point expressions, so only the
pairs the first four tests leave go through the step; the decision (pieces,
order, counts) is the traced one's.

>>> from scanviz.visibility import solve
>>> from scanviz.visibility.examples import cyclic_overlap
>>> result = solve("depth_sort", cyclic_overlap(), 24, 24)
>>> result.algorithm.splits > 0, result.algorithm.unresolved
(True, 0)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import ClassVar

import numpy as np

from .. import steps
from ..trace.display import RichDisplay
from ..trace.events import AmbiguityTest, PairTested, PiecesSwapped, PolygonSplit, PolygonsSorted
from .draw_decisions import samples
from .interface import (
    Decision,
    Visibility,
    budget,
    check_budget,
    over_budget,
    piece_record,
    register,
)
from .painter import depth_order
from .screen_polygons import STRADDLES, Piece, Surfaces

TESTS = ("x_extent", "y_extent", "s_behind_plane", "other_in_front", "no_overlap")
REVERSED = {"s_behind_plane": "other_behind_plane", "other_in_front": "s_in_front"}
SPLITS_PER_POLYGON = 16
SPLITS_SPARE = 64
HARD_PER_POLYGON = 64  # the default work budget: pairs past the four cheap tests, per polygon
HARD_SPARE = 4096
PAIRS_PER_POLYGON = 256  # and every pair tested, minimax included (the vectorised scans' work)
PAIRS_SPARE = 2**20
SAMPLE_CHECKS = 256  # pairs checked sample by sample ("no_shared_sample") at most
_ERROR_BOUND = 3.3306690738754716e-16  # Shewchuk's ccwerrboundA: (3 + 16 eps) eps
_EXTENTS = ((2, True), (2, False), (0, True), (0, False), (1, True), (1, False))  # zmin, zmax, ...


@dataclass
class DepthSortStats(RichDisplay):
    """Counts of one depth sort.

    ``tests`` counts each test run by name (minimax included), ``settled``
    the pairs each test settled; ``unresolved`` the pairs accepted in list
    order because no split could break them (see the module).
    """

    pieces: int = 0
    left_out: int = 0
    pairs_tested: int = 0
    tests: dict[str, int] = field(default_factory=dict)
    settled: dict[str, int] = field(default_factory=dict)
    swaps: int = 0
    splits: int = 0
    unresolved: int = 0


@steps.step(
    "depth_order_test",
    takes=(
        "S and S' as vertices ((x, y, z), ...) (sample frame), their depth planes "
        "(x0, y0, z0, dz/dx, dz/dy) and the plane tolerance"
    ),
    returns=(
        "the first ambiguity test that passes, in order: 'x_extent', 'y_extent', "
        "'s_behind_plane', 'other_in_front', 'no_overlap'; None if none does"
    ),
)
def depth_order_test(s, other, s_plane, other_plane, tolerance) -> str | None:
    """The slides' ambiguity tests of depth sort, in order: which one shows S may go before S'.

    A vertex is in front of a plane when its depth is below the plane's
    there by more than `tolerance`, behind when above by more (the plane's
    depth is ``z0 + dzdx * (x - x0) + dzdy * (y - y0)``).

    Examples
    --------
    >>> flat = lambda z: (0.0, 0.0, z, 0.0, 0.0)
    >>> far = ((0, 0, 9), (4, 0, 9), (0, 4, 9))
    >>> depth_order_test(far, ((5, 0, 1), (9, 0, 1), (5, 4, 1)), flat(9), flat(1), 1e-9)
    'x_extent'
    >>> depth_order_test(far, ((1, 1, 1), (5, 1, 1), (1, 5, 1)), flat(9), flat(1), 1e-9)
    's_behind_plane'
    """
    if _apart(s, other, 0):
        return "x_extent"
    if _apart(s, other, 1):
        return "y_extent"
    if all(z - _plane_at(other_plane, x, y) >= -tolerance for x, y, z in s):
        return "s_behind_plane"
    if all(z - _plane_at(s_plane, x, y) <= tolerance for x, y, z in other):
        return "other_in_front"
    if not projections_overlap([v[:2] for v in s], [v[:2] for v in other]):
        return "no_overlap"
    return None


def _apart(s, other, axis: int) -> bool:
    """Extents apart along `axis`; touching is apart (no sample is owned on a max border)."""
    s_low, s_high = min(v[axis] for v in s), max(v[axis] for v in s)
    low, high = min(v[axis] for v in other), max(v[axis] for v in other)
    return s_high <= low or high <= s_low


def _plane_at(plane, x, y):
    x0, y0, z0, dzdx, dzdy = plane
    return z0 + dzdx * (x - x0) + dzdy * (y - y0)  # plane_depth's expression, to the bit


def projections_overlap(a, b) -> bool:
    """Whether the interiors of the projections `a` and `b` ((x, y) vertices) intersect, exactly.

    The edge-intersection test done exactly and in one pass: two convex
    polygons have disjoint interiors iff the line of some edge of one has the
    other wholly on its outer (closed) side -- no edges cross and neither is
    inside the other (the separating axis theorem). Touching along an edge or
    at a vertex is not overlapping: no sample is owned by both. A concave
    polygon is tested by its convex hull (sound: an overlap is never missed);
    one of no area overlaps nothing.

    >>> square = [(0, 0), (2, 0), (2, 2), (0, 2)]
    >>> projections_overlap(square, [(2, 0), (4, 0), (4, 2)]), projections_overlap(square, square)
    (False, True)
    """
    hull_a, hull_b = convex_hull(a), convex_hull(b)
    if len(hull_a) < 3 or len(hull_b) < 3:
        return False
    return not (_separates(hull_a, hull_b) or _separates(hull_b, hull_a))


def _separates(hull, other) -> bool:
    """Whether an edge line of counter-clockwise `hull` has all of `other` outside or on it."""
    for p, q in zip(hull, hull[1:] + hull[:1], strict=True):
        if all(_orientation(p, q, r) <= 0 for r in other):
            return True
    return False


def convex_hull(points) -> list:
    """The convex hull of (x, y) points, counter-clockwise, without collinear points (exact).

    >>> convex_hull([(0, 0), (1, 0), (2, 0), (1, 1), (0, 2), (2, 2)])
    [(0, 0), (2, 0), (2, 2), (0, 2)]
    """
    ordered = sorted(set(map(tuple, points)))
    if len(ordered) < 3:
        return ordered
    lower: list = []
    upper: list = []
    for chain, sequence in ((lower, ordered), (upper, ordered[::-1])):
        for point in sequence:
            while len(chain) >= 2 and _orientation(chain[-2], chain[-1], point) <= 0:
                chain.pop()
            chain.append(point)
    return lower[:-1] + upper[:-1]


def _orientation(a, b, c) -> int:
    """Sign of (a - c) x (b - c): a float filter, exact fractions when it cannot decide."""
    left = (a[0] - c[0]) * (b[1] - c[1])
    right = (a[1] - c[1]) * (b[0] - c[0])
    determinant = left - right
    if abs(determinant) > _ERROR_BOUND * (abs(left) + abs(right)):
        return 1 if determinant > 0 else -1
    (ax, ay), (bx, by), (cx, cy) = (map(Fraction, point[:2]) for point in (a, b, c))
    exact = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx)
    return (exact > 0) - (exact < 0)


@register
@dataclass(frozen=True)
class DepthSort(Visibility):
    """Depth sort.

    Options: ``max_splits``, the split budget (past it, pairs are accepted
    unresolved); the work budgets ``max_hard_pairs`` (pairs that pass none of
    the four cheap tests: extents and planes) and ``max_pairs`` (all pairs
    tested), past which the sort raises `scanviz.limits.ResourceLimitError`.
    None: the defaults of the module (`SPLITS_PER_POLYGON`,
    `HARD_PER_POLYGON`, `PAIRS_PER_POLYGON` per polygon plus a spare).
    """

    name: ClassVar[str] = "depth_sort"
    max_splits: int | None = None
    max_hard_pairs: int | None = None
    max_pairs: int | None = None

    def __post_init__(self) -> None:
        check_budget("max_splits", self.max_splits, 0)
        check_budget("max_hard_pairs", self.max_hard_pairs, 1)
        check_budget("max_pairs", self.max_pairs, 1)

    def decide(self, surfaces: Surfaces, tracer) -> Decision:
        pieces = surfaces.pieces()
        splits = budget(self.max_splits, SPLITS_PER_POLYGON, SPLITS_SPARE, len(pieces))
        hard = budget(self.max_hard_pairs, HARD_PER_POLYGON, HARD_SPARE, len(pieces))
        pairs = budget(self.max_pairs, PAIRS_PER_POLYGON, PAIRS_SPARE, len(pieces))
        sorter = _Sorter(surfaces, depth_order(pieces, "zmax"), tracer, splits, (hard, pairs))
        order = sorter.run()
        sorter.stats.pieces, sorter.stats.left_out = len(order), surfaces.count - len(pieces)
        return Decision(sorter.stats, tuple(order), "over")

    def depth_slack(self, surfaces: Surfaces, stats: DepthSortStats) -> float | None:
        """The tolerance, when no pair was left unresolved: each pair's test that let S go
        first shows S no nearer than S' by more than it (None: a pair was accepted as listed)."""
        return surfaces.tolerance if stats.unresolved == 0 else None


class _Sorter:
    """The list of depth sort and its loop (see the module).

    The list is the stack of moved pieces (its top the far end), then the
    unmoved pieces sorted on zmax, farthest first (``rest[start:]``, with
    ``keys`` = -zmax for binary search). Pieces are ids into ``pieces`` and
    the per-piece arrays.
    """

    def __init__(self, surfaces, ordered: list[Piece], tracer, budget: int, work: tuple) -> None:
        self.surfaces, self.tracer, self.budget = surfaces, tracer, budget
        self.hard_budget, self.pairs_budget = work
        self.hard_pairs = self.sample_checks = 0
        self.stats = DepthSortStats()
        self.test = steps.get("depth_order_test")
        self.prune = tracer is None and not steps.replaced()
        self.pieces: list[Piece] = []
        self.width = max((len(p.vertices) for p in ordered), default=3)
        capacity = 2 * len(ordered) + 8
        self.arrays = np.zeros((capacity, 6))  # zmin, zmax, xmin, xmax, ymin, ymax
        self.corners = np.zeros((capacity, 3, self.width))  # x, y, z per vertex, padded
        self.owner = np.zeros(capacity, np.int64)  # each piece's polygon
        for piece in ordered:
            self._add(piece)
        self.rest = np.arange(len(ordered), dtype=np.int64)
        self.keys = -self.arrays[: len(ordered), 1].copy()
        self.start = 0
        self.stack: list[int] = []
        if self._traced("polygons_sorted"):
            tracer.emit(PolygonsSorted("zmax", tuple(map(piece_record, ordered))))

    def _traced(self, kind: str, **where) -> bool:
        return self.tracer is not None and self.tracer.wants(kind, **where)

    def _add(self, piece: Piece) -> int:
        """Append `piece`: its extents and its vertices, padded with its first one."""
        v, new = piece.vertices, len(self.pieces)
        if new == len(self.arrays):
            self.arrays = np.concatenate([self.arrays, np.zeros_like(self.arrays)])
            self.corners = np.concatenate([self.corners, np.zeros_like(self.corners)])
            self.owner = np.concatenate([self.owner, np.zeros_like(self.owner)])
        if len(v) > self.width:
            extra = np.repeat(self.corners[:, :, :1], len(v) - self.width, axis=2)
            self.corners, self.width = np.concatenate([self.corners, extra], axis=2), len(v)
        self.arrays[new] = [v[:, k].min() if low else v[:, k].max() for k, low in _EXTENTS]
        self.corners[new] = np.concatenate([v, np.repeat(v[:1], self.width - len(v), axis=0)]).T
        self.owner[new] = piece.polygon
        self.pieces.append(piece)
        return new

    def run(self) -> list[Piece]:
        """The pieces in painting order: scan the far end, then paint it, swap or split."""
        painted = []
        while self.stack or self.start < len(self.rest):
            s = self.stack[-1] if self.stack else int(self.rest[self.start])
            action = self._scan(s)
            if self.stats.pairs_tested > self.pairs_budget:
                advice = f"after {self.stats.splits:,} splits the list is still being reordered"
                raise over_budget("depth sort's pair tests", self.pairs_budget, "max_pairs", advice)
            if action is None:
                painted.append(self.pieces[s])
                if self.stack:
                    self.stack.pop()
                else:
                    self.start += 1
            elif action[0] == "swap":
                self._move(action[1])
            else:
                self._split(*action[1:])
        return painted

    # The scan of one S: the moved pieces below it, then the sorted window of the rest.

    def _scan(self, s: int):
        for other in self.stack[-2::-1]:
            if self.arrays[other, 1] <= self.arrays[s, 0]:
                self._minimax(s, other)
                continue
            action = self._examine(s, other)
            if action is not None:
                return action
        first = self.start + (0 if self.stack else 1)
        end = first + int(np.searchsorted(self.keys[first:], -self.arrays[s, 0], side="left"))
        window = self.rest[first:end]
        codes = self._settled_by(s, window) if self.prune else np.full(len(window), 4)
        hard = np.flatnonzero(codes >= 4)
        for k in hard.tolist():
            action = self._examine(s, int(window[k]))
            if action is not None:
                self._count_settled(codes[:k])
                return action
        self._count_settled(codes)
        if end < len(self.rest):
            self._minimax(s, int(self.rest[end]))  # the rest is sorted: every later S' is nearer
        return None

    def _minimax(self, s: int, other: int) -> None:
        self._count(("minimax",), "minimax")
        self._emit_pair(s, other, None, "minimax", "no_overlap")

    def _settled_by(self, s: int, window: np.ndarray) -> np.ndarray:
        """Per pair of the window, the index in TESTS of the first of the four cheap tests that
        passes, 4 if none does (the step's own expressions, vectorised)."""
        box, others = self.arrays[s], self.arrays[window]
        codes = np.full(len(window), 4, np.int64)
        y_apart = (others[:, 4] >= box[5]) | (others[:, 5] <= box[4])
        codes[y_apart] = 1
        codes[(others[:, 2] >= box[3]) | (others[:, 3] <= box[2])] = 0
        near = np.flatnonzero(codes == 4)
        if not len(near):
            return codes
        ids = window[near]
        planes = self.surfaces.planes[self.owner[ids]]
        own_plane = self.surfaces.planes[self.pieces[s].polygon]
        x, y, z = self.corners[s]
        behind = (z - _plane_at(planes.T[:, :, None], x, y) >= -self.surfaces.tolerance).all(1)
        ox, oy, oz = self.corners[ids].transpose(1, 0, 2)
        front = (oz - _plane_at(own_plane, ox, oy) <= self.surfaces.tolerance).all(1)
        codes[near[front]] = 3
        codes[near[behind]] = 2
        return codes

    def _count_settled(self, codes: np.ndarray) -> None:
        """Count the pairs the step was not called for (codes < 4) by the test that settled them."""
        for k, count in enumerate(np.bincount(codes, minlength=5)[:4].tolist()):
            if count:
                for name in ("minimax", *TESTS[: k + 1]):
                    self.stats.tests[name] = self.stats.tests.get(name, 0) + count
                self.stats.settled[TESTS[k]] = self.stats.settled.get(TESTS[k], 0) + count
                self.stats.pairs_tested += count

    def _count(self, run: tuple[str, ...], settled: str | None) -> None:
        for name in run:
            self.stats.tests[name] = self.stats.tests.get(name, 0) + 1
        if settled is not None:
            self.stats.settled[settled] = self.stats.settled.get(settled, 0) + 1
        self.stats.pairs_tested += 1

    # One pair: the tests, the reversed tests, and what to do.

    def _plain(self, piece: int):
        p = self.pieces[piece]
        plane = tuple(self.surfaces.planes[p.polygon].tolist())
        return tuple(map(tuple, p.vertices.tolist())), plane

    def _examine(self, s: int, other: int):
        (s_vertices, s_plane), (o_vertices, o_plane) = self._plain(s), self._plain(other)
        tolerance = self.surfaces.tolerance
        settled = self.test(s_vertices, o_vertices, s_plane, o_plane, tolerance)
        if settled not in TESTS[:4]:
            self._count_hard()
        run = _run(settled, TESTS)
        if settled is not None:
            self._count(("minimax", *(name for name, _ in run)), settled)
            self._emit_pair(s, other, run, settled, "order_ok")
            return None
        reverse = self.test(o_vertices, s_vertices, o_plane, s_plane, tolerance)
        reversed_run = _run(reverse, ("s_behind_plane", "other_in_front"))
        run += [(REVERSED.get(name, name), passed) for name, passed in reversed_run]
        settled = None if reverse is None else REVERSED.get(reverse, reverse)
        self._count(("minimax", *(name for name, _ in run)), settled)
        if settled is not None and other not in self.stack:
            self._emit_pair(s, other, run, settled, "swap")
            return ("swap", other)
        why = "interpenetration" if settled is None else "cycle"
        cut = self._choose_cut(s, other, why) if self.stats.splits < self.budget else None
        if cut is not None:
            self._emit_pair(s, other, run, settled, "split")
            return ("split", *cut, why)
        self.sample_checks += 1
        if self.sample_checks > SAMPLE_CHECKS or self._share_samples(s, other):
            self._emit_pair(s, other, run, settled, "unresolved")
            self.stats.unresolved += 1
        else:  # only their outlines meet (pieces cut along one line): any order paints the same
            self.stats.settled["no_shared_sample"] = (
                self.stats.settled.get("no_shared_sample", 0) + 1
            )
            self._emit_pair(s, other, run, settled, "no_shared_sample")
        return None

    def _count_hard(self) -> None:
        """Count a pair past the four cheap tests against the work budget."""
        self.hard_pairs += 1
        if self.hard_pairs > self.hard_budget:
            advice = (
                f"after {self.stats.splits:,} splits the polygons still cover and cut each other"
            )
            raise over_budget(
                "depth sort's overlapping pairs", self.hard_budget, "max_hard_pairs", advice
            )

    def _share_samples(self, s: int, other: int) -> bool:
        """Whether the two pieces cover a common sample (each painted alone)."""
        shared = samples(self.surfaces, self.pieces[s]) & samples(self.surfaces, self.pieces[other])
        return bool(shared.any())

    def _choose_cut(self, s: int, other: int, why: str):
        """(piece, cutter): a piece straddling the other's plane, from the pair, then the cycle."""
        members = [s, other]
        if why == "cycle":
            members += self.stack[self.stack.index(other) + 1 : -1]
        for piece in members:
            for cutter in members:
                p, q = self.pieces[piece], self.pieces[cutter]
                if p.polygon != q.polygon and self.surfaces.classify(p, q.polygon) == STRADDLES:
                    return piece, cutter
        return None

    def _emit_pair(self, s, other, run, settled, outcome) -> None:
        """A pair_tested event; `run` the tests after minimax (None: minimax settled it)."""
        piece = self.pieces[s]
        if self._traced("pair_tested", polygon=piece.polygon):
            tests = (AmbiguityTest("minimax", run is None),)
            tests += tuple(AmbiguityTest(name, passed) for name, passed in run or ())
            label = self.pieces[other].label
            self.tracer.emit(PairTested(piece.polygon, piece.label, label, tests, settled, outcome))

    # Changing the list.

    def _list(self) -> list[int]:
        """The list as the slides see it: the moved pieces (far end first), then the rest."""
        return [*self.stack[::-1], *self.rest[self.start :].tolist()]

    def _remove(self, piece: int) -> None:
        """Take `piece` out of the list; the pieces moved onto it go back to the sorted rest.

        They were moved because they must precede it (or one above them): with
        it gone, that no longer holds, so a later move of one is no cycle.
        """
        if piece in self.stack:
            at = self.stack.index(piece)
            self.stack, above = self.stack[:at], self.stack[at + 1 :]
            for moved in above:
                self._insert(moved)
            return
        at = self.start + int(np.flatnonzero(self.rest[self.start :] == piece)[0])
        self.rest, self.keys = np.delete(self.rest, at), np.delete(self.keys, at)

    def _insert(self, piece: int) -> None:
        """Put `piece` in the sorted rest, after the pieces of the same zmax."""
        key = -self.arrays[piece, 1]
        at = self.start + int(np.searchsorted(self.keys[self.start :], key, side="right"))
        self.rest, self.keys = np.insert(self.rest, at, piece), np.insert(self.keys, at, key)

    def _move(self, other: int) -> None:
        s = self.stack[-1] if self.stack else int(self.rest[self.start])
        self._remove(other)
        self.stack.append(other)
        self.stats.swaps += 1
        if self._traced("pieces_swapped"):
            self.tracer.emit(
                PiecesSwapped(
                    self.pieces[s].label,
                    self.pieces[other].label,
                    tuple(self.pieces[i].label for i in self._list()),
                )
            )

    def _split(self, piece: int, cutter: int, why: str) -> None:
        p, by = self.pieces[piece], self.pieces[cutter].polygon
        front, behind = self.surfaces.split(p, by)
        self._remove(piece)
        for part in (front, behind):
            self._insert(self._add(part))
        self.stats.splits += 1
        if self._traced("polygon_split", polygon=p.polygon):
            self.tracer.emit(
                PolygonSplit(p.polygon, p.label, by, why, piece_record(front), piece_record(behind))
            )
        if self._traced("polygons_sorted"):
            records = tuple(piece_record(self.pieces[i]) for i in self._list())
            self.tracer.emit(PolygonsSorted("zmax", records))


def _run(settled: str | None, names: tuple[str, ...]) -> list[tuple[str, bool]]:
    """The tests run up to the one that settled (all of `names` when none did) and their results."""
    if settled not in names:
        return [(name, False) for name in names] + ([(settled, True)] if settled else [])
    k = names.index(settled)
    return [(name, False) for name in names[:k]] + [(settled, True)]

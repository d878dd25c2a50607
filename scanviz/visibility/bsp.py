"""Binary space partitioning (Fuchs, Kedem and Naylor): build a tree of planes, display it in order.

As on the UMBC slides (MakeBSP, DisplayBSP): take a root polygon from the
list, put every other polygon in the list of the side of the root's plane
it lies on, split the ones that straddle it into a front and a back part,
and build both lists the same way. To display, at each node draw first the
subtree on the side away from the viewer, then the node's polygons, then
the other subtree: back to front, the painter's order made right by the
planes. Front to back (``order="front_to_back"``) reverses every node's
order and paints with a coverage mask (mode "under": a sample is written
only while still empty), so each sample is written once.

**Screen space.** The tree is built from `Surfaces`, in screen space: the
perspective map takes planes to planes and keeps the side of a plane a
point in front of the eye is on, so splitting there by the screen-space
planes makes the same partition, and the same tree, as in the world. A
node's plane is its root polygon's plane, with its sides named after the
polygon's orientation (its normal points to the front). The viewer, at
z = -inf here, is on the front side exactly when the polygon faces it: the
back-face test, which in screen space reads Newell's c > 0, i.e. the
polygon is counter-clockwise on the screen (`Surfaces.front_facing`). So a
piece that `Surfaces.classify` finds FRONT (nearer the viewer than the
plane) is in the node's front list if the node's polygon is front-facing
and in its back list otherwise, and the display draws the viewer's far
side first, as the world-space tree would.

**Classification** is `Surfaces.classify`'s, vectorised over a node's whole
list: a vertex within ``surfaces.tolerance`` = `PLANE_TOLERANCE` x max(1,
max |z|) of the plane in depth counts as on it; a piece with vertices
beyond the tolerance on both sides straddles and is split by
`Surfaces.split`, whose two parts partition the piece's samples exactly;
pieces on the plane (coplanar) stay at the node, drawn with its root.

``root`` chooses each node's root: "first" in the list (the list is the
input order, or `sequence` first), "fewest_splits" (of the first
`candidates` pieces of the list, the one whose plane splits fewest of the
others; ties to the earliest) or "random" (uniform, from a generator seeded
by `seed`). The build and the display use explicit stacks, so a deep tree
needs no Python recursion; the number of pieces is checked against the
memory limit (`scanviz.limits`) as it grows, which bounds the work on
hostile input (every plane splitting every polygon). See docs/visibility-bsp.md.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from .. import steps
from ..conventions import check_choice
from ..limits import check_memory
from ..trace.display import RichDisplay
from ..trace.events import BspCandidate, BspNode, BspVisited, PolygonSplit
from .interface import (
    Decision,
    Visibility,
    budget,
    check_budget,
    over_budget,
    piece_record,
    register,
)
from .screen_polygons import BEHIND, FRONT, ON, STRADDLES, Piece, Surfaces

ROOTS = ("first", "fewest_splits", "random")
ORDERS = ("back_to_front", "front_to_back")
PARTS = ("back", "self", "front")
PIECE_BYTES = 2048  # a piece, its vertices and cuts, and its place in the lists: an upper estimate
PIECES_PER_POLYGON = 8  # the default piece budget: this many per polygon, plus PIECES_SPARE
PIECES_SPARE = 4096


@dataclass(frozen=True)
class BspTreeNode:
    """One node: its root polygon, the labels of its pieces (the root's first, then the coplanar
    ones), its children's node numbers (-1: none), its parent (-1 at the root) and its depth."""

    node: int
    polygon: int
    pieces: tuple[str, ...]
    front: int = -1
    back: int = -1
    parent: int = -1
    side: str = "root"
    depth: int = 0


@dataclass(frozen=True)
class BspTree:
    """The tree as built and as displayed.

    ``nodes[k]`` is node k (numbered as built: depth first, front subtree
    first; node 0 is the root); ``visits`` the nodes in the order the display
    reached them; ``painted`` the nodes in the order their pieces were
    painted; ``painted_before[i]`` how many nodes were painted when
    ``visits[i]`` was reached (for showing the image so far).
    """

    nodes: tuple[BspTreeNode, ...] = ()
    visits: tuple[int, ...] = ()
    painted: tuple[int, ...] = ()
    painted_before: tuple[int, ...] = ()

    @property
    def height(self) -> int:
        """Levels of the tree (0: empty, 1: a root alone)."""
        return 1 + max((n.depth for n in self.nodes), default=-1)


@dataclass
class BspStats(RichDisplay):
    """nodes, splits (straddling pieces cut), depth (the tree's height), pieces painted,
    left_out (polygons seen edge-on or off the raster)."""

    nodes: int = 0
    splits: int = 0
    depth: int = 0
    pieces: int = 0
    left_out: int = 0


@steps.step(
    "bsp_display_order",
    takes="viewer_in_front: the viewer is on the front side of the node's plane; front_to_back: "
    "the display's direction (False: back to front)",
    returns='the order of the node\'s parts, a permutation of ("back", "self", "front"): '
    "the side away from the viewer first when back to front, the viewer's side first otherwise",
)
def display_order(viewer_in_front: bool, front_to_back: bool) -> tuple[str, str, str]:
    """DisplayBSP at one node: which subtree to draw first, then the node itself, then the other.

    Examples
    --------
    >>> display_order(True, False), display_order(False, False)
    (('back', 'self', 'front'), ('front', 'self', 'back'))
    >>> display_order(True, True)
    ('front', 'self', 'back')
    """
    far, near = ("back", "front") if viewer_in_front else ("front", "back")
    return (near, "self", far) if front_to_back else (far, "self", near)


def classify_all(surfaces: Surfaces, pieces: list[Piece], q: int) -> np.ndarray:
    """`Surfaces.classify` of each piece against q's plane, vectorised: (m,) ndarray of str."""
    if not pieces:
        return np.array([], dtype=str)
    vertices = np.concatenate([piece.vertices for piece in pieces])
    sizes = [len(piece.vertices) for piece in pieces]
    starts = np.cumsum([0] + sizes[:-1])
    owners = np.repeat([piece.polygon for piece in pieces], sizes)
    d = surfaces.vertex_gaps(vertices, owners, q)
    far = np.logical_or.reduceat(d > surfaces.tolerance, starts)
    near = np.logical_or.reduceat(d < -surfaces.tolerance, starts)
    return np.where(far & near, STRADDLES, np.where(far, BEHIND, np.where(near, FRONT, ON)))


@dataclass
class _Task:
    """A list still to build a subtree from, and where the subtree hangs."""

    pieces: list[Piece]
    parent: int = -1
    side: str = "root"
    depth: int = 0


@dataclass
class _Builder:
    """The state of one build: the nodes so far, their pieces, the counts and the generator."""

    surfaces: Surfaces
    options: BSP
    tracer: object
    rng: np.random.Generator
    nodes: list[dict] = field(default_factory=list)
    node_pieces: list[list[Piece]] = field(default_factory=list)
    splits: int = 0
    pieces: int = 0
    checked: int = 1024
    budget: int = 0  # the most pieces the build may make

    def build(self, pieces: list[Piece]) -> None:
        """MakeBSP with an explicit stack (front subtree first, so nodes number as the trace's)."""
        self.pieces = len(pieces)
        stack = [_Task(pieces)] if pieces else []
        while stack:
            task = stack.pop()
            front, back = self.node(task)
            node, depth = len(self.nodes) - 1, task.depth + 1
            if back:
                stack.append(_Task(back, node, "back", depth))
            if front:
                stack.append(_Task(front, node, "front", depth))

    def node(self, task: _Task) -> tuple[list[Piece], list[Piece]]:
        """Make the node of `task`'s list: choose a root, partition the rest; (front, back)."""
        candidates, k, sides = self.choose(task.pieces)
        root, rest = task.pieces[k], task.pieces[:k] + task.pieces[k + 1 :]
        facing = self.surfaces.front_facing(root.polygon)
        front, back, coplanar = [], [], [root]
        for piece, side in zip(rest, sides.tolist(), strict=True):
            if side == ON:
                coplanar.append(piece)
                continue
            if side == STRADDLES:
                nearer, farther = self.split(piece, root.polygon)
            else:
                nearer, farther = (piece, None) if side == FRONT else (None, piece)
            # The viewer's side (nearer) is the front side iff the root faces the viewer.
            viewer_side, far_side = (front, back) if facing else (back, front)
            for part, to in ((nearer, viewer_side), (farther, far_side)):
                if part is not None:
                    to.append(part)
        self.add_node(task, coplanar, front, back, candidates)
        return front, back

    def add_node(self, task, coplanar, front, back, candidates) -> None:
        """Record the node (its root and coplanar pieces), link it to its parent, trace it."""
        number, root = len(self.nodes), coplanar[0]
        labels = tuple(p.label for p in coplanar)
        self.nodes.append(
            {
                "node": number,
                "polygon": root.polygon,
                "pieces": labels,
                "parent": task.parent,
                "side": task.side,
                "depth": task.depth,
            }
        )
        self.node_pieces.append(coplanar)
        if task.parent >= 0:
            self.nodes[task.parent][task.side] = number
        if self.tracer is not None and self.tracer.wants("bsp_node", polygon=root.polygon):
            self.tracer.emit(
                BspNode(
                    number,
                    task.parent,
                    task.side,
                    task.depth,
                    root.polygon,
                    root.label,
                    tuple(p.label for p in front),
                    tuple(p.label for p in back),
                    labels[1:],
                    candidates,
                )
            )

    def choose(self, pieces: list[Piece]) -> tuple[tuple[BspCandidate, ...], int, np.ndarray]:
        """The candidates with their splits, the root's index in `pieces` by the root rule, and
        the sides of the other pieces of its plane."""
        rule = self.options.root
        if rule == "fewest_splits":
            considered = range(min(self.options.candidates, len(pieces)))
        elif rule == "random":
            considered = [int(self.rng.integers(len(pieces)))]
        else:
            considered = [0]
        sides = {
            k: classify_all(self.surfaces, pieces[:k] + pieces[k + 1 :], pieces[k].polygon)
            for k in considered
        }
        counted = [(int((sides[k] == STRADDLES).sum()), k) for k in considered]
        best = min(counted)[1]  # fewest splits, then the earliest
        return tuple(BspCandidate(pieces[k].label, s) for s, k in counted), best, sides[best]

    def split(self, piece: Piece, q: int) -> tuple[Piece, Piece]:
        """`Surfaces.split`, counted against the memory limit and traced (why: "straddles")."""
        nearer, farther = self.surfaces.split(piece, q)
        self.splits += 1
        self.pieces += 1
        if self.pieces > self.budget:
            advice = "its planes cut the polygons over and over"
            raise over_budget("the BSP tree's pieces", self.budget, "max_pieces", advice)
        if self.pieces >= self.checked:
            check_memory(self.pieces * PIECE_BYTES, f"a BSP tree of {self.pieces} pieces so far")
            self.checked = 2 * self.pieces  # check again when it has doubled
        if self.tracer is not None and self.tracer.wants("polygon_split", polygon=piece.polygon):
            self.tracer.emit(
                PolygonSplit(
                    piece.polygon,
                    piece.label,
                    q,
                    "straddles",
                    piece_record(nearer),
                    piece_record(farther),
                )
            )
        return nearer, farther

    def tree_nodes(self) -> tuple[BspTreeNode, ...]:
        """The nodes built, frozen."""
        return tuple(BspTreeNode(**node) for node in self.nodes)


def display(surfaces: Surfaces, nodes, pieces: list[list[Piece]], front_to_back: bool, tracer):
    """DisplayBSP with an explicit stack: the pieces in painting order, the visits, the nodes
    painted, and per visit the nodes painted before it."""
    order, visits, painted, before = [], [], [], []
    choose = steps.get("bsp_display_order")
    stack = [("visit", 0)] if nodes else []
    while stack:
        action, number = stack.pop()
        node = nodes[number]
        if action == "self":
            painted.append(number)
            order.extend(pieces[number])
            continue
        in_front = surfaces.front_facing(node.polygon)
        sequence = _checked_order(choose(in_front, front_to_back))
        visits.append(number)
        before.append(len(painted))
        if tracer is not None and tracer.wants("bsp_visited", polygon=node.polygon):
            first = next(part for part in sequence if part != "self")
            tracer.emit(BspVisited(number, node.pieces[0], in_front, first))
        for part in reversed(sequence):
            child = number if part == "self" else getattr(node, part)
            if child >= 0:
                stack.append(("self" if part == "self" else "visit", child))
    return order, tuple(visits), tuple(painted), tuple(before)


def _checked_order(sequence: object) -> tuple[str, ...]:
    """The display step's answer as a tuple, if it is an ordering of PARTS."""
    try:
        parts = tuple(sequence)
    except TypeError:
        parts = ()
    if sorted(parts, key=str) != sorted(PARTS):
        raise ValueError(
            f"step 'bsp_display_order' must return an ordering of {PARTS}; got {sequence!r}"
        )
    return parts


@register
@dataclass(frozen=True)
class BSP(Visibility):
    """A BSP tree built in screen space and displayed for the viewer (see the module).

    Parameters
    ----------
    root : {"first", "fewest_splits", "random"}
        How each node's root is chosen from its list.
    order : {"back_to_front", "front_to_back"}
        The display's direction; front to back paints with a coverage mask.
    candidates : int
        Pieces (the first of the list) "fewest_splits" considers at each node.
    seed : int
        Seeds the generator of "random".
    sequence : tuple of int
        Polygon ids put first in the list, in this order (the others follow in
        input order); ids of polygons that take no part are ignored.
    max_pieces : int or None
        The most pieces the tree may hold; building past it raises
        `scanviz.limits.ResourceLimitError`. None: `PIECES_PER_POLYGON` per
        polygon plus `PIECES_SPARE` (the pieces, and with them the time, can
        grow as the square of the polygons where every plane cuts every
        polygon).

    Examples
    --------
    >>> from scanviz.visibility import ScreenPolygons, solve
    >>> scene = ScreenPolygons.from_polygons([
    ...     [(0, 0, 1), (8, 0, 1), (0, 8, 1)],  # near, front-facing
    ...     [(2, 2, 9), (8, 2, 9), (2, 8, 9)],  # far
    ... ])
    >>> result = solve(BSP(), scene, 8, 8)
    >>> [n.pieces for n in result.detail.nodes], [p.label for p in result.order]
    ([('0',), ('1',)], ['1', '0'])
    >>> result.detail.nodes[0].back, int(result.polygon[3, 3])
    (1, 0)
    """

    name: ClassVar[str] = "bsp"
    root: str = "first"
    order: str = "back_to_front"
    candidates: int = 5
    seed: int = 0
    sequence: tuple[int, ...] = ()
    max_pieces: int | None = None

    def __post_init__(self) -> None:
        check_choice("root", self.root, ROOTS)
        check_budget("max_pieces", self.max_pieces, 1)
        check_choice("order", self.order, ORDERS)
        for name in ("candidates", "seed"):
            value = getattr(self, name)
            if not isinstance(value, int | np.integer) or isinstance(value, bool):
                raise TypeError(f"{name!r} must be an int; got {value!r}")
        if self.candidates < 1:
            raise ValueError(f"'candidates' must be at least 1; got {self.candidates}")
        if not isinstance(self.sequence, tuple) or not all(
            isinstance(p, int | np.integer) and not isinstance(p, bool) and p >= 0
            for p in self.sequence
        ):
            raise TypeError(
                f"'sequence' must be a tuple of polygon ids (ints >= 0); got {self.sequence!r}"
            )
        if len(set(self.sequence)) != len(self.sequence):
            raise ValueError(f"'sequence' must not repeat a polygon; got {self.sequence!r}")

    def decide(self, surfaces: Surfaces, tracer) -> Decision:
        pieces = self.listed(surfaces)
        builder = _Builder(surfaces, self, tracer, np.random.default_rng(self.seed))
        builder.budget = budget(self.max_pieces, PIECES_PER_POLYGON, PIECES_SPARE, len(pieces))
        builder.build(pieces)
        nodes = builder.tree_nodes()
        front_to_back = self.order == "front_to_back"
        order, visits, painted, before = display(
            surfaces, nodes, builder.node_pieces, front_to_back, tracer
        )
        tree = BspTree(nodes, visits, painted, before)
        left_out = surfaces.count - len(pieces)
        stats = BspStats(len(nodes), builder.splits, tree.height, len(order), left_out)
        return Decision(stats, tuple(order), "under" if front_to_back else "over", detail=tree)

    def depth_slack(self, surfaces: Surfaces, stats: object) -> float:
        """2 x the tolerance: a piece on the far side of a node's plane may come within the
        tolerance in front of it, a piece on the near side within the tolerance behind it."""
        return 2 * surfaces.tolerance

    def listed(self, surfaces: Surfaces) -> list[Piece]:
        """The polygon list MakeBSP starts from: `sequence` first, then input order."""
        bad = [p for p in self.sequence if p >= surfaces.count]
        if bad:
            raise ValueError(
                f"'sequence' names polygon {bad[0]}, but the scene has {surfaces.count} polygons"
            )
        rank = {p: k for k, p in enumerate(self.sequence)}
        pieces = surfaces.pieces()
        return sorted(pieces, key=lambda piece: rank.get(piece.polygon, len(rank)))

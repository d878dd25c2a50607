"""Step through a BSP tree: its build, node by node, then its display, beside the images.

`BspView` draws what a traced `solve` with `scanviz.visibility.bsp.BSP`
recorded: the tree as a graph (front children to the left, as in Foley et
al.), the screen partition (every final piece's region in its polygon's
color, the line of each split made so far), the painting order, the image
painted so far, the final image and the z-buffer's. The steps are the
``bsp_node`` and ``polygon_split`` events of the build, then the
``bsp_visited`` events of the display. `bsp_stepper` runs the algorithm and
wraps the view in a `Stepper`.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np

from ..trace import Trace
from ..visibility.bsp import BSP
from ._common import WIDEST, html_table, listed, pixel_image, quiet_canvas, status_label
from .stepper import Stepper, figure_widget, refresh_figure, stepper_of
from .visibility import against_zbuffer, polygon_color, polygon_colors, solve_traced

STEP_KINDS = ("bsp_node", "polygon_split", "bsp_visited")
TRACE_KINDS = (*STEP_KINDS, "paint_order", "pixel_painted")
# Boxes: filled by node state (current as in the tables), edged in their polygon's color.
CURRENT, PAINTED, BUILT, PENDING = "#ffe9a8", "#9bc53d", "#ffffff", "#eeeeee"
TREE_EDGE = "0.35"  # grey, not red: red marks samples that differ from the z-buffer
EDGE_STYLES = {"front": "-", "back": "--"}
LABEL_BOX = {"fc": "white", "ec": "none", "alpha": 0.8, "pad": 1}  # labels stay legible over lines


def tree_layout(tree) -> dict[int, tuple[float, float]]:
    """(x, y) of each node: x its rank in order (front subtree, node, back subtree), y -depth."""
    places, stack, rank = {}, [(0, False)] if tree.nodes else [], 0
    while stack:
        number, expanded = stack.pop()
        node = tree.nodes[number]
        if expanded:
            places[number] = (float(rank), -float(node.depth))
            rank += 1
            continue
        if node.back >= 0:
            stack.append((node.back, False))
        stack.append((number, True))
        if node.front >= 0:
            stack.append((node.front, False))
    return places


class BspView:
    """The BSP tree, the screen partition and the painting order after `step` build/display events.

    Parameters
    ----------
    trace : Trace
        Events of a traced BSP `solve`: ``bsp_node``, ``polygon_split``,
        ``bsp_visited``, ``paint_order`` and ``pixel_painted``.
    result : VisibilityResult
        The same run: its ``detail`` is the tree (`BspTree`), its ``polygon`` the final ids.
    zbuffer_result : ZBufferResult
        The z-buffer's run of the same polygons, shown beside it.

    Attributes
    ----------
    steps : Trace
        The events a step moves over (`STEP_KINDS`); a `Stepper` drives `show`.
    widget : ipywidgets.VBox
    event : ipywidgets.HTML
        The current step in words: a node and its lists, a split, a visit.
    order : ipywidgets.HTML
        The painting order; the pieces painted so far in bold, the current node's highlighted.
    node_boxes : dict of int to matplotlib Text
        The tree's nodes (their boxes are colored: pending, built, current, painted).
    split_lines : list of matplotlib Line2D
        One per split, in the partition panel; visible once the split is made.
    so_far : matplotlib AxesImage
        The image painted after the pieces painted so far.
    """

    def __init__(self, trace: Trace, result, zbuffer_result) -> None:
        self.trace, self.result, self.tree = trace, result, result.detail
        self.steps = trace.of_kind(*STEP_KINDS)
        self.height, self.width = result.polygon.shape
        painted = [e for e in trace if e.kind == "paint_order"]
        self.pieces = painted[0].pieces if painted else ()
        pixels = [e for e in trace if e.kind == "pixel_painted"]
        self._piece_ends = _ends_of_pieces(self.pieces, pixels)
        self._pixel_x = np.array([e.x for e in pixels], np.int64)
        self._pixel_y = np.array([e.y for e in pixels], np.int64)
        self._pixel_polygon = np.array([e.polygon for e in pixels], np.int64)
        self._pixel_painted = np.array([e.painted for e in pixels], bool)
        self._node_of = {(n.polygon, label): n.node for n in self.tree.nodes for label in n.pieces}
        self._build_figure(zbuffer_result)
        self.event, self.order, self.note = widgets.HTML(), widgets.HTML(), status_label()
        self._canvas = figure_widget(self.figure)
        self.widget = widgets.VBox(
            [
                self.note,
                self._canvas,
                widgets.HBox([self.event, self.order], layout={"flex_flow": "row wrap"}),
            ]
        )
        self.step = 0
        self.show(0)

    def _build_figure(self, zbuffer_result) -> None:
        import matplotlib.pyplot as plt

        with plt.ioff():
            fig = plt.figure(figsize=(WIDEST, 6.5))
        quiet_canvas(fig)
        grid = fig.add_gridspec(2, 3, height_ratios=(1.1, 1))
        ax_tree, ax_part = fig.add_subplot(grid[0, :2]), fig.add_subplot(grid[0, 2])
        ax_now, ax_final, ax_z = (fig.add_subplot(grid[1, k]) for k in range(3))
        self._draw_tree(ax_tree)
        self._draw_partition(ax_part)
        blank = polygon_colors(np.full((self.height, self.width), -1))
        self.so_far = pixel_image(ax_now, blank, offset=-0.5)  # pixel squares on samples
        against_zbuffer(ax_final, ax_z, self.result.polygon, zbuffer_result.polygon, offset=-0.5)
        titles = ("painted so far", "BSP: final", "z-buffer (red: BSP differs)")
        for ax, title in zip((ax_now, ax_final, ax_z), titles, strict=True):
            ax.set_title(title, fontsize=10)
        self.figure, self.axes = fig, (ax_tree, ax_part, ax_now, ax_final, ax_z)
        fig.tight_layout()

    def _draw_tree(self, ax) -> None:
        places = tree_layout(self.tree)
        self.node_boxes = {}
        for node in self.tree.nodes:
            x, y = places[node.node]
            for side, style in EDGE_STYLES.items():
                child = getattr(node, side)
                if child >= 0:
                    cx, cy = places[child]
                    ax.plot([x, cx], [y, cy], color=TREE_EDGE, ls=style, lw=1.2, zorder=1)
                    ax.text(
                        (x + cx) / 2,
                        (y + cy) / 2,
                        side,
                        color=TREE_EDGE,
                        fontsize=9,
                        ha="center",
                        va="center",
                        bbox=LABEL_BOX,
                    )
            self.node_boxes[node.node] = ax.text(
                x,
                y,
                ", ".join(node.pieces),
                ha="center",
                va="center",
                fontsize=11,
                zorder=2,
                bbox={
                    "boxstyle": "round",
                    "fc": PENDING,
                    "ec": polygon_color(node.polygon),
                    "lw": 2.5,
                },
            )
        xs = [p[0] for p in places.values()] or [0.0]
        ys = [p[1] for p in places.values()] or [0.0]
        ax.set_xlim(min(xs) - 0.7, max(xs) + 0.7)
        ax.set_ylim(min(ys) - 0.6, max(ys) + 0.6)
        ax.set_axis_off()
        ax.set_title("BSP tree (front to the left, back to the right)", fontsize=10)

    def _draw_partition(self, ax) -> None:
        from matplotlib.patches import Polygon

        self.regions = {}
        for piece in self.pieces:
            xy = np.array(piece.vertices)[:, :2]
            color = polygon_color(piece.polygon)
            patch = Polygon(xy, closed=True, fc=color, ec="0.3", lw=0.5, alpha=0.45)
            self.regions[piece.polygon, piece.label] = ax.add_patch(patch)
            centre = xy.mean(axis=0)
            ax.text(
                *centre,
                piece.label,
                fontsize=9,
                ha="center",
                va="center",
                bbox=LABEL_BOX,
                clip_on=True,
            )
        self.split_lines = []
        for event in self.steps:
            if event.kind == "polygon_split":
                ends = _shared_points(event.front.vertices, event.behind.vertices)
                (line,) = ax.plot(*ends.T, color="k", lw=1.5, ls="--", visible=False)
                self.split_lines.append(line)
        ax.set_xlim(-0.5, self.width - 0.5)
        ax.set_ylim(-0.5, self.height - 0.5)
        ax.set_aspect("equal")
        ax.set_title("screen partition (dashed: splits)", fontsize=10)

    def painted_count(self, step: int) -> int:
        """How many nodes the display has painted after the first `step` steps."""
        visits = [e for e in self.steps[:step] if e.kind == "bsp_visited"]
        if step >= len(self.steps) and visits:
            return len(self.tree.painted)
        return self.tree.painted_before[len(visits) - 1] if visits else 0

    def show(self, step: int) -> None:
        """Show the tree, partition, order and images after the first `step` steps."""
        self.step = int(step)
        shown = self.steps[: self.step]
        current = shown[-1] if len(shown) else None
        built = {e.node for e in shown if e.kind == "bsp_node"}
        painted_nodes = self.tree.painted[: self.painted_count(self.step)]
        focus = self._focus(current)
        for number, box in self.node_boxes.items():
            state = (number == focus, number in painted_nodes, number in built)
            box.get_bbox_patch().set_facecolor(_state_color(*state))
            box.set_fontweight("bold" if number == focus else "normal")
        splits = sum(e.kind == "polygon_split" for e in shown)
        for k, line in enumerate(self.split_lines):
            line.set_visible(k < splits)
        focused = set(self.tree.nodes[focus].pieces) if focus >= 0 else set()
        for (polygon, label), patch in self.regions.items():
            mine = focus >= 0 and polygon == self.tree.nodes[focus].polygon and label in focused
            patch.set_linewidth(2.5 if mine else 0.5)
            patch.set_edgecolor("black" if mine else "0.3")
        pieces_painted = sum(len(self.tree.nodes[n].pieces) for n in painted_nodes)
        self.so_far.set_data(polygon_colors(self._ids_after(pieces_painted)))
        self.event.value = _describe(current)
        self._show_order(pieces_painted, focused, focus)
        refresh_figure(self.figure, self._canvas)

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the node built, the piece split, or the node visited."""
        if step == 0:
            return (
                f"The start: {len(self.pieces)} pieces to place in a tree of planes, which is "
                "then walked from the viewpoint to paint them back to front."
            )
        event = self.steps[step - 1]
        if event.kind == "polygon_split":
            return (
                f"Piece {event.piece} straddles the plane of polygon {event.by}, so it is split: "
                f"{event.front.label} lies in front of that plane and {event.behind.label} behind."
            )
        if event.kind == "bsp_node":
            where = (
                "the root" if event.parent < 0 else f"the {event.side} child of node {event.parent}"
            )
            sides = [
                f"{listed(event.front, 'nothing')} in front of its plane",
                f"{listed(event.back, 'nothing')} behind",
            ] + ([f"{listed(event.coplanar, 'nothing')} on it"] if event.coplanar else [])
            if not (event.front or event.back or event.coplanar):
                sides = ["a leaf, as no other piece is left in its part of space"]
            chosen = next((c for c in event.candidates if c.label == event.piece), None)
            choice = (
                f", chosen from {len(event.candidates)} candidates as making the fewest "
                f"splits ({chosen.splits})"
                if chosen is not None and len(event.candidates) > 1
                else ""
            )
            return (
                f"Node {event.node}, {where}, takes piece {event.piece}{choice}: "
                + "; ".join(sides)
                + "."
            )
        visits = sum(e.kind == "bsp_visited" for e in self.steps[:step])
        before = self.tree.painted[: self.tree.painted_before[visits - 1]]
        done = listed((label for n in before for label in self.tree.nodes[n].pieces), "nothing")
        node = self.tree.nodes[event.node]
        if node.front < 0 and node.back < 0:
            after = f"after {done}" if before else "the first"
            return f"Node {event.node} is a leaf, so piece {event.piece} is painted now, {after}."
        side = "in front of" if event.viewer_in_front else "behind"
        later = "front" if event.first == "back" else "back"
        return (
            f"At node {event.node} (piece {event.piece}) the viewpoint is {side} its plane, so "
            f"the {event.first} subtree is displayed first, then {event.piece}, then the "
            f"{later} subtree; painted so far: {done}."
        )

    @staticmethod
    def _focus(event) -> int:
        """The node the current step is about (-1: none, or a split)."""
        return -1 if event is None or event.kind == "polygon_split" else event.node

    def _ids_after(self, pieces: int) -> np.ndarray:
        """The ids the first `pieces` pieces painted, from their `pixel_painted` events."""
        ids = np.full((self.height, self.width), -1, np.int64)
        done = np.flatnonzero(self._pixel_painted[: self._piece_ends[pieces - 1] if pieces else 0])
        # The last write to each sample wins: the first of each sample in reverse order.
        flat = (self._pixel_y[done] * self.width + self._pixel_x[done])[::-1]
        _, first = np.unique(flat, return_index=True)
        last = done[::-1][first]
        ids[self._pixel_y[last], self._pixel_x[last]] = self._pixel_polygon[last]
        return ids

    def _show_order(self, painted: int, focused: set, focus: int) -> None:
        rows, states = [], []
        for k, piece in enumerate(self.pieces):
            node = self._node_of.get((piece.polygon, piece.label), -1)
            rows.append((k + 1, piece.label, piece.polygon, node))
            current = node == focus and piece.label in focused
            states.append("current" if current else "done" if k < painted else "pending")
        self.order.value = "<b>painting order</b>" + html_table(
            ("#", "piece", "polygon", "node"), rows, states=states
        )


def _state_color(current: bool, painted: bool, built: bool) -> str:
    return CURRENT if current else PAINTED if painted else BUILT if built else PENDING


def _ends_of_pieces(pieces, pixels) -> list[int]:
    """For each piece in painting order, the index after its last `pixel_painted` event."""
    ends, k = [], 0
    for piece in pieces:
        key = (piece.polygon, piece.label)
        while k < len(pixels) and (pixels[k].polygon, pixels[k].piece) == key:
            k += 1
        ends.append(k)
    return ends


def _shared_points(front, behind) -> np.ndarray:
    """The two ends of a split: the vertices both parts have (the cut's crossings)."""
    theirs = {tuple(v) for v in behind}
    shared = [v[:2] for v in front if tuple(v) in theirs]
    return np.array(shared or [(np.nan, np.nan)], np.float64).reshape(-1, 2)


def _names(labels) -> str:
    return html.escape(", ".join(labels) or "none")


def _describe(event) -> str:
    """The step in words."""
    if event is None:
        return "<i>start: the polygon list, before the first node</i>"
    if event.kind == "bsp_node":
        candidates = "; ".join(f"{c.label}: {c.splits}" for c in event.candidates)
        return (
            f"<b>node {event.node}</b> (depth {event.depth}, {event.side} of node {event.parent}):"
            f" root {html.escape(event.piece)}<br>front: {_names(event.front)}<br>"
            f"back: {_names(event.back)}<br>coplanar: {_names(event.coplanar)}<br>"
            f"candidates (splits): {html.escape(candidates)}"
        )
    if event.kind == "polygon_split":
        return (
            f"<b>split</b> {html.escape(event.piece)} by the plane of polygon {event.by} "
            f"({event.why}): {html.escape(event.front.label)} in front (nearer), "
            f"{html.escape(event.behind.label)} behind"
        )
    side = "front" if event.viewer_in_front else "back"
    return (
        f"<b>at {html.escape(event.piece)}</b> (node {event.node}): viewpoint on {side} "
        f"&rarr; display {event.first} first"
    )


def bsp_stepper(polygons, width: int, height: int, **options) -> Stepper:
    """Run BSP on `polygons` (a `ScreenPolygons`) traced and step through build and display.

    Parameters
    ----------
    polygons : ScreenPolygons
    width, height : int
        Raster size.
    **options
        `BSP` options (root, order, candidates, seed, sequence), then `solve`'s
        (sample, subpixel_bits, perspective).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `BspView`.

    Examples
    --------
    >>> from scanviz.visibility import examples
    >>> stepper = bsp_stepper(examples.slides_bsp(), 32, 24, sequence=examples.BSP_SEQUENCE)
    >>> stepper.slider.max, stepper.views[0].tree.nodes[0].pieces
    (13, ('3',))
    """
    fields = {"root", "order", "candidates", "seed", "sequence"}
    chosen = BSP(**{k: v for k, v in options.items() if k in fields})
    rest = {k: v for k, v in options.items() if k not in fields}
    result, reference = solve_traced(chosen, polygons, width, height, TRACE_KINDS, **rest)
    view = BspView(result.trace, result, reference)
    return stepper_of(view, "BSP tree: build, then display", "steps")

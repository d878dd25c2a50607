"""
A BSP tree: the splits and the back-to-front order
==================================================

A binary space partitioning tree (Fuchs, Kedem and Naylor 1980; Foley et al.
1990, §15.5.2) is built once: a root polygon's plane sorts the others into a
front and a back list, cutting any polygon that straddles it, and each list is
built the same way. To display, each node's far side from the viewer is drawn
first, then the node, then its near side: a back-to-front order for any eye.
Here the UMBC slides' five walls, with polygon 3 as the root, whose plane
cuts wall 5 into 5a (in front) and 5b (behind).
"""

import matplotlib.pyplot as plt
import numpy as np

import scanviz as sv
from scanviz.visibility import examples, solve
from scanviz.visibility.bsp import BSP

walls = examples.slides_bsp()
result = solve(
    BSP(sequence=examples.BSP_SEQUENCE),
    walls,
    32,
    24,
    trace=sv.Recorder(kinds=["polygon_split"]),
)
nodes = result.detail.nodes

# %%
# Lay the tree out: x is each node's place in an in-order walk, y its depth.

column = {}


def place(node):
    if node == -1:
        return
    place(nodes[node].front)
    column[node] = len(column)
    place(nodes[node].back)


place(0)

fig, (tree_ax, image_ax) = plt.subplots(1, 2, figsize=(10, 4.8))
for node in nodes:
    x, y = column[node.node], -node.depth
    for child, side in ((node.front, "front"), (node.back, "back")):
        if child != -1:
            cx, cy = column[child], -nodes[child].depth
            tree_ax.plot([x, cx], [y, cy], color="grey", zorder=1)
            tree_ax.text((x + cx) / 2, (y + cy) / 2, side, fontsize=9, ha="center", color="grey")
    tree_ax.scatter(x, y, s=700, color=f"C{node.polygon}", zorder=2)
    tree_ax.text(x, y, ", ".join(node.pieces), ha="center", va="center", color="white", zorder=3)
splits = [f"{e.piece} cut by the plane of {e.by}" for e in result.trace.of_kind("polygon_split")]
tree_ax.set_title(f"the tree: {len(nodes)} nodes; " + "; ".join(splits), fontsize=10)
tree_ax.set_xlim(-0.7, len(nodes) - 0.3)
tree_ax.set_ylim(-max(n.depth for n in nodes) - 0.6, 0.6)
tree_ax.set_axis_off()

# %%
# The pieces as painted, back to front: each outlined on the screen and
# numbered with its place in the painting order.

visible = np.ma.masked_less(result.polygon, 0)
image_ax.imshow(visible, origin="lower", cmap="tab10", vmin=-0.5, vmax=9.5, alpha=0.6)
for step, piece in enumerate(result.order, start=1):
    xy = piece.vertices[:, :2]
    colour = f"C{piece.polygon}"
    image_ax.add_patch(plt.Polygon(xy, fill=False, edgecolor=colour, lw=2))
    centre = xy.mean(axis=0)
    image_ax.text(*centre, f"{step}: {piece.label}", ha="center", va="center", fontsize=8)
order = " → ".join(piece.label for piece in result.order)
image_ax.set_title(
    f"painting order {order}\n(filled: the wall each pixel shows; outlined: the pieces)",
    fontsize=10,
)
image_ax.set_xlabel("x (pixels)")
image_ax.set_ylabel("y (pixels)")
fig.tight_layout()
plt.show()

"""
The z-buffer on the slides' three polygons
==========================================

The z-buffer (Catmull 1974) keeps, for every pixel, the depth of the nearest
fragment drawn so far and which polygon it came from; a new fragment is
written only if it is strictly nearer. On the UMBC slides' example
(Rheingans, "Z-Buffer") a triangle at depth 5 lies in front of a square at
depth 9, and a third, sloped triangle pierces the first one, so neither is
entirely in front: the depth buffer decides pixel by pixel. Depths are shown
in the slides' units (smaller is nearer), read back from the buffer's [0, 1].
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap

from scanviz import load_scene, render
from scanviz.scene.builtin import SLIDE_DEPTH

scene = load_scene("builtin:umbc_zbuffer")
size = 12
result = render(scene, size, size, shading="flat")
slide_depth = np.where(np.isinf(result.depth), np.nan, result.depth * SLIDE_DEPTH)

# %%
# The frame, the depth buffer and the polygon-id buffer, each cell labelled.
fig, (image_ax, depth_ax, id_ax) = plt.subplots(1, 3, figsize=(13, 4.6), layout="constrained")
extent = (0, size, 0, size)
image_ax.imshow(result.image, origin="lower", extent=extent)
image_ax.set_title(
    f"frame: {result.stats.depth_passed} writes, {result.stats.depth_failed} rejected"
)

shown = depth_ax.imshow(slide_depth, origin="lower", cmap="viridis_r", extent=extent)
depth_ax.set_title("depth buffer (empty: +inf)")
fig.colorbar(shown, ax=depth_ax, shrink=0.8, label="depth z (slide units)")

# each polygon in a paler version of its colour, so the labels stay readable
id_colours = ListedColormap(
    ["white", *((1 + np.array(obj.material.color)) / 2 for obj in scene.objects)]
)
id_ax.imshow(
    result.polygon,
    origin="lower",
    cmap=id_colours,
    vmin=-1.5,
    vmax=len(scene.objects) - 0.5,
    extent=extent,
)
id_ax.set_title("id buffer: the nearest polygon's index")

for y, x in np.argwhere(result.polygon >= 0):
    depth = slide_depth[y, x]
    depth_ax.text(
        x + 0.5,
        y + 0.5,
        f"{depth:.3g}",
        ha="center",
        va="center",
        fontsize=7,
        color="white" if depth > 6 else "black",
    )
    id_ax.text(x + 0.5, y + 0.5, str(result.polygon[y, x]), ha="center", va="center", fontsize=9)
for ax in (image_ax, depth_ax, id_ax):
    ax.set_xticks(range(0, size + 1, 2))
    ax.set_yticks(range(0, size + 1, 2))
    ax.set_xlabel("x (pixels)")
image_ax.set_ylabel("y (pixels)")
plt.show()

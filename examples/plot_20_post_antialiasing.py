"""
Post-anti-aliasing a rendered image's edges
===========================================

Post-anti-aliasing (Wang 1989, ch. 4, "Post-anti-aliasing", and ch. 5) draws
the polygon edges after the image was rendered aliased: each edge is walked
column by column and three pixels per column are blended with areas read
from a precomputed table, instead of computed by DISLOP_L's formula. Here the
feature edges of the built-in UMBC z-buffer scene, drawn aliased, by the table,
and by DISLOP_L areas; the table route agrees with the computed areas to
within its quantisation.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import render
from scanviz.antialias.post_edges import antialiased_edges
from scanviz.scene.builtin import builtin_scene

scene = builtin_scene("umbc_zbuffer")
plain = render(scene, 200, 160)  # no edges: the background they are blended over
images = {
    "aliased edges (render(edges=True))": render(scene, 200, 160, edges=True).image,
    "post-anti-aliased (area table)": antialiased_edges(scene, plain, method="post"),
    "DISLOP_L areas, computed": antialiased_edges(scene, plain, method="dislop"),
}
table, computed = images["post-anti-aliased (area table)"], images["DISLOP_L areas, computed"]
largest = np.abs(table - computed).max()

# %%
# The top row is the whole image, the bottom row the square outlined in it.

zoom = (slice(60, 100), slice(80, 120))  # rows, columns
fig, axes = plt.subplots(2, 3, figsize=(11, 6.6), layout="constrained")
for column, (title, image) in enumerate(images.items()):
    axes[0, column].imshow(image, origin="lower")
    axes[0, column].add_patch(
        plt.Rectangle((80, 60), 40, 40, fill=False, edgecolor="tab:orange", lw=1.5)
    )
    axes[0, column].set_title(title, fontsize=10)
    axes[1, column].imshow(
        image[zoom], origin="lower", extent=(79.5, 119.5, 59.5, 99.5), interpolation="nearest"
    )
    axes[1, column].set_xlabel("x (pixels)")
axes[1, 0].set_ylabel("y (pixels)")
axes[1, 1].set_title(f"table − computed: largest difference {largest:.3f}", fontsize=10)
plt.show()

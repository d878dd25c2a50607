"""
Who owns a sample on a shared edge
==================================

Two triangles that share an edge must not leave a gap along it, nor cover a
sample twice. scanviz decides a sample exactly on an edge as if it were
nudged by an infinitesimal (epsilon, epsilon^2): edges are half-open in y, a
sample on a left edge is inside and one on a right edge outside, so a pixel
owns its left and lower borders (the top-left rule of Direct3D and OpenGL
under a y-flip; Foley et al. 1990, §3.6). Below, the samples lying exactly on
the shared edge (circled) go to the right triangle (its end points, the
quad's lowest and highest corners, to neither), and the two masks add up to
the mask of the whole quadrilateral: every sample is counted 0 or 1 times.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import scan_convert

width, height = 12, 12
left = [(3, 1), (9, 10), (1, 9)]
right = [(3, 1), (11, 4), (9, 10)]
quad = [(3, 1), (11, 4), (9, 10), (1, 9)]

left_mask = scan_convert(left, width, height).mask
right_mask = scan_convert(right, width, height).mask
count = left_mask.astype(int) + right_mask
same_as_quad = np.array_equal(count, scan_convert(quad, width, height).mask)

# %%
# The samples that lie exactly on the shared edge from (3, 1) to (9, 10).
on_edge = np.array([(3 + 2 * k, 1 + 3 * k) for k in range(4)])  # steps of (2, 3) along it

# %%
# Each cell is centred on its sample: sample (x, y) sits at the integer point.
extent = (-0.5, width - 0.5, -0.5, height - 0.5)
fig, axes = plt.subplots(1, 3, figsize=(11, 4.8), layout="constrained")
panels = [
    (left_mask, "Blues", f"left triangle: {left_mask.sum()} samples"),
    (right_mask, "Oranges", f"right triangle: {right_mask.sum()} samples"),
    (count, "Greys", f"left + right: max {count.max()}, = quad: {same_as_quad}"),
]
for ax, (image, cmap, title) in zip(axes, panels, strict=True):
    shown = ax.imshow(image, origin="lower", cmap=cmap, vmin=0, vmax=2, extent=extent)
    for triangle, colour in [(left, "tab:blue"), (right, "tab:orange")]:
        ax.add_patch(plt.Polygon(triangle, fill=False, color=colour, lw=1.5))
    ax.scatter(*on_edge.T, s=90, facecolors="none", edgecolors="crimson", lw=1.5)
    ax.set_title(title)
    ax.set_xlabel("x (pixels)")
axes[0].set_ylabel("y (pixels, row 0 at the bottom)")
fig.colorbar(shown, ax=axes[2], ticks=[0, 1, 2], shrink=0.8, label="samples covered")
fig.suptitle("Samples on the shared edge (circled) belong to exactly one triangle")
plt.show()

"""
Five classic visibility algorithms beside the z-buffer
======================================================

The z-buffer decides visibility at each sample while it paints; the classic
algorithms decide first, in object space (painter's, depth sort, BSP) or in
image space (scanline, Warnock's area subdivision), as Sutherland, Sproull and
Schumacker (1974) classify them. All six render the built-in UMBC z-buffer
scene here and each is compared with the z-buffer pixel for pixel: the
painter's single depth key fails where the sloped triangle crosses the
others, and where two polygons have exactly the same depth an algorithm may
show either one (a tie, not an error).
"""

import matplotlib.pyplot as plt

import scanviz as sv
from scanviz.scene.builtin import builtin_scene

scene = builtin_scene("umbc_zbuffer")
names = ["zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock"]
results = {name: sv.render(scene, 96, 96, visibility=name) for name in names}
reference = results["zbuffer"]

# %%
# Each panel outlines in yellow the pixels that show another polygon than the
# z-buffer, and counts how many of them are ties in depth.

fig, axes = plt.subplots(2, 3, figsize=(9, 6.4))
for ax, (name, result) in zip(axes.flat, results.items(), strict=True):
    differ = result.polygon != reference.polygon
    ties = differ & (result.depth == reference.depth)
    if name == "zbuffer":
        verdict = "the reference"
    elif not differ.any():
        verdict = "matches the z-buffer pixel for pixel"
    else:
        verdict = f"{int(differ.sum())} pixels differ, {int(ties.sum())} of them depth ties"
    ax.imshow(result.image, origin="lower")
    if differ.any():
        ax.contour(differ, levels=[0.5], colors="yellow", linewidths=1.2)
    ax.set_title(f"{name}\n{verdict}", fontsize=9)
    ax.set_axis_off()
fig.tight_layout()
plt.show()

"""
An OBJ model in every visibility mode
=====================================

The small house in ``models/house.obj`` (walls, a gabled roof and a chimney)
is read with `scanviz.load_scene` and rendered with each of the visibility
modes `render` takes: the z-buffer (Catmull 1974), the painter's algorithm,
depth sort, BSP trees, scanline visibility and Warnock's area subdivision
(Sutherland, Sproull and Schumacker 1974), and two anti-aliased ones,
Carpenter's a-buffer (1984) and the flawed z-buffer that blends coverage.
Each panel counts the pixels whose colour differs from the z-buffer's.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import scanviz as sv

# The model is models/house.obj of the repository: found from here or from the working folder.
here = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
house = next(p / "models" / "house.obj" for p in (here, *here.parents) if (p / "models").is_dir())
scene = sv.load_scene(house)

modes = ["zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock", "abuffer", "flawed"]
images = {mode: sv.render(scene, 160, 160, visibility=mode).image for mode in modes}
reference = images["zbuffer"]

# %%
# A pixel counts as different when one of its channels differs by more than
# one level of 255: the opaque algorithms agree with the z-buffer, the
# anti-aliased modes differ along the edges, where they blend.

fig, axes = plt.subplots(2, 4, figsize=(12, 6.4), layout="constrained")
for ax, (mode, image) in zip(axes.flat, images.items(), strict=True):
    differ = int((np.abs(image - reference).max(axis=-1) > 1 / 255).sum())
    ax.imshow(image, origin="lower")
    note = "the reference" if mode == "zbuffer" else f"{differ:,} pixels differ from the z-buffer"
    ax.set_title(f"{mode}\n{note}", fontsize=10)
    ax.set_axis_off()
plt.show()

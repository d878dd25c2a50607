"""
The a-buffer: pixel masks and the fragment packer
=================================================

Carpenter's a-buffer (1984) keeps, for every pixel an edge crosses, a list of
fragments: the polygon's colour, depth, exact covered area and a bit mask of
the sub-samples it covers, here 8 x 4 = 32 bits. Once every polygon is in,
the packer walks the list nearest first (Rendermatic thesis §6.3.6, eqs.
6.3-6.6): each fragment takes the part of the pixel still visible through
those in front of it (weight A), leaves the rest (Q) to those behind, and the
background gets what nobody covers. Top: three polygons crossing one pixel
and their masks; bottom: what each level of the packer takes.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap

from scanviz import area_coverage
from scanviz.abuffer import Fragments, mask_to_grid, pixel_masks, popcount, resolve

layout = "8x4"
polygons = {
    "red": ([(-0.2, -0.1), (0.5, -0.2), (0.3, 0.8), (-0.1, 0.9)], 0.2, (0.9, 0.2, 0.2)),
    "green": ([(-0.3, -0.3), (1.3, -0.3), (1.3, 0.3), (-0.3, 0.45)], 0.4, (0.2, 0.75, 0.3)),
    "blue": ([(0.45, 0.2), (1.2, -0.1), (1.1, 1.15), (0.7, 0.95)], 0.6, (0.25, 0.35, 0.9)),
}
background = (0.0, 0.0, 0.0)

# %%
# One fragment per polygon at pixel (0, 0): its mask, its exact area, its depth.
rows = []
for number, (outline, depth, colour) in enumerate(polygons.values()):
    mask = pixel_masks(outline, 1, 1, mask=layout).masks[0]
    area = area_coverage(outline, 1, 1)[0, 0]
    rows.append(
        dict(x=0, y=0, mask=int(mask), area=float(area), z=depth, color=colour, object=number)
    )
fragments = Fragments.from_rows(rows)

# %%
# Insert them in drawing order and pack the pixel, recording the packer's steps.
packed = resolve(fragments, 1, 1, layout=layout, background=background, trace=True)
steps = sorted(packed.trace.of_kind("pixel_packed")[0].steps, key=lambda step: step.level)

fig, axes = plt.subplots(2, 4, figsize=(13, 6.4), layout="constrained")
for ax, (name, (outline, depth, colour)), row in zip(
    axes[0, :3], polygons.items(), rows, strict=True
):
    ax.imshow(
        mask_to_grid(row["mask"], layout),
        origin="lower",
        extent=(0, 1, 0, 1),
        cmap=ListedColormap(["white", colour]),
        vmin=0,
        vmax=1,
    )
    ax.add_patch(plt.Polygon(outline, fill=False, color="black", lw=1.5))
    ax.set_title(
        f"{name}, z = {depth}: {popcount(row['mask'])}/32 bits, area {row['area']:.3f}", fontsize=10
    )

axes[0, 3].imshow(packed.image, origin="lower", extent=(0, 1, 0, 1))
axes[0, 3].set_title(f"packed pixel, coverage {packed.alpha[0, 0]:.3f}", fontsize=10)

# %%
# Each level of the packer: still visible (grey) and taken by this fragment (colour).
for ax, step in zip(axes[1, :3], steps, strict=True):
    levels = mask_to_grid(step.region, layout).astype(int) + mask_to_grid(step.mask_a, layout)
    colour = step.fragment.color
    ax.imshow(
        levels,
        origin="lower",
        extent=(0, 1, 0, 1),
        cmap=ListedColormap(["white", "lightgrey", colour]),
        vmin=0,
        vmax=2,
    )
    ax.set_title(f"level {step.level}: A = {step.a:.3f}, Q = {step.q:.3f}", fontsize=10)

shares = [step.a for step in steps] + [steps[-1].q]
bar_colours = [step.fragment.color for step in steps] + [background]
axes[1, 3].bar(range(len(shares)), shares, color=bar_colours, edgecolor="black")
axes[1, 3].set_xticks(range(len(shares)), [*polygons, "background"])
axes[1, 3].set_ylabel("share of the pixel")
axes[1, 3].set_title(f"shares (sum {sum(shares):.3f})", fontsize=10)

for ax in [*axes[0], *axes[1, :3]]:
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    ax.set_xticks([0, 1])
    ax.set_yticks([0, 1])
    # the sub-sample cells: 8 columns, 4 rows
    ax.set_xticks(np.linspace(0, 1, 9), minor=True)
    ax.set_yticks(np.linspace(0, 1, 5), minor=True)
    ax.grid(which="minor", color="0.6", lw=0.5)
fig.suptitle("One pixel (0, 0): masks of three fragments, then the packer front to back")
plt.show()

"""
A watertight triangle fan
=========================

A mesh is watertight when every sample inside it is drawn exactly once,
however many triangles meet there. Here twelve triangles share the vertex at
the sample (12, 12) and each spoke with its two neighbours; the ownership rule
of scanviz (exact arithmetic on snapped vertices, edges half-open; Foley et
al. 1990, §3.6) gives every sample to one triangle. `rasterize_triangles`
counts how many triangles cover each sample: 1 inside the fan, 0 outside, and
the count equals the mask of the fan's outline drawn as a single polygon.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import rasterize_triangles, scan_convert

width, height = 25, 25
centre = np.array([12.0, 12.0])
angles = np.linspace(0, 2 * np.pi, 12, endpoint=False) + 0.2
ring = centre + 11 * np.column_stack([np.cos(angles), np.sin(angles)])
fan = np.array([[centre, ring[i], ring[(i + 1) % 12]] for i in range(12)])

counts = rasterize_triangles(fan, width, height)
outline_mask = scan_convert(ring, width, height).mask

# %%
# Which triangle took each sample: scan-convert the triangles one at a time.
owner = np.full((height, width), np.nan)
for index, triangle in enumerate(fan):
    owner[scan_convert(triangle, width, height).mask] = index
centre_owner = int(owner[12, 12])

# %%
# Cells are centred on their samples (sample (x, y) at the integer point).
extent = (-0.5, width - 0.5, -0.5, height - 0.5)
fig, (owner_ax, count_ax) = plt.subplots(1, 2, figsize=(10, 4.8), layout="constrained")
owner_ax.imshow(owner, origin="lower", cmap="tab20", vmin=0, vmax=19, extent=extent)
owner_ax.set_title(f"owner of each sample (the centre goes to triangle {centre_owner})")
shown = count_ax.imshow(counts, origin="lower", cmap="Greys", vmin=0, vmax=2, extent=extent)
values = ", ".join(str(value) for value in np.unique(counts))
count_ax.set_title(
    f"triangles covering each sample: {values}\n(equals the outline's mask: {np.array_equal(counts, outline_mask)})"
)
fig.colorbar(shown, ax=count_ax, ticks=[0, 1, 2], shrink=0.8, label="coverage count")
for ax in (owner_ax, count_ax):
    for triangle in fan:
        ax.add_patch(plt.Polygon(triangle, fill=False, color="crimson", lw=0.8))
    ax.plot(*centre, "+", color="black", ms=8)
    ax.set_xlabel("x (pixels)")
    ax.set_ylabel("y (pixels)")
plt.show()

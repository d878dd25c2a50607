"""
Affine against perspective-correct interpolation
================================================

Texture coordinates (u, v) are linear on the surface in eye space, but not on
the screen: after the perspective divide, u/w and 1/w are the quantities
that vary linearly across the screen (Heckbert & Moreton 1991; Blinn 1992).
A floor made of two triangles, receding from the viewer, carries (u, v) at
its corners and is drawn through the z-buffer; each sample's checker square
is (floor(u) + floor(v)) mod 2. Interpolated affinely in screen space the
squares do not shrink with distance and the rows bend where the two
triangles meet; with ``perspective=True`` the rows stay straight.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.scene import Camera
from scanviz.transform import vertex_tables
from scanviz.visibility import ScreenPolygons, zbuffer

size = 160
camera = Camera(eye=(0, 1, 2.5), look_at=(0, 0, -1), window=(-0.5, 0.5, -0.5, 0.5), near=1, far=20)
floor = np.array([(-0.8, 0, 1), (0.8, 0, 1), (0.8, 0, -7), (-0.8, 0, -7)])
texture_uv = np.array([(0, 0), (4, 0), (4, 20), (0, 20)], dtype=float)
triangles = [[0, 1, 2], [0, 2, 3]]

# %%
# Project the corners: display x, y, depth z and 1/w for each vertex.
tables = vertex_tables(camera, floor, size, size)
display = tables["display"]
inv_w = 1 / tables["clip"][:, 3]
polygons = ScreenPolygons.from_polygons(
    [display[t] for t in triangles],
    [texture_uv[t] for t in triangles],
    [inv_w[t] for t in triangles],
)

# %%
# The same triangles, their (u, v) interpolated both ways.
results = {
    perspective: zbuffer(polygons, size, size, perspective=perspective)
    for perspective in (False, True)
}
drawn = results[True].polygon >= 0


def checker(uv):
    squares = (np.floor(uv[..., 0]) + np.floor(uv[..., 1])) % 2
    return np.where(drawn, 0.25 + 0.5 * squares, np.nan)


v_error = np.where(
    drawn, np.abs(results[False].values[..., 1] - results[True].values[..., 1]), np.nan
)

fig, axes = plt.subplots(1, 3, figsize=(12, 4.2), layout="constrained")
panels = [
    ("affine in screen space", results[False]),
    ("perspective-correct (u/w, 1/w)", results[True]),
]
for ax, (title, result) in zip(axes[:2], panels, strict=True):
    ax.imshow(checker(result.values), origin="lower", cmap="Greys", vmin=0, vmax=1)
    ax.plot(*display[[0, 2], :2].T, "--", color="crimson", lw=1, label="shared diagonal")
    ax.set_title(title)
axes[0].legend(loc="upper right")
shown = axes[2].imshow(v_error, origin="lower", cmap="magma")
axes[2].set_title(f"|v affine - v correct| (max {np.nanmax(v_error):.1f} squares)")
fig.colorbar(shown, ax=axes[2], shrink=0.8)
for ax in axes:
    ax.set_xlim(0, size)
    ax.set_ylim(0, size)
    ax.set_xlabel("x (pixels)")
axes[0].set_ylabel("y (pixels)")
plt.show()

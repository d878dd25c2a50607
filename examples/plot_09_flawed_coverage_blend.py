"""
The seam of the coverage blend, and the a-buffer without it
===========================================================

The obvious way to anti-alias with a z-buffer is to give each fragment its
covered area a and blend ``colour = new * a + old * (1 - a)`` (Rendermatic
thesis §6.3; Carpenter 1984). It fails where two polygons of one surface
share an edge: the first blend already mixes in the background the second
polygon should hide, and the second, at the same depth, fails the depth test
(ties keep the earlier polygon). So a white quad made of two triangles on
black shows a dark seam along its diagonal, black where the first triangle
covers only a sliver of the pixel. The a-buffer keeps each pixel's fragments
until every polygon is in and packs them with their masks and areas: no
seam. ``render(..., visibility="flawed")`` runs the flawed
blend so the two can be compared.
"""

import matplotlib.pyplot as plt

from scanviz import render
from scanviz.scene import Camera, Material, Mesh, Scene, SceneObject

size = 16
white = Material(color=(1, 1, 1), ambient=1.0, diffuse=0.0, specular=0.0)
corners = [(1.3, 1.2, 0), (14.6, 2.1, 0), (14.2, 14.5, 0), (1.6, 13.8, 0)]
quad = Mesh(corners, [[0, 1, 2], [0, 2, 3]], closed=False, smooth=False)
camera = Camera(
    eye=(0, 0, 1),
    look_at=(0, 0, 0),
    window=(0, size, 0, size),
    near=0.5,
    far=2,
    projection="orthographic",
)
scene = Scene([SceneObject(quad, white)], camera=camera, lights=(), background=(0, 0, 0))

# %%
# The same two triangles through the plain z-buffer, the coverage blend and the a-buffer.
titles = {
    "zbuffer": "z-buffer (aliased)",
    "flawed": "z-buffer + coverage blend",
    "abuffer": "a-buffer",
}
images = {
    visibility: render(scene, size, size, shading="flat", visibility=visibility).image[..., 0]
    for visibility in titles
}

# %%
# Inside the quad every pixel should be white; the seam is how far each falls short.
seam = images["abuffer"] - images["flawed"]

fig, axes = plt.subplots(1, 4, figsize=(14, 3.8), layout="constrained")
for ax, (visibility, title) in zip(axes[:3], titles.items(), strict=True):
    ax.imshow(
        images[visibility], origin="lower", cmap="gray", vmin=0, vmax=1, extent=(0, size, 0, size)
    )
    ax.plot(
        [corners[0][0], corners[2][0]],
        [corners[0][1], corners[2][1]],
        ":",
        color="tab:orange",
        lw=1,
    )
    ax.set_title(title)
shown = axes[3].imshow(seam, origin="lower", cmap="magma", extent=(0, size, 0, size))
axes[3].set_title(f"a-buffer - blend (max {seam.max():.2f})")
fig.colorbar(shown, ax=axes[3], shrink=0.8)
for ax in axes:
    ax.set_xlabel("x (pixels)")
axes[0].set_ylabel("y (pixels)")
plt.show()

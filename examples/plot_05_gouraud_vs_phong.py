"""
Flat, Gouraud and Phong shading of a coarse sphere
==================================================

Flat shading lights each triangle once; Gouraud (1971) lights the vertices
and interpolates the colours; Phong (1975) interpolates the normals and
lights every pixel. A specular highlight is narrower than a triangle of this
320-triangle sphere, so Gouraud shading samples it too coarsely: a highlight
between the vertices is lost, one near a vertex is smeared over its triangles
(Rendermatic thesis, ch. 4; Foley et al. 1990, §16.2). The profile on the
right runs along the row through Phong's brightest pixel.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import render
from scanviz.scene.builtin import builtin_scene

size = 200
sphere = builtin_scene("sphere", level=2)
images = {
    shading: render(sphere, size, size, shading=shading).image
    for shading in ("flat", "gouraud", "phong")
}

# %%
# The highlight: Phong's brightest pixel.
brightness = {shading: image.mean(axis=2) for shading, image in images.items()}
peak_y, peak_x = np.unravel_index(brightness["phong"].argmax(), (size, size))

fig, axes = plt.subplots(1, 4, figsize=(13, 3.6), layout="constrained")
for ax, (shading, image) in zip(axes[:3], images.items(), strict=True):
    ax.imshow(image, origin="lower")
    ax.plot(peak_x, peak_y, "o", ms=14, mfc="none", mec="cyan")
    ax.set_title(f"{shading}: {brightness[shading][peak_y, peak_x]:.2f} at the circle")
    ax.set_axis_off()

profile_ax = axes[3]
columns = np.arange(size)
for shading, colour in zip(images, ["tab:grey", "tab:blue", "tab:red"], strict=True):
    profile_ax.plot(columns, brightness[shading][peak_y], color=colour, label=shading)
profile_ax.axvline(peak_x, color="cyan", lw=0.8)
profile_ax.set_xlim(peak_x - 60, peak_x + 60)
profile_ax.set_xlabel(f"x (pixels) along row y = {peak_y}")
profile_ax.set_ylabel("brightness (mean of r, g, b)")
profile_ax.set_title("the highlight Gouraud misses")
profile_ax.legend()
plt.show()

"""
Fast Phong shading: its error against exact Phong
=================================================

Over a screen triangle, Phong shading's cos θ and cos φ are rational
functions of the pixel; fast Phong shading (Bishop and Weimer 1986; Wang 1989,
ch. 3) replaces each by a second-order Taylor polynomial, stepped with two
additions per pixel, and looks the specular power up in a table. The
polynomial is exact at the point it is expanded about and drifts away from
it: here a triangle with a sphere's normals, shaded both ways, and the
largest channel error per pixel for an expansion about a vertex and about the
centroid.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.shading import ReflectionModel, exact_phong_triangle, fast_phong_triangle

size, radius, centre = 170, 150.0, np.array([100.0, 100.0])
vertices = 20 + np.array([(0.08, 0.08), (0.92, 0.2), (0.35, 0.9)]) * 140
offsets = (vertices - centre) / radius
normals = np.column_stack([offsets, np.sqrt(1 - (offsets**2).sum(axis=1))])  # a sphere's
model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.75, 0.55, 0.3), ks=0.7, n=8, r_plus_r0=1.5)
to_light = np.array([-0.3, 0.4, 1.0]) / np.linalg.norm([-0.3, 0.4, 1.0])
to_viewer = (0.0, 0.0, 1.0)
shade = {"width": size, "height": size}

exact = exact_phong_triangle(vertices, normals, to_light, to_viewer, model, **shade)
fast = {
    expansion: fast_phong_triangle(
        vertices, normals, to_light, to_viewer, model, expansion=expansion, **shade
    )
    for expansion in ("vertex", "centroid")
}


def picture(shaded):
    image = np.ones((size, size, 3))
    image[shaded.ys, shaded.xs] = shaded.colors / 255
    return image


# %%
# The error map: the largest difference over the three channels, in levels
# of 0..255, at each pixel of the triangle.

fig, axes = plt.subplots(1, 4, figsize=(13, 4), layout="constrained")
axes[0].imshow(picture(exact), origin="lower")
axes[0].set_title("exact Phong", fontsize=10)
axes[1].imshow(picture(fast["vertex"]), origin="lower")
axes[1].set_title("fast Phong, about a vertex", fontsize=10)
for ax, (expansion, run) in zip(axes[2:], fast.items(), strict=True):
    error = np.abs(run.colors - exact.colors).max(axis=1)
    error_map = np.full((size, size), np.nan)
    error_map[run.ys, run.xs] = error
    shown = ax.imshow(error_map, origin="lower", cmap="magma", vmin=0, vmax=40)
    ax.set_title(f"error about the {expansion}\n(largest {error.max():.0f} levels)", fontsize=10)
fig.colorbar(
    shown, ax=axes[2:], label="largest channel error (levels; scale stops at 40)", shrink=0.8
)
for ax in axes:
    ax.set_xlim(25, 155)
    ax.set_ylim(25, 155)
    ax.set_xlabel("x (pixels)")
axes[0].set_ylabel("y (pixels)")
plt.show()

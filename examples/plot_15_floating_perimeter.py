"""
The Floating Perimeter Algorithm against the z-buffer
=====================================================

The Floating Perimeter Algorithm (Wang 1989, ch. 2) takes the facets of a grid
surface nearest first and keeps four 1-D arrays, the top and bottom of each
column and the left and right of each row of what is drawn so far: a point of
a later edge is hidden when it lies strictly inside that perimeter. Each
point it tests is decided again here by the z-buffer on the same surface and
view: the lines agree except within about a pixel of silhouettes, and the
hidden-surface mode picks the z-buffer's facet at every pixel.
"""

import matplotlib.pyplot as plt

from scanviz.surfaces import View, compare_with_zbuffer, floating_perimeter, polynomial

surface = polynomial(20)
view = View((0.24, -3.43, 3.02), (-0.24, 3.43, -3.58))  # from in front, above
found = compare_with_zbuffer(surface, view, 160, 160)
surface_mode = floating_perimeter(surface, view, 160, 160, mode="surface")

# %%
# Left: the hidden-line drawing, with the tested points where the two
# disagree. Right: the hidden-surface picture, facet by facet.

points = found.fpa.points
false_hidden = ~found.fpa.visible & found.zbuffer_visible
false_visible = found.fpa.visible & ~found.zbuffer_visible

fig, (lines_ax, surface_ax) = plt.subplots(1, 2, figsize=(10, 5))
lines_ax.imshow(found.fpa.image, origin="lower")
lines_ax.scatter(*points[false_visible].T, s=6, color="tab:blue", label="FPA shows, z-buffer hides")
lines_ax.scatter(*points[false_hidden].T, s=6, color="tab:red", label="FPA hides, z-buffer shows")
lines_ax.set_title(
    f"hidden lines: {found.points:,} points tested\n"
    f"{found.false_visible:,} falsely visible "
    f"({found.on_perimeter:,} on the perimeter), {found.false_hidden:,} falsely hidden",
    fontsize=10,
)
lines_ax.legend(loc="upper right", fontsize=8)

surface_ax.imshow(surface_mode.image, origin="lower")
surface_ax.set_title(
    f"hidden surfaces: {found.facet_mismatch} of {found.pixels:,} pixels\n"
    "show another facet than the z-buffer",
    fontsize=10,
)
for ax in (lines_ax, surface_ax):
    ax.set_xlabel("screen x (pixels)")
    ax.set_ylabel("screen y (pixels)")
fig.tight_layout()
plt.show()

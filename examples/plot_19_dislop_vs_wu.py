"""
DISLOP lines against Wu's lines and supersampling
=================================================

DISLOP_L (Wang 1989, ch. 4, "Algorithm DISLOP_L for Line Rendering") gives
each pixel the area it shares with the line drawn as a rectangle one pixel
wide, computed column by column from the slope and one distance. Wu's line
(Wu 1991) splits a unit of intensity between the two pixels nearest the line
in each column, and 4 × 4 supersampling counts sub-pixel samples inside the
rectangle. Each is compared here with the exact area of the rectangle in
every pixel, on one line and then on lines at every angle.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.antialias.compare import coverage_methods

methods = ["DISLOP_L", "Wu", "supersample 4×4"]
p0, p1 = (1.4, 2.2), (22.6, 13.9)
coverage = coverage_methods(p0, p1, 24, 16)
exact = coverage["exact band"]

# %%
# The largest error of each method on lines of length 20 from the centre of
# a 32 × 32 raster, at angles from 0° to 90°.

angles = np.linspace(0, 90, 31)
worst = {name: [] for name in methods}
for angle in angles:
    direction = 10 * np.array([np.cos(np.radians(angle)), np.sin(np.radians(angle))])
    start, end = (16.3, 16.2) - direction, (16.3, 16.2) + direction
    line = coverage_methods(tuple(start), tuple(end), 32, 32)
    for name in methods:
        worst[name].append(np.abs(line[name] - line["exact band"]).max())

fig, axes = plt.subplots(2, 4, figsize=(13, 5.6), layout="constrained")
axes[0, 0].imshow(exact, origin="lower", cmap="gray_r", vmin=0, vmax=1)
axes[0, 0].set_title("exact area of the 1-pixel band", fontsize=10)
for column, name in enumerate(methods, start=1):
    error = coverage[name] - exact
    axes[0, column].imshow(coverage[name], origin="lower", cmap="gray_r", vmin=0, vmax=1)
    axes[0, column].set_title(name, fontsize=10)
    shown = axes[1, column].imshow(error, origin="lower", cmap="RdBu_r", vmin=-0.25, vmax=0.25)
    axes[1, column].set_title(
        f"{name} − exact\nlargest |error| {np.abs(error).max():.2g}", fontsize=10
    )
for ax in axes[:, 1:].flat:
    ax.set_xticks([])
    ax.set_yticks([])
axes[0, 0].set_xticks([])
axes[0, 0].set_yticks([])
fig.colorbar(shown, ax=axes[1, 1:], label="coverage error", shrink=0.8)

for name in methods:
    axes[1, 0].plot(angles, worst[name], marker=".", label=name)
axes[1, 0].set_xlabel("line angle (degrees)")
axes[1, 0].set_ylabel("largest |error| in a pixel")
axes[1, 0].set_title("every angle", fontsize=10)
axes[1, 0].legend(fontsize=8)
plt.show()

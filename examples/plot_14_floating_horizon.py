"""
The floating horizon on a grid surface
======================================

The Floating Horizon Algorithm (Rogers 1985, §4-2, after Williamson 1972 and
Wright 1973) draws one family of grid curves of a surface z = f(x, y),
nearest curve first. It keeps, for every screen column, the highest and lowest
height drawn so far (the upper and lower horizons): a later curve is visible
only where it rises above the upper one or falls below the lower one. It
cannot draw both families of curves at once (Wang 1989, ch. 2), so each
family is drawn here in its own panel, with the final horizons.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.surfaces import View, rogers
from scanviz.surfaces.horizon import floating_horizon

surface = rogers(41)
view = View((6.0, 8.0, 3.0), (-6.0, -8.0, -3.0))  # from a corner: both families work
families = {
    "x": "curves y = constant (family x)",
    "y": "curves x = constant (family y)",
}

fig, axes = plt.subplots(1, 2, figsize=(10, 5))
for ax, (family, title) in zip(axes, families.items(), strict=True):
    result = floating_horizon(surface, view, 256, 256, family=family)
    columns = np.arange(len(result.up))
    ax.imshow(result.image, origin="lower")
    ax.plot(columns, result.up, color="tab:red", lw=1, alpha=0.7, label="final upper horizon")
    ax.plot(columns, result.low, color="tab:blue", lw=1, alpha=0.7, label="final lower horizon")
    ax.set_title(
        f"{title}\n{result.stats.curves} curves, {len(result.segments):,} visible pieces",
        fontsize=10,
    )
    ax.set_xlabel("screen x (pixels)")
    ax.set_ylabel("screen y (pixels)")
    ax.legend(loc="lower right", fontsize=8)
fig.tight_layout()
plt.show()

"""
Drift of the textbook x += dx/dy
================================

The textbook scan converter steps each edge's crossing by adding dx/dy once
per row (Foley et al. 1990, §3.6). In floating point every addition rounds,
and along a long edge the errors add up until a crossing lands on the wrong
side of a sample and a span gains or loses a pixel. scanviz's default exact
DDA never rounds; ``arithmetic="float32"`` and ``"float64"`` run the textbook
update so its drift can be measured. Here a thin triangle 4,096 rows tall:
float32 drifts by hundredths of a pixel and lengthens a few dozen spans,
float64 drifts a hundred million times less and no span changes.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap

from scanviz import Recorder, scan_convert

height = 4096
width = height // 3 + 2
triangle = [(0.1, 0.1), (height / 3 + 0.37, height - 0.3), (0.2, height - 0.3)]


def right_crossings(arithmetic):
    """The right edge's crossing x on each row, and the covered samples."""
    result = scan_convert(
        triangle, width, height, arithmetic=arithmetic, trace=Recorder(kinds=["aet_sorted"])
    )
    rows = result.trace.of_kind("aet_sorted")
    right_x = [
        max(entry.x_exact if arithmetic == "exact" else entry.x for entry in row.entries)
        for row in rows
    ]
    return np.array([row.y for row in rows]), np.array(right_x, dtype=float), result.mask


rows, exact_x, exact_mask = right_crossings("exact")
runs = {arithmetic: right_crossings(arithmetic) for arithmetic in ("float64", "float32")}

# %%
# The error of the crossing, row by row, and the samples the float modes get wrong.
fig, (error_ax, zoom_ax) = plt.subplots(
    1, 2, figsize=(10, 4.5), layout="constrained", width_ratios=(1.7, 1)
)
for (arithmetic, (_, drifted_x, mask)), colour in zip(
    runs.items(), ["tab:blue", "tab:red"], strict=True
):
    wrong = int((mask != exact_mask).sum())
    error = np.abs(drifted_x - exact_x)
    # log axis: rows with no error at all are left out
    error_ax.semilogy(
        rows,
        np.where(error > 0, error, np.nan),
        color=colour,
        label=f"{arithmetic}: {wrong} samples wrong",
    )
error_ax.set_xlabel("row y")
error_ax.set_ylabel("|x - exact x| of the right edge (pixels)")
error_ax.set_ylim(1e-14, 1)
error_ax.set_title("the rounding error adds up along the edge")
error_ax.legend(loc="lower right")

# %%
# Zoom on the first rows where float32 pushes the crossing across a sample.
float32_mask = runs["float32"][2]
wrong_y, wrong_x = np.nonzero(float32_mask != exact_mask)
y0, y1 = wrong_y.min() - 4, wrong_y.min() + 20
x0, x1 = wrong_x.min() - 6, wrong_x.min() + 8
zoom = exact_mask[y0:y1, x0:x1].astype(int)
zoom[(float32_mask != exact_mask)[y0:y1, x0:x1]] = 2
colours = ListedColormap(["white", "lightgrey", "crimson"])
# cells centred on their samples (sample (x, y) at the integer point)
extent = (x0 - 0.5, x1 - 0.5, y0 - 0.5, y1 - 0.5)
zoom_ax.imshow(zoom, origin="lower", cmap=colours, vmin=0, vmax=2, extent=extent)
in_view = (rows >= y0) & (rows < y1)
zoom_ax.plot(exact_x[in_view], rows[in_view], "k.-", lw=1, label="exact crossing")
zoom_ax.plot(
    runs["float32"][1][in_view], rows[in_view], "x", color="tab:red", label="float32 crossing"
)
zoom_ax.set_title(
    f"float32 adds {len(wrong_x)} samples (red), rows {wrong_y.min()}-{wrong_y.max()}"
)
zoom_ax.set_xlabel("x (pixels)")
zoom_ax.set_ylabel("row y")
zoom_ax.legend(loc="upper left")
plt.show()

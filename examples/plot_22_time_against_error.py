"""
Coverage: run time against error
================================

Anti-aliasing a polygon means giving each pixel the fraction of it the
polygon covers. Point sampling is cheap and wrong by up to a whole pixel at
edges; k × k supersampling and the a-buffer's sub-pixel masks (Carpenter 1984)
shrink the error as they spend more samples; the exact area (`area_coverage`)
has none. With the pieces of the package's coverage benchmark
(`docs/benchmarks.md`) at its quick size, each method is timed on five seeded
polygons on a 64 × 64 raster and its error measured against the exact areas
at the edge pixels.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz.bench import best_time
from scanviz.bench.coverage import coverage_errors, coverage_scene, methods

size = 64
scene = coverage_scene(5, size)  # stars, triangles and a catalog shape, seeded
coverage = {name: method for name, method in methods() if method is not None}
exact = [coverage["exact area"](contours, size) for contours in scene]

rows = []
for name, method in coverage.items():
    seconds = best_time(lambda m=method: [m(c, size) for c in scene], budget=0.5)
    errors = np.concatenate(
        [coverage_errors(method(c, size), e) for c, e in zip(scene, exact, strict=True)]
    )
    rows.append((name, 1e3 * seconds, float(np.sqrt(np.mean(errors**2)))))

# %%
# The exact area has error 0, which a log scale cannot show: it is drawn on
# the bottom of the plot. The 4 × 4 mask and 4 × 4 supersampling take the same
# samples, so they have the same error.

floor = min(rms for _, _, rms in rows if rms > 0) / 10
fig, ax = plt.subplots(figsize=(8, 5.2))
for name, ms, rms in rows:
    error = rms if rms > 0 else floor
    label = name if rms > 0 else f"{name} (error 0)"
    below = name.startswith("a-buffer")  # keep its label off the supersampling one
    ax.loglog(ms, error, "o", color="tab:orange" if below else "tab:blue")
    ax.annotate(
        label,
        (ms, error),
        textcoords="offset points",
        xytext=(5, -11 if below else 4),
        fontsize=8,
    )
ax.set_xlabel("time to cover the 5 polygons (ms, median of runs)")
ax.set_ylabel("RMS coverage error at edge pixels")
ax.set_title("Anti-aliasing by coverage: error against time")
ax.grid(True, which="both", alpha=0.3)
ax.margins(x=0.35, y=0.15)
fig.tight_layout()
plt.show()

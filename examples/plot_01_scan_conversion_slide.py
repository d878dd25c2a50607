"""
The edge table and active edge table of a slide polygon
========================================================

Scan conversion in the textbook order (Foley et al. 1990, §3.6): the edge
table buckets each edge by the row where it starts, the active edge table
holds the edges crossing the current row, sorted by x, and the spans between
pairs of crossings are filled. Here the trace of a small concave polygon is
drawn row by row: each row's spans, coloured by the row they were filled in.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import scan_convert

polygon = [(2, 1), (10, 3), (13, 11), (7, 7), (2, 9)]
result = scan_convert(polygon, 16, 13, trace=True)
spans = result.trace.of_kind("span")

fig, ax = plt.subplots(figsize=(6, 5))
rows = np.full((13, 16), np.nan)
for span in spans:
    rows[span.y, span.x_start : span.x_end] = span.y
ax.imshow(rows, origin="lower", cmap="viridis", extent=(0, 16, 0, 13))
ax.add_patch(plt.Polygon(polygon, fill=False, color="black", lw=1.5))
ax.set_title(f"{len(spans)} spans on {len({s.y for s in spans})} rows")
ax.set_xlabel("x (pixels)")
ax.set_ylabel("y (pixels, row 0 at the bottom)")
plt.show()

"""
The midpoint line and its decision variable
===========================================

The midpoint algorithm (Bresenham 1965; Rheingans, UMBC CMSC 435 slides,
"Line Drawing") draws one pixel per column of a shallow line. Between the
two candidates east (E) and north-east (NE) it looks at the sign of the
line's implicit function f at their midpoint: d = 2 f(x + 1, y + 1/2) < 0
means the line passes above the midpoint, so NE is nearer. d is then updated
by one of two integer constants, so no multiplication or division is done
inside the loop. The trace records d at every pixel.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import Recorder, midpoint_line

x0, y0, x1, y1 = 1, 1, 14, 6
recorder = Recorder()
xs, ys = midpoint_line(x0, y0, x1, y1, trace=recorder)
setup, *steps = recorder.trace()
decided = [step for step in steps if step.choice != "last"]

# %%
# Left: the pixels drawn (cells centred on their integer points), the ideal
# line and each midpoint tested, coloured by the step it chose.
colours = {"axial": "tab:blue", "diagonal": "tab:red"}
fig, (grid_ax, d_ax) = plt.subplots(
    1, 2, figsize=(13, 4.6), layout="constrained", width_ratios=(1.5, 1)
)
drawn = np.zeros((y1 + 2, x1 + 2))
drawn[ys, xs] = 1
grid_ax.imshow(
    drawn, origin="lower", cmap="Greys", vmin=0, vmax=2.5, extent=(-0.5, x1 + 1.5, -0.5, y1 + 1.5)
)
grid_ax.plot([x0, x1], [y0, y1], color="black", lw=1.5, label="ideal line")
for step in decided:
    grid_ax.plot(step.x + 1, step.y + 0.5, "o", color=colours[step.choice], ms=6)
    grid_ax.annotate(
        f"{step.d:+d}",
        (step.x + 1, step.y + 0.5),
        textcoords="offset points",
        xytext=(0, 7),
        ha="center",
        fontsize=8,
        color=colours[step.choice],
    )
grid_ax.plot(
    [], [], "o", color=colours["axial"], label="d >= 0: midpoint on or above the line, step E"
)
grid_ax.plot(
    [], [], "o", color=colours["diagonal"], label="d < 0: midpoint below the line, step NE"
)
grid_ax.set_xticks(range(x1 + 2))
grid_ax.set_yticks(range(y1 + 2))
grid_ax.set_xlabel("x (pixels)")
grid_ax.set_ylabel("y (pixels)")
grid_ax.set_title(f"midpoint_line({x0}, {y0}, {x1}, {y1}): {len(xs)} pixels")
grid_ax.legend(loc="upper left", fontsize=8)

# %%
# Right: d at each column; the bar's colour is the step taken from it.
d_ax.bar(
    [step.x for step in decided],
    [step.d for step in decided],
    color=[colours[step.choice] for step in decided],
)
d_ax.axhline(0, color="black", lw=0.8)
d_ax.set_xlabel("x (pixels)")
d_ax.set_ylabel("decision variable d")
d_ax.set_title(f"d starts at {setup.d_start}; E adds {setup.d_axial}, NE adds {setup.d_diagonal}")
plt.show()

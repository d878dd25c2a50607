"""
The colour ring: a complex function as a coloured surface
=========================================================

Wang (1989, ch. 3, "A Color-Ring Look-up Table") draws a complex function F as
a grid surface whose height is abs(F(x + iy)) and whose colour is the phase
arg F, looked up in a closed ring of colours that blends only two primaries
at a time: green to red to blue and back to green. Zeros become valleys and
poles peaks, and every colour of the ring appears once around each of them.
Here is the ring of 192 colours and the dissertation's function with three
poles and two zeros.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import render
from scanviz.shading import colour_ring
from scanviz.surfaces import View
from scanviz.surfaces.complex import phase_scene, three_poles_two_zeros

ring = colour_ring(64)
surface = three_poles_two_zeros(41)  # |F| on [-2, 2]^2, clipped at 4, and arg F
view = View((6, -8, 9), (-6, 8, -8))
image = render(phase_scene(surface, view, 300, 300), 300, 300, shading="flat").image

# %%
# Left: entry k of the ring stands for the phase 360° k / 192. Right: each
# triangle of the surface takes the ring colour of its mean phase.

fig = plt.figure(figsize=(10, 4.8))
ring_ax = fig.add_subplot(1, 2, 1, projection="polar")
phases = 2 * np.pi * np.arange(len(ring)) / len(ring)
ring_ax.bar(phases, 1, width=2 * np.pi / len(ring), bottom=1, color=ring, align="edge", linewidth=0)
ring_ax.grid(False)
ring_ax.set_yticks([])
ring_ax.set_title(f"the colour ring: {len(ring)} entries, phase arg F", fontsize=10)

surface_ax = fig.add_subplot(1, 2, 2)
surface_ax.imshow(image, origin="lower")
surface_ax.set_title(
    "|F| as height, arg F as colour:\nthree poles (peaks) and two zeros", fontsize=10
)
surface_ax.set_axis_off()
fig.tight_layout()
plt.show()

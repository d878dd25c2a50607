"""
The z-buffer, one depth test at a time
======================================

The z-buffer keeps, for every pixel, the depth of the nearest surface drawn
so far; a new fragment is written only if it is nearer (Catmull 1974). On the
UMBC slide scene a triangle pierces another, so which one wins changes along
a line across them. The stepper's frames show each depth test as it passes
or fails, and the buffers as they fill.
"""

from scanviz import load_scene
from scanviz.widgets import zbuffer_stepper

scene = load_scene("builtin:umbc_zbuffer")
stepper = zbuffer_stepper(scene, 12, 12)
print(f"{len(stepper.model)} steps:", stepper.label.value)

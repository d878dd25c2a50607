"""
Stepping through scan conversion without a kernel
=================================================

In a notebook a stepper is a widget: Play, a slider and the views of one
step. ``stepper.save("scan.gif")`` draws the same steps from the same trace
into an animated GIF (or ``stepper.save("frames/")`` into PNG files), for
slides, handouts and pages like this one. Here the edge table and active
edge table of Foley et al. (1990, §3.6) fill a concave polygon row by row:
each frame is one event of the trace, with the sentence that narrates it.
"""

from scanviz.widgets import scan_conversion_stepper

polygon = [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)]
stepper = scan_conversion_stepper(polygon, 14, 13)
print(f"{len(stepper.model)} steps:", stepper.label.value)

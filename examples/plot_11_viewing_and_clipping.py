"""
Viewing and clipping a small scene
==================================

The viewing pipeline takes every polygon from world to eye space, then to
homogeneous clip space, where it is clipped against the view volume before
the divide by w (Sutherland-Hodgman against six planes; Blinn & Newell 1978),
then to normalized device coordinates and to the screen (Rendermatic thesis,
App. D). The lesson's scene, a cube on a floor with a flag beside them, meets
every verdict: back faces of the cube are culled, its front faces accepted
whole, the floor clipped by the far and side planes, the flag rejected.
"""

import matplotlib.pyplot as plt
import numpy as np

from scanviz import render
from scanviz.pipeline.viewing import view_scene
from scanviz.transform import ndc_from_clip
from scanviz.transform.examples import viewing_scene

size = 64
scene = viewing_scene()
viewed = view_scene(scene, size, size)
colours = {"culled": "0.6", "accepted": "tab:green", "clipped": "tab:orange", "rejected": "tab:red"}
verdict_styles = {verdict: {"color": colour, "lw": 1.5} for verdict, colour in colours.items()}

fig, (eye_ax, ndc_ax, screen_ax) = plt.subplots(
    1, 3, figsize=(14, 4.8), layout="constrained", width_ratios=(1, 1.4, 1)
)

# %%
# Eye space seen from above: the eye at the origin looks down -z, the view
# volume is the frustum between the near and far planes.
volume = viewed.volume["eye"]
frustum = volume[[0, 1, 5, 4, 0]]
eye_ax.plot(frustum[:, 0], -frustum[:, 2], color="black", lw=1, label="view volume")
eye_ax.plot(0, 0, "k^", ms=8, label="eye")
for polygon, verdict in zip(viewed.polygons["eye"], viewed.verdicts, strict=True):
    closed = np.vstack([polygon, polygon[:1]])
    eye_ax.plot(closed[:, 0], -closed[:, 2], **verdict_styles[verdict])
eye_ax.set_xlabel("eye x")
eye_ax.set_ylabel("distance in front of the eye (-z)")
eye_ax.set_aspect("equal")
eye_ax.set_title("eye space, from above")
eye_ax.legend(loc="lower right", fontsize=8)

# %%
# NDC: each polygon divided by w before clipping (dashed) and after (filled);
# the view volume is the square [-1, 1] x [-1, 1].
ndc_ax.add_patch(plt.Rectangle((-1, -1), 2, 2, fill=False, color="black", lw=1))
for polygon, clipped, verdict in zip(
    viewed.polygons["clip"], viewed.polygons["ndc"], viewed.verdicts, strict=True
):
    if verdict == "culled":
        continue
    unclipped = ndc_from_clip(polygon)
    ndc_ax.add_patch(
        plt.Polygon(unclipped[:, :2], fill=False, ls="--", color=colours[verdict], lw=1)
    )
    if len(clipped):
        ndc_ax.add_patch(plt.Polygon(clipped[:, :2], alpha=0.5, color=colours[verdict]))
    new = [vertex for vertex in clipped if not np.isclose(unclipped, vertex).all(axis=1).any()]
    if new:
        ndc_ax.plot(*np.array(new)[:, :2].T, "o", color="crimson", ms=4)
ndc_ax.plot([], [], "o", color="crimson", ms=4, label="vertex made by the clipper")
ndc_ax.set_xlim(-2.5, 2.5)
ndc_ax.set_ylim(-2.1, 1.3)
ndc_ax.set_aspect("equal")
ndc_ax.set_xlabel("NDC x")
ndc_ax.set_ylabel("NDC y")
ndc_ax.set_title("NDC: before (dashed) and after clipping")
ndc_ax.legend(loc="lower right", fontsize=8)

# %%
# The screen: what the rasterizer receives, drawn over the rendered image.
screen_ax.imshow(render(scene, size, size).image, origin="lower", extent=(0, size, 0, size))
for polygon, verdict in zip(viewed.polygons["display"], viewed.verdicts, strict=True):
    if len(polygon):
        screen_ax.add_patch(plt.Polygon(polygon[:, :2], fill=False, **verdict_styles[verdict]))
screen_ax.set_xlabel("x (pixels)")
screen_ax.set_ylabel("y (pixels)")
screen_ax.set_title(f"display, {size} x {size}")

counts = {verdict: viewed.verdicts.count(verdict) for verdict in colours}
for verdict, colour in colours.items():
    screen_ax.plot([], [], color=colour, label=f"{verdict}: {counts[verdict]}")
fig.legend(*screen_ax.get_legend_handles_labels(), loc="outside right center", title="polygons")
plt.show()

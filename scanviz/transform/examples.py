"""The scene the viewing lesson steps through: every verdict of culling and clipping in 11 polygons.

`viewing_scene` is small enough to follow polygon by polygon:

- a cube (6 faces, a closed mesh) turned -30 degrees about y, wholly inside
  the view volume: culling marks the 3 faces that turn away from the eye and
  the clipper accepts the other 3 unchanged;
- a floor of 4 square tiles under it, wider and deeper than the view
  volume: the clipper cuts every tile (near the left, right, far and bottom planes);
- a small flag to the right, outside the view volume: the clipper rejects it.

The floor and the flag are open meshes, so they are never culled.
"""

from __future__ import annotations

import math

import numpy as np

from ..scene.builtin import box
from ..scene.model import Camera, Light, Material, Mesh, Scene, SceneObject


def viewing_scene() -> Scene:
    """A cube on a floor and a flag beside them, for a 64 x 64 raster.

    Returns
    -------
    Scene
        Objects "cube", "floor", "flag" (polygons 0-5, 6-9 and 10 when
        numbered through the scene); a perspective camera at (0.8, 1.3, 3.2)
        looking at the origin, window 0.9 x 0.9 on the near plane at 1.4,
        far plane at 5; a point key light and a dim directional fill light.

    Examples
    --------
    >>> scene = viewing_scene()
    >>> [(o.name, o.mesh.face_count, o.mesh.closed) for o in scene.objects]
    [('cube', 6, True), ('floor', 4, False), ('flag', 1, False)]
    """
    turn = math.radians(-30)  # its +x face turns toward the eye
    cube_from_model = np.eye(4)
    cube_from_model[[0, 0, 2, 2], [0, 2, 0, 2]] = (
        math.cos(turn),
        math.sin(turn),
        -math.sin(turn),
        math.cos(turn),
    )
    grid = (-1.6, 0.0, 1.6)
    floor_corners = np.array([(x, -0.5, z) for z in grid for x in grid])
    tiles = ((0, 3, 4, 1), (1, 4, 5, 2), (3, 6, 7, 4), (4, 7, 8, 5))  # counter-clockwise from +y
    flag = np.array([(2.2, -0.5, -1.0), (2.8, -0.5, -1.0), (2.5, 0.6, -1.0)])
    return Scene(
        (
            SceneObject(box(1.0), Material(color=(0.85, 0.35, 0.25)), cube_from_model, "cube"),
            SceneObject(
                Mesh(floor_corners, tiles, smooth=False, closed=False),
                Material(color=(0.35, 0.65, 0.35)),
                name="floor",
            ),
            SceneObject(
                Mesh(flag, ((0, 1, 2),), smooth=False, closed=False),
                Material(color=(0.3, 0.4, 0.85)),
                name="flag",
            ),
        ),
        Camera(
            eye=(0.8, 1.3, 3.2),
            look_at=(0.0, 0.0, 0.0),
            window=(-0.45, 0.45, -0.45, 0.45),
            near=1.4,
            far=5.0,
        ),
        lights=(
            Light("point", color=(0.85, 0.85, 0.8), position=(4.0, 5.0, 6.0)),
            Light("directional", color=(0.25, 0.27, 0.35), direction=(1.0, 0.2, -1.0)),
        ),
        background=(0.9, 0.9, 0.88),
        name="viewing",
    )

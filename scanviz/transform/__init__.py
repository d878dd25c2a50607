"""Viewing transforms, clipping and back-face culling: world -> eye -> clip -> NDC -> display.

Conventions (details in `scanviz.transform.viewing` and ``docs/viewing.md``):
column vectors, ``q = M @ p``, matrices named ``a_from_b`` and composed right to
left; eye space right-handed looking down -z, y up; visible clip space is
-w <= x, y <= w and 0 <= z <= w; NDC z is 0 at near and 1 at far; display is
in pixels, y up, row 0 at the bottom.
"""

from .clip import CLIP_PLANES, classify, clip_polygon, outcodes
from .cull import back_facing, cull_faces, face_normals
from .viewing import (
    STAGES,
    clip_from_eye,
    display_from_ndc,
    eye_from_world,
    image_from_display,
    ndc_from_clip,
    transform_points,
    transform_vertices,
    vertex_tables,
)

__all__ = [
    "CLIP_PLANES",
    "STAGES",
    "back_facing",
    "classify",
    "clip_from_eye",
    "clip_polygon",
    "cull_faces",
    "display_from_ndc",
    "eye_from_world",
    "face_normals",
    "image_from_display",
    "ndc_from_clip",
    "outcodes",
    "transform_points",
    "transform_vertices",
    "vertex_tables",
]

"""Shading: the Phong illumination model, vertex and face normals, Gooch tones, feature edges.

Flat, Gouraud and Phong shading differ only in where the pipeline evaluates
`illuminate`: once per polygon, once per vertex (then interpolating colors),
or once per pixel (interpolating normals). See docs/shading.md.
"""

from .edges import feature_edges
from .gooch import gooch
from .illumination import (
    MATERIAL_FIELDS,
    face_normals,
    illuminate,
    illuminate_traced,
    material_array,
    vertex_normals,
)

__all__ = [
    "MATERIAL_FIELDS",
    "face_normals",
    "feature_edges",
    "gooch",
    "illuminate",
    "illuminate_traced",
    "material_array",
    "vertex_normals",
]

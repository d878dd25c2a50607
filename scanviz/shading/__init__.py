"""Shading: the Phong illumination model, vertex and face normals, Gooch tones, feature edges,
fast Phong shading (Taylor quadratics stepped by forward differences), the specular look-up
table and the colour ring of Wang (1989, ch. 3).

Flat, Gouraud and Phong shading differ only in where the pipeline evaluates
`illuminate`: once per polygon, once per vertex (then interpolating colors),
or once per pixel (interpolating normals). See docs/shading.md.
"""

from . import fast_phong
from .colour_ring import (
    MAX_RING_STEPS,
    colour_ring,
    marked_triangles,
    replace_entry,
    ring_index,
    triangle_ring_index,
)
from .edges import feature_edges
from .fast_phong import *  # noqa: F403 -- fast Phong and its Taylor algebra, as `fast_phong.__all__` lists them
from .gooch import gooch
from .illumination import (
    MATERIAL_FIELDS,
    face_normals,
    illuminate,
    illuminate_traced,
    material_array,
    vertex_normals,
)
from .lut import (
    lut_level,
    lut_level_coherent,
    lut_level_compiled,
    lut_levels,
    specular_levels_exact,
    specular_lut,
    table_size,
)

__all__ = [
    "MATERIAL_FIELDS",
    "MAX_RING_STEPS",
    *fast_phong.__all__,
    "colour_ring",
    "lut_level",
    "lut_level_coherent",
    "lut_level_compiled",
    "lut_levels",
    "marked_triangles",
    "replace_entry",
    "ring_index",
    "specular_levels_exact",
    "specular_lut",
    "table_size",
    "triangle_ring_index",
    "face_normals",
    "feature_edges",
    "gooch",
    "illuminate",
    "illuminate_traced",
    "material_array",
    "vertex_normals",
]

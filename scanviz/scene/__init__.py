"""Scenes: meshes, materials, camera, lights (`model`), and the built-in scenes (`builtin`)."""

from .builtin import (
    BUILTIN_MESHES,
    BUILTIN_SCENES,
    BuiltinScene,
    box,
    builtin_scene,
    function_surface_mesh,
    icosphere,
    terrain,
    torus,
    uv_sphere,
)
from .model import Camera, Light, Material, Mesh, Scene, SceneObject

__all__ = [
    "BUILTIN_MESHES",
    "BUILTIN_SCENES",
    "BuiltinScene",
    "Camera",
    "Light",
    "Material",
    "Mesh",
    "Scene",
    "SceneObject",
    "box",
    "builtin_scene",
    "function_surface_mesh",
    "icosphere",
    "terrain",
    "torus",
    "uv_sphere",
]

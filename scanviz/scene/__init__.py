"""Scenes: meshes, materials, camera, lights (`model`), and the built-in scenes."""

from .model import Camera, Light, Material, Mesh, Scene, SceneObject

__all__ = ["Camera", "Light", "Material", "Mesh", "Scene", "SceneObject"]

"""Reading and writing scenes: the JSON scene format and Wavefront OBJ meshes.

See ``docs/scene-format.md`` for the JSON format.
"""

from .obj import load_obj
from .scene_json import load_scene, scene_from_dict, scene_to_dict

__all__ = ["load_obj", "load_scene", "scene_from_dict", "scene_to_dict"]

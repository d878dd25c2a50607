"""Reading and writing scenes: the JSON scene format and Wavefront OBJ meshes.

See ``docs/scene-format.md`` for the JSON format.
"""

from .obj import frame_model, load_obj
from .scene_json import is_obj_path, load_scene, read_json, scene_from_dict, scene_to_dict

__all__ = [
    "frame_model",
    "is_obj_path",
    "load_obj",
    "load_scene",
    "read_json",
    "scene_from_dict",
    "scene_to_dict",
]

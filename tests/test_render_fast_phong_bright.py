"""Issue 27: render(shading="fast_phong") under a bright light: tables of 255 levels, same image."""

import dataclasses

import numpy as np

from scanviz import render
from scanviz.limits import memory_limit
from scanviz.pipeline import fast_shade
from scanviz.scene import Camera, Light, Material, Scene, SceneObject
from scanviz.scene.builtin import icosphere


def spheres(colour: float, specular=(1.0, 0.9, 0.8)) -> Scene:
    objects = []
    for k, ks in enumerate(specular):
        placed = np.eye(4)
        placed[0, 3] = 2.5 * (k - 1)
        objects.append(SceneObject(icosphere(1), Material(specular=ks), world_from_model=placed))
    light = Light(direction=(0.3, -0.2, -1.0), color=(colour,) * 3)
    return Scene(objects, camera=Camera(eye=(0, 0, 5)), lights=(light,))


def test_a_bright_light_renders_within_a_small_memory_limit():
    # colour 10^6: N = 2.55 x 10^8 levels, a 2 GB table per material before; 255 entries now
    with memory_limit("64M"):
        result = render(spheres(1e6), 32, 32, shading="fast_phong")
    columns = "".join("#" if shown else "." for shown in (result.polygon >= 0).any(axis=0))
    assert columns.strip(".").split(".") == ["#######"] * 3  # three spheres, three materials
    assert result.image.max() == 1.0


def test_tables_cut_at_255_levels_change_no_pixel(monkeypatch):
    # colour 4: N = 1020 x ks levels; each light's colour clips at 255, so the cut is invisible
    scene = spheres(4.0)
    cut = render(scene, 40, 40, shading="fast_phong")
    whole_model = fast_shade._model

    def uncut(*arguments):
        return dataclasses.replace(whole_model(*arguments), top_level=None)

    monkeypatch.setattr(fast_shade, "_model", uncut)
    whole = render(scene, 40, 40, shading="fast_phong")
    assert (
        len(uncut(np.array([1, 1, 1, 0.1, 0.7, 1.0, 8, 0, 0]), scene.lights[0], np.zeros(3)).table)
        == 1020
    )
    assert np.array_equal(cut.image, whole.image)
    assert (cut.image[cut.polygon >= 0] == 1.0).any()  # some highlight saturates

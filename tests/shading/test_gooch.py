"""Gooch tone shading: the endpoints, the blend between them, and the shared conventions."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from scanviz.scene.model import Light, Material
from scanviz.shading import gooch, material_array

RED = material_array([Material(color=(1.0, 0.0, 0.0), diffuse=0.5)])
UP = [(0.0, 0.0, 1.0)]
SUN = Light()  # shining straight down


def tone(normals, *, light=SUN, material=RED, eye=None, view_dir=(1, 0, 0), **parameters):
    normals = np.asarray(normals, dtype=float)
    materials = np.repeat(material, len(normals), axis=0)
    return gooch(
        np.zeros_like(normals), normals, materials, eye, light, view_dir=view_dir, **parameters
    )


def test_facing_the_light_gives_k_warm_and_facing_away_gives_k_cool():
    b, y, alpha, beta = 0.3, 0.5, 0.25, 0.5
    kd = np.array([0.5, 0.0, 0.0])  # diffuse * color
    warm = np.array([y, y, 0]) + beta * kd
    cool = np.array([0, 0, b]) + alpha * kd
    shaded = tone([(0, 0, 1), (0, 0, -1)], b=b, y=y, alpha=alpha, beta=beta)
    np.testing.assert_array_equal(shaded, [warm, cool])


def test_defaults_are_the_papers():
    shaded = tone([(0, 0, 1), (0, 0, -1)], material=material_array([Material(color=(0, 0, 0))]))
    np.testing.assert_array_equal(shaded, [(0.4, 0.4, 0.0), (0.0, 0.0, 0.4)])


def test_the_tone_blends_linearly_in_the_cosine():
    angle = np.radians(np.linspace(0, 180, 37))
    normals = np.stack([np.sin(angle), np.zeros_like(angle), np.cos(angle)], axis=1)
    shaded = tone(normals)
    warm, cool = tone([(0, 0, 1), (0, 0, -1)])
    t = ((1 + np.cos(angle)) / 2)[:, None]
    np.testing.assert_allclose(shaded, t * warm + (1 - t) * cool, atol=1e-15)


def test_a_point_light_sets_only_the_direction():
    near = tone(UP, light=Light(kind="point", position=(0, 0, 0.5)))
    far = tone(UP, light=Light(kind="point", position=(0, 0, 500.0)))
    np.testing.assert_array_equal(near, far)
    np.testing.assert_array_equal(near, tone(UP))


def test_a_surface_seen_from_behind_is_toned_on_its_visible_side():
    front = tone(UP, view_dir=None, eye=(0, 0, 5))
    back = tone([(0, 0, -1)], view_dir=None, eye=(0, 0, 5))
    np.testing.assert_array_equal(front, back)


@given(st.lists(st.tuples(*[st.floats(-5, 5)] * 3), min_size=1, max_size=10))
def test_one_point_alone_gets_bit_for_bit_its_tone_among_many(normals):
    together = tone(normals, eye=(1, 2, 3), view_dir=None)
    assert ((0 <= together) & (together <= 1)).all()
    for i, normal in enumerate(normals):
        assert (
            tone([normal], eye=(1, 2, 3), view_dir=None).tobytes() == together[i : i + 1].tobytes()
        )


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"light": "sun"}, TypeError, "'light' must be a Light"),
        ({"alpha": -0.1}, ValueError, "'alpha' must be finite and >= 0"),
        ({"b": float("nan")}, ValueError, "'b' must be finite and >= 0"),
        ({"y": "0.4"}, TypeError, "'y' must be a number"),
        ({"eye": (0, 0, 5)}, ValueError, "exactly one of 'eye'"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    with pytest.raises(error, match=message):
        tone(UP, **arguments)

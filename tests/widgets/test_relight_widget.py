"""The relight widget: sliders for a light and the material, the image from RenderResult.relight."""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import ipywidgets as widgets  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from scanviz import load_scene, render  # noqa: E402
from scanviz.scene import Camera, Light  # noqa: E402
from scanviz.widgets._common import WIDEST  # noqa: E402
from scanviz.widgets.relight import RelightView, light_direction, relight_widget  # noqa: E402


@pytest.fixture(scope="module")
def result():
    return render(load_scene("builtin:sphere"), 32, 32)


def test_the_widget_builds_with_its_sliders_and_a_figure_that_fits(result):
    view = relight_widget(result)
    assert isinstance(view.widget, widgets.HBox)
    assert set(view.sliders) == {"azimuth", "elevation", "diffuse", "specular", "exponent"}
    assert view.figure.get_size_inches()[0] <= WIDEST
    assert "relit 32x32" in view.status.value


def test_a_slider_change_shows_what_relight_gives(result):
    view = relight_widget(result)
    before = view.image.get_array().copy()
    view.sliders["azimuth"].value = -75.0
    view.sliders["specular"].value = 0.9
    view.sliders["exponent"].value = 4.0
    material = dataclasses.replace(
        result.record.scene.objects[0].material, specular=0.9, exponent=4.0
    )
    light = Light(direction=light_direction(result.record.scene.camera, -75.0, 30.0))
    light = dataclasses.replace(light, color=result.record.scene.lights[0].color)
    expected = result.relight(lights=(light,), materials={0: material}).image
    shown = np.asarray(view.image.get_array())
    np.testing.assert_array_equal(shown, expected)
    assert not np.array_equal(shown, before)
    assert "azimuth -75°" in view._title.get_text()


def test_the_light_direction_is_seen_from_the_camera():
    camera = Camera(eye=(0.0, 0.0, 5.0))
    np.testing.assert_allclose(light_direction(camera, 0, 0), (0, 0, -1), atol=1e-15)
    np.testing.assert_allclose(light_direction(camera, 90, 0), (-1, 0, 0), atol=1e-15)
    np.testing.assert_allclose(light_direction(camera, 0, 90), (0, -1, 0), atol=1e-15)
    side = Camera(eye=(5.0, 0.0, 0.0))  # looking along -x: the headlight shines along -x
    np.testing.assert_allclose(light_direction(side, 0, 0), (-1, 0, 0), atol=1e-15)


def test_results_relight_cannot_recompute_are_refused():
    flat = render(load_scene("builtin:sphere"), 8, 8, shading="flat")
    with pytest.raises(ValueError, match="shading='flat' render fixes its colors per polygon"):
        RelightView(flat)
    with pytest.raises(TypeError, match="'result' must be a RenderResult"):
        relight_widget("sphere")

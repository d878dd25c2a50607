"""Relighting with sliders: the image function run again as a light and a material change.

Other views draw a trace; this one calls `RenderResult.relight`, the last
stage of the pipeline (Rendermatic thesis ch. 7), each time a slider moves:
visibility is never run again, which is what makes the sliders live.
"""

from __future__ import annotations

import dataclasses
import time

import ipywidgets as widgets
import numpy as np

from ..pipeline.result import RenderResult
from ..scene.model import Light
from ..vectors import unit_vectors
from ._common import DisplaysWidget, new_figure, say, status_label
from .stepper import figure_widget, refresh_figure

FIGURE_INCHES = 5.0  # the image's square figure: with the sliders, inside `_common.WIDEST`


def light_direction(camera, azimuth: float, elevation: float) -> tuple[float, float, float]:
    """The `Light.direction` of a light at (azimuth, elevation) degrees seen from the camera.

    Azimuth 0, elevation 0 is a light behind the viewer (a headlight);
    azimuth turns it to the viewer's right about the camera's up, elevation
    raises it toward up. The light shines along the returned vector, from
    that side toward the scene.

    Examples
    --------
    >>> from scanviz.scene import Camera
    >>> light_direction(Camera(), 0, 0)
    (-0.0, -0.0, -1.0)
    >>> np.round(light_direction(Camera(), 90, 0), 12)
    array([-1., -0., -0.])
    """
    back = unit_vectors(np.subtract(camera.eye, camera.look_at)[None])[0]
    right = unit_vectors(np.cross(camera.up, back)[None])[0]
    up = np.cross(back, right)
    a, e = np.radians(azimuth), np.radians(elevation)
    toward = np.cos(e) * (np.sin(a) * right + np.cos(a) * back) + np.sin(e) * up
    return tuple(float(c) for c in -toward)


class RelightView(DisplaysWidget):
    """Sliders for one directional light and every object's material, over the relit image.

    Every object is relit as made wholly of its own material with the
    sliders' diffuse, specular and exponent (the meaning of `relight`'s
    ``materials``: a mesh's face and vertex materials give way to it).

    Parameters
    ----------
    result : RenderResult
        A Phong or Gooch render by an opaque visibility algorithm (the ones
        `relight` can recompute).

    Attributes
    ----------
    widget : ipywidgets.Box
        The sliders beside the image, and a line giving the relight's time.
    sliders : dict of str to ipywidgets slider
        "azimuth", "elevation" (degrees, seen from the camera),
        "diffuse", "specular", "exponent" (of every object).
    current : RenderResult
        The relit result on show: ``result.relight`` with the sliders' light and materials.

    Raises
    ------
    ValueError
        For a result `relight` cannot recompute (flat, Gouraud, a-buffer), naming what to re-render.
    """

    def __init__(self, result: RenderResult):
        if not isinstance(result, RenderResult):
            raise TypeError(f"'result' must be a RenderResult; got {type(result).__name__}")
        if result.record is None:
            raise ValueError(
                "'result' must be made by scanviz.render (it keeps what relight needs)"
            )
        self.result = result
        scene = result.record.scene
        self._objects = [o.material for o in scene.objects]
        first = self._objects[0] if self._objects else None
        self._color = scene.lights[0].color if scene.lights else (1.0, 1.0, 1.0)
        self.sliders = {
            "azimuth": _slider(30.0, -180.0, 180.0, 1.0, "azimuth °"),
            "elevation": _slider(30.0, -89.0, 89.0, 1.0, "elevation °"),
            "diffuse": _slider(first.diffuse if first else 0.7, 0.0, 1.0, 0.01, "diffuse kd"),
            "specular": _slider(first.specular if first else 0.3, 0.0, 1.0, 0.01, "specular ks"),
            "exponent": widgets.FloatLogSlider(
                value=min(max(first.exponent if first else 32.0, 1.0), 512.0),
                base=2,
                min=0,
                max=9,
                step=0.1,
                description="exponent n",
            ),
        }
        began = time.perf_counter()
        self.current = self._relit()  # the first image is the sliders' too; refuses a flat render
        self.figure, (ax,) = new_figure(1, width=FIGURE_INCHES, height=FIGURE_INCHES)
        self.image = ax.imshow(self.current.image, origin="lower", interpolation="nearest")
        ax.set_axis_off()
        self._title = ax.set_title("", fontsize=9)
        self._canvas = figure_widget(self.figure)
        self.status = status_label()
        self._show(time.perf_counter() - began)
        for slider in self.sliders.values():
            slider.observe(lambda _: self.update(), names="value")
        controls = widgets.VBox([*self.sliders.values(), self.status])
        self.widget = widgets.HBox([controls, self._canvas])

    def lights(self) -> tuple[Light, ...]:
        """The one directional light the sliders give (the color of the scene's first light)."""
        s = self.sliders
        camera = self.result.record.scene.camera
        direction = light_direction(camera, s["azimuth"].value, s["elevation"].value)
        return (Light(direction=direction, color=self._color),)

    def materials(self) -> dict:
        """Every object's own material with the sliders' diffuse, specular and exponent."""
        s = self.sliders
        changed = {k: float(s[k].value) for k in ("diffuse", "specular", "exponent")}
        return {i: dataclasses.replace(m, **changed) for i, m in enumerate(self._objects)}

    def update(self) -> None:
        """Relight with the sliders' light and materials and show the image."""
        began = time.perf_counter()
        self.current = self._relit()
        self._show(time.perf_counter() - began)

    def _relit(self) -> RenderResult:
        return self.result.relight(lights=self.lights(), materials=self.materials())

    def _show(self, spent: float) -> None:
        self.image.set_data(self.current.image)
        s = self.sliders
        self._title.set_text(
            f"light at azimuth {s['azimuth'].value:.0f}°, elevation {s['elevation'].value:.0f}°"
        )
        refresh_figure(self.figure, self._canvas)
        height, width = self.current.polygon.shape
        say(self.status, f"relit {width}x{height} in {spent * 1e3:.0f} ms (visibility not rerun)")


def _slider(value: float, low: float, high: float, step: float, description: str):
    return widgets.FloatSlider(value=value, min=low, max=high, step=step, description=description)


def relight_widget(result: RenderResult) -> RelightView:
    """Sliders for the light direction and the material; the image follows them by `relight`.

    Parameters
    ----------
    result : RenderResult
        A Phong or Gooch render by an opaque visibility algorithm.

    Returns
    -------
    RelightView
        Display it (or its ``.widget``) in a notebook.

    Examples
    --------
    >>> from scanviz import load_scene, render
    >>> view = relight_widget(render(load_scene("builtin:sphere"), 24, 24))
    >>> view.sliders["azimuth"].value = -60.0
    >>> bool((view.image.get_array() == view.current.image).all())
    True
    """
    return RelightView(result)

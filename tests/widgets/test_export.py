"""Steppers as pictures: `Stepper.save` (GIF or PNG frames) and the static still of a widget."""

import numpy as np
import pytest
from PIL import Image

from scanviz import scan_convert
from scanviz.widgets import Stepper, scan_conversion_stepper
from scanviz.widgets.export import frame_steps, save_steps, static_html

TRIANGLE = [(0, 0), (4, 0), (4, 3)]


@pytest.fixture(scope="module")
def stepper():
    return scan_conversion_stepper(TRIANGLE, 5, 3)


def test_frame_steps_keep_both_ends_and_thin_evenly():
    for total in (0, 1, 7, 100, 12_345):
        for most in (2, 5, 120):
            steps = frame_steps(total, max_frames=most)
            assert steps[0] == 0 and steps[-1] == total
            assert steps == sorted(set(steps)) and len(steps) <= most
            assert len(steps) == min(total + 1, most)
    with pytest.raises(ValueError, match="'a step'"):
        frame_steps(5, [6])
    with pytest.raises(ValueError, match="'max_frames'"):
        frame_steps(5, max_frames=1)


def test_a_gif_has_one_frame_per_step_drawn_and_the_stepper_stays_put(stepper, tmp_path):
    stepper.slider.value = 2
    paths = stepper.save(tmp_path / "scan.gif", steps=[0, 3, len(stepper.model)])
    assert paths == [tmp_path / "scan.gif"] and stepper.slider.value == 2
    with Image.open(paths[0]) as gif:
        assert gif.n_frames == 3 and gif.info["loop"] == 0
        frames = []
        for k in range(gif.n_frames):
            gif.seek(k)
            frames.append(np.asarray(gif.convert("RGB")))
    assert not np.array_equal(frames[0], frames[-1])  # the end is not the start


def test_png_frames_go_into_a_folder_named_by_step(stepper, tmp_path):
    paths = stepper.save(tmp_path / "frames", max_frames=3)
    last = len(stepper.model)
    assert [p.name for p in paths] == [f"step_{s:05d}.png" for s in frame_steps(last, None, 3)]
    pictures = [np.asarray(Image.open(p).convert("RGB")) for p in paths]
    assert pictures[0].shape == pictures[-1].shape and pictures[0].shape[1] >= 480
    assert not np.array_equal(pictures[0], pictures[-1])


def test_a_refused_trace_cannot_be_saved(tmp_path, monkeypatch):
    monkeypatch.setattr(Stepper, "MAX_STEPS", 2)
    refused = Stepper(scan_convert(TRIANGLE, 5, 3, trace=True).trace)
    with pytest.raises(ValueError, match="refused its trace"):
        save_steps(refused, tmp_path / "x.gif")


def test_the_static_still_shows_the_text_and_pictures_not_the_controls(stepper):
    still = static_html(stepper.widget)
    assert stepper.label.value in still and "<img" in still
    assert "<button" not in still and "slider" not in still.lower()


def _every_stepper():
    from scanviz.scene.builtin import builtin_scene
    from scanviz.shading import ReflectionModel
    from scanviz.surfaces import View, gaussian
    from scanviz.visibility import examples
    from scanviz.widgets import (
        bsp_stepper,
        depth_sort_stepper,
        dislop_stepper,
        fast_phong_stepper,
        fill_stepper,
        horizon_stepper,
        interpolation_stepper,
        line_stepper,
        painter_stepper,
        perimeter_stepper,
        scanline_visibility_stepper,
        viewing_stepper,
        warnock_stepper,
        zbuffer_stepper,
    )

    corner = View((3, 4, 3), (-3, -4, -3))
    model = ReflectionModel(
        Ia=255, ka=0.1, Ip=255, kd=(0.75, 0.55, 0.3), ks=0.7, n=32, r_plus_r0=1.5
    )
    triangle = [(3.3, 3.2), (12.7, 5.1), (6.6, 12.4)], [(0, 0, 1), (0.3, 0, 1), (0, 0.3, 1)]
    return {
        "scan conversion": lambda: scan_conversion_stepper(TRIANGLE, 5, 3),
        "fill": lambda: fill_stepper([(1, 1), (14, 3), (6, 12)], 16, 14),
        "midpoint line": lambda: line_stepper(0, 0, 5, 2),
        "z-buffer": lambda: zbuffer_stepper(builtin_scene("umbc_zbuffer"), 12, 12),
        "interpolation": lambda: interpolation_stepper("umbc_zbuffer"),
        "viewing": lambda: viewing_stepper(builtin_scene("sphere", level=0), 32, 32),
        "painter": lambda: painter_stepper(examples.slides_painter(), 16, 12),
        "depth sort": lambda: depth_sort_stepper(examples.cyclic_overlap(), 24, 24),
        "bsp": lambda: bsp_stepper(examples.slides_bsp(), 32, 24),
        "warnock": lambda: warnock_stepper(examples.slides_painter(), 16, 12),
        "scanline": lambda: scanline_visibility_stepper(examples.interpenetrating(), 16, 12),
        "horizon": lambda: horizon_stepper(gaussian(4), corner, 32, 32),
        "perimeter": lambda: perimeter_stepper(gaussian(4), corner, 32, 32),
        "fast phong": lambda: fast_phong_stepper(
            *triangle, (0.2, 0.2, 1), (0, 0, 1), model, width=16, height=16
        ),  # fmt: skip
        "dislop": lambda: dislop_stepper((1.3, 1.6), (13.7, 12.1), 16, 14),
    }


@pytest.mark.parametrize("name", list(_every_stepper()))
def test_every_stepper_saves_a_gif_that_shows_its_steps(name, tmp_path):
    stepper = _every_stepper()[name]()
    last = len(stepper.model)
    (path,) = stepper.save(tmp_path / "steps.gif", steps=[0, last // 2, last])
    with Image.open(path) as gif:
        frames = []
        for k in range(gif.n_frames):
            gif.seek(k)
            frames.append(np.asarray(gif.convert("RGB")))
    assert len(frames) == 3 and last > 0
    assert not np.array_equal(frames[0], frames[-1]), f"{name}: the end looks like the start"

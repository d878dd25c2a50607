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

"""`python -m scanviz surface --antialias`: Wang's ch. 5 from the command line."""

import matplotlib.image
import numpy as np
import pytest

from scanviz.antialias.surfaces import antialiased_hidden_lines, smoothed_surface
from scanviz.cli import _default_view, main
from scanviz.surfaces import gaussian, polynomial

SIZE = ["--width", "48", "--height", "40"]


@pytest.mark.parametrize("method", ["dislop", "post"])
def test_lines_are_the_antialiased_hidden_lines(tmp_path, capsys, method):
    path = tmp_path / "lines.png"
    assert main(["surface", "gaussian", "--antialias", method, "-o", str(path), *SIZE]) == 0
    assert f"fpa: {method}: " in capsys.readouterr().out
    surface = gaussian()
    view = _default_view(surface, None, None, False)
    lines = antialiased_hidden_lines(surface, view, 48, 40, method=method, background=1.0, intensity=0.0)  # fmt: skip
    written = matplotlib.image.imread(path)[::-1, :, 0]
    np.testing.assert_allclose(written, lines.image, atol=1 / 255 + 1e-6)  # 8-bit PNG
    assert ((written > 0.1) & (written < 0.9)).mean() > 0.05  # grey: anti-aliased


def test_surface_mode_smooths_the_silhouette(tmp_path, capsys):
    path = tmp_path / "surface.png"
    argv = ["surface", "polynomial", "--points", "12", "--mode", "surface", "--shading", "flat"]
    assert main([*argv, "--antialias", "dislop", "-o", str(path), *SIZE]) == 0
    out = capsys.readouterr().out
    assert "fpa: dislop: " in out and "outline pieces" in out
    surface = polynomial(12)
    view = _default_view(surface, None, None, False)
    smooth = smoothed_surface(surface, view, 48, 40, shading="flat", background=(1.0, 1.0, 1.0))
    written = matplotlib.image.imread(path)[::-1, :, :3]
    np.testing.assert_allclose(written, smooth.image, atol=1 / 255 + 1e-6)


def test_none_is_the_aliased_drawing(tmp_path):
    plain, none = tmp_path / "plain.png", tmp_path / "none.png"
    assert main(["surface", "gaussian", "-o", str(plain), *SIZE]) == 0
    assert main(["surface", "gaussian", "--antialias", "none", "-o", str(none), *SIZE]) == 0
    np.testing.assert_array_equal(matplotlib.image.imread(plain), matplotlib.image.imread(none))


@pytest.mark.parametrize(
    ("argv", "message"),
    [(["--algorithm", "fha", "--antialias", "dislop"], "--antialias applies to --algorithm fpa only; got fha"),
     (["--antialias", "wu"], None)],
)  # fmt: skip
def test_refused_options_name_the_rule(capsys, argv, message):
    assert main(["surface", "gaussian", *argv, *SIZE]) == 2
    err = capsys.readouterr().err
    assert (message or "invalid choice: 'wu'") in err


def test_the_complex_surface_is_refused(capsys):
    assert main(["surface", "three_poles", "--points", "9", "--antialias", "post", *SIZE]) == 2
    assert "--antialias does not apply to three_poles" in capsys.readouterr().err

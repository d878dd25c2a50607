"""bench shading: runs in quick mode, every mode on every scene, errors measured against Phong."""

import numpy as np
import pytest

from scanviz.bench.shading import MODES, error_levels, run_shading
from scanviz.cli import main


def test_quick_bench_prints_every_mode_and_writes_the_plot(capsys, tmp_path):
    rows = run_shading(quick=True, plot=str(tmp_path / "shading.png"))
    out = capsys.readouterr().out
    assert {r["mode"] for r in rows} == set(MODES) and len(rows) == 2 * len(MODES)
    assert all(r["max"] == r["rms"] == 0.0 for r in rows if r["mode"] == "phong")  # the reference
    assert all(r["rms"] > 0 for r in rows if r["mode"] == "flat")
    sides = sorted({r["side"] for r in rows}, reverse=True)
    assert sides[0] > sides[1] > 0  # a finer sphere has smaller triangles on the screen
    assert "fast_phong" in out and (tmp_path / "shading.png").stat().st_size > 0


def test_error_levels_is_the_largest_channel_in_levels():
    a = np.zeros((2, 2, 3))
    b = a.copy()
    b[0, 0] = (1 / 255, 3 / 255, 0)
    b[1, 1] = (0, 0, 4 / 255)
    worst, rms = error_levels(a, b, np.array([[True, True], [False, True]]))
    assert worst == pytest.approx(4.0) and rms == pytest.approx(np.sqrt((9 + 0 + 16) / 3))


def test_the_cli_runs_it_and_refuses_other_suites_options(capsys):
    assert main(["bench", "shading", "--quick"]) == 0
    assert main(["bench", "shading", "--quick", "--grids", "10"]) == 2
    assert "--grids: options of 'bench surfaces' only" in capsys.readouterr().err

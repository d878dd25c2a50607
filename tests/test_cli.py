"""The command line: the slide example's table, JSON shape, PNG output, clean errors."""

import json
import subprocess
import sys

import matplotlib.image
import pytest

from scanviz.cli import main

SLIDE = "4,1 1,11 9,5 12,8 12,1"


def test_trace_prints_the_slide_table(capsys):
    assert main(["trace", "--vertices", SLIDE]) == 0
    out = capsys.readouterr().out
    rows = {line.split("|")[0].strip(): line for line in out.splitlines() if "|" in line}
    assert "e0: 3 7/10, -3/10, 11, -1" in rows["2"]
    assert "e0: 2 4/5" in rows["5"] and "e1: 9, -1 1/3, 11, +1" in rows["5"]
    assert rows["5"].rstrip().endswith("[3,9) w-1 [9,12) w-1")
    assert "e1: 7 2/3" in rows["6"] and "[3,8) w-1 [10,12) w-1" in rows["6"]
    assert "horizontal, kept for topology" in out


def test_trace_json_shape(capsys):
    assert main(["trace", "--vertices", SLIDE, "--json"]) == 0
    events = json.loads(capsys.readouterr().out)["events"]
    assert all("kind" in e for e in events)
    aet = {e["y"]: e["entries"] for e in events if e["kind"] == "aet_sorted"}
    assert [entry["x"] for entry in aet[6]] == pytest.approx([2.5, 23 / 3, 10, 12])
    assert set(aet[6][0]) >= {"x", "dxdy", "ymax", "winding"}
    spans = [(e["y"], e["x_start"], e["x_end"]) for e in events if e["kind"] == "span"]
    assert spans[:2] == [(1, 4, 12), (2, 4, 12)]


def test_center_sampling_and_rules_are_options(capsys):
    assert (
        main(
            [
                "trace",
                "--vertices",
                SLIDE,
                "--sample",
                "center",
                "--rule",
                "evenodd",
                "--subpixel-bits",
                "none",
            ]
        )
        == 0
    )
    assert "e0: 3 17/20" in capsys.readouterr().out  # row 1 is the scanline y = 1.5


def test_fill_writes_a_png_with_y_up(tmp_path):
    out = tmp_path / "fill.png"
    assert (
        main(["fill", "--vertices", "0,0 4,0 0,4", "--width", "6", "--height", "5", "-o", str(out)])
        == 0
    )
    image = matplotlib.image.imread(out)[..., 0]
    assert image.shape == (5, 6)
    assert image[-1, :4].all() and not image[0].any()  # bottom row full, top row empty


@pytest.mark.parametrize(
    "args, message",
    [
        (["trace", "--vertices", "4,1 1,nan 9,5"], "not finite"),
        (["trace", "--vertices", "4,1 1,2"], "at least 3"),
        (["trace", "--vertices", "4,1 1,2 x"], "not of the form x,y"),
        (["trace", "--vertices", SLIDE, "--width", "-3"], "'width' must be in"),
        (["fill", "--vertices", SLIDE, "-o", "/nonexistent/dir/out.png"], "error"),
    ],
)
def test_bad_input_is_one_line_without_traceback(args, message):
    run = subprocess.run([sys.executable, "-m", "scanviz", *args], capture_output=True, text=True)
    assert run.returncode != 0
    assert message in run.stderr
    assert "Traceback" not in run.stderr and len(run.stderr.strip().splitlines()) == 1


def test_bad_option_value_exits_nonzero():
    run = subprocess.run(
        [sys.executable, "-m", "scanviz", "trace", "--vertices", SLIDE, "--subpixel-bits", "17"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2 and "subpixel_bits" in run.stderr and "Traceback" not in run.stderr


def test_bench_quick_runs(capsys):
    assert main(["bench", "raster", "--quick"]) == 0
    out = capsys.readouterr().out
    assert "100,000 small triangles" in out and "scanviz ms" in out

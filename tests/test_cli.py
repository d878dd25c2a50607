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


# --- issue 8 -------------------------------------------------------------------------------

TRIANGLE_OBJ = "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n"


def one_error_line(capsys, argv, status=2):
    assert main(argv) == status
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err


@pytest.mark.parametrize(
    "argv, message",
    [
        (["render", "builtin:sphere", "-o", "f.qqq"], "unsupported image file extension '.qqq'; supported: .png, .jpg"),
        (["render", "builtin:sphere", "-o", "/tmp"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", "/dev/full"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", "noext"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", ""], "-o/--output must be a file name; got ''"),
        (["render", "builtin:sphere", "--width", "0"], "argument --width: must be >= 1; got 0"),
        (["render", "builtin:sphere", "--height", "1" * 5000], "must be an integer of at most 30 digits"),
        (["render", "builtin:sphere", "--visibility", "x\ny"], r"invalid choice: 'x\ny'"),
        (["render", "no\nsuch.json"], r"No such file or directory: 'no\nsuch.json'"),
        (["render", "builtin:sphere", "--bogus"], "unrecognized arguments: --bogus"),
        (["fill", "--vertices", "0,0 4,0 0,4", "--scale", "100000", "-o", "x.png"], "over the memory limit"),
        ([], "the following arguments are required: command"),
    ],
)  # fmt: skip
def test_issue8_d11_every_cli_error_is_one_line(capsys, argv, message):
    assert message in one_error_line(capsys, argv)


def test_issue8_d11_bad_files_are_one_line_naming_the_file(capsys, tmp_path):
    scene = tmp_path / "scene.json"
    scene.write_bytes(b"\xff\xfe{}")
    assert "scene.json' is not UTF-8 text" in one_error_line(capsys, ["render", str(scene)])
    scene.write_text('{"version": ' + "9" * 5000 + "}")
    assert "integer literal of 5000 digits" in one_error_line(capsys, ["render", str(scene)])
    from scanviz.limits import file_limit

    with file_limit("1M"):
        assert "larger than the file limit" in one_error_line(capsys, ["render", "/dev/zero"])


def test_issue8_d6_deep_json_is_one_line(capsys, tmp_path):
    scene = tmp_path / "deep.json"
    scene.write_text("[" * 5000 + "]" * 5000)
    assert "nested 5000 deep" in one_error_line(capsys, ["render", str(scene)])


def test_issue8_d11_interrupt_is_one_line_and_130(capsys, monkeypatch):
    import scanviz.pipeline

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(scanviz.pipeline, "render", interrupted)
    assert one_error_line(capsys, ["render", "builtin:painter"], status=130) == "interrupted\n"


@pytest.mark.parametrize("suffix", [".png", ".jpg", ".JPEG", ".tif"])
def test_issue8_d11_image_formats(tmp_path, suffix):
    out = tmp_path / f"painter{suffix}"
    assert (
        main(["render", "builtin:painter", "--width", "16", "--height", "12", "-o", str(out)]) == 0
    )
    image = matplotlib.image.imread(out)
    assert image.shape[:2] == (12, 16)
    # Pixel (x, y) = (3, 3) of the slide (y up) is in the second polygon: green, opaque.
    pixel = image[12 - 1 - 3, 3, :3] / (255 if image.dtype.kind == "u" else 1)
    assert pixel.tolist() == pytest.approx([0, 1, 0], abs=0.02)


def test_issue8_d13_render_an_obj_model_with_every_option(tmp_path, capsys):
    model = tmp_path / "tri.OBJ"
    model.write_text(TRIANGLE_OBJ)
    out = tmp_path / "tri.png"
    for options in (
        [],
        ["--visibility", "abuffer", "--mask", "4x4", "--weights", "mask", "--edges"],
        ["--visibility", "flawed", "--affine", "--no-cull", "--shading", "flat"],
        [
            "--perspective-correct",
            "--cull",
            "--shading",
            "gooch",
            "--width",
            "32",
            "--height",
            "16",
        ],
    ):
        assert (
            main(
                ["render", str(model), "-o", str(out), "--width", "24", "--height", "24", *options]
            )
            == 0
        )
        image = matplotlib.image.imread(out)
        assert image[..., :3].std() > 0  # the model shows against the background
    assert capsys.readouterr().err == ""


def test_issue8_d13_render_options_reach_the_renderer(monkeypatch):
    import scanviz.pipeline

    seen = {}
    real = scanviz.pipeline.render

    def spy(scene, width, height, **options):
        seen.update(options)
        return real(scene, width, height, **options)

    monkeypatch.setattr(scanviz.pipeline, "render", spy)
    argv = ["render", "builtin:painter", "--width", "16", "--height", "12"]
    assert main(argv) == 0 and seen["cull"] is None and seen["perspective_correct"] is True
    assert main([*argv, "--affine", "--cull", "--visibility", "abuffer", "--mask", "8x4"]) == 0
    assert seen["cull"] is True and seen["perspective_correct"] is False
    assert seen["visibility"] == "abuffer" and seen["mask"] == "8x4"
    assert main([*argv, "--no-cull", "--weights", "mask", "--edges"]) == 0
    assert seen["cull"] is False and seen["weights"] == "mask" and seen["edges"] is True


def test_conformance_command_parses_its_arguments():
    from scanviz.cli import build_parser

    args = build_parser().parse_args(["conformance", "--fuzz", "50", "--seed", "7"])
    assert (args.command, args.fuzz, args.seed) == ("conformance", 50, 7)

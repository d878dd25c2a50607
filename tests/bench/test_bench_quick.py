"""Every bench suite runs in quick mode (none rots), into one report; Ctrl-C stops cleanly.

No test depends on timing: the quick run is asserted to finish and print
each suite's table, not how fast. One ``bench all --quick`` run (module
fixture) serves every suite's test; the module runs on one xdist worker.
"""

import contextlib
import importlib
import io
import json

import numpy as np
import pytest

from scanviz.bench import SUITES, run
from scanviz.bench import scaling as bench_scaling
from scanviz.bench.report import machine, markdown, read_rows
from scanviz.cli import main

pytestmark = pytest.mark.xdist_group("bench")

TABLE_HEADS = {
    "raster": "scanviz ms",
    "render": "Mtri/s",
    "coverage": "RMS error",
    "grading": "students/min",
    "visibility": "polygons/s",
    "surfaces": "zbuf-phong",
    "shading": "max err",
    "antialias": "RMS err",
    "scaling": "growth exponent k",
}


@pytest.fixture(scope="module")
def quick_report(tmp_path_factory):
    """`bench all --quick --report R --plot-dir P` run once: (status, stdout, report, plots)."""
    folder = tmp_path_factory.mktemp("bench")
    report, plots = folder / "report.md", folder / "plots"
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        status = main(["bench", "all", "--quick", "--report", str(report), "--plot-dir", str(plots)])  # fmt: skip
    return status, out.getvalue(), report, plots


def section(report_text: str, suite: str) -> str:
    return report_text.split(f"\n## {suite}\n", 1)[1].split("\n## ", 1)[0]


def test_every_suite_has_a_table_head():
    assert set(TABLE_HEADS) == set(SUITES)


def test_bench_all_quick_exits_0_with_every_suite_ok(quick_report):
    status, out, report, _ = quick_report
    assert status == 0
    assert f"{report}: {len(SUITES)} suites in " in out.splitlines()[-1]
    rows = read_rows(report)
    assert list(rows["suites"]) == list(SUITES) and rows["quick"] is True
    assert all(entry["status"] == "ok" for entry in rows["suites"].values())


@pytest.mark.parametrize("suite", SUITES)
def test_each_suite_runs_in_quick_mode_and_its_table_is_printed_and_reported(quick_report, suite):
    _, out, report, _ = quick_report
    text = report.read_text()
    assert TABLE_HEADS[suite] in section(text, suite)
    assert TABLE_HEADS[suite] in out  # the tee still printed it
    assert read_rows(report)["suites"][suite]["rows"]  # its run_* returned rows


def test_plot_dir_gets_a_plot_per_plotting_suite(quick_report):
    from scanviz.bench import PLOTTING

    plots = quick_report[3]
    assert sorted(p.stem for p in plots.glob("*.png")) == sorted(PLOTTING)


def test_the_header_names_the_machine_the_versions_and_the_peers(quick_report):
    text = quick_report[2].read_text()
    header = text.split("\n## ", 1)[0]
    for field in ("- date: ", "UTC", "- machine: ", " cores (", "RAM", "- OS: ", "Python ", "numpy ", "numba ", "threads", "- peers: ", "OpenCV", "moderngl", "skia-python", "cairo"):  # fmt: skip
        assert field in header, field
    info = read_rows(quick_report[2])["machine"]
    assert info["cores"] >= 1 and info["numpy"] == np.__version__
    assert set(info["peers"]) == {"OpenCV", "moderngl", "skia-python", "cairo"}


def test_compare_matches_the_rows_of_two_reports(quick_report, capsys):
    report = quick_report[2]
    assert main(["bench", "compare", str(report), str(report)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) > 10 and all(line.endswith("1.00") for line in lines[2:])


def fake_suites(monkeypatch, calls, stop_at=None, error=None):
    """Replace every suite's run_* by one that prints a line and returns a row (or raises)."""
    for suite in SUITES:

        def fake(*, quick=False, plot=None, suite=suite):
            calls.append(suite)
            print(f"table of {suite}")
            if suite == stop_at:
                raise error
            return [{"suite": suite, "ms": 1.0}]

        monkeypatch.setattr(importlib.import_module(f"scanviz.bench.{suite}"), f"run_{suite}", fake)


def test_ctrl_c_in_bench_all_writes_the_partial_report_and_exits_130(monkeypatch, capsys, tmp_path):
    calls = []
    fake_suites(monkeypatch, calls, stop_at="coverage", error=KeyboardInterrupt())
    report = tmp_path / "partial.md"
    assert main(["bench", "all", "--report", str(report)]) == 130
    err = capsys.readouterr().err
    assert f"bench: interrupted (partial report written to {report})\n" in err
    assert "Traceback" not in err and calls == ["raster", "render", "coverage"]
    text = report.read_text()
    assert "## raster\n\nok" in text and "## coverage\n\ninterrupted" in text
    assert "table of coverage" in section(text, "coverage") and "## grading" not in text
    assert "Not run (the run was stopped first): grading, visibility" in text
    assert read_rows(report)["suites"]["render"] == {"status": "ok", "seconds": pytest.approx(0, abs=1), "rows": [{"suite": "render", "ms": 1.0}]}  # fmt: skip


def test_ctrl_c_in_one_suite_is_one_line_and_130(monkeypatch, capsys):
    fake_suites(monkeypatch, [], stop_at="raster", error=KeyboardInterrupt())
    assert main(["bench", "raster"]) == 130
    assert capsys.readouterr().err == "bench: interrupted\n"


def test_a_failing_suite_is_reported_with_its_traceback_and_the_others_run(monkeypatch, capsys, tmp_path):  # fmt: skip
    calls = []
    fake_suites(monkeypatch, calls, stop_at="render", error=RuntimeError("broken kernel"))
    report = tmp_path / "report.md"
    assert main(["bench", "all", "--report", str(report)]) == 1
    assert calls == list(SUITES)
    assert "1 suites failed" in capsys.readouterr().err
    text = report.read_text()
    assert "## render\n\nfailed" in text and "RuntimeError: broken kernel" in section(
        text, "render"
    )


@pytest.mark.parametrize(
    "argv, message",
    [
        (["raster", "--report", "r.md"], "--report: options of 'bench all' only"),
        (["all", "--plot", "p.png"], "'bench all' takes --plot-dir"),
        (["compare", "a.md"], "'bench compare' takes two report files"),
        (["raster", "a.md"], "'bench compare' takes two report files"),
        (["all", "--grids", "10"], "--grids: options of 'bench surfaces' only"),
    ],
)
def test_bench_options_of_other_commands_are_refused_in_one_line(capsys, argv, message):
    assert main(["bench", *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.splitlines()) == 1


def test_run_returns_the_rows_and_refuses_an_unknown_suite(monkeypatch):
    fake_suites(monkeypatch, [])
    assert run("scaling", quick=True) == [{"suite": "scaling", "ms": 1.0}]
    with pytest.raises(ValueError, match="'suite' must be one of"):
        run("nope")


def test_markdown_rows_section_round_trips_numpy_values(tmp_path):
    from scanviz.bench.report import SuiteRun

    runs = [SuiteRun("raster", "a table\n", [{"ms": np.float64(1.5), "n": np.int64(3)}], 0.5)]
    path = tmp_path / "r.md"
    path.write_text(markdown(machine(), runs, command="x", quick=False))
    assert read_rows(path)["suites"]["raster"]["rows"] == [{"ms": 1.5, "n": 3}]
    assert "Not run (the run was stopped first): render," in path.read_text()
    with pytest.raises(ValueError, match="not a scanviz bench report"):
        (tmp_path / "other.md").write_text("# hello\n")
        read_rows(tmp_path / "other.md")


# --- bench scaling ------------------------------------------------------------------------


def synthetic_rows(k_triangles, k_pixels, c=2e-6):
    rows = [
        {"sweep": "triangles", "method": "zbuffer", "triangles": n, "width": 1024, "height": 1024,
         "status": "ok", "ms": 1e3 * c * n**k_triangles}
        for n in (10**3, 10**4, 10**5, 10**6)
    ] + [
        {"sweep": "pixels", "method": "zbuffer", "triangles": 10**4, "width": s, "height": s,
         "status": "ok", "ms": 1e3 * c * (s * s) ** k_pixels}
        for s in (256, 512, 1024, 2048)
    ]  # fmt: skip
    return rows + [dict(rows[0], status="skipped", ms=None)]


@pytest.mark.parametrize("k_triangles, k_pixels", [(1.0, 1.0), (1.3, 0.7), (2.0, 0.5)])
def test_the_growth_exponents_and_factor_of_a_power_law_are_recovered(k_triangles, k_pixels):
    rows = synthetic_rows(k_triangles, k_pixels)
    (fit,) = bench_scaling.fits(rows)
    assert fit["k_triangles"] == pytest.approx(k_triangles) and fit["k_pixels"] == pytest.approx(k_pixels)  # fmt: skip
    sizes = [10**3, 10**4, 10**5, 10**6]
    seconds = [2e-6 * n**k_triangles for n in sizes]
    assert bench_scaling.power_law(sizes, seconds, k_triangles) == pytest.approx(2e-6)


def test_prediction_is_linear_after_one_point_then_follows_the_growth():
    assert bench_scaling._predicted([], 10**6) == 0.0
    assert bench_scaling._predicted([(100, 1.0)], 1000) == pytest.approx(10.0)
    assert bench_scaling._predicted([(100, 1.0), (1000, 100.0)], 10_000) == pytest.approx(1e4)
    assert bench_scaling._predicted([(100, 1.0), (1000, 2.0)], 10_000) == pytest.approx(20.0)


class _Bar:
    def __init__(self):
        self.lines = []

    def write(self, text):
        self.lines.append(text)

    def update(self, n=1):
        pass


def test_a_sweep_skips_what_is_predicted_over_budget_and_everything_larger(monkeypatch):
    seconds = {2: 0.01, 4: 0.04, 8: 1.0}  # 8 is predicted 0.16 s, then 16 at 1 * 4**2.32 s
    monkeypatch.setattr(bench_scaling, "BUDGET", 5.0)
    monkeypatch.setattr(
        bench_scaling,
        "_in_process",
        lambda method, cells, size: {"seconds": seconds[size], "runs": 1, "peak_bytes": 0},
    )
    bar = _Bar()
    rows = bench_scaling._sweep("pixels", "zbuffer", [(4, s) for s in (2, 4, 8, 16, 32)], True, bar)
    assert [r["status"] for r in rows] == ["ok", "ok", "ok", "skipped", "skipped"]
    assert rows[3]["reason"].startswith("predicted ") and "> 5 s" in rows[3]["reason"]
    assert rows[4]["reason"] == rows[3]["reason"] and len(bar.lines) == 5


def test_a_refused_point_is_reported_and_stops_the_sweep(monkeypatch):
    from scanviz.limits import memory_limit

    monkeypatch.setattr(bench_scaling, "BUDGET", 1e9)  # nothing predicted over it
    bar = _Bar()
    with memory_limit("64K"):
        rows = bench_scaling._sweep("pixels", "zbuffer", [(2, 8), (2, 512), (2, 1024)], True, bar)
    assert [r["status"] for r in rows] == ["ok", "refused", "skipped"]
    assert "over the memory limit of 64.0 KiB" in rows[1]["reason"]
    assert rows[2]["reason"] == "a smaller point was refused"
    assert "refused: " in bar.lines[1]


def test_the_grid_covers_every_sample_once_and_the_scene_fills_the_view():
    from scanviz import render
    from scanviz.raster import fill_polygons, rasterize_triangles

    xy, depth = bench_scaling.screen_triangles(5, 32)
    assert xy.shape == (50, 3, 2) and depth.shape == (50, 3)
    assert (rasterize_triangles(xy, 32, 32) == 1).all()  # watertight and over the whole raster
    assert (fill_polygons(xy, 32, 32) == 1).all()
    result = render(bench_scaling.height_field_scene(5), 32, 32, shading="phong")
    assert (result.polygon >= 0).all() and result.stats.polygons_in == 50


def test_a_point_measured_in_a_subprocess_reports_time_and_peak_memory():
    measured = bench_scaling._in_subprocess("rasterize_triangles", 2, 16)
    assert measured["seconds"] > 0 and measured["runs"] >= 1
    assert isinstance(measured["peak_bytes"], int) and measured["peak_bytes"] >= 0
    json.dumps(measured)


def test_the_scaling_plot_is_written(tmp_path):
    rows = synthetic_rows(1.0, 0.8)
    path = tmp_path / "scaling.png"
    bench_scaling.save_plot(rows + bench_scaling.fits(rows), str(path))
    assert path.stat().st_size > 0

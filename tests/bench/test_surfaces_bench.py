"""`python -m scanviz bench surfaces`: Table 2-4's storage, the arrays a run holds, the trends, the CLI.

Oracles: the byte counts Wang quotes for his formulas (spec §1.7), the
formulas as the spec writes them, array sizes from shapes and dtypes, exact
power laws timed by a fake clock, and ratios of the dissertation's printed
seconds worked out by hand. No test depends on real timing.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.bench import surfaces as bench
from scanviz.cli import main
from scanviz.surfaces import View, gaussian


def test_the_storage_formulas_give_the_bytes_the_dissertation_quotes():
    assert bench.fpa_storage_bytes(40, 40, 768, 480) == 34250
    assert bench.fpa_storage_bytes(50, 50, 768, 480) == 50330
    assert bench.anderson_storage_bytes(40, 40) == 33306
    assert bench.anderson_storage_bytes(50, 50) == 51626
    assert bench.fha_storage_bytes(40, 768) == 3584


@settings(max_examples=20)
@given(nx=st.integers(2, 500), ny=st.integers(2, 500), hr=st.integers(1, 4096), vr=st.integers(1, 4096))  # fmt: skip
def test_the_storage_formulas_are_the_specs(nx, ny, hr, vr):
    fpa = 12 * nx * ny + 24 + 2 + 2 + 4 * hr + 4 * vr + 6 * (nx - 1) * (ny - 1) + 100 + 2 + 2 + 800
    assert bench.fpa_storage_bytes(nx, ny, hr, vr) == fpa
    assert bench.anderson_storage_bytes(nx, ny) == 12 * nx * ny + 24 + 2 + 16 * (nx + ny) + 8 * nx * ny  # fmt: skip
    assert bench.fha_storage_bytes(nx, hr) == 12 * nx + 24 + 4 * hr + 8
    assert set(bench.fpa_storage(nx, ny, hr, vr)) <= set(bench.PURPOSES)


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda: bench.fpa_storage_bytes(1, 40, 768, 480), ValueError, "'nx' must be >= 2; got 1"),
        (lambda: bench.fpa_storage_bytes(40, 40, 0, 480), ValueError, "'hr' must be >= 1; got 0"),
        (lambda: bench.anderson_storage_bytes(40, 2.5), TypeError, "'ny' must be an int; got 2.5"),
        (lambda: bench.fha_storage_bytes(True, 768), TypeError, "'nx' must be an int; got True"),
    ],
)
def test_the_storage_formulas_refuse_bad_sizes(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_measured_storage_counts_the_arrays_of_a_run():
    surface, width, height = gaussian(6), 40, 30
    view = View((6, 8, 3), (-6, -8, -3))
    measured = bench.measured_storage(surface, view, width, height)
    facets, points = surface.facets, surface.nx * surface.ny
    fpa = measured["fpa"]
    assert fpa["horizons / perimeters"] == 8 * (2 * width + 2 * height)  # four int64 arrays
    assert fpa["enumerated facets"] == 8 * facets * (1 + 1 + 2)  # order, classes, (row, column)
    assert fpa["edge list"] == 8 * surface.edges * (3 + 1)  # (kind, row, column) and facet
    assert fpa["grid points"] == 8 * (surface.nx + surface.ny + points)
    assert fpa["projected points"] == 2 * 16 * points
    assert fpa["output image"] == 24 * width * height
    assert measured["fha"]["horizons / perimeters"] == 2 * 8 * width  # up, low float64
    zbuffer = measured["zbuffer"]
    assert zbuffer["depth + polygon buffers"] == 16 * width * height
    assert zbuffer["mesh"] == 24 * points + 2 * facets * 3 * 8
    raster = fpa["raster points"] // (2 * 8 + 8)  # (x, y) and the edge of each point
    assert fpa["point flags"] == 2 * raster and raster >= surface.edges


def test_the_1985_trends_are_those_of_the_printed_seconds():
    smooth = bench.wang_trends("smooth", 300, 60)
    ratio, k, side_ratio, side_k = smooth["fpa"]
    assert ratio == pytest.approx(4.30 / 0.40)  # Table 2-2, FPA 300, 60x60 over 10x10
    assert side_ratio == pytest.approx(6.18 / 2.93)  # 60x60, image 600 over 100
    assert 0 < k < 1 and 0 < side_k < 1  # the dissertation's claim: less than linear
    facets = np.log([81, 361, 841, 2401, 3481])  # 40x40 at 300 is only estimated: not fitted
    slope = np.polyfit(facets, np.log([0.40, 0.87, 1.57, 3.30, 4.30]), 1)[0]
    assert k == pytest.approx(slope)
    assert bench.wang_trends("smooth", 400, 60)["fpa"][0] is None  # 60x60 at 400 is an estimate
    assert bench.wang_trends("random", 300, 60)["anderson"][0] == pytest.approx(9.534 / 0.221)
    assert bench.wang_trends("random", 64, 10)["fpa"][:2] == (None, None)  # no such column


class Clock:
    """A fake `process_time`: each reading takes 1 ns; the fake algorithm its declared time."""

    now = 0.0

    def __call__(self) -> float:
        self.now += 1e-9
        return self.now


def test_the_fits_and_ratios_recover_exact_power_laws(monkeypatch, capsys):
    clock = Clock()

    def power_law(surface, view, side):  # 10 ms at 81 facets and 100^2: facets^0.5 side^1.5
        clock.now += 1e-2 * (surface.facets / 81) ** 0.5 * (side / 100) ** 1.5

    monkeypatch.setitem(bench.ALGORITHMS, "power-law", power_law)
    monkeypatch.setattr(bench, "process_time", clock)
    monkeypatch.setattr(bench, "LEAST_SECONDS", 0.045)  # 10 ms a run: 5 runs per cell
    result = bench.run_surfaces(
        grids=(10, 20, 60),
        images=(100, 200, 400),
        grid_image=100,
        image_grid=10,
        repeat=2,
        algorithms=("power-law",),
    )
    out = capsys.readouterr().out
    cells = [t.seconds for t in result.by_grid if t.surface == "smooth"]
    assert cells == pytest.approx([1e-2, 1e-2 * (361 / 81) ** 0.5, 1e-2 * (3481 / 81) ** 0.5])
    row = next(line for line in out.splitlines() if line.startswith("random  power-law"))
    ratio, k, k_all, side_ratio, side_k = (float(v) for v in row.split()[2:])
    assert ratio == pytest.approx((3481 / 81) ** 0.5, abs=0.01)
    assert k == k_all == pytest.approx(0.5, abs=0.005)
    assert side_ratio == pytest.approx(4**1.5, abs=0.01) and side_k == pytest.approx(1.5, abs=0.005)
    assert result.by_grid[0].runs == 5 and result.by_grid[-1].runs == 2  # 10 ms, 65 ms a run


def test_cli_bench_surfaces_quick_prints_every_algorithm_the_storage_and_the_plot(tmp_path, capsys):
    plot = tmp_path / "surfaces.png"
    assert main(["bench", "surfaces", "--quick", "--plot", str(plot)]) == 0
    out = capsys.readouterr().out
    lines = out.splitlines()
    header = next(line for line in lines if line.startswith("surface ") and "facets" in line)
    for name in bench.ALGORITHMS:
        assert f" {name}" in header
        for kind in bench.SURFACES:
            assert any(line.startswith(f"{kind:<8}{name:<15}") for line in lines), (kind, name)
    for kind, grid in (("smooth", "10x10"), ("smooth", "20x20"), ("random", "20x20")):
        assert any(line.split()[:2] == [kind, grid] for line in lines)
    assert "1985 FPA" in out and "1985 Anderson" in out
    assert "34,250" in out and "33,306" in out and "3,584" in out  # Table 2-4 at 40x40, 768x480
    assert "Anderson: formula only" in out
    for purpose in bench.PURPOSES + bench.SCANVIZ_PURPOSES:
        assert any(line.startswith(purpose) for line in lines), purpose
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_bench_surfaces_takes_its_own_options(capsys):
    argv = ["bench", "surfaces", "--grids", "3,4", "--images", "8", "--repeat", "1"]
    assert main([*argv, "--algorithms", "fpa-lines,fha"]) == 0
    out = capsys.readouterr().out
    header = next(line for line in out.splitlines() if line.startswith("surface ") and "facets" in line)  # fmt: skip
    assert header.split()[-2:] == ["fpa-lines", "fha"] and "zbuf-flat" not in header
    assert any(line.split()[:3] == ["smooth", "4x4", "9"] for line in out.splitlines())


@pytest.mark.parametrize(
    "argv, message",
    [
        (["bench", "surfaces", "--algorithms", "nonsense"], "'nonsense' is not one of fha"),
        (["bench", "surfaces", "--grids", "1"], "argument --grids: must be >= 2; got 1"),
        (["bench", "surfaces", "--images", "10,,20"], "integers >= 2 separated by commas"),
        (["bench", "surfaces", "--repeat", "0"], "must be >= 1"),
        (["bench", "surfaces", "--sizes", "10"], "--sizes: options of 'bench visibility' only"),
        (["bench", "surfaces", "--width", "9"], "--width: options of 'bench visibility' only"),
        (["bench", "visibility", "--grids", "10"], "--grids: options of 'bench surfaces' only"),
        (["bench", "raster", "--repeat", "2"], "options of 'bench visibility' or 'bench surfaces'"),
        (["bench", "raster", "--sizes", "10"], "--sizes: options of 'bench visibility' only"),
    ],
)
def test_cli_bench_surfaces_refuses_bad_options_in_one_line(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and message in err, err

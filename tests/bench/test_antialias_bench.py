"""bench antialias: quick mode prints every method; the references are exact; peers share our pixels."""

import math

import numpy as np
import pytest

from scanviz.antialias.peers import exact_band_line
from scanviz.bench import antialias
from scanviz.bench.antialias import KINDS, disk_coverage, methods, run_antialias
from scanviz.bench.antialias_peers import LIBRARIES, PEERS
from scanviz.cli import main
from tests.antialias.exact import disk_coverage as oracle_disk_coverage


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    import contextlib
    import io

    plot = tmp_path_factory.mktemp("bench") / "antialias.png"
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rows = run_antialias(quick=True, plot=str(plot))
    return rows, out.getvalue(), plot


def test_quick_bench_prints_every_method_and_writes_the_plot(quick_run):
    rows, out, plot = quick_run
    for kind in KINDS:
        names = [name for name, _ in methods(kind, 64)]
        assert [r["method"] for r in rows if r["kind"] == kind] == names
        for name in names:
            assert any(line.startswith(f"{kind:<7}{name}") for line in out.splitlines()), name
    for library in LIBRARIES:  # installed ones measured, the others said so
        for kind in KINDS:
            (row,) = [r for r in rows if r["kind"] == kind and r["method"] == library]
            assert row["available"] == (library in PEERS)
    assert "not available" in out or set(PEERS) == set(LIBRARIES)
    assert "intensity per unit length by angle" in out and plot.stat().st_size > 0


def test_the_references_have_zero_error(quick_run):
    rows, _, _ = quick_run
    for name in ("exact band", "exact area"):
        for row in (r for r in rows if r["method"] == name):
            assert row["max"] == 0.0 and np.allclose(row["intensity"], 1.0, rtol=0, atol=1e-12)
    # DISLOP_L exact is the same area by another route: rounding only
    for row in (r for r in rows if r["method"] == "DISLOP_L exact" and r["available"]):
        assert row["max"] < 1e-9


def test_supersampling_error_falls_with_k(quick_run):
    rows, _, _ = quick_run
    for kind in KINDS:
        by_k = {r["method"]: r for r in rows if r["kind"] == kind}
        errors = [by_k[f"supersample {k}x{k}"]["rms"] for k in (2, 4, 8)]
        assert errors[0] > errors[1] > errors[2] > 0, (kind, errors)
        assert by_k["supersample 8x8"]["max"] < by_k["supersample 2x2"]["max"]


def test_wu_dims_with_slope_and_dislop_does_not(quick_run):
    # Wang's claim (§4.2): DISLOP_L's intensity per unit length is constant; Wu's is cos(angle)
    rows, _, _ = quick_run
    wu = next(r for r in rows if r["method"] == "Wu")
    assert np.allclose(wu["intensity"], np.cos(np.radians(wu["angles"])), rtol=0, atol=1e-9)
    for row in (r for r in rows if r["method"].startswith("DISLOP_L") and r["available"]):
        assert np.allclose(row["intensity"], 1.0, atol=1e-9)


def test_missing_methods_print_not_available(monkeypatch, capsys):
    monkeypatch.setattr(antialias, "_dislop", lambda name: None)
    rows = run_antialias(quick=True)
    out = capsys.readouterr().out
    for name in ("DISLOP_L (printed)", "DISLOP_L exact", "DISLOP_E", "DISLOP_S"):
        (row,) = [r for r in rows if r["method"] == name]
        assert not row["available"]
        assert any(name in line and "not available" in line for line in out.splitlines())


# ---------------------------------------------------------------- the peers' pixel convention


@pytest.mark.parametrize("library", PEERS)
def test_a_horizontal_line_at_a_row_centre_lights_that_row_most(library):
    image = PEERS[library]["line"]((4.0, 10.5), (44.0, 10.5), 48, 24)
    assert image.shape == (24, 48) and image.sum(axis=1).argmax() == 10
    rows = image.sum(axis=1)
    assert rows[9] == pytest.approx(rows[11], abs=0.05 * rows[10])  # centred, not half a row off


@pytest.mark.parametrize("library", PEERS)
def test_a_vertical_line_at_a_column_centre_lights_that_column_most(library):
    image = PEERS[library]["line"]((7.5, 3.0), (7.5, 20.0), 16, 24)
    assert image.sum(axis=0).argmax() == 7


@pytest.mark.parametrize("library", PEERS)
@pytest.mark.parametrize("kind", ["edge", "disk"])
def test_peer_fills_sit_where_the_shape_is(library, kind):
    # the centroid of the coverage is the shape's: a half-pixel or y-flip slip would move it
    centre = (13.3, 9.7)
    if kind == "edge":
        shape = ([(8.3, 4.7), (18.3, 4.7), (18.3, 14.7), (8.3, 14.7)],)
    else:
        shape = (centre, 4.6)
    image = PEERS[library][kind](*shape, 32, 24)
    ys, xs = np.mgrid[0:24, 0:32] + 0.5
    total = image.sum()
    assert (image * xs).sum() / total == pytest.approx(centre[0], abs=0.1)
    # OpenCV's fillPoly LINE_AA fills its LINE_8 pixels (centres up to 1/2 px outside, rounded per
    # scanline) and blends the AA outline over them: measured 0.17 px low here, while its outline
    # alone is centred on the edges to 0.02 px; a y-flip slip would be 0.5 px or more
    tolerance = 0.2 if (library, kind) == ("OpenCV LINE_AA", "edge") else 0.1
    assert (image * ys).sum() / total == pytest.approx(centre[1], abs=tolerance)


LINE_TOTALS = {
    # found by this bench: skia draws a width-1 stroke as an anti-aliased hairline, whose total is
    # the major-axis extent (as Wu's), not the band's area
    "skia": lambda p0, p1: pytest.approx(abs(p1[0] - p0[0]), rel=0.01),
    # OpenCV's LINE_AA line spreads over about 1.3 px and runs past the ends
    "OpenCV LINE_AA": lambda p0, p1: pytest.approx(1.33 * math.dist(p0, p1), rel=0.05),
}


@pytest.mark.parametrize("library", PEERS)
def test_peer_line_totals(library):
    p0, p1 = (5.3, 10.2), (40.7, 27.9)
    assert PEERS[library]["line"](p0, p1, 64, 32).sum() == LINE_TOTALS[library](p0, p1)
    assert exact_band_line(p0, p1, 64, 32).sum() == pytest.approx(math.dist(p0, p1))


# ---------------------------------------------------------------- the disk reference


def test_disk_coverage_is_the_closed_form_area():
    rng = np.random.default_rng(3)
    for _ in range(6):
        centre, radius = rng.uniform(8, 12, 2), float(rng.uniform(0.3, 7))
        mine = disk_coverage(centre, radius, 20, 20)
        assert np.allclose(mine, oracle_disk_coverage(*centre, radius, 20, 20), rtol=0, atol=1e-12)
        assert mine.sum() == pytest.approx(math.pi * radius**2, abs=1e-9)
    assert disk_coverage((3, 3), 0.0, 4, 4).sum() == 0


def test_the_cli_runs_it_and_refuses_other_suites_options(capsys):
    assert main(["bench", "antialias", "--quick"]) == 0
    assert "DISLOP_L" in capsys.readouterr().out
    assert main(["bench", "antialias", "--quick", "--repeat", "3"]) == 2

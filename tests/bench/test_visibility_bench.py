"""`python -m scanviz bench visibility`: its scenes, its oracle of unique nearest surfaces, its fit, its budget.

Oracles: `tests.visibility.support.unique_nearest` (every polygon drawn
alone: the package's grouped version must equal it), exact power laws for
the growth fit, shoelace areas for the scene generator, and a deliberately
slow algorithm registered for one test to exercise the budget.
"""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.bench import visibility as bench
from scanviz.cli import main
from scanviz.conventions import SAMPLE_MODES
from scanviz.visibility import ALGORITHMS, Decision, ScreenPolygons, Visibility
from tests.visibility import support

EXAMPLES = max(settings.default.max_examples // 5, 1)


@settings(max_examples=EXAMPLES)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(0, 9),
    interpenetrating=st.booleans(),
    sample=st.sampled_from(SAMPLE_MODES),
    bits=st.sampled_from([8, 0, None]),
)
def test_unique_nearest_is_the_one_of_each_polygon_drawn_alone(seed, n, interpenetrating, sample, bits):  # fmt: skip
    polygons = support.random_scene(np.random.default_rng(seed), n, 20, interpenetrating)
    options = {"sample": sample, "subpixel_bits": bits}
    expected = support.unique_nearest(polygons, 20, 16, **options)
    assert np.array_equal(bench.unique_nearest(polygons, 20, 16, **options), expected)


def test_unique_nearest_sees_ties_of_coplanar_and_crossing_polygons():
    polygons = ScreenPolygons.from_polygons(
        [
            [(0, 0, 0.5), (16, 0, 0.5), (16, 16, 0.5), (0, 16, 0.5)],
            [(4, 4, 0.5), (12, 4, 0.5), (12, 12, 0.5), (4, 12, 0.5)],  # coplanar over 8x8
            [(0, 0, 0.2), (16, 0, 0.8), (0, 16, 0.2)],  # crosses z = 0.5 at x = 8
        ]
    )
    unique = bench.unique_nearest(polygons, 16, 16)
    assert np.array_equal(unique, support.unique_nearest(polygons, 16, 16))
    assert not unique[6, 10] and unique[2, 2] and unique[14, 14]
    assert unique[5, 8] == support.unique_nearest(polygons, 16, 16, tol=0.0)[5, 8]


@pytest.mark.parametrize("count", [1, 10, 300])
def test_disjoint_groups_partition_the_polygons_into_non_overlapping_boxes(count):
    polygons = bench.random_triangles(count, 64, 48)
    groups = bench.disjoint_groups(polygons, 64, 48)
    assert sorted(p for g in groups for p in g) == list(range(count))
    xy = polygons.xy.reshape(-1, 3, 2)
    for group in groups:
        boxes = [(xy[p].min(axis=0), xy[p].max(axis=0)) for p in group]
        for i, (low_i, high_i) in enumerate(boxes):
            for low_j, high_j in boxes[i + 1 :]:
                inside = (np.maximum(low_i, low_j) <= np.minimum(high_i, high_j)).all()
                on_raster = (np.maximum(low_i, low_j) < (64, 48)).all()
                on_raster &= (np.minimum(high_i, high_j) >= 0).all()
                assert not (inside and on_raster)


def test_random_triangles_are_seeded_and_have_the_stated_area_and_slopes():
    a, b = bench.random_triangles(2000, 256, 128), bench.random_triangles(2000, 256, 128)
    assert np.array_equal(a.xy, b.xy) and np.array_equal(a.z, b.z)
    assert not np.array_equal(a.xy, bench.random_triangles(2000, 256, 128, seed=1).xy)
    xy = a.xy.reshape(-1, 3, 2)
    (x0, y0), (x1, y1), (x2, y2) = xy[:, 0].T, xy[:, 1].T, xy[:, 2].T
    area = np.abs((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)).sum() / 2
    assert abs(area / (256 * 128) - bench.DEPTH_COMPLEXITY) < 0.1 * bench.DEPTH_COMPLEXITY
    z = a.z.reshape(-1, 3)
    assert (np.ptp(z, axis=1) <= bench.DEPTH_SPREAD).all() and a.value_count == 0


def test_growth_exponent_fits_a_power_law_over_the_runs_that_count():
    counts = [10, 100, 1000, 10000]
    assert bench.growth_exponent(counts, [3e-3 * (n / 10) ** 1.5 for n in counts])[0] == pytest.approx(1.5)  # fmt: skip
    k, low, high = bench.growth_exponent(counts, [5e-4, 5e-4, 2e-3, 2e-1])  # 10, 100: overhead
    assert (low, high) == (1000, 10000) and k == pytest.approx(2.0)
    assert bench.growth_exponent(counts, [1e-4, 2e-4, 5e-4, 2e-3]) is None


def test_predicted_seconds_extrapolates_the_last_growth():
    assert bench.predicted_seconds([], 1000) == 0.0
    assert bench.predicted_seconds([(10, 1e-3)], 100) == pytest.approx(0.1)  # one size: n^2
    history = [(10, 1e-3), (100, 1e-2), (1000, 1.0)]  # n^2 from 100 to 1,000
    assert bench.predicted_seconds(history, 10000) == pytest.approx(100.0)
    assert bench.predicted_seconds([(100, 1.0), (1000, 0.5)], 10000) == pytest.approx(
        5.0
    )  # at least n^1


def test_agreement_counts_covered_samples():
    reference = np.array([[0, 0, 1, -1]])
    polygon = np.array([[0, 1, 1, -1]])
    unique = np.array([[True, False, True, True]])
    assert bench.agreement(polygon, reference, unique) == (2 / 3, 2 / 3, 1.0)
    assert bench.agreement(np.full((1, 4), -1), np.full((1, 4), -1), unique) == (0.0, 0.0, 0.0)


class Clock:
    """A fake `perf_counter`: each reading takes 1 us, and the slow algorithm its declared time."""

    now = 0.0

    def __call__(self) -> float:
        self.now += 1e-6
        return self.now


CLOCK = Clock()


@dataclass(frozen=True)
class Slow(Visibility):
    """The painter's order, taking 1e-5 n^2 seconds of the fake clock (10 s at 1,000)."""

    name: ClassVar[str] = "slow_for_test"

    def decide(self, surfaces, tracer):
        CLOCK.now += 1e-5 * surfaces.count**2
        pieces = sorted(surfaces.pieces(), key=lambda piece: -piece.zmin)
        return Decision(None, tuple(pieces), "over")


def test_an_algorithm_over_budget_is_reported_not_run(monkeypatch, capsys):
    monkeypatch.setitem(ALGORITHMS, Slow.name, Slow)
    monkeypatch.setattr(bench, "perf_counter", CLOCK)
    rows = bench.run_visibility(
        sizes=(10, 100, 1000), width=16, height=16, repeat=2, algorithms=(Slow.name,), budget=2.0
    )
    out = capsys.readouterr().out
    slow = {(r["scene"], r["polygons"]): r for r in rows if r["algorithm"] == Slow.name}
    assert (
        slow["random", 100]["ms"] == pytest.approx(100.0, rel=1e-3)
        and slow["random", 100]["runs"] == 2
    )
    assert slow["random", 100]["agree_unique"] == 1.0
    # From 10 to 100 the time grew as n^2: 1,000 would take 10 s, over the 2 s budget.
    assert slow["random", 1000]["over_budget"]
    assert slow["random", 1000]["predicted_s"] == pytest.approx(10.0, rel=1e-3)
    assert all(r["over_budget"] for (scene, _), r in slow.items() if scene != "random")
    assert "over budget (predicted 9.99 s per run, 0.202 s spent)" in out  # 1 us per reading
    assert "over budget from 1,000 polygons" in out
    assert f"{Slow.name} k = 2.00  (10..100 polygons)" in out
    assert all(not r["over_budget"] for r in rows if r["algorithm"] == "zbuffer")


def test_cli_bench_visibility_quick_prints_the_table_fit_and_plot(tmp_path, capsys):
    plot = tmp_path / "visibility.png"
    argv = ["bench", "visibility", "--quick", "--sizes", "10,100,400", "--plot", str(plot)]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "visibility benchmark: 64x64" in out and "agree@unique" in out
    for name in ALGORITHMS:
        assert f"\n{name:<11}random" in out and f"\n  {name:<11}k = " in out
    assert "sphere (no cull)" in out
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_bench_sees_the_painters_failures(capsys):
    rows = bench.run_visibility(quick=True, sizes=(10, 300), algorithms=("painter",))
    capsys.readouterr()
    painter = [r for r in rows if r["algorithm"] == "painter"]
    assert min(r["agree_unique"] for r in painter) < 1.0  # random triangles interpenetrate
    assert all(r["agree_unique"] == 1.0 for r in rows if r["algorithm"] == "zbuffer")


@pytest.mark.parametrize(
    "argv, message",
    [
        (["bench", "visibility", "--algorithms", "nonsense"], "'nonsense' is not one of zbuffer"),
        (["bench", "raster", "--sizes", "10"], "--sizes: options of 'bench visibility' only"),
        (["bench", "visibility", "--sizes", "10,,100"], "integers >= 1 separated by commas"),
        (["bench", "visibility", "--sizes", "0"], "must be >= 1"),
        (["bench", "visibility", "--budget", "0"], "seconds > 0"),
        (["bench", "visibility", "--width", "0"], "must be >= 1"),
    ],
)
def test_cli_bench_visibility_refuses_bad_options_in_one_line(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and message in err, err


def test_the_bench_counts_holes_and_depths_beyond_the_promise(capsys):
    rows = bench.run_visibility(quick=True, sizes=(10, 100), algorithms=("bsp", "depth_sort"))
    out = capsys.readouterr().out
    assert "holes" in out and ">slack" in out
    for row in rows:
        assert row["holes"] == 0 and row["beyond_slack"] == 0, row
    painter = bench.run_visibility(quick=True, sizes=(10,), algorithms=("painter",))
    capsys.readouterr()
    assert [r["beyond_slack"] for r in painter if r["algorithm"] == "painter"] == [None, None]


def test_bench_compare_refuses_a_device_in_one_line(capsys):
    from scanviz.cli import main

    assert main(["bench", "compare", "/dev/zero", "/dev/zero"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        "python -m scanviz bench: error: '/dev/zero' is a character device, not a regular file; "
        "only regular files are read"
    ]

"""Issue 27: the fuzz campaign's category "time and memory against size", and the CLI's lines."""

import time
from pathlib import Path

import numpy as np
import pytest

from scanviz.conformance import checks, fuzz

SCALING = "time and memory against size"
MEASURES_MEMORY = Path("/proc/self/clear_refs").exists()


def run_cases(monkeypatch, **cases):
    """Run the scaling category on `cases` (name -> ScalingCase) alone."""
    monkeypatch.setattr(checks, "scaling_cases", lambda: cases)
    entry = fuzz.ENTRY_POINTS[SCALING]
    monkeypatch.setitem(
        fuzz.ENTRY_POINTS,
        SCALING,
        fuzz.EntryPoint(
            entry.strategy, entry.call, files=True, inputs=lambda: [{"case": n} for n in cases]
        ),
    )
    return fuzz.run_entry(SCALING, 1, seed=0)


def test_issue27_a_quadratic_entry_point_is_too_slow(monkeypatch):
    monkeypatch.setattr(checks, "BASE_SECONDS", 0.05)
    counts = run_cases(
        monkeypatch,
        linear=checks.ScalingCase(lambda n: time.sleep(1e-6 * n), 1_000, "vertices", 1e-4),
        quadratic=checks.ScalingCase(lambda n: time.sleep(1e-6 * n * n), 1_000, "vertices", 1e-4),
    )
    assert (counts.tried, counts.correct, counts.other, counts.slow) == (2, 1, 1, 1)
    assert "too slow: " in counts.cases[0] and "for 1,000 vertices" in counts.cases[0]


def test_issue27_a_refusal_counts_only_within_the_time_bound(monkeypatch):
    def refuses_late(n):
        time.sleep(0.3)
        raise ValueError(f"'polygon' of {n} vertices is over the budget")

    counts = run_cases(
        monkeypatch, late=checks.ScalingCase(refuses_late, 10, "vertices", 0.0, warm=0)
    )
    assert counts.slow == 0 and counts.clear == 1  # BASE_SECONDS covers it
    monkeypatch.setattr(checks, "BASE_SECONDS", 0.1)
    counts = run_cases(
        monkeypatch, late=checks.ScalingCase(refuses_late, 10, "vertices", 0.0, warm=0)
    )
    assert counts.slow == 1 and counts.clear == 0


@pytest.mark.skipif(not MEASURES_MEMORY, reason="peak memory is read from /proc (Linux)")
def test_issue27_an_unestimated_allocation_is_over_memory(monkeypatch):
    def allocates(n):
        return np.ones(n * 2**20 // 8).sum()  # n MiB, touched, never estimated

    counts = run_cases(
        monkeypatch,
        small=checks.ScalingCase(allocates, 8, "MiB", 0.01),
        large=checks.ScalingCase(allocates, 400, "MiB", 0.01),  # the limit is 64M
    )
    assert (counts.correct, counts.other, counts.memory) == (1, 1, 1)
    assert "over memory: the peak rose by" in counts.cases[0]


def test_issue27_an_answer_to_a_request_over_the_limit_is_a_failure(monkeypatch):
    counts = run_cases(
        monkeypatch, answers=checks.ScalingCase(lambda n: n, 8192, "pixels", 0.0, refuses=True)
    )
    assert counts.other == 1 and "answered a request over the memory limit" in counts.cases[0]


def test_issue27_the_table_counts_too_slow_and_over_memory():
    results = {"a": fuzz.Counts(3, 1, 0, 2, 1, 1, ["a: x -> too slow: 9 s", "a: y -> over memory"])}
    header, row, total, *cases = fuzz.format_table(results)
    assert header.split()[-4:] == ["too", "slow", "over", "memory"]
    assert (
        row.split()[1:] == ["3", "1", "0", "2", "1", "1"] and total.split()[1:] == row.split()[1:]
    )
    assert cases == ["  a: x -> too slow: 9 s", "  a: y -> over memory"]


def test_issue27_every_scaling_case_has_a_bound_and_a_warm_up():
    cases = checks.scaling_cases()
    assert len(cases) >= 20 and all(c.seconds >= checks.BASE_SECONDS for c in cases.values())
    assert {c.refuses for c in cases.values()} == {True, False}
    for name in cases:  # every visibility algorithm gets many polygons
        assert len(name) <= 60


@pytest.mark.parametrize(
    "argv",
    [
        ["render", "OUT/huge.obj"],  # numpy's RuntimeWarning, then the error
        ["render", "builtin:" + "a" * 5000],
        ["trace", "--vertices", "0,0 4,0 0,4 " + "1,1,1 " * 1000],
        ["render", "OUT/scene.json", "--visibility", "x" * 5000],
    ],
)
def test_issue27_the_cli_check_sees_what_a_user_sees(argv):
    with pytest.raises(ValueError) as error:  # exit 2: one line, judged by the clear-error rule
        assert checks.check_cli({"argv": argv}) == ""
    assert len(str(error.value)) < checks.MAX_CLI_LINE

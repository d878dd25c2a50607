"""The fuzz campaign's bounded budget (``make test``) and its ability to find failures."""

import signal

import pytest

from scanviz.conformance import checks, fuzz
from scanviz.conformance.classify import clear_error

BUDGET = 300  # inputs across all entry points, a few seconds


def _examples(name: str) -> int:
    shares = sum(e.share for e in fuzz.ENTRY_POINTS.values())
    return max(1, round(BUDGET * fuzz.ENTRY_POINTS[name].share / shares))


@pytest.mark.parametrize("name", list(fuzz.ENTRY_POINTS))
def test_every_fuzzed_input_gives_a_correct_result_or_a_clear_error(name):
    counts = fuzz.run_entry(name, _examples(name), seed=0)
    assert counts.tried > 0
    assert counts.other == 0, "\n".join(counts.cases[: fuzz.MAX_REPORTED])


def test_a_wrong_mask_is_anything_else(monkeypatch):
    real = checks.scan_convert

    def flips_a_sample(*args, **kwargs):
        result = real(*args, **kwargs)
        if result.mask.size:
            result.mask[0, 0] = not result.mask[0, 0]
        return result

    monkeypatch.setattr(checks, "scan_convert", flips_a_sample)
    counts = fuzz.run_entry("scan_convert (valid, oracle)", 30, seed=0)
    assert counts.other > 0
    assert "mask differs from the exact oracle" in counts.cases[0]


@pytest.mark.skipif(not hasattr(signal, "setitimer"), reason="the time budget needs SIGALRM")
def test_a_hang_is_anything_else(monkeypatch):
    def hangs(args):
        while True:
            pass

    monkeypatch.setattr(fuzz, "CALL_SECONDS", 0.2)
    monkeypatch.setitem(
        fuzz.ENTRY_POINTS, "Polygon", fuzz.EntryPoint(fuzz.ENTRY_POINTS["Polygon"].strategy, hangs)
    )
    counts = fuzz.run_entry("Polygon", 2, seed=0)
    assert counts.other == 2 and "over the 0.2 s budget" in counts.cases[0]


def test_an_allocation_beyond_the_limit_is_anything_else(monkeypatch):
    pytest.importorskip("resource", reason="the address-space cap needs resource (POSIX)")

    def allocates(args):
        return bytearray(8 * 2**30)  # far over the memory limit and the address-space cap

    monkeypatch.setitem(
        fuzz.ENTRY_POINTS,
        "Polygon",
        fuzz.EntryPoint(fuzz.ENTRY_POINTS["Polygon"].strategy, allocates),
    )
    counts = fuzz.run_entry("Polygon", 1, seed=0)
    assert counts.other == 1 and "MemoryError" in counts.cases[0]


@pytest.mark.parametrize(
    "error, files, clear",
    [
        (ValueError("'width' must be in 0..65536; got -1"), False, True),
        (ValueError("objects[0].material.exponent must be >= 0; got -0.18"), False, True),
        (TypeError("contour 0 must be an (N, 2) array of numbers"), False, True),
        (FileNotFoundError(2, "No such file or directory"), True, True),
        (FileNotFoundError(2, "No such file or directory"), False, False),
        (ValueError("need at least one array to concatenate"), False, False),
        (
            ValueError("zero-size array to reduction operation maximum which has no identity"),
            False,
            False,
        ),
        (KeyError("QQQ"), False, False),
        (RecursionError("maximum recursion depth exceeded"), False, False),
        (ValueError("'width' must be an int\nsecond line"), False, False),
        (ValueError("'clip_points' row 0 is not finite"), False, False),
        (TypeError("ambient must be an array; got a number"), False, True),
        (ValueError("could not convert string to float: 'abc'"), False, False),
        (TypeError("'triangle' must be a (3, 2) array: could not convert string"), False, True),
    ],
)
def test_the_clear_error_rule(error, files, clear):
    assert clear_error(error, files=files) is clear


def test_midpoint_line_check_finds_a_wrong_pixel():
    import numpy as np

    xs, ys = checks.midpoint_line(0, 0, 5, 2)
    assert checks.check_line_pixels(0, 0, 5, 2, xs, ys) == ""
    ys = ys.copy()
    ys[2] += 1
    assert "not the nearest" in checks.check_line_pixels(0, 0, 5, 2, xs, np.asarray(ys))

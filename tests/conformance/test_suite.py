"""The conformance suite: every category passes, and a broken implementation makes one fail."""

import numpy as np
import pytest

import scanviz.conformance as conformance
from scanviz.catalog import SHAPES
from scanviz.conformance import exact, suite
from scanviz.raster import scan_compiled
from tests import oracle


@pytest.mark.parametrize("name", list(suite.CATEGORIES))
def test_category_passes(name):
    outcome = suite.run_category(name, seed=0)
    assert outcome.passed, f"{name}: {outcome.failure}"


def test_a_kernel_that_drops_a_sample_fails_watertight_fans(monkeypatch):
    compiled = scan_compiled.rasterize_triangles

    def drops_one_sample(*args):
        counts = compiled(*args).copy()
        covered = np.argwhere(counts > 0)
        if len(covered):
            counts[tuple(covered[len(covered) // 2])] -= 1
        return counts

    monkeypatch.setattr(scan_compiled, "rasterize_triangles", drops_one_sample)
    outcome = suite.run_category("watertight fans", seed=0)
    assert not outcome.passed
    assert outcome.failure.startswith("rasterize_triangles sample=corner fan of")


def test_a_kernel_that_owns_the_right_edge_fails_the_fill_convention(monkeypatch):
    compiled = scan_compiled.paint_mask

    def paints_one_more(spans, width, height):
        wider = spans.copy()
        wider[:, 2] = np.minimum(wider[:, 2] + 1, width)
        return compiled(wider, width, height)

    monkeypatch.setattr(scan_compiled, "paint_mask", paints_one_more)
    outcome = suite.run_category("fill convention", seed=0)
    assert not outcome.passed and "scan_convert" in outcome.failure


def test_a_category_that_raises_fails_with_the_exception_on_one_line(monkeypatch):
    def broken(rng):
        raise ZeroDivisionError("division by zero\nsecond line")

    monkeypatch.setitem(suite.CATEGORIES, "watertight fans", broken)
    outcome = suite.run_category("watertight fans")
    assert not outcome.passed
    assert outcome.failure == "raised ZeroDivisionError: division by zero second line"


def test_main_exits_1_when_a_category_fails_and_prints_one_line_each(monkeypatch, capsys):
    monkeypatch.setattr(
        suite,
        "CATEGORIES",
        {
            "passes": lambda rng: suite.Outcome(True, "3 cases"),
            "fails": lambda rng: suite.Outcome(False, "2 cases", "case 1 is wrong"),
        },
    )
    assert conformance.main() == 1
    lines = capsys.readouterr().out.splitlines()
    column = len("PASS  ") + suite.NAME_WIDTH + 2  # the counts line up after the longest name
    assert lines[0] == "PASS  passes".ljust(column) + "3 cases"
    assert lines[1] == "FAIL  fails".ljust(column) + "2 cases; first failure: case 1 is wrong"
    assert lines[2].startswith("conformance: 1 passed, 1 failed in ")
    assert len(lines) == 3


def test_main_exits_0_when_all_pass(monkeypatch, capsys):
    monkeypatch.setattr(suite, "CATEGORIES", {"passes": lambda rng: suite.Outcome(True, "1 case")})
    assert conformance.main() == 0


def test_main_says_when_hypothesis_is_missing(monkeypatch, capsys):
    monkeypatch.setattr(suite, "CATEGORIES", {})
    monkeypatch.setitem(__import__("sys").modules, "scanviz.conformance.fuzz", None)
    assert conformance.main(fuzz=10) == 1
    assert "pip install hypothesis" in capsys.readouterr().out


def test_categories_are_deterministic_for_a_seed():
    first = suite.run_category("watertight fans", seed=3)
    assert first == suite.run_category("watertight fans", seed=3)
    assert first.counts != suite.run_category("watertight fans", seed=4).counts


@pytest.mark.parametrize("sample", ["corner", "center"])
@pytest.mark.parametrize("bits", [8, None, 0])
def test_the_suite_oracle_agrees_with_the_tests_oracle(sample, bits):
    # Two oracles written apart: the suite's lattice rule and tests/oracle.py's row rule.
    for shape in SHAPES.values():
        contours = [c.tolist() for c in shape.polygon.contours]
        mine = exact.sample_winding(
            exact.snap_contours(contours, bits), shape.width, shape.height, sample
        )
        theirs = oracle.winding_image(shape.polygon, shape.width, shape.height, sample, bits)
        np.testing.assert_array_equal(mine, theirs, err_msg=shape.name)


def test_exact_coverage_of_a_square_with_a_hole():
    outer = [(0, 0), (3, 0), (3, 3), (0, 3)]
    hole = [(1, 1), (1, 2), (2, 2), (2, 1)]
    image = exact.coverage(exact.snap_contours([outer, hole], 8), 3, 3)
    assert image.tolist() == [[1, 1, 1], [1, 0, 1], [1, 1, 1]]
    half = exact.coverage(exact.snap_contours([[(0, 0), (2, 0), (0, 2)]], 8), 2, 2)
    assert [[str(v) for v in row] for row in half] == [["1", "1/2"], ["1/2", "0"]]

"""The conformance category of DISLOP passes, and fails on each way of getting an area wrong."""

import numpy as np

from scanviz.antialias import circle, line, tables
from scanviz.conformance import antialias_checks, suite

NAME = "DISLOP vs exact area"


def _outcome():
    return antialias_checks.dislop_vs_exact_area(np.random.default_rng(0))


def _line_kernel(monkeypatch, change):
    """Replace dislop_line's compiled kernel by `change(kernel, *args)`."""
    kernel = line._line_kernel
    monkeypatch.setattr(line, "_line_kernel", lambda *args: change(kernel, *args))


def test_it_is_the_eighteenth_category_and_passes():
    assert list(suite.CATEGORIES).index(NAME) == 17
    outcome = suite.run_category(NAME, seed=0)
    assert outcome.passed, outcome.failure
    assert outcome.counts.endswith(" pixels / 1528 segments / 120 polygons / 300 disks")


def test_an_exact_mode_that_misses_the_fourth_pixel_is_caught(monkeypatch):
    def printed(kernel, u0, v0, u1, v1, steep, flip, exact, image):
        kernel(u0, v0, u1, v1, steep, flip, False, image)

    _line_kernel(monkeypatch, printed)
    outcome = _outcome()
    assert not outcome.passed and outcome.failure.startswith("dislop_line exact=True, ")


def test_a_bias_below_the_area_tolerance_in_one_octant_breaks_the_symmetry(monkeypatch):
    def biased(kernel, u0, v0, u1, v1, steep, flip, exact, image):
        shift = 1e-10 if flip else 0.0  # 1e-10 of a pixel: within the 1e-9 of the area checks
        kernel(u0, v0 + shift, u1, v1 + shift, steep, flip, exact, image)

    _line_kernel(monkeypatch, biased)
    outcome = _outcome()
    assert not outcome.passed and outcome.failure.startswith("dislop_line exact=True of ")
    assert " reflected (transpose=" in outcome.failure


def test_a_line_that_loses_intensity_per_unit_length_is_caught(monkeypatch):
    def dimmer(kernel, *args):
        kernel(*args)
        image = args[-1]
        image *= 1 - 1e-10  # each pixel within the area tolerance, a long line's total not

    _line_kernel(monkeypatch, dimmer)
    outcome = _outcome()
    assert not outcome.passed and "total" in outcome.failure and "length" in outcome.failure


def test_a_post_table_read_one_distance_step_off_is_caught(monkeypatch):
    table = tables.line_table()
    monkeypatch.setattr(tables, "line_table", lambda: np.roll(table, 1, axis=1))
    outcome = _outcome()
    assert not outcome.passed and outcome.failure.startswith("post_antialias vs dislop_line, ")


def test_edge_areas_on_the_wrong_side_are_caught(monkeypatch):
    # Wrapped where the category calls it: edge.py's walk has a compiled and a traced copy.
    dislop_edge = antialias_checks.dislop_edge

    def wrong_side(polygon, width, height):
        image = dislop_edge(polygon, width, height)
        cut = (image > 0) & (image < 1)
        image[cut] = 1 - image[cut]
        return image

    monkeypatch.setattr(antialias_checks, "dislop_edge", wrong_side)
    outcome = _outcome()
    assert not outcome.passed and outcome.failure.startswith("dislop_edge of ")


def test_a_disk_one_percent_too_small_is_caught(monkeypatch):
    kernel = circle._round_kernel
    monkeypatch.setattr(
        circle,
        "_round_kernel",
        lambda cx, cy, r, ring, image: kernel(cx, cy, 0.99 * r, ring, image),
    )
    outcome = _outcome()
    assert not outcome.passed and outcome.failure.startswith("dislop_disk(")
    assert "total - pi R^2" in outcome.failure

"""The DISLOP_L stepper and the anti-aliasing figures, headless: built from real runs, checked against them."""

import math
import re

import matplotlib
import numpy as np
import pytest

from scanviz.antialias import dislop_line
from scanviz.antialias.columns import LINE_BRANCHES, line_column
from scanviz.antialias.compare import intensity_per_length
from scanviz.antialias.peers import (
    exact_band_line,
    gupta_sproull_line,
    supersampled_line,
    wu_line,
)
from scanviz.antialias.tables import degree_slope, periodic_table
from scanviz.raster import midpoint_line
from scanviz.widgets import DislopView, dislop_stepper
from scanviz.widgets._common import fmt
from scanviz.widgets.antialias import (
    DIGITS,
    ROLES,
    plot_coverage_comparison,
    plot_period_table,
    plot_post_antialias,
    plot_ropiness,
)

matplotlib.use("Agg")

W, H = 17, 14
STEEP_ISH = ((2.3, 1.6), (14.1, 11.7))  # slope 0.856 > 0.75: the printed formula is inexact
LINES = {
    "rising": STEEP_ISH,
    "gentle": ((0.7, 2.6), (15.3, 7.1)),
    "steep": ((3.2, 0.6), (8.9, 13.3)),
    "falling": ((1.4, 12.2), (15.8, 3.9)),
    "steep falling": ((5.3, 13.1), (12.6, 0.8)),
    "horizontal": ((1.5, 6.3), (14.5, 6.3)),
    "off the edge": ((-4.2, -1.3), (9.6, 20.4)),
}
AREA = {"upper": "up", "middle": "mid", "lower": "low", "spill": "spill"}


def areas(event):
    return [getattr(event, AREA[role]) for role in ROLES]


@pytest.mark.parametrize("exact", [False, True], ids=["printed", "exact"])
@pytest.mark.parametrize("name", list(LINES))
def test_the_last_step_shows_dislop_lines_image(name, exact):
    p0, p1 = LINES[name]
    stepper = dislop_stepper(p0, p1, W, H, exact=exact)
    view = stepper.views[0]
    assert isinstance(view, DislopView) and stepper.slider.max == len(view.steps) > 5
    stepper.slider.value = stepper.slider.max
    compiled = dislop_line(p0, p1, W, H, exact=exact)
    np.testing.assert_array_equal(view.coverage.get_array(), compiled)
    stepper.slider.value = 0
    assert (view.coverage.get_array() == 0).all() and not view.pixel_patch.get_visible()


def test_each_step_shows_its_column_and_its_values():
    stepper = dislop_stepper(*STEEP_ISH, W, H)
    view = stepper.views[0]
    done = np.zeros((H, W), bool)
    for step, column in enumerate(view.steps, 1):
        stepper.slider.value = step
        text = view.text.value
        assert view.pixel_patch.get_visible() and view.pixel_patch.get_xy() == (column.x, column.y)
        assert view.column_patch.get_x() == column.x and view.column_patch.get_width() == 1
        assert f"<b>column {step} of {len(view.steps)}</b>" in text
        assert f"middle pixel ({column.x}, {column.y})" in text
        for value in (column.slope, column.dxy, column.fcv, column.scv, *areas(column)):
            assert fmt(value, DIGITS) in text
        assert f"<b>{column.branch}</b>" in text
        labels = {role: view.labels[role] for role in ROLES}
        rising = {"upper": 1, "middle": 0, "lower": -1, "spill": 2 if column.dxy > 0 else -2}
        for role, area in zip(ROLES, areas(column), strict=True):  # a rising x-major line: y up
            assert labels[role].get_position() == (column.x + 0.5, column.y + rising[role] + 0.5)
            shown = labels[role].get_text().split("\n")[0]  # 9 pt: two decimals, as ".87"
            assert abs(float(shown) - (area if role != "spill" else 0.0)) <= 0.005
        done[:, column.x] = True
        shown = view.coverage.get_array()
        assert (shown[~done] == 0).all()  # only the columns done are drawn
        for role, area in zip(ROLES, areas(column), strict=True):
            x, y = view._pixels(column)[role]
            assert not 0 <= y < H or shown[y, x] == area  # the current column is drawn too


def test_the_interval_of_dxy_names_the_branch_the_core_took():
    for p0, p1 in LINES.values():
        for exact in (False, True):
            stepper = dislop_stepper(p0, p1, W, H, exact=exact)
            view = stepper.views[0]
            for step, column in enumerate(view.steps, 1):
                stepper.slider.value = step
                branch = LINE_BRANCHES[line_column(column.slope, column.dxy)[5]]
                assert f"&rarr; <b>{branch}</b>" in view.text.value
                if column.branch not in ("cap", "exact"):
                    assert branch == column.branch


def test_the_sum_of_a_middle_column_is_sec_a_and_a_cap_holds_less():
    stepper = dislop_stepper(*LINES["gentle"], W, H)
    view = stepper.views[0]
    m = view.steps[0].slope
    sec_a = math.sqrt(1 + m * m)
    branches = {c.branch for c in view.steps}
    assert "cap" in branches and branches - {"cap"}
    for step, column in enumerate(view.steps, 1):
        stepper.slider.value = step
        total = sum(areas(column))
        if column.branch == "cap":
            assert total < sec_a - 1e-3 or math.isclose(total, sec_a, abs_tol=1e-12)
            assert "an end column holds only the part of the band" in view.text.value
        else:
            assert math.isclose(total, sec_a, rel_tol=1e-14)
            assert f"= sec a = Ta = {fmt(sec_a, DIGITS)}" in view.text.value
            assert "the printed formula is exact here" in view.text.value  # m = 0.31
            assert "formula − exact" not in view.text.value


def test_a_steep_ish_printed_line_shows_the_exact_areas_and_the_difference():
    stepper = dislop_stepper(*STEEP_ISH, W, H)
    view = stepper.views[0]
    truth = exact_band_line(*STEEP_ISH, W, H)  # the exact area, by area_coverage: independent
    assert view.steps[0].slope > 0.75 and len(view.exact_steps) == len(view.steps)
    seen_spill = 0.0
    for step, (column, exact) in enumerate(zip(view.steps, view.exact_steps, strict=True), 1):
        stepper.slider.value = step
        text = view.text.value
        assert "formula − exact" in text and (exact.x, exact.y) == (column.x, column.y)
        for role, area, true_area in zip(ROLES, areas(column), areas(exact), strict=True):
            x, y = view._pixels(column)[role]
            assert not 0 <= y < H or true_area == pytest.approx(truth[y, x], abs=1e-12)
            assert fmt(true_area, DIGITS) in text
            assert fmt(area - true_area, DIGITS) in text
        if column.branch != "cap":
            worst = max(abs(a - e) for a, e in zip(areas(column), areas(exact), strict=True))
            assert f"off by up to {fmt(worst, DIGITS)} of a pixel" in text
            seen_spill = max(seen_spill, exact.spill)
            assert column.spill == 0.0 and view.labels["spill"].get_visible()
            first, second = view.labels["spill"].get_text().split("\n")
            assert first == "0" and second.startswith("(ex ") and second.endswith(")")
            assert abs(float(second[4:-1]) - exact.spill) <= 0.005
    assert seen_spill > 1e-4  # the line does reach a fourth pixel somewhere


def test_an_exact_run_compares_with_nothing_and_shows_its_fourth_pixel():
    stepper = dislop_stepper(*STEEP_ISH, W, H, exact=True)
    view = stepper.views[0]
    assert view.exact_steps is None
    spills = [k for k, c in enumerate(view.steps, 1) if c.branch == "exact" and c.spill > 0]
    stepper.slider.value = spills[0]
    text = view.text.value
    assert (
        "<b>exact</b>: the exact band area in five rows" in text and "formula − exact" not in text
    )
    assert view.labels["spill"].get_visible()


@pytest.mark.parametrize(
    ("name", "upper", "lower"),
    [("steep", "right", "left"), ("falling", "below", "above"), ("steep falling", "left", "right")],
)
def test_the_roles_are_placed_on_the_raster_in_every_octant(name, upper, lower):
    stepper = dislop_stepper(*LINES[name], W, H)
    view = stepper.views[0]
    step = len(view.steps) // 2
    stepper.slider.value = step
    column = view.steps[step - 1]
    assert f"upper ({upper})" in view.text.value and f"lower ({lower})" in view.text.value
    image = dislop_line(*LINES[name], W, H)
    for role, area in zip(ROLES, areas(column), strict=True):
        x, y = view._pixels(column)[role]
        assert image[y, x] == area
    if view.steep:
        assert view.column_patch.get_y() == column.y and view.column_patch.get_height() == 1


def test_first_and_last_step_controls_and_text():
    stepper = dislop_stepper(*STEEP_ISH, W, H)
    view, count = stepper.views[0], len(stepper.views[0].steps)
    assert stepper.prev_button.disabled and not stepper.next_button.disabled
    assert stepper.label.value == f"step 0 / {count}: start"
    assert f"start: {count} columns to walk" in view.text.value
    stepper.next_button.click()
    assert view.step == 1 and view.steps[0].branch == "cap" and "<b>cap</b>" in view.text.value
    stepper.slider.value = count
    assert stepper.next_button.disabled and not stepper.prev_button.disabled
    assert stepper.label.value == f"step {count} / {count}: dislop_column"
    assert f"<b>column {count} of {count}</b>" in view.text.value
    stepper.prev_button.click()
    assert view.step == count - 1


def test_columns_wholly_off_the_raster_are_not_steps():
    p0, p1 = LINES["off the edge"]
    _, trace = dislop_line(p0, p1, W, H, trace=True)
    view = dislop_stepper(p0, p1, W, H).views[0]
    assert 0 < len(view.steps) < len(trace)
    assert f"({len(trace) - len(view.steps)} more lie wholly off the raster)" in view.text.value


@pytest.mark.parametrize(
    ("p0", "p1", "size"),
    [
        ((4.2, 3.1), (4.2, 3.1), (10, 8)),
        ((30.0, 2.0), (40.0, 5.0), (10, 8)),
        ((1.0, 50.0), (9.0, 52.0), (10, 8)),
        ((-9.0, -20.0), (-3.0, -2.0), (10, 8)),
        ((1.0, 1.0), (6.0, 3.0), (0, 0)),
        ((1.0, 1.0), (6.0, 3.0), (0, 10)),
    ],
    ids=["zero length", "right of the raster", "above the raster", "below left", "0x0", "0x10"],
)
def test_a_line_with_nothing_on_the_raster_says_nothing_to_step(p0, p1, size):
    stepper = dislop_stepper(p0, p1, *size)
    view = stepper.views[0]
    assert len(view.steps) == 0 and stepper.slider.max == 0
    assert stepper.next_button.disabled and stepper.prev_button.disabled
    assert "nothing to step" in view.text.value
    assert (view.coverage.get_array() == 0).all()


BAD = [
    ({"p0": (1.0, np.nan)}, "p0"),
    ({"p0": (1.0, 2.0, 3.0)}, "p0"),
    ({"p1": "end"}, "p1"),
    ({"p1": (2.0**21, 0.0)}, "p1"),
    ({"width": -1}, "width"),
    ({"height": 2.5}, "height"),
    ({"exact": "yes"}, "exact"),
]


@pytest.mark.parametrize(("bad", "name"), BAD, ids=[f"{n}-{i}" for i, (_, n) in enumerate(BAD)])
def test_bad_input_raises_what_dislop_line_raises(bad, name):
    arguments = {"p0": (1.0, 1.0), "p1": (6.0, 3.0), "width": 8, "height": 6, "exact": False, **bad}
    with pytest.raises((TypeError, ValueError)) as expected:
        dislop_line(**arguments)
    assert name in str(expected.value)
    with pytest.raises(expected.type, match=re.escape(str(expected.value))):
        dislop_stepper(**arguments)


# ---------------------------------------------------------------- the comparison


def test_the_comparison_panels_are_each_methods_output_and_its_error():
    p0, p1, w, h = (1.3, 2.2), (17.6, 9.1), 20, 12
    figure = plot_coverage_comparison(p0, p1, w, h)
    xs, ys = midpoint_line(1, 2, 17, 9)
    binary = np.zeros((h, w))
    binary[ys, xs] = 1.0
    exact = exact_band_line(p0, p1, w, h)
    expected = {
        "midpoint (binary)": binary,
        "Wu": wu_line(p0, p1, w, h),
        "Gupta–Sproull": gupta_sproull_line(p0, p1, w, h),
        "supersample 4×4": supersampled_line(p0, p1, w, h, k=4),
        "DISLOP_L": dislop_line(p0, p1, w, h),
        "exact band": exact,
    }
    length = math.dist(p0, p1)
    panels = figure.axes[: 2 * len(expected)]
    for k, (name, image) in enumerate(expected.items()):
        top, bottom = panels[2 * k], panels[2 * k + 1]
        np.testing.assert_array_equal(top.images[0].get_array(), image)
        np.testing.assert_array_equal(bottom.images[0].get_array(), image - exact)
        assert top.get_title() == f"{name}\nI/length = {fmt(image.sum() / length, 4)}"
        assert top.images[0].origin == "lower"
    assert panels[8].get_title() == "DISLOP_L\nI/length = 1"  # the band lies on the raster
    assert panels[2].get_title().startswith("Wu\nI/length = 0.92")  # extent, not length


def test_the_comparison_of_a_zero_length_line_does_not_raise():
    figure = plot_coverage_comparison((3.5, 3.5), (3.5, 3.5), 8, 8)
    assert figure.axes[0].get_title() == "midpoint (binary)\nI/length = –"


def test_the_comparison_raises_what_the_lines_raise():
    with pytest.raises(ValueError, match="'p0'"):
        plot_coverage_comparison((np.inf, 0), (1, 1), 8, 8)
    with pytest.raises((TypeError, ValueError), match="width"):
        plot_coverage_comparison((0, 0), (1, 1), -2, 8)


# ---------------------------------------------------------------- ropiness

ANGLES = np.arange(0.0, 90.1, 2.5)


@pytest.fixture(scope="module")
def ropiness():
    return intensity_per_length(ANGLES, 30, 40, 40)


def test_dislop_is_constant_intensity_over_the_middle_columns(ropiness):
    np.testing.assert_allclose(ropiness["DISLOP_L"], 1.0, rtol=0, atol=1e-9)


def test_wu_is_the_cosine_of_the_angle_to_the_major_axis(ropiness):
    folded = np.radians(np.minimum(ANGLES, 90.0 - ANGLES))
    np.testing.assert_allclose(ropiness["Wu"], np.cos(folded), rtol=0, atol=1e-12)
    assert ropiness["Wu"][ANGLES == 45.0] == pytest.approx(1 / math.sqrt(2), abs=1e-12)


def test_supersampling_is_ropy_and_finer_samples_are_less_so(ropiness):
    spread = {k: np.ptp(ropiness[f"supersample {k}×{k}"]) for k in (2, 4)}
    assert spread[2] > spread[4] > 0.01  # the per-column count jumps with the angle
    assert ropiness["supersample 4×4"][0] == 1.0  # horizontal: every column has 4 of 16 rows x 4


def test_the_ropiness_plot_draws_the_data():
    figure = plot_ropiness(ANGLES[::4], 30, 40, 40)
    data = intensity_per_length(ANGLES[::4], 30, 40, 40)
    lines = {line.get_label(): line for line in figure.axes[0].lines}
    for name, values in data.items():
        np.testing.assert_array_equal(lines[name].get_xdata(), ANGLES[::4])
        np.testing.assert_array_equal(lines[name].get_ydata(), values)


@pytest.mark.parametrize(
    ("angles", "length", "message"),
    [
        ([0, 95], 20, "'angles' must be a 1-D array of finite degrees in 0..90"),
        ([[0, 10]], 20, "'angles' must be a 1-D array"),
        ([0, np.nan], 20, "'angles' must be a 1-D array"),
        ([0, 10], 50, "'length' must be in 5..28"),
        ([0, 10], 3, "'length' must be in 5..28"),
    ],
)
def test_bad_ropiness_input_is_a_clear_error(angles, length, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        intensity_per_length(angles, length, 36, 40)


def test_a_length_that_is_not_a_number_is_a_type_error():
    with pytest.raises(TypeError, match="'length' must be a finite real number"):
        plot_ropiness([0, 10], "long", 36, 40)


# ---------------------------------------------------------------- the periodic table


def test_the_period_table_of_the_5_degree_line_is_table_4_5():
    figure = plot_period_table(degree_slope(5), 64)
    left, right = figure.axes
    dots = [line for line in left.lines if line.get_linestyle() == "None"]
    steps = right.lines
    table = periodic_table(degree_slope(5), 64)
    assert table.period == 57 and "period p = 57" in figure.texts[0].get_text()
    for k, (dot, step) in enumerate(zip(dots, steps, strict=True)):
        np.testing.assert_array_equal(dot.get_xdata(), -0.5 + np.arange(58) / 57)
        np.testing.assert_array_equal(dot.get_ydata(), table.areas[:, k])
        np.testing.assert_array_equal(step.get_ydata(), table.intensities[:, k])
    # the printed rows of Table 4-5 (spec §3.7): areas to 4 decimals, 64-level intensities
    printed = {
        0: ((0.0000, 0.5019, 0.5019), (0, 32, 32)),
        27: ((0.0021, 0.9721, 0.0296), (0, 61, 2)),
        28: ((0.0078, 0.9791, 0.0169), (0, 62, 1)),
        57: ((0.5019, 0.5019, 0.0000), (32, 32, 0)),
    }
    for j, (row_areas, row_levels) in printed.items():
        shown = [dot.get_ydata()[j] for dot in dots]
        np.testing.assert_allclose(shown, row_areas, atol=5e-5)
        assert [int(step.get_ydata()[j]) for step in steps] == list(row_levels)


def test_the_period_table_raises_what_periodic_table_raises():
    with pytest.raises(ValueError, match="'m' must be a first-octant slope"):
        plot_period_table(1.5)
    with pytest.raises(ValueError, match="'levels' must be in 2..256"):
        plot_period_table(0.3, levels=1)


# ---------------------------------------------------------------- post-anti-aliasing


def disk_images(size=24):
    ys, xs = np.mgrid[:size, :size]
    before = ((xs - 12.3) ** 2 + (ys - 10.8) ** 2 < 49).astype(float)
    after = before.copy()
    after[3, 12] = 0.4  # the one pixel that changes most
    after[before.astype(bool) & (np.roll(before, 1, axis=1) == 0)] = 0.7
    return before, after


def test_the_post_antialias_panels_are_the_images_and_the_zoomed_region():
    before, after = disk_images()
    figure = plot_post_antialias(before, after, zoom=(4, 6, 14, 12))
    whole_before, part_before, whole_after, part_after = figure.axes
    np.testing.assert_array_equal(whole_before.images[0].get_array(), before)
    np.testing.assert_array_equal(whole_after.images[0].get_array(), after)
    np.testing.assert_array_equal(part_before.images[0].get_array(), before[6:12, 4:14])
    np.testing.assert_array_equal(part_after.images[0].get_array(), after[6:12, 4:14])
    assert part_after.images[0].get_extent() == [4, 14, 6, 12]
    assert whole_after.patches[0].get_bbox().bounds == (4, 6, 10, 6)


def test_the_default_zoom_is_around_the_pixel_that_changed_most():
    before, after = disk_images()
    figure = plot_post_antialias(np.dstack([before] * 3), np.dstack([after] * 3))
    assert figure.axes[1].get_title() == "before, x 9..15, y 0..6"
    assert figure.axes[3].images[0].get_array().shape == (6, 6, 3)


def test_a_grey_image_beside_a_colour_one_is_shown_in_colour():
    before, after = disk_images()
    figure = plot_post_antialias(before, np.dstack([after, after, before]), zoom=(0, 0, 8, 8))
    np.testing.assert_array_equal(figure.axes[0].images[0].get_array(), np.dstack([before] * 3))


@pytest.mark.parametrize(
    ("after", "zoom", "error", "message"),
    [
        (np.zeros((8, 9)), None, ValueError, "must have one shape"),
        (np.zeros((9, 8, 3)), None, ValueError, "must have one shape"),
        (np.zeros((8, 8, 4)), None, ValueError, "'after' must be an (H, W) or (H, W, 3) array"),
        (np.full((8, 8), 1.5), None, ValueError, "'after' must hold finite values in [0, 1]"),
        (
            np.zeros((8, 8)),
            (0, 0, 9, 4),
            ValueError,
            "'zoom' must satisfy 0 <= x_start < x_end <= 8",
        ),
        (np.zeros((8, 8)), (3, 0, 3, 4), ValueError, "'zoom' must satisfy"),
        (np.zeros((8, 8)), (0, 0, 4), TypeError, "'zoom' must be (x_start, y_start, x_end, y_end)"),
        (np.zeros((8, 8)), (0, 0, 4.0, 4), TypeError, "4 ints"),
    ],
)
def test_bad_post_antialias_input_is_a_clear_error(after, zoom, error, message):
    with pytest.raises(error, match=re.escape(message)):
        plot_post_antialias(np.zeros((8, 8)), after, zoom=zoom)

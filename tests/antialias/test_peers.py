"""The classic line anti-aliasers: exact band vs shapely, total intensity, octant symmetry, convergence."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.antialias.peers import (
    GS_STEPS,
    GS_TABLE,
    abuffer_line,
    cone_band_volume,
    exact_band_line,
    gupta_sproull_line,
    supersampled_line,
    wu_line,
)

from .exact import band_coverage

SIZE = 64
JITTER = (1e-3 / math.pi, 1e-3 / math.e, 1e-3 / math.sqrt(7), 1e-3 / math.sqrt(11))
"""Added to (x0, y0, x1, y1): hypothesis likes round numbers, these break the algorithms' ties."""


def _fan(count: int = 37, seed: int = 5):
    """Long (40 px) segments at angles 0..180 degrees (+-1), centred near the raster's middle."""
    rng = np.random.default_rng(seed)
    for angle in np.linspace(0.0, 180.0, count):
        a = math.radians(angle + rng.uniform(-1, 1))
        centre, direction = rng.uniform(30, 34, 2), np.array([math.cos(a), math.sin(a)])
        yield centre - 20 * direction, centre + 20 * direction


def _major(p0, p1):
    """The major-axis coordinates (pixel-centred, as the algorithms use them) and the slope."""
    axis = int(abs(p1[1] - p0[1]) > abs(p1[0] - p0[0]))
    u0, u1 = sorted((p0[axis] - 0.5, p1[axis] - 0.5))
    run, rise = abs(p1[axis] - p0[axis]), abs(p1[1 - axis] - p0[1 - axis])
    return u0, u1, rise / run


points = st.tuples(st.floats(1, 31), st.floats(1, 31))


# ---------------------------------------------------------------- the exact band, the ground truth


@given(points, points)
@settings(max_examples=max(settings.default.max_examples // 5, 10))
def test_exact_band_is_shapely_band_area(p0, p1):
    assert np.allclose(exact_band_line(p0, p1, 32, 32), band_coverage(p0, p1, 32, 32), rtol=0, atol=1e-9)  # fmt: skip


def test_exact_band_sums_to_the_length_and_clips_far_segments():
    for p0, p1 in _fan(9):
        assert exact_band_line(p0, p1, SIZE, SIZE).sum() == pytest.approx(40.0, abs=1e-9)
    huge = exact_band_line(
        (-(2**20), 7.3), (2**20, 7.3), 16, 16
    )  # corners beyond 2**20 without the cut
    assert (
        np.allclose(huge[7], 0.8) and np.allclose(huge[6], 0.2) and huge.sum() == pytest.approx(16)
    )


# ---------------------------------------------------------------- total intensity of long lines


def test_wu_total_is_the_major_extent_exactly():
    # each major column sums to 1 (the end columns to the part spanned): brightness falls with slope
    for p0, p1 in _fan():
        u0, u1, slope = _major(p0, p1)
        total = wu_line(p0, p1, SIZE, SIZE).sum()
        assert total == pytest.approx(u1 - u0, abs=1e-9)
        assert total == pytest.approx(40.0 / math.sqrt(1 + slope**2), abs=1e-9)


def test_gupta_sproull_total_is_its_columns_times_the_band_per_column():
    # Measured over the fan: -2.1% .. +2.2% of (columns x sqrt(1 + m**2)). The cone's marginal sums to
    # 1 over whole-pixel steps across the band, but GS keeps 3 pixels a column: near 45 degrees the
    # 4th, at D up to 1.06, held Filter(1.06) = 0.08 (-2.1% at 45.8°, -1.8% at 135.7°); and the
    # 1/16-step table rounds D by up to 1/32, which averages out along a line unless its slope is
    # near a simple fraction (+2.2% at 119.8°, m = 0.57 ~ 4/7).
    errors = []
    for p0, p1 in _fan():
        u0, u1, slope = _major(p0, p1)
        columns = math.floor(u1 + 0.5) - math.floor(u0 + 0.5) + 1  # both ends drawn whole
        errors.append(gupta_sproull_line(p0, p1, SIZE, SIZE).sum() / (columns * math.hypot(1, slope)) - 1)  # fmt: skip
    assert -0.03 < min(errors) and max(errors) < 0.03
    assert min(errors) < -0.015  # the 45-degree loss is real: the three-pixel truncation


@pytest.mark.parametrize(
    ("method", "tolerance"),
    [
        # at 45° a k x k grid's samples lie on diagonals sqrt(2)/(2k) apart: the 1-wide band holds
        # floor or ceil of 1/that many, +-(sqrt(2)/(2k))/1 at worst; measured over the fan: -0.9%..+5.9%
        (lambda p0, p1: supersampled_line(p0, p1, SIZE, SIZE, k=4), 0.065),
        # 8x8 masks: the same aliasing at half the spacing; measured -1.0%..+5.5%
        (lambda p0, p1: abuffer_line(p0, p1, SIZE, SIZE, mask="8x8"), 0.06),
        (lambda p0, p1: exact_band_line(p0, p1, SIZE, SIZE), 1e-12),
    ],
    ids=["supersample 4x4", "a-buffer 8x8", "exact band"],
)
def test_sampling_totals_are_the_band_area(method, tolerance):
    for p0, p1 in _fan():
        assert abs(method(p0, p1).sum() / 40.0 - 1) < tolerance


# ---------------------------------------------------------------- symmetry under the 8 octant reflections


def _reflections(p0, p1):
    """(transform of a point, transform of an image) for the 8 symmetries of the SIZE x SIZE raster."""
    for swap in (False, True):
        for flip_x in (False, True):
            for flip_y in (False, True):

                def point(p, swap=swap, flip_x=flip_x, flip_y=flip_y):
                    x, y = (p[1], p[0]) if swap else (p[0], p[1])
                    return (SIZE - x if flip_x else x, SIZE - y if flip_y else y)

                def image(a, swap=swap, flip_x=flip_x, flip_y=flip_y):
                    a = a.T if swap else a
                    a = a[:, ::-1] if flip_x else a
                    return a[::-1] if flip_y else a

                yield point(p0), point(p1), image


METHODS = {
    "wu": wu_line,
    "gupta_sproull": gupta_sproull_line,
    "supersample 4x4": supersampled_line,
    "a-buffer 8x8": abuffer_line,
    "a-buffer 8x8 unsnapped": lambda p0, p1, w, h: abuffer_line(p0, p1, w, h, subpixel_bits=None),
    "exact band": exact_band_line,
}


@pytest.mark.parametrize("name", METHODS)
@given(st.tuples(*[st.floats(2, 62)] * 4))
@settings(max_examples=max(settings.default.max_examples // 10, 5))
def test_every_method_is_symmetric_under_the_octant_reflections(name, ends):
    # Every method here treats the 8 symmetries of the pixel grid alike (the sample grids too), up
    # to ties (a centre line through a midpoint, |dx| = |dy|); the jitter keeps inputs off them.
    x0, y0, x1, y1 = (value + jitter for value, jitter in zip(ends, JITTER, strict=True))
    method = METHODS[name]
    original = method((x0, y0), (x1, y1), SIZE, SIZE)
    for q0, q1, transform in _reflections((x0, y0), (x1, y1)):
        assert np.allclose(method(q0, q1, SIZE, SIZE), transform(original), rtol=0, atol=1e-9)
        assert np.allclose(method(q1, q0, SIZE, SIZE), transform(original), rtol=0, atol=1e-9)


# ---------------------------------------------------------------- supersampling converges to the area


def test_supersampling_converges_to_the_exact_area():
    lines = list(_fan(8, seed=11))
    exact = [exact_band_line(p0, p1, SIZE, SIZE) for p0, p1 in lines]
    rms = []
    for k in (1, 2, 4, 8, 16, 32):
        errors = np.concatenate(
            [
                (supersampled_line(p0, p1, SIZE, SIZE, k=k) - e).ravel()
                for (p0, p1), e in zip(lines, exact, strict=True)
            ]  # fmt: skip
        )
        # per sample row a convex band gives one interval (+-2 samples), and the rows are a midpoint
        # rule of the covered length (total variation <= 2): |error| <= 2/k + 1/k per pixel
        assert np.abs(errors).max() <= 3.0 / k
        rms.append(float(np.sqrt(np.mean(errors**2))))
    assert all(a > b for a, b in zip(rms, rms[1:], strict=False)), rms


# ---------------------------------------------------------------- Wu and Gupta-Sproull in detail


def _wu_pseudo_code(x0, y0, x1, y1, width, height):
    """Wikipedia's "Xiaolin Wu's line algorithm", literally, with integer-centred pixels."""
    image = np.zeros((height, width))

    def plot(x, y, c):
        if 0 <= x < width and 0 <= y < height:
            image[y, x] += c

    def fpart(x):
        return x - math.floor(x)

    steep = abs(y1 - y0) > abs(x1 - x0)
    if steep:
        x0, y0, x1, y1 = y0, x0, y1, x1
    if x0 > x1:
        x0, x1, y0, y1 = x1, x0, y1, y0
    gradient = (y1 - y0) / (x1 - x0)

    def pair(x, y, c):
        for row, value in ((math.floor(y), (1 - fpart(y)) * c), (math.floor(y) + 1, fpart(y) * c)):
            plot(row, x, value) if steep else plot(x, row, value)

    xend = math.floor(x0 + 0.5)
    pair(xend, y0 + gradient * (xend - x0), 1 - fpart(x0 + 0.5))
    xpxl1, intery = xend, y0 + gradient * (xend - x0) + gradient
    xend = math.floor(x1 + 0.5)
    pair(xend, y1 + gradient * (xend - x1), fpart(x1 + 0.5))
    for x in range(xpxl1 + 1, xend):
        pair(x, intery, 1.0)
        intery += gradient
    return image


@given(st.tuples(*[st.floats(-3, 20)] * 4))
@settings(max_examples=max(settings.default.max_examples // 5, 10))
def test_wu_is_the_textbook_pseudo_code(ends):
    x0, y0, x1, y1 = (value + jitter for value, jitter in zip(ends, JITTER, strict=True))
    mine = wu_line((x0, y0), (x1, y1), 16, 16)
    if math.floor(max(abs(x1 - x0), abs(y1 - y0))) >= 1:  # ends in different columns
        book = _wu_pseudo_code(x0 - 0.5, y0 - 0.5, x1 - 0.5, y1 - 0.5, 16, 16)
        assert np.allclose(mine, book, rtol=0, atol=1e-9)
    assert mine.max() <= 1.0 + 1e-12


def test_wu_golden_pixels():
    # from (0.5, 0.5) to (4.5, 2.5), slope 1/2: centre heights 0, .5, 1, 1.5, 2 in columns 0..4;
    # the end columns are half spanned
    expected = np.array(
        [[1.0, 0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 1.0, 0.5, 0.0], [0.0, 0.0, 0.0, 0.5, 1.0]]
    )
    assert np.allclose(wu_line((0.5, 0.5), (4.5, 2.5), 5, 3)[:, :5], expected * [0.5, 1, 1, 1, 0.5])
    assert np.allclose(wu_line((1.2, 1.5), (1.7, 1.5), 3, 3)[1], [0, 0.5, 0])  # one column: u1 - u0


def test_cone_filter_table_against_a_numerical_cone():
    # the cone of radius 1 and volume 1, integrated over the band |t - D| <= 1/2 on a fine grid
    n = 1200
    t = (np.arange(n) + 0.5) / n * 2 - 1
    tx, ty = np.meshgrid(t, t)
    cone = np.clip(1 - np.hypot(tx, ty), 0, None) * 3 / math.pi * (2 / n) ** 2
    for d in (0.0, 0.25, 0.5, 0.8, 1.0, 1.3):
        assert cone_band_volume(d) == pytest.approx(cone[np.abs(tx - d) <= 0.5].sum(), abs=2e-4)
    for d in np.linspace(0, 0.5, 11):  # whole-pixel translates of the band tile the plane
        assert sum(cone_band_volume(d + j) for j in (-1, 0, 1)) == pytest.approx(1.0, abs=1e-12)
    assert len(GS_TABLE) == 1.5 * GS_STEPS + 1 and GS_TABLE[-1] == 0.0
    assert np.all(np.diff(GS_TABLE) < 0)


def test_gupta_sproull_horizontal_line_rows_sum_to_one():
    image = gupta_sproull_line((3.0, 10.5), (40.0, 10.5), SIZE, SIZE)
    columns = image[:, 3:40]  # the midpoint line's columns 3..39 (ends at u = 2.5 and 39.5)
    assert np.allclose(columns.sum(axis=0), 1.0) and np.allclose(columns[10], GS_TABLE[0])
    assert image[:, :2].sum() == 0 and image[:, 41:].sum() == 0


# ---------------------------------------------------------------- degenerate and bad input


@pytest.mark.parametrize("name", METHODS)
def test_degenerate_segments_do_not_raise(name):
    method = METHODS[name]
    assert method((5.2, 5.7), (5.2, 5.7), 16, 16).sum() == 0  # zero length
    assert method((-90, -40), (-20, -60), 16, 16).sum() == 0  # off the raster
    assert method((3.5, 2), (3.5, 12), 16, 16).sum() == pytest.approx(10, rel=0.15)  # vertical
    assert method((2, 3.5), (12, 3.5), 16, 16).sum() == pytest.approx(10, rel=0.15)  # horizontal
    assert method((1, 1), (1 + 1e-300, 1), 16, 16).sum() == pytest.approx(0, abs=1e-9)
    assert method((0, 0), (5, 5), 0, 0).shape == (0, 0)


@pytest.mark.parametrize("name", METHODS)
def test_bad_input_names_the_argument(name):
    method = METHODS[name]
    with pytest.raises(ValueError, match="'p0'"):
        method((math.nan, 0), (1, 1), 8, 8)
    with pytest.raises(ValueError, match="'p1'"):
        method((0, 0), (1, 2, 3), 8, 8)
    with pytest.raises(TypeError, match="'p1'"):
        method((0, 0), ("a", 1), 8, 8)
    with pytest.raises(ValueError, match="'p0'"):
        method((2.0**21, 0), (1, 1), 8, 8)
    with pytest.raises(ValueError, match="'width'"):
        method((0, 0), (1, 1), -1, 8)
    with pytest.raises(TypeError, match="'height'"):
        method((0, 0), (1, 1), 8, 8.0)


def test_bad_options_name_the_argument():
    with pytest.raises(ValueError, match="'k'"):
        supersampled_line((0, 0), (1, 1), 8, 8, k=0)
    with pytest.raises(TypeError, match="'k'"):
        supersampled_line((0, 0), (1, 1), 8, 8, k=2.0)
    with pytest.raises(ValueError, match="'mask'"):
        abuffer_line((0, 0), (1, 1), 8, 8, mask="3x3")
    with pytest.raises(ValueError, match="'subpixel_bits'"):
        abuffer_line((0, 0), (0, 0), 8, 8, subpixel_bits=17)

"""DISLOP_L: Wang 1989 Table 4-1 and Fig 5-1, constant intensity, exact band area, octants, trace."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.antialias import DislopColumn, dislop_line
from scanviz.antialias.columns import band_row, line_column
from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.trace import Recorder

from .exact import band_coverage

M5 = math.tan(5 * 3.14156 / 180)  # the dissertation's pi

# Table 4-1 rows (k: dxy, (up, mid, low), 16 levels, 256 levels), spec §3.7 / golden check 12.
TABLE_4_1 = {
    0: (0.0000, (0.0119, 0.9800, 0.0119), (0, 15, 0), (3, 250, 3)),
    1: (0.0875, (0.0894, 0.9144, 0.0000), (1, 14, 0), (23, 233, 0)),
    6: (-0.4751, (0.0000, 0.5268, 0.4770), (0, 8, 7), (0, 134, 122)),
    11: (-0.0376, (0.0004, 0.9638, 0.0396), (0, 14, 1), (0, 246, 10)),
    23: (0.0122, (0.0191, 0.9783, 0.0064), (0, 15, 0), (5, 249, 2)),
    40: (0.4995, (0.5014, 0.5024, 0.0000), (8, 8, 0), (128, 128, 0)),
    57: (-0.0132, (0.0060, 0.9780, 0.0198), (0, 15, 0), (2, 249, 5)),
    69: (0.0367, (0.0387, 0.9646, 0.0005), (1, 14, 0), (10, 246, 0)),
    80: (-0.0010, (0.0114, 0.9800, 0.0124), (0, 15, 0), (3, 250, 3)),
    91: (-0.0386, (0.0003, 0.9630, 0.0406), (0, 14, 1), (0, 246, 10)),
}

# Fig 5-1: the segment (100.3, 150.2)-(108.6, 155.8) in the dissertation's integer-centred
# pixels; in scanviz's [x, x+1] pixels it is the same pixels for the segment shifted by 1/2.
FIG_5_1 = {
    (100, 151): 0.128100, (100, 150): 0.120004,
    (101, 152): 0.009429, (101, 151): 0.766019, (101, 150): 0.424035,
    (102, 152): 0.450147, (102, 151): 0.749695, (102, 150): 0.006482,
    (103, 153): 0.158312, (103, 152): 0.918017, (103, 151): 0.129996,
    (104, 154): 0.013888, (104, 153): 0.785659, (104, 152): 0.406778,
    (105, 154): 0.474247, (105, 153): 0.728506, (105, 152): 0.003572,
    (106, 155): 0.175252, (106, 154): 0.915607, (106, 153): 0.115466,
    (107, 156): 0.019209, (107, 155): 0.804438, (107, 154): 0.382678,
    (108, 156): 0.463541, (108, 155): 0.706456, (108, 154): 0.001523,
    (109, 156): 0.067772, (109, 155): 0.087664,
}  # fmt: skip
FIG_P0, FIG_P1 = (100.8, 150.7), (109.1, 156.3)

coordinate = st.integers(-64, 20 * 64).map(lambda k: k / 64)  # dyadic: reflections are exact
segment = st.tuples(coordinate, coordinate, coordinate, coordinate)


def test_table_4_1_middle_formula():
    dxy = 0.0
    for k in range(100):
        if k in TABLE_4_1:
            printed_dxy, areas, levels16, levels256 = TABLE_4_1[k]
            up, mid, low = line_column(M5, dxy)[:3]
            assert dxy == pytest.approx(printed_dxy, abs=1.5e-4)
            assert (up, mid, low) == pytest.approx(areas, abs=1.5e-4)
            assert tuple(math.floor(a * 15 + 0.5) for a in (up, mid, low)) == levels16
            assert tuple(math.floor(a * 255 + 0.5) for a in (up, mid, low)) == levels256
        dxy += M5
        if dxy > 0.5:
            dxy -= 1.0


@given(st.floats(0, 1), st.floats(-0.5, 0.5, exclude_min=True))
@settings(max_examples=settings.default.max_examples // 2)
def test_constant_intensity(m, dxy):
    assert sum(line_column(m, dxy)[:3]) == pytest.approx(math.sqrt(1 + m * m), abs=1e-12)


def test_constant_intensity_examples():
    assert sum(line_column(M5, 0.3)[:3]) == pytest.approx(1.003820, abs=1e-6)
    assert sum(line_column(0.68, -0.2)[:3]) == pytest.approx(1.209297, abs=1e-6)


@pytest.mark.parametrize("exact", [False, True])
@pytest.mark.parametrize("trace", [None, True])
def test_fig_5_1(exact, trace):
    result = dislop_line(FIG_P0, FIG_P1, 120, 170, exact=exact, trace=trace)
    image = result[0] if trace else result
    for (x, y), area in FIG_5_1.items():
        assert image[y, x] == pytest.approx(area, abs=1e-5)
    assert np.count_nonzero(image) == 28
    assert image.sum() == pytest.approx(10.012492, abs=1e-6)


def _slope(p):
    dx, dy = abs(p[2] - p[0]), abs(p[3] - p[1])
    return min(dx, dy) / max(dx, dy) if max(dx, dy) else 0.0


@given(segment)
@settings(max_examples=settings.default.max_examples // 4)
def test_exact_mode_is_the_band_area(p):
    expected = band_coverage(p[:2], p[2:], 20, 20)
    assert np.abs(dislop_line(p[:2], p[2:], 20, 20, exact=True) - expected).max() < 1e-9


@given(segment)
@settings(max_examples=settings.default.max_examples // 4)
def test_dissertation_mode_error(p):
    """Exact up to slope 0.75; above, at most the 4th-pixel spill 0.021447 (finding, spec §3.2)."""
    error = np.abs(dislop_line(p[:2], p[2:], 20, 20) - band_coverage(p[:2], p[2:], 20, 20)).max()
    assert error < (1e-9 if _slope(p) <= 0.75 else 0.021448)


def test_worst_spill_is_at_slope_1_and_half_offset():
    up, mid, low = line_column(1.0, 0.5)[:3]
    exact = [band_row(1.0, 0.5, r) for r in (2, 1, 0, -1)]
    assert exact[0] == pytest.approx(0.021447, abs=1e-6)  # the fourth pixel
    assert up - exact[1] == pytest.approx(exact[0], abs=1e-12)  # credited to the up pixel
    assert (mid, low) == pytest.approx(exact[2:], abs=1e-12)
    assert line_column(0.75, 0.5)[0] == pytest.approx(band_row(0.75, 0.5, 1), abs=1e-12)


def _reflections(p, size):
    x0, y0, x1, y1 = p
    return [
        ((size - x0, y0, size - x1, y1), lambda a: a[:, ::-1]),
        ((x0, size - y0, x1, size - y1), lambda a: a[::-1]),
        ((y0, x0, y1, x1), lambda a: a.T),
        ((x1, y1, x0, y0), lambda a: a),
    ]


@given(segment, st.booleans())
@settings(max_examples=settings.default.max_examples // 4)
def test_octant_symmetry(p, exact):
    """Exact symmetry, but for the printed formula past slope 0.75: it is discontinuous at
    dxy = +-1/2 (the 4th pixel's area jumps sides), so rounding can flip it (finding)."""
    size = 20
    bound = 1e-12 if exact or _slope(p) <= 0.75 else 0.021448
    image = dislop_line(p[:2], p[2:], size, size, exact=exact)
    for q, undo in _reflections(p, size):
        other = dislop_line(q[:2], q[2:], size, size, exact=exact)
        assert np.abs(undo(other) - image).max() < bound


@given(segment, st.booleans())
@settings(max_examples=settings.default.max_examples // 4)
def test_traced_equals_compiled(p, exact):
    recorder = Recorder()
    traced = dislop_line(p[:2], p[2:], 20, 20, exact=exact, trace=recorder)
    assert np.array_equal(traced, dislop_line(p[:2], p[2:], 20, 20, exact=exact))


def test_trace_events():
    image, trace = dislop_line(FIG_P0, FIG_P1, 120, 170, trace=True)
    events = list(trace)
    assert all(isinstance(e, DislopColumn) for e in events)
    assert [e.x for e in events] == list(range(99, 111))
    assert [e.branch for e in events][:3] == ["cap"] * 3 and events[-1].branch == "cap"
    middle = events[3]  # column 102: the middle formula, 3 pixels
    assert (middle.branch, middle.y, middle.major) == ("three", 151, "x")
    assert (middle.up, middle.mid, middle.low) == pytest.approx(
        (0.450147, 0.749695, 0.006482), abs=1e-5
    )
    assert middle.up + middle.mid + middle.low == pytest.approx(math.sqrt(1 + middle.slope**2))


def test_trace_steep_line_goes_row_by_row():
    _, trace = dislop_line((3.5, 0.5), (4.5, 9.5), 10, 10, trace=True, exact=True)
    assert {e.major for e in trace} == {"y"} and {e.branch for e in list(trace)[3:-3]} == {"exact"}


@pytest.mark.parametrize(
    "p0, p1",
    [((3, 3), (3, 3)), ((-50, -50), (-40, -45)), ((100, 5), (200, 5)), ((-3, 30), (-30, 3))],
)
def test_degenerate_and_off_raster(p0, p1):
    image = dislop_line(p0, p1, 10, 10)
    assert image.shape == (10, 10) and not image.any()


@pytest.mark.parametrize("exact", [False, True])
def test_vertical_lines(exact):
    centred = dislop_line((2.5, -3), (2.5, 30), 10, 10, exact=exact)  # on column 2's centre
    assert centred[:, 2].tolist() == [1.0] * 10 and centred.sum() == 10.0
    between = dislop_line((3.0, 30), (3.0, -3), 10, 10, exact=exact)  # on the border of 2 and 3
    assert between[:, 2].tolist() == between[:, 3].tolist() == [0.5] * 10


def test_horizontal_line_on_a_pixel_row():
    image = dislop_line((1, 4.5), (6, 4.5), 8, 8)
    assert image[4, 1:6].tolist() == [1.0] * 5 and image.sum() == 5.0
    assert dislop_line((1, 4.5), (6, 4.5), 0, 0).shape == (0, 0)


@pytest.mark.parametrize(
    "args, kwargs, error, text",
    [
        (((0, math.nan), (1, 1), 4, 4), {}, ValueError, "'p0' is not finite"),
        (((0, 0, 0), (1, 1), 4, 4), {}, ValueError, "'p0' must be a (2) array"),
        (((0, 0), (1, 1), -1, 4), {}, ValueError, "'width' must be in 0.."),
        (((0, 0), (1, 1), 4, 2.5), {}, TypeError, "'height' must be an int"),
        (((0, 0), (1, 1), 4, 4), {"exact": 1}, TypeError, "'exact' must be a bool"),
        (((0, 0), (1, 1), 4, 4), {"trace": "yes"}, TypeError, "'trace' must be None, True"),
    ],
)
def test_bad_input(args, kwargs, error, text):
    with pytest.raises(error, match=text.replace("(", r"\(").replace(")", r"\)")):
        dislop_line(*args, **kwargs)


# Table slices of DISLOP_L column areas (golden checks 16, 18): (m, dxy, (up, mid, low), 64-level ints).
SLICES = [
    (M5, -0.5 + 0 / 57, (0.0, 0.5019, 0.5019), (0, 32, 32)),  # Table 4-5, j = 0
    (M5, -0.5 + 28 / 57, (0.0078, 0.9791, 0.0169), (0, 62, 1)),  # j = 28
    (M5, -0.5 + 57 / 57, (0.5019, 0.5019, 0.0), (32, 32, 0)),  # j = 57
    (0.08, -0.48, (0.0, 0.5216, 0.4816), (0, 33, 30)),  # Table 4-8, j = 1
    (0.08, 0.0, (0.0108, 0.9816, 0.0108), (1, 62, 1)),  # j = 25
    (0.68, -0.30, (0.0154, 0.7893, 0.4046), (1, 50, 25)),  # Table 5-1, j = 10
    (0.68, 0.0, (0.1454, 0.9185, 0.1454), (9, 58, 9)),  # j = 25
]


@pytest.mark.parametrize("m, dxy, areas, levels", SLICES)
def test_table_slices(m, dxy, areas, levels):
    values = line_column(m, dxy)[:3]
    assert values == pytest.approx(areas, abs=1e-4)
    assert tuple(math.floor(a * 63 + 0.5) for a in values) == levels


def test_fig_5_2_distances():
    """dxy per column of the Fig 5-1 segment, columns 100..108 (Fig 5-2, golden check 19)."""
    _, trace = dislop_line(FIG_P0, FIG_P1, 120, 170, trace=True)
    dxy = {e.x: e.dxy for e in trace}
    printed = [-0.0024, -0.3277, 0.3470, 0.0217, -0.3036, 0.3711, 0.0458, -0.2795, 0.3952]
    assert [dxy[x] for x in range(100, 109)] == pytest.approx(printed, abs=1e-4)


def test_trace_round_trips_and_filters():
    _, trace = dislop_line(FIG_P0, FIG_P1, 120, 170, trace=True)
    assert type(trace).from_json(trace.to_json()) == trace
    rows = Recorder(rows=(151, 152))
    dislop_line(FIG_P0, FIG_P1, 120, 170, trace=rows)
    assert [(e.x, e.y) for e in rows.trace()] == [(101, 151), (102, 151)]


def test_memory_limit_is_checked_before_allocating():
    with memory_limit("1M"), pytest.raises(ResourceLimitError, match="dislop_line: a 1000x1000"):
        dislop_line((0, 0), (1, 1), 1000, 1000)

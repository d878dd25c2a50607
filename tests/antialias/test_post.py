"""Post-anti-aliasing (Wang 1989 §4.8, §5.1, §5.2): table look-ups against DISLOP, Fig 5-6, blending."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.antialias import dislop_line
from scanviz.antialias.post import PostColumn, post_antialias, silhouette_mask
from scanviz.antialias.tables import column_indices
from scanviz.trace import Recorder

FIG_P0, FIG_P1 = (100.8, 150.7), (109.1, 156.3)  # the dissertation's (100.3, 150.2)-(108.6, 155.8)
# Fig 5-6: the shared edge, (x, y): (flag 0, flag 1) over its middle columns 101..108.
FIG_5_6 = {
    (101, 151): (0.807524, 0.192476), (101, 150): (0.020192, 0.979808),
    (102, 152): (0.974819, 0.025181), (102, 151): (0.178196, 0.821804),
    (103, 152): (0.478315, 0.521685),
    (104, 153): (0.788889, 0.211111), (104, 152): (0.014726, 0.985274),
    (105, 154): (0.967804, 0.032196), (105, 153): (0.161111, 0.838889),
    (106, 154): (0.454216, 0.545784),
    (107, 155): (0.769395, 0.230605), (107, 154): (0.010121, 0.989879),
    (108, 156): (0.959929, 0.040071), (108, 155): (0.144887, 0.855113),
}  # fmt: skip
TABLE_ERROR = 0.013527  # the measured worst error of the 51 x 51 x 3 line look-up (test_tables)


def _random_segments(count, size, seed=13):
    return np.random.default_rng(seed).uniform(-4, size + 4, (count, 2, 2))


def test_one_segment_on_black_against_dislop_line():
    """Only the table's quantisation of m and dxy: max <= the LUT's worst error; RMS measured."""
    black, errors = np.zeros((64, 64)), []
    for p0, p1 in _random_segments(200, 64):
        out = post_antialias(black, [(p0, p1)])
        assert np.array_equal(out[:, :, 0], out[:, :, 2])
        direct = dislop_line(p0, p1, 64, 64)
        touched = (out[:, :, 0] > 0) | (direct > 0)
        errors.append((out[:, :, 0] - direct)[touched])
    errors = np.concatenate(errors)
    assert np.abs(errors).max() <= TABLE_ERROR
    assert math.sqrt(np.mean(errors**2)) < 0.005  # measured 0.0047


def test_figure_5_1_caps_are_dislop_l_and_the_middle_is_the_table():
    out = post_antialias(np.zeros((160, 112)), [(FIG_P0, FIG_P1)])[:, :, 0]
    direct = dislop_line(FIG_P0, FIG_P1, 112, 160)
    caps = [99, 100, 101, 108, 109, 110]  # ixs - 1 .. ixs + 1 and ixe - 1 .. ixe + 1
    assert np.abs(out[:, caps] - direct[:, caps]).max() < 1e-15
    assert 0 < np.abs(out - direct).max() <= TABLE_ERROR
    column = out[
        152:155, 104
    ]  # Fig 5-1's column #4 gets Table 5-1's j = 10 (0.4046, 0.7893, 0.0154)
    assert column == pytest.approx([0.4046, 0.7893, 0.0154], abs=1e-4)


def test_trace_equals_untraced_and_reports_the_fig_5_2_indices():
    image = np.full((160, 112, 3), 0.25)
    plain = post_antialias(image, [(FIG_P0, FIG_P1)])
    traced, trace = post_antialias(image, [(FIG_P0, FIG_P1)], trace=True)
    assert np.array_equal(plain, traced)
    events = list(trace)
    assert all(isinstance(e, PostColumn) and e.kind == "post_column" for e in events)
    assert [e.x for e in events] == list(range(102, 108))  # the table columns ixs+2..ixe-2
    assert [e.j for e in events] == column_indices(FIG_P0, FIG_P1).j[2:8].tolist()
    assert {e.i for e in events} == {34}
    simple = post_antialias(image, [(FIG_P0, FIG_P1)], recurrence="simple", trace=True)[1]
    assert [e.j for e in simple] == [43, 27, 11, 45, 29, 13]
    assert type(trace).from_json(trace.to_json()) == trace
    recorder = Recorder(rows=(152, 153))
    post_antialias(image, [(FIG_P0, FIG_P1)], trace=recorder)
    assert [(e.x, e.y) for e in recorder.trace()] == [(103, 152)]


coordinate = st.integers(-5 * 64, 30 * 64).map(lambda k: k / 64)


@given(
    st.lists(
        st.tuples(st.tuples(coordinate, coordinate), st.tuples(coordinate, coordinate)), max_size=4
    ),
    st.sampled_from(["line", "edge"]),
    st.sampled_from(["exact", "simple"]),
    st.sampled_from(["area", "intensity"]),
)
@settings(max_examples=settings.default.max_examples // 4)
def test_traced_equals_untraced(segments, kind, recurrence, table):
    flags = [k % 2 for k in range(len(segments))] if kind == "edge" else None
    options = {"kind": kind, "flags": flags, "recurrence": recurrence, "table": table}
    image = np.zeros((24, 24))
    plain = post_antialias(image, np.reshape(segments, (-1, 2, 2)), **options)
    traced, trace = post_antialias(image, np.reshape(segments, (-1, 2, 2)), trace=True, **options)
    assert np.array_equal(plain, traced)
    for event in trace:
        assert 0 <= event.j <= 50 and 0 <= event.i <= 50 and 0 <= event.segment < len(segments)


def test_area_and_intensity_tables_agree_within_one_level():
    """§4.8: at 64 levels the look-up is within one intensity level (of the area table, of DISLOP_L)."""
    black = np.zeros((64, 64))
    for levels in (16, 64, 256):
        for p0, p1 in _random_segments(60, 64, seed=levels):
            area = post_antialias(black, [(p0, p1)])[:, :, 1]
            level = post_antialias(black, [(p0, p1)], table="intensity", levels=levels)[:, :, 1]
            assert np.abs(level * (levels - 1) - area * (levels - 1)).max() <= 0.5 + 1e-9
            if levels == 64:
                direct = np.floor(dislop_line(p0, p1, 64, 64) * 63 + 0.5)
                assert np.abs(np.rint(level * 63) - direct).max() <= 1


def test_figure_5_6_shared_edge_flags_add_to_one():
    black = np.zeros((160, 112))
    flag0 = post_antialias(black, [(FIG_P0, FIG_P1)], kind="edge", flags=[0])[:, :, 0]
    flag1 = post_antialias(black, [(FIG_P0, FIG_P1)], kind="edge", flags=[1])[:, :, 0]
    written = (flag0 > 0) | (flag1 > 0)
    assert np.allclose((flag0 + flag1)[written], 1.0, atol=1e-12)
    assert set(np.nonzero(written)[1].tolist()) == set(range(101, 109))  # ixs+1..ixe-1 only
    printed = np.array([(flag0[y, x], flag1[y, x], *FIG_5_6[x, y]) for x, y in FIG_5_6])
    assert np.abs(printed[:, :2] - printed[:, 2:]).max() < 0.0064  # measured 0.00635: the LUT
    assert written.sum() == len(FIG_5_6)


def _half_plane_coverage(p0, p1, inside, shape):
    """Exact coverage of pixels [x, x+1] x [y, y+1] by the half-plane of p0-p1 holding `inside`."""
    p0, p1, inside = map(np.asarray, (p0, p1, inside))
    direction = (p1 - p0) / np.linalg.norm(p1 - p0)
    normal = np.array([-direction[1], direction[0]])
    normal *= np.sign(np.dot(inside - p0, normal))
    a, b = p0 - 1e3 * direction, p1 + 1e3 * direction
    plane = shapely.Polygon([a, b, b + 1e3 * normal, a + 1e3 * normal])
    image = np.zeros(shape)
    for y in range(shape[0]):
        for x in range(shape[1]):
            image[y, x] = plane.intersection(shapely.box(x, y, x + 1, y + 1)).area
    return image


@pytest.mark.parametrize("angle", [7, 40, 75, 110, 160, 200, 250, 300, 345])
def test_edge_flags_in_every_octant_against_the_half_plane(angle):
    """flag 1: inside at lower y (|dy| <= |dx|) or lower x (steeper); every written pixel is exact to the LUT."""
    centre, direction = (
        np.array([12.3, 11.6]),
        np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))]),
    )
    p0, p1 = centre - 9 * direction, centre + 9 * direction
    steep = abs(direction[1]) > abs(direction[0])
    for flag in (0, 1):
        offset = np.array([1.0, 0.0] if steep else [0.0, 1.0]) * (-3 if flag else 3)
        exact = _half_plane_coverage(p0, p1, centre + offset, (25, 25))
        out = post_antialias(np.zeros((25, 25)), [(p0, p1)], kind="edge", flags=[flag])[:, :, 0]
        written = out > 0
        assert written.sum() >= 15
        assert np.abs(out - exact)[written].max() <= 0.0101


def test_blending_over_a_background_is_linear():
    rng = np.random.default_rng(2)
    first, second = rng.uniform(0, 1, (2, 40, 40, 3))
    color = (0.9, 0.3, 0.6)
    segments = _random_segments(5, 40, seed=3)
    for kind, flags in (("line", None), ("edge", [0, 1, 1, 0, 1])):

        def blend(image, segments=segments, kind=kind, flags=flags):
            return post_antialias(
                image, segments[:1], kind=kind, flags=flags and flags[:1], color=color
            )

        mixed = blend(0.3 * first + 0.7 * second)
        assert np.allclose(mixed, 0.3 * blend(first) + 0.7 * blend(second), atol=1e-12)
        coverage = post_antialias(
            np.zeros((40, 40)), segments[:1], kind=kind, flags=flags and flags[:1]
        )
        assert np.allclose(blend(first), coverage * color + (1 - coverage) * first, atol=1e-12)
    out = post_antialias(first, segments, color=color)  # several: blended one after the other
    step = first
    for segment in segments:
        step = post_antialias(step, [segment], color=color)
    assert np.array_equal(out, step)


def test_transposed_segment_gives_the_transposed_image():
    for p0, p1 in np.rint(_random_segments(20, 32, seed=5) * 64) / 64:
        out = post_antialias(np.zeros((36, 36)), [(p0, p1)])
        swapped = post_antialias(np.zeros((36, 36)), [(p0[::-1], p1[::-1])])
        assert np.array_equal(out, swapped.transpose(1, 0, 2))


@pytest.mark.parametrize(
    "p0, p1",
    [
        ((3.3, 3.3), (3.3, 3.3)),  # zero length
        ((-30, -5), (-10, -20)),  # off the raster
        ((-300.5, 4.5), (400.2, 7.1)),  # far beyond both sides
        ((5.5, 1.2), (5.5, 14.8)),  # vertical
        ((1.2, 5.5), (14.8, 5.5)),  # horizontal
        ((1.5, 1.5), (14.5, 14.5)),  # 45 degrees
        ((14.5, 1.5), (1.5, 14.5)),  # -45 degrees
    ],
)
def test_degenerate_segments(p0, p1):
    for kind, flags in (("line", None), ("edge", [1])):
        for table in ("area", "intensity"):
            out = post_antialias(
                np.zeros((16, 16)), [(p0, p1)], kind=kind, flags=flags, table=table
            )
            assert out.shape == (16, 16, 3) and np.all((out >= 0) & (out <= 1))
    line = post_antialias(np.zeros((16, 16)), [(p0, p1)])[:, :, 0]
    assert np.abs(line - dislop_line(p0, p1, 16, 16)).max() <= TABLE_ERROR
    assert post_antialias(np.zeros((4, 4)), np.zeros((0, 2, 2))).shape == (4, 4, 3)


@pytest.mark.parametrize(
    "arguments, error, words",
    [
        ({"image": np.zeros((4, 4, 2))}, ValueError, "'image'"),
        ({"image": np.full((4, 4), 2.0)}, ValueError, "'image'"),
        ({"image": [["a"]]}, TypeError, "'image'"),
        ({"segments": [(0, 0, 1, 1)]}, ValueError, "'segments'"),
        ({"segments": [((0, 0), (1, math.nan))]}, ValueError, "'segments'"),
        ({"kind": "circle"}, ValueError, "'kind'"),
        ({"kind": "edge"}, ValueError, "'flags'"),
        ({"kind": "edge", "flags": [2]}, ValueError, "'flags'"),
        ({"kind": "edge", "flags": [0, 1]}, ValueError, "'flags'"),
        ({"kind": "edge", "flags": [0.5]}, TypeError, "'flags'"),
        ({"flags": [1]}, ValueError, "'flags'"),
        ({"color": (1, 1)}, ValueError, "'color'"),
        ({"color": (1, 1, 1.5)}, ValueError, "'color'"),
        ({"color": "red"}, TypeError, "'color'"),
        ({"table": "lut"}, ValueError, "'table'"),
        ({"levels": 1}, ValueError, "'levels'"),
        ({"levels": 64.0}, TypeError, "'levels'"),
        ({"recurrence": "fast"}, ValueError, "'recurrence'"),
        ({"image": np.full((4, 4), 0.5), "table": "intensity"}, ValueError, "black"),
        ({"trace": "yes"}, TypeError, "'trace'"),
    ],
)
def test_bad_input_names_the_argument(arguments, error, words):
    arguments = {"image": np.zeros((4, 4)), "segments": [((0, 0), (3, 2))], **arguments}
    with pytest.raises(error, match=words):
        post_antialias(arguments.pop("image"), arguments.pop("segments"), **arguments)


def _two_disks(shade_back, shade_front, size=40):
    """An aliased render: a back disk, a front disk overlapping it, on black; and its labels."""
    y, x = np.mgrid[0:size, 0:size] + 0.5
    back = (x - 15) ** 2 + (y - 18) ** 2 < 10**2
    front = (x - 25) ** 2 + (y - 21) ** 2 < 8**2
    labels = np.where(front, 2, np.where(back, 1, 0))
    image = np.choose(labels, [0.0, shade_back, shade_front]) * (1 - 0.002 * y)  # a slight shading
    return image, labels


def _label_boundary(labels, pairs):
    """Pixels with a 4-neighbour of another label, for the label pairs in `pairs`."""
    mask = np.zeros(labels.shape, dtype=bool)
    for axis in (0, 1):
        a, b = labels, np.roll(labels, -1, axis=axis)
        cut = np.zeros(labels.shape, dtype=bool)
        for p, q in pairs:
            cut |= ((a == p) & (b == q)) | ((a == q) & (b == p))
        edge = [slice(None), slice(None)]
        edge[axis] = slice(-1, None)
        cut[tuple(edge)] = False  # no wrap-around
        mask |= cut | np.roll(cut, 1, axis=axis)
    return mask


def test_silhouette_mask_on_overlapping_disks():
    image, labels = _two_disks(0.9, 0.3)
    everything = _label_boundary(labels, [(0, 1), (0, 2), (1, 2)])
    assert np.array_equal(silhouette_mask(image, 0.2), everything)  # the shading stays below 0.2
    front_over_back = _label_boundary(labels, [(0, 1), (1, 2)])  # 0.9 | 0, 0.9 | 0.3; not 0.3 | 0
    assert np.array_equal(silhouette_mask(image, 0.5), front_over_back)
    rgb = np.stack([image, 0.5 * image, np.zeros_like(image)], axis=2)
    assert np.array_equal(silhouette_mask(rgb, 0.2), everything)
    assert not silhouette_mask(np.full((5, 5), 0.4), 0.0).any()
    assert silhouette_mask(np.zeros((0, 3)), 0.1).shape == (0, 3)


def test_silhouette_mask_bad_input():
    with pytest.raises(ValueError, match="'threshold'"):
        silhouette_mask(np.zeros((3, 3)), 1.5)
    with pytest.raises(TypeError, match="'threshold'"):
        silhouette_mask(np.zeros((3, 3)), "0.1")
    with pytest.raises(ValueError, match="'image'"):
        silhouette_mask(np.zeros(3), 0.1)

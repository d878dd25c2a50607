"""Homogeneous Sutherland-Hodgman clipping: outcodes, trivial cases, oracles, attributes, traces."""

from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.scene import Camera
from scanviz.trace import Recorder, Trace
from scanviz.transform import CLIP_PLANES, classify, clip_from_eye, clip_polygon, outcodes

BASE = settings.default.max_examples
UNIT_SQUARE = shapely.box(-1, -1, 1, 1)


def exact_distances(row):
    """Signed distances of one clip-space point to the six planes, as exact Fractions."""
    x, y, z, w = (Fraction(float(v)) for v in row)
    return dict(zip(CLIP_PLANES, (z, w - z, w + x, w - x, w + y, w - y), strict=True))


def verdict_of(points, attributes=None):
    recorder = Recorder()
    clipped, values = clip_polygon(points, attributes, trace=recorder)
    return clipped, values, recorder.trace()[0]


@st.composite
def clip_vertex(draw):
    """A clip-space vertex, often exactly on a plane or at w = 0."""
    w = draw(st.one_of(st.floats(-3, 3), st.sampled_from([0.0, 1.0, 2.5])))
    coordinate = st.one_of(st.floats(-4, 4), st.sampled_from([-1.0, 0.0, 1.0]).map(lambda k: k * w))
    return draw(coordinate), draw(coordinate), draw(coordinate), w


clip_polygons = st.lists(clip_vertex(), min_size=3, max_size=8)


@st.composite
def convex_ndc_polygons(draw):
    """A convex polygon in clip space with w > 0 and 0 <= z <= w: only x and y planes can cut."""
    corners = draw(st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=3, max_size=9))
    hull = shapely.MultiPoint(corners).convex_hull
    if not isinstance(hull, shapely.Polygon) or hull.area < 1e-3:
        hull = shapely.Polygon([(-2, -0.5), (2.5, -0.25), (0, 3)])
    ndc = np.array(hull.exterior.coords[:-1])
    w = np.array(draw(st.lists(st.floats(0.1, 10), min_size=len(ndc), max_size=len(ndc))))
    z = np.array(draw(st.lists(st.floats(0, 1), min_size=len(ndc), max_size=len(ndc))))
    return np.column_stack([ndc * w[:, None], z * w, w]), hull


# --- outcodes and trivial cases -----------------------------------------------------------


def test_outcode_bits_follow_the_plane_order():
    inside = [0.0, 0.0, 0.5, 1.0]
    outside_one = [[0, 0, -0.1, 1], [0, 0, 1.1, 1], [-1.1, 0, 0.5, 1], [1.1, 0, 0.5, 1]]
    outside_one += [[0, -1.1, 0.5, 1], [0, 1.1, 0.5, 1]]
    assert outcodes([inside, *outside_one]).tolist() == [0, 1, 2, 4, 8, 16, 32]
    assert CLIP_PLANES == ("near", "far", "left", "right", "bottom", "top")
    on_every_boundary = [[1, -1, 0, 1], [-1, 1, 1, 1], [0, 0, 0, 0]]
    assert outcodes(on_every_boundary).tolist() == [0, 0, 0]


def test_trivially_accepted_polygons_come_back_as_the_very_same_arrays():
    points = np.array([[0, 0, 0.5, 1], [1, 0, 0, 1], [1, 1, 1, 1], [-1, 1, 0.2, 1.0]])
    attributes = np.arange(8.0).reshape(4, 2)
    clipped, values, event = verdict_of(points, attributes)
    assert clipped is points and values is attributes
    assert event.verdict == "accepted" and event.counts == () and event.outcodes == (0,) * 4
    assert clip_polygon(points)[1] is None


def test_trivially_rejected_polygons_come_back_empty():
    points = [[2, 0, 0.5, 1], [3, 1, 0.5, 1], [5, -4, -1, 1]]  # all right of x = w
    clipped, values, event = verdict_of(points, np.ones((3, 5)))
    assert clipped.shape == (0, 4) and values.shape == (0, 5)
    assert event.verdict == "rejected" and event.counts == () and event.vertices == ()
    assert clip_polygon(points)[1] is None


@given(st.lists(clip_vertex(), min_size=3, max_size=12), st.randoms(use_true_random=False))
@settings(max_examples=BASE // 2)
def test_classify_predicts_what_the_clipper_does(vertices, random):
    count = len(vertices)
    faces = [random.sample(range(count), random.randint(3, count)) for _ in range(6)]
    expected = {"accept": {"accepted"}, "reject": {"rejected"}, "clip": {"clipped", "rejected"}}
    for face, verdict in zip(faces, classify(vertices, faces), strict=True):
        assert verdict_of(np.array(vertices)[face])[2].verdict in expected[verdict]
    assert classify(vertices, []).shape == (0,)


# --- oracles ------------------------------------------------------------------------------


@given(convex_ndc_polygons())
@settings(max_examples=BASE * 2)
def test_x_y_clipping_matches_shapely_in_ndc(case):
    points, ndc_polygon = case
    clipped, _ = clip_polygon(points)
    expected = ndc_polygon.intersection(UNIT_SQUARE)
    if len(clipped) == 0:
        assert expected.area < 1e-12
        return
    result = shapely.Polygon(clipped[:, :2] / clipped[:, 3:])
    assert result.area == pytest.approx(expected.area, rel=1e-9, abs=1e-12)
    assert result.symmetric_difference(expected).area <= 1e-9 * max(expected.area, 1e-3)


def eye_space_clip(polygon, near, far):
    """Oracle: exact Sutherland-Hodgman in eye space against -far <= z <= -near."""
    for inside in (lambda p: -p[2] - near, lambda p: p[2] + far):
        kept = []
        for start, end in zip(polygon[-1:] + polygon[:-1], polygon, strict=True):
            d_start, d_end = inside(start), inside(end)
            if (d_start < 0) != (d_end < 0) and d_start != 0 and d_end != 0:
                t = d_start / (d_start - d_end)
                kept.append(tuple(s + t * (e - s) for s, e in zip(start, end, strict=True)))
            if d_end >= 0:
                kept.append(end)
        polygon = kept
    return polygon


eye_coordinate = st.floats(-6, 6)
eye_triangles = st.lists(
    st.tuples(eye_coordinate, eye_coordinate, st.floats(-12, 4)), min_size=3, max_size=3
)


@given(eye_triangles, st.floats(-2, 1), st.floats(0.2, 2), st.floats(0.1, 1), st.floats(2, 10))
@settings(max_examples=BASE * 2)
def test_triangles_through_the_eye_plane_match_eye_space_clipping(triangle, low, size, near, far):
    camera = Camera(window=(low, low + size, -1, 1), near=near, far=far)
    projection = clip_from_eye(camera)
    eye_points = np.column_stack([triangle, np.ones(3)])
    clipped, _ = clip_polygon(eye_points @ projection.T)
    assert (clipped[:, 3] >= near * (1 - 1e-12)).all()  # nothing at or behind the eye survives
    exact = [tuple(Fraction(v) for v in p) for p in triangle]
    oracle = [[float(v) for v in p] + [1.0] for p in eye_space_clip(exact, near, far)]
    expected = 0.0
    if len(oracle) >= 3:
        projected = np.array(oracle) @ projection.T
        expected = shapely.Polygon(projected[:, :2] / projected[:, 3:]).intersection(UNIT_SQUARE)
        expected = expected.area
    area = shapely.Polygon(clipped[:, :2] / clipped[:, 3:]).area if len(clipped) else 0.0
    assert area == pytest.approx(expected, rel=1e-7, abs=1e-10)


@given(clip_polygons)
@settings(max_examples=BASE * 3)
def test_output_is_inside_every_plane_and_keeps_every_inside_vertex(vertices):
    points = np.array(vertices)
    clipped, _, event = verdict_of(points)
    scale = 1 + np.abs(points).max()
    for row in clipped:
        assert min(exact_distances(row).values()) >= -1e-12 * scale
    assert len(clipped) == 0 or len(clipped) >= 3
    if event.verdict != "rejected":
        inside = points[outcodes(points) == 0]
        assert {tuple(p) for p in inside.tolist()} <= {tuple(p) for p in clipped.tolist()}
    assert event.verdict == ("rejected" if len(clipped) == 0 else event.verdict)
    assert event.vertices == tuple(map(tuple, clipped.tolist()))


@given(clip_polygons, st.integers(0, 2**32 - 1))
@settings(max_examples=BASE * 2)
def test_attributes_linear_in_clip_coordinates_stay_exact(vertices, seed):
    rng = np.random.default_rng(seed)
    weights, offset = rng.uniform(-2, 2, (4, 3)), rng.uniform(-2, 2, 3)
    points = np.array(vertices)
    clipped, values = clip_polygon(points, points @ weights + offset)
    tolerance = 1e-12 * (1 + np.abs(points).max()) * (1 + np.abs(weights).sum())
    assert np.allclose(values, clipped @ weights + offset, rtol=0, atol=tolerance)


def test_new_vertices_lie_exactly_on_their_plane():
    points = [[0, 0, 0.5, 1], [3, 0.2, 0.4, 1.3], [0.3, 4, 2.5, 1.7]]
    clipped, _ = clip_polygon(points)
    new = [row for row in clipped.tolist() if row not in points]
    assert len(new) == len(clipped) - 1 == 3
    assert all(min(exact_distances(row).values()) == 0 for row in new)


def test_an_edge_shared_by_two_polygons_is_cut_at_bitwise_the_same_point():
    rng = np.random.default_rng(2024)
    for _ in range(200):
        w = rng.uniform(0.5, 2, 4)
        inside = rng.uniform(-0.9, 0.9, (4, 3)) * [1, 1, 0.5] + [0, 0, 0.5]
        p, q, r, s = np.column_stack([inside * w[:, None], w])
        q[0] = q[3] * rng.uniform(1.5, 4)  # q right of x = w
        first, _ = clip_polygon([p, q, r])
        second, _ = clip_polygon([q, p, s])  # the same edge, walked the other way
        crossings = [{tuple(v) for v in out.tolist() if v[0] == v[3]} for out in (first, second)]
        assert crossings[0] & crossings[1], "the shared edge p-q was cut at different points"


# --- degenerate input never raises --------------------------------------------------------


@pytest.mark.parametrize(
    ("points", "verdict", "count"),
    [
        ([[0, 0, 0.5, 1]] * 3, "accepted", 3),  # one point, three times
        ([[5, 0, 0.5, 1]] * 4, "rejected", 0),
        ([[0, 0, 0.5, 1], [2, 0, 0.5, 1], [4, 0, 0.5, 1]], "clipped", 3),  # collinear: zero area
        ([[1, 0, 0.5, 1], [2, -1, 0.5, 1], [2, 1, 0.5, 1]], "rejected", 0),  # x = w at a vertex
        ([[1, -1, 0.5, 1], [2, 0, 0.5, 1], [1, 1, 0.5, 1]], "rejected", 0),  # touches along an edge
        ([[-1, -1, 0, 1], [1, -1, 0, 1], [1, 1, 0, 1]], "accepted", 3),  # in the near plane
        ([[0, 0, -1, 0], [1, 0, 0.5, 1], [0, 1, 0.5, 1]], "clipped", 4),  # a vertex with w = 0
        ([[0, 0, -1, 0], [1, 0, -1, 0], [0, 1, -1, 0]], "rejected", 0),  # all in the eye plane
        ([[0, 0, 0, 0], [1, 0, 0.5, 1], [0, 1, 0.5, 1]], "accepted", 3),  # 0 is on every plane
    ],
)
def test_degenerate_polygons_are_clipped_without_raising(points, verdict, count):
    clipped, values, event = verdict_of(points, np.zeros((len(points), 1)))
    assert (event.verdict, len(clipped), len(values)) == (verdict, count, count)


def test_a_vertex_on_a_plane_is_not_duplicated():
    # The vertex (1, 0) is on x = w; its neighbours lie on either side.
    points = [[0, -0.5, 0.5, 1], [1, 0, 0.5, 1], [2, 0.5, 0.5, 1], [0, 0.5, 0.5, 1]]
    rows = clip_polygon(points)[0].tolist()
    assert all(rows[i] != rows[i - 1] for i in range(len(rows)))
    assert rows == [[0, -0.5, 0.5, 1], [1, 0, 0.5, 1], [1, 0.5, 0.5, 1], [0, 0.5, 0.5, 1]]


# --- trace --------------------------------------------------------------------------------


def test_clipped_event_counts_vertices_after_each_plane():
    # A triangle cut by the near and the right plane; the others leave the count unchanged.
    points = [[0, 0, -0.5, 1], [3, 0, 0.5, 1], [0, 0.5, 0.5, 1]]
    recorder = Recorder(polygons=[4])
    clipped, _ = clip_polygon(points, trace=recorder, polygon=4)
    clip_polygon(points, trace=recorder, polygon=5)
    (event,) = recorder.trace()
    assert event.kind == "polygon_clipped" and event.polygon == 4 and event.verdict == "clipped"
    assert event.outcodes == (1, 8, 0)  # near, right, inside
    assert event.counts == (4, 4, 4, len(clipped), len(clipped), len(clipped))
    assert Trace.from_json(recorder.trace().to_json()) == recorder.trace()


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        (([[0, 0, 0, 1]] * 2,), ValueError, "'clip_points' must have at least 3 rows"),
        (([[0, 0, 0]] * 3,), ValueError, r"'clip_points' must be an \(N, 4\) array"),
        (([[0, 0, 0, np.nan]] * 3,), ValueError, "'clip_points' row 0 is not finite"),
        (([[0, 0, 0, 1]] * 3, np.ones((2, 1))), ValueError, "one row per vertex"),
        (([[0, 0, 0, 1]] * 3, np.ones(3)), ValueError, r"'attributes' must be an \(N, K\)"),
        (([[0, 0, 0, 1]] * 3, [[np.inf]] * 3), ValueError, "'attributes' row 0 is not finite"),
    ],
)
def test_bad_arguments_raise_naming_the_argument(arguments, error, message):
    with pytest.raises(error, match=message):
        clip_polygon(*arguments)


def test_bad_faces_and_tracers_raise_naming_the_argument():
    points = [[0, 0, 0, 1]] * 4
    with pytest.raises(ValueError, match=r"'faces\[1\]' indexes outside 0..3"):
        classify(points, [[0, 1, 2], [1, 2, 4]])
    with pytest.raises(ValueError, match=r"'faces\[0\]' has 2 vertices"):
        classify(points, [[0, 1]])
    with pytest.raises(TypeError, match=r"'faces\[0\]' must be a 1-D sequence of int"):
        classify(points, [[0.5, 1, 2]])
    with pytest.raises(TypeError, match="'trace' must be None or a Tracer"):
        clip_polygon(points[:3], trace=[])

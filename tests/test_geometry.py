"""Polygon: construction, read-only contours, and validation messages (DESIGN §6)."""

import math
import re
import warnings
from unittest import mock

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Polygon, geometry, raster
from scanviz.antialias import dislop_edge, dislop_line
from scanviz.conventions import COORD_LIMIT

TRIANGLE = [(0, 0), (4, 0), (4, 3)]


def test_one_contour_or_a_list_of_contours():
    assert Polygon(TRIANGLE).contour_count == 1
    assert Polygon([TRIANGLE]).contour_count == 1
    ragged = Polygon([TRIANGLE, [(1, 1), (2, 1), (2, 2), (1, 2)]])
    assert (ragged.contour_count, ragged.vertex_count) == (2, 7)
    assert ragged.offsets.tolist() == [0, 3, 7]
    assert ragged.vertices.shape == (7, 2)
    assert ragged.bounds() == (0.0, 0.0, 4.0, 3.0)


def test_contours_are_read_only_float64_copies():
    points = np.array(TRIANGLE, dtype=np.int32)
    polygon = Polygon(points)
    points[0] = (9, 9)
    contour = polygon.contours[0]
    assert contour.dtype == np.float64 and contour[0].tolist() == [0.0, 0.0]
    with pytest.raises(ValueError, match="read-only"):
        contour[0, 0] = 1.0


def test_edges_close_each_contour():
    edges = [(c, i, a.tolist(), b.tolist()) for c, i, a, b in Polygon(TRIANGLE).edges()]
    assert edges == [
        (0, 0, [0.0, 0.0], [4.0, 0.0]),
        (0, 1, [4.0, 0.0], [4.0, 3.0]),
        (0, 2, [4.0, 3.0], [0.0, 0.0]),
    ]


def test_equality_copy_and_repr():
    polygon = Polygon([TRIANGLE, [(1, 1), (2, 1), (2, 2)]])
    assert Polygon(polygon) == polygon
    assert eval(repr(polygon), {"Polygon": Polygon}) == polygon
    assert Polygon(TRIANGLE) != Polygon(TRIANGLE[::-1])
    with pytest.raises(TypeError):
        hash(polygon)


def test_coordinate_limit_is_inclusive():
    edge = Polygon([(-COORD_LIMIT, -COORD_LIMIT), (COORD_LIMIT, 0), (0, COORD_LIMIT)])
    assert edge.bounds() == (-COORD_LIMIT, -COORD_LIMIT, COORD_LIMIT, COORD_LIMIT)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_non_finite_coordinate_names_contour_and_vertex(bad):
    with pytest.raises(ValueError, match=r"contour 1 vertex 2 is not finite"):
        Polygon([TRIANGLE, [(0, 0), (1, 0), (bad, 1), (0, 1)]])


@pytest.mark.parametrize("far", [COORD_LIMIT + 1, -COORD_LIMIT - 0.5, 1e300])
def test_coordinate_beyond_limit_names_contour_and_vertex(far):
    with pytest.raises(ValueError, match=r"contour 0 vertex 1 .* beyond the coordinate limit"):
        Polygon([(0, 0), (far, 0), (0, 1)])


@pytest.mark.parametrize(
    ("contours", "message"),
    [
        (
            [(0, 0, 0), (1, 0, 0), (0, 1, 0)],
            r"contour 0 must be an \(N, 2\) array; got shape \(3, 3\)",
        ),
        ([TRIANGLE, [1, 2, 3]], r"contour 1 must be an \(N, 2\) array; got shape \(3,\)"),
        (np.zeros((2, 3, 2, 2)), r"'contours' must be an \(N, 2\) array or a list"),
        ([], r"'contours' must hold at least one contour"),
        ([(0, 0), (1, 1)], r"contour 0 has 2 distinct vertices; a contour needs at least 3"),
        ([(0, 0), (1, 1), (0, 0), (1, 1)], r"contour 0 has 2 distinct vertices"),
        ([TRIANGLE, [(5, 5)] * 4], r"contour 1 has 1 distinct vertices"),
    ],
    ids=["N-by-3", "flat", "4-d", "empty", "two-points", "two-distinct", "one-distinct"],
)
def test_bad_shapes_raise_value_error_naming_the_rule(contours, message):
    with pytest.raises(ValueError, match=message):
        Polygon(contours)


def test_non_numbers_raise_type_error():
    with pytest.raises(TypeError, match=r"contour 0 must be an \(N, 2\) array of numbers"):
        Polygon([[("a", "b"), (1, 0), (0, 1)]])


@pytest.mark.parametrize("huge", [10**400, 2**1024, -(2**1024), 2**20 + 1])
def test_issue8_d8_huge_python_ints_name_the_vertex_and_the_limit(huge):
    with pytest.raises(ValueError, match=r"contour 0 vertex 1 = .* limit of \+-2\*\*20"):
        Polygon([(0, 0), (huge, 0), (0, 1)])


@pytest.mark.parametrize(
    "bad",
    [1 + 7j, 1j, "4", "0", True, np.bool_(False), None, b"1", [0], {"x": 1}],
    ids=lambda v: type(v).__name__,
)
def test_issue8_d9_non_real_coordinates_are_refused_naming_the_vertex(bad):
    with pytest.raises(
        TypeError, match=r"contour 0 must be an \(N, 2\) array of numbers.*vertex 1"
    ):
        Polygon([(0, 0), (bad, 0), (0, 1)])


@pytest.mark.parametrize("dtype", [complex, bool, "U3", "datetime64[s]"])
def test_issue8_d9_arrays_of_non_real_dtype_are_refused(dtype):
    with pytest.raises(TypeError, match=r"got dtype"):
        Polygon(np.zeros((3, 2), dtype=dtype))


def test_issue8_d9_ragged_contours_name_the_vertex_of_the_wrong_length():
    with pytest.raises(ValueError, match=r"contour 0 vertex 1 has 3 coordinates"):
        Polygon([(0, 0), (1, 0, 5), (0, 1)])
    with pytest.raises(ValueError, match=r"contour 1 vertex 2 has 1 coordinates"):
        Polygon([TRIANGLE, [(0, 0), (1, 0), (1,), (0, 1)]])


def test_issue8_d9_real_numbers_of_any_kind_are_accepted_exactly():
    from fractions import Fraction

    polygon = Polygon([(np.int8(0), np.uint64(0)), (Fraction(1, 4), np.float32(0.5)), (0, 2**20)])
    assert polygon.contours[0].tolist() == [[0.0, 0.0], [0.25, 0.5], [0.0, 2.0**20]]
    objects = np.array([(0, 0), (4, 0), (-0.0, 4)], dtype=object)
    assert Polygon(objects).contours[0].tolist() == [[0.0, 0.0], [4.0, 0.0], [-0.0, 4.0]]
    with pytest.raises(ValueError, match="beyond"):
        Polygon(np.array([(0, 0), (1, 0), (np.iinfo(np.int64).min, 1)]))


def test_issue8_fuzz_nesting_deeper_than_numpy_holds_is_a_shape_error():
    # Found by the fuzz campaign: 33+ levels made numpy raise RuntimeError (32 dimensions).
    for depth in (40, 5000):
        value = 0
        for _ in range(depth):
            value = [value]
        with pytest.raises(ValueError, match=r"contour 0 must be an \(N, 2\) array; .*vertex 0"):
            Polygon(value)


EDGE_VALUES = [0.0, -0.0, 1.5, -7.0, COORD_LIMIT, -COORD_LIMIT, COORD_LIMIT + 1, -COORD_LIMIT - 0.5]
EDGE_VALUES += [math.nan, math.inf, -math.inf, 1e300]


def _checked(array) -> tuple:
    try:
        result = geometry.as_coordinates(array, "contour 0", ("N", 2))
    except (TypeError, ValueError) as error:
        return type(error), str(error)
    assert result is not array and result.flags.writeable  # always a new, writable copy
    return result.dtype, result.tolist()


@settings(max_examples=settings.default.max_examples)
@given(
    values=st.lists(st.sampled_from(EDGE_VALUES), min_size=6, max_size=6),
    dtype=st.sampled_from(["float64", "float32", "int64", "int32", "uint64", "int16", "object"]),
)
def test_fast_check_returns_and_raises_as_the_detailed_check(values, dtype):
    # `_within_limit` lets valid input skip the per-coordinate fault codes: same result, same errors.
    array = np.array(values, dtype=object).reshape(3, 2)
    if dtype != "object":
        with np.errstate(invalid="ignore", over="ignore"):
            array = np.array(values).reshape(3, 2).astype(dtype)
        if dtype[0] in "iu" and not np.array_equal(array, np.reshape(values, (3, 2))):
            return  # not values of that integer dtype
    fast = _checked(array)
    with mock.patch.object(geometry, "_within_limit", lambda raw: False):
        assert _checked(array) == fast


# --- issue 27: ndarray subclasses at the coordinate gate -------------------------------------------

with warnings.catch_warnings():
    warnings.simplefilter("ignore", PendingDeprecationWarning)  # np.matrix: what users still pass
    MATRIX = np.matrix(TRIANGLE)
MASKED = np.ma.masked_array(TRIANGLE, mask=[[0, 0], [0, 1], [0, 0]], dtype=float)


def test_issue27_a_matrix_is_taken_as_a_plain_array():
    array = geometry.as_coordinates(MATRIX, "'triangle'", (3, 2))
    assert type(array) is np.ndarray and array.tolist() == [[0, 0], [4, 0], [4, 3]]
    samples = raster.triangle_samples(MATRIX, 6, 6)  # indexed a matrix's rows as (1, 2) before
    plain = raster.triangle_samples(TRIANGLE, 6, 6)
    assert samples.xs.tolist() == plain.xs.tolist() and samples.ys.tolist() == plain.ys.tolist()


GATED = {
    "Polygon": Polygon,
    "as_coordinates": lambda v: geometry.as_coordinates(v, "'points'", ("N", 2)),
    "scan_convert": lambda v: raster.scan_convert(v, 8, 8),
    "fill_polygons": lambda v: raster.fill_polygons([v], 8, 8),
    "rasterize_triangles": lambda v: raster.rasterize_triangles(v[None], 8, 8),
    "triangle_samples": lambda v: raster.triangle_samples(v, 8, 8),
    "dislop_edge": lambda v: dislop_edge(v, 8, 8),
    "dislop_line": lambda v: dislop_line(v[0], v[1], 8, 8),
}


@pytest.mark.parametrize("entry", GATED.values(), ids=GATED.keys())
def test_issue27_masked_values_are_refused_not_read(entry):
    with pytest.raises(
        ValueError, match="masked array with 1 masked value; fill the masked values"
    ):
        entry(MASKED)


@pytest.mark.parametrize("entry", GATED.values(), ids=GATED.keys())
def test_issue27_a_masked_array_with_nothing_masked_is_its_data(entry):
    unmasked = np.ma.masked_array(TRIANGLE, dtype=float)
    plain = entry(np.array(TRIANGLE, dtype=float))
    result = entry(unmasked)
    if isinstance(plain, np.ndarray):
        assert type(result) is np.ndarray and np.array_equal(result, plain)


@pytest.mark.parametrize("dtype", ["m8[s]", "M8[s]", "complex128", "bool", "U3", "S3"])
def test_issue27_times_complex_bool_and_text_dtypes_are_refused(dtype):
    shown = re.escape(str(np.dtype(dtype)))
    with pytest.raises(TypeError, match=rf"^'points' must be .* got dtype {shown}$"):
        geometry.as_coordinates(np.zeros((3, 2), dtype), "'points'", ("N", 2))

"""The shared shape catalog: every shape renders in every mode and means what it says."""

import itertools

import numpy as np
import pytest

from scanviz import Polygon, scan_convert
from scanviz.catalog import SHAPES, Shape, get
from scanviz.conventions import ARITHMETICS, RULES, SAMPLE_MODES
from tests.oracle import oracle_mask

BITS = (0, 3, 8, 16, None)
REQUIRED = {
    "convex",
    "concave",
    "pentagram",
    "bow_tie",
    "square_with_hole",
    "two_squares_overlapping",
    "horizontal_and_vertical_edges",
    "vertices_on_samples",
    "umbc_example",
    "sliver",
    "subpixel",
    "huge",
    "tiny",
    "collinear",
    "repeated_vertices",
}


def mask(shape: Shape, **options) -> np.ndarray:
    return scan_convert(shape.polygon, shape.width, shape.height, **options).mask


def test_catalog_has_the_canonical_and_degenerate_shapes():
    assert REQUIRED <= SHAPES.keys()
    assert any(s.degenerate for s in SHAPES.values())
    for name, shape in SHAPES.items():
        assert shape.name == name and isinstance(shape.polygon, Polygon)
        assert shape.description and "\n" not in shape.description
        assert 0 < shape.width <= 64 and 0 < shape.height <= 64


def test_catalog_is_read_only():
    with pytest.raises(TypeError):
        SHAPES["mine"] = SHAPES["convex"]  # type: ignore[index]


def test_get_unknown_name_lists_the_names():
    assert get("pentagram") is SHAPES["pentagram"]
    with pytest.raises(
        KeyError, match=r"unknown shape 'circle'; known shapes: convex, .*pentagram"
    ):
        get("circle")


@pytest.mark.parametrize("name", SHAPES)
def test_every_mode_renders_and_exact_mode_matches_the_oracle(name):
    shape = get(name)
    covered = set()
    for sample, rule, arithmetic, bits in itertools.product(SAMPLE_MODES, RULES, ARITHMETICS, BITS):
        result = mask(shape, sample=sample, rule=rule, arithmetic=arithmetic, subpixel_bits=bits)
        if arithmetic == "exact":
            expected = oracle_mask(shape.polygon, shape.width, shape.height, sample, rule, bits)
            np.testing.assert_array_equal(result, expected, err_msg=f"{sample} {rule} {bits}")
            covered.add(int(result.sum()))
    # Degenerate shapes cover nothing anywhere; the others cover something in some mode.
    assert (covered == {0}) == shape.degenerate, covered


def test_pentagram_centre_is_in_for_nonzero_only():
    shape = get("pentagram")
    nonzero, evenodd = mask(shape, rule="nonzero"), mask(shape, rule="evenodd")
    assert nonzero[16, 16] and not evenodd[16, 16]
    assert (evenodd <= nonzero).all() and nonzero.sum() > evenodd.sum()


def test_bow_tie_lobes_wind_once_so_rules_agree():
    shape = get("bow_tie")
    np.testing.assert_array_equal(mask(shape, rule="nonzero"), mask(shape, rule="evenodd"))
    assert mask(shape).any()


@pytest.mark.parametrize("rule", RULES)
def test_square_with_hole_leaves_the_hole_uncovered(rule):
    result = mask(get("square_with_hole"), rule=rule)
    assert not result[12:21, 12:21].any()  # samples strictly inside the hole [11.25, 20.75]
    assert result[4:29, 4:12].all() and result[4:29, 21:29].all()


def test_two_squares_overlap_is_out_for_evenodd_only():
    shape = get("two_squares_overlapping")
    nonzero, evenodd = mask(shape, rule="nonzero"), mask(shape, rule="evenodd")
    assert nonzero[12:20, 12:20].all() and not evenodd[12:20, 12:20].any()
    np.testing.assert_array_equal(nonzero[:12], evenodd[:12])


def test_rectilinear_shape_owns_its_lower_and_left_edges():
    result = mask(get("horizontal_and_vertical_edges"))
    expected = np.zeros((32, 32), dtype=bool)
    expected[4:10, 4:24] = True
    expected[10:26, 4:10] = True
    np.testing.assert_array_equal(result, expected)


def test_repeated_vertices_render_like_the_plain_square():
    square = Polygon([(5.5, 5.5), (20.5, 5.5), (20.5, 20.5), (5.5, 20.5)])
    for sample in SAMPLE_MODES:
        expected = scan_convert(square, 24, 24, sample=sample).mask
        np.testing.assert_array_equal(mask(get("repeated_vertices"), sample=sample), expected)


def test_subpixel_triangle_holds_only_the_centre_of_its_pixel():
    shape = get("subpixel")
    assert not mask(shape, sample="corner").any()
    assert np.argwhere(mask(shape, sample="center")).tolist() == [[5, 5]]


def test_tiny_triangle_covers_its_sample_only_unsnapped():
    shape = get("tiny")
    assert np.argwhere(mask(shape, subpixel_bits=None)).tolist() == [[8, 8]]
    for bits in (0, 8, 16):
        assert not mask(shape, subpixel_bits=bits).any()


@pytest.mark.parametrize("arithmetic", ARITHMETICS)
def test_huge_triangle_covers_the_whole_raster(arithmetic):
    assert mask(get("huge"), arithmetic=arithmetic).all()

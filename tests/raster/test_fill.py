"""Fill variants of the UMBC slides: solid, pattern, colour wash, vertex colours; traced == compiled."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import scan_convert
from scanviz.raster.fill import ColourWash, Pattern, Solid, VertexColours, fill_polygon

TRIANGLE = [(1.25, 1.5), (14.5, 3.0), (6.0, 12.75)]
SQUARE_WITH_HOLE = [[(1, 1), (13, 1), (13, 11), (1, 11)], [(4, 4), (4, 8), (10, 8), (10, 4)]]


def covered(mask):
    ys, xs = np.nonzero(mask)
    return xs, ys


def test_solid_fills_the_samples_scan_convert_covers():
    result = fill_polygon(SQUARE_WITH_HOLE, 15, 13, Solid((0.2, 0.4, 0.6)), rule="evenodd")
    mask = scan_convert(SQUARE_WITH_HOLE, 15, 13, rule="evenodd").mask
    np.testing.assert_array_equal(result.mask, mask)
    np.testing.assert_array_equal(result.image[mask], np.tile([0.2, 0.4, 0.6], (mask.sum(), 1)))
    assert (result.image[~mask] == 0).all() and not mask[6, 6]  # the hole stays background


def test_the_slides_checker_is_x_plus_y_mod_2():
    c1, c2 = (1.0, 0.5, 0.0), (0.0, 0.25, 1.0)
    result = fill_polygon(TRIANGLE, 16, 14, Pattern.checker(c1, c2))
    xs, ys = covered(result.mask)
    want = np.where(((xs + ys) % 2 == 1)[:, None], c1, c2)
    np.testing.assert_array_equal(result.image[ys, xs], want)


def test_a_screen_pattern_stays_and_a_polygon_pattern_moves_with_the_polygon():
    rng = np.random.default_rng(3)
    tile = rng.random((3, 5, 3))
    moved = [(x + 7, y + 4) for x, y in TRIANGLE]
    for anchor, shift in (("screen", (0, 0)), ("polygon", (7, 4))):
        a = fill_polygon(TRIANGLE, 30, 24, Pattern(tile, anchor))
        b = fill_polygon(moved, 30, 24, Pattern(tile, anchor))
        xs, ys = covered(a.mask)
        assert b.mask[ys + 4, xs + 7].all() and b.mask.sum() == a.mask.sum()
        if anchor == "screen":
            np.testing.assert_array_equal(a.image[ys, xs], tile[ys % 3, xs % 5])
            np.testing.assert_array_equal(b.image[ys + 4, xs + 7], tile[(ys + 4) % 3, (xs + 7) % 5])
        else:
            np.testing.assert_array_equal(b.image[ys + shift[1], xs + shift[0]], a.image[ys, xs])
            np.testing.assert_array_equal(a.image[ys, xs], tile[(ys - 1) % 3, (xs - 1) % 5])


def test_a_colour_wash_is_linear_across_the_polygon():
    wash = ColourWash((1, 0, 0), (0, 0, 1), direction=(1.0, 0.5))
    result = fill_polygon(TRIANGLE, 16, 14, wash)
    xs, ys = covered(result.mask)
    along = np.array(TRIANGLE) @ [1.0, 0.5]
    t = (xs + 0.5 * ys - along.min()) / np.ptp(along)  # corner sampling: pixel (x, y) at (x, y)
    want = np.array([1, 0, 0]) + t[:, None] * np.array([-1, 0, 1])
    np.testing.assert_allclose(result.image[ys, xs], want, atol=1e-12)


def test_vertex_colours_are_the_barycentric_blend():
    colours = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    result = fill_polygon(TRIANGLE, 16, 14, VertexColours(colours))
    xs, ys = covered(result.mask)
    (ax, ay), (bx, by), (cx, cy) = TRIANGLE
    area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
    beta = ((xs - ax) * (cy - ay) - (cx - ax) * (ys - ay)) / area
    gamma = ((bx - ax) * (ys - ay) - (xs - ax) * (by - ay)) / area
    want = (
        (1 - beta - gamma)[:, None] * colours[0]
        + beta[:, None] * colours[1]
        + gamma[:, None] * colours[2]
    )
    np.testing.assert_allclose(result.image[ys, xs], want, atol=1e-12)


def test_the_wash_is_carried_in_the_aet():
    trace = fill_polygon(TRIANGLE, 16, 14, ColourWash(), trace=True).trace
    assert len(trace.of_kind("edge_values")) and len(trace.of_kind("span_values"))
    assert len(fill_polygon(TRIANGLE, 16, 14, Solid(), trace=True).trace.of_kind("span"))


coordinate = st.floats(0, 24, allow_nan=False).map(lambda v: round(v * 16) / 16)


@settings(max_examples=30)
@given(
    st.lists(st.tuples(coordinate, coordinate), min_size=3, max_size=6),
    st.sampled_from(["corner", "center"]),
    st.integers(0, 3),
)
def test_traced_equals_compiled(vertices, sample, which):
    rng = np.random.default_rng(len(vertices))
    fill = [
        Solid((0.5, 0.25, 1.0)),
        Pattern(rng.random((2, 3, 3)), "polygon"),
        ColourWash((0, 1, 0), (1, 0, 1), (0.3, -1.0)),
        VertexColours(rng.random((len(vertices), 3))),
    ][which]
    try:
        fast = fill_polygon(vertices, 24, 24, fill, sample=sample)
    except ValueError as error:  # fewer than 3 distinct vertices
        assert "distinct" in str(error)
        return
    slow = fill_polygon(vertices, 24, 24, fill, sample=sample, trace=True)
    np.testing.assert_array_equal(fast.image, slow.image)
    np.testing.assert_array_equal(fast.mask, slow.mask)


def test_bad_fills_are_clear_errors():
    with pytest.raises(
        TypeError, match="'fill' must be a Solid, Pattern, ColourWash or VertexColours"
    ):
        fill_polygon(TRIANGLE, 8, 8, (1, 0, 0))
    with pytest.raises(ValueError, match="'color' must be an RGB triple in \\[0, 1\\]"):
        Solid((1.5, 0, 0))
    with pytest.raises(ValueError, match="'tile' must be an \\(h, w, 3\\) RGB array"):
        Pattern(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="'anchor'"):
        Pattern.checker(anchor="polygons")
    with pytest.raises(ValueError, match="'direction' must be a nonzero"):
        ColourWash(direction=(0, 0))
    with pytest.raises(ValueError, match="one colour per vertex: 3; got 2"):
        fill_polygon(TRIANGLE, 8, 8, VertexColours([[0, 0, 0], [1, 1, 1]]))
    with pytest.raises(ValueError, match="takes a polygon of one contour; got 2"):
        fill_polygon(SQUARE_WITH_HOLE, 8, 8, ColourWash())
    with pytest.raises(ValueError, match="'background'"):
        fill_polygon(TRIANGLE, 8, 8, background=(0, 0, 2))

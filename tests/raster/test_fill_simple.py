"""`fill_polygons`' edge-by-edge path for simple polygons against the AET and the reference.

A polygon proven simple (`star_orientation`, else `simple_orientation`) is
marked edge by edge without an active edge table (`mark_simple`); the others
still go through the AET. Both must give the coverage the traced reference
gives: random stars (simple, either orientation, partly off the raster),
random self-intersecting polygons, degenerate ones (repeated vertices,
touching edges, collinear runs, contours winding twice round their centre),
and more polygons on one sample than one batch of int8 or int16 marks holds.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LinearRing

from scanviz import Polygon, fill_polygons, rasterize_triangles, scan_convert
from scanviz.conventions import RULES, SAMPLE_MODES
from scanviz.raster import scan_compiled, simple_fill
from scanviz.raster.fixed import snap

WIDTH, HEIGHT = 40, 32


def mask_sum(polygons, width, height, **options) -> np.ndarray:
    total = np.zeros((height, width), np.int32)
    for polygon in polygons:
        total += scan_convert(polygon, width, height, **options).mask
    return total


def aet_marks_sum(polygons, width, height, sample, rule, bits) -> np.ndarray:
    """The old path: every polygon through `scan_polygon`'s marks, then the row sums."""
    marks = np.zeros((height, width), np.int32)
    for polygon in polygons:
        s = snap(Polygon(polygon), sample, bits)
        scan_compiled.scan_polygon(
            np.array(s.units), s.offsets, s.scale, width, height, rule == "evenodd", True,
            np.float64, marks, 0,
        )  # fmt: skip
    return np.cumsum(marks, axis=1, dtype=np.int32)


def simple_marks_sum(polygon, width, height, sample, bits) -> np.ndarray | None:
    """The new path alone, whatever it costs: `mark_simple`'s marks summed, or None if not simple."""
    s = snap(Polygon(polygon), sample, bits)
    turn = orientation(polygon, sample, bits)
    if not turn:
        return None
    marks = np.zeros((height, width), np.int16)
    simple_fill.mark_simple(np.array(s.units), 0, len(s.units), s.scale, turn, marks)
    return np.cumsum(marks, axis=1, dtype=np.int32)


def orientation(polygon, sample="corner", bits=8) -> int:
    s = snap(Polygon(polygon), sample, bits)
    boxes = np.empty((4, len(s.units)), np.int64)
    return simple_fill.simple_orientation(np.array(s.units), 0, len(s.units), boxes)


def star_orientation(polygon, sample="corner", bits=8) -> int:
    s = snap(Polygon(polygon), sample, bits)
    return simple_fill.star_orientation(np.array(s.units), 0, len(s.units))


def assert_proof_sound(vertices, turn) -> None:
    """A nonzero orientation proves the snapped contour simple, turning that way (shapely)."""
    if turn:
        ring = LinearRing(vertices)
        assert ring.is_simple
        assert turn == (1 if ring.is_ccw else -1)


@st.composite
def stars(draw) -> np.ndarray:
    """A star: sorted angles, radii alternating, center anywhere near the raster; maybe clockwise."""
    n = draw(st.integers(3, 40))
    angles = np.sort(draw(st.lists(st.floats(0, 2 * np.pi), min_size=n, max_size=n, unique=True)))
    outer = draw(st.floats(2, 60))
    inner = draw(st.lists(st.floats(0.1, 1), min_size=n, max_size=n))
    radii = np.where(np.arange(n) % 2 == 0, outer, outer * np.array(inner))
    center = np.array([draw(st.floats(-10, WIDTH + 10)), draw(st.floats(-10, HEIGHT + 10))])
    star = center + radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)])
    return star[::-1] if draw(st.booleans()) else star


@settings(max_examples=3 * settings.default.max_examples)
@given(
    drawn=st.lists(stars(), min_size=1, max_size=6),
    sample=st.sampled_from(SAMPLE_MODES),
    rule=st.sampled_from(RULES),
    bits=st.sampled_from([0, 4, 8]),
)
def test_stars_equal_the_aet_and_the_reference(drawn, sample, rule, bits):
    polygons = [p for p in drawn if len(np.unique(p, axis=0)) >= 3]
    options = dict(sample=sample, rule=rule, subpixel_bits=bits)
    image = fill_polygons(polygons, WIDTH, HEIGHT, **options)
    np.testing.assert_array_equal(image, mask_sum(polygons, WIDTH, HEIGHT, **options))
    np.testing.assert_array_equal(image, aet_marks_sum(polygons, WIDTH, HEIGHT, sample, rule, bits))
    for polygon in polygons:  # each simple one alone, edge by edge, as the AET has it
        alone = simple_marks_sum(polygon, WIDTH, HEIGHT, sample, bits)
        if alone is not None:
            expected = aet_marks_sum([polygon], WIDTH, HEIGHT, sample, rule, bits)
            np.testing.assert_array_equal(alone, expected)


@settings(max_examples=3 * settings.default.max_examples)
@given(
    vertices=st.lists(
        st.tuples(st.integers(-8, WIDTH + 8), st.integers(-8, HEIGHT + 8)), min_size=3, max_size=30
    ),
    rule=st.sampled_from(RULES),
)
def test_random_polygons_equal_the_reference_and_simple_means_simple(vertices, rule):
    if len(set(vertices)) < 3:
        return
    image = fill_polygons([vertices], WIDTH, HEIGHT, rule=rule, subpixel_bits=0)
    np.testing.assert_array_equal(
        image, mask_sum([vertices], WIDTH, HEIGHT, rule=rule, subpixel_bits=0)
    )
    assert_proof_sound(vertices, orientation(vertices, bits=0))
    assert_proof_sound(vertices, star_orientation(vertices, bits=0))


@settings(max_examples=2 * settings.default.max_examples)
@given(drawn=stars(), bits=st.sampled_from([0, 4, 8]))
def test_star_proof_is_sound_and_agrees_with_the_pairwise_proof(drawn, bits):
    if len(np.unique(drawn, axis=0)) < 3:
        return
    snapped = snap(Polygon(drawn), "corner", bits).pixel_vertices()
    star, pairwise = star_orientation(drawn, bits=bits), orientation(drawn, bits=bits)
    assert_proof_sound(snapped, star)
    if star and pairwise:
        assert star == pairwise
    alone = simple_marks_sum(drawn, WIDTH, HEIGHT, "corner", bits)
    if star and alone is None:  # proven simple by the star test only: mark it as such
        s = snap(Polygon(drawn), "corner", bits)
        marks = np.zeros((HEIGHT, WIDTH), np.int8)
        simple_fill.mark_simple(np.array(s.units), 0, len(s.units), s.scale, star, marks)
        expected = aet_marks_sum([drawn], WIDTH, HEIGHT, "corner", "nonzero", bits)
        np.testing.assert_array_equal(np.cumsum(marks, axis=1, dtype=np.int32), expected)


def regular(points, step=1, radius=10.0, center=(16.0, 16.0)) -> list:
    """Vertices k * step of a regular `points`-gon: a star polygon {points/step}."""
    angles = 2 * np.pi * step * np.arange(points) / points
    return [(center[0] + radius * np.cos(a), center[1] + radius * np.sin(a)) for a in angles]


@pytest.mark.parametrize(
    "vertices, star",
    [
        (regular(7), 1),  # convex: star-shaped round any inner point
        (regular(7)[::-1], -1),
        (regular(5, 2), 0),  # a pentagram winds twice round its centre: not simple
        (regular(7, 3)[::-1], 0),
        ([(2, 2), (11, 2), (20, 2), (20, 18), (2, 18)], 1),  # straight on: still simple
        ([(2, 2), (30, 2), (30, 4), (16, 4), (16, 30), (14, 30), (14, 4), (2, 4)], 1),  # a T
        ([(0, 0), (30, 0), (30, 30), (20, 30), (20, 5), (10, 5), (10, 30), (0, 30)], 0),  # a U
        ([(0, 0), (20, 0), (20, 20), (10, 10), (0, 20)], 1),  # a vertex at the box centre
        ([(0, 0), (20, 0), (20, 20), (10, 14), (0, 20)], 1),  # a notch, the centre still seen
        ([(0, 0), (20, 0), (20, 20), (10, 20), (10, 20), (0, 20)], 0),  # a repeated vertex
    ],
)
def test_star_proof_examples(vertices, star):
    assert star_orientation(vertices, bits=0) == star
    assert_proof_sound(vertices, star)
    for rule in RULES:
        image = fill_polygons([vertices], WIDTH, HEIGHT, rule=rule, subpixel_bits=0)
        expected = mask_sum([vertices], WIDTH, HEIGHT, rule=rule, subpixel_bits=0)
        np.testing.assert_array_equal(image, expected)


@pytest.mark.parametrize(
    "vertices",
    [
        [(2, 2), (20, 2), (20, 2), (20, 18), (2, 18)],  # a repeated vertex
        [(2, 2), (11, 2), (20, 2), (20, 18), (2, 18)],  # straight on at (11, 2)
        [(2, 2), (20, 2), (20, 18), (11, 2), (2, 18)],  # a vertex on another edge
        [(2, 2), (20, 18), (20, 2), (2, 18)],  # a bow tie
        [(2, 2), (11, 10), (20, 2), (20, 18), (11, 10), (2, 18)],  # touching at a vertex
        [(2, 2), (20, 2), (20, 18), (2, 18), (2, 10), (30, 10), (2, 10)],  # a spike back
    ],
)
def test_degenerate_polygons_take_the_aet_and_equal_the_reference(vertices):
    assert orientation(vertices, bits=0) == 0
    assert_proof_sound(vertices, star_orientation(vertices, bits=0))
    for rule in RULES:
        image = fill_polygons([vertices], WIDTH, HEIGHT, rule=rule)
        np.testing.assert_array_equal(image, mask_sum([vertices], WIDTH, HEIGHT, rule=rule))


def test_simple_polygons_are_proven_simple_both_ways_round():
    square = [(1, 1), (9, 1), (9, 7), (1, 7)]
    assert orientation(square) == 1
    assert orientation(square[::-1]) == -1
    big = [(-(2**20), -(2**20)), (2**20, -(2**20)), (0, 2**20)]  # 2**29 units at 8 bits
    assert orientation(big) == 1
    assert orientation(big, bits=16) == 0  # 2**37 units: beyond int64 turns, left to the AET
    np.testing.assert_array_equal(
        fill_polygons([big], 16, 16, subpixel_bits=16), mask_sum([big], 16, 16, subpixel_bits=16)
    )


@pytest.mark.parametrize(
    "count",
    [2**7 - 1, 2**7, 2**15 - 1, 2**15 + 3],  # all in int8 marks, in int16, one batch, then two
)
def test_many_polygons_on_one_sample_keep_exact_counts(count):
    rng = np.random.default_rng(5)
    corners = rng.uniform(2.5, 5.9, (count, 1, 2))
    squares = corners + np.array([(0, 0), (4, 0), (4, 4), (0, 4)], float)  # all cover (6, 6)
    triangles = np.concatenate([squares[:, [0, 1, 2]], squares[:, [0, 2, 3]]])
    image = fill_polygons(squares, 12, 12)
    assert image[6, 6] == count
    np.testing.assert_array_equal(image, rasterize_triangles(triangles, 12, 12))

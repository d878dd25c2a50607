"""The common machinery of the visibility algorithms: planes, pieces and cuts, the three paint modes.

Oracles: each polygon drawn alone by the z-buffer (its coverage, depths and
values), exact Fraction planes, and the painting orders written out by hand
(last writer wins for "over", first for "under").
"""

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.visibility import Piece, ScreenPolygons, Surfaces, zbuffer
from scanviz.visibility.draw_decisions import fill, paint
from tests.visibility.support import polygon_depths, random_scene

W, H = 24, 20


def scene_of(seed, n=6, interpenetrating=True):
    return random_scene(np.random.default_rng(seed), n, W, interpenetrating)


def test_planes_are_the_exact_planes_of_the_snapped_vertices():
    polygons = ScreenPolygons.from_polygons([[(0.3, 0.1, 0.2), (9.7, 1.2, 0.6), (2.2, 8.9, 0.9)]])
    surfaces = Surfaces.of(polygons, W, H)
    v = [tuple(Fraction(float(c)) for c in row) for row in surfaces.vertices(0)]
    (x0, y0, z0), (x1, y1, z1), (x2, y2, z2) = v
    det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    dzdx = ((z1 - z0) * (y2 - y0) - (z2 - z0) * (y1 - y0)) / det
    dzdy = ((x1 - x0) * (z2 - z0) - (x2 - x0) * (z1 - z0)) / det
    for x, y in [(0, 0), (5, 3), (23, 19)]:
        exact = z0 + dzdx * (x - x0) + dzdy * (y - y0)
        assert abs(surfaces.depth(0, x, y) - float(exact)) < 1e-14
    assert float(surfaces.vertices(0)[1, 0]) == 9.69921875  # snapped to 1/256: 2483/256


def test_drawn_leaves_out_edge_on_and_off_raster_polygons():
    polygons = ScreenPolygons.from_polygons(
        [
            [(1, 1, 0.5), (8, 1, 0.5), (1, 8, 0.5)],
            [(1, 1, 0.5), (4, 4, 0.5), (8, 8, 0.5)],  # collinear: seen edge-on
            [(30, 30, 0.5), (40, 30, 0.5), (30, 40, 0.5)],  # off the raster
        ]
    )
    surfaces = Surfaces.of(polygons, W, H)
    assert surfaces.drawn.tolist() == [True, False, False]
    assert [p.label for p in surfaces.pieces()] == ["0"]


def test_classify_against_a_plane():
    polygons = ScreenPolygons.from_polygons(
        [
            [(0, 0, 0.5), (10, 0, 0.5), (0, 10, 0.5)],  # the plane z = 0.5
            [(2, 2, 0.9), (6, 2, 0.9), (2, 6, 0.9)],  # behind it
            [(2, 2, 0.1), (6, 2, 0.1), (2, 6, 0.1)],  # in front
            [(3, 3, 0.5), (7, 3, 0.5), (3, 7, 0.5)],  # on it
            [(2, 2, 0.1), (6, 2, 0.9), (2, 6, 0.1)],  # through it
        ]
    )
    surfaces = Surfaces.of(polygons, W, H)
    pieces = surfaces.pieces()
    assert [surfaces.classify(p, 0) for p in pieces[1:]] == ["behind", "front", "on", "straddles"]
    front, behind = surfaces.split(pieces[4], 0)
    assert (front.label, behind.label) == ("4a", "4b")
    assert (surfaces.gaps(front, 0) <= 1e-12).all()
    assert (surfaces.gaps(behind, 0) >= -1e-12).all()
    # the cut is the line z = 0.5 on the slope from x = 2 (0.1) to x = 6 (0.9): x = 4
    assert sorted({round(float(x), 9) for x in behind.vertices[:, 0]}) == [4.0, 6.0]


@settings(max_examples=25)
@given(st.integers(0, 10**6))
def test_split_pieces_partition_their_polygon_s_samples(seed):
    polygons = scene_of(seed, n=2)
    if polygons.count < 2:
        return
    surfaces = Surfaces.of(polygons, W, H)
    whole = [p for p in surfaces.pieces() if p.polygon == 0]
    if not whole or not surfaces.drawn[1]:
        return
    front, behind = surfaces.split(whole[0], 1)
    alone = polygon_depths(polygons, W, H)[0]
    counts = np.zeros((H, W), int)
    for piece in (front, behind):
        painted = paint(surfaces, [piece], "over")
        counts += painted.polygon >= 0
        kept = painted.polygon >= 0  # each piece draws its polygon's own depths where it draws
        assert np.array_equal(painted.depth[kept], alone[kept])
    assert np.array_equal(counts, np.isfinite(alone).astype(int))


def _covering_orders(polygons, order):
    """Per sample: the last (over) and first (under) polygon of `order` that covers it."""
    covered = np.isfinite(polygon_depths(polygons, W, H))
    last = np.full((H, W), -1)
    first = np.full((H, W), -1)
    for p in order:
        last[covered[p]] = p
    for p in reversed(order):
        first[covered[p]] = p
    return last, first


@settings(max_examples=20)
@given(st.integers(0, 10**6), st.sampled_from([True, None]))
def test_over_is_last_writer_and_under_first_writer(seed, trace):
    polygons = scene_of(seed)
    surfaces = Surfaces.of(polygons, W, H)
    pieces = surfaces.pieces()[::-1]
    last, first = _covering_orders(polygons, [p.polygon for p in pieces])
    over = paint(surfaces, pieces, "over", trace=trace)
    under = paint(surfaces, pieces, "under", trace=trace)
    assert np.array_equal(over.polygon, last) and np.array_equal(under.polygon, first)
    assert over.stats.path == ("traced reference" if trace else "compiled")


@settings(max_examples=20)
@given(st.integers(0, 10**6), st.booleans())
def test_fill_with_the_z_buffer_s_ids_is_the_z_buffer(seed, perspective):
    polygons = scene_of(seed)
    reference = zbuffer(polygons, W, H, perspective=perspective)
    surfaces = Surfaces.of(polygons, W, H, perspective=perspective)
    for trace in (None, True):
        filled = fill(surfaces, reference.polygon, trace=trace)
        assert np.array_equal(filled.polygon, reference.polygon)
        assert np.array_equal(filled.depth, reference.depth)
        assert np.array_equal(filled.values, reference.values)


@settings(max_examples=20)
@given(st.integers(0, 10**6))
def test_cut_pieces_paint_the_same_traced_and_compiled(seed):
    polygons = scene_of(seed, n=4)
    surfaces = Surfaces.of(polygons, W, H)
    pieces: list[Piece] = []
    for piece in surfaces.pieces():
        others = [q for q in range(polygons.count) if q != piece.polygon and surfaces.drawn[q]]
        if others and surfaces.classify(piece, others[0]) == "straddles":
            pieces.extend(surfaces.split(piece, others[0]))
        else:
            pieces.append(piece)
    for mode in ("over", "under"):
        compiled = paint(surfaces, pieces, mode)
        traced = paint(surfaces, pieces, mode, trace=True)
        assert np.array_equal(compiled.polygon, traced.polygon)
        assert np.array_equal(compiled.depth, traced.depth)
        assert np.array_equal(compiled.values, traced.values)
        assert compiled.stats.fragments == traced.stats.fragments


def test_paint_arguments_are_checked():
    surfaces = Surfaces.of(scene_of(1), W, H)
    with pytest.raises(ValueError, match="'mode' must be one of"):
        paint(surfaces, surfaces.pieces(), "sideways")
    with pytest.raises(ValueError, match="'target' is needed for mode 'target'"):
        paint(surfaces, surfaces.pieces(), "target")

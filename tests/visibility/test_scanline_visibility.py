"""Scanline visibility: the z-buffer's image, exact spans, coherence that changes nothing, the trace."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import render
from scanviz.io import load_scene
from scanviz.trace import Recorder, Trace
from scanviz.visibility import ScreenPolygons, Surfaces, examples, solve, zbuffer
from scanviz.visibility.scanline_visibility import Scanline, ScanlineStats
from tests.visibility.support import assert_agrees, polygon_depths, random_scene

SIZE = 24
SAMPLES = st.sampled_from(["corner", "center"])


def nearest_oracle(polygons, width, height, **options):
    """(H, W) ids by definition: per sample, the least (plane depth, index) of the polygons covering it.

    Coverage is each polygon drawn alone by the z-buffer; the depths are the
    planes `Surfaces.depth` evaluates, compared sample by sample.
    """
    covered = np.isfinite(polygon_depths(polygons, width, height, **options))
    surfaces = Surfaces.of(polygons, width, height, **options)
    ids = np.full((height, width), -1, np.int64)
    for y in range(height):
        for x in range(width):
            over = np.flatnonzero(covered[:, y, x]).tolist()
            if over:
                ids[y, x] = min(over, key=lambda p: (surfaces.depth(p, x, y), p))
    return ids


def scene(seed, n, interpenetrating):
    return random_scene(np.random.default_rng(seed), n, SIZE, interpenetrating)


# --- agreement with the z-buffer --------------------------------------------------------------


@settings(max_examples=12)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), sample=SAMPLES)
def test_agrees_with_the_zbuffer_without_interpenetration(seed, n, sample):
    polygons = scene(seed, n, False)
    assert_agrees("scanline", polygons, SIZE, SIZE, sample=sample)


@settings(max_examples=12)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 9), sample=SAMPLES)
def test_agrees_with_the_zbuffer_through_interpenetration(seed, n, sample):
    polygons = scene(seed, n, True)
    result, _, _ = assert_agrees("scanline", polygons, SIZE, SIZE, sample=sample)
    assert np.array_equal(result.polygon, nearest_oracle(polygons, SIZE, SIZE, sample=sample))


@pytest.mark.parametrize("compiled", [True, False])
def test_every_sample_is_the_nearest_plane_by_definition(compiled):
    for seed in range(4):
        polygons = scene(seed, 8, True)
        trace = None if compiled else Recorder(kinds=["surface_table_built"])
        result = solve("scanline", polygons, SIZE, SIZE, trace=trace)
        assert np.array_equal(result.polygon, nearest_oracle(polygons, SIZE, SIZE))


@pytest.mark.parametrize(
    ("make", "width", "height"),
    [
        (examples.slides_painter, 16, 12),
        (examples.slides_zbuffer, 10, 9),
        (examples.cyclic_overlap, 24, 24),
        (examples.interpenetrating, 16, 12),
        (examples.long_behind_short, 16, 12),
    ],
)
def test_the_slides_examples_give_the_zbuffers_ids(make, width, height):
    polygons = make()
    result, reference = solve("scanline", polygons, width, height), zbuffer(polygons, width, height)
    assert np.array_equal(result.polygon, reference.polygon)
    assert np.array_equal(result.depth, reference.depth)


def test_interpenetrating_rectangles_are_split_where_they_cross():
    result = solve("scanline", examples.interpenetrating(), 16, 12, trace=Recorder())
    assert result.algorithm.spans_split > 0
    split = [e for e in result.trace if e.kind == "visible_span" and e.split_at is not None]
    assert split and all(e.x_start - 1 <= e.split_at <= e.x_start for e in split)
    # rectangle 0 rises from 0.2 to 0.8 along x, rectangle 1 falls from 0.7 to 0.3: 0 first, then 1
    row = result.polygon[5]
    assert row[3] == 0 and row[12] == 1


# --- spans are the z-buffer's coverage ----------------------------------------------------------


@settings(max_examples=10)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 9), sample=SAMPLES)
def test_the_decided_samples_are_exactly_those_covered(seed, n, sample):
    polygons = scene(seed, n, True)
    result = solve("scanline", polygons, SIZE, SIZE, sample=sample)
    covered = np.isfinite(polygon_depths(polygons, SIZE, SIZE, sample=sample)).any(axis=0)
    assert np.array_equal(result.polygon >= 0, covered)


# --- coherence ----------------------------------------------------------------------------------


def crossing_in_y():
    """Two rectangles with the same vertical edges whose planes cross along y = 6.

    Every row has the same span [2, 14) over the same two surfaces, yet the
    visible one changes at row 6: coherence must not carry it over.
    """
    flat = [(2, 1, 0.5), (14, 1, 0.5), (14, 11, 0.5), (2, 11, 0.5)]
    tilted = [(2, 1, 0.3), (14, 1, 0.3), (14, 11, 0.7), (2, 11, 0.7)]
    return ScreenPolygons.from_polygons([flat, tilted])


def test_coherence_reuses_decisions_but_not_across_a_crossing():
    polygons = crossing_in_y()
    result = solve(Scanline(coherence=True), polygons, 16, 12)
    assert result.algorithm.spans_reused > 0
    assert np.array_equal(result.polygon, zbuffer(polygons, 16, 12).polygon)
    assert result.polygon[5, 8] == 1 and result.polygon[7, 8] == 0


@settings(max_examples=10)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 9), crossing=st.booleans())
def test_coherence_on_or_off_gives_the_same_pixels(seed, n, crossing):
    polygons = scene(seed, n, crossing)
    on = solve(Scanline(coherence=True), polygons, SIZE, SIZE)
    off = solve(Scanline(coherence=False), polygons, SIZE, SIZE)
    assert np.array_equal(on.polygon, off.polygon)
    assert off.algorithm.spans_reused == 0
    needing = on.algorithm.spans_decided + on.algorithm.spans_reused
    assert needing == off.algorithm.spans_decided


def test_coherence_on_the_sphere_unculled():
    # Culled, no two faces of the sphere overlap: no span has two surfaces to decide between.
    sphere = load_scene("builtin:sphere")
    culled = render(sphere, 64, 64, shading="flat", visibility="scanline").visibility.algorithm
    assert isinstance(culled, ScanlineStats) and culled.path == "compiled"
    assert culled.spans_decided == culled.spans_reused == 0
    both = render(sphere, 64, 64, shading="flat", visibility="scanline", cull=False)
    assert 0 < both.visibility.algorithm.spans_reused < both.visibility.algorithm.spans_decided
    assert np.array_equal(both.image, render(sphere, 64, 64, shading="flat", cull=False).image)


# --- traced == untraced, and the trace ----------------------------------------------------------


@settings(max_examples=10)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 9),
    crossing=st.booleans(),
    coherence=st.booleans(),
    sample=SAMPLES,
)
def test_traced_decides_as_untraced(seed, n, crossing, coherence, sample):
    polygons = scene(seed, n, crossing)
    chosen = Scanline(coherence=coherence)
    fast = solve(chosen, polygons, SIZE, SIZE, sample=sample)
    traced = solve(chosen, polygons, SIZE, SIZE, sample=sample, trace=Recorder(kinds=[]))
    assert np.array_equal(fast.polygon, traced.polygon)
    assert np.array_equal(fast.depth, traced.depth)
    assert fast.algorithm.path == "compiled" and traced.algorithm.path == "reference"
    assert {**vars(fast.algorithm), "path": ""} == {**vars(traced.algorithm), "path": ""}
    assert np.array_equal(fast.detail.y_start, traced.detail.y_start)
    assert np.array_equal(fast.detail.y_end, traced.detail.y_end)


@pytest.mark.parametrize("coherence", [True, False])
def test_traced_splits_and_reuses_as_untraced(coherence):
    scenes = [(examples.interpenetrating(), 16, 12), (examples.cyclic_overlap(), 24, 24)]
    scenes += [(random_scene(np.random.default_rng(seed), 14, 40, True), 40, 40) for seed in (1, 2)]
    split = reused = 0
    for polygons, width, height in scenes:
        fast = solve(Scanline(coherence=coherence), polygons, width, height)
        traced = solve(Scanline(coherence=coherence), polygons, width, height, trace=Recorder([]))
        assert np.array_equal(fast.polygon, traced.polygon)
        assert {**vars(fast.algorithm), "path": ""} == {**vars(traced.algorithm), "path": ""}
        split += fast.algorithm.spans_split
        reused += fast.algorithm.spans_reused
    assert split > 0 and (reused > 0) == coherence


def test_the_trace_tiles_each_row_with_its_spans():
    polygons = scene(7, 8, True)
    result = solve("scanline", polygons, SIZE, SIZE, trace=Recorder())
    stats, events = result.algorithm, list(result.trace)
    kinds = [e.kind for e in events]
    assert kinds[0] == "surface_table_built"
    table = events[0].surfaces
    assert [(s.y_start, s.polygon) for s in table] == sorted((s.y_start, s.polygon) for s in table)
    rows = [e for e in events if e.kind == "active_surfaces"]
    assert len(rows) == stats.rows and max(len(e.active) for e in rows) == stats.max_active
    surfaces = Surfaces.of(polygons, SIZE, SIZE)
    spans = [e for e in events if e.kind == "visible_span"]
    assert sum(e.reused for e in spans) == stats.spans_reused
    for row in rows:
        here = [e for e in spans if e.y == row.y]
        assert here[0].x_start == 0 and here[-1].x_end == SIZE
        assert all(a.x_end == b.x_start for a, b in zip(here, here[1:], strict=False))
        for e in here:
            assert set(e.surfaces) <= set(row.active)
            assert (result.polygon[e.y, e.x_start : e.x_end] == e.visible).all()
            assert e.depths == tuple(float(surfaces.depth(p, e.x_start, e.y)) for p in e.surfaces)
    pieces = sum(e.split_at is not None for e in spans)
    assert len(spans) == stats.spans + pieces
    assert list(Trace.from_json(result.trace.to_json())) == events


def test_the_slides_surface_table_and_active_surfaces():
    result = solve("scanline", examples.slides_painter(), 16, 12, trace=Recorder())
    table = result.trace[0].surfaces
    # by first row, then index: the triangle and the rectangle start at row 2, the square at 5
    assert [(s.polygon, s.y_start, s.y_end) for s in table] == [(0, 2, 5), (1, 2, 6), (2, 5, 10)]
    rows = {e.y: e for e in result.trace if e.kind == "active_surfaces"}
    assert rows[2].entered == (0, 1) and rows[2].active == (1, 0)  # sorted on x: 1 starts at x=1
    assert rows[5].exhausted == (0,) and rows[5].entered == (2,)
    assert rows[6].exhausted == (1,) and rows[6].active == (2,)


# --- degenerate input ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "polygons",
    [
        [[(2, 2, 0.5), (12, 2, 0.5), (2, 12, 0.5)], [(2, 2, 0.5), (12, 2, 0.5), (12, 12, 0.5)]],
        [[(2, 2, 0.5), (6, 6, 0.2), (10, 10, 0.9)], [(1, 1, 0.4), (9, 1, 0.4), (1, 9, 0.4)]],
        [
            [(-30, -30, 0.5), (-20, -30, 0.5), (-20, -20, 0.5)],
            [(40, 2, 0.1), (50, 2, 0.1), (45, 9, 0.1)],
        ],
        [[(0, 0, 0.5), (0, 0, 0.5), (0, 0, 0.5)]],
        [[(1, 1, 0.5), (30, 1, 0.5), (30, 30, 0.5), (1, 30, 0.5)]],
        [[(1, 1, 0.5), (13, 13, 0.5), (13, 1, 0.5), (1, 13, 0.5)]],
    ],
    ids=["coplanar", "edge-on", "off-raster", "a-point", "beyond-the-raster", "bowtie"],
)
def test_degenerate_input_renders_as_the_zbuffer(polygons):
    scene_polygons = ScreenPolygons.from_polygons(polygons)
    for trace in (None, Recorder()):
        result = solve("scanline", scene_polygons, 16, 16, trace=trace)
        assert np.array_equal(result.polygon, zbuffer(scene_polygons, 16, 16).polygon)


def test_an_empty_scene_is_background():
    empty = ScreenPolygons.from_polygons([[(0, 0, 0.5), (0, 0, 0.5), (0, 0, 0.5)]])
    result = solve("scanline", empty, 8, 8, trace=Recorder())
    assert (result.polygon == -1).all() and result.algorithm.rows == 0
    assert [e.kind for e in result.trace] == ["surface_table_built"]


def test_the_option_is_checked():
    with pytest.raises(TypeError, match="'coherence' must be a bool"):
        Scanline(coherence="yes")


# --- the pipeline -------------------------------------------------------------------------------


@pytest.mark.parametrize("shading", ["flat", "gouraud", "phong", "gooch"])
def test_render_by_name_is_the_zbuffers_image_on_the_sphere(shading):
    sphere = load_scene("builtin:sphere")
    result = render(sphere, 48, 48, shading=shading, visibility="scanline")
    assert result.visibility.name == "scanline"
    assert np.array_equal(result.image, render(sphere, 48, 48, shading=shading).image)


@pytest.mark.parametrize("ulps", [1, 3, 8, 40])
def test_planes_that_cross_within_rounding_are_decided_sample_by_sample(ulps):
    # Depth differences of a few ulps: the float depths may flicker in sign along the row,
    # so only a certificate that bounds the rounding may decide a whole span at once.
    step = ulps * 2.0**-53
    polygons = []
    for k in range(4):
        low, high = 0.5 - (k + 1) * step, 0.5 + (k + 1) * step
        polygons.append([(1, 1 + k, low), (15, 1 + k, high), (15, 15 - k, high), (1, 15 - k, low)])
    polygons.append([(1, 1, 0.5), (15, 1, 0.5), (15, 15, 0.5), (1, 15, 0.5)])
    scene_polygons = ScreenPolygons.from_polygons(polygons)
    expected = nearest_oracle(scene_polygons, 16, 16)
    for chosen, trace in (
        (Scanline(), None),
        (Scanline(coherence=False), None),
        (Scanline(), Recorder(kinds=[])),
    ):
        result = solve(chosen, scene_polygons, 16, 16, trace=trace)
        assert np.array_equal(result.polygon, expected)

"""The banded, multi-threaded z-buffer: the traced reference's bits with 1 and with 2 threads.

The compiled z-buffer cuts the raster into bands of `BAND_ROWS` rows shared
among numba's threads; each band walks its polygons from their first row.
Random triangle and quadrilateral soups taller than several bands (so that
polygons cross band boundaries, start below the raster and end above it)
must give the traced reference's depth, ids, values and counts exactly,
whatever the thread count.
"""

import numba
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.visibility import ScreenPolygons, zbuffer, zbuffer_compiled
from scanviz.visibility.zbuffer_compiled import BAND_ROWS

BASE = settings.default.max_examples
WIDTH, HEIGHT = 23, 5 * BAND_ROWS + 3  # five whole bands and a partial one
THREADS = sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)})


@st.composite
def soups(draw):
    """Up to 12 triangles/quads, some larger than the raster, with depths, 2 values and 1/w."""
    count = draw(st.integers(1, 12))
    coordinate = st.integers(-3 * 16, (HEIGHT + 6) * 16).map(lambda v: v / 16)
    unit = st.floats(0, 1, allow_nan=False)
    polygons, values, inv_w = [], [], []
    for _ in range(count):
        n = draw(st.sampled_from([3, 3, 4]))
        xy = draw(st.lists(st.tuples(coordinate, coordinate), min_size=n, max_size=n))
        polygons.append([(x, y, draw(unit)) for x, y in xy])
        values.append([[draw(unit), draw(unit)] for _ in range(n)])
        inv_w.append([0.25 + draw(unit) for _ in range(n)])
    return ScreenPolygons.from_polygons(polygons, values, inv_w)


@settings(max_examples=BASE)
@given(polygons=soups(), perspective=st.booleans(), bits=st.sampled_from([0, 4, 8]))
def test_banded_equals_reference_with_any_thread_count(polygons, perspective, bits):
    options = dict(perspective=perspective, subpixel_bits=bits)
    reference = zbuffer(polygons, WIDTH, HEIGHT, trace=True, **options)
    before, least = numba.get_num_threads(), zbuffer_compiled.PARALLEL_WORK
    zbuffer_compiled.PARALLEL_WORK = 0  # the bands go to the threads however small the raster
    try:
        for threads in THREADS:
            numba.set_num_threads(threads)
            compiled = zbuffer(polygons, WIDTH, HEIGHT, **options)
            assert compiled.stats.path == "compiled"
            np.testing.assert_array_equal(compiled.polygon, reference.polygon)
            np.testing.assert_array_equal(compiled.depth, reference.depth)
            np.testing.assert_array_equal(compiled.values, reference.values)
            assert {**vars(compiled.stats), "path": ""} == {**vars(reference.stats), "path": ""}
    finally:
        numba.set_num_threads(before)
        zbuffer_compiled.PARALLEL_WORK = least


def test_a_polygon_across_every_band_and_beyond_the_raster():
    """One quad from below the raster to above it: every band walks it from row 0."""
    top = HEIGHT + 20.0
    quad = [[(-5.0, -9.5, 0.2), (30.0, -9.0, 0.4), (28.0, top + 0.25, 0.9), (-4.0, top, 0.1)]]
    polygons = ScreenPolygons.from_polygons(quad, [[[0.0], [1.0], [2.0], [3.0]]])
    reference = zbuffer(polygons, WIDTH, HEIGHT, trace=True)
    compiled = zbuffer(polygons, WIDTH, HEIGHT)
    assert (compiled.polygon == 0).all()
    np.testing.assert_array_equal(compiled.depth, reference.depth)
    np.testing.assert_array_equal(compiled.values, reference.values)
    assert compiled.stats.rows_scanned == reference.stats.rows_scanned == HEIGHT

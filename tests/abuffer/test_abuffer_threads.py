"""The compiled a-buffer shared among numba's threads: the references' bits with 1 and 2 threads.

`chunk_fragments` runs its two passes (masks and areas per polygon window,
then the fragments) over numba's threads for large chunks; each polygon's
cells and first row are fixed before a pass. `insert_fragments` cuts the
pixel-sorted fragments into runs of whole pixels, one per thread. So random
polygon soups must give `polygon_fragments`' fragments bit for bit, in
drawing order, and random deep stacks the traced reference's lists, whatever
the thread count; the thresholds are patched to 0 so that small inputs take
the threaded paths too.
"""

import numba
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.abuffer import fragments_compiled, pixelstruct_compiled, resolve
from scanviz.pipeline import render
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder

from .test_fragments_compiled import (
    HEIGHT,
    WIDTH,
    assert_identical,
    compiled,
    polygon,
    reference,
    screen_polygons,
    stacks,
)

THREADS = sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)})


def threaded(run):
    """run() with the threaded paths forced, once per thread count; the results."""
    before = numba.get_num_threads()
    least = fragments_compiled.PARALLEL_WORK, pixelstruct_compiled.PARALLEL_FRAGMENTS
    fragments_compiled.PARALLEL_WORK = pixelstruct_compiled.PARALLEL_FRAGMENTS = 0
    try:
        results = []
        for threads in THREADS:
            numba.set_num_threads(threads)
            results.append(run())
        return results
    finally:
        numba.set_num_threads(before)
        fragments_compiled.PARALLEL_WORK, pixelstruct_compiled.PARALLEL_FRAGMENTS = least


@settings(max_examples=25, derandomize=True, deadline=None)
@given(
    st.lists(polygon(), min_size=1, max_size=12),
    st.sampled_from([0, 4]),
    st.sampled_from(["4x4", "8x8"]),
    st.sampled_from([8, None]),
    st.booleans(),
    st.integers(0, 2**32 - 1),
)
def test_threaded_pass_equals_polygon_fragments(polygons, value_count, mask, bits, perspective, seed):  # fmt: skip
    table = screen_polygons(polygons, value_count, np.random.default_rng(seed))
    options = {"mask": mask, "subpixel_bits": bits, "perspective": perspective}
    expected = reference(table, WIDTH, HEIGHT, **options)
    for got in threaded(lambda: compiled(table, WIDTH, HEIGHT, **options)):
        assert_identical(got, expected)


@settings(max_examples=30, derandomize=True, deadline=None)
@given(stacks(), st.sampled_from(["none", "object"]))
def test_threaded_insertion_equals_the_reference(fragments, merge):
    """Deep stacks in 2 pixels: with 2 threads, each pixel's run on its own thread."""
    traced = resolve(fragments, 2, 1, trace=Recorder(), merge=merge)
    for fast in threaded(lambda: resolve(fragments, 2, 1, merge=merge)):
        np.testing.assert_allclose(traced.image, fast.image, rtol=0, atol=1e-12)
        assert {**vars(traced.stats), "path": ""} == {**vars(fast.stats), "path": ""}
        for x in range(2):
            assert traced.pixel(x, 0) == fast.pixel(x, 0)


def test_threaded_render_is_the_one_thread_render(monkeypatch):
    """A terrain render: image, depth, ids and fragment lists equal with 1 and 2 threads."""
    scene = builtin_scene("terrain", n=12)
    options = {"visibility": "abuffer", "shading": "phong", "mask": "8x8"}
    monkeypatch.setattr(fragments_compiled, "PARALLEL_WORK", 2**62)  # the one-thread twins
    monkeypatch.setattr(pixelstruct_compiled, "PARALLEL_FRAGMENTS", 2**62)
    serial = render(scene, 24, 24, **options)
    for fast in threaded(lambda: render(scene, 24, 24, **options)):
        assert np.array_equal(fast.image, serial.image)
        assert np.array_equal(fast.depth, serial.depth)
        assert np.array_equal(fast.polygon, serial.polygon)
        assert vars(fast.abuffer.stats) == vars(serial.abuffer.stats)
        for name in ("head", "next", "zmin", "zmax", "area", "mask", "color"):
            assert np.array_equal(
                getattr(fast.abuffer.table, name), getattr(serial.abuffer.table, name)
            )

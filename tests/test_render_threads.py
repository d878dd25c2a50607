"""`render`'s compiled path against its traced reference on random scenes, with 1 and 2 threads.

The compiled z-buffer shares bands of rows among numba's threads and the
Phong model runs compiled; neither may change a bit. Random triangle soups
(some faces crossing the near plane or the window, so clipping runs; some
facing away; point and directional lights; perspective and orthographic
cameras) are rendered with ``trace=True`` and without, and must give the
same ids and depths bit for bit and the same image to 1e-12, whatever the
thread count.
"""

import dataclasses

import numba
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import render
from scanviz.pipeline import shade as shade_module
from scanviz.raster import interpolate
from scanviz.scene.model import Camera, Light, Material, Mesh, Scene, SceneObject
from scanviz.shading import shade_compiled as s_kernels
from scanviz.visibility import zbuffer_compiled as z_kernels

BASE = settings.default.max_examples
THREADS = sorted({1, min(2, numba.config.NUMBA_NUM_THREADS)})


@st.composite
def soups(draw):
    """A scene of 1..8 random triangles near the view volume, random material, lights, camera."""
    count = draw(st.integers(1, 8))
    coordinate = st.floats(-1.6, 1.6, allow_nan=False)
    positions = np.array(
        draw(
            st.lists(
                st.tuples(coordinate, coordinate, st.floats(-1.0, 4.5)),
                min_size=3 * count,
                max_size=3 * count,
            )
        )  # fmt: skip
    )
    faces = [np.array([3 * i, 3 * i + 1, 3 * i + 2]) for i in range(count)]
    material = Material(
        color=tuple(draw(st.lists(st.floats(0, 1), min_size=3, max_size=3))),
        specular=draw(st.floats(0, 1)),
        exponent=draw(st.sampled_from([1.0, 8.0, 33.5])),
        fudge=draw(st.sampled_from([0.0, 0.5])),
    )
    mesh = Mesh(positions, faces, smooth=draw(st.booleans()), closed=draw(st.booleans()))
    lights = [Light(direction=(0.3, -0.2, -1.0))]
    if draw(st.booleans()):
        lights.append(Light(kind="point", position=(0.5, 1.0, 3.0), color=(0.6, 0.5, 0.4)))
    camera = Camera(
        eye=(0.2, 0.1, 5.0), near=1.0, far=9.0, projection=draw(st.sampled_from(["perspective", "orthographic"]))
    )  # fmt: skip
    return Scene((SceneObject(mesh, material),), camera=camera, lights=tuple(lights))


@settings(max_examples=BASE, deadline=None)
@given(scene=soups(), shading=st.sampled_from(["flat", "gouraud", "phong"]))
def test_compiled_render_is_the_traced_one_with_any_thread_count(scene, shading):
    traced = render(scene, 21, 37, shading=shading, trace=True)
    before = numba.get_num_threads()
    least = (
        z_kernels.PARALLEL_WORK,
        s_kernels.PARALLEL_POINTS,
        shade_module.PARALLEL_PIXELS,
        interpolate.PARALLEL_VERTICES,
    )
    # Threads however small the scene: the bands, the shading and the image gather.
    z_kernels.PARALLEL_WORK = s_kernels.PARALLEL_POINTS = shade_module.PARALLEL_PIXELS = 0
    interpolate.PARALLEL_VERTICES = 0
    try:
        for threads in THREADS:
            numba.set_num_threads(threads)
            compiled = render(scene, 21, 37, shading=shading)
            assert compiled.stats.path == "compiled" and traced.stats.path == "reference"
            np.testing.assert_array_equal(compiled.polygon, traced.polygon)
            np.testing.assert_array_equal(compiled.depth, traced.depth)
            np.testing.assert_allclose(compiled.image, traced.image, rtol=0, atol=1e-12)
            assert dataclasses.replace(compiled.stats, path="") == dataclasses.replace(
                traced.stats, path=""
            )
    finally:
        numba.set_num_threads(before)
        (
            z_kernels.PARALLEL_WORK,
            s_kernels.PARALLEL_POINTS,
            shade_module.PARALLEL_PIXELS,
            interpolate.PARALLEL_VERTICES,
        ) = least

"""Render benchmark: the large built-in mesh at 1024 x 1024 through the z-buffer.

scanviz's compiled path (flat, Gouraud, Phong) is timed end to end
(`scanviz.render` with no tracer: cull, transform, clip, rasterize, z-buffer,
shade). When moderngl and Mesa's EGL (llvmpipe) are installed, the same mesh
is drawn through Mesa in the same run with equivalent shaders (per-face,
per-vertex and per-pixel Phong lighting of one directional light), and the
time ratio printed. Mesa's time includes the draw and `glFinish`, not the
upload of the mesh, which is done once.
"""

from __future__ import annotations

import dataclasses

import numba
import numpy as np

from ..pipeline import render
from ..progress import progress
from ..scene.builtin import builtin_scene
from ..transform import clip_from_eye, eye_from_world
from . import best_time

SIZE = 1024

_VERTEX = """
#version 330
uniform mat4 clip_from_world;
in vec3 position; in vec3 normal; in vec3 color;
out vec3 v_normal; out vec3 v_position; flat out vec3 v_flat; out vec3 v_color;
void main() {
    gl_Position = clip_from_world * vec4(position, 1.0);
    gl_Position.z = 2.0 * gl_Position.z - gl_Position.w;  // scanviz depth [0, w] -> GL [-w, w]
    v_normal = normal; v_position = position; v_flat = color; v_color = color;
}
"""
_FRAGMENT = """
#version 330
uniform int mode; uniform vec3 light_dir; uniform vec3 eye;
in vec3 v_normal; in vec3 v_position; flat in vec3 v_flat; in vec3 v_color;
out vec4 color;
void main() {
    if (mode == 0) { color = vec4(v_flat, 1.0); return; }
    if (mode == 1) { color = vec4(v_color, 1.0); return; }
    vec3 n = normalize(v_normal); vec3 l = -normalize(light_dir);
    vec3 v = normalize(eye - v_position); vec3 r = 2.0 * dot(n, l) * n - l;
    float d = max(dot(n, l), 0.0);
    color = vec4(vec3(0.1 + 0.7 * d + (d > 0.0 ? 0.3 * pow(max(dot(r, v), 0.0), 32.0) : 0.0)), 1.0);
}
"""


def _mesa(scene):
    """A function drawing `scene`'s first object through Mesa per mode, or None if unavailable."""
    try:
        import moderngl

        ctx = moderngl.create_standalone_context(backend="egl")
    except Exception as error:  # no moderngl, no EGL, no driver: all mean "not measured"
        return (
            None,
            f"Mesa not measured ({type(error).__name__}: {str(error).splitlines()[0][:60]})",
        )
    obj = scene.objects[0]
    matrix = obj.world_from_model
    world = obj.mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]
    triangles = np.array([f for f in obj.mesh.faces if len(f) == 3])
    normals = np.zeros_like(world)
    face_n = np.cross(
        world[triangles[:, 1]] - world[triangles[:, 0]],
        world[triangles[:, 2]] - world[triangles[:, 0]],
    )
    for k in range(3):
        np.add.at(normals, triangles[:, k], face_n)
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    corners = triangles.reshape(-1)
    data = np.hstack([world[corners], normals[corners], np.full((len(corners), 3), 0.7)]).astype(
        "f4"
    )
    program = ctx.program(vertex_shader=_VERTEX, fragment_shader=_FRAGMENT)
    clip = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    program["clip_from_world"].write(clip.T.astype("f4").tobytes())
    program["light_dir"].value = (0.0, 0.0, -1.0)
    program["eye"].value = tuple(scene.camera.eye)
    vao = ctx.vertex_array(
        program, [(ctx.buffer(data.tobytes()), "3f 3f 3f", "position", "normal", "color")]
    )
    target = ctx.simple_framebuffer((SIZE, SIZE))
    target.use()
    ctx.enable(moderngl.DEPTH_TEST)

    def draw(mode: int) -> None:
        program["mode"].value = mode
        target.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
        vao.render(moderngl.TRIANGLES)
        ctx.finish()

    return draw, ctx.info["GL_RENDERER"]


def _fresh(scene):
    """`scene` with new (equal) objects: their world-space data is made again on first render."""
    objects = tuple(dataclasses.replace(o) for o in scene.objects)
    return dataclasses.replace(scene, objects=objects)


def run_render(*, quick: bool = False) -> list[dict]:
    """Time each shading mode on the large mesh, print the table, return its rows.

    "ms" is a render of a scene rendered before (its objects' world-space
    faces, normals and materials are kept with them, as Mesa keeps the mesh
    it was given once); "first ms" renders new, equal objects, so it includes
    that work. Each compiled image is checked against the same render on one
    thread (the traced reference is checked against both in the tests).
    """
    scene = builtin_scene("terrain")
    size = 256 if quick else SIZE
    triangles = scene.triangle_count()
    mesa, mesa_info = _mesa(scene) if not quick else (None, "Mesa not measured (--quick)")
    threads = numba.get_num_threads()
    print(
        f"render benchmark: builtin:terrain, {triangles} triangles, {size}x{size}, z-buffer, "
        f"compiled path, {threads} threads (median of runs)"
    )
    header = f"{'shading':<9}{'ms':>8}{'first ms':>10}{'Mtri/s':>8}{'Mpx/s':>8}{'visible px':>12}{'1 thread':>10}"
    if mesa is not None:
        header += f"{'Mesa ms':>9}{'ratio':>8}"
    print(header)
    rows = []
    with progress(3, "render bench", threshold=0 if not quick else 10) as bar:
        for mode, shading in enumerate(("flat", "gouraud", "phong")):
            seconds = best_time(lambda s=shading: render(scene, size, size, shading=s), repeat=5)
            first = best_time(
                lambda s=shading: render(_fresh(scene), size, size, shading=s), repeat=3
            )
            result = render(scene, size, size, shading=shading)
            numba.set_num_threads(1)
            try:
                alone = render(scene, size, size, shading=shading)
            finally:
                numba.set_num_threads(threads)
            same = (
                np.array_equal(alone.polygon, result.polygon)
                and np.array_equal(alone.depth, result.depth)
                and np.array_equal(alone.image, result.image)
            )
            visible = int((result.polygon >= 0).sum())
            row = {"shading": shading, "ms": seconds * 1e3, "first_ms": first * 1e3, "visible": visible,
                   "threads": threads, "same_as_one_thread": same}  # fmt: skip
            line = (
                f"{shading:<9}{seconds * 1e3:>8.1f}{first * 1e3:>10.1f}{triangles / seconds / 1e6:>8.2f}"
                f"{visible / seconds / 1e6:>8.2f}{visible:>12}{'same' if same else 'DIFFERS':>10}"
            )
            if mesa is not None:
                theirs = best_time(lambda m=mode: mesa(m), repeat=5)
                row |= {"mesa_ms": theirs * 1e3, "ratio": theirs / seconds}
                line += f"{theirs * 1e3:>9.1f}{theirs / seconds:>7.2f}x"
            bar.write(line)
            bar.update(1)
            rows.append(row)
    print(f"Mesa: {mesa_info}" if mesa is not None else mesa_info)
    print("ratio = Mesa time / scanviz time (> 1: scanviz is faster); Mpx/s counts visible pixels;")
    print(
        "first ms: new objects, world-space normals and faces made again (Mesa's upload is not timed)"
    )
    return rows

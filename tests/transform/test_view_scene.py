"""The viewing pipeline of a whole scene, stop by stop (`scanviz.pipeline.viewing.view_scene`).

Expected values come from computations written here: the look-at basis, the
frustum projection, the back-face test with cross products, the clip planes,
and `prepare` (the renderer's own path) for the polygons that reach the screen.
"""

import dataclasses
import math

import numpy as np
import pytest

from scanviz.pipeline import prepare
from scanviz.pipeline.viewing import STOPS, view_scene, view_volume
from scanviz.scene import Camera
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import Recorder, Trace
from scanviz.transform.examples import viewing_scene


@pytest.fixture(scope="module")
def scene():
    return viewing_scene()


@pytest.fixture(scope="module")
def traced(scene):
    recorder = Recorder()
    return view_scene(scene, 64, 64, trace=recorder), recorder.trace()


def look_at(eye, target, up):
    """World -> eye by hand: rows right, up, backward, then the eye moved to the origin."""
    eye, target, up = (np.asarray(v, float) for v in (eye, target, up))
    backward = (eye - target) / np.linalg.norm(eye - target)
    right = np.cross(up, backward)
    right /= np.linalg.norm(right)
    true_up = np.cross(backward, right)
    rotation = np.array([right, true_up, backward])
    return rotation, -rotation @ eye


def world_faces(scene):
    """Every face's world vertices, object by object (no object here is mirrored)."""
    faces = []
    for obj in scene.objects:
        world = obj.mesh.positions @ obj.world_from_model[:3, :3].T + obj.world_from_model[:3, 3]
        faces += [world[list(face)] for face in obj.mesh.faces]
    return faces


def test_eye_space_is_the_look_at_of_the_camera(scene, traced):
    viewed, _ = traced
    rotation, shift = look_at(scene.camera.eye, scene.camera.look_at, scene.camera.up)
    for world, eye in zip(world_faces(scene), viewed.polygons["eye"], strict=True):
        np.testing.assert_allclose(eye, world @ rotation.T + shift, atol=1e-12)
    np.testing.assert_allclose(
        viewed.volume["world"][:4] @ rotation.T + shift, viewed.volume["eye"][:4], atol=1e-12
    )


def test_culled_faces_are_those_turned_away_from_the_eye(scene, traced):
    viewed, trace = traced
    eye = np.array(scene.camera.eye)
    expected = []
    for number, (face, obj) in enumerate(zip(world_faces(scene), viewed.objects, strict=True)):
        normal = np.cross(face[1] - face[0], face[2] - face[0])  # planar, counter-clockwise
        if scene.objects[obj].mesh.closed and normal @ (face.mean(axis=0) - eye) >= 0:
            expected.append(number)
    assert expected == [0, 2, 4]  # the cube's -z, -x and -y faces
    assert [k for k, v in enumerate(viewed.verdicts) if v == "culled"] == expected
    culled = [e.polygon for e in trace if e.kind == "face_culled" and e.culled]
    assert culled == expected
    assert [e.polygon for e in trace if e.kind == "face_culled"] == list(range(6))  # cube only


def test_every_verdict_happens_and_the_clipper_sees_every_face_kept(traced):
    viewed, trace = traced
    assert viewed.verdicts == ("culled", "accepted", "culled", "accepted", "culled", "accepted",
                               "clipped", "clipped", "clipped", "clipped", "rejected")  # fmt: skip
    clipped = [(e.polygon, e.verdict) for e in trace if e.kind == "polygon_clipped"]
    kept = [(k, v) for k, v in enumerate(viewed.verdicts) if v != "culled"]
    assert clipped == kept


def test_the_trace_runs_in_pipeline_order_and_round_trips(traced):
    _, trace = traced
    stops = [e.stage for e in trace if e.kind == "polygons_transformed"]
    assert stops == list(STOPS)
    kinds = [e.kind for e in trace]
    assert kinds[0] == "polygons_transformed" and kinds[1:7] == ["face_culled"] * 6
    assert kinds[7:9] == ["polygons_transformed"] * 2  # eye, clip
    assert kinds[9:17] == ["polygon_clipped"] * 8
    assert kinds[17:] == ["polygons_transformed"] * 2  # ndc, display
    assert Trace.from_json(trace.to_json()) == trace


def test_matrices_in_the_events_are_the_viewing_matrices(scene, traced):
    _, trace = traced
    matrices = {e.stage: e.matrix for e in trace if e.kind == "polygons_transformed"}
    assert matrices["world"] is None and matrices["ndc"] is None
    rotation, shift = look_at(scene.camera.eye, scene.camera.look_at, scene.camera.up)
    eye_from_world = np.eye(4)
    eye_from_world[:3, :3], eye_from_world[:3, 3] = rotation, shift
    np.testing.assert_allclose(np.reshape(matrices["eye"], (4, 4)), eye_from_world, atol=1e-12)
    n, f = scene.camera.near, scene.camera.far
    half = 0.45  # the window is (-0.45, 0.45, -0.45, 0.45): symmetric
    projection = [[n / half, 0, 0, 0], [0, n / half, 0, 0], [0, 0, -f / (f - n), -f * n / (f - n)],
                  [0, 0, -1, 0]]  # fmt: skip
    np.testing.assert_allclose(np.reshape(matrices["clip"], (4, 4)), projection, atol=1e-12)
    np.testing.assert_allclose(
        np.reshape(matrices["display"], (4, 4)),
        [[32, 0, 0, 32], [0, 32, 0, 32], [0, 0, 1, 0], [0, 0, 0, 1]],
    )


def test_the_frustum_becomes_the_ndc_box(traced):
    viewed, _ = traced
    box = [(x, y, z) for z in (0, 1) for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    np.testing.assert_allclose(viewed.volume["ndc"], box, atol=1e-12)
    np.testing.assert_allclose(
        viewed.volume["display"], [(32 * (x + 1), 32 * (y + 1), z) for x, y, z in box], atol=1e-9
    )


def test_ndc_polygons_lie_in_the_box_and_new_vertices_on_its_faces(traced):
    viewed, trace = traced
    for ndc in viewed.polygons["ndc"]:
        assert np.all(np.abs(ndc[:, :2]) <= 1 + 1e-12)
        assert np.all((ndc[:, 2] >= -1e-12) & (ndc[:, 2] <= 1 + 1e-12))
    for event in (e for e in trace if e.kind == "polygon_clipped" and e.verdict == "clipped"):
        given = {tuple(v) for v in viewed.polygons["clip"][event.polygon]}
        for x, y, z, w in (v for v in event.vertices if tuple(v) not in given):
            on = [abs(x) - w, abs(y) - w, z, z - w]  # on a side, the near or the far plane
            assert min(abs(d) for d in on) <= 1e-12 * max(1.0, abs(w))


def test_the_screen_polygons_are_those_prepare_draws(scene, traced):
    viewed, _ = traced
    prepared = prepare(scene, 64, 64, shading="flat", cull=None).polygons
    drawn = sorted(
        np.column_stack([prepared.xy[a:b], prepared.z[a:b]]).round(9).tolist()
        for a, b in zip(prepared.offsets[:-1], prepared.offsets[1:], strict=True)
    )
    ours = sorted(p.round(9).tolist() for p in viewed.polygons["display"] if len(p))
    assert ours == drawn


def test_cull_false_keeps_every_face_and_an_infinite_far_is_drawn_past_the_scene():
    sphere = builtin_scene("sphere", level=0)
    far_away = dataclasses.replace(sphere, camera=dataclasses.replace(sphere.camera, far=math.inf))
    viewed = view_scene(far_away, 32, 32, cull=False)
    assert "culled" not in viewed.verdicts
    deepest = max(-p[:, 2].min() for p in viewed.polygons["eye"])
    assert deepest < viewed.far < 2 * deepest
    np.testing.assert_allclose(-viewed.volume["eye"][4:, 2], viewed.far)


def test_view_volume_corners():
    corners = view_volume(Camera(window=(-1, 2, -1, 1), near=2.0, far=6.0))
    np.testing.assert_allclose(corners[:4], [(-1, -1, -2), (2, -1, -2), (2, 1, -2), (-1, 1, -2)])
    np.testing.assert_allclose(corners[4:], [(-3, -3, -6), (6, -3, -6), (6, 3, -6), (-3, 3, -6)])
    ortho = view_volume(Camera(window=(-1, 1, -1, 1), near=1.0, far=4.0, projection="orthographic"))
    np.testing.assert_allclose(ortho[4:, :2], ortho[:4, :2])
    with pytest.raises(ValueError, match="'far' must be finite"):
        view_volume(Camera(far=math.inf))

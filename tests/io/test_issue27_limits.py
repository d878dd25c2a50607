"""Issue 27: scene and OBJ readers never block on a special file, and estimate meshes first."""

import json
import os
import tracemalloc

import pytest

from scanviz import cli
from scanviz.io import load_obj, load_scene, obj, read_json, scene_from_dict, scene_json
from scanviz.limits import ResourceLimitError, memory_limit, wall_clock_limit
from scanviz.scene.model import mesh_bytes

TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
CAMERA = {"eye": [0, 0, 5], "look_at": [0, 0, 0]}


class Blocked(BaseException):
    pass


def scene_with_faces(faces: list) -> dict:
    positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]
    return {
        "camera": CAMERA,
        "lights": [],
        "objects": [{"mesh": {"positions": positions, "faces": faces}}],
    }


def refuse(*args, **kwargs):
    raise AssertionError("reached: the estimate should have refused first")


# --- special files -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "read", [load_obj, read_json, load_scene], ids=["load_obj", "read_json", "load_scene"]
)
@pytest.mark.parametrize("name", ["scene.json", "model.obj"])
def test_issue27_readers_refuse_a_fifo_without_blocking(tmp_path, read, name):
    fifo = tmp_path / name
    os.mkfifo(fifo)
    with (
        wall_clock_limit(5, Blocked, f"{read.__name__} blocked on a FIFO"),
        pytest.raises(ValueError, match=r"is a FIFO \(named pipe\), not a regular file"),
    ):
        read(fifo)


def test_issue27_render_of_a_fifo_is_one_line_error(tmp_path, capsys):
    fifo = tmp_path / "p.json"
    os.mkfifo(fifo)
    with wall_clock_limit(5, Blocked, "render blocked on a FIFO"):
        status = cli.main(["render", str(fifo), "-o", str(tmp_path / "out.png")])
    error = capsys.readouterr().err
    assert status == 2 and error.count("\n") == 1, error
    assert "is a FIFO (named pipe), not a regular file" in error


@pytest.mark.parametrize("read", [load_obj, load_scene])
def test_issue27_readers_refuse_dev_zero(read):
    with pytest.raises(ValueError, match="'/dev/zero' is a character device, not a regular file"):
        read("/dev/zero")


# --- OBJ: faces counted before the parse, the mesh estimated before it is built ------------------


def test_issue27_obj_faces_are_counted_before_the_parse(monkeypatch):
    monkeypatch.setattr(obj, "_parse", refuse)
    text = TRIANGLE + "f 1 2 3\n" * 200_000  # 1.6 MB of text for about 90 MB of mesh
    with (
        memory_limit("64M"),
        pytest.raises(ResourceLimitError, match=r"at least 200,000 faces\) needs about"),
    ):
        load_obj(text)


def test_issue27_obj_mesh_is_estimated_from_its_counts_before_it_is_built(monkeypatch):
    monkeypatch.setattr(obj, "Mesh", refuse)
    text = TRIANGLE + "f\t1 2 3\n" * 200_000  # tabs: not counted before the parse
    rule = (
        r"^the mesh of the OBJ text \(200,000 faces, 600,000 corners, 3 vertices\) needs about "
        r".* over the memory limit of 64\.0 MiB"
    )
    with memory_limit("64M"), pytest.raises(ResourceLimitError, match=rule):
        load_obj(text)


def test_issue27_obj_file_mesh_estimate_names_the_file(tmp_path):
    path = tmp_path / "many.obj"
    path.write_text(TRIANGLE + "f\t1 2 3\n" * 200_000)
    with (
        memory_limit("64M"),
        pytest.raises(ResourceLimitError, match=r"^the mesh of '.*many\.obj'"),
    ):
        load_obj(path)


def test_issue27_obj_index_beyond_int64_names_the_line():
    with pytest.raises(ValueError, match=r"^line 4: vertex index 99999999999999999999 is out"):
        load_obj(TRIANGLE + "f 1 2 99999999999999999999\n")


# --- JSON: the parse and the mesh estimated ------------------------------------------------------


def test_issue27_json_scene_mesh_is_estimated_before_it_is_built(monkeypatch):
    monkeypatch.setattr(scene_json, "Mesh", refuse)
    data = scene_with_faces([[0, 1, 2]] * 200_000)
    rule = r"^objects\[0\]\.mesh \(200,000 faces, 600,000 corners, 4 vertices\) needs about"
    with memory_limit("64M"), pytest.raises(ResourceLimitError, match=rule):
        scene_from_dict(data)


def test_issue27_json_scene_file_estimate_names_the_file(tmp_path):
    path = tmp_path / "many.json"
    path.write_text(
        json.dumps(scene_with_faces([[0, 1, 2]] * 150_000))
    )  # parse: 53 MB, mesh: 65 MB
    with memory_limit("56M"), pytest.raises(ResourceLimitError, match=r"^'.*many\.json': objects"):
        load_scene(path)


def test_issue27_json_parse_is_estimated_before_parsing(tmp_path, monkeypatch):
    monkeypatch.setattr(scene_json.json, "loads", refuse)
    path = tmp_path / "big.json"
    path.write_text(json.dumps(scene_with_faces([[0, 1, 2]] * 10_000)))
    with memory_limit("1M"), pytest.raises(ResourceLimitError, match=r"^parsing '.*big\.json' \("):
        read_json(path)


# --- the estimates are honest: they cover the measured peak, and not by more than 2x -------------


def peak_bytes(build) -> int:
    tracemalloc.start()
    try:
        build()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


QUAD_NORMALS = TRIANGLE + "v 1 1 0\nvn 0 0 1\nvn 0 1 0\n"


@pytest.mark.parametrize(
    ("text", "faces", "corners"),
    [
        (TRIANGLE + "f 1 2 3\n" * 20_000, 20_000, 60_000),
        (TRIANGLE + "v 1 1 0\n" + "f 1 2 3 4 1 2 3 4\n" * 20_000, 20_000, 160_000),
        (QUAD_NORMALS + "f 1//1 2//2 3//1 4//2\n" * 20_000, 20_000, 80_000),
    ],
    ids=["triangles", "octagons", "quads with normals"],
)
def test_issue27_obj_estimate_covers_the_measured_peak(text, faces, corners):
    vertices = text.count("\nv ") + 1
    estimate = obj._TEXT_BYTES * len(text) + mesh_bytes(faces, corners, vertices)
    peak = peak_bytes(lambda: load_obj(text))
    assert peak <= estimate <= 2 * peak, (peak, estimate)


@pytest.mark.parametrize("size", [3, 8])
def test_issue27_json_mesh_estimate_covers_the_measured_peak(size):
    data = scene_with_faces([[0, 1, 2, 3, 0, 1, 2, 3][:size]] * 20_000)
    peak = peak_bytes(lambda: scene_from_dict(data))
    estimate = mesh_bytes(20_000, 20_000 * size, 4)
    assert peak <= estimate <= 2 * peak, (peak, estimate)

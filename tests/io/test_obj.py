"""Wavefront OBJ reading: face forms, indices, normals, ignored statements, errors by line."""

import numpy as np
import pytest

from scanviz.io import load_obj

SQUARE = """
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vn 0 0 1
"""


def faces(mesh):
    return [face.tolist() for face in mesh.faces]


@pytest.mark.parametrize(
    "face",
    ["f 1 2 3 4", "f 1/1 2/2 3/3 4/1", "f -4 -3 -2 -1", "f 1/-3 2/2 -2/3 4/1"],
)
def test_faces_without_normals(face):
    mesh = load_obj(SQUARE + face + "\n")
    assert faces(mesh) == [[0, 1, 2, 3]]
    assert mesh.normals is None
    assert mesh.positions.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


@pytest.mark.parametrize("face", ["f 1//1 2//1 3//1 4//1", "f 1/1/1 2/2/-1 3/3/1 -1//1"])
def test_faces_with_normals(face):
    mesh = load_obj(SQUARE + face + "\n")
    assert faces(mesh) == [[0, 1, 2, 3]]
    assert mesh.normals.tolist() == [[0, 0, 1]] * 4


def test_negative_indices_are_relative_to_the_latest_element():
    mesh = load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -4 -3 -1\n")
    assert faces(mesh) == [[0, 1, 2], [0, 1, 3]]


def test_polygons_of_any_size_and_forward_references():
    ring = "".join(f"v {np.cos(a)} {np.sin(a)} 0\n" for a in np.linspace(0, 6, 7))
    mesh = load_obj("f 1 2 3 4 5 6 7\n" + ring)
    assert faces(mesh) == [list(range(7))] and mesh.triangle_count() == 5


def test_comments_continuations_and_ignored_statements():
    text = """# a comment line
mtllib scene.mtl
o square
g side
s 1
usemtl red   # trailing comment
v 0 0 0 1
v 1 0 0 0.5 0.5 0.5
v 1 1 0
v 0 1 0
vp 0.5
l 1 2
p 3
f 1 2 \\
  3 4
"""
    mesh = load_obj(text)
    assert faces(mesh) == [[0, 1, 2, 3]] and len(mesh.positions) == 4


def test_normals_are_normalized():
    mesh = load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 3\nf 1//1 2//1 3//1\n")
    assert mesh.normals.tolist() == [[0, 0, 1]] * 3


CUBE = """
v -1 -1 -1
v 1 -1 -1
v 1 1 -1
v -1 1 -1
v -1 -1 1
v 1 -1 1
v 1 1 1
v -1 1 1
vn 0 0 -1
vn 0 0 1
vn -1 0 0
vn 1 0 0
vn 0 -1 0
vn 0 1 0
f 1//1 4//1 3//1 2//1
f 5//2 6//2 7//2 8//2
f 1//3 5//3 8//3 4//3
f 2//4 3//4 7//4 6//4
f 1//5 2//5 6//5 5//5
f 4//6 8//6 7//6 3//6
"""


def test_positions_used_with_different_normals_are_split():
    mesh = load_obj(CUBE, closed=True)
    assert len(mesh.positions) == 24 and mesh.face_count == 6 and mesh.closed
    expected = [[0, 0, -1], [0, 0, 1], [-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0]]
    corners = {tuple(p) for p in mesh.positions.tolist()}
    assert len(corners) == 8  # each corner now appears once per face normal
    for face, normal in zip(mesh.faces, expected, strict=True):
        assert (mesh.normals[face] == normal).all()
        assert len(set(face.tolist())) == 4
    # a face's corners keep their positions: face 0 is z = -1
    assert (mesh.positions[mesh.faces[0]][:, 2] == -1).all()
    # vertices sorted by position, then normal index: the split copies are adjacent
    assert mesh.positions[:3].tolist() == [[-1, -1, -1]] * 3


def test_consistent_normals_keep_the_file_order():
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0\nvn 1 0 0\nf 3//2 1//1 2//3\n"
    mesh = load_obj(text)
    assert mesh.positions.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    assert faces(mesh) == [[2, 0, 1]]
    assert mesh.normals.tolist() == [[0, 0, 1], [1, 0, 0], [0, 1, 0]]


def test_mixed_normals_are_ignored():
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n"
    mesh = load_obj(text, smooth=False)
    assert mesh.normals is None and not mesh.smooth and len(mesh.positions) == 4


def test_unused_positions_are_kept_without_normals_and_dropped_with_them():
    assert len(load_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\nf 1 2 3\n").positions) == 4
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\nvn 0 0 1\nf 1//1 2//1 3//1\n"
    assert len(load_obj(text).positions) == 3


def test_empty_file_gives_an_empty_mesh():
    mesh = load_obj("# nothing\n")
    assert mesh.positions.shape == (0, 3) and mesh.faces == ()


def test_files(tmp_path):
    path = tmp_path / "square.obj"
    path.write_text(SQUARE + "f 1 2 3 4\n")
    assert faces(load_obj(path)) == faces(load_obj(str(path))) == [[0, 1, 2, 3]]
    (tmp_path / "bad.obj").write_text("v 0 0 0\n\nf 1 2 0\n")
    with pytest.raises(ValueError, match=r"bad\.obj', line 3: vertex index 0 is invalid"):
        load_obj(tmp_path / "bad.obj")
    with pytest.raises(FileNotFoundError):
        load_obj(tmp_path / "missing.obj")
    with pytest.raises(TypeError, match="'source' must be a path or OBJ text"):
        load_obj(b"v 0 0 0\n")


@pytest.mark.parametrize(
    "text, rule",
    [
        (
            "v 0 0 0\nv 1 0 0\nf 1 2 0\n",
            "line 3: vertex index 0 is invalid; OBJ indices start at 1",
        ),
        ("v 0 0 0\nv 1 0 0\nf 1 2 3\n", r"line 3: vertex index 3 is out of range 1..2 \('v' lines"),
        ("v 0 0 0\nv 1 0 0\nf 1 2 -3\n", "line 3: vertex index -3 reaches before the first one"),
        ("v 0 0 0\nv 1 0 0\nf 1 2 x\n", "line 3: vertex index 'x' is not an integer"),
        ("v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3: a face needs >= 3 corners; got 2"),
        (
            "v 0 0 0\nf 1/1/1/1 1 1\n",
            "line 2: face corner '1/1/1/1' is not v, v/vt, v//vn or v/vt/vn",
        ),
        ("v 0 0 0\nf /1 1 1\n", "line 2: face corner '/1' is not"),
        (
            "v 0 0 0\nvn 0 0 1\nf 1//1 1//2 1//1\n",
            r"line 3: normal index 2 is out of range 1..1 \('vn'",
        ),
        ("v 0 0 0\nf 1/0 1 1\n", "line 2: texture index 0 is invalid"),
        ("v 0 0\n", "line 1: 'v' needs x y z, x y z w or x y z r g b; got 2 values"),
        ("v 0 0 a\n", "line 1: 'v' needs numbers; got '0 0 a'"),
        ("\n\nv 0 nan 0\n", "line 3: 'v' values must be finite"),
        ("vn 0 0 0\n", "line 1: 'vn' must not be the zero vector"),
        ("vn 0 1\n", "line 1: 'vn' needs 3 values; got 2"),
        ("v 0 0 0\nbogus 1 2\n", "line 2: unknown statement 'bogus'"),
        ("cstype bspline\n", r"line 1: free-form geometry \('cstype'\) is not supported"),
    ],
)
def test_errors_name_the_line(text, rule):
    with pytest.raises(ValueError, match=rule):
        load_obj(text)


# --- issue 8 -------------------------------------------------------------------------------

TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"


@pytest.mark.parametrize("length", [1e-200, 1e200, 1e-320, 1e308])
def test_issue8_d5_normals_of_any_finite_length_are_normalized(length):
    mesh = load_obj(TRIANGLE + f"vn {length} {length} {length}\nf 1//1 2//1 3//1\n")
    assert np.allclose(mesh.normals, 3**-0.5, rtol=1e-15)


def test_issue8_d11_a_real_file_with_bom_crlf_and_ignored_statements(tmp_path):
    text = (
        "\ufeff# exported\r\nmtllib scene.mtl\r\no cube\r\ng side\r\nusemtl red\r\ns 1\r\n"
        "v 0 0 0\r\nv 1 0 0\r\nv 1 1 \\\r\n  0\r\nv 0 1 0\r\nvt 0 0\r\nvt 1 0 0\r\nvp 0.5\r\n"
        "vn 0 0 2\r\nf 1/1/1 2/2/1 3/1/1 4/2/1 # a quad\r\nl 1 2\r\ns off\r\n"
    )
    path = tmp_path / "cube.obj"
    path.write_bytes(text.encode("utf-8"))
    for mesh in (load_obj(path), load_obj(text)):
        assert faces(mesh) == [[0, 1, 2, 3]]
        assert mesh.positions.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        assert mesh.normals.tolist() == [[0, 0, 1]] * 4


def test_issue8_d11_file_errors_name_the_file(tmp_path):
    path = tmp_path / "latin1.obj"
    path.write_bytes(b"# caf\xe9\nv 0 0 0\n")
    with pytest.raises(ValueError, match=r"latin1.obj' is not UTF-8 text: byte 5 is 0xe9"):
        load_obj(path)
    empty = tmp_path / "empty.obj"
    empty.write_text("")
    assert load_obj(empty).positions.shape == (0, 3) and load_obj(empty).faces == ()


def test_issue8_d13_frame_model_shows_the_whole_model_filling_the_view():
    from scanviz.io import frame_model
    from scanviz.pipeline import render
    from scanviz.transform import vertex_tables

    mesh = load_obj(TRIANGLE + "v 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    for aspect, (width, height) in ((1.0, (64, 64)), (2.0, (128, 64)), (0.5, (32, 64))):
        scene = frame_model(mesh, aspect=aspect, name="tetra")
        camera = scene.camera
        assert camera.projection == "perspective" and camera.look_at == (0.5, 0.5, 0.5)
        display = vertex_tables(camera, mesh.positions, width, height)["display"]
        assert (display[:, 0] > 0).all() and (display[:, 0] < width).all()
        assert (display[:, 1] > 0).all() and (display[:, 1] < height).all()
        # The bounding sphere (radius sqrt(3)/2) spans 1 / 1.1 of the smaller side.
        distance = np.linalg.norm(np.subtract(camera.eye, camera.look_at))
        assert distance == pytest.approx(1.1 * 3**0.5 / 2 / np.sin(np.radians(20)))
        image = render(scene, width, height).image
        covered = (image != np.array(scene.background)).any(axis=2)
        assert covered.any() and not (covered[0].any() or covered[-1].any())
        assert not (covered[:, 0].any() or covered[:, -1].any())

"""The JSON scene format: exact round trips, transform order, and errors that name the path."""

import copy
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from scanviz.io import load_scene, scene_from_dict, scene_to_dict
from scanviz.scene import (
    BUILTIN_SCENES,
    Camera,
    Light,
    Material,
    Mesh,
    Scene,
    SceneObject,
    builtin_scene,
    icosphere,
)

DOCS = Path(__file__).parents[2] / "docs" / "scene-format.md"


def assert_same_scene(a, b):
    """Every field equal, arrays exactly (Mesh, SceneObject and Scene compare by identity)."""
    assert (a.name, a.camera, a.lights, a.ambient, a.background) == (
        b.name,
        b.camera,
        b.lights,
        b.ambient,
        b.background,
    )
    assert len(a.objects) == len(b.objects)
    for x, y in zip(a.objects, b.objects, strict=True):
        assert (x.name, x.material) == (y.name, y.material)
        assert np.array_equal(x.world_from_model, y.world_from_model)
        m, n = x.mesh, y.mesh
        assert np.array_equal(m.positions, n.positions) and m.positions.dtype == n.positions.dtype
        assert [f.tolist() for f in m.faces] == [f.tolist() for f in n.faces]
        for key in ("normals", "face_materials", "vertex_materials"):
            p, q = getattr(m, key), getattr(n, key)
            assert (p is None and q is None) or np.array_equal(p, q), key
        assert (m.smooth, m.closed, m.materials) == (n.smooth, n.closed, n.materials)


def through_json(scene):
    return scene_from_dict(json.loads(json.dumps(scene_to_dict(scene), allow_nan=False)))


@pytest.fixture(scope="module")
def builtins():
    return {name: builtin_scene(name) for name in BUILTIN_SCENES}


@pytest.mark.parametrize("name", list(BUILTIN_SCENES))
def test_every_builtin_round_trips_exactly(builtins, name):
    assert_same_scene(through_json(builtins[name]), builtins[name])


def test_a_scene_using_every_field_round_trips_exactly():
    palette = (Material(color=(1, 0, 0)), Material(color=(0.1, 0.2, 0.3), fudge=0.25))
    sphere = icosphere(1)
    mesh = Mesh(
        sphere.positions,
        sphere.faces,
        normals=sphere.normals,
        smooth=False,
        closed=False,
        face_materials=np.arange(sphere.face_count) % 3 - 1,
        vertex_materials=np.arange(len(sphere.positions)) % 2,
        materials=palette,
    )
    angle = 0.1
    rotation = np.eye(4)
    rotation[:2, :2] = [[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]]
    scene = Scene(
        (
            SceneObject(mesh, Material(exponent=7.5, transparency=1 / 3), rotation, "odd"),
            SceneObject(Mesh([[0, 0, 0], [1e-300, 0, 0], [0, 1e11, 0]], [[2, 1, 0]])),
        ),
        Camera(
            eye=(0.1, 0.2, 0.3),
            look_at=(1, 2, 3),
            up=(0, 0, 1),
            window=(-0.5, 1 / 3, -0.25, 0.25),
            near=-1.5,
            far=2.5,
            projection="orthographic",
        ),
        lights=(Light("point", (0.5, 2, 0), (1, 2, 3)), Light(direction=(1e-9, 0, 0))),
        ambient=(0.1, 0.2, 0.3),
        background=(1, 1, 1),
        name="everything",
    )
    assert_same_scene(through_json(scene), scene)


def test_documented_example_loads():
    blocks = re.findall(r"```json\n(.*?)```", DOCS.read_text(), re.DOTALL)
    scene = scene_from_dict(json.loads(blocks[0]))
    assert [o.name for o in scene.objects] == ["table", "ball", "ring", "card"]
    card = scene.objects[3].mesh
    assert card.materials[0] == Material(color=(1, 0, 0), ambient=1, diffuse=0, specular=0)
    assert card.face_materials.tolist() == [0, 1]
    assert scene.objects[1].material.exponent == 50
    ring = scene.objects[2].world_from_model
    assert np.array_equal(ring[:3, :3], [[1, 0, 0], [0, 0, -1], [0, 1, 0]])  # exact 90 degrees


def test_documented_errors_are_the_real_ones():
    section = DOCS.read_text().split("## Errors")[1].split("```text\n")[1].split("```")[0]
    messages = [message for _, _, message in ERROR_CASES.values()]
    for line in section.splitlines():
        if line.startswith("objects[0].mesh.obj:"):
            continue  # tested in test_obj_paths_start_at_the_scene_file
        if line.endswith("..."):  # an abbreviated message
            assert any(m.startswith(line[:-3]) for m in messages), line
        else:
            assert line in messages, line


def base():
    return {
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
        "lights": [{"kind": "point", "position": [1, 2, 3]}],
        "materials": {"brass": {"color": [0.8, 0.6, 0.1]}, "glass": {"transparency": 0.5}},
        "objects": [
            {"mesh": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]]}}
            for _ in range(3)
        ],
    }


def test_defaults_and_palette():
    scene = scene_from_dict(base())
    assert scene.camera == Camera(eye=(0, 0, 5)) and scene.name == ""
    assert scene.objects[0].material == Material()
    data = base()
    data["objects"][1]["material"] = "glass"
    assert scene_from_dict(data).objects[1].material == Material(transparency=0.5)


def transform_of(*steps):
    data = base()
    data["objects"][0]["transform"] = list(steps)
    return scene_from_dict(data).objects[0].world_from_model


def test_transform_steps_apply_in_order():
    scale_then_move = transform_of({"scale": 2}, {"translate": [1, 0, 0]})
    assert (scale_then_move @ [1, 0, 0, 1]).tolist() == [3, 0, 0, 1]
    move_then_scale = transform_of({"translate": [1, 0, 0]}, {"scale": 2})
    assert (move_then_scale @ [1, 0, 0, 1]).tolist() == [4, 0, 0, 1]
    assert np.array_equal(transform_of(), np.eye(4))
    assert transform_of({"scale": [1, 2, -3]}).diagonal().tolist() == [1, 2, -3, 1]


def test_rotation_is_right_handed_and_exact_at_quarter_turns():
    quarter = transform_of({"rotate": {"axis": [0, 0, 2], "degrees": 90}})
    assert (quarter @ [1, 0, 0, 1]).tolist() == [0, 1, 0, 1]
    assert (
        transform_of({"rotate": {"axis": [1, 0, 0], "degrees": -270}}) @ [0, 1, 0, 1]
    ).tolist() == [
        0,
        0,
        1,
        1,
    ]
    turn = transform_of({"rotate": {"axis": [1, 1, 1], "degrees": 120}})
    assert np.allclose(turn @ [1, 0, 0, 1], [0, 1, 0, 1])  # cycles the axes
    assert np.allclose(turn[:3, :3] @ turn[:3, :3].T, np.eye(3))


def test_matrix_step_is_taken_as_rows():
    matrix = [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]]
    assert transform_of({"matrix": matrix}).tolist() == matrix
    composed = transform_of({"matrix": matrix}, {"translate": [1, 1, 1]})
    assert (composed @ [1, 0, 0, 1]).tolist() == [6, 8, 8, 1]


def test_builtin_mesh_and_overrides():
    data = base()
    data["objects"][0]["mesh"] = {"builtin_mesh": "icosphere", "level": 1, "closed": False}
    data["objects"][1]["mesh"] = {"builtin_mesh": "box", "size": [1, 2, 3]}
    data["objects"][2]["mesh"] = {"builtin_mesh": "terrain", "n": 4, "seed": 7, "smooth": False}
    first, second, third = scene_from_dict(data).objects
    assert first.mesh.triangle_count() == 80 and not first.mesh.closed
    assert second.mesh.positions.max(axis=0).tolist() == [0.5, 1, 1.5]
    assert third.mesh.triangle_count() == 32 and not third.mesh.smooth


def test_obj_paths_start_at_the_scene_file(tmp_path):
    (tmp_path / "models").mkdir()
    (tmp_path / "models" / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    data = base()
    data["objects"][0]["mesh"] = {"obj": "models/tri.obj", "closed": True}
    (tmp_path / "scene.json").write_text(json.dumps(data))
    mesh = load_scene(tmp_path / "scene.json").objects[0].mesh
    assert mesh.closed and mesh.triangle_count() == 1
    assert scene_from_dict(data, base_dir=tmp_path).objects[0].mesh.closed
    (tmp_path / "models" / "tri.obj").write_text("v 0 0 0\nv 1 0 0\n\nf 1 2 0\n")
    with pytest.raises(
        ValueError, match=r"objects\[0\]\.mesh\.obj: .*tri\.obj', line 4: vertex index 0"
    ):
        load_scene(str(tmp_path / "scene.json"))
    data["objects"][0]["mesh"]["obj"] = "models/none.obj"
    with pytest.raises(FileNotFoundError, match=r"objects\[0\]\.mesh\.obj"):
        scene_from_dict(data, base_dir=tmp_path)


def test_files_name_themselves_in_errors(tmp_path):
    path = tmp_path / "nan.json"
    text = json.dumps(base()).replace('"eye": [0, 0, 5]', '"eye": [0, NaN, 5]')
    path.write_text(text)
    with pytest.raises(ValueError, match=r"nan\.json': camera\.eye\[1\] must be finite; got nan"):
        load_scene(path)
    path.write_text(json.dumps(base()).replace('"look_at"', '"look_at": [0, 0, 0], "lookat"'))
    with pytest.raises(ValueError, match=r"nan\.json': camera has an unknown key 'lookat'"):
        load_scene(path)
    path.write_text("{ not json")
    with pytest.raises(ValueError, match=r"nan\.json': not valid JSON: .*line 1 column 3"):
        load_scene(path)
    with pytest.raises(TypeError, match="'source' must be a path, a dict or 'builtin:NAME'"):
        load_scene(3)
    with pytest.raises(TypeError, match="'scene' must be a scanviz.scene.Scene"):
        scene_to_dict(base())


def setter(path, value):
    """A mutation of base() that sets (or with value=DELETE, deletes) the value at `path`."""

    def mutate(data):
        *parents, last = path
        for key in parents:
            data = data[key]
        if value is DELETE:
            del data[last]
        else:
            data[last] = value

    return mutate


DELETE = object()
NAN, INF = math.nan, math.inf
MESH = ("objects", 0, "mesh")

# name: (mutation, error type, message); each message names the JSON path and the rule.
ERROR_CASES = {
    "scene not an object": (lambda d: d.clear() or d.update(x=1), ValueError, "the scene is missing the required key 'camera'"),
    "missing camera": (setter(("camera",), DELETE), ValueError, "the scene is missing the required key 'camera'"),
    "missing eye": (setter(("camera", "eye"), DELETE), ValueError, "camera is missing the required key 'eye'"),
    "missing lights": (setter(("lights",), DELETE), ValueError, "the scene is missing the required key 'lights'"),
    "missing mesh": (setter(("objects", 1, "mesh"), DELETE), ValueError, "objects[1] is missing the required key 'mesh'"),
    "missing faces": (setter((*MESH, "faces"), DELETE), ValueError, "objects[0].mesh is missing the required key 'faces'"),
    "missing position": (setter(("lights", 0, "position"), DELETE), ValueError, "lights[0] is missing the required key 'position'"),
    "unknown top key": (setter(("lightz",), []), ValueError, "the scene has an unknown key 'lightz' (did you mean 'lights'?); allowed keys: ambient, background, camera, lights, materials, name, objects, version"),
    "unknown material key": (setter(("objects", 2, "material"), {"difuse": 0.5}), ValueError, "objects[2].material has an unknown key 'difuse' (did you mean 'diffuse'?); allowed keys: ambient, color, diffuse, exponent, fudge, specular, transparency"),
    "unknown object key": (setter(("objects", 0, "transfrom"), []), ValueError, "objects[0] has an unknown key 'transfrom' (did you mean 'transform'?); allowed keys: material, mesh, name, transform"),
    "unknown mesh key": (setter((*MESH, "normal"), []), ValueError, "objects[0].mesh has an unknown key 'normal' (did you mean 'normals'?)"),
    "direction on point light": (setter(("lights", 0, "direction"), [0, 0, 1]), ValueError, "lights[0] has an unknown key 'direction'; allowed keys: color, kind, position"),
    "diffuse out of range": (setter(("objects", 2, "material"), {"diffuse": 1.5}), ValueError, "objects[2].material.diffuse must be in [0.0, 1.0]; got 1.5"),
    "color out of range": (setter(("objects", 1, "material"), {"color": [1, 2, 0]}), ValueError, "objects[1].material.color components must be in [0, 1]; got (1.0, 2.0, 0.0)"),
    "negative exponent": (setter(("materials", "brass", "exponent"), -1), ValueError, "materials.brass.exponent must be in [0.0, 10000.0]; got -1.0"),
    "transparency type": (setter(("objects", 0, "material"), {"transparency": "half"}), TypeError, "objects[0].material.transparency must be a number; got 'half'"),
    "boolean number": (setter(("objects", 0, "material"), {"specular": True}), TypeError, "objects[0].material.specular must be a number; got True"),
    "unknown palette name": (setter(("objects", 2, "material"), "gren"), ValueError, "objects[2].material names an unknown material 'gren'; known: brass, glass"),
    "material wrong type": (setter(("objects", 2, "material"), 3), TypeError, "objects[2].material must be a material object or the name of one in 'materials'; got a number"),
    "palette entry a name": (setter(("materials", "copy"), "brass"), TypeError, "materials.copy must be a material object; got a string"),
    "eye NaN": (setter(("camera", "eye"), [0, NAN, 5]), ValueError, "camera.eye[1] must be finite; got nan"),
    "eye Infinity": (setter(("camera", "eye"), [0, 0, INF]), ValueError, "camera.eye[2] must be finite; got inf"),
    "near -Infinity": (setter(("camera", "near"), -INF), ValueError, "camera.near must be finite; got -inf"),
    "eye string": (setter(("camera", "eye"), [0, 0, "5"]), TypeError, "camera.eye[2] must be a number; got '5'"),
    "eye too short": (setter(("camera", "eye"), [0, 5]), ValueError, "camera.eye must have 3 numbers; got 2"),
    "eye not array": (setter(("camera", "eye"), 5), TypeError, "camera.eye must be an array; got a number"),
    "up parallel": (setter(("camera", "up"), [0, 0, 1]), ValueError, "camera.up (0.0, 0.0, 1.0) must not be parallel to the view direction (0.0, 0.0, -5.0)"),
    "eye at look_at": (setter(("camera", "look_at"), [0, 0, 5]), ValueError, "camera.look_at must differ from 'eye'"),
    "near >= far": (setter(("camera", "near"), 200), ValueError, "camera.near must be < 'far'; got near=200.0, far=100.0"),
    "near zero": (setter(("camera", "near"), 0), ValueError, "camera.near must be > 0 for a perspective camera (at least 1e-99); got 0.0"),
    "empty window": (setter(("camera", "window"), [1, -1, -1, 1]), ValueError, "camera.window must have left < right and bottom < top; got (1.0, -1.0, -1.0, 1.0)"),
    "flat window": (setter(("camera", "window"), [-1, 1, 1, 1]), ValueError, "camera.window must have left < right and bottom < top"),
    "projection": (setter(("camera", "projection"), "fisheye"), ValueError, "camera.projection must be 'perspective' or 'orthographic'; got 'fisheye'"),
    "light kind": (setter(("lights", 0, "kind"), "spot"), ValueError, "lights[0].kind must be 'point' or 'directional'; got 'spot'"),
    "light color": (setter(("lights", 0, "color"), [-1, 0, 0]), ValueError, "lights[0].color components must be >= 0 and <= 1e+06; got (-1.0, 0.0, 0.0)"),
    "zero direction": (setter(("lights", 0), {"kind": "directional", "direction": [0, 0, 0]}), ValueError, "lights[0].direction must not be the zero vector"),
    "lights not array": (setter(("lights",), {}), TypeError, "lights must be an array; got an object"),
    "ambient range": (setter(("ambient",), [2, 0, 0]), ValueError, "ambient components must be in [0, 1]; got (2.0, 0.0, 0.0)"),
    "version": (setter(("version",), 2), ValueError, "version must be 1; got 2"),
    "name type": (setter(("objects", 1, "name"), 7), TypeError, "objects[1].name must be a string; got a number"),
    "face index range": (setter((*MESH, "faces"), [[0, 1, 2], [0, 1, 9]]), ValueError, "objects[0].mesh.faces[1] indexes outside 0..2: [0, 1, 9]"),
    "face index negative": (setter((*MESH, "faces"), [[0, -1, 2]]), ValueError, "objects[0].mesh.faces[0] indexes outside 0..2: [0, -1, 2]"),
    "face index float": (setter((*MESH, "faces"), [[0, 1, 2], [0, 1, 1.0]]), TypeError, "objects[0].mesh.faces[1][2] must be an integer; got 1.0"),
    "face too small": (setter((*MESH, "faces"), [[0, 1]]), ValueError, "objects[0].mesh.faces[0] has 2 vertices; a face needs >= 3"),
    "faces not arrays": (setter((*MESH, "faces"), [0, 1, 2]), TypeError, "objects[0].mesh.faces[0] must be an array; got a number"),
    "position width": (setter((*MESH, "positions"), [[0, 0, 0], [1, 0], [0, 1, 0]]), ValueError, "objects[0].mesh.positions[1] must have 3 entries; got 2"),
    "position NaN": (setter((*MESH, "positions"), [[0, 0, 0], [1, 0, NAN], [0, 1, 0]]), ValueError, "objects[0].mesh.positions[1][2] must be finite; got nan"),
    "position null": (setter((*MESH, "positions"), [[0, 0, 0], [1, 0, None], [0, 1, 0]]), TypeError, "objects[0].mesh.positions[1][2] must be a number; got None"),
    "normals count": (setter((*MESH, "normals"), [[0, 0, 1]]), ValueError, "objects[0].mesh.normals must have one row per position (3); got 1"),
    "smooth type": (setter((*MESH, "smooth"), "yes"), TypeError, "objects[0].mesh.smooth must be true or false; got 'yes'"),
    "face materials range": (setter((*MESH, "face_materials"), [3]), ValueError, "objects[0].mesh.face_materials must index 'materials' (or be -1); got [3]"),
    "face materials type": (setter((*MESH, "face_materials"), [0.5]), TypeError, "objects[0].mesh.face_materials[0] must be an integer; got 0.5"),
    "vertex materials count": (setter((*MESH, "vertex_materials"), [-1]), ValueError, "objects[0].mesh.vertex_materials must have 3 entries; got 1"),
    "mesh material name": (setter((*MESH, "materials"), ["brass", "tin"]), ValueError, "objects[0].mesh.materials[1] names an unknown material 'tin'; known: brass, glass"),
    "mesh of no form": (setter(MESH, {"vertices": []}), ValueError, "objects[0].mesh must hold 'positions' and 'faces', or 'obj' (a file), or 'builtin_mesh'"),
    "unknown builtin mesh": (setter(MESH, {"builtin_mesh": "sphere"}), ValueError, "objects[0].mesh.builtin_mesh must be one of box, icosphere, terrain, torus, uv_sphere; got 'sphere'"),
    "builtin mesh parameter": (setter(MESH, {"builtin_mesh": "icosphere", "levl": 2}), ValueError, "objects[0].mesh has an unknown key 'levl' (did you mean 'level'?); allowed keys: builtin_mesh, closed, level, smooth"),
    "builtin mesh value": (setter(MESH, {"builtin_mesh": "icosphere", "level": 99}), ValueError, "objects[0].mesh.level must be in 0..8; got 99"),
    "obj with positions": (setter((*MESH, "obj"), "x.obj"), ValueError, "objects[0].mesh has an unknown key 'positions'; allowed keys: closed, obj, smooth"),
    "transform not list": (setter(("objects", 1, "transform"), {"scale": 2}), TypeError, "objects[1].transform must be an array; got an object"),
    "two-key step": (setter(("objects", 1, "transform"), [{"scale": 1, "translate": [1, 2, 3]}]), ValueError, "objects[1].transform[0] must have exactly one key, one of matrix, rotate, scale, translate; got ['scale', 'translate']"),
    "unknown step": (setter(("objects", 1, "transform"), [{"rotat": {}}]), ValueError, "objects[1].transform[0] has an unknown key 'rotat' (did you mean 'rotate'?); allowed keys: matrix, rotate, scale, translate"),
    "zero scale": (setter(("objects", 1, "transform"), [{"translate": [1, 2, 3]}, {"scale": 0}]), ValueError, "objects[1].transform[1].scale factors must be nonzero (the normals need an inverse); got 0"),
    "translate NaN": (setter(("objects", 1, "transform"), [{"translate": [1, NAN, 3]}]), ValueError, "objects[1].transform[0].translate[1] must be finite; got nan"),
    "rotate zero axis": (setter(("objects", 1, "transform"), [{"rotate": {"axis": [0, 0, 0], "degrees": 3}}]), ValueError, "objects[1].transform[0].rotate.axis must not be the zero vector"),
    "rotate no degrees": (setter(("objects", 1, "transform"), [{"rotate": {"axis": [0, 0, 1]}}]), ValueError, "objects[1].transform[0].rotate is missing the required key 'degrees'"),
    "matrix rows": (setter(("objects", 1, "transform"), [{"matrix": [[1, 0, 0, 0]] * 3}]), ValueError, "objects[1].transform[0].matrix must have 4 rows; got 3"),
    "empty step": (setter(("objects", 1, "transform"), [{}]), ValueError, "objects[1].transform[0] must have exactly one key"),
    "step not object": (setter(("objects", 1, "transform"), [[1, 2, 3]]), TypeError, "objects[1].transform[0] must be an object; got an array"),
    "matrix singular": (setter(("objects", 1, "transform"), [{"matrix": [[1, 0, 0, 0]] * 3 + [[0, 0, 0, 1]]}]), ValueError, "objects[1].transform[0].matrix 3x3 block must be invertible"),
}  # fmt: skip


@pytest.mark.parametrize("case", list(ERROR_CASES))
def test_bad_scenes_name_the_path_and_the_rule(case):
    mutate, error, message = ERROR_CASES[case]
    data = base()
    mutate(data)
    with pytest.raises(error) as raised:
        scene_from_dict(data)
    assert type(raised.value) is error
    assert str(raised.value).startswith(message), str(raised.value)


def test_scene_must_be_an_object():
    with pytest.raises(TypeError, match="the scene must be an object; got an array"):
        scene_from_dict([])


def test_input_is_not_modified():
    data = base()
    data["objects"][0]["transform"] = [{"scale": 2}]
    before = copy.deepcopy(data)
    scene_from_dict(data)
    assert data == before


# --- issue 8 -------------------------------------------------------------------------------

CAMERA = {"eye": [0, 0, 5], "look_at": [0, 0, 0]}


def one_object(**obj):
    return {"camera": CAMERA, "lights": [], "objects": [{"mesh": {"builtin_mesh": "box"}} | obj]}


@pytest.mark.parametrize(
    "data, message",
    [
        (one_object(transform=[{"scale": 1e200}]), "objects[0].transform[0].scale factors must have magnitudes in [1e-100, 1e+100]"),
        (one_object(transform=[{"scale": 1e90}, {"scale": 1e90}]), "objects[0].transform (the product of its steps) 3x3 entries must be within +-1e+100"),
        (one_object(transform=[{"translate": [0, 0, 1e200]}]), "objects[0].transform[0].translate must be within +-1e+99"),
        (one_object(transform=[{"scale": 2e98}, {"translate": [0, 0, 9e98]}]), "objects[0]: mesh position 4 [-1.0, -1.0, 1.0] lands at world [-2e+98, -2e+98, 1.1"),
        (one_object(transform=[{"translate": [0, 0, -1e13]}]), "objects[0] mesh position 0 is 1e+13 from the eye, more than 1e+12 times 1"),
        (one_object(material={"exponent": 1e308}), "objects[0].material.exponent must be in [0.0, 10000.0]; got 1e+308"),
        ({"camera": CAMERA | {"window": [0, 5e-324, 0, 5e-324]}, "lights": [], "objects": []}, "camera.window width must be at least 1e-12"),
        ({"camera": CAMERA, "lights": [{"kind": "point", "position": [0, 0, 1e308]}], "objects": []}, "lights[0].position components must be within +-1e+99"),
        ({"camera": CAMERA | {"eye": [0, 0, 10**400]}, "lights": [], "objects": []}, "camera.eye[2] must be finite"),
    ],
)  # fmt: skip
def test_issue8_d3_limits_are_checked_at_the_json_path(data, message):
    with pytest.raises(ValueError) as raised:
        scene_from_dict(data)
    assert str(raised.value).startswith(message), str(raised.value)


def test_issue8_d5_a_huge_rotation_axis_is_a_rotation():
    data = one_object(transform=[{"rotate": {"axis": [1e308, 1e308, 0], "degrees": 180}}])
    matrix = scene_from_dict(data).objects[0].world_from_model
    assert np.allclose(matrix[:3, :3], [[0, 1, 0], [1, 0, 0], [0, 0, -1]], atol=1e-15)


@pytest.mark.parametrize("depth", [65, 5000, 100_000])
def test_issue8_d6_deep_json_is_refused_before_parsing(tmp_path, depth):
    path = tmp_path / "deep.json"
    path.write_text('{"camera": ' + "[" * depth + "]" * depth + ', "s": "[[[[[["}')
    with pytest.raises(
        ValueError, match=rf"deep.json': JSON nested {depth + 1} deep; .* at most 64"
    ):
        load_scene(path)
    path.write_text(
        '{"name": "'
        + "[" * depth
        + '", "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "lights": [], "objects": []}'
    )
    assert load_scene(path).name == "[" * depth  # brackets inside strings do not count


def test_issue8_d11_file_errors_name_the_file(tmp_path):
    path = tmp_path / "scene.json"
    path.write_bytes(b'{"name": "caf\xe9"}')
    with pytest.raises(ValueError, match=r"scene.json' is not UTF-8 text: byte 13 is 0xe9"):
        load_scene(path)
    path.write_text('{"version": ' + "1" * 5000 + "}")
    with pytest.raises(
        ValueError, match=r"scene.json': an integer literal of 5000 digits is beyond"
    ):
        load_scene(path)


def test_issue8_d11_an_empty_inline_mesh_loads():
    data = {"camera": CAMERA, "lights": [], "objects": [{"mesh": {"positions": [], "faces": []}}]}
    assert scene_from_dict(data).objects[0].mesh.positions.shape == (0, 3)


@pytest.mark.parametrize("name", ["model.obj", "MODEL.OBJ", "Model.Obj"])
def test_issue8_d13_load_scene_frames_an_obj_file(tmp_path, name):
    path = tmp_path / name
    path.write_text("v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n")
    scene = load_scene(path)
    assert scene.objects[0].mesh.positions[1].tolist() == [2, 0, 0]
    assert scene.camera.look_at == (1.0, 1.0, 0.0) and scene.lights and scene.name == path.stem
    assert scene.objects[0].material == Material()


def test_issue8_fuzz_file_names_in_errors_are_quoted(tmp_path):
    # Found by the fuzz campaign: a file name holding a newline made a two-line message.
    path = tmp_path / "a\nb.json"
    path.write_text('"x"')
    with pytest.raises(TypeError) as caught:
        load_scene(path)
    assert "\n" not in str(caught.value) and repr(str(path)) in str(caught.value)

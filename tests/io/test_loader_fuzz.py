"""Hostile input for the loaders and the command line (issue 8, deliverable 2).

Every outcome must be a correct result or a ValueError/TypeError naming the
rule (OSError for files); a scene that loads must render without NaN and
survive a JSON round trip; the CLI must exit 0 or 2 with at most one line on
stderr. ``OUTCOMES`` counts what happened, for the fuzz report.
"""

from __future__ import annotations

import collections
import copy
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from scanviz.cli import main
from scanviz.io import load_obj, scene_from_dict, scene_to_dict
from scanviz.limits import file_limit, memory_limit
from scanviz.pipeline import render

OUTCOMES: collections.Counter = collections.Counter()

# --- values ---------------------------------------------------------------------------------


def nested(depth: int) -> list:
    value: list = []
    for _ in range(depth):
        value = [value]
    return value


HOSTILE = st.sampled_from(
    [
        math.nan,
        math.inf,
        -math.inf,
        -0.0,
        5e-324,
        2.2250738585072014e-308,
        1e308,
        -1e308,
        1e99,
        1e100,
        10**400,
        2**1024,
        2**20 + 1,
        2**63,
        -1,
        0,
        True,
        None,
        "0",
        "",
        "a\nb",
        [],
        {},
        [[]],
        [1, 2],
        [math.nan] * 3,
        [1e308] * 3,
        [0, 0, 0],
        nested(50),
        {"unknown": 1},
    ]
)

# --- scene dicts -------------------------------------------------------------------------------

BASE_SCENE = {
    "version": 1,
    "name": "fuzz",
    "camera": {
        "eye": [0, 0, 5],
        "look_at": [0, 0, 0],
        "up": [0, 1, 0],
        "window": [-1, 1, -1, 1],
        "near": 1,
        "far": 10,
        "projection": "perspective",
    },
    "lights": [
        {"kind": "point", "position": [2, 3, 4], "color": [1, 1, 1]},
        {"kind": "directional", "direction": [0, 0, -1]},
    ],
    "ambient": [1, 1, 1],
    "background": [0, 0, 0],
    "materials": {"red": {"color": [1, 0, 0], "exponent": 8, "fudge": 0.1}},
    "objects": [
        {
            "name": "triangle",
            "mesh": {
                "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                "faces": [[0, 1, 2]],
                "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1]],
                "closed": False,
                "materials": ["red"],
                "face_materials": [0],
                "vertex_materials": [-1, 0, -1],
            },
            "material": {"color": [0.5, 0.5, 0.5], "transparency": 0.25},
            "transform": [
                {"scale": 0.5},
                {"rotate": {"axis": [0, 0, 1], "degrees": 30}},
                {"translate": [0.1, 0, 0]},
                {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
            ],
        },
        {"mesh": {"builtin_mesh": "icosphere", "level": 1}, "material": "red"},
    ],
}


def paths(value, prefix=()):
    """Every (path, value) inside a JSON value, the root included."""
    yield prefix
    if isinstance(value, dict):
        for key, item in value.items():
            yield from paths(item, (*prefix, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from paths(item, (*prefix, index))


SCENE_PATHS = [p for p in paths(BASE_SCENE) if p]


@st.composite
def mutated_scenes(draw):
    """BASE_SCENE with 1-3 values replaced by hostile ones, or keys added or removed."""
    data = copy.deepcopy(BASE_SCENE)
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(SCENE_PATHS))
        parent = data
        try:
            for key in path[:-1]:
                parent = parent[key]
            action = draw(st.sampled_from(["replace", "replace", "delete", "add"]))
            if action == "replace":
                parent[path[-1]] = draw(HOSTILE)
            elif action == "delete":
                del parent[path[-1]]
            elif isinstance(parent, dict):
                parent[draw(st.sampled_from(["extra", "difuse", "obj", "size"]))] = draw(HOSTILE)
            elif isinstance(parent, list):
                parent.append(draw(HOSTILE))
            else:  # an earlier mutation replaced the container by a scalar
                continue
        except (KeyError, IndexError, TypeError):
            continue  # an earlier mutation removed the path
    return data


def check_scene_outcome(data) -> None:
    try:
        scene = scene_from_dict(data)
    except (ValueError, TypeError) as error:
        assert str(error) and "\n" not in str(error).strip()
        OUTCOMES["scene dicts: clear error"] += 1
        return
    image = render(scene, 4, 4, shading="phong").image
    assert np.isfinite(image).all()
    again = scene_from_dict(json.loads(json.dumps(scene_to_dict(scene))))
    assert scene_to_dict(again) == scene_to_dict(scene)
    OUTCOMES["scene dicts: loaded, rendered, round-tripped"] += 1


@settings(derandomize=True, max_examples=200, deadline=None)
@given(mutated_scenes())
def test_issue8_fuzz_scene_dicts(data):
    check_scene_outcome(data)


MAGNITUDES = st.sampled_from([0.0, -0.0, 5e-324, 1e-300, 1e-12, 0.5, 1.0, 3.0, 1e6, 1e98, 1e99])


@st.composite
def extreme_scenes(draw):
    """Valid-looking scenes whose numbers sit near the documented limits."""
    signed = st.tuples(MAGNITUDES, st.sampled_from([-1.0, 1.0])).map(lambda t: t[0] * t[1])
    point = st.lists(signed, min_size=3, max_size=3)
    near = draw(st.sampled_from([1e-99, 1e-12, 0.5, 1.0, 1e98]))
    half = draw(st.sampled_from([1e-99, 1e-12, 1.0, 1e50, 1e99]))
    return {
        "camera": {
            "eye": draw(point),
            "look_at": draw(point),
            "up": draw(st.sampled_from([[0, 1, 0], [1e-300, 1e-300, 0], [1e300, 0, 1]])),
            "window": [-half, half, -half, half],
            "near": near,
            "far": draw(st.sampled_from([near * 2, near * 1e12, 1e99, math.inf])),
            "projection": draw(st.sampled_from(["perspective", "orthographic"])),
        },
        "lights": [
            {"kind": "point", "position": draw(point), "color": [1e6, 1, 0]},
            {"kind": "directional", "direction": draw(point)},
        ],
        "objects": [
            {
                "mesh": {
                    "positions": draw(st.lists(point, min_size=3, max_size=3)),
                    "faces": [[0, 1, 2]],
                },
                "material": {
                    "exponent": draw(st.sampled_from([0, 1, 1e4])),
                    "fudge": draw(MAGNITUDES),
                },
                "transform": [{"scale": draw(st.sampled_from([1e-100, 1e-50, 1.0, 1e50, 1e100]))}],
            }
        ],
    }


@settings(derandomize=True, max_examples=200, deadline=None)
@given(extreme_scenes())
def test_issue8_fuzz_extreme_scenes_load_and_render_or_name_the_rule(data):
    try:
        scene = scene_from_dict(data)
    except (ValueError, TypeError) as error:
        assert str(error)
        OUTCOMES["extreme scenes: clear error"] += 1
        return
    for shading in ("flat", "gouraud", "phong", "gooch"):
        image = render(scene, 4, 4, shading=shading, visibility="zbuffer").image
        assert np.isfinite(image).all()
    OUTCOMES["extreme scenes: rendered in 4 shadings"] += 1


# --- OBJ text --------------------------------------------------------------------------------

NUMBERS = st.sampled_from(
    ["0", "-0", "1", "-1.5", "1e308", "1e309", "-1e400", "nan", "inf", "5e-324", "1e-200",
     "1e200", "0x10", "1,5", "", "9" * 400]
)  # fmt: skip
INDICES = st.sampled_from(
    ["1", "2", "3", "-1", "-3", "0", "4", "99999999999999999999", "x", "1.5", ""]
)
CORNERS = st.one_of(
    INDICES,
    st.tuples(INDICES, INDICES).map("/".join),
    st.tuples(INDICES, INDICES).map(lambda t: f"{t[0]}//{t[1]}"),
    st.tuples(INDICES, INDICES, INDICES).map("/".join),
)
OBJ_LINES = st.one_of(
    st.lists(NUMBERS, min_size=2, max_size=7).map(lambda n: "v " + " ".join(n)),
    st.lists(NUMBERS, min_size=2, max_size=4).map(lambda n: "vn " + " ".join(n)),
    st.lists(NUMBERS, min_size=1, max_size=3).map(lambda n: "vt " + " ".join(n)),
    st.lists(CORNERS, min_size=1, max_size=6).map(lambda c: "f " + " ".join(c)),
    st.sampled_from(
        ["v 0 0 0", "v 1 0 0", "v 0 1 0", "vn 0 0 1", "f 1 2 3", "f 1//1 2//1 3//1",
         "mtllib a.mtl", "usemtl red", "o thing", "g group", "s 1", "s off", "l 1 2", "p 1",
         "vp 0.5", "# comment", "", "   ", "v 0 0 \\", "curv 0 1 1 2", "bogus 1", "\x00", "f"]
    ),
)  # fmt: skip


@st.composite
def obj_texts(draw):
    lines = draw(st.lists(OBJ_LINES, max_size=12))
    end = draw(st.sampled_from(["\n", "\r\n"]))
    bom = draw(st.sampled_from(["", "\ufeff"]))
    return bom + end.join(["v 0 0 0", *lines]) + end


@settings(derandomize=True, max_examples=200, deadline=None)
@given(obj_texts())
def test_issue8_fuzz_obj_text(text):
    try:
        mesh = load_obj(text)
    except ValueError as error:
        assert str(error).startswith("line ") or "index" in str(error), str(error)
        OUTCOMES["OBJ text: clear error"] += 1
        return
    assert np.isfinite(mesh.positions).all()
    if mesh.normals is not None:
        assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1.0)
    OUTCOMES["OBJ text: loaded"] += 1


# --- the command line ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cli-fuzz")
    (folder / "model.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (folder / "scene.json").write_text(json.dumps(BASE_SCENE))
    (folder / "latin1.json").write_bytes(b'{"name": "caf\xe9"}')
    (folder / "deep.json").write_text("[" * 3000 + "]" * 3000)
    return folder


def cli_tokens(folder):
    scenes = [
        "builtin:painter",
        "builtin:umbc_zbuffer",
        "builtin:nope",
        "builtin:",
        str(folder / "model.obj"),
        str(folder / "scene.json"),
        str(folder / "latin1.json"),
        str(folder / "deep.json"),
        "/dev/zero",
        str(folder / "missing\n.json"),
        str(folder),
        "",
    ]
    outputs = [str(folder / name) for name in ("a.png", "a.JPG", "a.tif", "a.qqq", "noext", "")] + [
        str(folder)
    ]
    values = ["0", "-1", "1", "8", "x", "1" * 50, "nan", "a\nb", "", "--"]
    options = [
        "--width",
        "--height",
        "--shading",
        "--visibility",
        "--mask",
        "--weights",
        "--sample",
        "--edges",
        "--affine",
        "--perspective-correct",
        "--no-perspective-correct",
        "--cull",
        "--no-cull",
        "--plan",
        "-o",
        "--scale",
        "--vertices",
        "--rule",
        "--subpixel-bits",
        "--arithmetic",
        "--json",
        "--bogus",
    ]
    choices = [
        "flat",
        "gouraud",
        "phong",
        "gooch",
        "zbuffer",
        "abuffer",
        "flawed",
        "4x4",
        "8x4",
        "area",
        "mask",
        "corner",
        "center",
        "none",
        "17",
        "0,0 4,0 0,4",
        "0,0 1e400,0 0,1",
        "0,0 4,0",
        "0,0;1,1 2,2 3,1",
    ]
    return scenes, outputs, st.sampled_from(values + options + choices)  # fmt: skip


@st.composite
def cli_argvs(draw, folder):
    scenes, outputs, token = cli_tokens(folder)
    command = draw(st.sampled_from(["render", "render", "render", "fill", "trace", "bogus"]))
    argv = [command]
    if command == "render":
        argv += [draw(st.sampled_from(scenes)), "--width", "8", "--height", "8"]
    if command in ("fill", "render") and draw(st.booleans()):
        argv += ["-o", draw(st.sampled_from(outputs))]
    if command in ("fill", "trace") and draw(st.booleans()):
        argv += ["--vertices", "0,0 4,0 0,4"]
    return argv + draw(st.lists(token, max_size=5))


@settings(
    derandomize=True,
    max_examples=150,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(data=st.data())
def test_issue8_fuzz_command_line(files, capsys, data):
    argv = data.draw(cli_argvs(files))
    if "--width" in argv[5:] or "--height" in argv[5:] or "--scale" in argv:
        return  # a raster the user asks to be large is a long render, not an error
    with file_limit("1M"), memory_limit("256M"):
        status = main(argv)
    err = capsys.readouterr().err
    assert status in (0, 2), (argv, status, err)
    assert "Traceback" not in err and len(err.splitlines()) <= 1, (argv, err)
    OUTCOMES[f"CLI: exit {status}"] += 1

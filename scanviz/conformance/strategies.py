"""Hypothesis strategies of hostile, extreme and random valid inputs for the fuzz campaign.

Each strategy mixes valid values (most of the time) with special floats and
integers, oddballs of the wrong type, odd numpy arrays and deeply nested
lists (`Deep` markers, built only when an input is used). The checks that
judge the outcomes are in `scanviz.conformance.checks`.
"""

from __future__ import annotations

import copy
import json
import math
import warnings
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

import numpy as np
from hypothesis import strategies as st

SPECIAL_FLOATS = (
    math.nan, math.inf, -math.inf, -0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e308,
    -1e308, 1.7976931348623157e308, 2.0**20, -(2.0**20), 2.0**20 + 1, -(2.0**20) - 1,
    2.0**20 - 1, 0.5, 1 / 3, 1e-7,
)  # fmt: skip
SPECIAL_INTS = (
    0, 1, -1, 2**20, -(2**20), 2**20 + 1, -(2**20) - 1, 2**31, 2**63, 2**64, 10**400, 2**1024,
    -(10**400),
)  # fmt: skip


def special_scalars() -> st.SearchStrategy:
    return st.one_of(
        st.sampled_from(SPECIAL_FLOATS),
        st.sampled_from(SPECIAL_INTS),
        st.floats(),
        st.integers(),
        st.complex_numbers(max_magnitude=10),
        st.sampled_from([np.float32(1.5), np.float16(2), np.int64(3), np.uint8(4), np.bool_(True)]),
        st.builds(Fraction, st.integers(-9, 9), st.integers(1, 9)),
        st.sampled_from([Decimal("1.5"), Decimal("NaN")]),
    )


def oddballs() -> st.SearchStrategy:
    return st.one_of(
        st.text(max_size=4),
        st.sampled_from(["0", "4", "1e400", "nan", "", "\n"]),
        st.none(),
        st.booleans(),
        st.just(object()),
        st.binary(max_size=3),
        st.just({}),
        st.just(set()),
    )


@dataclass(frozen=True)
class Deep:
    """`depth` nested lists around 0, built only when the input is used (short in reproducers)."""

    depth: int

    def build(self) -> list:
        value: object = 0
        for _ in range(self.depth):
            value = [value]
        return value  # type: ignore[return-value]


def materialize(value: object) -> object:
    """`value` with every `Deep` marker replaced by its nested lists."""
    if isinstance(value, Deep):
        return value.build()
    if isinstance(value, list | tuple):
        return type(value)(materialize(v) for v in value)
    if isinstance(value, dict):
        return {k: materialize(v) for k, v in value.items()}
    return value


def deep_lists() -> st.SearchStrategy:
    return st.builds(Deep, st.sampled_from([3, 40, 3000]))


def valid_coordinates(low: float = -2.0, high: float = 14.0) -> st.SearchStrategy:
    return st.one_of(
        st.integers(int(low), int(high)),
        st.floats(low, high, allow_nan=False).map(lambda v: round(v * 256) / 256),
        st.floats(low, high, allow_nan=False),
    )


def coordinates() -> st.SearchStrategy:
    valid = valid_coordinates()
    return st.one_of(valid, valid, valid, valid, special_scalars(), oddballs())


def points() -> st.SearchStrategy:
    coordinate = coordinates()
    valid_pair = st.tuples(valid_coordinates(), valid_coordinates())
    return st.one_of(
        valid_pair,
        valid_pair,
        st.lists(coordinate, min_size=2, max_size=2),
        st.lists(coordinate, max_size=4),  # ragged
        coordinate,
    )


def odd_arrays() -> st.SearchStrategy:
    """numpy arrays of odd dtypes and shapes."""

    def build(shape, dtype, fill):
        with warnings.catch_warnings():  # NaN cast to int: the odd array is the point
            warnings.simplefilter("ignore")
            return np.full(shape, fill).astype(dtype) if dtype != "U3" else np.full(shape, "1")

    return st.builds(
        build,
        st.sampled_from([(0,), (3,), (3, 2), (4, 2), (3, 3), (2, 3, 2), (0, 2), (1, 3, 2), (3, 1)]),
        st.sampled_from(["float64", "float32", "int64", "complex128", "object", "bool", "U3"]),
        st.sampled_from([1.0, 0.0, math.nan, math.inf, 2.0**20 + 1, 3.25]),
    )


def contour_inputs() -> st.SearchStrategy:
    return st.one_of(
        st.lists(points(), max_size=7),
        st.lists(st.tuples(valid_coordinates(), valid_coordinates()), min_size=3, max_size=7),
        odd_arrays(),
        deep_lists(),
    )


def polygon_inputs() -> st.SearchStrategy:
    contour = contour_inputs()
    return st.one_of(contour, contour, st.lists(contour, max_size=3), oddballs(), special_scalars())


def sizes() -> st.SearchStrategy:
    return st.one_of(
        st.integers(0, 12),
        st.integers(0, 12),
        st.integers(0, 12),
        st.sampled_from([-1, 2**16 + 1, 10**400, 1.5, "4", True, None, np.int64(5), 4.0, 1j]),
    )


def option_values(values: tuple) -> st.SearchStrategy:
    return st.one_of(st.sampled_from(values), st.sampled_from(values), oddballs())


def subpixel_bits_values() -> st.SearchStrategy:
    return st.one_of(
        st.sampled_from([8, 8, None, 0, 4, 16]), st.sampled_from([-1, 17, 2.0, "8", True, 10**400])
    )


def scan_convert_args(valid: bool) -> st.SearchStrategy:
    if valid:
        polygon = st.lists(
            st.lists(st.tuples(valid_coordinates(), valid_coordinates()), min_size=3, max_size=7),
            min_size=1,
            max_size=3,
        ).filter(lambda cs: all(len(set(c)) >= 3 for c in cs))
        options = st.fixed_dictionaries(
            {},
            optional={
                "sample": st.sampled_from(["corner", "center"]),
                "rule": st.sampled_from(["nonzero", "evenodd"]),
                "subpixel_bits": st.sampled_from([8, None, 0, 3, 16]),
            },
        )
        size = st.integers(0, 12)
    else:
        polygon, size = polygon_inputs(), sizes()
        options = st.fixed_dictionaries(
            {},
            optional={
                "sample": option_values(("corner", "center")),
                "rule": option_values(("nonzero", "evenodd")),
                "subpixel_bits": subpixel_bits_values(),
                "arithmetic": option_values(("exact", "float32", "float64")),
                "trace": st.sampled_from([None, True, False, "yes", 5]),
            },
        )
    return st.fixed_dictionaries(
        {"polygon": polygon, "width": size, "height": size, "options": options}
    )


def raster_options(rule: bool) -> st.SearchStrategy:
    optional = {
        "sample": option_values(("corner", "center")),
        "subpixel_bits": subpixel_bits_values(),
    }
    if rule:
        optional["rule"] = option_values(("nonzero", "evenodd"))
    return st.fixed_dictionaries({}, optional=optional)


def triangle_inputs() -> st.SearchStrategy:
    valid = st.lists(st.tuples(valid_coordinates(), valid_coordinates()), min_size=3, max_size=3)
    return st.one_of(valid, valid, valid, st.lists(points(), max_size=4), odd_arrays(), oddballs())


def line_ends() -> st.SearchStrategy:
    valid = st.integers(-40, 40)
    hostile = st.one_of(valid, valid, valid, special_scalars(), oddballs())
    return st.one_of(
        st.tuples(valid, valid, valid, valid), st.tuples(hostile, hostile, hostile, hostile)
    )


# --- scenes, files, OBJ, traces, CLI -------------------------------------------------------


def base_scene() -> dict:
    return {
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
        "lights": [
            {"kind": "directional", "direction": [0, 0, -1]},
            {"kind": "point", "position": [2, 2, 4]},
        ],
        "objects": [
            {
                "mesh": {
                    "positions": [[-1, -1, 0], [1, -1, 0], [0, 1, 0]],
                    "faces": [[0, 1, 2]],
                    "closed": False,
                },
                "material": {"color": [0.8, 0.4, 0.2], "specular": 0.5, "exponent": 20},
                "transform": [{"scale": 1.5}, {"rotate": {"axis": [0, 0, 1], "degrees": 10}}],
            },
            {
                "mesh": {"builtin_mesh": "icosphere", "level": 1},
                "transform": [{"translate": [0, 0, -1]}],
            },
        ],
    }


SCENE_SLOTS = (
    ("camera", "eye"), ("camera", "look_at"), ("camera", "up"), ("camera", "window"),
    ("camera", "near"), ("camera", "far"), ("camera", "projection"), ("lights", 0, "direction"),
    ("lights", 1, "position"), ("lights", 0, "color"), ("lights", 0, "kind"),
    ("objects", 0, "mesh", "positions"), ("objects", 0, "mesh", "positions", 0),
    ("objects", 0, "mesh", "positions", 1, 2), ("objects", 0, "mesh", "faces"),
    ("objects", 0, "mesh", "faces", 0, 1), ("objects", 0, "material", "exponent"),
    ("objects", 0, "material", "color"), ("objects", 0, "material", "specular"),
    ("objects", 0, "transform", 0, "scale"), ("objects", 0, "transform", 1, "rotate", "axis"),
    ("objects", 0, "transform", 1, "rotate", "degrees"), ("objects", 1, "mesh", "level"),
    ("objects", 1, "mesh", "builtin_mesh"), ("objects", 1, "transform", 0, "translate"),
    ("ambient",), ("background",), ("objects",), ("lights",), ("camera",), ("name",),
)  # fmt: skip


def scene_values() -> st.SearchStrategy:
    vector = st.lists(coordinates(), min_size=3, max_size=3)
    return st.one_of(
        special_scalars(),
        oddballs(),
        vector,
        vector,
        st.lists(st.sampled_from(SPECIAL_FLOATS), min_size=3, max_size=4),
        st.sampled_from([[1e308, 1e308, 0], [0, 1e-300, 0], [1e-200] * 3, [0, 0, 1e300], []]),
        st.sampled_from([1e308, 1e200, 1e150, 1e-150, 5e-324, [0, 0, 1e308], [1e150] * 3]),
        deep_lists(),
        st.dictionaries(st.sampled_from(["kind", "x", "scale", "eye"]), coordinates(), max_size=2),
    )


def with_value(data: dict, slot: tuple, value: object) -> dict:
    """A deep copy of `data` with the value at `slot` replaced (when the path exists)."""
    data = copy.deepcopy(data)
    target = data
    try:
        for key in slot[:-1]:
            target = target[key]
        target[slot[-1]] = value
    except (KeyError, IndexError, TypeError):  # an earlier change removed the path
        pass
    return data


def scene_dicts() -> st.SearchStrategy:
    mutated = st.builds(
        with_value, st.just(base_scene()), st.sampled_from(SCENE_SLOTS), scene_values()
    )
    twice = st.builds(with_value, mutated, st.sampled_from(SCENE_SLOTS[:12]), scene_values())
    return st.one_of(st.just(base_scene()), mutated, mutated, twice, deep_lists(), oddballs())


def dumps_generated(data: object) -> str:
    """JSON text of generated data: odd objects as their repr, too deep nesting as brackets."""
    try:
        return json.dumps(materialize(data), default=repr)
    except RecursionError:
        return "[" * 3000 + "]" * 3000


def file_bytes() -> st.SearchStrategy:
    scene_text = scene_dicts().map(lambda d: dumps_generated(d).encode())
    return st.one_of(
        scene_text,
        scene_text.map(lambda b: b"\xef\xbb\xbf" + b),
        st.sampled_from(
            [
                b"",
                b"\xff\xfe{}",
                b"[" * 5000 + b"]" * 5000,
                b'{"camera": ' * 3000,
                b'{"version": ' + b"1" * 5000 + b"}",
                b'{"camera": NaN}',
                b"\x00\x01\x02",
                b"v 0 0 0\nf 1 1 1\n",
            ]
        ),
        st.binary(max_size=40),
    )


OBJ_LINES = (
    "v 0 0 0", "v 1 0 0", "v 0 1 0", "v 1 1 0", "v 1e308 0 0", "v nan 0 0", "v 1e400 0 0",
    "vn 1e-200 1e-200 1e-200", "vn 1e200 1e200 1e200", "vn 0 0 1", "vt 0.5 0.5", "f 1 2 3",
    "f 1/1/1 2/1/1 3/1/1", "f 1//1 2//1 3//1", "f 1 2 3 4", "f -1 -2 -3", "f 1 2", "f 0 1 2",
    "f 9 1 2", "g group", "o thing", "s 1", "mtllib x.mtl", "usemtl red", "# comment", "",
    "v 1 2", "f a b c", "\ufeffv 0 0 0", "v " + "9" * 5000 + " 0 0",
)  # fmt: skip


def trace_texts() -> st.SearchStrategy:
    span = {"kind": "span", "polygon": 0, "y": 1, "x_start": 0, "x_end": 3, "winding": 1}
    value = st.one_of(
        special_scalars(), oddballs(), st.just("1/0"), st.just(["span"]), deep_lists()
    )
    mutated = st.builds(
        lambda key, v: {"events": [{**span, key: v}]},
        st.sampled_from(list(span)),
        value,
    )
    documents = st.one_of(
        st.just({"events": [span]}),
        mutated,
        mutated,
        st.builds(lambda v: {"events": v}, value),
        st.builds(lambda v: {"events": [v]}, value),
        st.just({"events": [{"kind": "span"}]}),
        deep_lists(),
    )
    return st.one_of(
        documents.map(dumps_generated),
        st.sampled_from(['{"events": ' * 4000, "", "nan", '{"events": [1]}', "[" * 50000]),
        st.text(max_size=20),
    )


CLI_TOKENS = (
    "trace", "fill", "render", "qqq", "--vertices", "0,0 4,0 0,4", "0,0 nan,0 0,4", "0,0 1j,0 0,1",
    "1e400,0 0,0 0,1", "0,0 4,0", "--width", "--height", "0", "-1", "5", "70000", "1e400", "nan",
    "--sample", "center", "--rule", "evenodd", "--subpixel-bits", "none", "17", "--arithmetic",
    "float32", "--json", "--plan", "--shading", "gooch", "--visibility", "abuffer", "--scale",
    "3", "-o", "OUT/out.png", "OUT/out.qqq", "OUT/noext", "OUT", "", "/dev/full", "a\nb",
    "builtin:painter", "builtin:sphere", "builtin:nope", "OUT/scene.json", "OUT/bad.json",
    "OUT/model.obj", "/nonexistent/x.json", "--mask", "4x4", "--edges", "--no-cull", "--affine",
    "OUT/huge.obj", "\u00b2", "x" * 5000, "1," * 3000, "OUT/" + "a" * 5000 + ".png",
    "0,0 4,0 0,4 " + "1,1,1 " * 1000,
)  # fmt: skip


def cli_argvs() -> st.SearchStrategy:
    valid = st.sampled_from(
        [
            ["trace", "--vertices", "0,0 4,0 0,4"],
            ["fill", "--vertices", "0,0 4,0 4,3", "-o", "OUT/out.png"],
            ["render", "builtin:painter", "--width", "8", "--height", "6", "-o", "OUT/out.png"],
            ["render", "OUT/scene.json", "--width", "6", "--height", "6"],
        ]
    )
    tokens = st.lists(st.sampled_from(CLI_TOKENS), max_size=8)
    appended = st.builds(
        lambda a, b: a + b, valid, st.lists(st.sampled_from(CLI_TOKENS), max_size=3)
    )
    return st.one_of(valid, appended, appended, tokens, tokens)

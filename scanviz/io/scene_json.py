"""Scenes as JSON: read, validate and write (format: ``docs/scene-format.md``).

A scene file is one JSON object. Every value is checked where it is read, and
an error names its JSON path and the rule it breaks, e.g.
``objects[2].material.diffuse must be in [0.0, 1.0]; got 1.5``. Unknown keys
are errors too, so a misspelt key never passes silently. The semantic rules
(ranges, a valid camera, faces within the positions) are the scene model's
(`scanviz.scene.model`); this module adds JSON types, paths and the
transform steps.

Transform convention: an object's ``"transform"`` is a list of steps T_1 ..
T_n applied in order, step 1 first. Points are column vectors, so
``world_from_model = T_n @ ... @ T_2 @ T_1``.
"""

from __future__ import annotations

import difflib
import functools
import inspect
import json
import math
import numbers
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import replace
from pathlib import Path

import numpy as np

from ..limits import check_memory, json_nesting, read_bounded
from ..scene.builtin import BUILTIN_MESHES, builtin_scene
from ..scene.model import (
    LINEAR_LIMIT,
    WORLD_LIMIT,
    Camera,
    Light,
    Material,
    Mesh,
    Scene,
    SceneObject,
    check_modeling_matrix,
    mesh_bytes,
)
from ..vectors import unit_vectors
from .obj import frame_model, load_obj

FORMAT_VERSION = 1
BUILTIN_PREFIX = "builtin:"
MAX_DEPTH = 64
"""Deepest nesting of JSON arrays and objects a scene file may have (a scene needs 7)."""
JSON_BYTES = 32
"""Bytes of parsed JSON per character of text, at most (measured with tracemalloc: 12 for lists
of positions or faces, 21 for empty arrays, up to 27 for nested objects); as for trace JSON."""
MAX_INTEGER_DIGITS = 400
"""Longest integer literal read; longer ones are beyond float64 anyway (1.8e308 has 309 digits)."""
_OBJ_SUFFIX = ".obj"

# --- JSON values, each checked at its path -----------------------------------------------


def _kind(value: object) -> str:
    """The JSON name of a value's type, for messages."""
    if value is None:
        return "null"
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, numbers.Real):
        return "a number"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, list | tuple):
        return "an array"
    if isinstance(value, Mapping):
        return "an object"
    return type(value).__name__


def _object(
    path: str, value: object, required: tuple[str, ...], optional: tuple[str, ...] | None = ()
) -> Mapping:
    """`value` as a JSON object with every `required` key, others only from `optional` (None: any)."""
    where = path or "the scene"
    if not isinstance(value, Mapping):
        raise TypeError(f"{where} must be an object; got {_kind(value)}")
    for key in required:
        if key not in value:
            raise ValueError(f"{where} is missing the required key {key!r}")
    allowed = (*required, *(optional or ()))
    for key in value:
        if key not in allowed and optional is not None:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(
                f"{where} has an unknown key {key!r}{hint}; allowed keys: {', '.join(sorted(allowed))}"
            )
    return value


def _array(path: str, value: object) -> list:
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if not isinstance(value, list | tuple):
        raise TypeError(f"{path} must be an array; got {_kind(value)}")
    return list(value)


def _number(path: str, value: object) -> float:
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        raise TypeError(f"{path} must be a number; got {value!r}")
    try:
        number = float(value)
    except OverflowError:
        number = math.inf  # an integer beyond float64
    if not math.isfinite(number):  # JSON NaN, Infinity and -Infinity
        raise ValueError(f"{path} must be finite; got {value}")
    return number


def _integer(path: str, value: object) -> int:
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{path} must be an integer; got {value!r}")
    return int(value)


def _string(path: str, value: object) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{path} must be a string; got {_kind(value)}")
    return value


def _boolean(path: str, value: object) -> bool:
    if not isinstance(value, bool):
        raise TypeError(f"{path} must be true or false; got {value!r}")
    return value


def _each(path: str, value: object, read: Callable, *args: object) -> tuple:
    """A JSON array read entry by entry: ``read(f"{path}[i]", entry, *args)``."""
    return tuple(read(f"{path}[{i}]", item, *args) for i, item in enumerate(_array(path, value)))


def _vector(path: str, value: object, size: int) -> tuple[float, ...]:
    items = _array(path, value)
    if len(items) != size:
        raise ValueError(f"{path} must have {size} numbers; got {len(items)}")
    return _each(path, items, _number)


def _plain_integer(x: object) -> bool:
    return type(x) is int


def _plain_number(x: object) -> bool:
    return type(x) is int or (type(x) is float and math.isfinite(x))


def _items(path: str, value: object, item: Callable) -> list:
    """A JSON array whose every entry passes `item` (`_number` or `_integer`)."""
    values = _array(path, value)
    if all(map(_plain_integer if item is _integer else _plain_number, values)):
        return values  # the fast path for plain JSON
    return [item(f"{path}[{i}]", x) for i, x in enumerate(values)]


def _table(path: str, value: object, width: int | None, item: Callable) -> list:
    """Rows of `width` entries each (any length if None), every entry checked by `item`."""
    rows = _array(path, value)
    for i, row in enumerate(rows):
        rows[i] = _items(f"{path}[{i}]", row, item)
        if width is not None and len(rows[i]) != width:
            raise ValueError(f"{path}[{i}] must have {width} entries; got {len(rows[i])}")
    return rows


def _located(path: str, error: ValueError | TypeError) -> ValueError | TypeError:
    """The model's error with `path` put in front of the field it names ("'diffuse' must ...")."""
    message = str(error)
    match = re.fullmatch(r"'(\w+(?:\[\d+\])*)'(.*)", message, re.DOTALL)
    if match:
        message = f"{path}.{match[1]}{match[2]}" if path else f"{match[1]}{match[2]}"
    elif path:
        message = f"{path}: {message}"
    return type(error)(message)


def _build(path: str, constructor: Callable, *args: object, **kwargs: object):
    """Call a model constructor, its ValueError/TypeError re-raised at `path`."""
    try:
        return constructor(*args, **kwargs)
    except (ValueError, TypeError) as error:
        raise _located(path, error) from None
    except OverflowError as error:  # an integer too large for int64 or float64
        raise _located(path, ValueError(f"{error}")) from None


# --- scene parts -------------------------------------------------------------------------

_MATERIAL_NUMBERS = ("ambient", "diffuse", "specular", "exponent", "transparency", "fudge")


def _material(path: str, value: object, palette: Mapping[str, Material]) -> Material:
    """An inline material object, or the name of one in the palette."""
    if isinstance(value, str):
        if value not in palette:
            known = ", ".join(palette) if palette else "none: the scene has no 'materials'"
            raise ValueError(f"{path} names an unknown material {value!r}; known: {known}")
        return palette[value]
    if not isinstance(value, Mapping):
        raise TypeError(
            f"{path} must be a material object or the name of one in 'materials'; got {_kind(value)}"
        )
    fields = _object(path, value, (), ("color", *_MATERIAL_NUMBERS))
    kwargs = {k: _number(f"{path}.{k}", v) for k, v in fields.items() if k != "color"}
    if "color" in fields:
        kwargs["color"] = _vector(f"{path}.color", fields["color"], 3)
    return _build(path, Material, **kwargs)


def _camera(path: str, value: object) -> Camera:
    fields = _object(path, value, ("eye", "look_at"), ("up", "window", "near", "far", "projection"))
    kwargs: dict[str, object] = {}
    for key, size in (("eye", 3), ("look_at", 3), ("up", 3), ("window", 4)):
        if key in fields:
            kwargs[key] = _vector(f"{path}.{key}", fields[key], size)
    for key in ("near", "far"):
        if key in fields:
            kwargs[key] = _number(f"{path}.{key}", fields[key])
    if "projection" in fields:
        kwargs["projection"] = _string(f"{path}.projection", fields["projection"])
    return _build(path, Camera, **kwargs)


def _light(path: str, value: object) -> Light:
    kind = _string(f"{path}.kind", _object(path, value, ("kind",), None)["kind"])
    where = {"point": "position", "directional": "direction"}
    if kind not in where:
        raise ValueError(f"{path}.kind must be 'point' or 'directional'; got {kind!r}")
    fields = _object(path, value, ("kind", where[kind]), ("color",))
    kwargs = {key: _vector(f"{path}.{key}", fields[key], 3) for key in fields if key != "kind"}
    return _build(path, Light, kind, **kwargs)


def _rotation(path: str, value: object) -> np.ndarray:
    fields = _object(path, value, ("axis", "degrees"))
    axis = unit_vectors(np.array(_vector(f"{path}.axis", fields["axis"], 3)))
    if not axis.any():
        raise ValueError(f"{path}.axis must not be the zero vector")
    x, y, z = axis
    degrees = _number(f"{path}.degrees", fields["degrees"])
    quarter_turns, rest = divmod(degrees, 90.0)
    if rest == 0:  # exact for multiples of 90 degrees
        cos, sin = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter_turns) % 4]
    else:
        cos, sin = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    cross = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    matrix = np.eye(4)  # Rodrigues: counter-clockwise about the axis seen from its tip
    matrix[:3, :3] = cos * np.eye(3) + sin * cross + (1 - cos) * np.outer((x, y, z), (x, y, z))
    return matrix


def _step(path: str, value: object) -> np.ndarray:
    steps = ("matrix", "rotate", "scale", "translate")
    if len(_object(path, value, (), steps)) != 1:
        raise ValueError(
            f"{path} must have exactly one key, one of {', '.join(steps)}; got {sorted(value)}"
        )
    (name,) = value
    argument, path = value[name], f"{path}.{name}"
    matrix = np.eye(4)
    if name == "translate":
        matrix[:3, 3] = _vector(path, argument, 3)
        if not (np.abs(matrix[:3, 3]) <= WORLD_LIMIT).all():
            raise ValueError(f"{path} must be within +-{WORLD_LIMIT:g}; got {argument}")
    elif name == "scale":
        if isinstance(argument, list | tuple):
            factors = _vector(path, argument, 3)
        else:
            factors = (_number(path, argument),) * 3
        if 0.0 in factors:
            raise ValueError(
                f"{path} factors must be nonzero (the normals need an inverse); got {argument}"
            )
        if not all(1 / LINEAR_LIMIT <= abs(f) <= LINEAR_LIMIT for f in factors):
            raise ValueError(
                f"{path} factors must have magnitudes in [{1 / LINEAR_LIMIT:g}, {LINEAR_LIMIT:g}] "
                f"(the matrix and its inverse stay bounded); got {argument}"
            )
        matrix[:3, :3] = np.diag(factors)
    elif name == "rotate":
        matrix = _rotation(path, argument)
    else:
        rows = _array(path, argument)
        if len(rows) != 4:
            raise ValueError(f"{path} must have 4 rows; got {len(rows)}")
        matrix = np.array(_each(path, rows, _vector, 4))
        try:  # the model's rules: affine, bounded, an invertible 3x3 block
            check_modeling_matrix(matrix)
        except ValueError as error:
            raise ValueError(str(error).replace("'world_from_model'", path, 1)) from None
    return matrix


def _transform(path: str, value: object) -> np.ndarray:
    """world_from_model = T_n @ ... @ T_1: the steps in order, step 1 applied first."""
    steps = _each(path, value, _step)
    if not steps:
        return np.eye(4)
    with np.errstate(all="ignore"):  # an overflowing product is caught just below
        matrix = functools.reduce(lambda world_from_model, step: step @ world_from_model, steps)
    try:
        check_modeling_matrix(matrix)
    except ValueError as error:
        composed = f"{path} (the product of its steps)"
        raise ValueError(str(error).replace("'world_from_model'", composed, 1)) from None
    return matrix


_INLINE_MESH = ("normals", "smooth", "closed", "face_materials", "vertex_materials", "materials")


def _inline_mesh(path: str, fields: Mapping, palette: Mapping[str, Material]) -> Mesh:
    _object(path, fields, ("positions", "faces"), _INLINE_MESH)
    kwargs: dict[str, object] = {
        "positions": _table(f"{path}.positions", fields["positions"], 3, _number),
        "faces": tuple(_table(f"{path}.faces", fields["faces"], None, _integer)),
    }
    if "normals" in fields:
        kwargs["normals"] = _table(f"{path}.normals", fields["normals"], 3, _number)
    for key in ("smooth", "closed"):
        if key in fields:
            kwargs[key] = _boolean(f"{path}.{key}", fields[key])
    for key in ("face_materials", "vertex_materials"):
        if key in fields:
            kwargs[key] = _items(f"{path}.{key}", fields[key], _integer)
    if "materials" in fields:
        kwargs["materials"] = _each(f"{path}.materials", fields["materials"], _material, palette)
    faces, vertices = kwargs["faces"], len(kwargs["positions"])
    corners = sum(map(len, faces))
    check_memory(
        mesh_bytes(len(faces), corners, vertices),
        f"{path} ({len(faces):,} faces, {corners:,} corners, {vertices:,} vertices)",
    )
    return _build(path, Mesh, **kwargs)


def _mesh(path: str, value: object, palette: Mapping[str, Material], base_dir: Path) -> Mesh:
    """An inline mesh, an OBJ file (``{"obj": path}``) or a generator (``{"builtin_mesh": name}``)."""
    if not isinstance(value, Mapping):
        raise TypeError(f"{path} must be an object; got {_kind(value)}")
    if "obj" in value:
        fields = _object(path, value, ("obj",), ("smooth", "closed"))
        file = base_dir / _string(f"{path}.obj", fields["obj"])
        flags = {k: _boolean(f"{path}.{k}", fields[k]) for k in ("smooth", "closed") if k in fields}
        try:
            return load_obj(file, **flags)
        except OSError as error:
            raise type(error)(error.errno, f"{path}.obj: {error.strerror}", str(file)) from None
        except ValueError as error:
            raise ValueError(f"{path}.obj: {error}") from None
    if "builtin_mesh" in value:
        name = _string(f"{path}.builtin_mesh", value["builtin_mesh"])
        if name not in BUILTIN_MESHES:
            raise ValueError(
                f"{path}.builtin_mesh must be one of {', '.join(BUILTIN_MESHES)}; got {name!r}"
            )
        generator = BUILTIN_MESHES[name]
        parameters = tuple(inspect.signature(generator).parameters)
        fields = _object(path, value, ("builtin_mesh",), (*parameters, "smooth", "closed"))
        flags = {k: _boolean(f"{path}.{k}", fields[k]) for k in ("smooth", "closed") if k in fields}
        mesh = _build(path, generator, **{k: fields[k] for k in parameters if k in fields})
        return replace(mesh, **flags) if flags else mesh
    if "positions" in value or "faces" in value:
        return _inline_mesh(path, value, palette)
    raise ValueError(
        f"{path} must hold 'positions' and 'faces', or 'obj' (a file), or 'builtin_mesh' "
        f"(one of {', '.join(BUILTIN_MESHES)}); got keys {sorted(value)}"
    )


def _scene_object(
    path: str, value: object, palette: Mapping[str, Material], base_dir: Path
) -> SceneObject:
    fields = _object(path, value, ("mesh",), ("name", "material", "transform"))
    return _build(
        path,
        SceneObject,
        _mesh(f"{path}.mesh", fields["mesh"], palette, base_dir),
        _material(f"{path}.material", fields.get("material", {}), palette),
        _transform(f"{path}.transform", fields.get("transform", [])),
        _string(f"{path}.name", fields.get("name", "")),
    )


# --- public API --------------------------------------------------------------------------

_SCENE_KEYS = ("version", "name", "ambient", "background", "materials")


def scene_from_dict(data: Mapping, base_dir: str | os.PathLike | None = None) -> Scene:
    """Build and validate a `Scene` from its JSON form (parsed JSON: dicts, lists, numbers).

    Parameters
    ----------
    data : Mapping
        The scene object; see ``docs/scene-format.md``.
    base_dir : str or path-like, optional
        Where relative ``"obj"`` paths start; the current directory if None.

    Returns
    -------
    Scene

    Raises
    ------
    ValueError, TypeError
        For a missing, unknown or malformed key, or a value breaking a rule of
        the scene model; the message names the JSON path of the bad value.

    Examples
    --------
    >>> scene = scene_from_dict({
    ...     "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    ...     "lights": [{"kind": "directional", "direction": [0, 0, -1]}],
    ...     "materials": {"red": {"color": [1, 0, 0]}},
    ...     "objects": [{
    ...         "mesh": {"positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]]},
    ...         "material": "red",
    ...         "transform": [{"scale": 2}, {"translate": [1, 0, 0]}],
    ...     }],
    ... })
    >>> scene.objects[0].material.color, scene.objects[0].world_from_model[0].tolist()
    ((1.0, 0.0, 0.0), [2.0, 0.0, 0.0, 1.0])
    >>> scene_from_dict({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "near": 2, "far": 1},
    ...                  "lights": [], "objects": []})
    Traceback (most recent call last):
    ...
    ValueError: camera.near must be < 'far'; got near=2.0, far=1.0
    """
    fields = _object("", data, ("camera", "lights", "objects"), _SCENE_KEYS)
    if "version" in fields and _integer("version", fields["version"]) != FORMAT_VERSION:
        raise ValueError(f"version must be {FORMAT_VERSION}; got {fields['version']}")
    base = Path(base_dir) if base_dir is not None else Path()
    palette: dict[str, Material] = {}
    if "materials" in fields:
        materials = _object("materials", fields["materials"], (), None)
        for name, value in materials.items():
            if isinstance(value, str):
                raise TypeError(f"materials.{name} must be a material object; got a string")
            palette[name] = _material(f"materials.{name}", value, {})
    kwargs: dict[str, object] = {
        "camera": _camera("camera", fields["camera"]),
        "lights": _each("lights", fields["lights"], _light),
        "objects": _each("objects", fields["objects"], _scene_object, palette, base),
    }
    for key in ("ambient", "background"):
        if key in fields:
            kwargs[key] = _vector(key, fields[key], 3)
    if "name" in fields:
        kwargs["name"] = _string("name", fields["name"])
    return _build("", Scene, **kwargs)


def _check_depth(text: str, where: str) -> None:
    """Refuse JSON nested deeper than `MAX_DEPTH` before parsing it (the parser recurses)."""
    depth, _ = json_nesting(text)
    if depth > MAX_DEPTH:
        raise ValueError(
            f"{where}: JSON nested {depth} deep; a scene file may nest at most {MAX_DEPTH} deep"
        )


def _parse_int(literal: str) -> int:
    if len(literal.lstrip("-")) > MAX_INTEGER_DIGITS:
        raise ValueError(
            f"an integer literal of {len(literal.lstrip('-'))} digits is beyond float64 "
            f"(at most {MAX_INTEGER_DIGITS} digits are read)"
        )
    return int(literal)


def read_json(path: str | os.PathLike) -> object:
    """Parse a JSON file, bounded: `scanviz.limits.read_bounded`, `MAX_DEPTH`, `MAX_INTEGER_DIGITS`.

    Raises ValueError (naming the file) for a file that is not a regular
    file, text that is not UTF-8 or not JSON, nests too deep or holds an
    over-long integer; `scanviz.limits.ResourceLimitError` if its parse
    (`JSON_BYTES` a character) would pass the memory limit; OSError if unreadable.
    """
    text = read_bounded(path)
    _check_depth(text, repr(str(path)))
    check_memory(
        JSON_BYTES * len(text), f"parsing {str(path)!r} ({len(text):,} characters of JSON)"
    )
    try:
        return json.loads(text, parse_int=_parse_int)
    except json.JSONDecodeError as error:
        raise ValueError(f"{str(path)!r}: not valid JSON: {error}") from None
    except ValueError as error:  # from _parse_int
        raise ValueError(f"{str(path)!r}: {error}") from None


def is_obj_path(source: object) -> bool:
    """Whether `source` names an OBJ file: a path ending in ``.obj``, in any case."""
    return isinstance(source, str | os.PathLike) and os.fspath(source).lower().endswith(_OBJ_SUFFIX)


def load_scene(source: str | os.PathLike | Mapping) -> Scene:
    """Load a scene from a JSON file, an OBJ model, a parsed JSON dict, or ``"builtin:NAME"``.

    Parameters
    ----------
    source : str, path-like or Mapping
        ``"builtin:NAME"`` for `scanviz.scene.builtin_scene` (NAME in
        `scanviz.scene.BUILTIN_SCENES`); a Mapping for `scene_from_dict`; a
        path ending in ``.obj`` (any case) for an OBJ model, framed by
        `frame_model` (camera, lights and a neutral material chosen for it);
        otherwise the path of a JSON file, whose directory relative
        ``"obj"`` paths start from.

    Returns
    -------
    Scene

    Raises
    ------
    ValueError, TypeError
        As `scene_from_dict` or `load_obj`, the message prefixed with the file
        name; also for a file that is not UTF-8, not valid JSON, nested deeper
        than `MAX_DEPTH`, or larger than the file limit
        (`scanviz.limits.read_bounded`).
    OSError
        If a file cannot be read.

    Examples
    --------
    >>> load_scene("builtin:painter").objects[2].mesh.positions[0].tolist()
    [6.0, 5.0, 5.0]
    """
    if isinstance(source, Mapping):
        return scene_from_dict(source)
    if isinstance(source, str) and source.startswith(BUILTIN_PREFIX):
        return builtin_scene(source[len(BUILTIN_PREFIX) :])
    if not isinstance(source, str | os.PathLike):
        raise TypeError(f"'source' must be a path, a dict or 'builtin:NAME'; got {_kind(source)}")
    path = Path(source)
    if is_obj_path(path):
        return frame_model(load_obj(path), name=path.stem)
    data = read_json(path)
    try:
        return scene_from_dict(data, base_dir=path.parent)
    except (ValueError, TypeError) as error:
        raise type(error)(f"{str(path)!r}: {error}") from None


def _material_dict(material: Material) -> dict:
    return {"color": list(material.color)} | {k: getattr(material, k) for k in _MATERIAL_NUMBERS}


def _mesh_dict(mesh: Mesh) -> dict:
    data: dict[str, object] = {
        "positions": mesh.positions.tolist(),
        "faces": [face.tolist() for face in mesh.faces],
    }
    for key in ("normals", "face_materials", "vertex_materials"):
        if getattr(mesh, key) is not None:
            data[key] = getattr(mesh, key).tolist()
    if mesh.materials:
        data["materials"] = [_material_dict(m) for m in mesh.materials]
    return data | {"smooth": mesh.smooth, "closed": mesh.closed}


def scene_to_dict(scene: Scene) -> dict:
    """The JSON form of a scene: ``scene_from_dict(scene_to_dict(s))`` reproduces every field.

    Meshes are written inline, materials in full, transforms as one
    ``{"matrix": ...}`` step (none for the identity). Floats are written as
    Python floats, whose JSON text reads back exactly.

    Examples
    --------
    >>> from scanviz.scene import builtin_scene
    >>> data = scene_to_dict(builtin_scene("umbc_zbuffer"))
    >>> data["camera"]["window"], data["objects"][0]["transform"]
    ([0.0, 12.0, 0.0, 12.0], [{'matrix': [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]}])
    >>> data["objects"][0]["mesh"]["positions"]
    [[1.0, 1.0, 5.0], [7.0, 7.0, 5.0], [1.0, 7.0, 5.0]]
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"'scene' must be a scanviz.scene.Scene; got {type(scene).__name__}")
    camera = {k: list(getattr(scene.camera, k)) for k in ("eye", "look_at", "up", "window")}
    camera |= {k: getattr(scene.camera, k) for k in ("near", "far", "projection")}
    objects = []
    for obj in scene.objects:
        data: dict[str, object] = {"name": obj.name} if obj.name else {}
        data |= {"mesh": _mesh_dict(obj.mesh), "material": _material_dict(obj.material)}
        if not np.array_equal(obj.world_from_model, np.eye(4)):
            data["transform"] = [{"matrix": obj.world_from_model.tolist()}]
        objects.append(data)
    lights = []
    for light in scene.lights:
        where = "position" if light.kind == "point" else "direction"
        lights.append(
            {"kind": light.kind, "color": list(light.color), where: list(getattr(light, where))}
        )
    return {
        "version": FORMAT_VERSION,
        "name": scene.name,
        "camera": camera,
        "lights": lights,
        "ambient": list(scene.ambient),
        "background": list(scene.background),
        "objects": objects,
    }

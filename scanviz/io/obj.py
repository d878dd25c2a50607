"""Wavefront OBJ meshes: positions, normals and polygon faces.

What is read:

* ``v x y z [w]`` positions (a ``w`` weight is ignored; so are the r g b of
  the common ``v x y z r g b`` extension);
* ``vn x y z`` normals, normalized on reading (the format does not require
  unit length);
* ``f`` polygons of any size >= 3, each corner ``v``, ``v/vt``, ``v//vn`` or
  ``v/vt/vn``; indices start at 1, negative indices count back from the last
  element defined so far (-1 is the latest), positive ones may refer forward;
* ``#`` comments anywhere on a line, and ``\\`` line continuations; LF or CRLF
  line ends, and a leading UTF-8 byte-order mark.

Ignored, because a `~scanviz.scene.Mesh` has no place for them: texture
coordinates (``vt``, ``vp``), grouping and naming (``o``, ``g``, ``s``,
``mg``), materials (``usemtl``, ``mtllib``, ``usemap``, ``maplib``), point
and line elements (``p``, ``l``) and display attributes (``lod``, ``bevel``,
``c_interp``, ``d_interp``, ``shadow_obj``, ``trace_obj``). Free-form curves
and surfaces (``cstype``, ``curv``, ``surf``, ...) and unknown statements
raise, so that a file is never half read without notice.

Normals: if every face corner names a normal, the mesh gets per-vertex
normals. A mesh vertex is then one distinct (position, normal) pair, so a
position used with different normals in different faces (the corners of a
faceted cube) is split into one vertex per normal; vertices are ordered by
position index, then normal index, and positions no face uses are dropped.
If some corner has no normal, all normals are ignored and the renderer
derives them (``normals=None``); positions then keep the file's order.

Framing: `frame_model` puts a mesh in a scene of its own, with a camera on its
bounding sphere, two lights and a neutral material; ``load_scene("m.obj")``
(`scanviz.io.load_scene`) and ``python -m scanviz render m.obj`` use it.
"""

from __future__ import annotations

import math
import os
from array import array
from collections.abc import Iterator
from typing import NamedTuple

import numpy as np

from ..limits import check_memory, read_bounded
from ..scene.model import Camera, Light, Material, Mesh, Scene, SceneObject, mesh_bytes
from ..vectors import unit_vectors, vector_norm

IGNORED = frozenset(
    "vt vp o g s mg usemtl mtllib usemap maplib p l lod bevel c_interp d_interp shadow_obj "
    "trace_obj".split()
)
FREE_FORM = frozenset(
    "cstype deg bmat step curv curv2 surf parm trim hole scrv sp end con ctech stech".split()
)


_CHUNK = 2**20  # characters split into lines at once, so the file's lines never all exist together


def _lines(text: str) -> Iterator[str]:
    """``text.splitlines()``, lazily: chunks cut just after a newline split the same way."""
    start = 0
    while start < len(text):
        end = text.find("\n", start + _CHUNK) + 1 or len(text)
        yield from text[start:end].splitlines()
        start = end


def _statements(text: str) -> Iterator[tuple[int, str, list[str]]]:
    """Yield (line number, keyword, arguments) per statement, comments and continuations removed."""
    pending, start = "", 0
    for number, line in enumerate(_lines(text), 1):
        line = line.split("#", 1)[0].rstrip()
        if line.endswith("\\"):  # continues on the next line
            pending, start = pending + line[:-1] + " ", start or number
            continue
        tokens = (pending + line).split()
        if tokens:
            yield start or number, tokens[0], tokens[1:]
        pending, start = "", 0
    if pending.split():
        yield start, pending.split()[0], pending.split()[1:]


def _numbers(where: str, keyword: str, arguments: list[str]) -> list[float]:
    try:
        values = [float(a) for a in arguments]
    except ValueError:
        raise ValueError(
            f"{where}: {keyword!r} needs numbers; got {' '.join(arguments)!r}"
        ) from None
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"{where}: {keyword!r} values must be finite; got {values}")
    return values


_MAX_INDEX = 2**62


def _index(where: str, token: str, count: int, element: str) -> int:
    """0-based index of an OBJ reference (1-based, or negative from the end so far)."""
    try:
        index = int(token)
    except ValueError:
        raise ValueError(f"{where}: {element} index {token!r} is not an integer") from None
    if index == 0:
        raise ValueError(f"{where}: {element} index 0 is invalid; OBJ indices start at 1")
    if index < 0:
        if -index > count:
            raise ValueError(
                f"{where}: {element} index {index} reaches before the first one; "
                f"{count} defined so far"
            )
        return count + index
    if index > _MAX_INDEX:  # kept in an int64 array until the final count is known
        raise ValueError(f"{where}: {element} index {index} is out of range (over 2**62)")
    return index - 1  # checked against the final count: OBJ allows forward references


class _Parsed(NamedTuple):
    """An OBJ file's elements in flat arrays (8 bytes a number: no Python object per corner)."""

    positions: array  # x y z of each 'v', float64
    normals: array  # unit x y z of each 'vn', float64
    corner_vertex: array  # 0-based position index of each face corner, int64
    corner_normal: array  # 0-based normal index of each corner, -1 if it names none
    face_sizes: array  # corners of each face
    face_lines: array  # line of each face, for messages


def _parse(text: str, origin: str) -> _Parsed:
    """The positions, unit normals and faces of OBJ `text`, every index checked."""
    parsed = _Parsed(array("d"), array("d"), array("q"), array("q"), array("q"), array("q"))
    positions, normals, corner_vertex, corner_normal, face_sizes, face_lines = parsed
    for number, keyword, arguments in _statements(text):
        where = f"{origin}line {number}"
        if keyword == "v":
            if len(arguments) not in (3, 4, 6):
                raise ValueError(
                    f"{where}: 'v' needs x y z, x y z w or x y z r g b; got {len(arguments)} values"
                )
            positions.extend(_numbers(where, keyword, arguments)[:3])
        elif keyword == "vn":
            if len(arguments) != 3:
                raise ValueError(f"{where}: 'vn' needs 3 values; got {len(arguments)}")
            normal = unit_vectors(np.array(_numbers(where, keyword, arguments)))
            if not normal.any():
                raise ValueError(f"{where}: 'vn' must not be the zero vector")
            normals.extend(normal.tolist())
        elif keyword == "f":
            if len(arguments) < 3:
                raise ValueError(f"{where}: a face needs >= 3 corners; got {len(arguments)}")
            for corner in arguments:
                parts = corner.split("/")
                if len(parts) > 3 or not parts[0]:
                    raise ValueError(
                        f"{where}: face corner {corner!r} is not v, v/vt, v//vn or v/vt/vn"
                    )
                corner_vertex.append(_index(where, parts[0], len(positions) // 3, "vertex"))
                if len(parts) > 1 and parts[1]:
                    _index(where, parts[1], math.inf, "texture")  # syntax checked, then ignored
                corner_normal.append(
                    _index(where, parts[2], len(normals) // 3, "normal")
                    if len(parts) == 3 and parts[2]
                    else -1
                )
            face_sizes.append(len(arguments))
            face_lines.append(number)
        elif keyword in FREE_FORM:
            raise ValueError(f"{where}: free-form geometry ({keyword!r}) is not supported")
        elif keyword not in IGNORED:
            raise ValueError(f"{where}: unknown statement {keyword!r}")
    # Forward references are checked against the final counts, first corner first.
    counts = {"vertex": len(positions) // 3, "normal": len(normals) // 3}
    out = {
        "vertex": np.frombuffer(corner_vertex, np.int64) >= counts["vertex"],
        "normal": np.frombuffer(corner_normal, np.int64) >= counts["normal"],
    }
    wrong = np.flatnonzero(out["vertex"] | out["normal"])
    if wrong.size:
        first = int(wrong[0])
        element = "vertex" if out["vertex"][first] else "normal"
        index = (corner_vertex if element == "vertex" else corner_normal)[first]
        face = int(np.searchsorted(np.cumsum(face_sizes), first, side="right"))
        raise ValueError(
            f"{origin}line {face_lines[face]}: {element} index {index + 1} is out of range "
            f"1..{counts[element]} ({'v' if element == 'vertex' else 'vn'!r} lines in the file)"
        )
    return parsed


_TEXT_BYTES = 12
"""Bytes the parse holds per character of OBJ text, at most: it keeps 8 bytes a number in flat
arrays (measured with tracemalloc: 10 for "f 1 2 3" lines, 1.5 for "v" lines)."""


def load_obj(source: str | os.PathLike, *, smooth: bool = True, closed: bool = False) -> Mesh:
    """Read a Wavefront OBJ mesh from a file or from OBJ text.

    Parameters
    ----------
    source : str or path-like
        A path, or OBJ text: a ``str`` holding a newline is text, any other
        ``str`` or path-like object is a file name.
    smooth : bool
        Passed to `Mesh` (``s`` smoothing groups are ignored); it matters
        only when the file has no normals.
    closed : bool
        Whether the mesh bounds a solid, so that back faces may be culled.
        The file cannot say; the default keeps every face.

    Returns
    -------
    Mesh
        See the module notes for how normals split vertices.

    Raises
    ------
    ValueError
        For a malformed statement, an index out of range, an unsupported or
        unknown statement, naming the file and line; for a file that is not
        UTF-8 or larger than the file limit (`scanviz.limits.read_bounded`),
        or text whose parse would pass the memory limit.
    OSError
        If the file cannot be read.

    Examples
    --------
    >>> mesh = load_obj('''
    ... v 0 0 0
    ... v 1 0 0
    ... v 1 1 0
    ... v 0 1 0
    ... f 1 2 -2 -1   # a quad, the last two corners counted from the end
    ... ''')
    >>> [face.tolist() for face in mesh.faces], mesh.normals
    ([[0, 1, 2, 3]], None)
    >>> load_obj("v 0 0 0\\nf 1 2 3\\n")
    Traceback (most recent call last):
    ...
    ValueError: line 2: vertex index 2 is out of range 1..1 ('v' lines in the file)
    """
    if isinstance(source, str) and "\n" in source:
        text, origin = source.removeprefix("\ufeff"), ""
    elif isinstance(source, str | os.PathLike):
        text, origin = read_bounded(source), f"{str(source)!r}, "
    else:
        raise TypeError(f"'source' must be a path or OBJ text; got {type(source).__name__}")
    name = origin.removesuffix(", ") or "the OBJ text"
    # Before the (slow) parse: a line "f ..." is a face unless a backslash continued the line before.
    least = max(0, text.count("\nf ") + text.startswith("f ") - text.count("\\"))
    check_memory(
        _TEXT_BYTES * len(text) + mesh_bytes(least, 3 * least, 0),
        f"reading {name} ({len(text):,} characters of OBJ, at least {least:,} faces)",
    )
    parsed = _parse(text, origin)
    faces, corners = len(parsed.face_sizes), len(parsed.corner_vertex)
    vertices = len(parsed.positions) // 3
    check_memory(
        mesh_bytes(faces, corners, vertices),
        f"the mesh of {name} ({faces:,} faces, {corners:,} corners, {vertices:,} vertices)",
    )
    positions = np.frombuffer(parsed.positions, np.float64).reshape(-1, 3)
    vertex = np.frombuffer(parsed.corner_vertex, np.int64)
    normal = np.frombuffer(parsed.corner_normal, np.int64)
    cuts = np.cumsum(parsed.face_sizes)[:-1]
    if not corners or (normal < 0).any():
        faces_of = tuple(np.split(vertex, cuts)) if faces else ()
        return Mesh(positions, faces_of, smooth=smooth, closed=closed)
    normals = np.frombuffer(parsed.normals, np.float64).reshape(-1, 3)
    keys = vertex * len(normals) + normal  # one mesh vertex per (position, normal)
    unique, inverse = np.unique(keys, return_inverse=True)
    return Mesh(
        positions[unique // len(normals)],
        tuple(np.split(inverse.reshape(-1), cuts)),
        normals=normals[unique % len(normals)],
        smooth=smooth,
        closed=closed,
    )


# Framing: the camera looks at the bounding sphere's centre from this direction (+z, a bit
# above: 18.4 degrees), with a vertical half field of view of 20 degrees.
FRAME_DIRECTION = (0.0, 1.0, 3.0)
FRAME_HALF_ANGLE = math.radians(20.0)
FRAME_MARGIN = 1.1  # the sphere, grown by 10 %, just fits the window's smaller side
FRAME_LIGHTS = (
    Light("directional", color=(0.85, 0.85, 0.8), direction=(1.0, -1.0, -2.0)),  # key, upper left
    Light("directional", color=(0.25, 0.27, 0.35), direction=(-1.0, 0.5, -1.0)),  # fill, right
)
FRAME_BACKGROUND = (0.08, 0.08, 0.1)


def bounding_sphere(positions: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre of the axis-aligned bounding box and the largest distance from it to a position.

    >>> centre, radius = bounding_sphere(np.array([[0.0, 0, 0], [2, 0, 0], [0, 2, 0]]))
    >>> centre.tolist(), round(radius, 6)
    ([1.0, 1.0, 0.0], 1.414214)
    """
    if not len(positions):
        return np.zeros(3), 0.0
    low, high = positions.min(axis=0), positions.max(axis=0)
    centre = low / 2 + high / 2  # halves first: no overflow
    return centre, float(vector_norm(positions - centre).max())


def frame_model(mesh: Mesh, *, aspect: float = 1.0, name: str = "") -> Scene:
    """A scene showing `mesh` whole: camera on its bounding sphere, two lights, a neutral material.

    Parameters
    ----------
    mesh : Mesh
        Placed as is (identity ``world_from_model``).
    aspect : float
        Width / height of the raster the window is made for, in [1e-3, 1e3].
    name : str
        Of the scene and of its one object.

    Returns
    -------
    Scene
        A perspective camera at centre + d * (0, 1, 3) / ‖(0, 1, 3)‖ (from +z,
        18.4 degrees above) looking at the bounding sphere's centre (see
        `bounding_sphere`), up +y, at the distance d = 1.1 r / sin(20 deg)
        where the sphere grown by 10 % fills the window's smaller side (a
        half-angle of 20 degrees); near = d - 1.1 r, far = d + 1.1 r. A mesh
        with no extent is framed as a sphere of radius 1 (or of 1e-9 of its
        distance from the origin, if larger). Lights `FRAME_LIGHTS`: a key light
        from the upper left and a dim blue fill from the right; the default
        `Material` (grey 0.8, ambient 0.15, diffuse 0.7, specular 0.3,
        exponent 32); background `FRAME_BACKGROUND`.

    Examples
    --------
    >>> scene = frame_model(load_obj("v 0 0 0\\nv 2 0 0\\nv 0 2 0\\nf 1 2 3\\n"))
    >>> scene.camera.look_at, round(scene.camera.near, 3), round(scene.camera.far, 3)
    ((1.0, 1.0, 0.0), 2.993, 6.104)
    """
    if not isinstance(mesh, Mesh):
        raise TypeError(f"'mesh' must be a Mesh; got {type(mesh).__name__}")
    if isinstance(aspect, bool) or not isinstance(aspect, int | float) or not 1e-3 <= aspect <= 1e3:
        raise ValueError(f"'aspect' must be a number in [0.001, 1000]; got {aspect!r}")
    centre, radius = bounding_sphere(mesh.positions)
    if not radius > 0:
        radius = max(1.0, 1e-9 * float(np.abs(centre).max()))
    radius = max(radius, 1e-9 * float(np.abs(centre).max()))  # resolvable at the centre
    reach = FRAME_MARGIN * radius
    distance = reach / math.sin(FRAME_HALF_ANGLE)
    near, far = distance - reach, distance + reach
    half = math.tan(FRAME_HALF_ANGLE) * near  # the smaller side's half extent on the near plane
    half_width, half_height = (half * aspect, half) if aspect >= 1 else (half, half / aspect)
    eye = centre + distance * unit_vectors(np.array(FRAME_DIRECTION))
    try:
        camera = Camera(
            eye=tuple(eye.tolist()),
            look_at=tuple(centre.tolist()),
            window=(-half_width, half_width, -half_height, half_height),
            near=near,
            far=far,
        )
    except ValueError as error:
        raise ValueError(
            f"cannot frame the model (bounding sphere at {centre.tolist()}, radius {radius:g}): "
            f"{error}"
        ) from None
    return Scene(
        (SceneObject(mesh, Material(), name=name),),
        camera,
        lights=FRAME_LIGHTS,
        background=FRAME_BACKGROUND,
        name=name,
    )

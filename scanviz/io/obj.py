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
from collections.abc import Iterator

import numpy as np

from ..limits import check_memory, read_bounded
from ..scene.model import Camera, Light, Material, Mesh, Scene, SceneObject
from ..vectors import unit_vectors, vector_norm

IGNORED = frozenset(
    "vt vp o g s mg usemtl mtllib usemap maplib p l lod bevel c_interp d_interp shadow_obj "
    "trace_obj".split()
)
FREE_FORM = frozenset(
    "cstype deg bmat step curv curv2 surf parm trim hole scrv sp end con ctech stech".split()
)


def _statements(text: str) -> Iterator[tuple[int, str, list[str]]]:
    """Yield (line number, keyword, arguments) per statement, comments and continuations removed."""
    pending, start = "", 0
    for number, line in enumerate(text.splitlines(), 1):
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
    return index - 1  # checked against the final count: OBJ allows forward references


def _parse(text: str, origin: str) -> tuple[list, list, list]:
    """Positions, unit normals and faces as (line, [(position, normal or None), ...])."""
    positions: list[list[float]] = []
    normals: list[np.ndarray] = []
    faces: list[tuple[int, list[tuple[int, int | None]]]] = []
    for number, keyword, arguments in _statements(text):
        where = f"{origin}line {number}"
        if keyword == "v":
            if len(arguments) not in (3, 4, 6):
                raise ValueError(
                    f"{where}: 'v' needs x y z, x y z w or x y z r g b; got {len(arguments)} values"
                )
            positions.append(_numbers(where, keyword, arguments)[:3])
        elif keyword == "vn":
            if len(arguments) != 3:
                raise ValueError(f"{where}: 'vn' needs 3 values; got {len(arguments)}")
            normal = unit_vectors(np.array(_numbers(where, keyword, arguments)))
            if not normal.any():
                raise ValueError(f"{where}: 'vn' must not be the zero vector")
            normals.append(normal)
        elif keyword == "f":
            if len(arguments) < 3:
                raise ValueError(f"{where}: a face needs >= 3 corners; got {len(arguments)}")
            corners = []
            for corner in arguments:
                parts = corner.split("/")
                if len(parts) > 3 or not parts[0]:
                    raise ValueError(
                        f"{where}: face corner {corner!r} is not v, v/vt, v//vn or v/vt/vn"
                    )
                vertex = _index(where, parts[0], len(positions), "vertex")
                if len(parts) > 1 and parts[1]:
                    _index(where, parts[1], math.inf, "texture")  # syntax checked, then ignored
                normal = (
                    _index(where, parts[2], len(normals), "normal")
                    if len(parts) == 3 and parts[2]
                    else None
                )
                corners.append((vertex, normal))
            faces.append((number, corners))
        elif keyword in FREE_FORM:
            raise ValueError(f"{where}: free-form geometry ({keyword!r}) is not supported")
        elif keyword not in IGNORED:
            raise ValueError(f"{where}: unknown statement {keyword!r}")
    for number, corners in faces:
        for vertex, normal in corners:
            for index, count, element, keyword in (
                (vertex, len(positions), "vertex", "v"),
                (normal, len(normals), "normal", "vn"),
            ):
                if index is not None and index >= count:
                    raise ValueError(
                        f"{origin}line {number}: {element} index {index + 1} is out of range "
                        f"1..{count} ({keyword!r} lines in the file)"
                    )
    return positions, normals, faces


_BYTES_PER_CHARACTER = 12


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
    # Python lists of parsed numbers take about 12 bytes per byte of OBJ text (measured).
    check_memory(_BYTES_PER_CHARACTER * len(text), f"reading {len(text):,} characters of OBJ")
    positions, normals, faces = _parse(text, origin)
    sizes = [len(corners) for _, corners in faces]
    corners = [corner for _, face in faces for corner in face]
    if not corners or any(normal is None for _, normal in corners):
        return Mesh(
            np.array(positions, dtype=np.float64).reshape(-1, 3),
            tuple(np.array([v for v, _ in face]) for _, face in faces),
            smooth=smooth,
            closed=closed,
        )
    pairs = np.array(corners, dtype=np.int64)
    keys = pairs[:, 0] * len(normals) + pairs[:, 1]  # one mesh vertex per (position, normal)
    unique, inverse = np.unique(keys, return_inverse=True)
    return Mesh(
        np.array(positions)[unique // len(normals)],
        tuple(np.split(inverse.reshape(-1), np.cumsum(sizes)[:-1])),
        normals=np.array(normals)[unique % len(normals)],
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

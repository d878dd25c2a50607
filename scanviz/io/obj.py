"""Wavefront OBJ meshes: positions, normals and polygon faces.

What is read:

* ``v x y z [w]`` positions (a ``w`` weight is ignored; so are the r g b of
  the common ``v x y z r g b`` extension);
* ``vn x y z`` normals, normalized on reading (the format does not require
  unit length);
* ``f`` polygons of any size >= 3, each corner ``v``, ``v/vt``, ``v//vn`` or
  ``v/vt/vn``; indices start at 1, negative indices count back from the last
  element defined so far (-1 is the latest), positive ones may refer forward;
* ``#`` comments anywhere on a line, and ``\\`` line continuations.

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
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ..scene.model import Mesh

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
            normal = np.array(_numbers(where, keyword, arguments))
            length = np.linalg.norm(normal)
            if not length > 0:
                raise ValueError(f"{where}: 'vn' must not be the zero vector")
            normals.append(normal / length)
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
        unknown statement, naming the file and line.

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
        text, origin = source, ""
    elif isinstance(source, str | os.PathLike):
        text, origin = Path(source).read_text(encoding="utf-8", errors="replace"), f"{source}, "
    else:
        raise TypeError(f"'source' must be a path or OBJ text; got {type(source).__name__}")
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

"""Phong illumination of surface points, and the normals it needs (world space).

At a point with unit normal N, unit vector V toward the viewer and material
color Od (Phong 1975; the thesis' OPTICAL structure, App. B.7)::

    I = ka Ia Od + sum over lights  f_att Il [kd Od max(N.L, 0) + ks max(R.V, 0)^n]

L is the unit vector toward the light, R = 2(N.L)N - L its mirror image about
N, and the specular term is white and only present where N.L > 0. A point
light at distance d is attenuated by f_att = 1 / (1 + fudge d); a directional
light is not (f_att = 1). Lighting is two-sided: a point seen from behind
(N.V < 0) is lit as if its normal were reversed. The result is clipped to
[0, 1]. docs/shading.md derives the model and says where each shading method
(flat, Gouraud, Phong) evaluates it.

Every function works on N points at once with elementwise numpy arithmetic
only; dot products are written out as a0 b0 + a1 b1 + a2 b2, never as a
reduction (np.sum, einsum) whose order of additions may depend on the array
length. So a point shaded alone gets bit for bit the color it gets among many,
which is what lets the traced, one-point-at-a-time reference match the fast
path exactly.

Materials travel as rows of an (N, 9) float64 array with columns
`MATERIAL_FIELDS` (see `material_array`).
"""

from __future__ import annotations

import numbers
from collections.abc import Iterable, Sequence

import numpy as np
from numba import njit

from ..conventions import as_array, check_finite, check_finite_rows, type_name
from ..scene.faces import FaceCorners, face_corners, newell
from ..scene.model import Light, Material
from ..trace import Tracer
from ..trace.events import Illumination, LightTerm
from ..vectors import unit_vectors, vector_norm

MATERIAL_FIELDS = (
    "r",
    "g",
    "b",
    "ambient",
    "diffuse",
    "specular",
    "exponent",
    "transparency",
    "fudge",
)
_COLOR = slice(0, 3)
_AMBIENT, _DIFFUSE, _SPECULAR, _EXPONENT = 3, 4, 5, 6
_FUDGE = 8
_DEGENERATE = 1e-12  # a face whose area is below this fraction of its squared size has no normal


def material_array(materials: Iterable[Material]) -> np.ndarray:
    """Pack materials into rows of floats, columns `MATERIAL_FIELDS`.

    Parameters
    ----------
    materials : iterable of Material

    Returns
    -------
    (M, 9) ndarray of float64
        Row i is r, g, b, ambient, diffuse, specular, exponent, transparency,
        fudge of ``materials[i]``.

    Examples
    --------
    >>> material_array([Material(color=(1, 0.5, 0), exponent=8)])
    array([[1.  , 0.5 , 0.  , 0.15, 0.7 , 0.3 , 8.  , 0.  , 0.  ]])
    """
    rows = []
    for i, material in enumerate(materials):
        if not isinstance(material, Material):
            raise TypeError(f"'materials[{i}]' must be a Material; got {type(material).__name__}")
        rows.append(
            (
                *material.color,
                material.ambient,
                material.diffuse,
                material.specular,
                material.exponent,
                material.transparency,
                material.fudge,
            )
        )
    return np.array(rows, dtype=np.float64).reshape(-1, len(MATERIAL_FIELDS))


# --- validation at the boundary ----------------------------------------------------------


def _rows(name: str, value: object, columns: int, count: int | None = None) -> np.ndarray:
    array = as_array(value, f"{name!r} must be an array of numbers", got=type_name)
    if array.ndim != 2 or array.shape[1] != columns:
        raise ValueError(f"{name!r} must be an (N, {columns}) array; got shape {array.shape}")
    if count is not None and len(array) != count:
        raise ValueError(f"{name!r} must have one row per position ({count}); got {len(array)}")
    return check_finite_rows(name, array)


def _vector(name: str, value: object, size: int = 3) -> np.ndarray:
    array = as_array(value, f"{name!r} must be {size} numbers", got=repr)
    if array.shape != (size,):
        raise ValueError(f"{name!r} must have shape ({size},); got {array.shape}")
    return check_finite(name, array)


def _materials(value: object, count: int) -> np.ndarray:
    materials = _rows("materials", value, len(MATERIAL_FIELDS), count)
    for column in (_EXPONENT, _FUDGE):
        negative = np.flatnonzero(materials[:, column] < 0)
        if negative.size:
            raise ValueError(
                f"'materials' row {negative[0]}: {MATERIAL_FIELDS[column]} must be >= 0; "
                f"got {materials[negative[0], column]}"
            )
    return materials


def _lights(lights: object) -> tuple[Light, ...]:
    if not isinstance(lights, Sequence):
        raise TypeError(f"'lights' must be a sequence of Light; got {type(lights).__name__}")
    for i, light in enumerate(lights):
        if not isinstance(light, Light):
            raise TypeError(f"'lights[{i}]' must be a Light; got {type(light).__name__}")
    return tuple(lights)


def _ambient(value: object) -> np.ndarray:
    ambient = _vector("ambient_light", value)
    if (ambient < 0).any():
        raise ValueError(f"'ambient_light' components must be >= 0; got {ambient.tolist()}")
    return ambient


def _check_tracer(trace: object) -> None:
    if trace is not None and not isinstance(trace, Tracer):
        raise TypeError(f"'trace' must be None or a Tracer (wants/emit); got {trace!r}")


# --- vectors, one row per point ----------------------------------------------------------


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise a . b, written out so each row's arithmetic is the same for any N."""
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + a[:, 2] * b[:, 2]


def _unit(vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows scaled to unit length, and their lengths; zero rows stay zero (no overflow, no underflow)."""
    return unit_vectors(vectors), vector_norm(vectors)


def _unit_between(start: np.ndarray, end: object) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors from each row of `start` toward `end`, and the distances (inf beyond float64).

    Both ends are halved first (exact), so the difference of two finite points never overflows.
    """
    half, length = _unit(np.asarray(end, dtype=np.float64) / 2 - start / 2)
    with np.errstate(over="ignore"):
        return half, 2 * length


def _to_viewer(positions: np.ndarray, eye: object, view_dir: object) -> np.ndarray:
    """V at every point: toward the eye (perspective) or along `view_dir` (orthographic)."""
    if (eye is None) == (view_dir is None):
        raise ValueError(
            "give exactly one of 'eye' (the viewer's position) and "
            "'view_dir' (the direction toward an orthographic viewer)"
        )
    if eye is not None:
        return _unit_between(positions, _vector("eye", eye))[0]
    view = _vector("view_dir", view_dir)
    if not np.abs(view).max() > 0:
        raise ValueError("'view_dir' must not be the zero vector")
    direction, _ = _unit(view[None])
    return np.broadcast_to(direction, positions.shape)


def _facing_viewer(normals: np.ndarray, view: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals turned toward the viewer (two-sided lighting), and which were reversed."""
    unit, _ = _unit(normals)
    flipped = _dot(unit, view) < 0  # seen from behind: light the visible side
    return np.where(flipped[:, None], -unit, unit), flipped


def _toward_light(positions: np.ndarray, light: Light) -> tuple[np.ndarray, np.ndarray]:
    """L at every point (unit, toward the light) and the distance to a point light (else 0)."""
    if light.kind == "point":
        return _unit_between(positions, light.position)
    direction, _ = _unit(-np.asarray([light.direction]))
    return np.broadcast_to(direction, positions.shape), np.zeros(len(positions))


# --- the illumination model --------------------------------------------------------------


def _attenuation(fudge: np.ndarray, distance: np.ndarray) -> np.ndarray:
    """f_att = 1 / (1 + fudge d); exactly 1 where fudge = 0, even at an infinite d (no 0 * inf)."""
    falloff = np.zeros(np.broadcast(fudge, distance).shape)
    with np.errstate(over="ignore"):
        np.multiply(fudge, distance, out=falloff, where=fudge > 0)
    return 1 / (1 + falloff)


@njit(cache=True)
def _power_kernel(base, exponent, out):  # pragma: no cover - compiled
    for i in range(base.shape[0]):
        out[i] = base[i] ** exponent[i]


def _power(base: np.ndarray, exponent: np.ndarray) -> np.ndarray:
    """base ** exponent per element, the same bits for a row alone or in any batch.

    numpy's vectorised power can differ in the last bit with the memory layout
    (a SIMD body against a scalar remainder), which would break the traced ==
    batched identity; one scalar power per element cannot.
    """
    out = np.empty(base.shape[0])
    _power_kernel(
        np.ascontiguousarray(base, np.float64), np.ascontiguousarray(exponent, np.float64), out
    )
    return out


def _shade(
    positions: np.ndarray,
    normals: np.ndarray,
    materials: np.ndarray,
    view: np.ndarray,
    lights: tuple[Light, ...],
    ambient_light: np.ndarray,
    steps: dict | None = None,
) -> np.ndarray:
    """The model on validated rows; fills `steps` with every intermediate if given."""
    normal, flipped = _facing_viewer(normals, view)
    surface = materials[:, _COLOR]
    ambient = materials[:, _AMBIENT, None] * ambient_light * surface
    color = ambient
    terms = []
    for light in lights:
        to_light, distance = _toward_light(positions, light)
        n_dot_l = _dot(normal, to_light)
        r_dot_v = _dot(2 * n_dot_l[:, None] * normal - to_light, view)
        diffuse = materials[:, _DIFFUSE, None] * surface * np.maximum(n_dot_l, 0)[:, None]
        highlight = materials[:, _SPECULAR] * _power(
            np.maximum(r_dot_v, 0), materials[:, _EXPONENT]
        )
        specular = np.where(n_dot_l > 0, highlight, 0.0)  # no highlight on the unlit side
        attenuation = _attenuation(materials[:, _FUDGE], distance)
        contribution = (
            attenuation[:, None] * np.asarray(light.color) * (diffuse + specular[:, None])
        )
        color = color + contribution
        if steps is not None:
            terms.append((to_light, n_dot_l, r_dot_v, attenuation, diffuse, specular, contribution))
    color = np.clip(color, 0.0, 1.0)
    if steps is not None:
        steps.update(normal=normal, flipped=flipped, ambient=ambient, lights=terms, color=color)
    return color


def illuminate(
    positions: object,
    normals: object,
    materials: object,
    eye: object,
    lights: Sequence[Light],
    ambient_light: object,
    *,
    view_dir: object = None,
) -> np.ndarray:
    """The Phong illumination model at N points (world space).

    Parameters
    ----------
    positions : (N, 3) array_like of float
        The points.
    normals : (N, 3) array_like of float
        Their surface normals, any length: they are normalized here. A zero
        normal gets the ambient term only.
    materials : (N, 9) array_like of float
        Each point's material, a row of `material_array`.
    eye : (3,) array_like of float or None
        The viewer's position (perspective). None for an orthographic viewer,
        who is then given by `view_dir`.
    lights : sequence of Light
        Point and directional lights; empty for ambient light only.
    ambient_light : (3,) array_like of float
        The ambient light Ia, RGB >= 0.
    view_dir : (3,) array_like of float, optional
        Direction from the surface toward an orthographic viewer (normalized
        here). Give exactly one of `eye` and `view_dir`.

    Returns
    -------
    (N, 3) ndarray of float64
        RGB in [0, 1].

    Notes
    -----
    I = ka Ia Od + sum_lights f_att Il [kd Od max(N.L, 0) + ks max(R.V, 0)^n],
    specular only where N.L > 0, lit two-sided; see the module docstring and
    docs/shading.md. ``transparency`` is not used here: it matters only when
    fragments are composited.

    Examples
    --------
    A point facing the viewer, lit head-on: Od (ka + kd) + ks.

    >>> materials = material_array([Material(color=(1, 0.5, 0), ambient=0.1, diffuse=0.6)])
    >>> illuminate([[0, 0, 0]], [[0, 0, 2]], materials, (0, 0, 5), [Light()], (1, 1, 1))
    array([[1.  , 0.65, 0.3 ]])
    """
    positions = _rows("positions", positions, 3)
    normals = _rows("normals", normals, 3, len(positions))
    materials = _materials(materials, len(positions))
    _to_viewer(positions[:0], eye, view_dir)  # checks eye / view_dir
    return _shade_compiled(
        positions, normals, materials, eye, view_dir, _lights(lights), _ambient(ambient_light)
    )


def _shade_compiled(positions, normals, materials, eye, view_dir, lights, ambient_light):
    """`_shade` without steps, by the compiled twin (`scanviz.shading.shade_compiled`): the same bits."""
    from .shade_compiled import shade_rows

    return shade_rows(
        positions, normals, materials, *_light_arrays(eye, view_dir, lights), ambient_light
    )


def _light_arrays(eye, view_dir, lights):
    """(eye, toward_viewer, kinds, vectors, colors): the viewer and lights as `shade_rows` takes them."""
    from .shade_compiled import DIRECTIONAL, POINT

    if eye is not None:
        eye, toward_viewer = _vector("eye", eye), np.full(3, np.nan)
    else:
        eye, toward_viewer = np.zeros(3), _unit(_vector("view_dir", view_dir)[None])[0][0]
    kinds = np.array(
        [POINT if light.kind == "point" else DIRECTIONAL for light in lights], np.int64
    )
    vectors = np.array(
        [
            light.position if light.kind == "point" else _unit(-np.asarray([light.direction]))[0][0]
            for light in lights
        ],
        np.float64,
    ).reshape(-1, 3)
    colors = np.array([light.color for light in lights], np.float64).reshape(-1, 3)
    return eye, toward_viewer, kinds, vectors, colors


def _floats(row: np.ndarray) -> tuple[float, ...]:
    return tuple(float(v) for v in row)


def illuminate_traced(
    position: object,
    normal: object,
    material: object,
    eye: object,
    lights: Sequence[Light],
    ambient_light: object,
    *,
    trace: Tracer | None,
    pixel: tuple[int, int],
    view_dir: object = None,
    polygon: int | None = None,
) -> np.ndarray:
    """`illuminate` at one point, emitting an ``illumination`` event with every term.

    Parameters
    ----------
    position, normal : (3,) array_like of float
    material : (9,) array_like of float
        A row of `material_array`.
    eye, lights, ambient_light, view_dir
        As for `illuminate`.
    trace : Tracer or None
        Receives one ``illumination`` event (if it wants it).
    pixel : (int, int)
        The pixel (x, y) this point is shaded for; recorded in the event.
    polygon : int, optional
        The polygon the point lies on, for filtering; recorded in the event.

    Returns
    -------
    (3,) ndarray of float64
        Exactly ``illuminate([position], [normal], [material], ...)[0]``.

    Examples
    --------
    >>> from scanviz.trace import Recorder
    >>> recorder = Recorder()
    >>> material = material_array([Material(color=(1, 1, 1), specular=0.0)])[0]
    >>> illuminate_traced((0, 0, 0), (0, 0, -1), material, (0, 0, 5), [Light()], (1, 1, 1),
    ...                   trace=recorder, pixel=(3, 4))
    array([0.85, 0.85, 0.85])
    >>> event = recorder.trace()[0]
    >>> event.flipped, event.lights[0].n_dot_l, event.ambient
    (True, 1.0, (0.15, 0.15, 0.15))
    """
    _check_tracer(trace)
    if (
        not isinstance(pixel, tuple)
        or len(pixel) != 2
        or not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in pixel)
    ):
        raise TypeError(f"'pixel' must be a pair of ints (x, y); got {pixel!r}")
    positions = _vector("position", position)[None]
    normals = _vector("normal", normal)[None]
    materials = _materials(_vector("material", material, len(MATERIAL_FIELDS))[None], 1)
    view = _to_viewer(positions, eye, view_dir)
    lights = _lights(lights)
    steps: dict = {}
    color = _shade(positions, normals, materials, view, lights, _ambient(ambient_light), steps)
    x, y = int(pixel[0]), int(pixel[1])
    if trace is not None and trace.wants("illumination", polygon=polygon, y=y):
        terms = tuple(
            LightTerm(
                light=i,
                to_light=_floats(to_light[0]),
                n_dot_l=float(n_dot_l[0]),
                r_dot_v=float(r_dot_v[0]),
                attenuation=float(attenuation[0]),
                diffuse=_floats(diffuse[0]),
                specular=float(specular[0]),
                contribution=_floats(contribution[0]),
            )
            for i, (to_light, n_dot_l, r_dot_v, attenuation, diffuse, specular, contribution) in (
                enumerate(steps["lights"])
            )
        )
        event = Illumination(
            x=x,
            y=y,
            polygon=None if polygon is None else int(polygon),
            position=_floats(positions[0]),
            normal=_floats(steps["normal"][0]),
            flipped=bool(steps["flipped"][0]),
            to_viewer=_floats(view[0]),
            ambient=_floats(steps["ambient"][0]),
            lights=terms,
            color=_floats(color[0]),
        )
        trace.emit(event)
    return color[0]


# --- normals: what Mesh(normals=None) means ----------------------------------------------


def _face_area_vectors(
    positions: np.ndarray, corners: FaceCorners
) -> tuple[np.ndarray, np.ndarray]:
    """Newell's sums per face (twice the area vector; zero if degenerate), and the centroids."""
    area, centroid, spread = newell(positions, corners)
    area[vector_norm(area) <= _DEGENERATE * spread] = 0.0
    return area, centroid


def face_normals(positions: object, faces: Sequence[object]) -> np.ndarray:
    """Unit face normals by Newell's method; zero for a degenerate face.

    Parameters
    ----------
    positions : (V, 3) array_like of float
    faces : sequence of (k,) array_like of int
        Vertex indices, k >= 3, counter-clockwise seen from the front.

    Returns
    -------
    (F, 3) ndarray of float64

    Notes
    -----
    Newell's method sums, over the edges (i, j) of a face,
    n_x += (y_i - y_j)(z_i + z_j), n_y += (z_i - z_j)(x_i + x_j),
    n_z += (x_i - x_j)(y_i + y_j). The sum is twice the face's area vector; for a
    non-planar face it is the normal of the best-fitting plane, and it never
    depends on picking three "good" vertices. A face whose area is below
    1e-12 of its squared size (collinear or repeated vertices) gets the zero
    normal, which `illuminate` shades with ambient light only.

    Examples
    --------
    >>> square = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
    >>> face_normals(square, [[0, 1, 2, 3], [3, 2, 1, 0], [0, 1, 1]])
    array([[ 0.,  0.,  1.],
           [ 0.,  0., -1.],
           [ 0.,  0.,  0.]])
    """
    positions = _rows("positions", positions, 3)
    area, _ = _face_area_vectors(positions, face_corners(faces, len(positions)))
    return _unit(area)[0]


def vertex_normals(positions: object, faces: Sequence[object]) -> np.ndarray:
    """Unit vertex normals: the area-weighted average of the normals of the faces around each vertex.

    Parameters
    ----------
    positions : (V, 3) array_like of float
    faces : sequence of (k,) array_like of int

    Returns
    -------
    (V, 3) ndarray of float64
        Zero for a vertex on no (non-degenerate) face, or where the faces'
        normals cancel.

    Notes
    -----
    Gouraud's vertex normal is the average of the normals of the polygons that
    share the vertex. Weighting each by its face's area (summing the Newell
    vectors, whose length is twice the area) keeps a mesh's many small faces
    from outvoting one large face.

    Examples
    --------
    Two unit squares meeting at a right angle along the edge 0-1:

    >>> positions = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, -1), (1, 0, -1)]
    >>> vertex_normals(positions, [[0, 1, 2, 3], [0, 4, 5, 1]]).round(4)
    array([[ 0.    , -0.7071,  0.7071],
           [ 0.    , -0.7071,  0.7071],
           [ 0.    ,  0.    ,  1.    ],
           [ 0.    ,  0.    ,  1.    ],
           [ 0.    , -1.    ,  0.    ],
           [ 0.    , -1.    ,  0.    ]])
    """
    positions = _rows("positions", positions, 3)
    corners = face_corners(faces, len(positions))
    area, _ = _face_area_vectors(positions, corners)
    corner, face = corners.corner, corners.face
    sums = np.stack([np.bincount(corner, area[face, k], len(positions)) for k in range(3)], axis=1)
    return _unit(sums)[0]

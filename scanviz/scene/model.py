"""The scene: meshes with materials, a camera, lights and a background.

Every class is a frozen dataclass validated at construction, so a Scene that
exists is a valid one. Arrays are read-only float64 (positions, normals) or
int64 (indices). World space is right-handed, y up unless the camera says
otherwise.

Materials follow the thesis' Rendermatic OPTICAL structure and are inherited
object -> polygon -> vertex: a vertex of a face uses its own material if the
mesh sets one for it, else its face's, else the object's.

Limits
------
Every finite value a Scene holds is one the pipeline can carry without
overflow (derivation: ``docs/scene-format.md``, "Limits"):

* world coordinates (each object's positions after its ``world_from_model``,
  the camera's eye and look_at, point-light positions, finite near/far)
  within +-`WORLD_LIMIT` = 1e99;
* the linear (3x3) part of ``world_from_model`` and its inverse, every entry
  within +-`LINEAR_LIMIT` = 1e100; the bottom row (0, 0, 0, 1);
* a camera window and depth range at least `RELATIVE_EXTENT` = 1e-12 of their
  magnitude wide and at least `MIN_EXTENT` = 1e-99, a perspective window at
  least 1e-12 * near;
* material exponent in [0, `EXPONENT_LIMIT` = 1e4], fudge in [0, 1e99];
  light colors in [0, `LIGHT_LIMIT` = 1e6];
* in a Scene, every world position at most `DEPTH_RATIO` = 1e12 times the
  window's smaller extent from the eye (and, for a perspective camera, 1e12
  times near), so that clipping keeps the display coordinates exact to well
  under a pixel.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np

from ..conventions import check_finite_rows
from ..vectors import unit_vectors, vector_norm
from .faces import face_corners

WORLD_LIMIT = 1e99
"""Bound on every world coordinate: 2 * sqrt(3) * 1e99 < 1e100 keeps every 1/w and value in range."""
LINEAR_LIMIT = 1e100
"""Bound on the entries of a modeling transform's 3x3 block and of its inverse (normals use it)."""
EXPONENT_LIMIT = 1e4
"""Largest Phong exponent: cos**1e4 already narrows a highlight below 1/100 radian."""
FUDGE_LIMIT = 1e99
"""Largest point-light attenuation factor (per unit of distance)."""
LIGHT_LIMIT = 1e6
"""Largest light color component (an intensity; images are clipped to [0, 1] only at export)."""
RELATIVE_EXTENT = 1e-12
"""Smallest window or depth extent relative to its coordinates' magnitude."""
MIN_EXTENT = 1e-99
"""Smallest window or depth extent in absolute terms."""
DEPTH_RATIO = 1e12
"""Largest distance from the eye to a mesh position, in units of near and of the window's extent."""


def _finite_vector(
    name: str, value: object, size: int, limit: float = math.inf
) -> tuple[float, ...]:
    """`value` as `size` finite floats, each within +-`limit` (a ValueError names the rule)."""
    try:
        items = list(value)  # type: ignore[call-overload]
    except TypeError:
        raise TypeError(f"{name!r} must be {size} numbers; got {value!r}") from None
    if any(isinstance(v, bool | str | bytes) or not isinstance(v, numbers.Real) for v in items):
        raise TypeError(f"{name!r} must be {size} numbers; got {value!r}")
    try:
        vector = tuple(float(v) for v in items)
    except OverflowError:  # an int beyond float64
        raise ValueError(f"{name!r} must be finite; got {value!r}") from None
    if len(vector) != size:
        raise ValueError(f"{name!r} must have {size} components; got {len(vector)}")
    if not all(math.isfinite(v) for v in vector):
        raise ValueError(f"{name!r} must be finite; got {vector}")
    if not all(abs(v) <= limit for v in vector):
        raise ValueError(f"{name!r} components must be within +-{limit:g}; got {vector}")
    return vector


def _number(
    name: str, value: object, low: float, high: float = math.inf, *, infinite: bool = False
) -> float:
    """`value` as a float in [low, high]; +inf passes only where `infinite` allows it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name!r} must be a number; got {value!r}")
    try:
        value = float(value)
    except OverflowError:  # an int beyond float64
        raise ValueError(f"{name!r} must be finite; got {value!r}") from None
    if not (math.isfinite(value) or (infinite and value == math.inf)):
        raise ValueError(f"{name!r} must be finite; got {value}")
    if not (low <= value <= high or (infinite and value == math.inf)):
        raise ValueError(f"{name!r} must be in [{low}, {high}]; got {value}")
    return float(value)


@dataclass(frozen=True)
class Material:
    """How a surface reflects light (thesis App. B.7, OPTICAL).

    Parameters
    ----------
    color : (3,) float
        Base (diffuse) RGB in [0, 1].
    ambient, diffuse, specular : float
        Coefficients ka, kd, ks in [0, 1].
    exponent : float
        Phong specular exponent n in [0, 1e4] (`EXPONENT_LIMIT`).
    transparency : float
        0 opaque .. 1 fully transparent.
    fudge : float
        Attenuation of point lights, f_att = 1 / (1 + fudge * distance); 0 = none;
        at most 1e99 (`FUDGE_LIMIT`).
    """

    color: tuple[float, float, float] = (0.8, 0.8, 0.8)
    ambient: float = 0.15
    diffuse: float = 0.7
    specular: float = 0.3
    exponent: float = 32.0
    transparency: float = 0.0
    fudge: float = 0.0

    def __post_init__(self) -> None:
        color = _finite_vector("color", self.color, 3)
        if not all(0 <= c <= 1 for c in color):
            raise ValueError(f"'color' components must be in [0, 1]; got {color}")
        object.__setattr__(self, "color", color)
        for name in ("ambient", "diffuse", "specular", "transparency"):
            object.__setattr__(self, name, _number(name, getattr(self, name), 0.0, 1.0))
        exponent = _number("exponent", self.exponent, 0.0, EXPONENT_LIMIT)
        object.__setattr__(self, "exponent", exponent)
        object.__setattr__(self, "fudge", _number("fudge", self.fudge, 0.0, FUDGE_LIMIT))

    @property
    def opaque(self) -> bool:
        return self.transparency == 0.0


def _array(name: str, value: object, dtype, columns: int | None) -> np.ndarray:
    try:
        array = np.array(value, dtype=dtype)
    except OverflowError:
        raise ValueError(f"{name!r} holds an integer beyond {np.dtype(dtype).name}") from None
    except (TypeError, ValueError):
        raise TypeError(
            f"{name!r} must be an array of numbers; got {type(value).__name__}"
        ) from None
    if array.ndim == 1 and array.size == 0 and columns is not None:
        array = array.reshape(0, columns)  # [] is an empty table
    if array.dtype.kind == "i" and array.size:
        given = np.asarray(value)  # np.array([1.7], dtype=int) truncates silently
        if given.dtype.kind not in "iu":
            raise TypeError(f"{name!r} must hold integers; got {given.dtype} {given.tolist()}")
    if columns is not None and (array.ndim != 2 or array.shape[1] != columns):
        raise ValueError(f"{name!r} must be an (N, {columns}) array; got shape {array.shape}")
    if array.dtype.kind == "f":
        check_finite_rows(name, array)
    array.setflags(write=False)
    return array


MESH_FACE_BYTES = 288
MESH_CORNER_BYTES = 48
MESH_VERTEX_BYTES = 72


def mesh_bytes(faces: int, corners: int, vertices: int) -> int:
    """Peak bytes of building a `Mesh` of `faces` faces with `corners` corners in all.

    A face is an array object of its own, held twice while `Mesh` validates
    and splits them, and each corner's index passes through a few int64
    arrays. Measured with tracemalloc, per face: 347 bytes for a triangle and
    456 for an octagon from OBJ, 361 and 593 from JSON lists, 436 for an OBJ
    quad with normals; the constants cover each (tests/io/test_issue27_limits.py).
    """
    return MESH_FACE_BYTES * faces + MESH_CORNER_BYTES * corners + MESH_VERTEX_BYTES * vertices


@dataclass(frozen=True, eq=False)
class Mesh:
    """A polygon mesh.

    Parameters
    ----------
    positions : (V, 3) float64
        Vertex positions in model space.
    faces : tuple of (k_i,) int64 arrays
        Vertex indices, k_i >= 3, counter-clockwise seen from outside.
    normals : (V, 3) float64 or None
        Unit vertex normals, or None to derive them: averaged from the faces
        for ``smooth=True``, the face normal for faceted meshes.
    smooth : bool
        Average normals across faces (True) or keep faces flat (False).
    closed : bool
        The mesh bounds a solid, so back faces can be culled.
    face_materials, vertex_materials : (F,) / (V,) int64, optional
        Indices into ``materials``, -1 = inherit (face from object, vertex from face).
    materials : tuple of Material
        The palette those indices refer to.
    """

    positions: np.ndarray
    faces: tuple[np.ndarray, ...]
    normals: np.ndarray | None = None
    smooth: bool = True
    closed: bool = True
    face_materials: np.ndarray | None = None
    vertex_materials: np.ndarray | None = None
    materials: tuple[Material, ...] = ()

    def __post_init__(self) -> None:
        positions = _array("positions", self.positions, np.float64, 3)
        object.__setattr__(self, "positions", positions)
        corners = face_corners(self.faces, len(positions))  # validates every face at once
        corners.corner.setflags(write=False)
        faces = np.split(corners.corner, corners.starts[1:]) if len(corners.starts) else []
        object.__setattr__(self, "faces", tuple(faces))
        if self.normals is not None:
            normals = _array("normals", self.normals, np.float64, 3)
            if len(normals) != len(positions):
                raise ValueError(
                    f"'normals' must have one row per position ({len(positions)}); got {len(normals)}"
                )
            object.__setattr__(self, "normals", normals)
        for name, count in (("face_materials", len(faces)), ("vertex_materials", len(positions))):
            value = getattr(self, name)
            if value is None:
                continue
            indices = _array(name, value, np.int64, None).reshape(-1)
            if len(indices) != count:
                raise ValueError(f"{name!r} must have {count} entries; got {len(indices)}")
            if indices.size and (indices.min() < -1 or indices.max() >= len(self.materials)):
                raise ValueError(
                    f"{name!r} must index 'materials' (or be -1); got {indices.tolist()}"
                )
            object.__setattr__(self, name, indices)
        object.__setattr__(self, "materials", tuple(self.materials))

    @property
    def face_count(self) -> int:
        return len(self.faces)

    def triangle_count(self) -> int:
        return sum(len(f) - 2 for f in self.faces)


@dataclass(frozen=True, eq=False)
class SceneObject:
    """A mesh placed in the world by ``world_from_model`` (4x4), with its object-level material.

    ``world_from_model`` is affine (bottom row 0, 0, 0, 1); its 3x3 block and
    that block's inverse (which transforms normals) have entries within
    +-1e100 (`LINEAR_LIMIT`), its translation and every transformed mesh
    position are within +-1e99 (`WORLD_LIMIT`).
    """

    mesh: Mesh
    material: Material = field(default_factory=Material)
    world_from_model: np.ndarray = field(default_factory=lambda: np.eye(4))
    name: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.mesh, Mesh):
            raise TypeError(f"'mesh' must be a Mesh; got {type(self.mesh).__name__}")
        if not isinstance(self.material, Material):
            raise TypeError(f"'material' must be a Material; got {type(self.material).__name__}")
        if not isinstance(self.name, str):
            raise TypeError(f"'name' must be a string; got {type(self.name).__name__}")
        matrix = _array("world_from_model", self.world_from_model, np.float64, 4)
        if matrix.shape != (4, 4):
            raise ValueError(f"'world_from_model' must be 4x4; got {matrix.shape}")
        check_modeling_matrix(matrix)
        object.__setattr__(self, "world_from_model", matrix)
        self._check_world_positions()

    def world_positions(self) -> np.ndarray:
        """(V, 3) float64: the mesh positions moved into the world by ``world_from_model``."""
        matrix = self.world_from_model
        with np.errstate(over="ignore", invalid="ignore"):  # checked against WORLD_LIMIT
            return self.mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]

    def _check_world_positions(self) -> None:
        world = self.world_positions()
        outside = np.flatnonzero(~(np.abs(world) <= WORLD_LIMIT).all(axis=1))
        if outside.size:
            i = int(outside[0])
            label = f" of object {self.name!r}" if self.name else ""
            raise ValueError(
                f"mesh position {i}{label} {self.mesh.positions[i].tolist()} lands at world "
                f"{world[i].tolist()}, beyond the world coordinate limit +-{WORLD_LIMIT:g}"
            )


def check_modeling_matrix(matrix: np.ndarray) -> None:
    """Raise a ValueError unless the (4, 4) `matrix` may be a ``world_from_model``.

    It must be affine (bottom row 0, 0, 0, 1), its 3x3 block and that block's
    inverse must have entries within +-`LINEAR_LIMIT`, its translation within
    +-`WORLD_LIMIT`. The inverse is taken of the block scaled to entries <= 1,
    so a block of entries near 1e-100 or 1e100 is not mistaken for singular.
    """
    if not np.array_equal(matrix[3], (0.0, 0.0, 0.0, 1.0)):
        raise ValueError(
            f"'world_from_model' must be affine, bottom row (0, 0, 0, 1); got {matrix[3].tolist()}"
        )
    linear = matrix[:3, :3]
    if not (np.abs(linear) <= LINEAR_LIMIT).all():
        raise ValueError(
            f"'world_from_model' 3x3 entries must be within +-{LINEAR_LIMIT:g}; got {linear.tolist()}"
        )
    if not (np.abs(matrix[:3, 3]) <= WORLD_LIMIT).all():
        raise ValueError(
            f"'world_from_model' translation must be within +-{WORLD_LIMIT:g}; "
            f"got {matrix[:3, 3].tolist()}"
        )
    scale = np.abs(linear).max()  # the inverse of linear / scale is scale * inverse(linear)
    try:
        with np.errstate(all="ignore"):
            inverse = np.linalg.inv(linear / scale) / scale if scale > 0 else None
    except np.linalg.LinAlgError:
        inverse = None
    if inverse is None or not (np.abs(inverse) <= LINEAR_LIMIT).all():
        raise ValueError(
            "'world_from_model' 3x3 block must be invertible with inverse entries within "
            f"+-{LINEAR_LIMIT:g} (normals are transformed by the inverse transpose)"
        )


@dataclass(frozen=True)
class Camera:
    """A viewing camera after Smith's tutorial (thesis App. D).

    Parameters
    ----------
    eye, look_at, up : (3,) float
        World points and a direction; up must not be parallel to look_at - eye;
        eye and look_at within +-1e99 (`WORLD_LIMIT`), up any finite nonzero vector.
    window : (left, right, bottom, top)
        The view window on the near plane (perspective) or in eye space
        (orthographic); width and height at least 1e-12 of the window's largest
        coordinate magnitude (and of near, for a perspective camera) and at least 1e-99.
    near, far : float
        Distances along the view direction, 0 < near < far (orthographic: near < far),
        within +-1e99 (a perspective far may be inf; a perspective near is >= 1e-99);
        far - near at least 1e-12 of their magnitude and at least 1e-99.
    projection : {"perspective", "orthographic"}
    """

    eye: tuple[float, float, float] = (0.0, 0.0, 5.0)
    look_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
    up: tuple[float, float, float] = (0.0, 1.0, 0.0)
    window: tuple[float, float, float, float] = (-1.0, 1.0, -1.0, 1.0)
    near: float = 1.0
    far: float = 100.0
    projection: str = "perspective"

    def __post_init__(self) -> None:
        for name in ("eye", "look_at"):
            point = _finite_vector(name, getattr(self, name), 3, WORLD_LIMIT)
            object.__setattr__(self, name, point)
        object.__setattr__(self, "up", _finite_vector("up", self.up, 3))
        if self.projection not in ("perspective", "orthographic"):
            raise ValueError(
                f"'projection' must be 'perspective' or 'orthographic'; got {self.projection!r}"
            )
        perspective = self.projection == "perspective"
        near = _number("near", self.near, -WORLD_LIMIT, WORLD_LIMIT)
        far = _number("far", self.far, -WORLD_LIMIT, WORLD_LIMIT, infinite=perspective)
        if perspective and not near >= MIN_EXTENT:
            raise ValueError(
                f"'near' must be > 0 for a perspective camera (at least {MIN_EXTENT:g}); got {near}"
            )
        if not near < far:
            raise ValueError(f"'near' must be < 'far'; got near={near}, far={far}")
        if far != math.inf:
            _check_extent("'far' - 'near'", near, far)
        object.__setattr__(self, "near", near)
        object.__setattr__(self, "far", far)
        window = _finite_vector("window", self.window, 4)
        if not (window[0] < window[1] and window[2] < window[3]):
            raise ValueError(f"'window' must have left < right and bottom < top; got {window}")
        for what, low, high in (("width", *window[:2]), ("height", *window[2:])):
            _check_extent(f"'window' {what}", low, high, near if perspective else 0.0)
        object.__setattr__(self, "window", window)
        view, up = unit_vectors(np.array([np.subtract(self.look_at, self.eye), self.up]))
        if not view.any():
            raise ValueError("'look_at' must differ from 'eye'")
        if not vector_norm(np.cross(view, up)) >= 1e-9:  # also for up = 0
            raise ValueError(
                f"'up' {self.up} must not be parallel to the view direction "
                f"{tuple(np.subtract(self.look_at, self.eye).tolist())}"
            )


def _check_extent(what: str, low: float, high: float, near: float = 0.0) -> None:
    """`high - low` must resolve: at least `MIN_EXTENT`, 1e-12 of |low|, |high| and `near`."""
    least = max(MIN_EXTENT, RELATIVE_EXTENT * max(abs(low), abs(high), near))
    if not high - low >= least:
        raise ValueError(
            f"{what} must be at least {least:g} (1e-12 of the coordinates' magnitude"
            f"{' and of near' if near else ''}, and >= {MIN_EXTENT:g}); got {high - low:g}"
        )


@dataclass(frozen=True)
class Light:
    """A point light at ``position`` or a directional light shining along ``direction``.

    color : RGB intensity, each component in [0, 1e6] (`LIGHT_LIMIT`)
    position : point lights, a world point within +-1e99 (`WORLD_LIMIT`)
    direction : directional lights, any finite nonzero vector (its length is ignored)
    """

    kind: str = "directional"
    color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    position: tuple[float, float, float] | None = None
    direction: tuple[float, float, float] | None = None  # directional default: (0, 0, -1)

    def __post_init__(self) -> None:
        if self.kind not in ("point", "directional"):
            raise ValueError(f"'kind' must be 'point' or 'directional'; got {self.kind!r}")
        color = _finite_vector("color", self.color, 3)
        if not all(0 <= c <= LIGHT_LIMIT for c in color):
            raise ValueError(f"'color' components must be >= 0 and <= {LIGHT_LIMIT:g}; got {color}")
        object.__setattr__(self, "color", color)
        if self.kind == "point":
            if self.position is None:
                raise ValueError("a point light needs a 'position'")
            if self.direction is not None:
                raise ValueError("a point light takes a 'position', not a 'direction'")
            object.__setattr__(
                self, "position", _finite_vector("position", self.position, 3, WORLD_LIMIT)
            )
            object.__setattr__(self, "direction", None)
        else:
            direction = _finite_vector("direction", self.direction or (0.0, 0.0, -1.0), 3)
            if not any(direction):
                raise ValueError("'direction' must not be the zero vector")
            object.__setattr__(self, "direction", direction)
            object.__setattr__(self, "position", None)


@dataclass(frozen=True, eq=False)
class Scene:
    """Objects, a camera, lights, an ambient light color and a background color.

    ambient, background : RGB, each component in [0, 1]

    Every mesh position, in the world, lies within 1e12 (`DEPTH_RATIO`) times
    the camera's smaller window extent from the eye, and within 1e12 times
    near for a perspective camera.
    """

    objects: tuple[SceneObject, ...]
    camera: Camera = field(default_factory=Camera)
    lights: tuple[Light, ...] = (Light(),)
    ambient: tuple[float, float, float] = (1.0, 1.0, 1.0)
    background: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "objects", tuple(self.objects))
        object.__setattr__(self, "lights", tuple(self.lights))
        for name, kind, items in (
            ("objects", SceneObject, self.objects),
            ("lights", Light, self.lights),
            ("camera", Camera, (self.camera,)),
        ):
            wrong = [i for i, item in enumerate(items) if not isinstance(item, kind)]
            if wrong:
                where = name if name == "camera" else f"{name}[{wrong[0]}]"
                raise TypeError(f"{where!r} must be a {kind.__name__}")
        for name in ("ambient", "background"):
            value = _finite_vector(name, getattr(self, name), 3)
            if not all(0 <= c <= 1 for c in value):
                raise ValueError(f"{name!r} components must be in [0, 1]; got {value}")
            object.__setattr__(self, name, value)

        self._check_depth_ratio()

    def _check_depth_ratio(self) -> None:
        camera = self.camera
        left, right, bottom, top = camera.window
        scale = min(right - left, top - bottom)
        if camera.projection == "perspective":
            scale = min(scale, camera.near)
        for index, obj in enumerate(self.objects):
            if not len(obj.mesh.positions):
                continue
            distances = vector_norm(obj.world_positions() - np.array(camera.eye))
            farthest = int(np.argmax(distances))
            if distances[farthest] > DEPTH_RATIO * scale:
                raise ValueError(
                    f"'objects[{index}]' mesh position {farthest} is {distances[farthest]:g} from "
                    f"the eye, more than {DEPTH_RATIO:g} times {scale:g} (the camera's smaller "
                    "window extent, or near if smaller, for a perspective camera): clipping "
                    "would lose the pixel grid"
                )

    def triangle_count(self) -> int:
        return sum(o.mesh.triangle_count() for o in self.objects)

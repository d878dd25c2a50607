"""The scene: meshes with materials, a camera, lights and a background.

Every class is a frozen dataclass validated at construction, so a Scene that
exists is a valid one. Arrays are read-only float64 (positions, normals) or
int64 (indices). World space is right-handed, y up unless the camera says
otherwise.

Materials follow the thesis' Rendermatic OPTICAL structure and are inherited
object -> polygon -> vertex: a vertex of a face uses its own material if the
mesh sets one for it, else its face's, else the object's.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np

from .faces import face_corners


def _finite_vector(name: str, value: object, size: int) -> tuple[float, ...]:
    try:
        items = list(value)  # type: ignore[call-overload]
    except TypeError:
        raise TypeError(f"{name!r} must be {size} numbers; got {value!r}") from None
    if any(isinstance(v, bool | str | bytes) or not isinstance(v, numbers.Real) for v in items):
        raise TypeError(f"{name!r} must be {size} numbers; got {value!r}")
    vector = tuple(float(v) for v in items)
    if len(vector) != size:
        raise ValueError(f"{name!r} must have {size} components; got {len(vector)}")
    if not all(math.isfinite(v) for v in vector):
        raise ValueError(f"{name!r} must be finite; got {vector}")
    return vector


def _number(
    name: str, value: object, low: float, high: float = math.inf, *, infinite: bool = False
) -> float:
    """`value` as a float in [low, high]; +inf passes only where `infinite` allows it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name!r} must be a number; got {value!r}")
    if not (math.isfinite(value) or (infinite and value == math.inf)):
        raise ValueError(f"{name!r} must be finite; got {value}")
    if not low <= value <= high:
        raise ValueError(f"{name!r} must be in [{low}, {high}]; got {value}")
    return float(value)


@dataclass(frozen=True)
class Material:
    """How a surface reflects light (thesis App. B.7, OPTICAL).

    color : base (diffuse) RGB in [0, 1]
    ambient, diffuse, specular : coefficients ka, kd, ks in [0, 1]
    exponent : Phong specular exponent n >= 0
    transparency : 0 opaque .. 1 fully transparent
    fudge : attenuation of point lights, f_att = 1 / (1 + fudge * distance); 0 = none
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
        object.__setattr__(self, "exponent", _number("exponent", self.exponent, 0.0))
        object.__setattr__(self, "fudge", _number("fudge", self.fudge, 0.0))

    @property
    def opaque(self) -> bool:
        return self.transparency == 0.0


def _array(name: str, value: object, dtype, columns: int | None) -> np.ndarray:
    try:
        array = np.array(value, dtype=dtype)
    except (TypeError, ValueError):
        raise TypeError(
            f"{name!r} must be an array of numbers; got {type(value).__name__}"
        ) from None
    if array.dtype.kind == "i" and array.size:
        given = np.asarray(value)  # np.array([1.7], dtype=int) truncates silently
        if given.dtype.kind not in "iu":
            raise TypeError(f"{name!r} must hold integers; got {given.dtype} {given.tolist()}")
    if columns is not None and (array.ndim != 2 or array.shape[1] != columns):
        raise ValueError(f"{name!r} must be an (N, {columns}) array; got shape {array.shape}")
    if array.dtype.kind == "f" and not np.isfinite(array).all():
        row = int(np.argwhere(~np.isfinite(array))[0][0])
        raise ValueError(f"{name!r} row {row} is not finite: {array[row].tolist()}")
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class Mesh:
    """A polygon mesh.

    positions : (V, 3) float64, model space
    faces : tuple of (k_i,) int64 arrays, k_i >= 3, counter-clockwise seen from outside
    normals : (V, 3) float64 unit vertex normals, or None to derive them:
        averaged from the faces for ``smooth=True``, the face normal for faceted meshes
    smooth : average normals across faces (True) or keep faces flat (False)
    closed : the mesh bounds a solid, so back faces can be culled
    face_materials, vertex_materials : optional (F,) / (V,) int64 indices into
        ``materials``, -1 = inherit (face from object, vertex from face)
    materials : the palette those indices refer to
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
    """A mesh placed in the world by ``world_from_model`` (4x4), with its object-level material."""

    mesh: Mesh
    material: Material = field(default_factory=Material)
    world_from_model: np.ndarray = field(default_factory=lambda: np.eye(4))
    name: str = ""

    def __post_init__(self) -> None:
        matrix = _array("world_from_model", self.world_from_model, np.float64, 4)
        if matrix.shape != (4, 4):
            raise ValueError(f"'world_from_model' must be 4x4; got {matrix.shape}")
        object.__setattr__(self, "world_from_model", matrix)


@dataclass(frozen=True)
class Camera:
    """A viewing camera after Smith's tutorial (thesis App. D).

    eye, look_at, up : world points / direction; up must not be parallel to look_at - eye
    window : (left, right, bottom, top) of the view window on the near plane
        (perspective) or in eye space (orthographic)
    near, far : distances along the view direction, 0 < near < far (orthographic: near < far)
    projection : "perspective" or "orthographic"
    """

    eye: tuple[float, float, float] = (0.0, 0.0, 5.0)
    look_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
    up: tuple[float, float, float] = (0.0, 1.0, 0.0)
    window: tuple[float, float, float, float] = (-1.0, 1.0, -1.0, 1.0)
    near: float = 1.0
    far: float = 100.0
    projection: str = "perspective"

    def __post_init__(self) -> None:
        for name in ("eye", "look_at", "up"):
            object.__setattr__(self, name, _finite_vector(name, getattr(self, name), 3))
        window = _finite_vector("window", self.window, 4)
        if not (window[0] < window[1] and window[2] < window[3]):
            raise ValueError(f"'window' must have left < right and bottom < top; got {window}")
        object.__setattr__(self, "window", window)
        if self.projection not in ("perspective", "orthographic"):
            raise ValueError(
                f"'projection' must be 'perspective' or 'orthographic'; got {self.projection!r}"
            )
        near = _number("near", self.near, 0.0 if self.projection == "perspective" else -math.inf)
        far = _number("far", self.far, -math.inf, infinite=self.projection == "perspective")
        if self.projection == "perspective" and near <= 0:
            raise ValueError(f"'near' must be > 0 for a perspective camera; got {near}")
        if not near < far:
            raise ValueError(f"'near' must be < 'far'; got near={near}, far={far}")
        object.__setattr__(self, "near", near)
        object.__setattr__(self, "far", far)
        view = np.subtract(self.look_at, self.eye)
        if not np.linalg.norm(view) > 0:
            raise ValueError("'look_at' must differ from 'eye'")
        if np.linalg.norm(np.cross(view / np.linalg.norm(view), self.up)) < 1e-9 * max(
            np.linalg.norm(self.up), 1e-300
        ):
            raise ValueError(
                f"'up' {self.up} must not be parallel to the view direction {tuple(view.tolist())}"
            )


@dataclass(frozen=True)
class Light:
    """A point light at ``position`` or a directional light shining along ``direction``."""

    kind: str = "directional"
    color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    position: tuple[float, float, float] | None = None
    direction: tuple[float, float, float] | None = None  # directional default: (0, 0, -1)

    def __post_init__(self) -> None:
        if self.kind not in ("point", "directional"):
            raise ValueError(f"'kind' must be 'point' or 'directional'; got {self.kind!r}")
        color = _finite_vector("color", self.color, 3)
        if not all(c >= 0 for c in color):
            raise ValueError(f"'color' components must be >= 0; got {color}")
        object.__setattr__(self, "color", color)
        if self.kind == "point":
            if self.position is None:
                raise ValueError("a point light needs a 'position'")
            if self.direction is not None:
                raise ValueError("a point light takes a 'position', not a 'direction'")
            object.__setattr__(self, "position", _finite_vector("position", self.position, 3))
            object.__setattr__(self, "direction", None)
        else:
            direction = _finite_vector("direction", self.direction or (0.0, 0.0, -1.0), 3)
            if not any(direction):
                raise ValueError("'direction' must not be the zero vector")
            object.__setattr__(self, "direction", direction)
            object.__setattr__(self, "position", None)


@dataclass(frozen=True, eq=False)
class Scene:
    """Objects, a camera, lights, an ambient light color and a background color."""

    objects: tuple[SceneObject, ...]
    camera: Camera = field(default_factory=Camera)
    lights: tuple[Light, ...] = (Light(),)
    ambient: tuple[float, float, float] = (1.0, 1.0, 1.0)
    background: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "objects", tuple(self.objects))
        object.__setattr__(self, "lights", tuple(self.lights))
        for name in ("ambient", "background"):
            value = _finite_vector(name, getattr(self, name), 3)
            if not all(0 <= c <= 1 for c in value):
                raise ValueError(f"{name!r} components must be in [0, 1]; got {value}")
            object.__setattr__(self, name, value)

    def triangle_count(self) -> int:
        return sum(o.mesh.triangle_count() for o in self.objects)

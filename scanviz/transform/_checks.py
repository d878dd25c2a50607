"""Argument checks shared by the transform modules: points, faces, cameras, tracers."""

from __future__ import annotations

import numpy as np

from ..conventions import as_array, check_finite_rows, type_name
from ..geometry import NOT_REAL_KINDS, plain_array
from ..scene import Camera
from ..scene.faces import face_corners
from ..trace import Tracer


def as_points(
    name: str, value: object, columns: tuple[int, ...] | None, min_rows: int = 0
) -> np.ndarray:
    """`value` as a finite (N, k) float64 array with k in `columns` (None: any k), else an error.

    The gate of the transform functions: an ndarray subclass is made plain,
    a masked array with masked values and an array of bool, complex,
    datetime, timedelta, str, bytes or object dtype are refused
    (`scanviz.geometry.plain_array`).
    """
    value = plain_array(value, repr(name), NOT_REAL_KINDS)
    array = as_array(value, f"{name!r} must be an array of numbers", got=type_name)
    if array.ndim != 2 or (columns is not None and array.shape[1] not in columns):
        wanted = " or ".join(f"(N, {k})" for k in columns or ("K",))
        raise ValueError(f"{name!r} must be an {wanted} array; got shape {array.shape}")
    if len(array) < min_rows:
        raise ValueError(f"{name!r} must have at least {min_rows} rows; got {len(array)}")
    return check_finite_rows(name, array)


def flatten_faces(faces: object, vertex_count: int) -> tuple[np.ndarray, np.ndarray]:
    """Faces as one flat index array and the start of each face in it (see `face_corners`).

    >>> indices, starts = flatten_faces([[0, 1, 2], [2, 1, 3, 4]], 5)
    >>> indices.tolist(), starts.tolist()
    ([0, 1, 2, 2, 1, 3, 4], [0, 3])
    """
    corners = face_corners(faces, vertex_count)
    return corners.corner, corners.starts


def check_camera(camera: object) -> Camera:
    """`camera` if it is a `scanviz.scene.Camera`, else a TypeError."""
    if not isinstance(camera, Camera):
        raise TypeError(f"'camera' must be a scanviz.scene.Camera; got {type(camera).__name__}")
    return camera


def check_tracer(trace: object) -> Tracer | None:
    """`trace` if it is None or a Tracer, else a TypeError."""
    if trace is not None and not isinstance(trace, Tracer):
        raise TypeError(f"'trace' must be None or a Tracer (wants/emit); got {trace!r}")
    return trace

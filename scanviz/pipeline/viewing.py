"""The viewing stage of the pipeline for a whole scene, stop by stop, as a lesson shows it.

`view_scene` takes every polygon of a scene through `scanviz.transform` in
the order `prepare` runs it: back-face culling (in world space), world ->
eye -> clip, clipping, the divide to NDC and the viewport to display. It
returns each polygon at every stop, with the view volume there, and emits
to a tracer, in that order:

* ``polygons_transformed`` for "world" (the input),
* ``face_culled`` for every face of a culled object,
* ``polygons_transformed`` for "eye" and for "clip",
* ``polygon_clipped`` for every polygon not culled,
* ``polygons_transformed`` for "ndc" and for "display".

Polygons are numbered through the scene, object 0's faces first; the
``polygon`` of every event is that number. The result is the one `prepare`
draws (the tests hold them equal); `prepare` itself stays object by object
and fast.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from ..scene.model import Scene
from ..trace.events import PolygonsTransformed
from ..transform import (
    clip_from_eye,
    clip_polygon,
    cull_faces,
    display_from_ndc,
    eye_from_world,
    ndc_from_clip,
    transform_points,
)
from ..transform._checks import check_tracer
from .prepare import _object_in_world

STOPS = ("world", "eye", "clip", "ndc", "display")
VERDICTS = ("culled", "accepted", "clipped", "rejected")


@dataclass(frozen=True)
class ViewedScene:
    """Every polygon of a scene at every stop of the viewing pipeline.

    Attributes
    ----------
    objects : (P,) ndarray of int64
        The scene object of each polygon.
    verdicts : tuple of str
        Per polygon, one of `VERDICTS`: "culled" (a back face), "accepted"
        (inside the view volume), "clipped" (cut by it) or "rejected" (outside).
    polygons : Mapping of str to tuple of ndarray of float64
        Per stop of `STOPS`, each polygon's vertices there: (k, 3) in "world"
        and "eye", (k, 4) in "clip"; in "ndc" and "display" the polygon as
        clipped, (m, 3), with m = 0 for one culled or rejected.
    volume : Mapping of str to ndarray of float64
        Per stop, the view volume's 8 corners there, (8, 3) or (8, 4) in
        "clip": near face, then far face, each from (left, bottom)
        counter-clockwise as the camera sees it.
    far : float
        Distance of the far face in `volume`: the camera's far, or just
        beyond the scene when that is infinite.
    """

    objects: np.ndarray
    verdicts: tuple[str, ...]
    polygons: Mapping[str, tuple[np.ndarray, ...]]
    volume: Mapping[str, np.ndarray]
    far: float


def view_volume(camera, far: float | None = None) -> np.ndarray:
    """The 8 corners of a camera's view volume in eye space: near face, then far face.

    Parameters
    ----------
    camera : Camera
    far : float, optional
        Distance of the far face (default the camera's; give one when that is infinite).

    Returns
    -------
    (8, 3) ndarray of float64
        Each face from (left, bottom) counter-clockwise as the camera sees it.

    Examples
    --------
    >>> from scanviz.scene import Camera
    >>> view_volume(Camera(window=(-1, 1, -1, 1), near=1.0, far=3.0))[[0, 2, 4, 6]]
    array([[-1., -1., -1.],
           [ 1.,  1., -1.],
           [-3., -3., -3.],
           [ 3.,  3., -3.]])
    """
    far = camera.far if far is None else float(far)
    if not (math.isfinite(far) and far > camera.near):
        raise ValueError(f"'far' must be finite and beyond the near plane; got {far}")
    left, right, bottom, top = camera.window
    window = np.array([[left, bottom], [right, bottom], [right, top], [left, top]], float)
    # Perspective: the window lies on the near plane and the far face is it scaled by far / near.
    scale = far / camera.near if camera.projection == "perspective" else 1.0
    near_face = np.column_stack([window, np.full(4, -camera.near)])
    far_face = np.column_stack([window * scale, np.full(4, -far)])
    return np.vstack([near_face, far_face])


class _Numbered:
    """A tracer passing events on with their ``polygon`` counted through the scene."""

    def __init__(self, tracer, first: int) -> None:
        self.tracer, self.first = tracer, first

    def wants(self, kind: str, *, polygon: int | None = None, y: int | None = None) -> bool:
        number = None if polygon is None else polygon + self.first
        return self.tracer.wants(kind, polygon=number, y=y)

    def emit(self, event) -> None:
        self.tracer.emit(dataclasses.replace(event, polygon=event.polygon + self.first))


def _rows(points: np.ndarray) -> tuple[tuple[float, ...], ...]:
    return tuple(tuple(row) for row in points.tolist())


def view_scene(
    scene: Scene, width: int, height: int, *, cull: bool | None = None, trace=None
) -> ViewedScene:
    """Cull, transform and clip a scene's polygons, keeping each at every stop.

    Parameters
    ----------
    scene : Scene
    width, height : int
        Raster size in pixels (the display stop depends on it).
    cull : bool or None
        As `scanviz.render`: None culls the back faces of closed meshes only.
    trace : Tracer or None
        Receives the events listed in the module docstring.

    Returns
    -------
    ViewedScene

    Examples
    --------
    A cube seen from a corner shows three faces; the other three are culled:

    >>> from scanviz.scene import Camera, Scene, SceneObject
    >>> from scanviz.scene.builtin import box
    >>> scene = Scene((SceneObject(box(1.0)),), Camera(eye=(3, 4, 5), window=(-0.3, 0.3, -0.3, 0.3)))
    >>> viewed = view_scene(scene, 64, 64)
    >>> viewed.verdicts  # faces -z, +z, -x, +x, -y, +y
    ('culled', 'accepted', 'culled', 'accepted', 'culled', 'accepted')
    >>> len(viewed.polygons["display"][1]), len(viewed.polygons["display"][0])
    (4, 0)
    """
    trace = check_tracer(trace)
    camera = scene.camera
    eye_matrix, clip_matrix = eye_from_world(camera), clip_from_eye(camera)
    display_matrix = display_from_ndc(width, height)
    inside = [_object_in_world(obj) for obj in scene.objects]
    world = tuple(o.world[face] for o in inside for face in o.faces)
    objects = np.repeat(np.arange(len(inside)), [len(o.faces) for o in inside]).astype(np.int64)
    eye = tuple(transform_points(eye_matrix, p)[:, :3] for p in world)
    clip = tuple(transform_points(clip_matrix, p) for p in eye)

    far = camera.far
    if not math.isfinite(far):  # draw an infinite view volume just beyond the scene
        depth = max((float(-p[:, 2].min()) for p in eye if len(p)), default=0.0)
        far = max(2 * camera.near, 1.2 * depth)
    corners = view_volume(camera, far)
    clip_corners = transform_points(clip_matrix, corners)
    ndc_corners = ndc_from_clip(clip_corners)
    volume = {
        "world": transform_points(np.linalg.inv(eye_matrix), corners)[:, :3],
        "eye": corners,
        "clip": clip_corners,
        "ndc": ndc_corners,
        "display": transform_points(display_matrix, ndc_corners)[:, :3],
    }
    eye_at = {"world": tuple(float(c) for c in camera.eye), "eye": (0.0, 0.0, 0.0)}
    objects_tuple = tuple(objects.tolist())

    def emit(stop: str, matrix, polygons) -> None:
        if trace is not None and trace.wants("polygons_transformed"):
            flat = None if matrix is None else tuple(matrix.ravel().tolist())
            trace.emit(
                PolygonsTransformed(
                    stop,
                    flat,
                    objects_tuple,
                    tuple(_rows(p) for p in polygons),
                    _rows(volume[stop]),
                    eye_at.get(stop),
                )
            )

    emit("world", None, world)
    culled = np.zeros(len(world), bool)
    first = 0
    for obj, o in zip(scene.objects, inside, strict=True):
        if obj.mesh.closed if cull is None else cull:
            numbered = None if trace is None else _Numbered(trace, first)
            culled[first : first + len(o.faces)] = cull_faces(
                camera, o.world, o.flat_faces, trace=numbered
            )[0]
        first += len(o.faces)
    emit("eye", eye_matrix, eye)
    emit("clip", clip_matrix, clip)

    verdicts, ndc = [], []
    for number, points in enumerate(clip):
        if culled[number]:
            verdicts.append("culled")
            ndc.append(np.zeros((0, 3)))
            continue
        clipped, _ = clip_polygon(points, trace=trace, polygon=number)
        if not len(clipped):
            verdicts.append("rejected")
        else:
            verdicts.append("accepted" if clipped is points else "clipped")
        ndc.append(ndc_from_clip(clipped))
    display = tuple(transform_points(display_matrix, p)[:, :3] for p in ndc)
    emit("ndc", None, ndc)
    emit("display", display_matrix, display)

    stops = {"world": world, "eye": eye, "clip": clip, "ndc": tuple(ndc), "display": display}
    for array in (*volume.values(), *(p for polygons in stops.values() for p in polygons)):
        array.setflags(write=False)
    return ViewedScene(
        objects,
        tuple(verdicts),
        MappingProxyType(stops),
        MappingProxyType(volume),
        float(far),
    )

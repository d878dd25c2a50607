"""The scene made ready for visibility: cull, transform, clip, per-corner attributes, screen polygons."""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field, fields

import numpy as np

from ..conventions import COORD_LIMIT
from ..scene.faces import FaceCorners, face_corners
from ..scene.model import Scene
from ..shading import face_normals, material_array, vertex_normals
from ..transform import clip_from_eye, clip_polygon, cull_faces, eye_from_world
from ..transform.clip import ACCEPT, CLIP, REJECT, face_verdicts
from ..vectors import unit_vectors
from ..visibility import ScreenPolygons
from ..visibility.zbuffer import VALUE_LIMIT
from .prepare_compiled import clip_coordinates, in_range, screen_vertices, within
from .result import RenderStats, Stage
from .shade import _lit

TRANSPARENCY = 7  # column of `transparency` in a material row (scanviz.shading.MATERIAL_FIELDS)
CULLED = 3  # a face's verdict after ACCEPT, CLIP, REJECT (`scanviz.transform.clip.VERDICTS`)
# Per-vertex attributes each shading model interpolates.
ATTRIBUTES = {
    "flat": 0,
    "gouraud": 3,
    "phong": 15,
    "gooch": 15,
    "fast_phong": 15,
}  # phong: normal, position, material
# What each attribute column is, for messages: (first column, last column + 1, scene field).
ATTRIBUTE_FIELDS = {
    "gouraud": ((0, 3, "lit vertex colors"),),
    "phong": ((0, 3, "normals"), (3, 6, "positions"), (6, 15, "materials")),
    "gooch": ((0, 3, "normals"), (3, 6, "positions"), (6, 15, "materials")),
    "fast_phong": ((0, 3, "normals"), (3, 6, "positions"), (6, 15, "materials")),
}


@dataclass
class _Prepared:
    """The scene after culling, transformation and clipping: what the z-buffer draws."""

    polygons: ScreenPolygons
    flat_colors: np.ndarray  # (P, 3) for flat shading, else (P, 0)
    polygon_object: np.ndarray  # (P,) index of the scene object each polygon came from
    polygon_opacity: np.ndarray  # (P,) 1 - transparency of its polygon-level material
    stats: RenderStats
    stages: list[Stage]


@dataclass(frozen=True)
class _ObjectInWorld:
    """One object's faces in world space, with per-corner normals and material rows."""

    world: np.ndarray  # (V, 3) positions
    faces: tuple[np.ndarray, ...]  # counter-clockwise in world space
    flat_faces: FaceCorners  # the same faces flattened once, for every stage
    sizes: np.ndarray  # (F,) vertices per face
    corners: np.ndarray  # (sum sizes,) vertex index of each face corner
    face_normals: np.ndarray  # (F, 3) unit
    corner_normals: np.ndarray  # (sum sizes, 3) unit
    palette: np.ndarray  # (1 + materials, 9): row 0 is the object's material
    face_material: np.ndarray  # (F,) palette row: polygon level
    corner_material: np.ndarray  # (sum sizes,) palette row: vertex level, inherited
    # Where every corner of a vertex has that vertex's normal and material (smooth or given
    # normals, no face materials): those per vertex, so Gouraud lights each vertex once.
    vertex_normals: np.ndarray | None
    vertex_material: np.ndarray | None
    centroids: np.ndarray  # (F, 3) mean of each face's corners: where flat shading lights it
    kept: dict = field(default_factory=dict)  # per-corner tables made once, on first use

    def corner_surface(self) -> np.ndarray:
        """(sum sizes, 15): each corner's normal, world position and material (Phong, Gooch)."""
        if "surface" not in self.kept:
            surface = np.hstack(
                [self.corner_normals, self.world[self.corners], self.palette[self.corner_material]]
            )
            surface.setflags(write=False)
            self.kept["surface"] = surface
        return self.kept["surface"]


# Objects are immutable (frozen, read-only arrays): their world-space faces, normals and
# palette are made once and kept while the object lives, as a GPU keeps a mesh's buffers.
_IN_WORLD: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _object_in_world(obj) -> _ObjectInWorld:
    """`obj` in world space (`_world_space`), computed on its first render and kept with it."""
    found = _IN_WORLD.get(obj)
    if found is None:
        found = _IN_WORLD[obj] = _world_space(obj)
    return found


def _world_space(obj) -> _ObjectInWorld:
    mesh, matrix = obj.mesh, obj.world_from_model
    world = mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]
    # A mirroring transform turns counter-clockwise faces clockwise: reverse them back.
    mirrored = np.linalg.slogdet(matrix[:3, :3])[0] < 0  # the sign alone: det may overflow
    faces = tuple(f[::-1] for f in mesh.faces) if mirrored else mesh.faces
    flat_faces = face_corners(faces, len(world))
    corners, face_of_corner = flat_faces.corner, flat_faces.face
    sizes = np.diff(np.append(flat_faces.starts, len(corners)))
    faces_n = face_normals(world, flat_faces)
    per_vertex = None
    if mesh.normals is not None:
        # Normals take the inverse transpose; unit first, so no product overflows.
        per_vertex = unit_vectors(unit_vectors(mesh.normals) @ np.linalg.inv(matrix[:3, :3]))
        corner_normals = per_vertex[corners]
    elif mesh.smooth:
        per_vertex = vertex_normals(world, flat_faces)
        corner_normals = per_vertex[corners]
    else:
        corner_normals = faces_n[face_of_corner]
    face_material = np.zeros(len(sizes), np.int64)
    if mesh.face_materials is not None:
        face_material = np.where(mesh.face_materials >= 0, mesh.face_materials + 1, 0)
    corner_material = face_material[face_of_corner]
    if mesh.vertex_materials is not None:
        own = mesh.vertex_materials[corners]
        corner_material = np.where(own >= 0, own + 1, corner_material)
    vertex_material = None
    if per_vertex is not None and mesh.face_materials is None:
        vertex_material = np.zeros(len(world), np.int64)
        if mesh.vertex_materials is not None:
            vertex_material = np.where(mesh.vertex_materials >= 0, mesh.vertex_materials + 1, 0)
    else:
        per_vertex = None
    starts = flat_faces.starts
    centroids = (
        np.add.reduceat(world[corners], starts) / sizes[:, None]
        if len(starts)
        else np.zeros((0, 3))
    )
    palette = material_array((obj.material, *mesh.materials))
    found = _ObjectInWorld(
        world,
        faces,
        flat_faces,
        sizes,
        corners,
        faces_n,
        corner_normals,
        palette,
        face_material,
        corner_material,
        per_vertex,
        vertex_material,
        centroids,
    )
    for array in (*(getattr(found, f.name) for f in fields(found)), *flat_faces):
        if isinstance(array, np.ndarray):
            array.setflags(write=False)  # shared by every render of the object
    return found


def prepare(
    scene: Scene,
    width: int,
    height: int,
    *,
    shading: str,
    cull: bool | None,
    tracer=None,
    transparent_visible: bool = False,
) -> _Prepared:
    """Cull, transform and clip every object; return the screen polygons the z-buffer draws."""
    clip_from_world = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    stats = RenderStats(objects=len(scene.objects))
    rows = []  # per batch of polygons: (screen, values, sizes, flat, object, opacity)
    cull_ran = False
    for index, obj in enumerate(scene.objects):
        o = _object_in_world(obj)
        stats.polygons_in += len(o.faces)
        if tracer is not None:
            from ..transform import transform_vertices

            transform_vertices(scene.camera, o.world, width, height, trace=tracer, object=index)
        clip, codes, finite = clip_coordinates(o.world, clip_from_world)
        _check_vertices("positions (clip space)", ~finite, np.full(len(clip), index), "finite")
        # Back faces of a transparent object show through it where the visibility can show them.
        see_through = transparent_visible and not obj.material.opaque
        culling = (obj.mesh.closed and not see_through) if cull is None else cull
        if culling:
            cull_ran = True
        verdict = _verdicts(scene.camera, o, codes, culling, tracer, stats)
        values, flat = _attributes(scene, o, shading, stats)
        opacity = 1.0 - o.palette[o.face_material, TRANSPARENCY]
        polygons = (clip, verdict, values, flat, opacity)
        _add_accepted(rows, index, o, polygons, width, height)
        _add_clipped(rows, index, o, polygons, width, height, tracer, stats)
    return _assembled(rows, shading, stats, _stages(stats, cull, cull_ran))


def _verdicts(camera, o: _ObjectInWorld, codes, culling, tracer, stats) -> np.ndarray:
    """Each face's verdict (ACCEPT, REJECT, CLIP or CULLED), counted in `stats`."""
    keep = np.ones(len(o.faces), bool)
    if culling:
        culled, _ = cull_faces(camera, o.world, o.flat_faces, trace=tracer)
        keep &= ~culled
        stats.culled += int(culled.sum())
    verdict = face_verdicts(codes, o.corners, o.flat_faces.starts)
    verdict[~keep] = CULLED
    stats.off_screen += int((verdict == REJECT).sum())
    stats.accepted += int((verdict == ACCEPT).sum())
    return verdict


def _attributes(scene, o: _ObjectInWorld, shading, stats) -> tuple[np.ndarray, np.ndarray]:
    """Attributes per corner and flat colours per face, by shading model."""
    world, corners = o.world, o.corners
    if shading == "gouraud" and o.vertex_normals is not None:  # each vertex lit once
        values = _lit(scene, world, o.vertex_normals, o.palette[o.vertex_material])[corners]
        stats.shaded_vertices += len(world)
    elif shading == "gouraud":  # corners of one vertex differ: each corner lit
        values = _lit(scene, world[corners], o.corner_normals, o.palette[o.corner_material])
        stats.shaded_vertices += len(values)
    elif shading in ("phong", "gooch", "fast_phong"):
        values = o.corner_surface()
    else:
        values = np.zeros((len(corners), 0))
    flat = np.zeros((len(o.faces), 3 if shading == "flat" else 0))
    if shading == "flat" and len(o.faces):
        flat = _lit(scene, o.centroids, o.face_normals, o.palette[o.face_material])
    return values, flat


def _add_accepted(rows, index, o: _ObjectInWorld, polygons, width, height) -> None:
    """Append the object's accepted faces to `rows`, projected to the screen."""
    clip, verdict, values, flat, opacity = polygons
    accepted = verdict == ACCEPT
    everything = bool(accepted.all())  # the common case: no array needs picking from
    corner_keep = slice(None) if everything else np.repeat(accepted, o.sizes)
    face_keep = slice(None) if everything else accepted
    screen = screen_vertices(clip, o.corners[corner_keep], width, height)
    rows.append((screen, values[corner_keep], o.sizes[face_keep], flat[face_keep],
                 np.full(int(accepted.sum()), index), opacity[face_keep]))  # fmt: skip


def _add_clipped(rows, index, o: _ObjectInWorld, polygons, width, height, tracer, stats) -> None:
    """Append the object's straddling faces, clipped to the view volume (drawn after the rest)."""
    clip, verdict, values, flat, opacity = polygons
    starts = np.concatenate([[0], np.cumsum(o.sizes)])
    for f in np.flatnonzero(verdict == CLIP):
        points, attributes = clip_polygon(
            clip[o.faces[f]], values[starts[f] : starts[f + 1]], trace=tracer, polygon=int(f)
        )
        stats.clipped += 1
        if len(points) >= 3:
            rows.append((_divided(points, width, height), attributes, np.array([len(points)]),
                         flat[f : f + 1], np.array([index]), opacity[f : f + 1]))  # fmt: skip
        else:
            stats.off_screen += 1


def _stages(stats, cull, cull_ran) -> list[Stage]:
    """What the cull and clip stages did, for the render plan."""
    return [
        Stage(
            "cull",
            cull_ran,
            "closed meshes: back faces removed"
            if cull_ran
            else ("cull=False" if cull is False else "no closed mesh: every face may be seen"),
        ),
        Stage(
            "clip",
            stats.clipped > 0,
            f"{stats.clipped} polygons straddle the view volume"
            if stats.clipped
            else "every polygon trivially accepted or rejected",
        ),
    ]


def _assembled(rows, shading, stats, stages) -> _Prepared:
    """All objects' rows joined into the screen polygons the z-buffer draws."""
    screen, values, sizes, flat, objects, opacity = list(zip(*rows, strict=True)) or [()] * 6
    xy = _joined([part[0] for part in screen], (0, 2))
    z = _joined([part[1] for part in screen], (0,))
    inv_w = _joined([part[2] for part in screen], (0,))
    sizes = np.concatenate(sizes).astype(np.int64) if sizes else np.zeros(0, np.int64)
    k = ATTRIBUTES[shading]
    values = _joined(values, (0, k))
    flat_colors = np.concatenate(flat) if flat else np.zeros((0, 3 if k == 0 else 0))
    polygon_object = np.concatenate(objects).astype(np.int64) if objects else np.zeros(0, np.int64)
    vertex_object = np.repeat(polygon_object, sizes)
    screen = _checked_screen(xy, z, inv_w, values, sizes, vertex_object, shading)
    stats.polygons_drawn = len(sizes)
    polygon_opacity = np.concatenate(opacity) if opacity else np.zeros(0)
    return _Prepared(screen, flat_colors, polygon_object, polygon_opacity, stats, stages)


def _joined(parts: list, empty: tuple) -> np.ndarray:
    """The parts one after another (one part as it is: the screen polygons copy it)."""
    if len(parts) == 1:
        return parts[0]
    return np.concatenate(parts) if parts else np.zeros(empty)


def _screen_polygons(xyzw, values, sizes, vertex_object, width, height, shading) -> ScreenPolygons:
    """Clipped polygons divided by w into display coordinates, checked against the z-buffer's bounds.

    The scene limits (`scanviz.scene.model`) keep every value within them;
    should one ever be out, the error names the object and the field it came
    from, not an internal array.
    """
    xy, z, inv_w = _divided(xyzw, width, height)
    return _checked_screen(xy, z, inv_w, values, sizes, vertex_object, shading)


def _divided(xyzw, width, height):
    """(xy, z, inv_w) of clip points divided by w, as `prepare_kernels.screen_vertices` divides."""
    w = xyzw[:, 3]
    with np.errstate(all="ignore"):
        xy = np.column_stack([(xyzw[:, 0] / w + 1) / 2 * width, (xyzw[:, 1] / w + 1) / 2 * height])
        return xy, xyzw[:, 2] / w, 1 / w


def _checked_screen(xy, z, inv_w, values, sizes, vertex_object, shading) -> ScreenPolygons:
    """The screen polygons once every vertex is checked against the z-buffer's bounds."""
    checks = [
        ("positions (display x, y)", xy, COORD_LIMIT, f"within +-{COORD_LIMIT} pixels"),
        ("positions (depth z)", z[:, None], VALUE_LIMIT, f"within +-{VALUE_LIMIT:g}"),
        *(
            (field, values[:, first:stop], VALUE_LIMIT, f"within +-{VALUE_LIMIT:g}")
            for first, stop, field in ATTRIBUTE_FIELDS.get(shading, ())
        ),
    ]
    for what, array, limit, rule in checks:
        if not within(array, limit):  # one pass; NaN fails it too
            _check_vertices(what, ~(np.abs(array) <= limit).all(axis=1), vertex_object, rule)
    if not in_range(inv_w, 1 / VALUE_LIMIT, VALUE_LIMIT):
        far = ~((inv_w >= 1 / VALUE_LIMIT) & (inv_w <= VALUE_LIMIT))
        rule = f"in [{1 / VALUE_LIMIT:g}, {VALUE_LIMIT:g}]"
        _check_vertices("positions (1/w)", far, vertex_object, rule)
    return ScreenPolygons.checked(
        xy, z, inv_w, values, np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    )


def _check_vertices(what: str, broken: np.ndarray, vertex_object: np.ndarray, rule: str) -> None:
    if broken.any():
        obj = int(vertex_object[np.flatnonzero(broken)[0]])
        raise ValueError(
            f"'objects[{obj}]': its {what} after the viewing transform must be {rule} (the scene "
            "limits of scanviz.scene.model keep them there: the camera or the object is beyond them)"
        )

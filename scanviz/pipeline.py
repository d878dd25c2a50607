"""The pipeline: scene -> cull -> transform -> clip -> attributes -> z-buffer -> shade -> image.

`render` plans the work first (which stages can change the image, which can
be skipped and why), then runs each stage as a plain function over arrays.
With a tracer every stage records its events; without one the compiled
kernels run and nothing is recorded.

Shading is deferred: the z-buffer keeps, per pixel, the interpolated
attributes of the visible fragment, and the shading model runs once per
visible pixel (Phong, Gooch) or per vertex before rasterization (Gouraud) or
per polygon (flat). For opaque surfaces this gives the image a forward
renderer gives, without shading fragments that are later hidden.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import steps
from .conventions import (
    COORD_LIMIT,
    SAMPLE_MODES,
    check_choice,
    check_raster_size,
    check_subpixel_bits,
)
from .limits import check_memory
from .progress import progress
from .raster.api import as_tracer
from .scene.faces import FaceCorners, face_corners
from .scene.model import Scene
from .shading import face_normals, material_array, vertex_normals
from .trace import Recorder, Trace
from .transform import classify, clip_from_eye, clip_polygon, cull_faces, eye_from_world
from .vectors import unit_vectors
from .visibility import ScreenPolygons, zbuffer
from .visibility.zbuffer import VALUE_LIMIT

SHADINGS = ("flat", "gouraud", "phong", "gooch")
VISIBILITIES = ("zbuffer", "abuffer", "flawed")
TRANSPARENCY = 7  # column of `transparency` in a material row (scanviz.shading.MATERIAL_FIELDS)
# Per-vertex attributes each shading model interpolates.
ATTRIBUTES = {
    "flat": 0,
    "gouraud": 3,
    "phong": 15,
    "gooch": 15,
}  # phong: normal, position, material
# What each attribute column is, for messages: (first column, last column + 1, scene field).
ATTRIBUTE_FIELDS = {
    "gouraud": ((0, 3, "lit vertex colors"),),
    "phong": ((0, 3, "normals"), (3, 6, "positions"), (6, 15, "materials")),
    "gooch": ((0, 3, "normals"), (3, 6, "positions"), (6, 15, "materials")),
}
PROGRESS_POLYGONS = 2000  # a-buffer renders of more polygons show a progress bar
PROGRESS_EDGES = 20000  # feature edges drawn one by one: a bar above this many
# Bytes per pixel of the buffers a render holds at once (image, depth, ids, their copies), plus
# 8 per attribute per pixel, plus the shading temporaries of per-pixel shading.
PIXEL_BYTES = {"zbuffer": 8 * 8, "abuffer": 8 * 16, "flawed": 8 * 16}
SHADING_BYTES = 8 * 64  # per pixel or fragment shaded by Phong/Gooch: vectors of every light term
FRAGMENT_BYTES = 8 * 3 * 12  # per a-buffer fragment, held about three times (parts, table, resolve)


@dataclass(frozen=True)
class Stage:
    name: str
    runs: bool
    why: str


@dataclass(frozen=True)
class RenderPlan:
    """Which stages run for this scene and which are skipped, with the reason."""

    stages: tuple[Stage, ...]

    def __str__(self) -> str:
        width = max(len(s.name) for s in self.stages)
        return "\n".join(
            f"{'run ' if s.runs else 'skip'}  {s.name:<{width}}  {s.why}" for s in self.stages
        )

    def runs(self, name: str) -> bool:
        return any(s.name == name and s.runs for s in self.stages)


@dataclass
class RenderStats:
    """What ran: polygon counts through the stages, and the z-buffer's work."""

    objects: int = 0
    polygons_in: int = 0
    culled: int = 0
    off_screen: int = 0
    clipped: int = 0
    accepted: int = 0
    polygons_drawn: int = 0
    fragments_estimated: int = 0
    rows_scanned: int = 0
    spans: int = 0
    fragments: int = 0
    depth_passed: int = 0
    depth_failed: int = 0
    shaded_vertices: int = 0
    shaded_pixels: int = 0
    edge_pixels: int = 0
    path: str = "compiled"


@dataclass(frozen=True)
class RenderResult:
    """image (H, W, 3) float64 in [0, 1], row 0 at the bottom; depth (H, W) float64 (+inf: empty);
    polygon (H, W) int64 index into the drawn polygons (-1: background)."""

    image: np.ndarray
    depth: np.ndarray
    polygon: np.ndarray
    stats: RenderStats
    plan: RenderPlan
    trace: Trace | None = field(default=None)
    alpha: np.ndarray | None = field(default=None)  # (H, W) packed coverage (a-buffer only)
    abuffer: object = field(default=None)  # the a-buffer's result: .pixel(x, y) lists fragments

    def fragments_at(self, x: int, y: int) -> tuple:
        """The a-buffer's fragment list of pixel (x, y) after insertion (a-buffer renders only)."""
        if self.abuffer is None:
            raise ValueError("fragments_at needs a render with visibility='abuffer' or 'flawed'")
        return self.abuffer.pixel(x, y)


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


def _object_in_world(obj) -> _ObjectInWorld:
    mesh, matrix = obj.mesh, obj.world_from_model
    world = mesh.positions @ matrix[:3, :3].T + matrix[:3, 3]
    # A mirroring transform turns counter-clockwise faces clockwise: reverse them back.
    mirrored = np.linalg.slogdet(matrix[:3, :3])[0] < 0  # the sign alone: det may overflow
    faces = tuple(f[::-1] for f in mesh.faces) if mirrored else mesh.faces
    flat_faces = face_corners(faces, len(world))
    corners, face_of_corner = flat_faces.corner, flat_faces.face
    sizes = np.diff(np.append(flat_faces.starts, len(corners)))
    faces_n = face_normals(world, flat_faces)
    if mesh.normals is not None:
        # Normals take the inverse transpose; unit first, so no product overflows.
        normals = unit_vectors(unit_vectors(mesh.normals) @ np.linalg.inv(matrix[:3, :3]))
        corner_normals = normals[corners]
    elif mesh.smooth:
        corner_normals = vertex_normals(world, flat_faces)[corners]
    else:
        corner_normals = faces_n[face_of_corner]
    face_material = np.zeros(len(sizes), np.int64)
    if mesh.face_materials is not None:
        face_material = np.where(mesh.face_materials >= 0, mesh.face_materials + 1, 0)
    corner_material = face_material[face_of_corner]
    if mesh.vertex_materials is not None:
        own = mesh.vertex_materials[corners]
        corner_material = np.where(own >= 0, own + 1, corner_material)
    palette = material_array((obj.material, *mesh.materials))
    return _ObjectInWorld(
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
    )


def _viewer(camera):
    """(eye, view_dir) for `illuminate`: the eye point, or the direction toward an orthographic viewer."""
    if camera.projection == "perspective":
        return np.array(camera.eye), None
    return None, unit_vectors(np.subtract(camera.eye, camera.look_at))


def _lit(scene, positions, normals, materials):
    from .shading import illuminate

    eye, view_dir = _viewer(scene.camera)
    return illuminate(
        positions,
        normals,
        materials,
        eye=eye,
        view_dir=view_dir,
        lights=scene.lights,
        ambient_light=np.array(scene.ambient),
    )


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
    rows = {"xyzw": [], "values": [], "sizes": [], "flat": [], "object": [], "opacity": []}
    cull_ran = False
    for index, obj in enumerate(scene.objects):
        o = _object_in_world(obj)
        world, faces, sizes, corners = o.world, o.faces, o.sizes, o.corners
        stats.polygons_in += len(faces)
        if tracer is not None:
            from .transform import transform_vertices

            transform_vertices(scene.camera, world, width, height, trace=tracer, object=index)
        clip = np.hstack([world, np.ones((len(world), 1))]) @ clip_from_world.T
        unfit = ~np.isfinite(clip).all(axis=1)
        _check_vertices("positions (clip space)", unfit, np.full(len(clip), index), "finite")
        keep = np.ones(len(faces), bool)
        # Back faces of a transparent object show through it where the visibility can show them.
        see_through = transparent_visible and not obj.material.opaque
        if (obj.mesh.closed and not see_through) if cull is None else cull:
            cull_ran = True
            culled, _ = cull_faces(scene.camera, world, o.flat_faces, trace=tracer)
            keep &= ~culled
            stats.culled += int(culled.sum())
        verdict = classify(clip, o.flat_faces).astype(object)
        verdict[~keep] = "culled"
        stats.off_screen += int((verdict == "reject").sum())
        stats.accepted += int((verdict == "accept").sum())
        # Attributes per corner, by shading model.
        if shading == "gouraud":
            values = _lit(scene, world[corners], o.corner_normals, o.palette[o.corner_material])
            stats.shaded_vertices += len(values)
        elif shading in ("phong", "gooch"):
            values = np.hstack([o.corner_normals, world[corners], o.palette[o.corner_material]])
        else:
            values = np.zeros((len(corners), 0))
        flat = np.zeros((len(faces), 3 if shading == "flat" else 0))
        if shading == "flat" and len(faces):
            starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
            centroids = np.add.reduceat(world[corners], starts) / sizes[:, None]
            flat = _lit(scene, centroids, o.face_normals, o.palette[o.face_material])
        corner_keep = np.repeat(verdict == "accept", sizes)
        rows["xyzw"].append(clip[corners][corner_keep])
        rows["values"].append(values[corner_keep])
        rows["sizes"].append(sizes[verdict == "accept"])
        rows["flat"].append(flat[verdict == "accept"])
        opacity = 1.0 - o.palette[o.face_material, TRANSPARENCY]
        rows["object"].append(np.full(int((verdict == "accept").sum()), index))
        rows["opacity"].append(opacity[verdict == "accept"])
        starts = np.concatenate([[0], np.cumsum(sizes)])
        for f in np.flatnonzero(verdict == "clip"):  # drawn after the accepted faces of this object
            points, attributes = clip_polygon(
                clip[faces[f]], values[starts[f] : starts[f + 1]], trace=tracer, polygon=int(f)
            )
            stats.clipped += 1
            if len(points) >= 3:
                rows["xyzw"].append(points)
                rows["values"].append(attributes)
                rows["sizes"].append(np.array([len(points)]))
                rows["flat"].append(flat[f : f + 1])
                rows["object"].append(np.array([index]))
                rows["opacity"].append(opacity[f : f + 1])
            else:
                stats.off_screen += 1
    xyzw = np.concatenate(rows["xyzw"]) if rows["xyzw"] else np.zeros((0, 4))
    sizes = (
        np.concatenate(rows["sizes"]).astype(np.int64) if rows["sizes"] else np.zeros(0, np.int64)
    )
    k = ATTRIBUTES[shading]
    values = np.concatenate(rows["values"]) if rows["values"] else np.zeros((0, k))
    flat_colors = (
        np.concatenate(rows["flat"]) if rows["flat"] else np.zeros((0, 3 if k == 0 else 0))
    )
    polygon_object = (
        np.concatenate(rows["object"]).astype(np.int64) if rows["object"] else np.zeros(0, np.int64)
    )
    vertex_object = np.repeat(polygon_object, sizes)
    screen = _screen_polygons(xyzw, values, sizes, vertex_object, width, height, shading)
    stats.polygons_drawn = len(sizes)
    stages = [
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
    polygon_opacity = np.concatenate(rows["opacity"]) if rows["opacity"] else np.zeros(0)
    return _Prepared(screen, flat_colors, polygon_object, polygon_opacity, stats, stages)


def _screen_polygons(xyzw, values, sizes, vertex_object, width, height, shading) -> ScreenPolygons:
    """Clipped polygons divided by w into display coordinates, checked against the z-buffer's bounds.

    The scene limits (`scanviz.scene.model`) keep every value within them;
    should one ever be out, the error names the object and the field it came
    from, not an internal array.
    """
    w = xyzw[:, 3]
    with np.errstate(all="ignore"):
        xy = np.column_stack([(xyzw[:, 0] / w + 1) / 2 * width, (xyzw[:, 1] / w + 1) / 2 * height])
        z, inv_w = xyzw[:, 2] / w, 1 / w
    checks = [
        ("positions (display x, y)", xy, COORD_LIMIT, f"within +-{COORD_LIMIT} pixels"),
        ("positions (depth z)", z[:, None], VALUE_LIMIT, f"within +-{VALUE_LIMIT:g}"),
        *(
            (field, values[:, first:stop], VALUE_LIMIT, f"within +-{VALUE_LIMIT:g}")
            for first, stop, field in ATTRIBUTE_FIELDS.get(shading, ())
        ),
    ]
    for what, array, limit, rule in checks:
        _check_vertices(what, ~(np.abs(array) <= limit).all(axis=1), vertex_object, rule)
    far = ~((inv_w >= 1 / VALUE_LIMIT) & (inv_w <= VALUE_LIMIT))
    _check_vertices(
        "positions (1/w)", far, vertex_object, f"in [{1 / VALUE_LIMIT:g}, {VALUE_LIMIT:g}]"
    )
    return ScreenPolygons(
        xy=xy,
        z=z,
        inv_w=inv_w,
        values=values,
        offsets=np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
    )


def _check_vertices(what: str, broken: np.ndarray, vertex_object: np.ndarray, rule: str) -> None:
    if broken.any():
        obj = int(vertex_object[np.flatnonzero(broken)[0]])
        raise ValueError(
            f"'objects[{obj}]': its {what} after the viewing transform must be {rule} (the scene "
            "limits of scanviz.scene.model keep them there: the camera or the object is beyond them)"
        )


def render(
    scene: Scene,
    width: int,
    height: int,
    *,
    shading: str = "phong",
    visibility: str = "zbuffer",
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    perspective_correct: bool = True,
    cull: bool | None = None,
    edges: bool = False,
    mask: str = "8x8",
    weights: str = "area",
    trace: object = None,
) -> RenderResult:
    """Render a scene through the classic pipeline.

    Parameters
    ----------
    scene : Scene
        See `scanviz.scene` and `scanviz.io.load_scene` ("builtin:sphere", a JSON file, ...).
    width, height : int
        Raster size.
    shading : {"flat", "gouraud", "phong", "gooch"}
        Flat: one color per polygon. Gouraud: lit at vertices, colors
        interpolated. Phong: normals interpolated, lit per pixel. Gooch: tone
        shading per pixel.
    visibility : {"zbuffer", "abuffer", "flawed"}
        The z-buffer (one sample per pixel); Carpenter's a-buffer (pixel masks,
        exact areas, fragment lists and the packer: anti-aliased, with
        transparency); or the flawed coverage-blending z-buffer of the thesis
        §6.3, for comparison (it leaves seams between adjacent polygons).
    mask : {"4x4", "8x4", "8x8"}
        Sub-samples per pixel of the a-buffer's pixel masks.
    weights : {"area", "mask"}
        The packer weighs fragments by exact area or by mask bits.
    sample, subpixel_bits
        As in `scanviz.scan_convert`.
    perspective_correct : bool
        Interpolate attributes with 1/w (default) or affinely in screen space.
    cull : bool or None
        Back-face culling; None culls closed meshes only.
    edges : bool
        Draw silhouette, boundary and crease (> 30 degrees) edges in black over
        the image with the midpoint line algorithm, where they are not hidden.
    trace : None, True, or Tracer
        None runs the compiled kernels; a tracer runs the traced references.

    Returns
    -------
    RenderResult
        Image, depth and alpha never hold NaN.

    Raises
    ------
    scanviz.limits.ResourceLimitError
        If the render's buffers (per pixel; for the a-buffer, its fragments as
        they are made) would go over the memory limit (`scanviz.limits`).
    ValueError, TypeError
        On a bad argument, naming it and the rule.

    Notes
    -----
    An a-buffer render of more than `PROGRESS_POLYGONS` polygons shows a
    progress bar (tqdm); Ctrl-C or a kernel interrupt stops it between
    polygons with KeyboardInterrupt, returning nothing. The plan's a-buffer
    line bounds the work: at most the sum of the polygons' bounding boxes in
    fragments (`RenderStats.fragments_estimated`).
    """
    width, height = check_raster_size(width, height)
    check_choice("shading", shading, SHADINGS)
    check_choice("visibility", visibility, VISIBILITIES)
    check_choice("sample", sample, SAMPLE_MODES)
    check_subpixel_bits(subpixel_bits)
    check_choice("mask", mask, ("4x4", "8x4", "8x8"))
    check_choice("weights", weights, ("area", "mask"))
    if not isinstance(scene, Scene):
        raise TypeError(f"'scene' must be a scanviz.scene.Scene; got {type(scene).__name__}")
    tracer = as_tracer(trace)
    _check_render_memory(width, height, visibility, ATTRIBUTES[shading], shading)
    prepared = prepare(
        scene,
        width,
        height,
        shading=shading,
        cull=cull,
        tracer=tracer,
        transparent_visible=visibility == "abuffer",
    )
    stats = prepared.stats
    stats.fragments_estimated = _fragment_bound(prepared.polygons, width, height)
    options = {"subpixel_bits": subpixel_bits, "perspective": perspective_correct, "tracer": tracer}
    if visibility == "zbuffer":
        image, depth, polygon = _zbuffered(
            scene, prepared, width, height, shading, sample, **options
        )
        alpha = abuffer = None
    else:
        image, depth, polygon, abuffer = _antialiased(
            scene, prepared, width, height, shading, visibility, mask, weights, **options
        )
        alpha = abuffer.alpha
    _check_no_nan(visibility, image=image, depth=depth, alpha=alpha)
    if edges:
        stats.edge_pixels = _draw_feature_edges(scene, image, depth, width, height)
    plan = _plan(scene, prepared, shading, visibility, edges, tracer)
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    # Float bounds: with int bounds numpy takes a casting path ~20x slower on a 1024² image.
    np.clip(image, 0.0, 1.0, out=image)
    return RenderResult(image, depth, polygon, stats, plan, recorded, alpha, abuffer)


def _check_render_memory(width, height, visibility, attributes, shading) -> None:
    """Refuse a render whose per-pixel buffers alone are over the memory limit, before any is made.

    The z-buffer holds every attribute per pixel and shades pixels; the
    a-buffer's per-fragment storage is checked as it grows (`_polygon_fragments`).
    """
    per_pixel = PIXEL_BYTES[visibility]
    if visibility == "zbuffer":
        per_pixel += 8 * attributes + (SHADING_BYTES if shading in ("phong", "gooch") else 0)
    check_memory(
        width * height * per_pixel, f"a {width}x{height} {visibility} render with {shading} shading"
    )


def _fragment_bound(polygons: ScreenPolygons, width: int, height: int) -> int:
    """At most this many fragments: the sum of the polygons' bounding boxes in pixels, on the raster."""
    if not polygons.count:
        return 0
    starts = polygons.offsets[:-1]
    low = np.floor(np.minimum.reduceat(polygons.xy, starts, axis=0))
    high = np.ceil(np.maximum.reduceat(polygons.xy, starts, axis=0))
    size = np.array([width, height])
    extent = np.clip(high, 0, size) - np.clip(low, 0, size)
    return int(np.prod(np.maximum(extent, 0), axis=1).sum())


def _check_no_nan(stage: str, **arrays) -> None:
    """Last resort: a NaN that got past the arithmetic is an error naming the stage, never a pixel."""
    for name, array in arrays.items():
        if array is not None and np.isnan(array).any():
            raise ValueError(
                f"render: the {stage} stage produced {int(np.isnan(array).sum())} NaN values in "
                f"{name!r}; this is a bug in scanviz, please report it with the scene"
            )


def _zbuffered(
    scene, prepared, width, height, shading, sample, *, subpixel_bits, perspective, tracer
):
    """(image, depth, polygon) through the z-buffer, shading the visible pixels afterwards."""
    stats = prepared.stats
    result = zbuffer(
        prepared.polygons,
        width,
        height,
        sample=sample,
        subpixel_bits=subpixel_bits,
        perspective=perspective,
        trace=tracer,
    )
    z = result.stats
    stats.rows_scanned, stats.spans, stats.fragments = z.rows_scanned, z.spans, z.fragments
    stats.depth_passed, stats.depth_failed, stats.path = z.depth_passed, z.depth_failed, z.path
    visible = result.polygon >= 0
    if shading == "flat":  # one gather: row 0 of the table is the background (polygon -1)
        image = np.vstack([scene.background, prepared.flat_colors])[result.polygon + 1]
        return image, result.depth, result.polygon
    image = np.empty((height, width, 3))
    image[...] = scene.background
    if shading == "gouraud":
        image[visible] = result.values[visible]
    else:
        image[visible] = _shade_pixels(scene, shading, result.values[visible])
        stats.shaded_pixels = int(visible.sum())
        if shading == "phong" and tracer is not None and tracer.wants("illumination"):
            _trace_illumination(scene, tracer, result)
    return image, result.depth, result.polygon


def _antialiased(
    scene,
    prepared,
    width,
    height,
    shading,
    visibility,
    mask,
    weights,
    *,
    subpixel_bits,
    perspective,
    tracer,
):
    """(image, depth, polygon, a-buffer result): fragments per pixel, resolved by the a-buffer.

    Every fragment is shaded where it is, at the centroid of its covered
    sub-samples (the a-buffer needs every fragment's color before it knows
    which are seen). `depth` and `polygon` are those of each pixel's nearest
    fragment.
    """
    from .abuffer import MASK_LAYOUTS, Fragments, resolve

    polygons, stats = prepared.polygons, prepared.stats
    parts, owners = _polygon_fragments(
        polygons, width, height, mask, subpixel_bits, perspective, tracer, visibility
    )
    owner = np.concatenate(owners) if owners else np.zeros(0, np.int64)
    values = (
        np.concatenate([f.values for f in parts])
        if parts
        else np.zeros((0, polygons.values.shape[1]))
    )
    if shading == "flat":
        colors = prepared.flat_colors[owner]
    elif shading == "gouraud":
        colors = values
    else:
        colors = _shade_pixels(scene, shading, values)
        stats.shaded_pixels = len(owner)

    def joined(field, dtype):
        return (
            np.concatenate([getattr(f, field) for f in parts]).astype(dtype)
            if parts
            else np.zeros(0, dtype)
        )

    fragments = Fragments(
        x=joined("xs", np.int64),
        y=joined("ys", np.int64),
        polygon=owner.astype(np.int64),
        object=prepared.polygon_object[owner],
        mask=joined("masks", np.uint64),
        area=joined("areas", np.float64),
        zmin=joined("zmin", np.float64),
        zmax=joined("zmax", np.float64),
        color=np.asarray(colors, dtype=np.float64).reshape(-1, 3),
        opacity=prepared.polygon_opacity[owner],
    )
    result = resolve(
        fragments,
        width,
        height,
        layout=MASK_LAYOUTS[mask],
        weights=weights,
        background=scene.background,
        mode="abuffer" if visibility == "abuffer" else "flawed",
        trace=tracer,
    )
    stats.fragments, stats.path = len(owner), result.stats.path
    depth = np.full((height, width), np.inf)
    nearest = np.full((height, width), -1, np.int64)
    order = np.lexsort((-fragments.zmin, fragments.x, fragments.y))  # per pixel, nearest last
    depth[fragments.y[order], fragments.x[order]] = fragments.zmin[order]
    nearest[fragments.y[order], fragments.x[order]] = owner[order]
    return result.image, depth, nearest, result


def _polygon_fragments(polygons, width, height, mask, subpixel_bits, perspective, tracer, mode):
    """Every polygon's fragments, in drawing order, with a progress bar for large scenes.

    Storage grows polygon by polygon and is checked against the memory limit
    as it grows; Ctrl-C stops between polygons (KeyboardInterrupt, nothing returned).
    """
    from .abuffer.fragments import polygon_fragments

    parts, owners, stored = [], [], 0
    per_fragment = FRAGMENT_BYTES + 8 * polygons.value_count + SHADING_BYTES
    what = f"the fragments of a {width}x{height} {mode} render"
    with progress(polygons.count, f"{mode} polygons", threshold=PROGRESS_POLYGONS) as bar:
        for p in range(polygons.count):
            rows = slice(polygons.offsets[p], polygons.offsets[p + 1])
            found = polygon_fragments(
                polygons.xy[rows],
                polygons.z[rows],
                polygons.inv_w[rows],
                polygons.values[rows],
                width,
                height,
                mask=mask,
                subpixel_bits=subpixel_bits,
                perspective=perspective,
                trace=tracer,
                polygon_index=p,
            )
            bar.update(1)
            if found is None:
                continue
            stored += len(found.xs)
            check_memory(stored * per_fragment, f"{what} ({stored} fragments by polygon {p})")
            parts.append(found)
            owners.append(np.full(len(found.xs), p))
    return parts, owners


def _zbuffer_path(tracer) -> str:
    if tracer is not None:
        return "traced reference"
    if steps.replaced():
        return "reference: a step of scanviz.steps is replaced"
    return "opaque visibility, compiled kernel"


def _plan(scene, prepared, shading, visibility, edges, tracer) -> RenderPlan:
    transparent = any(
        not o.material.opaque or any(not m.opaque for m in o.mesh.materials) for o in scene.objects
    )
    deferred = shading in ("phong", "gooch") and visibility == "zbuffer"
    work = (
        f"{prepared.stats.polygons_drawn} polygons, at most "
        f"{prepared.stats.fragments_estimated} fragments (their bounding boxes)"
    )
    stages = [
        Stage("transform", True, "world -> eye -> clip -> NDC -> display"),
        *prepared.stages,
        Stage(
            "shade vertices",
            shading == "gouraud",
            "Gouraud lights each vertex" if shading == "gouraud" else f"{shading} shading",
        ),
        Stage(
            "shade pixels",
            shading in ("phong", "gooch"),
            (
                "per visible pixel only (deferred)"
                if deferred
                else "per fragment, at the centroid of its covered sub-samples"
            )
            if shading in ("phong", "gooch")
            else f"{shading} shading",
        ),
        Stage(
            "z-buffer",
            visibility == "zbuffer",
            _zbuffer_path(tracer) if visibility == "zbuffer" else f"visibility={visibility!r}",
        ),
        Stage(
            "a-buffer",
            visibility == "abuffer",
            f"anti-aliasing: pixel masks, exact areas, fragment lists, packer; {work}"
            if visibility == "abuffer"
            else f"coverage blending instead (the flawed z-buffer anti-aliasing); {work}"
            if visibility == "flawed"
            else "transparency ignored by the z-buffer"
            if transparent
            else "opaque scene without anti-aliasing",
        ),
        Stage(
            "feature edges",
            edges,
            "silhouettes and creases, midpoint lines, depth-tested" if edges else "edges=False",
        ),
        Stage(
            "trace",
            tracer is not None,
            "recording events" if tracer is not None else "no tracer: nothing recorded",
        ),
    ]
    return RenderPlan(tuple(stages))


def _shade_pixels(scene: Scene, shading: str, values: np.ndarray) -> np.ndarray:
    """Colors of visible pixels from their interpolated normal, position and material."""
    normals, positions, materials = values[:, 0:3], values[:, 3:6], values[:, 6:15]
    if shading == "phong":
        return _lit(scene, positions, normals, materials)
    from .shading import gooch

    eye, view_dir = _viewer(scene.camera)
    # Gooch tones are defined for one light; without any, light from the viewer (a headlight).
    light = scene.lights[0] if scene.lights else _headlight(scene.camera)
    return gooch(positions, normals, materials, eye, light, view_dir=view_dir)


def _headlight(camera):
    from .scene.model import Light

    return Light(kind="directional", direction=tuple(np.subtract(camera.look_at, camera.eye)))


EDGE_DEPTH_TOLERANCE = 1e-4  # NDC depth by which an edge pixel may lie behind the surface drawn


def _draw_feature_edges(scene: Scene, image, depth, width: int, height: int) -> int:
    """Draw every object's silhouette, boundary and crease edges where the z-buffer shows them.

    Edges with an end behind the eye plane are left out. Returns the pixels drawn.
    """
    from .raster.lines import midpoint_line
    from .shading import feature_edges

    clip_from_world = clip_from_eye(scene.camera) @ eye_from_world(scene.camera)
    eye, view_dir = _viewer(scene.camera)
    drawn = 0
    for obj in scene.objects:
        o = _object_in_world(obj)
        found = feature_edges(o.world, o.flat_faces, eye, view_dir=view_dir)
        pairs = np.concatenate([found["silhouette"], found["boundary"], found["crease"]])
        clip = np.hstack([o.world, np.ones((len(o.world), 1))]) @ clip_from_world.T
        with progress(len(pairs), "feature edges", threshold=PROGRESS_EDGES) as bar:
            for a, b in pairs:
                bar.update(1)
                if clip[a, 3] <= 0 or clip[b, 3] <= 0:
                    continue
                ends = [
                    (
                        (clip[v, 0] / clip[v, 3] + 1) / 2 * width,
                        (clip[v, 1] / clip[v, 3] + 1) / 2 * height,
                    )
                    for v in (a, b)
                ]
                if max(abs(c) for end in ends for c in end) > 2**20:
                    continue
                xs, ys = midpoint_line(*(int(np.floor(c)) for end in ends for c in end))
                along = np.linspace(0.0, 1.0, len(xs))
                z = clip[a, 2] / clip[a, 3] + along * (
                    clip[b, 2] / clip[b, 3] - clip[a, 2] / clip[a, 3]
                )
                inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
                xs, ys, z = xs[inside], ys[inside], z[inside]
                shown = z <= depth[ys, xs] + EDGE_DEPTH_TOLERANCE
                image[ys[shown], xs[shown]] = 0.0
                drawn += int(shown.sum())
    return drawn


def _trace_illumination(scene: Scene, tracer, result) -> None:
    """Record the Phong terms of every visible pixel the tracer wants (same colors as drawn)."""
    from .shading import illuminate_traced

    eye, view_dir = _viewer(scene.camera)
    for y, x in np.argwhere(result.polygon >= 0):
        polygon = int(result.polygon[y, x])
        if tracer.wants("illumination", polygon=polygon, y=int(y)):
            values = result.values[y, x]
            illuminate_traced(
                values[3:6],
                values[0:3],
                values[6:15],
                eye,
                scene.lights,
                np.array(scene.ambient),
                trace=tracer,
                pixel=(int(x), int(y)),
                view_dir=view_dir,
                polygon=polygon,
            )

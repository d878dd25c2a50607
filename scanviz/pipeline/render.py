"""`render`: plan the work, prepare the scene, decide visibility, shade, draw edges.

`render` plans the work first (which stages can change the image, which can
be skipped and why), then runs each stage as a plain function over arrays.
With a tracer every stage records its events; without one the compiled
kernels run and nothing is recorded.

Shading is deferred: the opaque visibility algorithms keep, per pixel, the
interpolated attributes of the visible fragment, and the shading model runs
once per visible pixel (Phong, Gooch) or per vertex before rasterization
(Gouraud) or per polygon (flat). For opaque surfaces this gives the image a
forward renderer gives, without shading fragments that are later hidden.
The opaque algorithms are chosen by name from `scanviz.visibility.ALGORITHMS`
(`solve` dispatches); the a-buffer path is `scanviz.pipeline.antialiased`.

The last stage, the image function (Rendermatic thesis ch. 7), is a function
of what each pixel keeps; `scanviz.pipeline.relight` runs it again under new
lights and materials (`RenderResult.relight`, docs/relight.md).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numba import njit, prange

from .. import steps
from ..conventions import SAMPLE_MODES, check_choice, check_raster_size, check_subpixel_bits
from ..limits import check_memory
from ..raster.api import as_tracer
from ..scene.model import Material, Scene
from ..shading.taylor import EXPANSIONS
from ..threads import use_threads
from ..trace import Recorder
from ..visibility import ALGORITHMS, ScreenPolygons, Visibility, algorithm, solve
from . import shade
from .antialiased import _antialiased
from .fast_shade import fast_phong_image
from .feature_lines import _draw_feature_edges
from .prepare import ATTRIBUTES, prepare
from .result import PixelRecord, RenderPlan, RenderResult, Stage
from .shade import _exact_materials, _image_function, _trace_illumination

SHADINGS = ("flat", "gouraud", "phong", "gooch", "fast_phong")
ANTIALIASED = ("abuffer", "flawed")
VISIBILITIES = (*ALGORITHMS, *ANTIALIASED)  # the opaque algorithms, then the a-buffer's two
# Bytes per pixel of the buffers a render holds at once (image, depth, ids, their copies), plus
# 8 per attribute per pixel, plus the shading temporaries of per-pixel shading.
PIXEL_BYTES = {"opaque": 8 * 8, "abuffer": 8 * 16, "flawed": 8 * 16}
SHADING_BYTES = 8 * 64  # per pixel or fragment shaded by Phong/Gooch: vectors of every light term
MERGES = ("none", "object")  # the a-buffer's `merge` (scanviz.abuffer.merge)
RELIGHTABLE = ("phong", "gooch")  # shaded per pixel from the kept normal, position and material
FIXED_BEFORE_VISIBILITY = {
    "flat": "per polygon before visibility",
    "gouraud": "per vertex before visibility",
}


def render(
    scene: Scene,
    width: int,
    height: int,
    *,
    shading: str = "phong",
    visibility: str | Visibility = "zbuffer",
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    perspective_correct: bool = True,
    cull: bool | None = None,
    edges: bool = False,
    mask: str = "8x8",
    weights: str = "area",
    merge: str = "none",
    expansion: str = "vertex",
    trace: object = None,
) -> RenderResult:
    """Render a scene through the classic pipeline.

    Parameters
    ----------
    scene : Scene
        See `scanviz.scene` and `scanviz.io.load_scene` ("builtin:sphere", a JSON file, ...).
    width, height : int
        Raster size.
    shading : {"flat", "gouraud", "phong", "gooch", "fast_phong"}
        Flat: one color per polygon. Gouraud: lit at vertices, colors
        interpolated. Phong: normals interpolated, lit per pixel. Gooch: tone
        shading per pixel.
        Fast Phong (Wang 1989, ch. 3) shades each visible triangle with Taylor
        quadratics of cos θ and cos φ stepped by forward differences and the
        highlight from a look-up table (opaque visibility only;
        `scanviz.pipeline.fast_shade`).

    visibility : {"zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock", "abuffer", "flawed"}
        The z-buffer (one sample per pixel); the classic opaque algorithms of
        `scanviz.visibility` (a name, or an instance such as
        ``BSP(root="fewest_splits")`` for its options), each painted with the
        z-buffer's scan conversion and shaded the same way; Carpenter's
        a-buffer (pixel masks, exact areas, fragment lists and the packer:
        anti-aliased, with transparency); or the flawed coverage-blending
        z-buffer of the thesis §6.3, for comparison (it leaves seams between
        adjacent polygons).
    mask : {"4x4", "8x4", "8x8"}
        Sub-samples per pixel of the a-buffer's pixel masks.
    weights : {"area", "mask"}
        The packer weighs fragments by exact area or by mask bits.
    merge : {"none", "object"}
        The a-buffer's lists as Carpenter keeps them short on smooth meshes:
        "object" merges, per pixel, the fragments of one object whose depth
        ranges overlap or abut (masks or-ed, colors weighted by area) before
        insertion; "none" (default) keeps one fragment per polygon
        (`scanviz.abuffer.merge`). Only the a-buffer visibilities use it.
    expansion : {"vertex", "centroid"}
        Fast Phong's Taylor expansion point in each triangle: its first vertex
        (the dissertation) or its centroid (smaller error,
        docs/shading-fast-phong.md). The other shadings ignore it.
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
        Image, depth and alpha never hold NaN. Its `record` keeps what the
        image function needs, so that ``result.relight(lights=...)`` can
        recompute a Phong or Gooch image without visibility (docs/relight.md).

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
    chunks of polygons (of up to 4,096; between polygons when traced) with
    KeyboardInterrupt, returning nothing. The plan's a-buffer
    line bounds the work: at most the sum of the polygons' bounding boxes in
    fragments (`RenderStats.fragments_estimated`).
    """
    width, height = check_raster_size(width, height)
    check_choice("shading", shading, SHADINGS)
    if isinstance(visibility, str):  # ALGORITHMS now: one registered after import counts too
        check_choice("visibility", visibility, (*ALGORITHMS, *ANTIALIASED))
    chosen = None if visibility in ANTIALIASED else algorithm(visibility)
    name = visibility if chosen is None else chosen.name
    if shading == "fast_phong" and chosen is None:
        raise ValueError(
            f"shading='fast_phong' shades the visible triangles of an opaque visibility "
            f"algorithm; visibility={name!r} blends fragments: use shading='phong' with it"
        )
    check_choice("sample", sample, SAMPLE_MODES)
    check_subpixel_bits(subpixel_bits)
    check_choice("mask", mask, ("4x4", "8x4", "8x8"))
    check_choice("weights", weights, ("area", "mask"))
    check_choice("merge", merge, MERGES)
    check_choice("expansion", expansion, EXPANSIONS)
    if not isinstance(scene, Scene):
        raise TypeError(f"'scene' must be a scanviz.scene.Scene; got {type(scene).__name__}")
    tracer = as_tracer(trace)
    _check_render_memory(width, height, name, ATTRIBUTES[shading], shading, edges)
    prepared = prepare(
        scene,
        width,
        height,
        shading=shading,
        cull=cull,
        tracer=tracer,
        transparent_visible=name == "abuffer",
    )
    stats = prepared.stats
    stats.fragments_estimated = _fragment_bound(prepared.polygons, width, height)
    options = {"subpixel_bits": subpixel_bits, "perspective": perspective_correct, "tracer": tracer}
    solved = alpha = abuffer = None
    if chosen is not None:
        image, solved = _opaque(
            scene, prepared, chosen, width, height, shading, sample, expansion=expansion, **options
        )
        depth, polygon = solved.depth, solved.polygon
    else:
        image, depth, polygon, abuffer = _antialiased(
            scene, prepared, width, height, shading, name, mask, weights, merge=merge, **options
        )
        alpha = abuffer.alpha
    _check_no_nan(name, image=image, depth=depth, alpha=alpha)
    edge_pixels = None
    if edges:
        edge_pixels, stats.edge_pixels = _feature_edge_pixels(scene, depth, width, height)
        image[edge_pixels] = 0.0
    stages = tuple(prepared.stages)
    plan = _plan(_transparent(scene, {}), stats, stages, shading, name, edges, tracer)
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    # Float bounds: with int bounds numpy takes a casting path ~20x slower on a 1024² image.
    np.clip(image, 0.0, 1.0, out=image)
    record = PixelRecord(scene, shading, name, prepared.polygon_object, edge_pixels, stages)
    return RenderResult(
        image, depth, polygon, stats, plan, recorded, alpha, abuffer, solved, record
    )


def _feature_edge_pixels(scene, depth, width, height) -> tuple[np.ndarray, int]:
    """((H, W) bool, count): where the feature edges draw black, kept so that a relight redraws them."""
    unmarked = np.ones((height, width), bool)
    drawn = _draw_feature_edges(scene, unmarked, depth, width, height)
    return ~unmarked, drawn


def _check_render_memory(width, height, visibility, attributes, shading, edges) -> None:
    """Refuse a render whose per-pixel buffers alone are over the memory limit, before any is made.

    The z-buffer holds every attribute per pixel and shades pixels (and keeps
    them: they are the record `relight` reads); the feature edges mark their
    pixels in two bytes per pixel; the a-buffer's per-fragment storage is
    checked as it grows (`_polygon_fragments`).
    """
    per_pixel = PIXEL_BYTES.get(visibility, PIXEL_BYTES["opaque"]) + (2 if edges else 0)
    if visibility not in ANTIALIASED:
        per_pixel += 8 * attributes + (
            SHADING_BYTES if shading in ("phong", "gooch", "fast_phong") else 0
        )
    check_memory(
        width * height * per_pixel, f"a {width}x{height} {visibility} render with {shading} shading"
    )


def _fragment_bound(polygons: ScreenPolygons, width: int, height: int) -> int:
    """At most this many fragments: the sum of the polygons' bounding boxes in pixels, on the raster."""
    return int(_bounding_boxes(polygons.xy, polygons.offsets, width, height))


@njit(cache=True)
def _bounding_boxes(xy, offsets, width, height):  # pragma: no cover - compiled
    """Sum over polygons of (their floor..ceil bounding box clipped to the raster), in pixels."""
    total = 0
    for p in range(offsets.shape[0] - 1):
        first = offsets[p]
        x_low = x_high = xy[first, 0]
        y_low = y_high = xy[first, 1]
        for v in range(first + 1, offsets[p + 1]):
            x_low, x_high = min(x_low, xy[v, 0]), max(x_high, xy[v, 0])
            y_low, y_high = min(y_low, xy[v, 1]), max(y_high, xy[v, 1])
        columns = min(max(np.ceil(x_high), 0.0), width) - min(max(np.floor(x_low), 0.0), width)
        rows = min(max(np.ceil(y_high), 0.0), height) - min(max(np.floor(y_low), 0.0), height)
        total += int(max(columns, 0.0) * max(rows, 0.0))
    return total


def _check_no_nan(stage: str, **arrays) -> None:
    """Last resort: a NaN that got past the arithmetic is an error naming the stage, never a pixel."""
    for name, array in arrays.items():
        # One pairwise sum first: NaN only if some entry is (depth holds +inf, never -inf).
        if array is not None and np.isnan(array.sum()) and np.isnan(array).any():
            raise ValueError(
                f"render: the {stage} stage produced {int(np.isnan(array).sum())} NaN values in "
                f"{name!r}; this is a bug in scanviz, please report it with the scene"
            )


def _opaque(
    scene,
    prepared,
    chosen,
    width,
    height,
    shading,
    sample,
    *,
    expansion,
    subpixel_bits,
    perspective,
    tracer,
):
    """(image, VisibilityResult): the visible pixels by `chosen`, shaded afterwards."""
    stats = prepared.stats
    result = solve(
        chosen,
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
    if shading in ("flat", "gouraud"):  # colors fixed before visibility: one gather
        colors = prepared.flat_colors if shading == "flat" else np.zeros((0, 3))
        background = np.asarray(scene.background, np.float64)
        image = _gathered_image(result.polygon, colors, result.values, background)
        return image, result
    if shading == "fast_phong":  # per screen triangle after visibility (pipeline/fast_shade.py)
        image, stats.shaded_pixels = fast_phong_image(
            scene, prepared.polygons, result, width, height, sample, subpixel_bits, expansion
        )
        return image, result
    _exact_materials(prepared.polygons, result)
    image, stats.shaded_pixels = _image_function(
        scene, shading, result.polygon, result.values, prepared.polygon_object, {}
    )
    if shading == "phong" and tracer is not None and tracer.wants("illumination"):
        _trace_illumination(scene, tracer, result)
    return image, result


def _gathered_image(polygon, colors, values, background):
    """(H, W, 3): each pixel's polygon's color (flat), else its values (Gouraud), else the background."""
    image = np.empty((*polygon.shape, 3))
    shared = use_threads(polygon.size, shade.PARALLEL_PIXELS)
    gather = _gather_shared if shared else _gather_here
    gather(polygon, colors, values, background, image)
    return image


@njit(cache=True, parallel=True)
def _gather_shared(polygon, colors, values, background, image):  # pragma: no cover - compiled
    for y in prange(polygon.shape[0]):
        _gather_row(y, polygon, colors, values, background, image)


@njit(cache=True)
def _gather_here(polygon, colors, values, background, image):  # pragma: no cover - compiled
    for y in range(polygon.shape[0]):
        _gather_row(y, polygon, colors, values, background, image)


@njit(cache=True, inline="always")
def _gather_row(y, polygon, colors, values, background, image):  # pragma: no cover - compiled
    for x in range(polygon.shape[1]):
        p = polygon[y, x]
        for c in range(3):
            if p < 0:
                image[y, x, c] = background[c]
            elif colors.shape[0]:
                image[y, x, c] = colors[p, c]
            else:
                image[y, x, c] = values[y, x, c]


def _zbuffer_path(tracer) -> str:
    if tracer is not None:
        return "traced reference"
    if steps.replaced():
        return "reference: a step of scanviz.steps is replaced"
    return "opaque visibility, compiled kernel"


def _transparent(scene: Scene, materials: Mapping[int, Material]) -> bool:
    """Whether any material of the scene lets light through (`materials` replaces objects' ones)."""
    return any(
        not materials[i].opaque
        if i in materials
        else not o.material.opaque or any(not m.opaque for m in o.mesh.materials)
        for i, o in enumerate(scene.objects)
    )


def _plan(transparent, stats, prepared_stages, shading, visibility, edges, tracer) -> RenderPlan:
    deferred = shading in ("phong", "gooch") and visibility not in ANTIALIASED
    opaque = visibility not in ANTIALIASED
    work = (
        f"{stats.polygons_drawn} polygons, at most "
        f"{stats.fragments_estimated} fragments (their bounding boxes)"
    )
    stages = [
        Stage("transform", True, "world -> eye -> clip -> NDC -> display"),
        *prepared_stages,
        Stage(
            "shade vertices",
            shading == "gouraud",
            "Gouraud lights each vertex" if shading == "gouraud" else f"{shading} shading",
        ),
        Stage(
            "shade pixels",
            shading in ("phong", "gooch", "fast_phong"),
            (
                "per visible pixel only (deferred)"
                if deferred
                else "per fragment, at the centroid of its covered sub-samples"
            )
            if shading in ("phong", "gooch")
            else "per visible triangle: Taylor quadratics stepped by forward differences, "
            "the highlight from a look-up table"
            if shading == "fast_phong"
            else f"{shading} shading",
        ),
        Stage(
            "z-buffer",
            visibility == "zbuffer",
            _zbuffer_path(tracer) if visibility == "zbuffer" else f"visibility={visibility!r}",
        ),
        Stage(
            "list priority / image space",
            opaque and visibility != "zbuffer",
            f"{visibility}: decides what is visible, painted with the z-buffer's scan conversion"
            f" ({_zbuffer_path(tracer)})"
            if opaque and visibility != "zbuffer"
            else f"visibility={visibility!r}",
        ),
        Stage(
            "a-buffer",
            visibility == "abuffer",
            f"anti-aliasing: pixel masks, exact areas, fragment lists, packer; {work}"
            if visibility == "abuffer"
            else f"coverage blending instead (the flawed z-buffer anti-aliasing); {work}"
            if visibility == "flawed"
            else f"transparency ignored by {'the z-buffer' if visibility == 'zbuffer' else visibility}"
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

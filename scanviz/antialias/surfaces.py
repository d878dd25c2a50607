"""Wang 1989, ch. 5: anti-aliased hidden-line drawings and smoothed visible surfaces of grid surfaces.

Hidden lines (§5.1): the Floating Perimeter Algorithm's visible segments (the
"image data file", one ``x_s y_s x_e y_e`` line per segment) drawn by
DISLOP_L, by post-anti-aliasing with the line LUT, or aliased (the FPA's own
raster points). Smoothed surfaces (§5.2): the hidden-surface FPA, shaded, and
its outer silhouette blended with the background by area (DISLOP_E on the
closed outline of the projected triangles, or the edge area LUT along it);
on request, pixels of inner silhouettes (a self-overlapping image) are found
by `post.silhouette_mask` and box-filtered.

Coordinates: the FPA's raster point (x, y) is the pixel whose sample, screen
(x, y), is nearest; its centre in scanviz pixel coordinates (pixel (x, y) =
[x, x+1] x [y, y+1]) is (x + 1/2, y + 1/2), where the segments start and end
(a run of one point becomes a unit segment centred there). See docs/antialiasing.md, "Chapter 5".
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..conventions import check_choice, short_repr
from ..limits import read_bounded
from ..surfaces import GridSurface, View, floating_perimeter
from ..surfaces.perimeter import PerimeterResult, visible_runs
from ..trace.display import RichDisplay
from .edge_algorithm import dislop_edge
from .line import dislop_line
from .post import post_antialias, silhouette_mask

LINE_METHODS = ("dislop", "post", "aliased")
COMBINE = ("max", "over", "sum")
SILHOUETTES = ("dislop", "post", "none")
SIDE_STEP = 1e-6  # how far beside an outline piece's midpoint its two sides are tested (pixels)


@dataclass(frozen=True)
class LineStats(RichDisplay):
    """segments drawn, ``points`` of them single raster points widened to a unit
    segment, ``pixels`` touched (coverage > 0), and seconds in the FPA and in drawing."""

    segments: int
    points: int
    pixels: int
    fpa_seconds: float
    draw_seconds: float


@dataclass(frozen=True)
class AntialiasedLines:
    """A hidden-line drawing and how it was made.

    Attributes
    ----------
    image : (H, W) ndarray of float64
        ``background + (intensity - background) * coverage``, row 0 at the bottom.
    coverage : (H, W) ndarray of float64
        The lines' combined coverage in [0, 1].
    segments : (N, 2, 2) ndarray of float64
        The segments drawn, ((x_s, y_s), (x_e, y_e)) in scanviz pixel coordinates.
    method, combine : str
    fpa : PerimeterResult
    stats : LineStats
    """

    image: np.ndarray
    coverage: np.ndarray
    segments: np.ndarray
    method: str
    combine: str
    fpa: PerimeterResult
    stats: LineStats


def fpa_segments(fpa: PerimeterResult) -> tuple[np.ndarray, int]:
    """The FPA's visible runs as (N, 2, 2) segments between pixel centres, and how many were points.

    A run of one raster point has no length, so DISLOP_L would draw nothing
    where the aliased drawing lights a pixel: it becomes the unit segment
    through the pixel centre along its edge's major axis.

    >>> from scanviz.surfaces import GridSurface, View, floating_perimeter
    >>> flat = GridSurface([0.0, 1.0], [0.0, 1.0], [[0, 0], [0, 0]])
    >>> fpa = floating_perimeter(flat, View((0.5, 0.5, 5), (0, 0, -1), "parallel"), 6, 6)
    >>> fpa_segments(fpa)[0][0].tolist()
    [[0.5, 5.5], [5.5, 5.5]]
    """
    first, last = visible_runs(fpa.visible, fpa.point_edge)
    points = fpa.points.astype(np.float64) + 0.5
    segments = np.stack([points[first], points[last]], axis=1)
    single = first == last
    if single.any():
        edge = fpa.point_edge[first[single]]
        edge_first = np.searchsorted(fpa.point_edge, edge, side="left")
        edge_last = np.searchsorted(fpa.point_edge, edge, side="right") - 1
        delta = np.abs(fpa.points[edge_last] - fpa.points[edge_first])
        half = np.where((delta[:, 0] >= delta[:, 1])[:, None], [0.5, 0.0], [0.0, 0.5])
        centre = points[first[single]]
        segments[single] = np.stack([centre - half, centre + half], axis=1)
    return segments.reshape(-1, 2, 2), int(single.sum())


def write_segments(path, segments) -> None:
    """Write the image data file of §5.1: one ``x_s y_s x_e y_e`` line per segment, exact floats.

    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "lines.txt")
    >>> write_segments(path, [[(100.3, 150.2), (108.6, 155.8)]])
    >>> open(path).read()
    '100.3 150.2 108.6 155.8\\n'
    """
    segments = _as_segments(segments)
    with open(path, "w", encoding="ascii") as file:
        for row in segments.reshape(-1, 4).tolist():
            file.write(" ".join(repr(float(v)) for v in row) + "\n")


def read_segments(path) -> np.ndarray:
    """Read an image data file (`write_segments`) as (N, 2, 2) float64; blank lines are skipped.

    Raises
    ------
    ValueError
        If a line does not hold 4 finite numbers (the message names the line).
    """
    rows = []
    text = read_bounded(path)  # a regular file within the file limit (no FIFO, no device)
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            values = [float(v) for v in line.split()]
        except ValueError:
            values = []
        if len(values) != 4 or not np.isfinite(values).all():
            raise ValueError(
                f"{path}: line {number} must hold 4 finite numbers x_s y_s x_e y_e; "
                f"got {line.strip()[:60]!r}"
            )
        rows.append(values)
    return np.array(rows, dtype=np.float64).reshape(-1, 2, 2)


def _as_segments(segments) -> np.ndarray:
    array = np.asarray(segments, dtype=np.float64)
    if array.size == 0:
        return np.zeros((0, 2, 2))
    if array.ndim != 3 or array.shape[1:] != (2, 2):
        raise ValueError(f"'segments' must be an (N, 2, 2) array; got shape {array.shape}")
    if not np.isfinite(array).all():
        raise ValueError("'segments' must be finite")
    return array


def antialiased_hidden_lines(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    method: str = "dislop",
    exact: bool = False,
    combine: str = "over",
    background: float = 0.0,
    intensity: float = 1.0,
) -> AntialiasedLines:
    """The FPA's visible lines drawn by DISLOP_L, post-anti-aliased, or aliased (Wang 1989 §5.1).

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
    method : {"dislop", "post", "aliased"}
        DISLOP_L on every segment; `post.post_antialias` with the line area
        LUT; or the FPA's raster points themselves.
    exact : bool
        DISLOP_L's exact band area (adds the fourth pixel past slope 0.75).
    combine : {"max", "over", "sum"}
        How the coverages of overlapping segments join (DISLOP route): the
        larger (a frame buffer written at one intensity keeps the brightest),
        ``1 - (1 - a)(1 - b)``, or the sum clipped to 1. The post route blends
        each table pixel over the image, i.e. "over".
    background, intensity : float in [0, 1]
        The grey level of the background and of the lines.

    Returns
    -------
    AntialiasedLines

    Raises
    ------
    ValueError
        If `method` or `combine` is unknown or a level is outside [0, 1]; as
        `floating_perimeter` otherwise.

    Examples
    --------
    >>> flat = GridSurface([0.0, 1.0], [0.0, 1.0], [[0, 0], [0, 0]])
    >>> lines = antialiased_hidden_lines(flat, View((0.5, 0.5, 5), (0, 0, -1), "parallel"), 6, 6)
    >>> lines.stats.segments, lines.image[0].round(2).tolist()
    (4, [0.75, 1.0, 1.0, 1.0, 1.0, 0.75])
    """
    check_choice("method", method, LINE_METHODS)
    check_choice("combine", combine, COMBINE)
    background, intensity = _level("background", background), _level("intensity", intensity)
    start = time.perf_counter()
    fpa = floating_perimeter(surface, view, width, height, "lines")
    segments, points = fpa_segments(fpa)
    drawn = time.perf_counter()
    height, width = fpa.lines.shape
    if method == "aliased":
        coverage = fpa.lines.astype(np.float64)
    else:
        coverage = draw_segments(
            segments, width, height, method=method, exact=exact, combine=combine
        )
    finished = time.perf_counter()
    stats = LineStats(
        len(segments), points, int((coverage > 0).sum()), drawn - start, finished - drawn
    )
    image = background + (intensity - background) * coverage
    return AntialiasedLines(image, coverage, segments, method, combine, fpa, stats)


def draw_segments(
    segments: object,
    width: int,
    height: int,
    *,
    method: str = "dislop",
    exact: bool = False,
    combine: str = "over",
) -> np.ndarray:
    """The coverage of 1-pixel-wide segments (an image data file's), by DISLOP_L or the line LUT.

    Parameters
    ----------
    segments : (N, 2, 2) array_like of float
        ((x_s, y_s), (x_e, y_e)) in scanviz pixel coordinates.
    width, height : int
    method : {"dislop", "post"}
    exact, combine
        As `antialiased_hidden_lines`.

    Returns
    -------
    (height, width) ndarray of float64 in [0, 1]

    Examples
    --------
    Fig 5-1's segment, our coordinates (the dissertation's + 1/2): pixel (101, 151).

    >>> coverage = draw_segments([[(100.8, 150.7), (109.1, 156.3)]], 120, 160)
    >>> round(float(coverage[151, 101]), 5), round(float(coverage.sum()), 6)
    (0.76602, 10.012492)
    """
    check_choice("method", method, ("dislop", "post"))
    check_choice("combine", combine, COMBINE)
    segments = _as_segments(segments)
    if method == "post":
        black = np.zeros((height, width))
        return post_antialias(black, segments, kind="line", table="area")[..., 0]
    coverage = np.zeros((height, width))
    for p0, p1 in segments:
        coverage = _combine(coverage, dislop_line(p0, p1, width, height, exact=exact), combine)
    return np.clip(coverage, 0.0, 1.0)


def _combine(coverage: np.ndarray, line: np.ndarray, combine: str) -> np.ndarray:
    if combine == "max":
        return np.maximum(coverage, line)
    if combine == "over":
        return coverage + line - coverage * line  # 1 - (1 - a)(1 - b), exact where a = 0
    return np.minimum(coverage + line, 1.0)


def _level(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
        raise TypeError(f"{name!r} must be a real number; got {short_repr(value)}")
    if not 0 <= value <= 1:  # compared as given: an int past float64 is out of range, not an error
        raise ValueError(f"{name!r} must be in [0, 1]; got {short_repr(value)}")
    return float(value)


@dataclass(frozen=True)
class SurfaceStats(RichDisplay):
    """``boundary`` pixels blended on the outline, ``inner`` pixels box-filtered (case b),
    outline ``pieces``, and seconds in the FPA, the outline and the blending."""

    boundary: int
    inner: int
    pieces: int
    fpa_seconds: float
    outline_seconds: float
    blend_seconds: float


@dataclass(frozen=True)
class SmoothedSurface:
    """A shaded hidden-surface image with its silhouettes anti-aliased.

    Attributes
    ----------
    image : (H, W, 3) ndarray of float64
    aliased : (H, W, 3) ndarray of float64
        The hidden-surface FPA's image (centre samples), before any blending.
    coverage : (H, W) ndarray of float64
        The area of each pixel inside the surface's outline that was used:
        DISLOP_E's (exact), the edge LUT's where an outline piece passes (else
        the aliased coverage), or the aliased coverage (0/1) for "none".
    silhouettes : (K, 2, 2) ndarray of float64
        The outline pieces: where the union of the projected triangles ends,
        in scanviz pixel coordinates.
    flags : (K,) ndarray of int64
        `post_antialias`'s edge flags: 1 = inside below (``|dy| <= |dx|``) or on the -x side.
    inner : (H, W) ndarray of bool
        Case b: pixels inside the outline that `post.silhouette_mask` marks (empty for "none").
    method : str
    fpa : PerimeterResult
    stats : SurfaceStats
    """

    image: np.ndarray
    aliased: np.ndarray
    coverage: np.ndarray
    silhouettes: np.ndarray
    flags: np.ndarray
    inner: np.ndarray
    method: str
    fpa: PerimeterResult
    stats: SurfaceStats


def screen_triangles(surface: GridSurface, view: View, width: int, height: int) -> np.ndarray:
    """The mesh's triangles in scanviz pixel coordinates, counter-clockwise, zero-area ones left out.

    Returns
    -------
    (T, 3, 2) ndarray of float64
        Display coordinates = screen + 1/2 (`View.camera`), so that
        ``render(surface.scene(view, w, h), w, h)`` draws the same triangles.
    """
    screen = view.screen_from_world(surface.points(), width, height)[0] + 0.5
    triangles = screen[np.asarray(surface.to_mesh().faces)]
    d1, d2 = triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    triangles[cross < 0] = triangles[cross < 0][:, ::-1]
    return triangles[cross != 0]


def _covered(points: np.ndarray, triangles: np.ndarray, chunk: int = 4096) -> np.ndarray:
    """Whether each point lies strictly inside some counter-clockwise triangle."""
    inside = np.zeros(len(points), dtype=bool)
    for lo in range(0, len(points), chunk):
        p = points[lo : lo + chunk, None, :]
        hit = np.ones((len(p), len(triangles)), dtype=bool)
        for k in range(3):
            a, b = triangles[None, :, k], triangles[None, :, (k + 1) % 3]
            hit &= (b[..., 0] - a[..., 0]) * (p[..., 1] - a[..., 1]) > (b[..., 1] - a[..., 1]) * (
                p[..., 0] - a[..., 0]
            )
        inside[lo : lo + chunk] = hit.any(axis=1)
    return inside


def outline(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The outline pieces of the union of counter-clockwise triangles and their edge flags.

    Candidates are the triangle edges not cancelled by the reversed edge of
    a neighbour (the grid's border and the folds of the projection); they are
    split where they cross each other, and a piece is on the outline if just
    beside its midpoint one side is covered by a triangle and the other is not.

    Returns
    -------
    pieces : (K, 2, 2) ndarray of float64
    flags : (K,) ndarray of int64
        1: the inside is below (``|dy| <= |dx|``) or on the -x side (steep), as `post_antialias`.

    >>> square = np.array([[(0, 0), (2, 0), (2, 2)], [(0, 0), (2, 2), (0, 2)]], float)
    >>> pieces, flags = outline(square)
    >>> len(pieces), flags.tolist()
    (4, [0, 1, 1, 0])
    """
    if len(triangles) == 0:
        return np.zeros((0, 2, 2)), np.zeros(0, np.int64)
    edges = np.stack([triangles, np.roll(triangles, -1, axis=1)], axis=2).reshape(-1, 2, 2)
    keys = np.round(edges, 9).reshape(-1, 4)
    reverse = keys[:, [2, 3, 0, 1]]
    forward = {tuple(k) for k in keys.tolist()}
    cancelled = np.array([tuple(r) in forward for r in reverse.tolist()])
    _, first = np.unique(keys[~cancelled], axis=0, return_index=True)
    candidates = edges[~cancelled][np.sort(first)]
    pieces = _split(candidates)
    direction = pieces[:, 1] - pieces[:, 0]
    length = np.hypot(direction[:, 0], direction[:, 1])
    pieces, direction, length = pieces[length > 0], direction[length > 0], length[length > 0]
    left = np.stack([-direction[:, 1], direction[:, 0]], axis=1) / length[:, None]
    middle = pieces.mean(axis=1)
    on_left = _covered(middle + SIDE_STEP * left, triangles)
    on_right = _covered(middle - SIDE_STEP * left, triangles)
    keep = on_left != on_right
    inward = np.where(on_left[:, None], left, -left)[keep]
    shallow = np.abs(direction[keep, 1]) <= np.abs(direction[keep, 0])
    flags = np.where(shallow, inward[:, 1] < 0, inward[:, 0] < 0).astype(np.int64)
    return pieces[keep], flags


def _split(segments: np.ndarray, chunk: int = 512) -> np.ndarray:
    """The segments cut at every point where another one crosses (or touches) them."""
    p, d = segments[:, 0], segments[:, 1] - segments[:, 0]
    pieces = []
    for lo in range(0, len(segments), chunk):
        pi, di = p[lo : lo + chunk, None], d[lo : lo + chunk, None]
        denominator = di[..., 0] * d[None, :, 1] - di[..., 1] * d[None, :, 0]
        offset = p[None] - pi
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (offset[..., 0] * d[None, :, 1] - offset[..., 1] * d[None, :, 0]) / denominator
            u = (offset[..., 0] * di[..., 1] - offset[..., 1] * di[..., 0]) / denominator
        cuts = (denominator != 0) & (t > 0) & (t < 1) & (u >= 0) & (u <= 1)
        for row in range(len(pi)):
            ts = np.unique(np.r_[0.0, t[row][cuts[row]], 1.0])
            points = pi[row, 0] + ts[:, None] * di[row, 0]
            pieces.append(np.stack([points[:-1], points[1:]], axis=1))
    return np.concatenate(pieces) if pieces else np.zeros((0, 2, 2))


def outline_loops(pieces: np.ndarray, flags: np.ndarray) -> list[np.ndarray] | None:
    """The outline pieces chained into closed loops, inside on the left; None if they do not close.

    Each piece is turned so that the inside is on its left (counter-clockwise
    around the surface's image, clockwise around a hole), then joined end to
    start. A vertex where two loops touch (two pieces start there), or a
    piece left open, gives None.
    """
    direction = pieces[:, 1] - pieces[:, 0]
    shallow = np.abs(direction[:, 1]) <= np.abs(direction[:, 0])
    # inside on the left of p0 -> p1 means: shallow, inside below iff dx < 0; steep, -x iff dy > 0.
    left = np.where(
        shallow, (flags == 1) == (direction[:, 0] < 0), (flags == 1) == (direction[:, 1] > 0)
    )
    turned = np.where(left[:, None, None], pieces, pieces[:, ::-1])
    key = [tuple(k) for k in np.round(turned, 6).reshape(-1, 4).tolist()]
    starts = {}
    for index, k in enumerate(key):
        if k[:2] in starts:
            return None
        starts[k[:2]] = index
    unused, loops = set(range(len(key))), []
    while unused:
        index = unused.pop()
        loop, first = [turned[index, 0]], key[index][:2]
        while key[index][2:] != first:
            index = starts.get(key[index][2:])
            if index is None or index not in unused:
                return None
            unused.discard(index)
            loop.append(turned[index, 0])
        if len(loop) >= 3:
            loops.append(np.array(loop))
    return loops


def smoothed_surface(
    surface: GridSurface,
    view: View,
    width: int,
    height: int,
    *,
    shading: str = "fast_phong",
    silhouettes: str = "dislop",
    background: object = (0.0, 0.0, 0.0),
    threshold: float | None = None,
) -> SmoothedSurface:
    """The shaded hidden-surface FPA with its silhouettes anti-aliased (Wang 1989 §5.2).

    Parameters
    ----------
    surface : GridSurface
    view : View
    width, height : int
        At least 2 each.
    shading : str
        A `render` shading ("fast_phong", "phong", "gouraud", "flat", "gooch").
    silhouettes : {"dislop", "post", "none"}
        Case a, the outer silhouette: every pixel the outline crosses gets
        ``A * C + (1 - A) * background``, with A its area inside the outline
        (DISLOP_E, exact; or the edge area LUT along the outline pieces) and C
        its shaded colour (for a pixel whose centre is outside, the mean of
        its shaded 8-neighbours). "none" is the aliased image.
    background : RGB in [0, 1]
    threshold : float in [0, 1] or None
        Case b (opt-in): pixels inside the outline (and not next to it) that
        `post.silhouette_mask` marks at this threshold are replaced by the
        mean of their 3 x 3 neighbourhood; None (default) leaves them. Measured
        against the a-buffer it barely helps (see docs/antialiasing.md).

    Returns
    -------
    SmoothedSurface

    Raises
    ------
    ValueError
        If `silhouettes` is unknown or `background` is not 3 levels in [0, 1];
        as `floating_perimeter` and `post.silhouette_mask` otherwise.

    Examples
    --------
    >>> flat = GridSurface([0.0, 1.0], [0.0, 1.0], [[0, 0], [0, 0]])
    >>> view = View((0.5, 0.5, 5), (0, 0, -1), "parallel")
    >>> smooth = smoothed_surface(flat, view, 6, 6, shading="flat")
    >>> smooth.stats.pieces, smooth.coverage[0].tolist()
    (4, [0.25, 0.5, 0.5, 0.5, 0.5, 0.25])
    """
    check_choice("silhouettes", silhouettes, SILHOUETTES)
    background = _background(background)
    start = time.perf_counter()
    scene = surface.scene(view, width, height, background=tuple(background.tolist()))
    fpa = floating_perimeter(
        surface, view, width, height, "surface", shading=shading, sample="center", scene=scene
    )
    aliased = fpa.image
    covered = fpa.facet >= 0
    outlined = time.perf_counter()
    pieces, flags = outline(screen_triangles(surface, view, width, height))
    if silhouettes == "dislop":
        coverage = _outline_area(surface, view, pieces, flags, width, height)
    elif silhouettes == "post":
        black = np.zeros(covered.shape)
        table = post_antialias(black, pieces, kind="edge", flags=flags, table="area")[..., 0]
        coverage = np.where(table > 0, table, covered.astype(np.float64))
    else:
        coverage = covered.astype(np.float64)
    blended = time.perf_counter()
    image = aliased.copy()
    boundary = (coverage < 1.0) | ~covered
    if silhouettes != "none" and boundary.any():
        colour = _spread(aliased, covered)
        area = coverage[boundary][:, None]
        image[boundary] = area * colour[boundary] + (1.0 - area) * background
    inner = np.zeros(covered.shape, dtype=bool)
    if silhouettes != "none" and threshold is not None:
        inner = silhouette_mask(aliased, threshold) & ~_grow(boundary)
        image[inner] = _box3(aliased)[inner]
    finished = time.perf_counter()
    stats = SurfaceStats(
        int((boundary & (coverage > 0)).sum()), int(inner.sum()), len(pieces),
        outlined - start, blended - outlined, finished - blended,
    )  # fmt: skip
    return SmoothedSurface(image, aliased, coverage, pieces, flags, inner, silhouettes, fpa, stats)


def _outline_area(surface, view, pieces, flags, width, height) -> np.ndarray:
    """DISLOP_E's area of the outline: its loops, or (if they do not close) all the triangles."""
    if len(pieces) == 0:
        return np.zeros((height, width))
    loops = outline_loops(pieces, flags)
    if loops:
        return dislop_edge(loops, width, height)
    return dislop_edge(list(screen_triangles(surface, view, width, height)), width, height)


def _spread(image: np.ndarray, covered: np.ndarray) -> np.ndarray:
    """The image, with each uncovered pixel given the mean of its covered 8-neighbours (two passes)."""
    colour, known = image.copy(), covered.copy()
    for _ in range(2):
        total = _neighbour_sum(np.where(known[..., None], colour, 0.0))
        count = _neighbour_sum(known[..., None].astype(np.float64))
        fill = ~known & (count[..., 0] > 0)
        colour[fill] = total[fill] / count[fill]
        known = known | fill
    return colour


def _neighbour_sum(values: np.ndarray) -> np.ndarray:
    padded = np.pad(values, ((1, 1), (1, 1), (0, 0)))
    height, width = values.shape[:2]
    return sum(
        padded[1 + dy : 1 + dy + height, 1 + dx : 1 + dx + width]
        for dy in (-1, 0, 1)
        for dx in (-1, 0, 1)
        if dy or dx
    )


def _box3(image: np.ndarray) -> np.ndarray:
    """The 3 x 3 mean, edges replicated."""
    padded = np.pad(image, ((1, 1), (1, 1), (0, 0)), mode="edge")
    height, width = image.shape[:2]
    return (
        sum(padded[dy : dy + height, dx : dx + width] for dy in range(3) for dx in range(3)) / 9.0
    )


def _grow(mask: np.ndarray) -> np.ndarray:
    """The mask and its 8-neighbours."""
    return (_neighbour_sum(mask[..., None].astype(np.float64))[..., 0] > 0) | mask


def _background(value: object) -> np.ndarray:
    array = np.asarray(value, dtype=np.float64) if not isinstance(value, str) else None
    if array is None or array.shape != (3,) or not (np.isfinite(array).all()):
        raise ValueError(f"'background' must be an RGB triple; got {short_repr(value)}")
    if not ((array >= 0) & (array <= 1)).all():
        raise ValueError(f"'background' must be in [0, 1]; got {short_repr(value)}")
    return array

"""Every visibility algorithm on one scene beside the z-buffer, and the taxonomy they fit in.

`compare_visibility` solves screen polygons with each algorithm of
`scanviz.visibility.ALGORITHMS` and draws one panel per algorithm: the
visible polygon of each pixel in a fixed palette (white: background), and
red outlines on the pixels where it shows another polygon than the
z-buffer. `taxonomy_table` is Sutherland's characterization of the
algorithms (object or image space; sort first, sort last or subdivide;
point sampling or continuous) as an HTML table, one row per algorithm.
`split_pieces` shows how a split polygon's pieces share out its samples.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable
from dataclasses import MISSING, dataclass, fields

import numpy as np

from ..trace import Recorder
from ..visibility import ALGORITHMS, ScreenPolygons, Surfaces, Visibility, algorithm, solve, zbuffer
from ..visibility.draw_decisions import samples
from ._common import WIDEST, pixel_image

PALETTE = (  # polygon p is PALETTE[p % 9]; no red in it: red marks a disagreement
    "#0072b2",
    "#e69f00",
    "#009e73",
    "#56b4e9",
    "#f0e442",
    "#cc79a7",
    "#8c564b",
    "#999999",
    "#17becf",
)
BACKGROUND = "#ffffff"
DIFFERENCE = "#e00000"
COLUMNS = 3  # panels per row


@dataclass(frozen=True)
class Taxon:
    """One algorithm in the taxonomy: where it works, when it sorts, how it samples."""

    name: str  # the `render(visibility=...)` name
    title: str
    space: str
    sort: str
    sampling: str
    decides: str
    module: str


TAXONOMY = (
    Taxon(
        "zbuffer",
        "z-buffer (Catmull)",
        "image",
        "sort last: a depth test at each sample, polygons in any order",
        "point sampling",
        "the nearest polygon per sample, while painting",
        "scanviz.visibility.zbuffer",
    ),
    Taxon(
        "abuffer",
        "a-buffer (Carpenter)",
        "image",
        "sort last: each pixel's fragment list, kept in depth order, packed at the end",
        "continuous within a pixel (exact area, sub-pixel mask)",
        "a blend of the fragments per pixel",
        "scanviz.abuffer",
    ),
    Taxon(
        "painter",
        "painter's algorithm",
        "object (list priority)",
        "sort first: whole polygons on one depth key, no test",
        "continuous (whole polygons), painted by point sampling",
        "an order of polygons, painted back to front",
        "scanviz.visibility.painter",
    ),
    Taxon(
        "depth_sort",
        "depth sort (Newell, Newell, Sancha)",
        "object (list priority)",
        "sort first on z, then the ambiguity tests: swap, or split a cycle",
        "continuous (extents, planes, edges), painted by point sampling",
        "an order of pieces, painted back to front",
        "scanviz.visibility.depth_sort",
    ),
    Taxon(
        "bsp",
        "BSP tree (Fuchs, Kedem, Naylor)",
        "object (list priority)",
        "sort first: a tree of planes built once, traversed for the eye",
        "continuous (planes), painted by point sampling",
        "an order of pieces, back to front (or front to back)",
        "scanviz.visibility.bsp",
    ),
    Taxon(
        "scanline",
        "scanline (Watkins, Bouknight)",
        "image",
        "sort first: y (sorted surface table), then x (active surfaces); z per span",
        "continuous along a row (exact spans, split where planes cross), point-sampled across",
        "the visible polygon per span",
        "scanviz.visibility.scanline_visibility",
    ),
    Taxon(
        "warnock",
        "area subdivision (Warnock)",
        "image",
        "subdivide to simplify: quadrants until one polygon decides, down to a pixel",
        "point sampling: an area is its samples, met and covered as the z-buffer's spans",
        "the visible polygon per area",
        "scanviz.visibility.warnock",
    ),
)
TAXONOMY_COLUMNS = (
    "algorithm",
    "visibility=",
    "space",
    "sort",
    "sampling",
    "decides",
    "module",
)


def taxonomy_table() -> str:
    """The taxonomy of the visibility algorithms (Sutherland, Sproull, Schumacker 1974), as HTML.

    One row per algorithm of scanviz (`TAXONOMY`): the space it works in
    (object: loop over polygons and decide each one's visibility; image:
    loop over pixels and decide what each shows), when it sorts (first,
    last, or subdivide to simplify), point sampling or continuous, what it
    decides, and its module.

    Returns
    -------
    str
        An HTML table (show it with ``IPython.display.HTML``).

    Examples
    --------
    >>> table = taxonomy_table()
    >>> table.startswith("<table") and "subdivide to simplify" in table
    True
    """
    cell = "<{0} style='padding:2px 8px;text-align:left;vertical-align:top'>{1}</{0}>"
    head = "".join(cell.format("th", html.escape(c)) for c in TAXONOMY_COLUMNS)
    body = "".join(
        "<tr>"
        + "".join(
            cell.format("td", f"<code>{html.escape(v)}</code>" if k in (1, 6) else html.escape(v))
            for k, v in enumerate(
                (t.title, t.name, t.space, t.sort, t.sampling, t.decides, t.module)
            )
        )
        + "</tr>"
        for t in TAXONOMY
    )
    return (
        "<table style='font-size:12px;border-collapse:collapse'>"
        f"<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
    )


def compare_visibility(
    polygons: ScreenPolygons,
    width: int,
    height: int,
    algorithms: Iterable[str | Visibility] | None = None,
    **options,
):
    """One panel per algorithm: the visible polygon per pixel, red where it is not the z-buffer's.

    Parameters
    ----------
    polygons : ScreenPolygons
        The scene, in display coordinates (e.g. `scanviz.visibility.examples`).
    width, height : int
        Raster size.
    algorithms : iterable of str or Visibility, optional
        Names in `scanviz.visibility.ALGORITHMS` or instances with options
        (``Painter(key="zmax")``); default: every registered algorithm, in
        the order of `algorithm_names`.
    **options
        ``sample``, ``subpixel_bits``, ``perspective``: as `scanviz.visibility.solve`.

    Returns
    -------
    matplotlib.figure.Figure
        One axes per algorithm, in the order given; each titled with the
        algorithm (and the options that differ from the defaults) and
        "N differ": the samples where it shows another polygon than the
        z-buffer (a different polygon, or one where the z-buffer shows the
        background, or the reverse). Those pixels are outlined in red.
        Polygon p is drawn in ``PALETTE[p % len(PALETTE)]``; a legend names
        the polygons when there are no more than the palette's colors.

    Examples
    --------
    >>> from scanviz.visibility import examples
    >>> figure = compare_visibility(examples.cyclic_overlap(), 24, 24, ["zbuffer", "painter"])
    >>> [axes.get_title() for axes in figure.axes]
    ['zbuffer\\n0 differ', 'painter\\n35 differ']
    """
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    chosen = [algorithm(a) for a in (algorithm_names() if algorithms is None else algorithms)]
    if not chosen:
        raise ValueError("'algorithms' must name at least one visibility algorithm")
    reference = solve("zbuffer", polygons, width, height, **options).polygon
    rows = math.ceil(len(chosen) / COLUMNS)
    columns = min(len(chosen), COLUMNS)
    side = WIDEST / COLUMNS  # inches per panel
    figure = Figure(figsize=(side * columns, side * rows * max(height / width, 0.5) + 0.8))
    for k, visibility in enumerate(chosen):
        shown = solve(visibility, polygons, width, height, **options).polygon
        axes = figure.add_subplot(rows, columns, k + 1)
        pixel_image(axes, polygon_colors(shown))
        wrong = outline_samples(axes, shown != reference)
        axes.set_title(f"{_label(visibility)}\n{wrong} differ", fontsize=10)
        axes.set_xlim(0, width)
        axes.set_ylim(0, height)
    if polygons.count <= len(PALETTE):
        handles = [Patch(fc=PALETTE[p], label=f"polygon {p}") for p in range(polygons.count)]
        handles.append(Patch(fc="none", ec=DIFFERENCE, label="not the z-buffer's"))
        columns = len(handles) if len(handles) <= 4 else math.ceil(len(handles) / 2)
        figure.legend(handles=handles, loc="lower center", ncol=columns, fontsize=9)
    figure.tight_layout(rect=(0, 0.06, 1, 1))
    return figure


def split_pieces(
    polygons: ScreenPolygons,
    width: int,
    height: int,
    visibility: str | Visibility = "bsp",
    polygon: int | None = None,
    **options,
):
    """The pieces of one split polygon: each piece's samples, and how many pieces cover each.

    Parameters
    ----------
    polygons : ScreenPolygons
        The scene, in display coordinates.
    width, height : int
        Raster size.
    visibility : str or Visibility
        A list-priority algorithm that splits ("bsp", "depth_sort").
    polygon : int, optional
        The polygon to show; default: the first one the algorithm split.
    **options
        As `scanviz.visibility.solve`.

    Returns
    -------
    matplotlib.figure.Figure
        Left, each piece's samples in its own colour (a square centred on
        each sample), with its outline (the polygon clipped at the cut
        lines) and label; right, the number of
        pieces covering each of the polygon's samples, titled with the
        samples covered once (red: none or two, which a correct split never
        leaves).

    Examples
    --------
    >>> from scanviz.visibility import examples
    >>> figure = split_pieces(examples.split_hole(), 32, 32)
    >>> figure.axes[1].get_title()
    'polygon 1: 22 of 22 samples covered once'
    """
    from matplotlib.figure import Figure

    result = solve(visibility, polygons, width, height, **options)
    split = [piece.polygon for piece in result.order if piece.cuts]
    if polygon is None and not split:
        raise ValueError(f"{_label(algorithm(visibility))} split no polygon of this scene")
    chosen = split[0] if polygon is None else int(polygon)
    pieces = [piece for piece in result.order if piece.polygon == chosen]
    surfaces = Surfaces.of(polygons, width, height, **options)
    masks = [samples(surfaces, piece) for piece in pieces]
    whole = next(p for p in surfaces.pieces() if p.polygon == chosen)
    inside, counts = samples(surfaces, whole), np.sum(masks, axis=0)
    figure = Figure(figsize=(WIDEST, WIDEST / 2 * max(height / width, 0.5) + 0.4))
    left, right = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    colors = np.ones((height, width, 3))
    for k, (piece, mask) in enumerate(zip(pieces, masks, strict=True)):
        colors[mask] = polygon_color(k)
        left.fill(*piece.vertices[:, :2].T, fc="none", ec="black", lw=1.0)  # the sample frame
        if mask.any():
            ys, xs = np.nonzero(mask)
            left.annotate(piece.label, (xs.mean(), ys.mean()), ha="center", va="center", fontsize=9)
    pixel_image(left, colors, offset=-0.5)  # each square centred on its sample
    title = f"{_label(algorithm(visibility))}: the {len(pieces)} pieces of polygon {chosen}"
    left.set_title(title, fontsize=10)
    once = int((inside & (counts == 1)).sum())
    pixel_image(right, np.where(inside, counts, np.nan), offset=-0.5, cmap="Greens", vmin=0, vmax=2)
    outline_samples(right, inside & (counts != 1) | ~inside & (counts > 0), offset=-0.5)
    right.set_title(
        f"polygon {chosen}: {once} of {int(inside.sum())} samples covered once", fontsize=10
    )
    for axes in (left, right):
        axes.set_xlim(-0.5, width - 0.5)
        axes.set_ylim(-0.5, height - 0.5)
    figure.tight_layout()
    return figure


def algorithm_names() -> list[str]:
    """The names in `scanviz.visibility.ALGORITHMS` in the taxonomy's order, then any others.

    >>> algorithm_names()[:2]
    ['zbuffer', 'painter']
    """
    known = [t.name for t in TAXONOMY if t.name in ALGORITHMS]
    return known + [name for name in ALGORITHMS if name not in known]


def polygon_color(polygon: int) -> tuple[float, float, float]:
    """RGB of polygon `polygon` in every visibility widget: ``PALETTE[polygon % len(PALETTE)]``.

    >>> [round(c, 3) for c in polygon_color(9)]
    [0.0, 0.447, 0.698]
    """
    from matplotlib.colors import to_rgb

    return to_rgb(PALETTE[int(polygon) % len(PALETTE)])


def polygon_colors(ids: np.ndarray) -> np.ndarray:
    """(H, W, 3) RGB of an (H, W) buffer of polygon ids: ``polygon_color(p)``, -1 white.

    >>> polygon_colors(np.array([[-1, 0]]))[0].round(3).tolist()
    [[1.0, 1.0, 1.0], [0.0, 0.447, 0.698]]
    """
    from matplotlib.colors import to_rgb

    ids = np.asarray(ids)
    colors = np.array([to_rgb(c) for c in (*PALETTE, BACKGROUND)])
    return colors[np.where(ids >= 0, ids % len(PALETTE), len(PALETTE))]


def outline_samples(
    axes, samples: np.ndarray, color: str = DIFFERENCE, *, offset: float = 0.0
) -> int:
    """Outline the pixels where (H, W) bool `samples` is True on `axes`; return their count.

    Pixel (x, y) is the unit square from (x + offset, y + offset): 0 for
    images drawn on ``extent=(0, W, 0, H)``, -0.5 for squares centred on the
    samples.
    """
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle

    ys, xs = np.nonzero(samples)
    squares = [
        Rectangle((x + offset, y + offset), 1, 1)
        for x, y in zip(xs.tolist(), ys.tolist(), strict=True)
    ]
    axes.add_collection(PatchCollection(squares, fc="none", ec=color, lw=1.2))
    return len(xs)


def solve_traced(chosen, polygons, width: int, height: int, kinds=None, **options):
    """(result, z-buffer result): `polygons` solved by `chosen`, recording the events of `kinds`
    (None: all), and by the z-buffer, both with `options`."""
    result = solve(chosen, polygons, width, height, trace=Recorder(kinds=kinds), **options)
    return result, zbuffer(polygons, width, height, **options)


def against_zbuffer(final_axes, zbuffer_axes, ids, zbuffer_ids, *, offset: float = 0.0):
    """Draw an algorithm's final polygon `ids` and the z-buffer's, outlining where they differ.

    `ids` and `zbuffer_ids` are (H, W) arrays of int64; `offset` is as in
    `outline_samples`. Returns the (H, W) bool array of the samples that differ.
    """
    wrong = ids != zbuffer_ids
    for axes, shown in ((final_axes, ids), (zbuffer_axes, zbuffer_ids)):
        pixel_image(axes, polygon_colors(shown), offset=offset)
        outline_samples(axes, wrong, offset=offset)
    return wrong


def _label(visibility: Visibility) -> str:
    """The algorithm's name, with the options that are not its defaults."""
    changed = [
        f"{f.name}={getattr(visibility, f.name)!r}"
        for f in fields(visibility)
        if f.default is not MISSING and getattr(visibility, f.name) != f.default
    ]
    return visibility.name + (f" ({', '.join(changed)})" if changed else "")

"""The comparison of visibility algorithms and the taxonomy table, headless."""

import importlib
import re
from html.parser import HTMLParser
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from matplotlib.colors import to_rgb, to_rgba

from scanviz.visibility import ALGORITHMS, Painter, ScreenPolygons, examples
from scanviz.widgets.visibility import (
    BACKGROUND,
    PALETTE,
    TAXONOMY,
    TAXONOMY_COLUMNS,
    compare_visibility,
    taxonomy_table,
)

matplotlib.use("Agg")

NAMES = ("zbuffer", "abuffer", "painter", "depth_sort", "bsp", "scanline", "warnock")


def differ_count(axes) -> int:
    match = re.search(r"\n(\d+) differ$", axes.get_title())
    assert match, axes.get_title()
    return int(match.group(1))


def outlined(axes) -> set[tuple[int, int]]:
    """The lower-left corners of the pixels outlined in red."""
    (collection,) = axes.collections
    return {tuple(int(v) for v in path.vertices.min(axis=0)) for path in collection.get_paths()}


def test_one_panel_per_registered_algorithm_in_the_taxonomys_order():
    figure = compare_visibility(examples.slides_painter(), 16, 12)
    assert len(figure.axes) == len(ALGORITHMS)
    titles = [a.get_title().split("\n")[0] for a in figure.axes]
    assert sorted(titles) == sorted(ALGORITHMS)
    assert titles == [name for name in NAMES if name in ALGORITHMS]


def test_painter_differs_on_the_cyclic_overlap_and_the_zbuffer_does_not():
    figure = compare_visibility(examples.cyclic_overlap(), 24, 24, ["zbuffer", "painter"])
    zbuffer, painter = figure.axes
    assert differ_count(zbuffer) == 0 and outlined(zbuffer) == set()
    assert differ_count(painter) > 0
    assert len(outlined(painter)) == differ_count(painter)


def test_outlines_mark_exactly_the_pixels_painted_wrong():
    # A long rectangle sloped from z = 1 (x = 0) to z = 9 (x = 8), and a square at z = 3 over its
    # right half, where the rectangle is at z >= 5: the square is nearer on all of its samples.
    long = [(0, 0, 1), (8, 0, 9), (8, 4, 9), (0, 4, 1)]
    square = [(4, 0, 3), (8, 0, 3), (8, 4, 3), (4, 4, 3)]
    # On its nearest vertex (1 < 3) the painter paints the rectangle last, over the whole square.
    figure = compare_visibility(ScreenPolygons.from_polygons([long, square]), 8, 4, ["painter"])
    (axes,) = figure.axes
    assert outlined(axes) == {(x, y) for x in range(4, 8) for y in range(4)}
    assert differ_count(axes) == 16


def test_the_image_shows_polygons_in_the_palette_on_white():
    figure = compare_visibility(examples.slides_painter(), 16, 12, ["zbuffer"])
    image = figure.axes[0].images[0].get_array()
    # Pixel (7, 7) is in the square (polygon 2) only; pixel (0, 11) is empty.
    assert np.allclose(image[7, 7], to_rgb(PALETTE[2]))
    assert np.allclose(image[11, 0], to_rgb(BACKGROUND))
    # Pixel (3, 3): the rectangle (depth 8) over the triangle (depth 10).
    assert np.allclose(image[3, 3], to_rgb(PALETTE[1]))


def test_options_that_are_not_defaults_are_in_the_title():
    figure = compare_visibility(examples.long_behind_short(), 16, 12, [Painter(key="zmax")])
    assert figure.axes[0].get_title().startswith("painter (key='zmax')\n")


def test_bad_algorithms_are_refused():
    with pytest.raises(ValueError, match="at least one"):
        compare_visibility(examples.slides_painter(), 16, 12, [])
    with pytest.raises(ValueError, match="visibility"):
        compare_visibility(examples.slides_painter(), 16, 12, ["nope"])


class _Cells(HTMLParser):
    def __init__(self):
        super().__init__()
        self.rows, self._in_cell = [], False

    def handle_starttag(self, tag, attrs):
        if tag == "tr":
            self.rows.append([])
        self._in_cell = self._in_cell or tag in ("td", "th")

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self._in_cell = False

    def handle_data(self, data):
        if self._in_cell:
            self.rows[-1].append(data)


def table_rows() -> list[list[str]]:
    parser = _Cells()
    parser.feed(taxonomy_table())
    return parser.rows[1:]


def test_the_taxonomy_lists_every_algorithm_once():
    names = [row[1] for row in table_rows()]
    assert sorted(names) == sorted(NAMES)
    assert set(ALGORITHMS) <= set(names)


def test_the_taxonomy_names_each_registered_algorithms_module():
    modules = {t.name: t.module for t in TAXONOMY}
    for name, cls in ALGORITHMS.items():
        # The z-buffer's Visibility is a stub in the interface: it decides while it paints.
        expected = "scanviz.visibility.interface" if name == "zbuffer" else modules[name]
        assert cls.__module__ == expected, name
    assert importlib.import_module(modules["zbuffer"]).zbuffer is not None
    assert {t.module for t in TAXONOMY if t.name == "abuffer"} == {"scanviz.abuffer"}


def test_the_taxonomy_uses_the_slides_dimensions():
    rows = {row[1]: dict(zip(TAXONOMY_COLUMNS, row, strict=True)) for row in table_rows()}
    assert rows["warnock"]["sort"].startswith("subdivide to simplify")
    assert rows["zbuffer"]["sort"].startswith("sort last") and rows["zbuffer"]["space"] == "image"
    for name in ("painter", "depth_sort", "bsp"):
        assert rows[name]["sort"].startswith("sort first") and rows[name]["space"].startswith(
            "object"
        )
    assert rows["zbuffer"]["sampling"] == "point sampling"
    assert rows["abuffer"]["sampling"].startswith("continuous")
    assert rows["bsp"]["module"] == "scanviz.visibility.bsp"


def test_the_docs_page_shows_the_same_taxonomy():
    page = (Path(__file__).parents[2] / "docs" / "visibility.md").read_text()
    rows = [
        f"| {t.title} | `{t.name}` | {t.space} | {t.sort} | {t.sampling} | {t.decides} | `{t.module}` |"
        for t in TAXONOMY
    ]
    assert [line for line in page.splitlines() if line in rows] == rows


def widget_figures(polygons, width, height):
    """Each stepping widget's figure on the scene, stepped to the middle."""
    from scanviz.widgets.bsp import bsp_stepper
    from scanviz.widgets.depth_sort import depth_sort_stepper, painter_stepper
    from scanviz.widgets.scanline_visibility import scanline_visibility_stepper
    from scanviz.widgets.warnock import warnock_stepper

    steppers = (depth_sort_stepper, painter_stepper, bsp_stepper)
    steppers += (scanline_visibility_stepper, warnock_stepper)
    figures = {}
    for make in steppers:
        stepper = make(polygons, width, height)
        stepper.slider.value = stepper.slider.max // 2
        figures[make.__name__] = stepper.views[0].figure
    return figures


def zbuffer_panel(figure):
    (axes,) = [a for a in figure.axes if a.get_title().startswith("z-buffer")]
    return axes.images[0].get_array()


def is_red(rgba) -> bool:
    r, g, b, a = rgba
    return a > 0 and r > 0.6 and g < 0.35 and b < 0.35


def red_artists(figure) -> list:
    """The artists drawn in red other than outline collections (no fill, red edges)."""
    from matplotlib.collections import Collection
    from matplotlib.colors import to_rgba_array

    found = []
    for artist in figure.findobj():
        if isinstance(artist, Collection) and not artist.get_facecolor()[:, 3].any():
            continue  # an outline: the only place red may be
        for getter in ("get_facecolor", "get_edgecolor", "get_color"):
            if not hasattr(artist, getter):
                continue
            try:
                colors = to_rgba_array(getattr(artist, getter)())
            except (TypeError, ValueError):
                continue
            if any(is_red(c) for c in colors):
                found.append((type(artist).__name__, getter))
    return found


def test_a_polygon_has_the_same_color_in_every_widget():
    polygons = examples.slides_painter()
    reference = compare_visibility(polygons, 16, 12, ["zbuffer"]).axes[0].images[0].get_array()
    # The square (polygon 2) at pixel (7, 7), the rectangle (polygon 1) over the triangle at (3, 3).
    assert np.allclose(reference[7, 7], to_rgb(PALETTE[2]))
    assert np.allclose(reference[3, 3], to_rgb(PALETTE[1]))
    for name, figure in widget_figures(polygons, 16, 12).items():
        np.testing.assert_allclose(zbuffer_panel(figure), reference, err_msg=name)


def test_the_widgets_use_red_only_for_the_outlines_of_differences():
    assert not any(is_red(to_rgba(c)) for c in PALETTE)
    for name, figure in widget_figures(examples.long_behind_short(), 16, 12).items():
        assert red_artists(figure) == [], name


def test_split_pieces_shows_each_sample_covered_once():
    from scanviz.widgets.visibility import split_pieces

    figure = split_pieces(examples.interpenetrating(), 16, 12, "bsp")
    left, right = figure.axes[:2]
    assert left.get_title() == "bsp: the 2 pieces of polygon 1"
    assert right.get_title() == "polygon 1: 96 of 96 samples covered once"
    assert sorted(text.get_text() for text in left.texts) == ["1a", "1b"]


def test_split_pieces_says_when_nothing_was_split():
    from scanviz.widgets.visibility import split_pieces

    with pytest.raises(ValueError, match="bsp split no polygon of this scene"):
        split_pieces(examples.slides_painter(), 16, 12, "bsp")

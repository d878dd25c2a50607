"""What the check shows: differing events as tables, the raster diff on its pixel grid, no repr."""

import re

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import to_rgb

from scanviz.exercises import check, get
from scanviz.exercises.compare import RasterDifference
from scanviz.exercises.display import (
    EXTRA,
    MATCHED,
    MISSING_COLOR,
    comparison_html,
    raster_figure,
)
from scanviz.trace import Span

REFERENCE = np.array(
    [[1, 1, 1, 1, 0],
     [0, 1, 1, 1, 0],
     [0, 0, 1, 1, 0],
     [0, 0, 0, 0, 0]], dtype=bool)  # fmt: skip  # row 0 at the bottom
YOURS = np.array(
    [[1, 1, 1, 1, 1],
     [1, 1, 1, 1, 0],
     [0, 0, 0, 1, 0],
     [0, 0, 0, 0, 0]], dtype=bool)  # fmt: skip
EXTRA_PIXELS = {(4, 0), (0, 1)}  # (x, y): yours only, read off the arrays above
MISSING_PIXELS = {(2, 2)}  # the reference's only


def _colour_at_pixels(figure, width: int, height: int) -> dict[tuple[int, int], str]:
    """The colour drawn in each pixel's square (sampled off its centre, clear of glyph and dot)."""
    canvas = FigureCanvasAgg(figure)
    canvas.draw()
    image = np.asarray(canvas.buffer_rgba())[:, :, :3] / 255
    axes = figure.axes[0]
    names = {"empty": to_rgb("white"), "matched": to_rgb(MATCHED), "extra": to_rgb(EXTRA),
             "missing": to_rgb(MISSING_COLOR)}  # fmt: skip
    found = {}
    for y in range(height):
        for x in range(width):
            px, py = axes.transData.transform((x + 0.8, y + 0.25))
            colour = image[image.shape[0] - 1 - int(round(py)), int(round(px))]
            found[(x, y)] = min(names, key=lambda n: np.abs(np.array(names[n]) - colour).sum())
    return found


def test_the_raster_diff_marks_exactly_the_differing_pixels():
    figure = raster_figure(RasterDifference(YOURS, REFERENCE))
    drawn = _colour_at_pixels(figure, 5, 4)
    assert {p for p, c in drawn.items() if c == "extra"} == EXTRA_PIXELS
    assert {p for p, c in drawn.items() if c == "missing"} == MISSING_PIXELS
    matched = {(x, y) for y in range(4) for x in range(5) if YOURS[y, x] and REFERENCE[y, x]}
    assert {p for p, c in drawn.items() if c == "matched"} == matched
    legend = [t.get_text() for t in figure.legends[0].get_texts()]
    assert legend == ["matched: 8", "extra (yours only): 2", "missing (reference only): 1"]


def test_the_raster_diff_draws_the_outline_on_a_readable_grid():
    triangle = [[0, 0], [6, 0], [6, 5]]
    small = raster_figure(RasterDifference(YOURS, REFERENCE), {"polygon": triangle})
    outline = [line for line in small.axes[0].lines if line.get_gid() == "outline"]
    assert len(outline) == 1
    assert np.array_equal(outline[0].get_xydata(), [[0, 0], [6, 0], [6, 5], [0, 0]])
    assert small.get_figwidth() * 100 / 5 >= 40  # >= 40 screen px a pixel at 100 dpi
    large = raster_figure(RasterDifference(np.zeros((40, 64), bool), np.ones((40, 64), bool)))
    assert large.get_figwidth() <= 8.0


def test_a_comparison_highlights_the_differing_fields_only():
    page = comparison_html(Span(0, 1, 1, 6, 1), Span(0, 1, 2, 6, 1))
    rows = dict(re.findall(r"<th[^>]*>(\w+)(?: ✗)?</th>(.*?)</tr>", page))
    highlighted = {name for name, cells in rows.items() if "#ffe0b2" in cells}
    assert highlighted == {"x_start"}
    assert "Span(" not in page


def _no_repr(page: str) -> None:
    for raw in ("AetEntry(", "AetItem(", "FragmentRecord(", "Opaque(", "{'image'", "PackStep(",
                "Fraction("):  # fmt: skip
        assert raw not in page, raw


def test_a_wrong_answer_shows_tables_a_raster_and_the_cause():
    exercise = get("span_rule")
    floor = next(v for v in exercise.variants if v.name == "floor_for_ceil")
    page = check("span_rule", case="triangle", source=floor.source)._repr_html_()
    _no_repr(page)
    assert "first difference at event 4 of 10" in page and "likely cause:" in page
    assert page.count("data:image/png;base64,") == 1
    assert "extra (yours only)" in page  # the raster's alternative text says what it shows


def test_the_stubs_show_no_raw_record_or_dict():
    for exercise_id in ("aet_update", "abuffer_insert", "pixel_pack"):
        report = check(exercise_id, case=get(exercise_id).public[0].label,
                       source=get(exercise_id).stub)  # fmt: skip
        page = report._repr_html_()
        _no_repr(page)
        assert "NotImplementedError" in page and "hidden cases are graded later" in page


def test_raster_png_draws_each_difference_once_and_keeps_them_apart():
    from scanviz.exercises import display
    from scanviz.exercises.compare import RasterDifference

    def difference(k):
        yours = np.zeros((6, 6), bool)
        yours[k, :] = True
        return RasterDifference(yours, np.ones((6, 6), bool))

    display._PNG_CACHE.clear()
    first = display.raster_png(difference(1), {"width": 6})
    assert len(display._PNG_CACHE) == 1
    assert display.raster_png(difference(1), {"width": 6}) == first  # an equal copy: the cache
    assert len(display._PNG_CACHE) == 1
    other = display.raster_png(difference(2), {"width": 6})
    assert other != first and len(display._PNG_CACHE) == 2
    assert other[:8] == b"\x89PNG\r\n\x1a\n"

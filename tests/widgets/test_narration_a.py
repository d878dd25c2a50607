"""Steppers narrate each step, panes follow the step, outputs fit, sample dots show the sampling.

Expected sentences and numbers come from the trace's own events or from the
polygon worked by hand (the UMBC slide polygon), never from the narration code.
"""

import html
import re

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text

from scanviz import Recorder, render, scan_convert
from scanviz.raster import ColourWash, Pattern, Solid
from scanviz.scene.builtin import builtin_scene
from scanviz.trace.table import format_number
from scanviz.widgets import (
    ABufferInspector,
    PolygonEditor,
    ScanConversionView,
    fill_stepper,
    interpolation_stepper,
    line_stepper,
    plot_scan,
    relight_widget,
    sampling_view,
    scan_conversion_stepper,
    zbuffer_stepper,
)
from scanviz.widgets._common import WIDEST
from scanviz.widgets.abuffer import FragmentInsertionView, PackerView
from scanviz.widgets.stepper import DOTS_LIMIT

matplotlib.use("Agg")

UMBC = [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)]


def index_of(trace, kind, **fields):
    """The step right after the first event of `kind` whose fields match."""
    return 1 + next(
        i
        for i, e in enumerate(trace)
        if e.kind == kind and all(getattr(e, k) == v for k, v in fields.items())
    )


@pytest.fixture(scope="module")
def umbc():
    return scan_conversion_stepper(UMBC, 14, 13)


@pytest.fixture(scope="module")
def zbuffer():
    return zbuffer_stepper(builtin_scene("umbc_zbuffer"), 12, 12)


# --- scan conversion ---------------------------------------------------------------------


def test_scan_span_sentence_names_the_row_pixels_and_crossings(umbc):
    view = umbc.views[0]
    # Row 6 of the slide polygon, by hand: e0 (4,1)-(1,11) crosses at 4 - 3 * 5/10 = 2 1/2,
    # e1 (9,5)-(1,11) at 9 - 8/6 = 7 2/3; the samples 3..7 lie between them.
    sentence = view.narrate(index_of(view.trace, "span", y=6, x_start=3))
    assert sentence.startswith("Row y = 6: pixels 3 ≤ x < 8 are filled")
    assert "x = 3 … 7" in sentence
    assert "2 1/2 (e0) and 7 2/3 (e1)" in sentence


def test_scan_retire_sentence_says_ymax_was_reached(umbc):
    view = umbc.views[0]
    sentence = view.narrate(index_of(view.trace, "edges_retired", y=8))
    assert sentence.startswith("Row y = 8:")
    assert "e2 (9,5)→(12,8)" in sentence and "e3 (12,1)→(12,8)" in sentence
    assert "leave the AET" in sentence and "ymax 8" in sentence


def test_scan_every_row_event_is_narrated_with_its_row_and_values(umbc):
    view = umbc.views[0]
    assert "start" in view.narrate(0).lower()
    for step, event in enumerate(view.trace, 1):
        sentence = view.narrate(step)
        assert sentence.endswith(".") and "_" not in sentence, sentence
        if hasattr(event, "y"):
            assert sentence.startswith(f"Row y = {event.y}:"), sentence
        if event.kind == "aet_sorted":
            for entry in event.entries:
                assert f"e{entry.edge} at {format_number(entry.x, entry.x_exact)}" in sentence
        if event.kind in ("edges_activated", "edges_retired"):
            assert all(f"e{edge} " in sentence for edge in event.edges)


def test_scan_narration_uses_the_sample_rows_of_center_sampling():
    view = scan_conversion_stepper(UMBC, 14, 13, sample="center").views[0]
    sentence = view.narrate(index_of(view.trace, "edges_activated", y=1))
    assert "samples (y = 1.5)" in sentence
    # Row 1's samples at y = 1.5: e0 crosses at 4 - 3 * 0.5/10 = 3.85 = 3 17/20.
    assert "3 17/20 (e0)" in view.narrate(index_of(view.trace, "span", y=1))


def test_the_stepper_shows_the_views_sentence(umbc):
    view = umbc.views[0]
    for step in (0, 4, len(view.trace)):
        umbc.slider.value = step
        assert html.escape(view.narrate(step)) in umbc.narration.value


def test_scan_aet_pane_is_the_current_rows(umbc):
    view = umbc.views[0]
    for step, event in enumerate(view.trace, 1):
        if event.kind == "aet_sorted":
            umbc.slider.value = step
            assert f"AET of row {event.y}</b>" in view.aet_html.value
            assert view.title.get_text() == f"step {step}, row {event.y}"


@pytest.mark.parametrize("sample", ["corner", "center"])
def test_scan_sample_dots_are_the_covered_samples(sample):
    trace = scan_convert(UMBC, 14, 13, sample=sample, trace=True).trace
    view = ScanConversionView(UMBC, 14, 13, trace, sample=sample)
    offset = 0.5 if sample == "center" else 0.0
    step = index_of(trace, "span", y=6)
    view.show(step)
    covered = trace.image_at(step, 14, 13) > 0
    inside = set(zip(*view.samples.inside.get_data(), strict=True))
    outside = set(zip(*view.samples.outside.get_data(), strict=True))
    ys, xs = np.nonzero(covered)
    assert inside == {(x + offset, y + offset) for x, y in zip(xs, ys, strict=True)}
    assert len(inside) + len(outside) == 14 * 13 and not inside & outside


def test_the_wide_edge_table_scrolls(umbc):
    umbc.slider.value = 12
    pane = umbc.views[0].et_html.value
    assert "overflow-x:auto" in pane and "scroll →" in pane


# --- midpoint line -----------------------------------------------------------------------


def test_line_sentences_follow_the_slides_decisions():
    stepper = line_stepper(0, 0, 5, 2)
    view = stepper.views[0]
    assert "octant 0" in view.narrate(1) and "starts at 1" in view.narrate(1)
    # The slides' line (0,0)-(5,2): d = 1, -3, 3, -1, 5 and the pixels (0,0) (1,0) (2,1) (3,1) (4,2).
    pixels = [(0, 0), (1, 0), (2, 1), (3, 1), (4, 2), (5, 2)]
    ds = [1, -3, 3, -1, 5, 1]
    for k in range(5):
        sentence = view.narrate(k + 2)
        assert sentence.startswith(f"Pixel {pixels[k]} is drawn")
        assert f"d = {ds[k]} " in sentence
        choice = "diagonal" if ds[k] < 0 else "axial"
        assert f"the step is {choice} to {pixels[k + 1]}" in sentence
        assert sentence.endswith(f"to {ds[k + 1]}.")
    # The first midpoint, by hand: between (1, 0) and (1, 1).
    assert "midpoint (1, 0.5)" in view.narrate(2)
    assert "end point" in view.narrate(7)


def test_line_tie_is_said_to_be_a_tie():
    view = line_stepper(0, 0, 4, 2).views[0]  # d = 0 at the first midpoint (1, 0.5), on the line
    assert "d = 0" in view.narrate(2) and "tie" in view.narrate(2)


# --- z-buffer ----------------------------------------------------------------------------


def test_zbuffer_sentence_compares_the_event_depths(zbuffer):
    view, trace = zbuffer.views[0], zbuffer.model.trace
    assert "+∞" in view.narrate(0)
    for step, event in enumerate(trace, 1):
        sentence = view.narrate(step)
        assert sentence.startswith(f"Depth test at pixel ({event.x}, {event.y}):")
        assert ("is written" in sentence) == event.passed
        numbers = [float(n) for n in re.findall(r"z = ([-0-9.e]+)", sentence)]
        assert numbers and abs(numbers[0] - event.z) <= 0.05 * abs(event.z)
        if event.stored is None:
            assert "nothing is stored" in sentence
        else:
            stored = float(re.search(r"([-0-9.e]+) stored", sentence).group(1))
            assert abs(stored - event.stored) <= 0.05 * abs(event.stored)


def test_zbuffer_history_follows_the_tested_pixel_until_one_is_picked(zbuffer):
    view, trace = zbuffer.views[0], zbuffer.model.trace
    view.follow.value = True
    for step in (1, 16, 30, 53):
        zbuffer.slider.value = step
        event = trace[step - 1]
        assert view.pixel == (event.x, event.y)
        assert view.pixel_marker.get_xy() == (event.x, event.y)
        assert view.history.value.startswith(f"<b>pixel ({event.x}, {event.y})</b>")
        assert "this step tests" in view.history.value
    view.pick(9, 6)
    zbuffer.slider.value = 16
    event = trace[15]
    assert view.pixel == (9, 6) and not view.follow.value
    assert "picked by you" in view.history.value
    assert f"this step tests ({event.x}, {event.y})" in view.history.value
    view.follow.value = True
    assert view.pixel == (event.x, event.y)


# --- interpolation and fills -------------------------------------------------------------


def test_interpolation_sentences_name_the_row_and_span():
    stepper = interpolation_stepper("umbc_zbuffer")
    view, trace = stepper.views[0], stepper.model.trace
    for step, event in enumerate(trace, 1):
        sentence = view.narrate(step)
        if event.kind == "polygon_setup":
            assert sentence.startswith(f"Polygon {event.polygon} is set up")
        elif event.kind == "span_values":
            assert sentence.startswith(
                f"Row y = {event.y}: span {event.x_start} ≤ x < {event.x_end}"
            )
        else:
            assert sentence.startswith(f"Row y = {event.y}:")
            assert all(f"e{e.edge} at x = " in sentence for e in event.entries)


@pytest.mark.parametrize("fill", [Solid((1.0, 0.5, 0.0)), Pattern.checker(), ColourWash()])
def test_fill_span_sentences(fill):
    stepper = fill_stepper([(1.25, 1.5), (14.5, 3.0), (6.0, 12.75)], 16, 14, fill)
    view = stepper.views[0]
    kind = "span_values" if isinstance(fill, ColourWash) else "span"
    step = index_of(view.trace, kind, y=5)
    event = view.trace[step - 1]
    sentence = view.narrate(step)
    assert sentence.startswith("Row y = 5: ")
    assert f"{event.x_start} ≤ x < {event.x_end}" in sentence
    if isinstance(fill, Solid):
        assert "colour (1, 0.5, 0)" in sentence
    elif isinstance(fill, Pattern):
        assert "tile pixel" in sentence
    else:
        assert "C (" in sentence and "per pixel" in sentence


# --- a-buffer ----------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cube():
    return render(
        builtin_scene("transparent_cube"),
        48,
        48,
        shading="flat",
        visibility="abuffer",
        trace=Recorder(region=(22, 22, 25, 25)),
    )


def test_packer_and_insertion_sentences_name_their_pixel(cube):
    packed = cube.trace.of_kind("pixel_packed")
    view = PackerView(packed)
    for step, event in enumerate(packed, 1):
        sentence = view.narrate(step)
        assert sentence.startswith(f"Pixel ({event.x}, {event.y}) is packed")
        assert f"alpha {event.alpha:.3g}" in sentence
    inserted = cube.trace.of_kind("fragment_inserted")
    view = FragmentInsertionView(inserted, "8x8")
    for step, event in enumerate(inserted, 1):
        sentence = view.narrate(step)
        assert f"pixel ({event.x}, {event.y})" in sentence
        assert ("complete" in sentence) == event.case.startswith("complete")
        bits = bin(event.fragment.mask).count("1")
        assert event.case.startswith("complete") or f"({bits} of 64 sub-samples" in sentence


# --- sampling ----------------------------------------------------------------------------

# A convex polygon, counter-clockwise, none of whose edges passes through a corner or
# centre sample of the raster (checked below), so the fill rule for ties plays no part.
CONVEX = [(1.3, 1.2), (8.6, 2.3), (7.8, 6.9), (4.4, 7.7), (1.7, 5.3)]


def inside_convex(vertices, xs, ys):
    """Point in a counter-clockwise convex polygon (left of every edge), and distance to the outline."""
    v = np.asarray(vertices, float)
    inside = np.ones(xs.shape, bool)
    nearest = np.full(xs.shape, np.inf)
    for (ax, ay), (bx, by) in zip(v, np.roll(v, -1, axis=0), strict=True):
        dx, dy = bx - ax, by - ay
        inside &= dx * (ys - ay) - dy * (xs - ax) > 0
        t = np.clip(((xs - ax) * dx + (ys - ay) * dy) / (dx * dx + dy * dy), 0, 1)
        nearest = np.minimum(nearest, np.hypot(xs - ax - t * dx, ys - ay - t * dy))
    return inside, nearest


@pytest.mark.parametrize("sample", ["corner", "center"])
def test_sampling_view_dots_are_the_samples_inside_the_polygon(sample):
    width, height = 10, 9
    view = sampling_view(CONVEX, width, height)
    view.toggle.value = sample
    offset = 0.5 if sample == "center" else 0.0
    ys, xs = np.mgrid[0:height, 0:width].astype(float)
    inside, nearest = inside_convex(CONVEX, xs + offset, ys + offset)
    assert nearest.min() > 0.01  # no sample on an edge, even after snapping to 1/256 pixel
    np.testing.assert_array_equal(view.coverage.get_array(), inside)
    np.testing.assert_array_equal(
        view.results[sample].mask, scan_convert(CONVEX, width, height, sample=sample).mask
    )
    dots = set(zip(*view.samples.inside.get_data(), strict=True))
    assert dots == {(x + offset, y + offset) for x, y in zip(xs[inside], ys[inside], strict=True)}
    hollow = set(zip(*view.samples.outside.get_data(), strict=True))
    assert hollow == {
        (x + offset, y + offset) for x, y in zip(xs[~inside], ys[~inside], strict=True)
    }


def test_sampling_toggle_redraws_in_place_and_says_what_moved():
    view = sampling_view(CONVEX, 10, 9)
    figure, image = view.figure, view.coverage
    corner, center = view.results["corner"].mask, view.results["center"].mask
    joined, left = int((center & ~corner).sum()), int((corner & ~center).sum())
    assert joined and left  # this polygon's fill changes both ways
    view.toggle.value = "center"
    assert view.figure is figure and view.coverage is image
    assert (
        "Center sampling" in view.explanation.value and "(x + ½, y + ½)" in view.explanation.value
    )
    assert f"{joined} pixels are filled only here" in view.explanation.value
    assert f"{left} pixels only there" in view.explanation.value
    assert len(view.only_here.get_paths()) == joined and len(view.only_there.get_paths()) == left
    view.toggle.value = "corner"
    assert "lower-left corner (x, y)" in view.explanation.value


def test_editor_and_plot_scan_draw_sample_dots():
    editor = PolygonEditor([(0, 0), (4, 0), (4, 3)], 6, 5, sample="center")
    editor.text.value = "1,1 5,1 5,4 1,4"
    xs, ys = editor.samples.inside.get_data()
    assert sorted(zip(xs, ys, strict=True)) == [
        (x + 0.5, y + 0.5) for x in range(1, 5) for y in range(1, 4)
    ]
    result = scan_convert(UMBC, 14, 13)
    ax = plot_scan(UMBC, result)
    filled = [line for line in ax.lines if line.get_marker() == "o" and line.get_mfc() != "none"]
    (dots,) = filled
    assert len(dots.get_xdata()) == int(result.mask.sum())
    plt.close(ax.figure)
    big = scan_convert(np.array(UMBC) * 6, DOTS_LIMIT + 20, 80)
    ax = plot_scan(np.array(UMBC) * 6, big)
    assert not [line for line in ax.lines if line.get_marker() == "o"]  # too small to see
    plt.close(ax.figure)


# --- every output fits ------------------------------------------------------------------


def figures_of_the_widgets(cube):
    """(name, figure) of every figure the widgets of this helper's modules make."""
    long_line = line_stepper(0, 0, 120, 17).views[0]
    steep = line_stepper(2, 1, 6, 40).views[0]
    big = np.array(UMBC) * 8
    yield "scan", scan_conversion_stepper(UMBC, 14, 13).views[0].figure
    yield (
        "scan big",
        ScanConversionView(big, 110, 100, scan_convert(big, 110, 100, trace=True).trace).figure,
    )
    yield "line", long_line.figure
    yield "steep line", steep.figure
    yield "zbuffer", zbuffer_stepper(builtin_scene("umbc_zbuffer"), 12, 12).views[0].figure
    yield "interpolation", interpolation_stepper("umbc_zbuffer").views[0].figure
    yield "fill", fill_stepper(UMBC, 14, 13, ColourWash()).views[0].figure
    yield "editor", PolygonEditor(big, 110, 100).figure
    inspector = ABufferInspector(cube)
    yield "a-buffer", inspector.figure
    yield "a-buffer masks", inspector.grid_figure
    yield "sampling", sampling_view(big, 110, 100).figure
    yield "relight", relight_widget(render(builtin_scene("sphere"), 24, 24, shading="phong")).figure
    ax = plot_scan(big, scan_convert(big, 110, 100))
    yield "plot_scan", ax.figure
    plt.close(ax.figure)


def overlapping(boxes):
    return any(a.overlaps(b) for a, b in zip(boxes, boxes[1:], strict=False))


def test_every_figure_fits_a_notebook_and_reads(cube):
    for name, figure in figures_of_the_widgets(cube):
        assert figure.get_figwidth() <= WIDEST + 1e-9, name
        canvas = FigureCanvasAgg(figure)  # the widgets hand their figures to a widget
        canvas.draw()
        renderer = canvas.get_renderer()
        for text in figure.findobj(Text):
            if text.get_visible() and text.get_text():
                assert text.get_fontsize() >= 9, (name, text.get_text(), text.get_fontsize())
        for ax in figure.axes:
            for labels in (ax.get_xticklabels(), ax.get_yticklabels()):
                shown = [t.get_window_extent(renderer) for t in labels if t.get_text()]
                assert not overlapping(shown), (name, [t.get_text() for t in labels])

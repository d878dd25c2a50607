"""ScanConversionView, headless: step the UMBC slide polygon and check what the view holds."""

import re

import matplotlib
import numpy as np
import pytest

from scanviz import Recorder, scan_convert
from scanviz.catalog import SHAPES, get
from scanviz.widgets import ScanConversionView, redraw_time, scan_conversion_stepper

matplotlib.use("Agg")

UMBC = [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)]


@pytest.fixture(scope="module")
def stepper():
    return scan_conversion_stepper(UMBC, 14, 13)


@pytest.fixture
def view(stepper):
    stepper.slider.value = 0
    return stepper.views[0]


def step_of(trace, kind, y):
    """The step right after the event of `kind` on row `y`."""
    return 1 + next(i for i, e in enumerate(trace) if e.kind == kind and e.y == y)


def aet_rows(view):
    """(edge id, change, highlighted) of each row of the AET table."""
    body = view.aet_html.value.split("<tbody>")[1]
    rows = re.findall(r"<tr style='([^']*)'>(.*?)</tr>", body)
    cells = [re.findall(r">([^<]*)</td>", row) for _, row in rows]
    return [(int(c[0][1:]), c[5], bool(style)) for (style, _), c in zip(rows, cells, strict=True)]


def test_aet_shows_exact_fractions_at_row_2(stepper, view):
    assert "3 7/10" not in view.aet_html.value
    stepper.slider.value = step_of(view.trace, "aet_sorted", 2)
    assert "AET of row 2" in view.aet_html.value
    assert "3 7/10" in view.aet_html.value and "-3/10" in view.aet_html.value
    stepper.next_button.click()  # the span of row 2: the same AET, nothing changed
    assert "3 7/10" in view.aet_html.value and view.highlights == {}


def test_scanline_follows_the_current_row(stepper, view):
    assert not view.scanline.get_visible()
    rows = []
    for step, event in enumerate(view.trace, 1):
        stepper.slider.value = step
        rows.append(getattr(event, "y", rows[-1] if rows else None))
        assert view.scanline.get_visible() == (rows[-1] is not None)
        if rows[-1] is not None:
            assert list(view.scanline.get_ydata()) == [rows[-1], rows[-1]]
    assert rows[-1] == 11


def test_image_so_far_is_the_trace_image(stepper, view):
    for step in range(len(view.trace) + 1):
        stepper.slider.value = step
        expected = view.trace.image_at(step, 14, 13)
        np.testing.assert_array_equal(view.image.get_array(), expected)
    np.testing.assert_array_equal(view.image.get_array() > 0, scan_convert(UMBC, 14, 13).mask)


def test_current_span_is_outlined(stepper, view):
    step = step_of(view.trace, "span", 6)
    stepper.slider.value = step
    span = view.trace[step - 1]
    assert view.span.get_visible()
    assert view.span.get_bbox().bounds == (span.x_start, 6, span.x_end - span.x_start, 1)
    stepper.prev_button.click()
    assert stepper.model.step == step - 1


@pytest.mark.parametrize(
    ("kind", "y", "changes"),
    [
        ("aet_sorted", 1, {0: "entering", 3: "entering"}),
        ("aet_sorted", 2, {0: "x changed"}),  # e3 is vertical: its x stays 12
        ("aet_sorted", 5, {0: "x changed", 1: "entering", 2: "entering"}),
        ("edges_retired", 8, {2: "retiring", 3: "retiring"}),
        ("edges_retired", 11, {0: "retiring", 1: "retiring"}),
    ],
)
def test_highlighted_entries_are_the_changed_ones(stepper, view, kind, y, changes):
    stepper.slider.value = step_of(view.trace, kind, y)
    assert view.highlights == changes
    highlighted = {edge: change for edge, change, lit in aet_rows(view) if lit}
    assert highlighted == changes
    assert all(change == "" for _, change, lit in aet_rows(view) if not lit)


def test_edge_table_marks_entering_edges_and_topology(stepper, view):
    assert "not built yet" in view.et_html.value
    stepper.slider.value = step_of(view.trace, "edges_activated", 5)
    assert view.et_html.value.count("background") == 2
    assert "horizontal: crosses no row, never active" in view.et_html.value
    assert "before the update for row 5" in view.aet_html.value


@pytest.mark.parametrize("name", ["pentagram", "bow_tie", "vertices_on_samples"])
def test_an_edge_moves_exactly_when_the_sort_swaps(name):
    shape = get(name)
    trace = scan_convert(shape.polygon, shape.width, shape.height, trace=True).trace
    view = ScanConversionView(shape.polygon, shape.width, shape.height, trace)
    moves = 0
    for step, event in enumerate(trace, 1):
        if event.kind == "aet_sorted":
            view.show(step)
            if "entering" not in view.highlights.values():
                moved = "moved" in view.highlights.values()
                assert moved == (event.swaps > 0), step
                moves += moved
    assert moves  # each of these shapes has a row where edges cross


def test_active_edges_are_drawn(stepper, view):
    stepper.slider.value = step_of(view.trace, "aet_sorted", 5)
    assert len(view.active_edges.get_segments()) == 4


def test_center_sampling_moves_scanline_and_filters_pass_through():
    stepper = scan_conversion_stepper(UMBC, 14, 13, sample="center", trace=Recorder(rows=(5, 8)))
    view = stepper.views[0]
    assert {getattr(e, "y", 5) for e in view.trace} == {5, 6, 7}
    stepper.slider.value = 3
    assert list(view.scanline.get_ydata()) == [5.5, 5.5]


def test_a_tracer_that_records_nothing_is_refused():
    class Silent:
        def wants(self, kind, **where):
            return False

        def emit(self, event):
            pass

    with pytest.raises(ValueError, match="'trace'"):
        scan_conversion_stepper(UMBC, 14, 13, trace=Silent())


def test_large_rasters_skip_per_pixel_detail():
    big = np.array(UMBC) * 20
    view = ScanConversionView(big, 260, 240, scan_convert(big, 260, 240, trace=True).trace)
    assert view.samples is None


def test_redraw_time_with_a_real_view(stepper):
    assert redraw_time(stepper, steps=3) > 0


def test_catalog_shapes_all_step_to_the_end():
    for name, shape in SHAPES.items():
        if shape.width * shape.height > 64 * 64:
            continue
        stepper = scan_conversion_stepper(shape.polygon, shape.width, shape.height)
        stepper.slider.value = len(stepper.model)
        final = stepper.views[0].image.get_array() > 0
        mask = scan_convert(shape.polygon, shape.width, shape.height).mask
        np.testing.assert_array_equal(final, mask, err_msg=name)

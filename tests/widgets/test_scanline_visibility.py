"""The scanline visibility stepper, headless: move the slider, check what the view now shows."""

import matplotlib
import numpy as np
import pytest

from scanviz.visibility import ScreenPolygons, examples, zbuffer
from scanviz.widgets.scanline_visibility import (
    BAND_COLORS,
    ScanlineVisibilityView,
    scanline_visibility_stepper,
)
from scanviz.widgets.visibility import polygon_colors

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def stepper():
    return scanline_visibility_stepper(examples.interpenetrating(), 16, 12)


def row_spans(trace, y):
    return [(i, e) for i, e in enumerate(trace) if e.kind == "visible_span" and e.y == y]


def test_at_the_start_nothing_is_decided(stepper):
    stepper.slider.value = 0
    view = stepper.views[0]
    assert isinstance(view, ScanlineVisibilityView) and view.row is None
    assert "no scanline yet" in view.ast.value
    assert (view.decided(0) == -1).all() and not view.visible_lines.get_segments()


def test_the_last_step_shows_the_final_image_and_the_zbuffers(stepper):
    view = stepper.views[0]
    stepper.slider.value = stepper.slider.max
    reference = zbuffer(examples.interpenetrating(), 16, 12).polygon
    assert np.array_equal(view.decided(stepper.slider.max), view.result.polygon)
    np.testing.assert_array_equal(view.decided_image.get_array(), polygon_colors(reference))
    final, shown_zbuffer = (ax.images[0].get_array() for ax in view.axes[2:])
    np.testing.assert_array_equal(shown_zbuffer, polygon_colors(reference))
    np.testing.assert_array_equal(final, polygon_colors(view.result.polygon))


def test_mid_row_the_slice_shows_the_rows_surfaces_and_the_spans_so_far(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    here = row_spans(trace, 5)
    split = next(k for k, (_, e) in enumerate(here) if e.split_at is not None)
    stepper.slider.value = here[split][0] + 1  # just after the span split at the crossing
    assert view.row == 5
    assert len(view.surface_lines.get_segments()) == sum(len(e.surfaces) for _, e in here)
    done = [e for _, e in here[: split + 1]]
    assert len(view.bands.get_paths()) == len(done)
    assert len(view.visible_lines.get_segments()) == sum(e.visible >= 0 for e in done)
    (line,) = view.splits.get_segments()
    assert line[0][0] == pytest.approx(here[split][1].split_at)
    assert view.current_band.get_visible() and view.current_band.get_x() == here[split][1].x_start
    # the visible piece's segment starts at the recorded depth of its surface
    piece = here[split][1]
    first = view.visible_lines.get_segments()[-1][0]
    assert tuple(first) == (piece.x_start, piece.depths[piece.surfaces.index(piece.visible)])
    # rows below are decided, the rest of this row not yet
    decided = view.decided(stepper.slider.value)
    assert np.array_equal(decided[:5], view.result.polygon[:5])
    assert (decided[5, piece.x_end :] == -1).all() and (decided[6:] == -1).all()
    assert view.spans.value.count("<tr") - 1 == len(here)
    assert view.spans.value.count("background:#ffe9a8") == 1  # the current span highlighted


def test_the_tables_show_the_ast_and_the_sst(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    rows = [(i, e) for i, e in enumerate(trace) if e.kind == "active_surfaces"]
    index, row = rows[3]
    stepper.slider.value = index + 1
    assert f"row y = {row.y}" in view.ast.value and str(row.active) in view.ast.value
    assert view.sst.value.count("<tr") - 1 == len(trace[0].surfaces)


def test_reused_spans_are_marked():
    flat = [(2, 1, 0.5), (14, 1, 0.5), (14, 11, 0.5), (2, 11, 0.5)]
    tilted = [(2, 1, 0.3), (14, 1, 0.3), (14, 11, 0.7), (2, 11, 0.7)]
    stepper = scanline_visibility_stepper(ScreenPolygons.from_polygons([flat, tilted]), 16, 12)
    view, trace = stepper.views[0], stepper.model.trace
    reused = next(i for i, e in enumerate(trace) if e.kind == "visible_span" and e.reused)
    stepper.slider.value = reused + 1
    colors = [tuple(c) for c in view.bands.get_facecolors()]
    assert tuple(BAND_COLORS["reused"]) in colors
    assert "yes" in view.spans.value
    off = scanline_visibility_stepper(
        ScreenPolygons.from_polygons([flat, tilted]), 16, 12, coherence=False
    )
    assert not any(e.reused for e in off.model.trace if e.kind == "visible_span")

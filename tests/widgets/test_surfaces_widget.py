"""The grid-surface views, headless: built from real traces, stepped, checked against the results."""

import io

import matplotlib
import numpy as np
import pytest
from matplotlib.colors import to_rgba

from scanviz.surfaces import (
    View,
    compare_with_zbuffer,
    floating_horizon,
    floating_perimeter,
    gaussian,
    polynomial,
    random_surface,
)
from scanviz.trace import Recorder
from scanviz.widgets._common import WIDEST
from scanviz.widgets.perimeter import HIDDEN, VISIBLE
from scanviz.widgets.stepper import Stepper
from scanviz.widgets.surface_grid import CURRENT
from scanviz.widgets.surfaces import (
    HOLE,
    STRUCTURAL,
    HorizonView,
    PerimeterView,
    horizon_stepper,
    perimeter_stepper,
    plot_grid,
    plot_mismatch,
    plot_results,
)

matplotlib.use("Agg")

SURFACE = random_surface(5, 55)
VIEW = View((3.2, -5.7, 1.4), (-3.2, 5.7, -0.9))  # case 8; the FPA leaves holes here at 48 x 48
SIZE = 48
PARALLEL = View((0, 0, 9), (1, 0.5, -1), projection="parallel")


@pytest.fixture(scope="module")
def stepper():
    return perimeter_stepper(SURFACE, VIEW, SIZE, SIZE)


@pytest.fixture(scope="module")
def horizon():
    return horizon_stepper(SURFACE, VIEW, SIZE, SIZE)


def merged(events, width, height):
    """The perimeter by merging the visible points of every edge event (Fig. 2-4(b)), independently.

    Returns the four arrays and the columns and rows some visible point reached.
    """
    top, bottom = np.zeros(width, np.int64), np.full(width, height, np.int64)
    right, left = np.zeros(height, np.int64), np.full(height, width, np.int64)
    columns, rows = np.zeros(width, bool), np.zeros(height, bool)
    for event in events:
        for (x, y), visible in zip(event.points, event.visible, strict=True):
            if visible and 0 <= x < width and 0 <= y < height:
                top[x], bottom[x] = max(top[x], y), min(bottom[x], y)
                right[y], left[y] = max(right[y], x), min(left[y], x)
                columns[x] = rows[y] = True
    arrays = {"top": top, "bottom": bottom, "right": right, "left": left}
    return arrays, {"columns": columns, "rows": rows}


def test_one_step_per_facet_start_edge_and_update(stepper):
    result = stepper.views[0].result
    assert stepper.slider.max == len(stepper.model.trace)
    assert stepper.slider.max == 1 + 2 * SURFACE.facets + SURFACE.edges
    assert result.stats.edges == SURFACE.edges == 40


def test_the_replayed_perimeter_at_the_last_step_is_the_results(stepper):
    view = stepper.views[0]
    arrays, known = view.perimeter(stepper.slider.max)
    for name in ("top", "bottom", "right", "left"):
        assert np.array_equal(arrays[name], getattr(view.result.perimeter, name)), name
    assert known["columns"].all() and not known["rows"].all()  # fitted to the width, centred in y


@pytest.mark.parametrize("facets", [0, 1, 7, 16])
def test_the_replayed_perimeter_after_k_facets_merges_their_visible_points(stepper, facets):
    view, trace = stepper.views[0], stepper.model.trace
    updates = [i for i, e in enumerate(trace) if e.kind == "perimeter_update"]
    step = updates[facets - 1] + 1 if facets else 1
    edges = [e for e in trace[:step] if e.kind == "perimeter_edge"]
    expected, reached = merged(edges, SIZE, SIZE)
    arrays, known = view.perimeter(step)
    for name in expected:
        assert np.array_equal(arrays[name], expected[name]), name
    for axis in ("columns", "rows"):
        assert np.array_equal(known[axis], reached[axis]), axis
    stepper.slider.value = step
    top_x, top_y = view.curves["top"].get_data()  # entry x spans x - 1/2 .. x + 1/2
    assert np.array_equal(top_x[0::2], np.arange(SIZE) - 0.5)
    assert np.array_equal(top_y[0::2][known["columns"]], arrays["top"][known["columns"]])
    assert np.isnan(top_y[0::2][~known["columns"]]).all()
    left_x, left_y = view.curves["left"].get_data()  # over the rows: x is the value
    assert np.array_equal(left_y[1::2], np.arange(SIZE) + 0.5)
    assert np.array_equal(left_x[0::2][known["rows"]], arrays["left"][known["rows"]])


def test_the_points_so_far_are_drawn_black_or_light_red(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    step = len(trace) // 2
    stepper.slider.value = step
    image = np.asarray(view.points_image.get_array())
    visible, hidden = set(), set()
    for event in trace[:step]:
        if event.kind == "perimeter_edge":
            for point, flag in zip(event.points, event.visible, strict=True):
                (visible if flag else hidden).add(point)
    for x, y in visible:
        assert tuple(image[y, x]) == to_rgba(VISIBLE)
    for x, y in hidden - visible:
        assert tuple(image[y, x]) == to_rgba(HIDDEN)
    drawn = image[..., 3] > 0
    assert drawn.sum() == len(visible | hidden)


def test_an_edge_step_shows_its_points_and_their_test(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    step = next(i for i, e in enumerate(trace) if e.kind == "perimeter_edge" and not all(e.visible))
    stepper.slider.value = step + 1
    event = trace[step]
    assert np.array_equal(view.edge_points.get_offsets(), np.array(event.points, float))
    faces = [tuple(c) for c in view.edge_points.get_facecolors()]
    assert faces == [to_rgba(VISIBLE if v else HIDDEN) for v in event.visible]
    assert f"<b>{event.verdict}</b>" in view.text.value
    assert view.text.value.count(">hidden<") == event.visible.count(False)


def test_the_current_facet_is_outlined_on_screen_and_from_above(stepper):
    view, trace = stepper.views[0], stepper.model.trace
    step = next(i for i, e in enumerate(trace) if e.kind == "perimeter_facet" and e.number == 5)
    stepper.slider.value = step + 1
    facet = trace[step]
    assert view.grid.current.get_visible()
    assert view.grid.current.get_xy() == (SURFACE.x[facet.column], SURFACE.y[facet.row])
    alphas = view.grid.cells.get_facecolors()[:, 3]
    assert (alphas[:4] == 1).all() and (alphas[4:] < 1).all()  # facets 1-4 done
    ends = {
        (e.edge.kind, e.edge.row, e.edge.column): (e.points[0], e.points[-1])
        for e in trace
        if e.kind == "perimeter_edge"
    }
    bottom, top = ends[("h", facet.row, facet.column)], ends[("h", facet.row + 1, facet.column)]
    xs, ys = view.facet_outline.get_data()
    assert list(zip(xs, ys, strict=True)) == [bottom[0], bottom[1], top[1], top[0], bottom[0]]
    assert view.facet_outline.get_color() == CURRENT


def test_the_coverage_grows_with_the_processed_facets(stepper):
    view = stepper.views[0]
    surface_mode = floating_perimeter(SURFACE, VIEW, SIZE, SIZE, "surface", sample="center")
    order = view.result.enumeration.order.reshape(-1)
    stepper.slider.value = stepper.slider.max
    covered = np.asarray(view.coverage_image.get_array())[..., 3] > 0
    assert np.array_equal(covered, surface_mode.facet >= 0)
    stepper.slider.value = 1  # the enumeration only: nothing processed
    assert not np.asarray(view.coverage_image.get_array())[..., 3].any()
    first = view.step_of(0)  # facet 1's first edge: still nothing covered
    stepper.slider.value = first
    assert not np.asarray(view.coverage_image.get_array())[..., 3].any()
    after_two = [i for i, e in enumerate(stepper.model.trace) if e.kind == "perimeter_update"][1]
    stepper.slider.value = after_two + 1
    covered = np.asarray(view.coverage_image.get_array())[..., 3] > 0
    first_two = np.isin(surface_mode.facet, np.flatnonzero(order <= 2))
    assert np.array_equal(covered, first_two) and covered.any()


def test_step_of_a_hole_point_is_the_edge_that_hides_it(stepper):
    comparison = compare_with_zbuffer(SURFACE, VIEW, SIZE, SIZE)
    assert comparison.holes > 0
    view, trace = stepper.views[0], stepper.model.trace
    for index in np.flatnonzero(comparison.hole).tolist():
        event = trace[view.step_of(index) - 1]
        point = tuple(comparison.fpa.points[index])
        assert event.kind == "perimeter_edge" and point in event.points
        assert not event.visible[event.points.index(point)]


def test_the_horizon_steps_curve_by_curve_and_replays_the_results_horizons(horizon):
    view = horizon.views[0]
    assert horizon.slider.max == SURFACE.ny == len(view.curve_events)
    up, low = view.horizons(horizon.slider.max)
    assert np.array_equal(up, view.result.up) and np.array_equal(low, view.result.low)
    assert np.isinf(view.horizons(0)[0]).all()


def test_the_horizon_draws_the_results_segments_and_the_current_curve(horizon):
    view = horizon.views[0]
    horizon.slider.value = horizon.slider.max
    drawn = np.array([s.ravel() for s in view.drawn.get_segments()])
    assert np.allclose(drawn, view.result.segments)
    horizon.slider.value = 2
    curve = view.curve_events[1]
    xs, ys = view.current_curve.get_data()
    assert np.allclose(np.stack([xs, ys], 1), curve.points)
    assert f"<b>curve {curve.curve}</b>" in view.text.value
    before, _ = view.horizons(1)
    _, before_line = view.curves["up before"].get_data()
    assert np.array_equal(np.isnan(before_line), np.isinf(before))


def test_a_parallel_view_steps_too():
    stepper = perimeter_stepper(gaussian(4), PARALLEL, 24, 24)
    stepper.slider.value = stepper.slider.max
    view = stepper.views[0]
    assert view.grid.event.case == 6
    arrays, _ = view.perimeter(stepper.slider.max)
    assert np.array_equal(arrays["top"], view.result.perimeter.top)


def test_plot_grid_numbers_each_facet_and_the_nine_regions():
    figure = plot_grid(SURFACE, VIEW)
    order = floating_perimeter(SURFACE, VIEW, 8, 8).enumeration.order
    numbers = [t for t in figure.axes[0].texts if t.get_bbox_patch() is None]
    texts = {t.get_text(): t.get_position() for t in numbers}
    for row, column in np.ndindex(order.shape):
        x, y = texts[str(order[row, column])]
        assert SURFACE.x[column] < x < SURFACE.x[column + 1]
        assert SURFACE.y[row] < y < SURFACE.y[row + 1]
    regions = [t for t in figure.axes[0].texts if t.get_bbox_patch() is not None]
    assert sorted(t.get_text() for t in regions if t.get_text().isdigit()) == list("123456789")
    assert figure.axes[0].get_title() == "from above: viewing case 8"


def test_plot_mismatch_marks_the_holes():
    comparison = compare_with_zbuffer(SURFACE, VIEW, SIZE, SIZE)
    figure = plot_mismatch(comparison, region=(10, 20, 28, 38))
    image = np.asarray(figure.axes[0].images[0].get_array())
    raster_holes = comparison.hole & ~comparison.structural
    assert raster_holes.any()
    for x, y in comparison.fpa.points[raster_holes]:
        assert np.allclose(image[y, x], to_rgba(HOLE)[:3])
    for x, y in comparison.fpa.points[comparison.structural]:
        assert np.allclose(image[y, x], to_rgba(STRUCTURAL)[:3])
    assert figure.axes[1].get_xlim() == (9.5, 27.5)


def test_every_figure_fits_a_notebook(stepper, horizon):
    comparison = compare_with_zbuffer(SURFACE, VIEW, 24, 24)
    figures = [
        stepper.views[0].figure,
        horizon.views[0].figure,
        plot_grid(gaussian(5), VIEW),
        plot_grid(gaussian(5), [VIEW] * 4),
        plot_grid(gaussian(5), [PARALLEL, View((0.2, 0.1, 5), (0, 0, -1))]),  # straight down
        plot_results(SURFACE, VIEW, 24, 24),
        plot_results(SURFACE, VIEW, 24, 60),
        plot_mismatch(comparison),
        plot_mismatch(comparison, region=(0, 0, 12, 12)),
    ]
    for figure in figures:
        assert figure.get_size_inches()[0] <= WIDEST + 1e-9
        buffer = io.BytesIO()
        figure.savefig(buffer, format="png")
        assert buffer.getvalue()[:4] == b"\x89PNG"


def test_bad_input_is_a_clear_error(stepper):
    result = stepper.views[0].result
    horizon_trace = Recorder()
    horizon_result = floating_horizon(SURFACE, VIEW, SIZE, SIZE, trace=horizon_trace)
    with pytest.raises(ValueError, match="no facets_enumerated event"):
        PerimeterView(horizon_trace.trace(), result, SURFACE, VIEW)
    with pytest.raises(ValueError, match="no horizon_curve events"):
        HorizonView(stepper.model.trace, horizon_result)
    surface_mode = floating_perimeter(SURFACE, VIEW, SIZE, SIZE, "surface")
    with pytest.raises(TypeError, match="lines-mode"):
        PerimeterView(stepper.model.trace, surface_mode, SURFACE, VIEW)
    with pytest.raises(ValueError, match="not of this surface"):
        PerimeterView(stepper.model.trace, result, gaussian(4), VIEW)
    with pytest.raises(ValueError, match="'coverage' must be an \\(48, 48\\)"):
        PerimeterView(stepper.model.trace, result, SURFACE, VIEW, coverage=np.zeros((4, 4), int))
    with pytest.raises(TypeError, match="'surface' must be"):
        plot_grid("gaussian", VIEW)
    with pytest.raises(ValueError, match="'views' must hold 1 to 4 views"):
        plot_grid(SURFACE, [VIEW] * 5)
    with pytest.raises(TypeError, match="'view' must be"):
        plot_grid(SURFACE, [VIEW, (0, 0, 5)])
    with pytest.raises(ValueError, match="'region' must satisfy"):
        plot_mismatch(compare_with_zbuffer(SURFACE, VIEW, 24, 24), region=(0, 0, 30, 10))
    with pytest.raises(ValueError, match="'point' must be in 0.."):
        stepper.views[0].step_of(10**6)


def test_plot_mismatch_marks_a_structural_hole_apart():
    view = View((0.24, -3.43, 3.02), (-0.24, 3.43, -3.58))  # lesson 08's failing case
    comparison = compare_with_zbuffer(polynomial(12), view, 80, 80)
    assert comparison.structural_holes == 1
    image = np.asarray(plot_mismatch(comparison).axes[0].images[0].get_array())
    ((x, y),) = comparison.fpa.points[comparison.structural]
    assert np.allclose(image[y, x], to_rgba(STRUCTURAL)[:3])
    assert np.allclose(image[y, x - 1], to_rgba(VISIBLE)[:3])  # a gap in a drawn line


def test_a_long_trace_is_cut_and_said_so(monkeypatch):
    monkeypatch.setattr(Stepper, "MAX_STEPS", 30)
    stepper = perimeter_stepper(SURFACE, VIEW, SIZE, SIZE)
    assert stepper.slider.max == 30
    assert "showing the first 30" in stepper.views[0].note.value
    stepper.slider.value = 30  # a facet whose top edge is beyond the cut: no outline, no error

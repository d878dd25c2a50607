"""Viewing cases, viewpoint cells and the FPA facet enumeration (spec §1.6.2-1.6.3, §8.5-8.6)."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from scanviz.surfaces.enumeration import (
    Enumeration,
    enumerate_facets,
    facet_sequence,
    region_classes,
    viewing_case,
    vp_cell,
)
from scanviz.surfaces.view import View

# Fig. 2-2 as reconstructed in spec §1.6.3, copied literally: top row (max y) first.
FIG_2_2 = {
    1: [[17, 8, 2, 6, 13], [12, 5, 1, 4, 11], [19, 9, 3, 7, 15], [20, 18, 10, 14, 16]],
    2: [[20, 19, 16, 17, 18], [15, 14, 11, 12, 13], [10, 8, 4, 5, 7], [9, 3, 1, 2, 6]],
    3: [[9, 3, 1, 2, 6], [10, 8, 4, 5, 7], [15, 14, 11, 12, 13], [20, 19, 16, 17, 18]],
    4: [[6, 7, 11, 15, 19], [2, 5, 10, 14, 18], [1, 4, 9, 13, 17], [3, 8, 12, 16, 20]],
    5: [[19, 15, 11, 7, 6], [18, 14, 10, 5, 2], [17, 13, 9, 4, 1], [20, 16, 12, 8, 3]],
    6: [[10, 11, 12, 16, 20], [5, 6, 9, 15, 19], [2, 4, 8, 14, 18], [1, 3, 7, 13, 17]],
    7: [[1, 3, 7, 13, 17], [2, 4, 8, 14, 18], [5, 6, 9, 15, 19], [10, 11, 12, 16, 20]],
    8: [[20, 16, 12, 11, 10], [19, 15, 9, 6, 5], [18, 14, 8, 4, 2], [17, 13, 7, 3, 1]],
    9: [[17, 13, 7, 3, 1], [18, 14, 8, 4, 2], [19, 15, 9, 6, 5], [20, 16, 12, 11, 10]],
}
# The spec's VP cell (column, row) of each grid.
FIG_2_2_CELLS = {
    1: (2, 2),
    2: (2, -1),
    3: (2, 4),
    4: (-1, 1),
    5: (5, 1),
    6: (-1, -1),
    7: (-1, 4),
    8: (5, -1),
    9: (5, 4),
}
# Spec §1.6.3: classes of case 1, top row first.
FIG_2_2_CASE_1_CLASSES = [[8, 8, 2, 6, 6], [5, 5, 1, 4, 4], [9, 9, 3, 7, 7], [9, 9, 3, 7, 7]]
# Spec §1.6.2: the facet classes each case allows.
ALLOWED_CLASSES = {
    1: set(range(1, 10)),
    2: {2, 6, 8},
    3: {3, 7, 9},
    4: {4, 6, 7},
    5: {5, 8, 9},
    6: {6},
    7: {7},
    8: {8},
    9: {9},
}
# A 5 x 4-facet grid on [0, 5] x [0, 4] and a viewpoint (x, y) in each case's region.
X, Y = np.arange(6.0), np.arange(5.0)
VIEWPOINTS = {
    1: (2.5, 2.5),
    2: (2.5, -3.0),
    3: (2.5, 7.0),
    4: (-3.0, 1.5),
    5: (8.0, 1.5),
    6: (-2.0, -2.0),
    7: (-2.0, 6.0),
    8: (7.0, -2.0),
    9: (7.0, 6.0),
}


def looking_at_centre(x, y, height=3.0):
    return View(point=(x, y, height), direction=(2.5 - x, 2.0 - y, -height))


@pytest.mark.parametrize("case", range(1, 10))
def test_fig_2_2_reference_grids(case):
    grid = enumerate_facets(X, Y, looking_at_centre(*VIEWPOINTS[case]))
    assert grid.case == case
    assert grid.vp_cell == FIG_2_2_CELLS[case]
    np.testing.assert_array_equal(grid.order[::-1], FIG_2_2[case])


def test_fig_2_2_case_1_classes():
    grid = enumerate_facets(X, Y, looking_at_centre(*VIEWPOINTS[1]))
    np.testing.assert_array_equal(grid.classes[::-1], FIG_2_2_CASE_1_CLASSES)


@pytest.mark.parametrize("case", range(1, 10))
def test_fig_2_2_grids_from_the_cell_alone(case):
    sequence = facet_sequence(5, 4, FIG_2_2_CELLS[case])
    numbers = np.asarray(FIG_2_2[case])[::-1]
    np.testing.assert_array_equal(numbers[sequence[:, 0], sequence[:, 1]], np.arange(1, 21))


@pytest.mark.parametrize(
    ("case", "direction"),
    [(2, (0, 1, -1)), (3, (0, -1, -1)), (4, (1, 0, -1)), (5, (-1, 0, -1)), (6, (1, 1, -1))]
    + [(7, (1, -1, -1)), (8, (-1, 1, -1)), (9, (-1, -1, -1)), (1, (0, 0, -1))],
)
def test_parallel_views_give_the_fig_2_2_grids(case, direction):
    # The viewpoint is at infinity along -direction; the point picks the cell on a still axis.
    point = (2.5, 1.5 if case in (4, 5) else 2.5, 9.0)
    view = View(point=point, direction=direction, projection="parallel")
    grid = enumerate_facets(X, Y, view)
    assert grid.case == case
    np.testing.assert_array_equal(grid.order[::-1], FIG_2_2[case])


def test_viewing_case_of_tables_2_2_and_2_3():
    # Spec §8.6: VP (6, 8, 3) on [-2, 2]^2 is case 9.
    assert viewing_case((-2, 2, -2, 2), View((6, 8, 3), (-6, -8, -3))) == 9


@pytest.mark.parametrize(
    ("point", "case"),
    [((-2, -2), 1), ((2, 2), 1), ((-2, 0), 1), ((0, -2.0000001), 2), ((2.0000001, 2), 5)],
)
def test_viewing_case_counts_limit_lines_as_inside(point, case):
    assert viewing_case((-2, 2, -2, 2), View((*point, 3), (0, 0, -1))) == case


@pytest.mark.parametrize(
    ("x", "y", "cell"),
    [(1.0, 1.0, (1, 1)), (0.0, 0.0, (0, 0)), (5.0, 4.0, (4, 3)), (5.0, 1.0, (4, 1))]
    + [(-0.5, 4.5, (-1, 4)), (2.0, -1e-9, (2, -1)), (5.000001, 0.5, (5, 0))],
)
def test_vp_cell_ties_go_to_the_upper_cell_and_the_last_plane_is_inside(x, y, cell):
    assert vp_cell(X, Y, View((x, y, 3), (0, 0, -1))) == cell


def test_vp_cell_of_a_nonuniform_grid_bisects():
    view = View((0.95, 0.15, 1), (1, 1, -1))
    assert vp_cell([0, 0.1, 0.9, 1.0], [0, 0.1, 0.2], view) == (2, 1)


def test_parallel_vp_cell_clamps_the_point_on_an_axis_the_view_does_not_move_along():
    view = View((-7.0, 20.0, 1.0), (0, -1, -1), projection="parallel")
    assert vp_cell(X, Y, view) == (0, 4)


def test_single_facet():
    grid = enumerate_facets([0, 1], [0, 1], View((0.5, 0.5, 2), (0, 0, -1)))
    assert (grid.order.tolist(), grid.classes.tolist(), grid.case) == ([[1]], [[1]], 1)
    assert grid.sequence.tolist() == [[0, 0]]


def test_region_classes_are_the_spec_table():
    classes = region_classes(3, 3, (1, 1))[::-1]  # top row first
    np.testing.assert_array_equal(classes, [[8, 2, 6], [5, 1, 4], [9, 3, 7]])


# -- invariants, on random (non-uniform) grids and viewpoints -------------------------------


@st.composite
def planes(draw):
    steps = draw(st.lists(st.floats(0.1, 3.0), min_size=1, max_size=6))
    return np.concatenate([[0.0], np.cumsum(steps)]) + draw(st.floats(-5, 5))


viewpoints = st.tuples(st.floats(-12, 12), st.floats(-12, 12))
projections = st.sampled_from(["perspective", "parallel"])
directions = st.tuples(st.sampled_from([-1.0, 0.0, 0.5]), st.sampled_from([-2.0, 0.0, 1.0]))


def random_view(point, direction, projection):
    return View((*point, 4.0), (*direction, -1.0), projection=projection)


def in_index_rectangle(cell, facets, target):
    """Facets lying in the index rectangle between the viewpoint cell and `target` (inclusive)."""
    inside = np.ones(len(facets), dtype=bool)
    for axis, vp in ((1, cell[0]), (0, cell[1])):
        low, high = sorted((vp, target[axis]))
        inside &= (facets[:, axis] >= low) & (facets[:, axis] <= high)
    return inside


@settings(max_examples=60)
@given(planes(), planes(), viewpoints, directions, projections)
def test_every_facet_is_numbered_once_and_the_sequence_agrees(x, y, point, direction, projection):
    grid = enumerate_facets(x, y, random_view(point, direction, projection))
    count = (x.size - 1) * (y.size - 1)
    assert isinstance(grid, Enumeration)
    assert grid.order.shape == grid.classes.shape == (y.size - 1, x.size - 1)
    assert sorted(grid.order.ravel().tolist()) == list(range(1, count + 1))
    assert grid.sequence.shape == (count, 2)
    assert grid.order[grid.sequence[:, 0], grid.sequence[:, 1]].tolist() == list(
        range(1, count + 1)
    )


@settings(max_examples=60)
@given(planes(), planes(), viewpoints, directions, projections)
def test_no_facet_is_numbered_before_one_between_it_and_the_viewpoint(
    x, y, point, direction, projection
):
    grid = enumerate_facets(x, y, random_view(point, direction, projection))
    facets = grid.sequence
    for number, target in enumerate(facets, start=1):
        nearer = in_index_rectangle(grid.vp_cell, facets, target)
        assert (grid.order[facets[nearer, 0], facets[nearer, 1]] <= number).all()


@settings(max_examples=40)
@given(planes(), planes(), viewpoints)
def test_perspective_sight_lines_cross_only_earlier_facets(x, y, point):
    # Independent of the index rule: a facet can hide a point only if it meets the XY segment
    # from the viewpoint to that point, so every facet that segment crosses comes earlier.
    grid = enumerate_facets(x, y, random_view(point, (0.0, 0.0), "perspective"))
    t = np.linspace(0.0, 1.0, 401)[:, None]
    for row, column in grid.sequence:
        for fx, fy in ((0.3, 0.3), (0.7, 0.4), (0.5, 0.8)):
            target = np.array(
                [x[column] + fx * (x[column + 1] - x[column]), y[row] + fy * (y[row + 1] - y[row])]
            )
            path = np.asarray(point) + t * (target - np.asarray(point))
            on_grid = (path[:, 0] >= x[0]) & (path[:, 0] < x[-1])
            on_grid &= (path[:, 1] >= y[0]) & (path[:, 1] < y[-1])
            columns = np.searchsorted(x, path[on_grid, 0], side="right") - 1
            rows = np.searchsorted(y, path[on_grid, 1], side="right") - 1
            assert (grid.order[rows, columns] <= grid.order[row, column]).all()


@settings(max_examples=60)
@given(planes(), planes(), viewpoints, directions, projections)
def test_classes_are_those_the_case_allows_and_rings_grow(x, y, point, direction, projection):
    view = random_view(point, direction, projection)
    grid = enumerate_facets(x, y, view)
    assert grid.case == viewing_case((x[0], x[-1], y[0], y[-1]), view)
    assert set(grid.classes.ravel().tolist()) <= ALLOWED_CLASSES[grid.case]
    rings = np.maximum(
        np.abs(grid.sequence[:, 1] - grid.vp_cell[0]), np.abs(grid.sequence[:, 0] - grid.vp_cell[1])
    )
    assert (np.diff(rings) >= 0).all()
    if grid.case >= 6:  # corner-on: one quadrant
        assert (grid.classes == grid.case).all()


@settings(max_examples=40)
@given(planes(), planes(), viewpoints)
def test_mirroring_the_grid_mirrors_the_classes(x, y, point):
    assume(point[0] not in x)  # on a plane, the tie rule picks the upper cell: not symmetric
    view = random_view(point, (0.0, 0.0), "perspective")
    mirrored = random_view((-point[0], point[1]), (0.0, 0.0), "perspective")
    grid = enumerate_facets(x, y, view)
    flipped = enumerate_facets(-x[::-1], y, mirrored)
    swap = np.array([0, 1, 2, 3, 5, 4, 8, 9, 6, 7])  # left and right exchange
    np.testing.assert_array_equal(flipped.classes, swap[grid.classes[:, ::-1]])


# -- bad input -----------------------------------------------------------------------------

VIEW = View((0.5, 0.5, 3), (0, 0, -1))


@pytest.mark.parametrize(
    ("x", "message"),
    [
        ([0.0], "at least 2 planes"),
        ([[0, 1], [2, 3]], "1-D array"),
        ([0, np.nan, 2], "'x' must be finite; entry 1"),
        ([0, 2, 2], "strictly increasing; entries 1 and 2"),
        ([0, 3, 1], "strictly increasing"),
    ],
)
def test_bad_planes_are_named(x, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(")):
        enumerate_facets(x, [0, 1], VIEW)


def test_ragged_planes_are_a_type_error():
    with pytest.raises((TypeError, ValueError), match="'y'"):
        vp_cell([0, 1], [[0], [1, 2]], VIEW)


@pytest.mark.parametrize(
    ("domain", "error", "message"),
    [
        ((0, 1, 0), ValueError, "4 finite numbers"),
        ((0, 1, 0, np.inf), ValueError, "4 finite numbers"),
        ((1, 0, 0, 1), ValueError, "xmin < xmax"),
        ((0, 1, 0, 0), ValueError, "ymin < ymax"),
        (None, TypeError, "'domain' must be 4 numbers"),
    ],
)
def test_bad_domain_is_named(domain, error, message):
    with pytest.raises(error, match=message):
        viewing_case(domain, VIEW)


def test_view_must_be_a_view():
    with pytest.raises(TypeError, match="'view' must be a scanviz.surfaces.View"):
        enumerate_facets([0, 1], [0, 1], ((0, 0, 1), (0, 0, -1)))


@pytest.mark.parametrize(
    ("columns", "rows", "cell", "error", "message"),
    [
        (0, 4, (0, 0), ValueError, "'columns' must be >= 1"),
        (5, 2.0, (0, 0), TypeError, "'rows' must be an int"),
        (5, 4, (6, 0), ValueError, r"'cell' must lie in -1..columns"),
        (5, 4, (0, -2), ValueError, r"'cell' must lie in -1..columns"),
        (5, 4, (0.5, 0), TypeError, r"'cell' must be a \(column, row\) pair"),
        (5, 4, 3, TypeError, r"'cell' must be a \(column, row\) pair"),
    ],
)
def test_bad_cells_are_named(columns, rows, cell, error, message):
    for function in (region_classes, facet_sequence):
        with pytest.raises(error, match=message):
            function(columns, rows, cell)

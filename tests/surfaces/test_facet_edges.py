"""Step V of the FPA: which edges each facet processes (spec §1.6.4, §1.1, §8.4)."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.surfaces.enumeration import enumerate_facets
from scanviz.surfaces.facet_edges import FacetEdges, facet_edges
from scanviz.surfaces.view import View

# Spec §1.6.4, copied literally: the sides each class processes in viewing case 1.
CASE_1_SIDES = {
    1: "TBLR",
    2: "TLR",
    3: "BLR",
    4: "TBR",
    5: "TBL",
    6: "TR",
    7: "BR",
    8: "TL",
    9: "BL",
}


def looking_down(x, y):
    return View(point=(x, y, 5.0), direction=(0.0, 0.0, -1.0))


def edge_list(edges):
    return [list(facet) for facet in edges.per_facet]


# -- hand-derived cases: expected edges written from the spec's table and neighbour rule -------


def test_case_1_every_class_once():
    # 3 x 3 facets, VP over the centre facet: facets 1..9 are classes 1..9 in order, and each
    # processes its class's sides of the spec table (T = ("h", r + 1, c), B = ("h", r, c),
    # L = ("v", r, c), R = ("v", r, c + 1)).
    grid = enumerate_facets([0, 1, 2, 3], [0, 1, 2, 3], looking_down(1.5, 1.5))
    assert grid.classes[grid.sequence[:, 0], grid.sequence[:, 1]].tolist() == list(range(1, 10))
    assert edge_list(facet_edges(grid)) == [
        [("h", 2, 1), ("h", 1, 1), ("v", 1, 1), ("v", 1, 2)],  # 1 (r1, c1): T B L R
        [("h", 3, 1), ("v", 2, 1), ("v", 2, 2)],  # 2 (r2, c1): T L R
        [("h", 0, 1), ("v", 0, 1), ("v", 0, 2)],  # 3 (r0, c1): B L R
        [("h", 2, 2), ("h", 1, 2), ("v", 1, 3)],  # 4 (r1, c2): T B R
        [("h", 2, 0), ("h", 1, 0), ("v", 1, 0)],  # 5 (r1, c0): T B L
        [("h", 3, 2), ("v", 2, 3)],  # 6 (r2, c2): T R
        [("h", 0, 2), ("v", 0, 3)],  # 7 (r0, c2): B R
        [("h", 3, 0), ("v", 2, 0)],  # 8 (r2, c0): T L
        [("h", 0, 0), ("v", 0, 0)],  # 9 (r0, c0): B L
    ]


def test_case_2_near_row_also_processes_its_unshared_bottom_edges():
    # 2 x 2 facets, VP below column 0: order (r0,c0), (r0,c1), (r1,c0), (r1,c1). The class table
    # alone would skip the bottom edges of row 0, which no other facet has (spec §1.6.4).
    grid = enumerate_facets([0, 1, 2], [0, 1, 2], View((0.5, -3.0, 2.0), (0.0, 1.0, -0.5)))
    assert grid.case == 2
    assert grid.order.tolist() == [[1, 2], [3, 4]]
    edges = facet_edges(grid)
    assert edges.sides == ("TBLR", "TBR", "TLR", "TR")
    assert edge_list(edges) == [
        [("h", 1, 0), ("h", 0, 0), ("v", 0, 0), ("v", 0, 1)],
        [("h", 1, 1), ("h", 0, 1), ("v", 0, 2)],
        [("h", 2, 0), ("v", 1, 0), ("v", 1, 1)],
        [("h", 2, 1), ("v", 1, 2)],
    ]


def test_case_9_corner():
    # 2 x 2 facets, VP beyond the upper-right corner: order (r1,c1), (r0,c1), (r1,c0), (r0,c0).
    grid = enumerate_facets([0, 1, 2], [0, 1, 2], View((3.0, 3.0, 2.0), (-1.0, -1.0, -1.0)))
    assert grid.case == 9
    assert grid.order.tolist() == [[4, 2], [3, 1]]
    assert edge_list(facet_edges(grid)) == [
        [("h", 2, 1), ("h", 1, 1), ("v", 1, 1), ("v", 1, 2)],
        [("h", 0, 1), ("v", 0, 1), ("v", 0, 2)],
        [("h", 2, 0), ("h", 1, 0), ("v", 1, 0)],
        [("h", 0, 0), ("v", 0, 0)],
    ]


def test_case_4_single_row_strip():
    # 3 x 1 facets seen from the left: each facet after the first skips only its L edge.
    grid = enumerate_facets([0, 1, 2, 3], [0, 1], View((-2.0, 0.5, 2.0), (1.0, 0.0, -0.5)))
    assert grid.case == 4
    assert edge_list(facet_edges(grid)) == [
        [("h", 1, 0), ("h", 0, 0), ("v", 0, 0), ("v", 0, 1)],
        [("h", 1, 1), ("h", 0, 1), ("v", 0, 2)],
        [("h", 1, 2), ("h", 0, 2), ("v", 0, 3)],
    ]


def test_single_facet_processes_its_four_edges():
    edges = facet_edges(enumerate_facets([0, 1], [0, 1], looking_down(0.5, 0.5)))
    assert edge_list(edges) == [[("h", 1, 0), ("h", 0, 0), ("v", 0, 0), ("v", 0, 1)]]
    assert edges.edges.tolist() == [[0, 1, 0], [0, 0, 0], [1, 0, 0], [1, 0, 1]]
    assert edges.facet.tolist() == [1, 1, 1, 1]


def test_case_1_matches_the_class_table_on_the_fig_2_2_grid():
    # Spec §1.6.4 [DOC]: in case 1, classes 2-5 process 3 edges and 6-9 process 2.
    grid = enumerate_facets(np.arange(6.0), np.arange(5.0), looking_down(2.5, 2.5))
    edges = facet_edges(grid)
    classes = grid.classes[grid.sequence[:, 0], grid.sequence[:, 1]]
    assert [edges.sides[i] for i in range(20)] == [CASE_1_SIDES[c] for c in classes]
    assert [len(s) for s in edges.sides] == [
        {1: 4, 6: 2, 7: 2, 8: 2, 9: 2}.get(c, 3) for c in classes
    ]


# -- golden counts (spec §1.1, §8.4) ---------------------------------------------------------


@pytest.mark.parametrize(
    ("n", "count"), [(10, 180), (20, 760), (30, 1740), (40, 3120), (50, 4900), (60, 7080)]
)
def test_edge_counts_of_table_2_2(n, count):
    # The Table 2-2 setup: an n x n grid on [-2, 2]^2 seen from (6, 8, 3), case 9.
    planes = np.linspace(-2.0, 2.0, n)
    edges = facet_edges(enumerate_facets(planes, planes, View((6, 8, 3), (-6, -8, -3))))
    assert edges.edges.shape == (count, 3) == (n * (n - 1) + n * (n - 1), 3)
    assert edges.facet.shape == (count,)
    assert sum(len(facet) for facet in edges.per_facet) == count


# -- invariants on random (non-uniform) grids, every case, viewpoints on lines and points ------


@st.composite
def planes(draw):
    steps = draw(st.lists(st.floats(0.1, 3.0), min_size=1, max_size=6))
    return np.concatenate([[0.0], np.cumsum(steps)]) + draw(st.floats(-5, 5))


@st.composite
def coordinate(draw, axis_planes):
    # Below, inside or above the grid; often exactly on a plane (a grid line or, on both axes,
    # above a grid point), where vp_cell's tie rule decides.
    kind = draw(st.sampled_from(["below", "plane", "inside", "above"]))
    if kind == "plane":
        return float(draw(st.sampled_from(axis_planes.tolist())))
    low, high = {"below": (-9.0, -0.01), "inside": (0.0, 1.0), "above": (1.01, 10.0)}[kind]
    return float(axis_planes[0] + draw(st.floats(low, high)) * (axis_planes[-1] - axis_planes[0]))


@st.composite
def grids(draw):
    uniform = draw(st.booleans())
    x, y = draw(planes()), draw(planes())
    if uniform:
        x = np.linspace(x[0], x[-1], x.size)
        y = np.linspace(y[0], y[-1], y.size)
    point = (draw(coordinate(x)), draw(coordinate(y)), 4.0)
    if draw(st.booleans()):
        view = View(point, (0.5, -0.5, -1.0))
    else:
        direction = (
            draw(st.sampled_from([-1.0, 0.0, 1.0])),
            draw(st.sampled_from([-1.0, 0.0, 1.0])),
        )
        view = View(point, (*direction, -1.0), projection="parallel")
    return enumerate_facets(x, y, view)


def all_edges(rows, columns):
    """Every edge of the grid with the facets on its sides (None where there is none)."""
    for row in range(rows + 1):
        for column in range(columns):
            below = (row - 1, column) if row > 0 else None
            above = (row, column) if row < rows else None
            yield (0, row, column), [f for f in (below, above) if f is not None]
    for row in range(rows):
        for column in range(columns + 1):
            left = (row, column - 1) if column > 0 else None
            right = (row, column) if column < columns else None
            yield (1, row, column), [f for f in (left, right) if f is not None]


def assert_each_edge_once_by_its_first_facet(grid):
    # Edge-centric oracle: walk the grid's edges, not the facets. Each edge has one or two
    # facets; it must be processed once, by the one numbered first. Hence when a facet processes
    # an edge, the facet across it (if any) comes later in the enumeration.
    rows, columns = grid.order.shape
    edges = facet_edges(grid)
    processor = {
        tuple(e): int(f) for e, f in zip(edges.edges.tolist(), edges.facet.tolist(), strict=True)
    }
    assert len(processor) == len(edges.edges)  # no edge twice
    expected = {
        edge: min(int(grid.order[f]) for f in facets) for edge, facets in all_edges(rows, columns)
    }
    assert processor == expected  # every edge once, by its earliest facet
    assert len(expected) == (columns + 1) * rows + (rows + 1) * columns  # Nx(Ny-1) + Ny(Nx-1)


@settings(max_examples=80)
@given(grids())
def test_every_edge_is_processed_exactly_once_by_the_first_of_its_facets(grid):
    assert_each_edge_once_by_its_first_facet(grid)


UNIFORM = np.arange(6.0)
NONUNIFORM = np.array([0.0, 0.1, 0.5, 1.7, 1.8, 3.0])


def placements(planes, side):
    """Viewpoint coordinates on one axis: beyond either end, or inside (generic and on a plane)."""
    span = planes[-1] - planes[0]
    if side == -1:
        return [planes[0] - 0.7 * span]
    if side == 1:
        return [planes[-1] + 0.7 * span]
    return [0.5 * (planes[2] + planes[3]), planes[2], planes[0], planes[-1]]


SIDES_OF_CASE = {1: (0, 0), 2: (0, -1), 3: (0, 1), 4: (-1, 0), 5: (1, 0)}
SIDES_OF_CASE |= {6: (-1, -1), 7: (-1, 1), 8: (1, -1), 9: (1, 1)}


@pytest.mark.parametrize("x", [UNIFORM, NONUNIFORM], ids=["uniform", "nonuniform"])
@pytest.mark.parametrize("case", range(1, 10))
def test_every_edge_once_in_every_case_including_viewpoints_on_lines_and_points(case, x):
    y = x[:5] * 1.3  # 5 x 4 facets, as Fig. 2-2
    x_side, y_side = SIDES_OF_CASE[case]
    for px in placements(x, x_side):
        for py in placements(y, y_side):
            # A parallel view from the same side: at infinity along -direction.
            parallel = View((px, py, 4.0), (-x_side, -y_side, -1.0), projection="parallel")
            for view in (View((px, py, 4.0), (0.3, 0.2, -1.0)), parallel):
                grid = enumerate_facets(x, y, view)
                assert grid.case == case
                assert_each_edge_once_by_its_first_facet(grid)
                assert facet_edges(grid).edges.shape == (6 * 4 + 5 * 5, 3)


@settings(max_examples=80)
@given(grids())
def test_flat_arrays_agree_with_per_facet_lists_in_processing_order(grid):
    edges = facet_edges(grid)
    count = grid.order.size
    assert isinstance(edges, FacetEdges)
    assert len(edges.per_facet) == len(edges.sides) == count
    assert (np.diff(edges.facet) >= 0).all() and set(edges.facet.tolist()) == set(
        range(1, count + 1)
    )
    flat = [(("h", "v")[k], r, c) for k, r, c in edges.edges.tolist()]
    assert flat == [edge for facet in edges.per_facet for edge in facet]
    for number, ((row, column), facet, sides) in enumerate(
        zip(grid.sequence.tolist(), edges.per_facet, edges.sides, strict=True), start=1
    ):
        named = {"T": ("h", row + 1, column), "B": ("h", row, column)}
        named |= {"L": ("v", row, column), "R": ("v", row, column + 1)}
        assert list(facet) == [named[s] for s in sides]  # sides in the order T, B, L, R
        assert sides == "".join(s for s in "TBLR" if s in sides)
        assert (edges.facet[[i for i, e in enumerate(flat) if e in facet]] == number).all()


@settings(max_examples=80)
@given(grids())
def test_sides_are_the_class_table_plus_the_unshared_boundary_edges(grid):
    # Spec §1.6.4: the class table holds wherever the neighbour across exists; an edge on the
    # grid's boundary has no other facet, so its facet always processes it. Independent of the
    # numbering: it uses only the classes.
    rows, columns = grid.order.shape
    edges = facet_edges(grid)
    for (row, column), sides in zip(grid.sequence.tolist(), edges.sides, strict=True):
        boundary = {
            "T": row == rows - 1,
            "B": row == 0,
            "L": column == 0,
            "R": column == columns - 1,
        }
        table = CASE_1_SIDES[int(grid.classes[row, column])]
        assert set(sides) == set(table) | {s for s, on in boundary.items() if on}


@settings(max_examples=80)
@given(grids())
def test_only_facet_1_processes_all_four_edges(grid):
    # Step V [DOC]: every facet but the first has an earlier neighbour, so it skips an edge.
    sides = facet_edges(grid).sides
    assert sides[0] == "TBLR"
    assert all(len(s) < 4 for s in sides[1:])


def test_arrays_are_read_only():
    edges = facet_edges(enumerate_facets([0, 1, 2], [0, 1], looking_down(0.5, 0.5)))
    with pytest.raises(ValueError, match="read-only"):
        edges.edges[0, 0] = 1
    with pytest.raises(ValueError, match="read-only"):
        edges.facet[0] = 2


# -- bad input -------------------------------------------------------------------------------

GRID = enumerate_facets([0, 1, 2], [0, 1, 2], looking_down(0.5, 0.5))


def test_rejects_what_is_not_an_enumeration():
    with pytest.raises(TypeError, match="'enumeration' must be a scanviz.surfaces.Enumeration"):
        facet_edges(GRID.order)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"order": np.array([1, 2, 3, 4])}, "non-empty 2-D integer array"),
        ({"order": GRID.order.astype(float)}, "non-empty 2-D integer array"),
        ({"order": np.array([[1, 2], [2, 4]])}, r"number the facets 1\.\.4, each once"),
        ({"order": np.array([[1, 2], [3, 5]])}, r"number the facets 1\.\.4, each once"),
        ({"sequence": GRID.sequence[::-1]}, "'enumeration.sequence' must list"),
        ({"sequence": GRID.sequence[:3]}, "'enumeration.sequence' must list"),
    ],
)
def test_rejects_an_inconsistent_enumeration(changes, message):
    with pytest.raises(ValueError, match=message):
        facet_edges(dataclasses.replace(GRID, **changes))

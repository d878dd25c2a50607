"""Grid surfaces: golden checks of Wang (1989) ch. 2 (spec §8.1, 8.2, 8.4), oracles, invariants."""

import dataclasses
import io
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.limits import ResourceLimitError, file_limit, memory_limit
from scanviz.scene.model import Mesh
from scanviz.surfaces import (
    BUILTIN_SURFACES,
    GridSurface,
    gaussian,
    polynomial,
    polynomial_height,
    random_surface,
    rogers,
)

POLYNOMIAL_DOMAIN = (-1.2, 1.2)


def database_lines(surface, **options):
    buffer = io.StringIO()
    surface.to_database(buffer, **options)
    return buffer.getvalue().splitlines()


def read(text):
    return GridSurface.from_database(io.StringIO(text))


def small_grids():
    """Random non-uniform grids: increasing axes of 2..6 points and arbitrary heights."""

    def axis(n):
        steps = st.lists(st.floats(0.01, 10, allow_nan=False), min_size=n - 1, max_size=n - 1)
        return st.tuples(st.floats(-100, 100), steps).map(
            lambda pair: np.concatenate([[pair[0]], pair[0] + np.cumsum(pair[1])])
        )

    def grid(shape):
        nx, ny = shape
        heights = st.lists(st.floats(-1e6, 1e6), min_size=nx * ny, max_size=nx * ny)
        return st.tuples(axis(nx), axis(ny), heights).map(
            lambda t: GridSurface(t[0], t[1], np.reshape(t[2], (ny, nx)))
        )

    return st.tuples(st.integers(2, 6), st.integers(2, 6)).flatmap(grid)


def grid_axes_ok(surface):
    return bool(np.all(np.diff(surface.x) > 0) and np.all(np.diff(surface.y) > 0))


# --- golden checks ----------------------------------------------------------------------------


def test_table_2_1_database_rows():
    lines = database_lines(gaussian())
    assert lines[:2] == ["-1.0 1.0 -1.0 1.0", "11 11"]
    triplets = lines[2:]
    assert len(triplets) == 121
    assert triplets[0] == "-1.0 -1.0 0.1353"
    assert triplets[10] == "1.0 -1.0 0.1353"  # (xNx, y1)
    assert triplets[11] == "-1.0 -0.8 0.1940"  # triplet #12 = (x1, y2)
    assert triplets[21] == "1.0 -0.8 0.1940"
    assert triplets[110] == "-1.0 1.0 0.1353"
    assert triplets[-1] == "1.0 1.0 0.1353"
    decimals = ["-1.0", "-0.8", "-0.6", "-0.4", "-0.2", "0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]
    assert [line.split()[0] for line in triplets[:11]] == decimals  # not -0.3999999999999999
    assert [line.split()[1] for line in triplets[::11]] == decimals


def test_table_2_1_values_within_the_printed_precision():
    surface = gaussian()
    assert surface.x.tolist() == pytest.approx(np.arange(-1.0, 1.01, 0.2).tolist(), abs=1e-15)
    assert abs(surface.z[0, 0] - 0.1353) < 5e-5 and abs(surface.z[1, 0] - 0.1940) < 5e-5


def test_nonuniform_polynomial_gives_28_by_28_planes():
    surface = GridSurface.nonuniform(
        polynomial_height, POLYNOMIAL_DOMAIN, POLYNOMIAL_DOMAIN, 66, 42, 3, 3, 0.23
    )
    assert (surface.nx, surface.ny) == (28, 28)
    assert surface.facets == 27 * 27


def test_nonuniform_plane_indices_match_the_spec():
    surface = GridSurface.nonuniform(
        polynomial_height, POLYNOMIAL_DOMAIN, POLYNOMIAL_DOMAIN, 66, 42, 3, 3, 0.23
    )
    columns = np.rint((surface.x + 1.2) / (2.4 / 65)).astype(int) + 1  # 1-based, as in the spec
    rows = np.rint((surface.y + 1.2) / (2.4 / 41)).astype(int) + 1
    assert columns.tolist() == [1, 2, 3, 4, 5, *range(8, 60, 3), 62, 63, 64, 65, 66]
    assert rows.tolist() == [*range(1, 12), 14, 17, 20, 23, 26, 29, *range(32, 43)]


def test_nonuniform_without_the_max_step_rule_is_the_bare_pseudocode():
    surface = GridSurface.nonuniform(
        polynomial_height, POLYNOMIAL_DOMAIN, POLYNOMIAL_DOMAIN, 66, 42, 3, 3, 0.23, max_step=False
    )
    assert (surface.nx, surface.ny) == (10, 22)


@pytest.mark.parametrize("tolerance, planes", [(0.22, (30, 30)), (0.24, (27, 26))])
def test_nonuniform_count_is_sharp_in_the_tolerance(tolerance, planes):
    surface = GridSurface.nonuniform(
        polynomial_height, POLYNOMIAL_DOMAIN, POLYNOMIAL_DOMAIN, 66, 42, 3, 3, tolerance
    )
    assert (surface.nx, surface.ny) == planes


@pytest.mark.parametrize(
    "n, facets, edges",
    [
        (10, 81, 180),
        (20, 361, 760),
        (30, 841, 1740),
        (40, 1521, 3120),
        (50, 2401, 4900),
        (60, 3481, 7080),
    ],
)
def test_facet_and_edge_counts_of_table_2_2(n, facets, edges):
    surface = GridSurface.from_function(lambda x, y: x * y, (-2, 2), (-2, 2), n, n)
    assert (surface.facets, surface.edges) == (facets, edges)


# --- the non-uniform procedure against a literal transcription ---------------------------------


def dissertation_planes(z, ratio_x, ratio_y, tolerance):
    """Wang's loop as printed (1-based a, b; sets), then the max-step fill one gap at a time."""
    nmax_y, nmax_x = z.shape
    xa, ya = {1, nmax_x}, {1, nmax_y}
    for a in range(2, nmax_x):
        for b in range(2, nmax_y):
            zab = z[b - 1, a - 1]
            if abs(zab - z[b - 1, a - 2]) + abs(zab - z[b - 2, a - 1]) > tolerance:
                xa |= {a - 1, a}
                ya |= {b - 1, b}
    filled = []
    for planes, ratio in ((sorted(xa), ratio_x), (sorted(ya), ratio_y)):
        out = [planes[0]]
        for following in planes[1:]:
            while following - out[-1] > ratio:
                out.append(out[-1] + ratio)
            out.append(following)
        filled.append([p - 1 for p in out])
    return filled


@settings(max_examples=25)
@given(
    seed=st.integers(0, 2**16),
    shape=st.tuples(st.integers(2, 12), st.integers(2, 12)),
    ratios=st.tuples(st.integers(1, 5), st.integers(1, 5)),
    tolerance=st.floats(0, 1.5),
)
def test_nonuniform_matches_the_transcribed_loop(seed, shape, ratios, tolerance):
    nx, ny = shape
    heights = np.random.default_rng(seed).random((ny, nx))
    temporary = GridSurface(np.arange(nx, dtype=float), np.arange(ny, dtype=float), heights)

    def f(x, y):  # the random heights as a function on the temporary grid
        return heights[np.rint(y).astype(int), np.rint(x).astype(int)]

    surface = GridSurface.nonuniform(f, (0, nx - 1), (0, ny - 1), nx, ny, *ratios, tolerance)
    columns, rows = dissertation_planes(heights, *ratios, tolerance)
    assert surface.x.tolist() == temporary.x[columns].tolist()
    assert surface.y.tolist() == temporary.y[rows].tolist()
    assert np.array_equal(surface.z, heights[np.ix_(rows, columns)])
    assert np.diff(columns).max() <= ratios[0] and np.diff(rows).max() <= ratios[1]


def test_nonuniform_keeps_only_the_ends_of_a_flat_surface_without_max_step():
    flat = GridSurface.nonuniform(
        lambda x, y: 0 * x, (0, 1), (0, 1), 9, 5, 2, 4, 0.0, max_step=False
    )
    assert (flat.x.tolist(), flat.y.tolist()) == ([0.0, 1.0], [0.0, 1.0])
    filled = GridSurface.nonuniform(lambda x, y: 0 * x, (0, 1), (0, 1), 9, 5, 2, 4, 0.0)
    assert filled.x.tolist() == [0.0, 0.25, 0.5, 0.75, 1.0] and filled.y.tolist() == [0.0, 1.0]


# --- construction and validation --------------------------------------------------------------


def test_from_function_is_uniform_with_exact_ends():
    surface = GridSurface.from_function(lambda x, y: x - y, (-1.2, 1.2), (0.0, 3.0), 30, 7)
    assert (surface.x[0], surface.x[-1], surface.y[0], surface.y[-1]) == (-1.2, 1.2, 0.0, 3.0)
    assert np.allclose(np.diff(surface.x), 2.4 / 29, rtol=0, atol=1e-15)
    assert np.allclose(np.diff(surface.y), 0.5, rtol=0, atol=1e-15)
    assert surface.z.shape == (7, 30)
    assert np.array_equal(surface.z, surface.x[None, :] - surface.y[:, None])


def test_scalar_and_vectorized_functions_agree():
    vectorized = GridSurface.from_function(
        lambda x, y: np.exp(-x * x - y * y), (-1, 1), (-1, 2), 5, 4
    )
    scalar = GridSurface.from_function(
        lambda x, y: math.exp(-x * x - y * y), (-1, 1), (-1, 2), 5, 4, vectorized=False
    )
    assert np.array_equal(vectorized.z, scalar.z)


def test_nonuniform_with_a_scalar_function():
    surface = GridSurface.nonuniform(
        lambda x, y: x**4 - x**2 - y**2,
        POLYNOMIAL_DOMAIN,
        POLYNOMIAL_DOMAIN,
        66,
        42,
        3,
        3,
        0.23,
        vectorized=False,
    )
    assert (surface.nx, surface.ny) == (28, 28)


def test_scalar_function_called_in_database_order():
    calls = []
    GridSurface.from_function(
        lambda x, y: calls.append((x, y)) or 0.0, (0, 1), (0, 1), 2, 2, vectorized=False
    )
    assert calls == [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]


def test_constant_from_a_vectorized_function_broadcasts():
    assert (
        GridSurface.from_function(lambda x, y: 2.5, (0, 1), (0, 1), 3, 2).z.tolist()
        == [[2.5] * 3] * 2
    )


def test_scalar_only_function_without_the_flag_says_what_to_do():
    with pytest.raises(TypeError, match="vectorized=False"):
        GridSurface.from_function(lambda x, y: math.exp(x), (0, 1), (0, 1), 2, 2)


@pytest.mark.parametrize(
    "f, message",
    [
        (lambda x, y: np.where(x > 0.5, np.nan, 0.0), r"'f' must be finite; f\(1.0, 0.0\) = nan"),
        (lambda x, y: np.zeros(5), r"'f' must return real heights of shape \(2, 2\)"),
        (lambda x, y: "high", "'f' must return real heights"),
    ],
)
def test_bad_function_results(f, message):
    with pytest.raises(ValueError, match=message):
        GridSurface.from_function(f, (0, 1), (0, 1), 2, 2)


@pytest.mark.parametrize(
    "args, error, message",
    [
        (((0, 1), (0, 1), 1, 2), ValueError, "'nx' must be >= 2"),
        (((0, 1), (0, 1), 2, 2.0), TypeError, "'ny' must be an int"),
        (((0, 1), (0, 1), True, 2), TypeError, "'nx' must be an int"),
        (((1, 0), (0, 1), 2, 2), ValueError, "'x_range' must be finite with low < high"),
        (((0, 1), (0, math.inf), 2, 2), ValueError, "'y_range' must be finite"),
        (((0, 1), 3, 2, 2), TypeError, "'y_range' must be a pair"),
    ],
)
def test_from_function_argument_errors(args, error, message):
    with pytest.raises(error, match=message):
        GridSurface.from_function(lambda x, y: x, *args)


def test_from_function_refuses_a_huge_grid_before_calling_f():
    calls = []
    with memory_limit("1M"), pytest.raises(ResourceLimitError, match="10000x10000 points"):
        GridSurface.from_function(lambda x, y: calls.append(1), (0, 1), (0, 1), 10_000, 10_000)
    assert calls == []


def test_huge_random_and_nonuniform_grids_are_refused():
    with memory_limit("1M"):
        with pytest.raises(ResourceLimitError):
            GridSurface.random(5000, 5000)
        with pytest.raises(ResourceLimitError):
            GridSurface.nonuniform(polynomial_height, (0, 1), (0, 1), 5000, 5000, 2, 2, 0.1)
        with pytest.raises(ResourceLimitError, match="mesh"):
            GridSurface.random(100, 100).to_mesh()


@pytest.mark.parametrize(
    "x, y, z, message",
    [
        ([0, 1], [0, 1], [[0, 1], [2]], r"'z' must be a rectangular \(Ny, Nx\) = \(2, 2\)"),
        ([0, 1], [0, 1], [[0, 1], [2, np.nan]], r"'z' must be finite; z\[1, 1\] is nan"),
        (
            [0, 1],
            [0, 1],
            [[0, 1, 2], [3, 4, 5]],
            r"'z' must have shape \(Ny, Nx\) = \(2, 2\); got \(2, 3\)",
        ),
        ([0], [0, 1], [[0], [1]], "'x' must be a 1-D array of at least 2 values"),
        ([0, 1], [[0, 1]], [[0, 1]], "'y' must be a 1-D array of at least 2 values"),
        (
            [0, 2, 2],
            [0, 1],
            [[0, 0, 0]] * 2,
            r"'x' must be strictly increasing; x\[2\] = 2.0 <= x\[1\] = 2.0",
        ),
        ([0, 1], [1, 0], [[0, 0]] * 2, r"'y' must be strictly increasing; y\[1\] = 0.0"),
        ([0, np.inf], [0, 1], [[0, 0]] * 2, r"'x' must be finite; x\[1\] is inf"),
    ],
)
def test_constructor_rejects_bad_arrays(x, y, z, message):
    with pytest.raises(ValueError, match=message):
        GridSurface(x, y, z)


def test_constructor_rejects_non_numbers():
    with pytest.raises(TypeError, match="'x' must be a 1-D array of numbers"):
        GridSurface(["a", "b"], [0, 1], [[0, 0], [0, 0]])


def test_arrays_are_read_only_float64_copies():
    heights = np.zeros((2, 2), dtype=np.int64)
    surface = GridSurface([0, 1], [0, 1], heights)
    heights[0, 0] = 7
    assert surface.z[0, 0] == 0.0
    for array in (surface.x, surface.y, surface.z):
        assert array.dtype == np.float64 and not array.flags.writeable
        with pytest.raises(ValueError):
            array[0] = 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        surface.x = np.array([0.0, 2.0])


def test_random_surface_distribution():
    surface = GridSurface.random(7, 5, seed=3)
    assert np.array_equal(surface.z, np.random.default_rng(3).random((5, 7)))
    assert (surface.x[0], surface.x[-1], surface.y[0], surface.y[-1]) == (-2.0, 2.0, -2.0, 2.0)
    large = GridSurface.random(200, 200, seed=0).z
    assert 0.0 <= large.min() and large.max() < 1.0
    assert abs(large.mean() - 0.5) < 0.01 and abs(large.var() - 1 / 12) < 0.005
    assert np.array_equal(GridSurface.random(4, 4, seed=1).z, GridSurface.random(4, 4, seed=1).z)
    assert not np.array_equal(
        GridSurface.random(4, 4, seed=1).z, GridSurface.random(4, 4, seed=2).z
    )


@pytest.mark.parametrize("seed", [-1, 1.5, True, "0"])
def test_random_rejects_bad_seeds(seed):
    with pytest.raises(TypeError, match="'seed' must be an int >= 0"):
        GridSurface.random(3, 3, seed=seed)


@pytest.mark.parametrize(
    "args, error, message",
    [
        ((66, 42, 0, 3, 0.23), ValueError, "'ratio_x' must be >= 1"),
        ((66, 42, 3, 2.0, 0.23), TypeError, "'ratio_y' must be an int"),
        ((66, 42, 3, 3, -0.1), ValueError, "'z_tolerance' must be finite and >= 0"),
        ((66, 42, 3, 3, math.nan), ValueError, "'z_tolerance' must be finite"),
        ((1, 42, 3, 3, 0.2), ValueError, "'nmax_x' must be >= 2"),
    ],
)
def test_nonuniform_argument_errors(args, error, message):
    with pytest.raises(error, match=message):
        GridSurface.nonuniform(polynomial_height, POLYNOMIAL_DOMAIN, POLYNOMIAL_DOMAIN, *args)


# --- the database format ----------------------------------------------------------------------


@settings(max_examples=30)
@given(small_grids())
def test_database_round_trip_is_exact_with_full_precision(surface):
    text = "\n".join(database_lines(surface, z_decimals=None))
    again = read(text)
    for name in "xyz":
        assert np.array_equal(getattr(again, name), getattr(surface, name))


def test_database_round_trip_at_four_decimals():
    surface = rogers(9)
    again = read("\n".join(database_lines(surface)))
    assert np.array_equal(again.x, surface.x) and np.array_equal(again.y, surface.y)
    assert np.abs(again.z - surface.z).max() <= 5e-5


def test_database_through_a_path(tmp_path):
    path = tmp_path / "gaussian.dat"
    gaussian().to_database(path)
    assert path.read_text().splitlines()[13] == "-1.0 -0.8 0.1940"
    assert np.abs(GridSurface.from_database(path).z - gaussian().z).max() <= 5e-5
    assert GridSurface.from_database(str(path)).nx == 11


def test_database_accepts_any_whitespace():
    reference = read("0 1 0 2\n2 2\n0 0 5\n1 0 6\n0 2 7\n1 2 8\n")
    for text in (
        "0 1 0 2 2 2 0 0 5 1 0 6 0 2 7 1 2 8",
        "\t0\t1  0 2\r\n2\n2\r\n0 0 5 1 0 6\n\n0 2\n7 1 2 8",
        "  0.0 1e0 0 2.0\n 2 2\n0 0 5.0000\n1 0 6\n0 2 7\n1 2 8",
    ):
        surface = read(text)
        assert all(np.array_equal(getattr(surface, n), getattr(reference, n)) for n in "xyz")


def test_database_from_a_binary_file():
    assert (
        GridSurface.from_database(io.BytesIO(b"0 1 0 1\n2 2\n0 0 1\n1 0 2\n0 1 3\n1 1 4\n")).z[1, 1]
        == 4
    )


GOOD = "0 1 0 2\n2 2\n0 0 5\n1 0 6\n0 2 7\n1 2 8\n"


@pytest.mark.parametrize(
    "text, message",
    [
        ("0 1 0 2\n2", r"line 2: expected 'Xmin Xmax Ymin Ymax' and 'Nx Ny'"),
        ("0 1 0 2\n2 two\n", r"line 2: Ny must be an int; got 'two'"),
        ("0 1 0 2\n1 2\n0 0 5\n0 2 7\n", r"line 2: Nx must be >= 2; got 1"),
        (
            GOOD.replace("1 2 8\n", ""),
            r"line 5: expected 4 triplets \(Nx \* Ny = 2 \* 2\); found only 3",
        ),
        (GOOD + "9\n", r"line 7: expected 4 triplets .*found an extra number"),
        (GOOD.replace("1 0 6", "1 0 six"), r"line 4: 'six' is not a number"),
        (GOOD.replace("0 2 7", "0 2 nan"), r"line 5: values must be finite; got 'nan'"),
        (
            GOOD.replace("1 0 6", "0 0 6"),
            r"line 4: triplet 2 has x = 0.0, not above the previous 0.0",
        ),
        (
            GOOD.replace("0 2 7", "0 0 7"),
            r"line 5: triplet 3 has y = 0.0, not above the previous 0.0",
        ),
        (
            GOOD.replace("1 2 8", "1.5 2 8"),
            r"line 6: triplet 4 has x = 1.5, but column 1 of row 1 has x = 1.0",
        ),
        (
            GOOD.replace("1 2 8", "1 2.5 8"),
            r"line 6: triplet 4 has y = 2.5, but its row starts with y = 2.0",
        ),
        (GOOD.replace("0 1 0 2", "0 1 0 3"), r"line 1: Ymax is 3.0 but the grid's is 2.0"),
    ],
)
def test_database_errors_name_the_line(text, message):
    with pytest.raises(ValueError, match="database " + message):
        read(text)


def test_database_rejects_a_bad_destination_and_precision():
    with pytest.raises(TypeError, match="'path_or_file' must be a path or a text file"):
        GridSurface.from_database(42)
    with pytest.raises(ValueError, match="'z_decimals' must be >= 0"):
        gaussian(3).to_database(io.StringIO(), z_decimals=-1)


def test_database_read_is_bounded_by_the_file_limit():
    with file_limit(100), pytest.raises(ResourceLimitError, match="file limit"):
        GridSurface.from_database(io.StringIO("0 " * 100))


def test_database_header_claiming_a_huge_grid_allocates_nothing():
    with pytest.raises(ValueError, match="expected 1000000000000 triplets"):
        read("0 1 0 1\n1000000 1000000\n0 0 0\n")


# --- the mesh ---------------------------------------------------------------------------------


def element_of(surface, points):
    """Grid element k = r (Nx - 1) + c containing each (x, y) point strictly inside a cell."""
    c = np.searchsorted(surface.x, points[:, 0]) - 1
    r = np.searchsorted(surface.y, points[:, 1]) - 1
    return r * (surface.nx - 1) + c


@settings(max_examples=25)
@given(small_grids())
def test_mesh_follows_facet_order(surface):
    mesh = surface.to_mesh()
    assert isinstance(mesh, Mesh) and not mesh.closed
    assert len(mesh.faces) == 2 * surface.facets
    grid_x, grid_y = np.meshgrid(surface.x, surface.y)
    assert np.array_equal(
        mesh.positions, np.column_stack([grid_x.ravel(), grid_y.ravel(), surface.z.ravel()])
    )
    triangles = mesh.positions[np.array([face.tolist() for face in mesh.faces])]
    centroids = triangles.mean(axis=1)
    assert np.array_equal(element_of(surface, centroids), np.arange(len(mesh.faces)) // 2)
    edge1, edge2 = (
        triangles[:, 1, :2] - triangles[:, 0, :2],
        triangles[:, 2, :2] - triangles[:, 0, :2],
    )
    signed = edge1[:, 0] * edge2[:, 1] - edge1[:, 1] * edge2[:, 0]
    assert (signed > 0).all()  # counter-clockwise seen from +z
    cell_area = np.outer(np.diff(surface.y), np.diff(surface.x)).ravel()
    assert np.allclose(signed[0::2] / 2 + signed[1::2] / 2, cell_area)


def test_mesh_splits_along_the_lower_left_to_upper_right_diagonal():
    surface = GridSurface.from_function(lambda x, y: x * y, (0, 3), (0, 2), 4, 3)
    faces = [face.tolist() for face in surface.to_mesh().faces]
    k = 1 * 3 + 2  # element (c, r) = (2, 1); corners v = r Nx + c = 6, 7, 10, 11
    assert faces[2 * k] == [6, 7, 11] and faces[2 * k + 1] == [6, 11, 10]


@settings(max_examples=20)
@given(small_grids())
def test_mesh_edges_are_the_grid_edges_plus_one_diagonal_per_facet(surface):
    faces = np.array([face.tolist() for face in surface.to_mesh().faces])
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    unique = len(np.unique(edges, axis=0))
    assert unique == surface.edges + surface.facets
    assert surface.nx * surface.ny - unique + len(faces) == 1  # Euler: an open disk


def test_counts_of_a_rectangular_grid():
    surface = GridSurface.random(5, 3)
    assert (surface.nx, surface.ny, surface.facets, surface.edges) == (5, 3, 8, 5 * 2 + 3 * 4)


# --- built-in surfaces ------------------------------------------------------------------------


def test_builtin_surfaces():
    assert set(BUILTIN_SURFACES) == {"gaussian", "polynomial", "rogers", "random"}
    for name, make in BUILTIN_SURFACES.items():
        surface = make(n=5)
        assert isinstance(surface, GridSurface) and (surface.nx, surface.ny) == (5, 5), name
    assert (gaussian().nx, polynomial().nx) == (11, 30)
    assert gaussian().z[5, 5] == 1.0
    assert (polynomial().x[0], polynomial().y[-1]) == (-1.2, 1.2)
    p = polynomial(5)
    assert p.z[0, 0] == pytest.approx(1.2**4 - 2 * 1.44) and p.z[2, 2] == 0.0
    r = rogers(5)
    assert (r.x[0], r.x[-1]) == (0.0, 2 * math.pi)
    assert r.z[2, 2] == pytest.approx(-1.5, abs=1e-15)  # a = 0 at (pi, pi)
    x, y = r.x[1], r.y[3]  # (pi/2, 3 pi/2)
    a = (x - math.pi) ** 2 + (y - math.pi) ** 2
    expected = 0.2 * math.sin(x) * math.cos(y) - 1.5 * math.cos(1.75 * a) * math.exp(-a)
    assert r.z[3, 1] == pytest.approx(expected, rel=1e-14)
    assert np.array_equal(random_surface(6, seed=4).z, GridSurface.random(6, 6, seed=4).z)

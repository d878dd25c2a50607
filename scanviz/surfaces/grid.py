"""Grid surfaces z = f(x, y): uniform and non-uniform grids, the database format, meshes.

A grid surface (Wang 1989, ch. 2) is the height field z = f(x, y) cut by Nx
planes x = const and Ny planes y = const. Grid point (i, j) is
(x[i], y[j], z[j, i]): ``z`` is indexed row first (y), like an image. The
cell between adjacent grid lines is a *grid element*; there are
(Nx - 1)(Ny - 1) of them (the *facets* once projected) and
Nx(Ny - 1) + Ny(Nx - 1) grid edges.

Database order lists the points with x varying fastest:
(x1, y1), (x2, y1), ..., (xNx, y1), (x1, y2), ..., (xNx, yNy); point (i, j)
is number ``j * Nx + i`` (0-based). Element (c, r) -- column c along x, row r
along y, 0-based -- is number ``k = r * (Nx - 1) + c``. Derivations and the
file format: ``docs/surfaces.md``.
"""

from __future__ import annotations

import math
import numbers
import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import TextIO

import numpy as np

from ..conventions import as_array
from ..limits import (
    ResourceLimitError,
    check_memory,
    current_file_limit,
    format_size,
    read_bounded,
)
from ..scene.model import Light, Material, Mesh, Scene, SceneObject
from .view import View

_BYTES_PER_POINT = 64  # z, the two sampling coordinates and f's temporaries
_BYTES_PER_TRIANGLE = 400  # Mesh keeps one index array per face (scene/builtin.py measured it)
_BYTES_PER_DATABASE_POINT = 160  # the text, its tokens and the parsed floats


def _check_points(nx: int, ny: int, what: str, per_point: int = _BYTES_PER_POINT) -> None:
    """Refuse, before allocating, a grid whose estimated size is over the memory limit."""
    check_memory(per_point * nx * ny, f"{what} of {nx}x{ny} points")


def _axis(name: str, value: object) -> np.ndarray:
    """`value` as a read-only, finite, strictly increasing float64 vector of >= 2 entries."""
    axis = as_array(value, f"{name!r} must be a 1-D array of numbers", copy=True, got=repr)
    if axis.ndim != 1 or axis.size < 2:
        raise ValueError(
            f"{name!r} must be a 1-D array of at least 2 values; got shape {axis.shape}"
        )
    bad = np.flatnonzero(~np.isfinite(axis))
    if bad.size:
        raise ValueError(f"{name!r} must be finite; {name}[{bad[0]}] is {axis[bad[0]]}")
    steps = np.flatnonzero(np.diff(axis) <= 0)
    if steps.size:
        i = steps[0] + 1
        raise ValueError(
            f"{name!r} must be strictly increasing; {name}[{i}] = {float(axis[i])!r} "
            f"<= {name}[{i - 1}] = {float(axis[i - 1])!r}"
        )
    axis.setflags(write=False)
    return axis


def _count(name: str, value: object, low: int = 2) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name!r} must be an int; got {value!r}")
    if value < low:
        raise ValueError(f"{name!r} must be >= {low}; got {value}")
    return int(value)


def _interval(name: str, value: object) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in value)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise TypeError(f"{name!r} must be a pair of numbers (low, high); got {value!r}") from None
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ValueError(f"{name!r} must be finite with low < high; got {(low, high)}")
    return low, high


def _uniform_axis(low: float, high: float, n: int) -> np.ndarray:
    """n equally spaced values from low to high, both ends exact.

    The weighted form (low (n-1-i) + high i) / (n-1) equals low + i D with
    D = (high - low) / (n - 1) in real arithmetic and gives the nearest double
    to decimal grids (-0.8, not -0.7999999999999999).
    """
    i = np.arange(n, dtype=np.float64)
    return (low * (n - 1 - i) + high * i) / (n - 1)


def _sample(f: Callable, x: np.ndarray, y: np.ndarray, vectorized: bool) -> np.ndarray:
    """z[j, i] = f(x[i], y[j]), checked to be real and finite."""
    if not callable(f):
        raise TypeError(f"'f' must be callable; got {f!r}")
    shape = (len(y), len(x))
    if vectorized:
        grid_x, grid_y = np.meshgrid(x, y)
        try:
            values = f(grid_x, grid_y)
        except TypeError as error:  # math.exp and friends refuse arrays
            raise TypeError(
                f"'f' failed on (Ny, Nx) arrays ({error}); pass vectorized=False for a scalar f"
            ) from error
    else:
        values = [[f(float(xi), float(yj)) for xi in x] for yj in y]
    try:
        z = np.broadcast_to(np.asarray(values, dtype=np.float64), shape).copy()
    except (TypeError, ValueError):
        raise ValueError(f"'f' must return real heights of shape {shape} (or a scalar)") from None
    bad = np.argwhere(~np.isfinite(z))
    if bad.size:
        j, i = bad[0]
        raise ValueError(f"'f' must be finite; f({float(x[i])!r}, {float(y[j])!r}) = {z[j, i]}")
    return z


def _fill_gaps(indices: np.ndarray, ratio: int) -> np.ndarray:
    """Insert s + R, s + 2R, ... into every gap of sorted `indices` wider than R (the max step)."""
    kept = [int(indices[0])]
    for following in indices[1:]:
        kept.extend(range(kept[-1] + ratio, int(following), ratio))
        kept.append(int(following))
    return np.array(kept, dtype=np.int64)


@dataclass(frozen=True, eq=False)
class GridSurface:
    """A height field sampled on a rectilinear grid (uniform or not).

    Parameters
    ----------
    x : (Nx,) array_like of float
        The planes x = const, finite, strictly increasing, Nx >= 2.
    y : (Ny,) array_like of float
        The planes y = const, finite, strictly increasing, Ny >= 2.
    z : (Ny, Nx) array_like of float
        Finite heights; ``z[j, i]`` is the height at ``(x[i], y[j])``.

    All three are stored as read-only float64 arrays. A grid over the memory
    limit (`scanviz.limits.check_memory`, 64 bytes per point) is refused.

    Examples
    --------
    >>> s = GridSurface([0.0, 1.0, 3.0], [0.0, 2.0], [[0, 1, 2], [3, 4, 5]])
    >>> float(s.z[1, 0]), s.facets, s.edges
    (3.0, 2, 7)
    """

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray

    def __post_init__(self) -> None:
        x, y = _axis("x", self.x), _axis("y", self.y)
        _check_points(len(x), len(y), "a grid surface")
        try:
            z = np.array(self.z, dtype=np.float64)
        except (TypeError, ValueError):  # ragged rows or non-numbers
            raise ValueError(
                f"'z' must be a rectangular (Ny, Nx) = ({len(y)}, {len(x)}) array of numbers"
            ) from None
        if z.shape != (len(y), len(x)):
            raise ValueError(f"'z' must have shape (Ny, Nx) = ({len(y)}, {len(x)}); got {z.shape}")
        bad = np.argwhere(~np.isfinite(z))
        if bad.size:
            j, i = bad[0]
            raise ValueError(f"'z' must be finite; z[{j}, {i}] is {z[j, i]}")
        z.setflags(write=False)
        for name, value in (("x", x), ("y", y), ("z", z)):
            object.__setattr__(self, name, value)

    # --- construction ---------------------------------------------------------------------

    @classmethod
    def from_function(
        cls,
        f: Callable,
        x_range: tuple[float, float],
        y_range: tuple[float, float],
        nx: int,
        ny: int,
        *,
        vectorized: bool = True,
    ) -> GridSurface:
        """The uniform grid of Wang's §2.2: Nx x Ny points, ends included.

        Parameters
        ----------
        f : callable
            ``f(x, y)``. With ``vectorized=True`` (the default) it is called
            once with two (Ny, Nx) float64 arrays (``numpy.meshgrid`` of the
            axes) and returns heights of that shape or a scalar (broadcast).
            With ``vectorized=False`` it is called once per point with two
            Python floats, in database order, and returns a number.
        x_range, y_range : (2,) tuple of float
            (Xmin, Xmax) and (Ymin, Ymax), finite, low < high.
        nx, ny : int
            Number of planes x = const and y = const, each >= 2.

        Returns
        -------
        GridSurface
            x_i = Xmin + i Dx with Dx = (Xmax - Xmin) / (Nx - 1), i = 0..Nx-1
            (both ends exact), likewise y; z[j, i] = f(x_i, y_j).

        Examples
        --------
        >>> s = GridSurface.from_function(lambda x, y: x + 10 * y, (0, 1), (0, 1), 3, 2)
        >>> s.x.tolist(), s.z.tolist()
        ([0.0, 0.5, 1.0], [[0.0, 0.5, 1.0], [10.0, 10.5, 11.0]])
        >>> float(GridSurface.from_function(math.hypot, (0, 1), (0, 1), 2, 2, vectorized=False).z[1, 1])
        1.4142135623730951
        """
        x_range, y_range = _interval("x_range", x_range), _interval("y_range", y_range)
        nx, ny = _count("nx", nx), _count("ny", ny)
        _check_points(nx, ny, "GridSurface.from_function")
        x, y = _uniform_axis(*x_range, nx), _uniform_axis(*y_range, ny)
        return cls(x, y, _sample(f, x, y, vectorized))

    @classmethod
    def nonuniform(
        cls,
        f: Callable,
        x_range: tuple[float, float],
        y_range: tuple[float, float],
        nmax_x: int,
        nmax_y: int,
        ratio_x: int,
        ratio_y: int,
        z_tolerance: float,
        *,
        max_step: bool = True,
        vectorized: bool = True,
    ) -> GridSurface:
        """The non-uniform grid of Wang's §2.2: keep the planes where the surface bends.

        Parameters
        ----------
        f : callable
            As in `from_function` (and `vectorized` likewise).
        x_range, y_range : (2,) tuple of float
            The domain, finite, low < high.
        nmax_x, nmax_y : int
            Planes of the finest, temporary uniform grid (Nmaxx, Nmaxy), >= 2.
        ratio_x, ratio_y : int
            Rx, Ry >= 1: the largest step between kept planes is Rx (Ry)
            temporary steps, Dmax = Dmin * R.
        z_tolerance : float
            Zt >= 0, finite.
        max_step : bool
            Enforce the maximum step Dmax (default). The dissertation states
            the rule in its prose but its pseudo-code omits it; False runs the
            pseudo-code alone.

        Returns
        -------
        GridSurface
            The temporary grid's points on the kept planes (same heights).

        Notes
        -----
        On the temporary grid (0-based indices a along x, b along y), for
        every interior point 1 <= a <= Nmaxx-2, 1 <= b <= Nmaxy-2 with
        abs(z[b, a] - z[b, a-1]) + abs(z[b, a] - z[b-1, a]) > Zt, the planes
        a-1, a and b-1, b are kept; the first and last planes always are.
        With `max_step`, each gap between consecutive kept planes wider
        than R steps gets the planes s + R, s + 2R, ... (< the next kept
        plane) from its lower end s (spec §1.3 [REC]; it reproduces the
        28 x 28 planes the dissertation reports for x**4 - x**2 - y**2).

        Examples
        --------
        >>> s = GridSurface.nonuniform(lambda x, y: x**4 - x**2 - y**2, (-1.2, 1.2), (-1.2, 1.2),
        ...                            66, 42, 3, 3, 0.23)
        >>> len(s.x), len(s.y)
        (28, 28)
        """
        x_range, y_range = _interval("x_range", x_range), _interval("y_range", y_range)
        nmax_x, nmax_y = _count("nmax_x", nmax_x), _count("nmax_y", nmax_y)
        ratio_x, ratio_y = _count("ratio_x", ratio_x, 1), _count("ratio_y", ratio_y, 1)
        if isinstance(z_tolerance, bool) or not isinstance(z_tolerance, numbers.Real):
            raise TypeError(f"'z_tolerance' must be a number; got {z_tolerance!r}")
        if not (math.isfinite(z_tolerance) and z_tolerance >= 0):
            raise ValueError(f"'z_tolerance' must be finite and >= 0; got {z_tolerance}")
        _check_points(nmax_x, nmax_y, "GridSurface.nonuniform's temporary grid")
        x, y = _uniform_axis(*x_range, nmax_x), _uniform_axis(*y_range, nmax_y)
        z = _sample(f, x, y, vectorized)
        inner = z[1:-1, 1:-1]
        bends = np.abs(inner - z[1:-1, :-2]) + np.abs(inner - z[:-2, 1:-1]) > z_tolerance
        kept = []
        for marks, n, ratio in (
            (bends.any(axis=0), nmax_x, ratio_x),
            (bends.any(axis=1), nmax_y, ratio_y),
        ):
            a = np.flatnonzero(marks) + 1  # interior index of each bending plane
            indices = np.unique(np.concatenate([[0, n - 1], a - 1, a]))
            kept.append(_fill_gaps(indices, ratio) if max_step else indices)
        columns, rows = kept
        return cls(x[columns], y[rows], z[np.ix_(rows, columns)])

    @classmethod
    def random(
        cls,
        nx: int,
        ny: int,
        seed: int = 0,
        x_range: tuple[float, float] = (-2.0, 2.0),
        y_range: tuple[float, float] = (-2.0, 2.0),
    ) -> GridSurface:
        """A uniform grid with independent uniform random heights in [0, 1).

        Parameters
        ----------
        nx, ny : int
            Grid points along x and y, >= 2.
        seed : int
            Seed (>= 0) of ``numpy.random.default_rng`` (PCG64).
        x_range, y_range : (2,) tuple of float
            The domain; the default [-2, 2]^2 is that of Wang's Figs 2-7/2-8.

        Returns
        -------
        GridSurface
            ``z = default_rng(seed).random((ny, nx))``: heights drawn in
            database order (x fastest), i.i.d. uniform on [0, 1).

        Examples
        --------
        >>> s = GridSurface.random(3, 2, seed=7)
        >>> bool((s.z == np.random.default_rng(7).random((2, 3))).all())
        True
        """
        if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
            raise TypeError(f"'seed' must be an int >= 0; got {seed!r}")
        x_range, y_range = _interval("x_range", x_range), _interval("y_range", y_range)
        nx, ny = _count("nx", nx), _count("ny", ny)
        _check_points(nx, ny, "GridSurface.random")
        z = np.random.default_rng(int(seed)).random((ny, nx))
        return cls(_uniform_axis(*x_range, nx), _uniform_axis(*y_range, ny), z)

    # --- counts ---------------------------------------------------------------------------

    @property
    def nx(self) -> int:
        """Number of planes x = const (grid points along x)."""
        return len(self.x)

    @property
    def ny(self) -> int:
        """Number of planes y = const (grid points along y)."""
        return len(self.y)

    @property
    def facets(self) -> int:
        """Number of grid elements (facets), (Nx - 1)(Ny - 1)."""
        return (self.nx - 1) * (self.ny - 1)

    @property
    def edges(self) -> int:
        """Number of grid edges, Nx(Ny - 1) + Ny(Nx - 1)."""
        return self.nx * (self.ny - 1) + self.ny * (self.nx - 1)

    # --- the database format (Table 2-1) --------------------------------------------------

    def to_database(
        self, path_or_file: str | os.PathLike | TextIO, *, z_decimals: int | None = 4
    ) -> None:
        """Write the plain-text database of Wang's Table 2-1.

        Parameters
        ----------
        path_or_file : str, path or text file
            Where to write (a path is created or overwritten, UTF-8).
        z_decimals : int or None
            Heights are printed with this many decimals, 4 as the table does;
            None prints the shortest text that reads back exactly. Coordinates
            are always printed exactly (shortest round-trip text).

        Notes
        -----
        Line 1 ``Xmin Xmax Ymin Ymax``, line 2 ``Nx Ny``, then one line
        ``x y z`` per point in database order (x fastest).

        Examples
        --------
        >>> import io
        >>> buffer = io.StringIO()
        >>> GridSurface([0.0, 0.5], [1.0, 2.0], [[1, 2], [3, 4.25]]).to_database(buffer)
        >>> print(buffer.getvalue(), end="")
        0.0 0.5 1.0 2.0
        2 2
        0.0 1.0 1.0000
        0.5 1.0 2.0000
        0.0 2.0 3.0000
        0.5 2.0 4.2500
        """
        if z_decimals is not None:
            z_decimals = _count("z_decimals", z_decimals, 0)
        text = self._database_text(z_decimals)
        if hasattr(path_or_file, "write"):
            path_or_file.write(text)  # type: ignore[union-attr]
            return
        with open(path_or_file, "w", encoding="utf-8", newline="\n") as file:  # type: ignore[arg-type]
            file.write(text)

    def _database_text(self, z_decimals: int | None) -> str:
        height = repr if z_decimals is None else f"{{:.{z_decimals}f}}".format
        xs, ys = [repr(float(v)) for v in self.x], [repr(float(v)) for v in self.y]
        header = [f"{xs[0]} {xs[-1]} {ys[0]} {ys[-1]}", f"{self.nx} {self.ny}"]
        heights = self.z.tolist()
        rows = (
            f"{xs[i]} {ys[j]} {height(heights[j][i])}"
            for j in range(self.ny)
            for i in range(self.nx)
        )
        return "\n".join([*header, *rows]) + "\n"

    @classmethod
    def from_database(cls, path_or_file: str | os.PathLike | TextIO) -> GridSurface:
        """Read the plain-text database of Wang's Table 2-1 (see `to_database`).

        Parameters
        ----------
        path_or_file : str, path or text file
            Tokens may be separated by any whitespace, lines broken anywhere.
            Files are bounded by `scanviz.limits.current_file_limit`.

        Returns
        -------
        GridSurface

        Raises
        ------
        ValueError
            Naming the line: a missing or extra number, a count that is not an
            int >= 2, a non-finite value, triplets that do not form the grid
            (x must repeat row by row, y be constant along a row, both
            strictly increase), or a header that disagrees with the grid.

        Examples
        --------
        >>> import io
        >>> text = "0 1  0 2\\n2 2\\n0 0 5\\n1 0 6\\n0 2 7\\n1 2 8\\n"
        >>> GridSurface.from_database(io.StringIO(text)).z.tolist()
        [[5.0, 6.0], [7.0, 8.0]]
        >>> GridSurface.from_database(io.StringIO(text.replace("0 2 7", "0 3 7")))
        Traceback (most recent call last):
        ...
        ValueError: database line 6: triplet 4 has y = 2.0, but its row starts with y = 3.0
        """
        return _parse_database(_read_text(path_or_file))

    # --- the mesh -------------------------------------------------------------------------

    def points(self) -> np.ndarray:
        """The grid points (x[i], y[j], z[j, i]) as an (Nx Ny, 3) array, in database order.

        Point ``j * Nx + i`` is grid point (column i, row j): the vertex order of
        `to_mesh` and of Table 2-1.

        >>> GridSurface([0.0, 1.0], [0.0, 2.0], [[0, 1], [2, 3]]).points().tolist()
        [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [0.0, 2.0, 2.0], [1.0, 2.0, 3.0]]
        """
        grid_x, grid_y = np.meshgrid(self.x, self.y)
        return np.stack([grid_x, grid_y, self.z], axis=-1).reshape(-1, 3)

    def scene(
        self,
        view: View,
        width: int,
        height: int,
        *,
        material: Material | None = None,
        smooth: bool = True,
        background: tuple[float, float, float] = (1.0, 1.0, 1.0),
    ) -> Scene:
        """The scanviz `Scene` of this surface as the Floating Perimeter Algorithm sees it.

        The mesh of `to_mesh` (open, so nothing is culled) and the camera
        `View.camera` fits to the grid points: ``render(scene, width,
        height).polygon // 2`` is the facet (grid element) index k = r (Nx - 1) + c
        of each pixel, the z-buffer answer to compare the FPA with. The fitted
        points lie half a pixel inside the window, so the clipper cuts no
        triangle and keeps the polygon numbering. One white directional light
        shines straight down (-z).

        Parameters
        ----------
        view : View
        width, height : int
            Raster size, each at least 2.
        material : Material, optional
            The surface's material (default: `Material()`).
        smooth : bool
            Vertex normals averaged across facets (True) or flat facets.
        background : RGB
            Default white, as the hidden-line drawings.

        Raises
        ------
        TypeError
            If `view` is not a View.
        ValueError
            As `View.camera` (a grid point behind a perspective viewpoint, a
            raster under 2 x 2).

        Examples
        --------
        >>> from scanviz import render
        >>> surface = GridSurface.from_function(lambda x, y: x * y, (0, 1), (0, 1), 3, 3)
        >>> result = render(surface.scene(View((0.5, -3, 3), (0, 1, -1)), 12, 12), 12, 12)
        >>> sorted(set((result.visibility.polygon[result.visibility.polygon >= 0] // 2).tolist()))
        [0, 1, 2, 3]
        """
        if not isinstance(view, View):
            raise TypeError(f"'view' must be a scanviz.surfaces.View; got {type(view).__name__}")
        points = self.points()
        camera = view.camera(width, height, points)
        obj = SceneObject(
            mesh=self.to_mesh(smooth=smooth),
            material=Material() if material is None else material,
            name="grid surface",
        )
        return Scene(
            objects=(obj,),
            camera=camera,
            lights=(Light(direction=(0.0, 0.0, -1.0)),),
            background=tuple(background),
            name=f"{self.nx}x{self.ny} grid surface",
        )

    def to_mesh(self, *, smooth: bool = True) -> Mesh:
        """Two triangles per grid element, in facet order, as an open `Mesh`.

        Parameters
        ----------
        smooth : bool
            Passed to `Mesh` (average vertex normals across faces).

        Returns
        -------
        Mesh
            Vertex ``j * Nx + i`` is (x[i], y[j], z[j, i]) (database order).
            Element (c, r) with k = r (Nx - 1) + c gives faces 2k and 2k + 1,
            split along its diagonal from (c, r) to (c + 1, r + 1):
            face 2k = (v, v + 1, v + Nx + 1) (below the diagonal) and face
            2k + 1 = (v, v + Nx + 1, v + Nx) (above it), v = r Nx + c, both
            counter-clockwise seen from +z. So ``face // 2`` is the element
            index k. ``closed`` is False.

        Examples
        --------
        >>> mesh = GridSurface.from_function(lambda x, y: 0 * x, (0, 2), (0, 1), 3, 2).to_mesh()
        >>> [face.tolist() for face in mesh.faces]
        [[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]]
        """
        check_memory(
            _BYTES_PER_TRIANGLE * 2 * self.facets,
            f"the mesh of a {self.nx}x{self.ny} grid surface ({2 * self.facets:,} triangles)",
        )
        positions = self.points()
        row, column = np.divmod(np.arange(self.facets), self.nx - 1)
        v = row * self.nx + column  # lower-left corner of element k
        below = np.stack([v, v + 1, v + self.nx + 1], axis=1)
        above = np.stack([v, v + self.nx + 1, v + self.nx], axis=1)
        faces = np.stack([below, above], axis=1).reshape(-1, 3)
        return Mesh(positions, faces, smooth=bool(smooth), closed=False)


def _read_text(path_or_file: str | os.PathLike | TextIO) -> str:
    """The whole text of a path or an open file, bounded by the file limit."""
    if not hasattr(path_or_file, "read"):
        if not isinstance(path_or_file, str | os.PathLike):
            raise TypeError(f"'path_or_file' must be a path or a text file; got {path_or_file!r}")
        return read_bounded(path_or_file)  # type: ignore[return-value]
    limit = current_file_limit()
    text = path_or_file.read(limit + 1)  # type: ignore[union-attr]
    if isinstance(text, bytes):
        text = text.decode("utf-8-sig")
    if len(text) > limit:
        raise ResourceLimitError(
            f"the database is longer than the file limit of {format_size(limit)} "
            "(raise it with scanviz.limits.file_limit(...))"
        )
    return text


class _Tokens:
    """The whitespace-separated tokens of a text, with the line each one is on."""

    def __init__(self, text: str) -> None:
        self.lines = text.splitlines()
        self.words = text.split()

    def line(self, index: int) -> int:
        """1-based line of token `index` (a token past the end: the last line)."""
        seen = 0
        for number, line in enumerate(self.lines, 1):
            seen += len(line.split())
            if seen > index:
                return number
        return max(len(self.lines), 1)

    def error(self, index: int, message: str) -> ValueError:
        return ValueError(f"database line {self.line(index)}: {message}")


def _parse_database(text: str) -> GridSurface:
    tokens = _Tokens(text)
    words = tokens.words
    if len(words) < 6:
        raise tokens.error(
            len(words), f"expected 'Xmin Xmax Ymin Ymax' and 'Nx Ny'; got {len(words)} numbers"
        )
    counts = []
    for index, name in ((4, "Nx"), (5, "Ny")):
        try:
            counts.append(int(words[index]))
        except ValueError:
            raise tokens.error(index, f"{name} must be an int; got {words[index]!r}") from None
        if counts[-1] < 2:
            raise tokens.error(index, f"{name} must be >= 2; got {counts[-1]}")
    nx, ny = counts
    expected = 6 + 3 * nx * ny
    if len(words) != expected:
        where = min(len(words), expected)
        found = "an extra number" if len(words) > expected else f"only {(len(words) - 6) / 3:g}"
        raise tokens.error(
            where, f"expected {nx * ny} triplets (Nx * Ny = {nx} * {ny}); found {found}"
        )
    _check_points(nx, ny, "a grid surface database", _BYTES_PER_DATABASE_POINT)
    numbers_ = _floats(tokens, [0, 1, 2, 3, *range(6, expected)])
    header, grid = numbers_[:4], numbers_[4:].reshape(ny, nx, 3)
    _check_grid(tokens, grid)
    x, y = grid[0, :, 0], grid[:, 0, 1]
    for slot, (name, value) in enumerate(
        (("Xmin", x[0]), ("Xmax", x[-1]), ("Ymin", y[0]), ("Ymax", y[-1]))
    ):
        if header[slot] != value:
            raise tokens.error(
                slot, f"{name} is {float(header[slot])!r} but the grid's is {float(value)!r}"
            )
    return GridSurface(x, y, grid[:, :, 2])


def _floats(tokens: _Tokens, indices: list[int]) -> np.ndarray:
    """Tokens at `indices` as finite float64 (an error names the first bad one's line)."""
    words = [tokens.words[i] for i in indices]
    try:
        values = np.array(words, dtype=np.float64)
    except ValueError:  # find the culprit only when there is one
        bad = next(k for k, word in enumerate(words) if not _is_float(word))
        raise tokens.error(indices[bad], f"{words[bad]!r} is not a number") from None
    infinite = np.flatnonzero(~np.isfinite(values))
    if infinite.size:
        k = infinite[0]
        raise tokens.error(indices[k], f"values must be finite; got {words[k]!r}")
    return values


def _is_float(word: str) -> bool:
    try:
        float(word)
    except ValueError:
        return False
    return True


def _check_grid(tokens: _Tokens, grid: np.ndarray) -> None:
    """Triplets (Ny, Nx, 3) must repeat the first row's x and keep y along each row."""
    ny, nx, _ = grid.shape

    def fail(point: int, coordinate: int, message: str) -> ValueError:
        return tokens.error(6 + 3 * point + coordinate, f"triplet {point + 1} {message}")

    x, y = grid[0, :, 0], grid[:, 0, 1]
    for axis, name, stride, coordinate in ((x, "x", 1, 0), (y, "y", nx, 1)):
        drop = np.flatnonzero(np.diff(axis) <= 0)
        if drop.size:
            k = drop[0] + 1
            previous, value = float(axis[k - 1]), float(axis[k])
            raise fail(
                k * stride,
                coordinate,
                f"has {name} = {value!r}, not above the previous {previous!r}",
            )
    p = _first(grid[:, :, 0] != x)
    if p is not None:
        value, expected = float(grid[:, :, 0].flat[p]), float(x[p % nx])
        raise fail(p, 0, f"has x = {value!r}, but column {p % nx} of row 1 has x = {expected!r}")
    p = _first(grid[:, :, 1] != y[:, None])
    if p is not None:
        value, expected = float(grid[:, :, 1].flat[p]), float(y[p // nx])
        raise fail(p, 1, f"has y = {value!r}, but its row starts with y = {expected!r}")


def _first(wrong: np.ndarray) -> int | None:
    """Flat index of the first True in `wrong`, or None."""
    hits = np.flatnonzero(wrong.ravel())
    return int(hits[0]) if hits.size else None


# --- built-in surfaces ------------------------------------------------------------------------


def gaussian_height(x, y):
    """exp(-x^2 - y^2), the surface of Wang's Table 2-1."""
    return np.exp(-x * x - y * y)


def polynomial_height(x, y):
    """x^4 - x^2 - y^2, the surface of Wang's Figs 2-5/2-6 (reconstructed, spec §1.3)."""
    return x**4 - x**2 - y**2


def rogers_height(x, y):
    """0.2 sin x cos y - 1.5 cos(1.75 a) exp(-a), a = (x - pi)^2 + (y - pi)^2 (Rogers 1985)."""
    a = (x - np.pi) ** 2 + (y - np.pi) ** 2
    return 0.2 * np.sin(x) * np.cos(y) - 1.5 * np.cos(1.75 * a) * np.exp(-a)


def gaussian(n: int = 11) -> GridSurface:
    """exp(-x^2 - y^2) on [-1, 1]^2, n x n points (n = 11 is Wang's Table 2-1).

    >>> gaussian().z[0, 0].round(4), gaussian().facets
    (np.float64(0.1353), 100)
    """
    return GridSurface.from_function(gaussian_height, (-1.0, 1.0), (-1.0, 1.0), n, n)


def polynomial(n: int = 30) -> GridSurface:
    """x^4 - x^2 - y^2 on [-1.2, 1.2]^2, n x n points (n = 30 is Wang's Fig 2-5).

    >>> polynomial().nx, float(polynomial(3).z[1, 1])
    (30, 0.0)
    """
    return GridSurface.from_function(polynomial_height, (-1.2, 1.2), (-1.2, 1.2), n, n)


def rogers(n: int = 41) -> GridSurface:
    """Rogers' sin-cos-exp surface (Wang's Figs 2-11/2-12) on [0, 2 pi]^2, n x n points.

    The dissertation does not give the domain; [0, 2 pi]^2 centres the
    ripple at (pi, pi) over one period of the sin cos term (spec §1.8 [EXT]).

    >>> round(float(rogers(3).z[1, 1]), 12)
    -1.5
    """
    return GridSurface.from_function(rogers_height, (0.0, 2 * np.pi), (0.0, 2 * np.pi), n, n)


def random_surface(n: int = 30, seed: int = 0) -> GridSurface:
    """Random heights in [0, 1) on [-2, 2]^2, n x n points (Wang's Fig 2-8); see `GridSurface.random`.

    >>> bool(random_surface(4).z.max() < 1.0)
    True
    """
    return GridSurface.random(n, n, seed)


BUILTIN_SURFACES: dict[str, Callable[..., GridSurface]] = {
    "gaussian": gaussian,
    "polynomial": polynomial,
    "rogers": rogers,
    "random": random_surface,
}
"""The built-in grid surfaces by name; each takes ``n`` (points per side)."""

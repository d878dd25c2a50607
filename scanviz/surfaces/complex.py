"""Complex functions as grid surfaces: height |F(x + iy)|, colour arg F (Wang 1989, §3.4).

A rational function F(s) = k (s - z1)...(s - z_nz) / ((s - p1)...(s - p_np))
is sampled on a uniform grid of s = x + iy. The grid surface has the heights
|F| (clipped, so that poles stay viewable peaks) and keeps the phases arg F
beside it; `phase_scene` colours each triangle of the surface through the
colour ring (`scanviz.shading.colour_ring`) by the dissertation's
per-triangle phase rule. Around a zero or a pole every colour of the ring
appears once: counter-clockwise green -> red -> blue around a zero, the
other way round a pole. Derivations and pictures: ``docs/colour-ring.md``.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..conventions import as_array, short_repr
from ..scene.model import Material, Scene, SceneObject
from ..shading.colour_ring import colour_ring, replace_entry, triangle_ring_index
from .grid import GridSurface, _check_points, _count, _interval, _uniform_axis
from .view import View

DEFAULT_CLIP = 4.0
"""Default height limit of `complex_surface`: about the width of the built-in's [-2, 2]^2 domain."""


def _complex_numbers(name: str, values: object) -> tuple[complex, ...]:
    try:
        items = tuple(values)  # type: ignore[arg-type]
    except TypeError:
        raise TypeError(
            f"{name!r} must be a sequence of complex numbers; got {short_repr(values)}"
        ) from None
    for i, value in enumerate(items):
        if isinstance(value, bool) or not isinstance(value, numbers.Complex):
            raise TypeError(f"'{name}[{i}]' must be a complex number; got {short_repr(value)}")
        if not (math.isfinite(complex(value).real) and math.isfinite(complex(value).imag)):
            raise ValueError(f"'{name}[{i}]' must be finite; got {complex(value)}")
    return tuple(complex(value) for value in items)


@dataclass(frozen=True)
class RationalFunction:
    """F(s) = gain (s - z1)...(s - z_nz) / ((s - p1)...(s - p_np)), given by its zeros and poles.

    Parameters
    ----------
    zeros, poles : sequence of complex
        Finite; either may be empty (no zeros and no poles is the constant
        `gain`). Repeats are multiple zeros or poles; a zero equal to a pole
        is refused (they would cancel).
    gain : complex
        k, finite and nonzero (F = 0 has no phase).

    Examples
    --------
    >>> F = RationalFunction(zeros=[1], poles=[-1j], gain=2)
    >>> F(np.array([0, 1, 1j]))
    array([0.+2.j, 0.+0.j, 1.+1.j])
    """

    zeros: tuple[complex, ...] = ()
    poles: tuple[complex, ...] = ()
    gain: complex = 1.0

    def __post_init__(self) -> None:
        zeros, poles = _complex_numbers("zeros", self.zeros), _complex_numbers("poles", self.poles)
        gain = self.gain
        if isinstance(gain, bool) or not isinstance(gain, numbers.Complex):
            raise TypeError(f"'gain' must be a complex number; got {short_repr(gain)}")
        gain = complex(gain)
        if not (math.isfinite(gain.real) and math.isfinite(gain.imag)):
            raise ValueError(f"'gain' must be finite; got {gain}")
        if gain == 0:
            raise ValueError("'gain' must be nonzero (F = 0 has no phase to colour)")
        cancelled = sorted(set(zeros) & set(poles), key=lambda c: (c.real, c.imag))
        if cancelled:
            raise ValueError(
                f"a zero equal to a pole cancels; remove both: {cancelled[0]} is in 'zeros' "
                f"(index {zeros.index(cancelled[0])}) and 'poles' (index {poles.index(cancelled[0])})"
            )
        for name, value in (("zeros", zeros), ("poles", poles), ("gain", gain)):
            object.__setattr__(self, name, value)

    def __call__(self, s: object) -> np.ndarray:
        """F at each point of `s` (array_like of complex); not finite exactly at a pole."""
        s = np.asarray(s, dtype=np.complex128)
        values = np.full(s.shape, self.gain, dtype=np.complex128)
        for zero in self.zeros:
            values *= s - zero
        with np.errstate(divide="ignore", invalid="ignore"):  # a pole: numpy's inf/nan
            for pole in self.poles:
                values /= s - pole
        return values


@dataclass(frozen=True, eq=False)
class ComplexSurface:
    """A complex function sampled on a grid: the surface z = min(abs(F), clip) and arg F.

    Attributes
    ----------
    surface : GridSurface
        x[i], y[j] and the heights ``z[j, i] = min(|F(x[i] + i y[j])|, clip)``.
    values : (Ny, Nx) ndarray of complex128
        F at the grid points, read-only.
    phase : (Ny, Nx) ndarray of float64
        arg F in [-pi, pi] (``numpy.angle``), 0 where F = 0; read-only.
    clip : float or None
        The height limit applied (None: none).
    function : callable
        F.
    """

    surface: GridSurface
    values: np.ndarray
    phase: np.ndarray
    clip: float | None
    function: Callable

    @property
    def clipped(self) -> np.ndarray:
        """(Ny, Nx) bool: the grid points whose height `clip` cut down."""
        return np.abs(self.values) > (math.inf if self.clip is None else self.clip)

    def triangle_entries(self, steps: int = 64) -> np.ndarray:
        """The ring entry of each triangle of ``surface.to_mesh()`` (faces 2k, 2k + 1 of element k).

        Parameters
        ----------
        steps : int
            S of the ring of 3 S colours.

        Returns
        -------
        (2 (Nx - 1)(Ny - 1),) ndarray of int64
            `scanviz.shading.triangle_ring_index` of the phases at each
            face's vertices, in the face's vertex order.

        Examples
        --------
        F(s) = s on one element of [-1, 1]^2: face 0 has the phases -3pi/4, -pi/4
        and pi/4 (mean -pi/4, so 7pi/4: entry 167 of 192); face 1 has -3pi/4, pi/4
        and 3pi/4, which straddle the cut, so -3pi/4 counts as 5pi/4 (mean 3pi/4:
        entry 71).

        >>> result = complex_surface(RationalFunction(zeros=[0]), (-1, 1), (-1, 1), 2, 2)
        >>> result.triangle_entries(64).tolist()
        [167, 71]
        """
        return _entries(self, np.array(self.surface.to_mesh().faces), len(colour_ring(steps)))


def _entries(result: ComplexSurface, faces: np.ndarray, size: int) -> np.ndarray:
    return triangle_ring_index(result.phase.ravel()[faces], size)


def _clip(clip: object) -> float | None:
    if clip is None:
        return None
    if isinstance(clip, bool) or not isinstance(clip, numbers.Real):
        raise TypeError(f"'clip' must be a number or None; got {short_repr(clip)}")
    if not (math.isfinite(clip) and clip > 0):
        raise ValueError(f"'clip' must be finite and > 0 (or None); got {clip}")
    return float(clip)


def _pole_on_grid(function: object, x: np.ndarray, y: np.ndarray) -> None:
    poles = function.poles if isinstance(function, RationalFunction) else ()
    for index, pole in enumerate(poles):
        i, j = np.flatnonzero(x == pole.real), np.flatnonzero(y == pole.imag)
        if i.size and j.size:
            raise ValueError(
                f"pole {index} ({pole}) lies on grid point (i, j) = ({i[0]}, {j[0]}), "
                f"x + iy = {complex(x[i[0]], y[j[0]])}: |F| is infinite there; "
                "move the pole or change the grid"
            )


def complex_surface(
    function: Callable,
    x_range: tuple[float, float],
    y_range: tuple[float, float],
    nx: int,
    ny: int,
    *,
    clip: float | None = DEFAULT_CLIP,
) -> ComplexSurface:
    """Sample F(x + iy) on a uniform grid: heights abs(F) (clipped) and phases arg F.

    Parameters
    ----------
    function : callable
        F, called once with the (Ny, Nx) complex128 array s = x + iy of the
        grid points (``numpy.meshgrid`` of the axes); it returns complex
        values of that same shape. A `RationalFunction` is the usual F.
    x_range, y_range : (2,) tuple of float
        (Xmin, Xmax), (Ymin, Ymax), finite, low < high; ends included.
    nx, ny : int
        Grid points along x and y, each >= 2.
    clip : float or None
        Heights above `clip` are cut down to it (default `DEFAULT_CLIP` = 4),
        so a pole near a grid point is a plateau, not a spike of height
        1e15 that shrinks the rest of the surface to a line. None keeps
        abs(F) as it is. The phases are never clipped.

    Returns
    -------
    ComplexSurface

    Raises
    ------
    TypeError
        If `function` is not callable or returns non-numbers.
    ValueError
        If `function` returns another shape, a pole of a `RationalFunction` lies exactly on a grid point
        (naming the pole and the point), F is not finite at a grid point,
        abs(F) overflows with ``clip=None``, or an argument breaks its rule.

    Examples
    --------
    F(s) = s on [-1, 1]^2 with 2 x 2 points: heights sqrt(2), phases -3pi/4 .. 3pi/4.

    >>> result = complex_surface(RationalFunction(zeros=[0]), (-1, 1), (-1, 1), 2, 2)
    >>> result.surface.z.round(4).tolist(), (result.phase / np.pi).tolist()
    ([[1.4142, 1.4142], [1.4142, 1.4142]], [[-0.75, -0.25], [0.75, 0.25]])
    >>> complex_surface(RationalFunction(poles=[1 + 2j]), (-1, 1), (0, 2), 3, 2)
    Traceback (most recent call last):
    ...
    ValueError: pole 0 ((1+2j)) lies on grid point (i, j) = (2, 1), x + iy = (1+2j): |F| is infinite there; move the pole or change the grid
    """
    if not callable(function):
        raise TypeError(f"'function' must be callable; got {short_repr(function)}")
    x_range, y_range = _interval("x_range", x_range), _interval("y_range", y_range)
    nx, ny = _count("nx", nx), _count("ny", ny)
    clip = _clip(clip)
    _check_points(nx, ny, "complex_surface", per_point=96)  # s, F, |F|, arg F and the grid
    x, y = _uniform_axis(*x_range, nx), _uniform_axis(*y_range, ny)
    _pole_on_grid(function, x, y)
    grid_x, grid_y = np.meshgrid(x, y)
    returned = function(grid_x + 1j * grid_y)
    values = as_array(returned, "'function' must return complex numbers", dtype=np.complex128)
    if values.shape != grid_x.shape:
        raise ValueError(
            f"'function' must return an array of the grid's shape (Ny, Nx) = {grid_x.shape}; "
            f"got {values.shape}"
        )
    values = values.copy()  # F's own array stays F's
    _check_finite("F", values, x, y, "a pole on the grid?")
    with np.errstate(over="ignore"):
        modulus = np.abs(values)
    if clip is None:
        _check_finite("|F|", modulus, x, y, "overflow; pass clip= to bound the heights")
    heights = modulus if clip is None else np.minimum(modulus, clip)
    phase = np.where(values == 0, 0.0, np.angle(values))  # arg 0 is undefined: take 0
    for array in (values, phase):
        array.setflags(write=False)
    return ComplexSurface(GridSurface(x, y, heights), values, phase, clip, function)


def _check_finite(what: str, values: np.ndarray, x: np.ndarray, y: np.ndarray, hint: str) -> None:
    bad = np.argwhere(~np.isfinite(values))
    if bad.size:
        j, i = bad[0]
        raise ValueError(
            f"{what} must be finite at every grid point; at (i, j) = ({i}, {j}), "
            f"x + iy = {complex(x[i], y[j])}, it is {values[j, i]} ({hint})"
        )


THREE_POLES_TWO_ZEROS = RationalFunction(
    zeros=tuple(0.55 * np.exp(1j * np.radians(10.0 + 180.0 * k)) for k in range(2)),
    poles=tuple(1.25 * np.exp(1j * np.radians(100.0 + 120.0 * k)) for k in range(3)),
    gain=2.0,
)
"""The built-in F (Figs 3-9..3-12 give no positions): poles on an equilateral triangle,
1.25 e^{i(100° + 120° k)}, zeros the pair ±0.55 e^{i 10°}, gain 2. Turned by 10°
from the symmetric position, no pole has a coordinate 0 or a simple fraction, so no
uniform grid of [-2, 2]^2 puts a grid point on one (n = 2..400 checked)."""


def three_poles_two_zeros(n: int = 41, *, clip: float | None = DEFAULT_CLIP) -> ComplexSurface:
    """The built-in complex surface: `THREE_POLES_TWO_ZEROS` on [-2, 2]^2, n x n points.

    >>> result = three_poles_two_zeros()
    >>> result.surface.nx, float(result.surface.z.max())
    (41, 4.0)
    """
    return complex_surface(THREE_POLES_TWO_ZEROS, (-2.0, 2.0), (-2.0, 2.0), n, n, clip=clip)


def phase_scene(
    result: ComplexSurface,
    view: View,
    width: int,
    height: int,
    steps: int = 64,
    marker: int | None = None,
    *,
    background: tuple[float, float, float] = (0.0, 0.0, 0.0),
) -> Scene:
    """The scene of a complex surface, each triangle coloured by its phase through the ring.

    Parameters
    ----------
    result : ComplexSurface
    view : View
        As `GridSurface.scene`: ``View.camera`` fitted to the grid points.
    width, height : int
        Raster size, each at least 2.
    steps : int
        S of the ring of 3 S colours (64: the dissertation's 192).
    marker : int, optional
        A ring entry shown white instead (`scanviz.shading.replace_entry`):
        the triangles of that phase (`ComplexSurface.triangle_entries`).
    background : RGB
        Default black, so a white marker stands out against it too.

    Returns
    -------
    Scene
        One object, the open mesh of ``result.surface.to_mesh()`` (faces 2k,
        2k + 1 are grid element k) with ``face_materials`` = the triangle's
        ring entry into a palette of one material per entry: colour = the
        entry, ambient 1, diffuse and specular 0. Under the scene's white
        ambient light every pixel of a triangle is its ring colour (the
        dissertation's colour look-up table; the lights play no part):
        exactly with ``shading="flat"`` or ``"phong"``, to rounding (1e-15)
        with ``"gouraud"``; ``"gooch"`` replaces colours by its tones.

    Raises
    ------
    TypeError
        If `result` is not a ComplexSurface or `view` not a View.
    ValueError
        As `GridSurface.scene`, `colour_ring` and `replace_entry`.

    Examples
    --------
    >>> from scanviz import render
    >>> result = three_poles_two_zeros(5)
    >>> scene = phase_scene(result, View((0, -6, 5), (0, 6, -5)), 24, 24)
    >>> bool((scene.objects[0].mesh.face_materials == result.triangle_entries()).all())
    True
    >>> out = render(scene, 24, 24, shading="flat")
    >>> face = out.polygon[12, 12]  # the pixel shows its triangle's ring colour
    >>> bool((out.image[12, 12, :3] == colour_ring(64)[result.triangle_entries()[face]]).all())
    True
    """
    if not isinstance(result, ComplexSurface):
        raise TypeError(f"'result' must be a ComplexSurface; got {short_repr(result)}")
    base = result.surface.scene(view, width, height, background=background)
    ring = colour_ring(steps)
    if marker is not None:
        ring = replace_entry(ring, marker)
    mesh = base.objects[0].mesh
    palette = tuple(
        Material(color=tuple(rgb), ambient=1.0, diffuse=0.0, specular=0.0) for rgb in ring.tolist()
    )
    coloured = dataclasses.replace(
        mesh, face_materials=_entries(result, np.array(mesh.faces), len(ring)), materials=palette
    )
    return dataclasses.replace(
        base,
        objects=(SceneObject(mesh=coloured, material=palette[0], name="complex surface"),),
        name=f"{result.surface.nx}x{result.surface.ny} complex surface coloured by phase",
    )

"""Fast Phong shading over one screen triangle (Bishop & Weimer 1986; S.-L. C. Wang 1989, ch. 3).

Per colour channel the reflection model of the dissertation is

    I = Ia ka + Ip / (r + r0) * (kd cos θ + ks cos^n φ),

with cos θ = N̂·L̂ and cos φ = R̂·V̂ (Phong) or N̂·Ĥ (Blinn). L and V are
constant over a triangle (a directional light, a distant viewer) and r + r0
is a constant of the surface. Inside a screen triangle the normal is the
linear N(x, y) = A x + B y + C (not renormalised), so cos θ and cos φ are
rational functions of the pixel (x, y). Fast Phong replaces them by their
second-order Taylor polynomials about an expansion point (vertex U, or the
centroid), steps each quadratic along a span with two additions per sample,
folds ambient and diffuse into one quadratic per channel and finds the
specular level ks Ip cos^n φ / (r + r0) in a look-up table by comparisons.

Coordinates: x, y are pixels measured from the expansion point; the sample
of pixel (px, py) sits at (px, py), or (px + 0.5, py + 0.5) for
``sample="center"`` (DESIGN §2). Values are 8-bit levels: Ia and Ip are
given in levels (255 is full) and colours are clipped to [0, 255].
docs/shading-fast-phong.md has the derivations, the choices and the
measured error.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np
from numba import njit

from .. import steps
from ..conventions import check_choice, check_index, sample_offset
from ..geometry import Polygon, as_coordinates
from ..raster import triangle_samples
from ..raster.api import as_tracer
from ..raster.fixed import snap
from ..trace import Recorder, Trace
from ..trace.events import FastPhongPixel, FastPhongSetup
from ..vectors import unit_vectors
from .illumination import _vector
from .lut import level_comparisons, lut_level_compiled
from .taylor import (
    CHANNELS,
    COS_SPECULAR,
    COS_THETA,
    EXPANSIONS,
    LEVELS,
    RationalForms,
    ReflectionModel,
    TaylorCoefficients,
    _direction,
    _normals,
    channel_quadratics,
    evaluate_quadratic,
    half_angle_gap,
    halfway_vector,
    normal_plane,
    rational_forms,
    taylor_coefficients,
)

__all__ = [  # the algebra lives in `taylor`; it is importable from here too
    "RationalForms",
    "ReflectionModel",
    "ShadedTriangle",
    "TaylorCoefficients",
    "channel_quadratics",
    "evaluate_quadratic",
    "exact_phong_triangle",
    "fast_phong_triangle",
    "forward_differences",
    "half_angle_gap",
    "halfway_vector",
    "normal_plane",
    "rational_forms",
    "taylor_coefficients",
]


# --- forward differencing over the covered samples (§2.5) --------------------------------


@njit(cache=True)
def _difference_kernel(quadratics, ys, xs, x0, y0):
    """Q and dQ of every quadratic at every sample: direct at a span's start, then two additions."""
    count, terms = len(ys), len(quadratics)
    values, steps = np.empty((count, terms)), np.empty((count, terms))
    for k in range(count):
        x, y = xs[k] - x0, ys[k] - y0
        direct = k == 0 or ys[k] != ys[k - 1] or xs[k] != xs[k - 1] + 1
        for j in range(terms):
            t5, t4, t3, t2, t1, t0 = quadratics[j]
            if direct:  # a span's first sample: Q and dQ from the coefficients
                values[k, j] = t5 * x * x + t4 * x * y + t3 * y * y + t2 * x + t1 * y + t0
                steps[k, j] = t5 * (2 * x + 1) + t4 * y + t2
            else:  # Q(x+1) = Q(x) + dQ(x), dQ(x+1) = dQ(x) + 2 T5: two additions
                values[k, j] = values[k - 1, j] + steps[k - 1, j]
                steps[k, j] = steps[k - 1, j] + 2 * t5
    return values, steps


@njit(cache=True)
def _color_kernel(values, ambient, table):
    """Table levels and clipped colours from the stepped (cos θ, cos φ, W_r, W_g, W_b)."""
    count = len(values)
    levels, colors = np.empty(count, np.int64), np.empty((count, 3))
    for k in range(count):
        levels[k] = lut_level_compiled(table, values[k, 1])
        specular = float(levels[k]) if values[k, 0] > 0 else 0.0
        for c in range(3):
            diffuse = values[k, 2 + c]
            color = (diffuse if diffuse > ambient[c] else ambient[c]) + specular
            colors[k, c] = min(max(color, 0.0), LEVELS)
    return levels, colors


@steps.step(
    "forward_difference",
    takes="a quadratic's value Q at a sample, its difference dQ to the next sample, and T5, "
    "its x² coefficient",
    returns="(Q, dQ) at the next sample along the span: Q + dQ and dQ + 2 T5",
)
def forward_difference(value: float, difference: float, t5: float) -> tuple[float, float]:
    """One sample right along a span of Q = T5 x² + T4 xy + T3 y² + T2 x + T1 y + T0.

    dQ(x) = Q(x + 1) - Q(x) = T5 (2x + 1) + T4 y + T2 changes by 2 T5 per sample, so
    Q(x + 1) = Q(x) + dQ(x) and dQ(x + 1) = dQ(x) + 2 T5: two additions.

    >>> forward_difference(4.0, 5.0, 1.0)  # x² at x = 2 (and 2x + 1): 9 and 7 at x = 3
    (9.0, 7.0)
    """
    return value + difference, difference + 2 * t5


def _shade_reference(quadratics, ys, xs, x0, y0, ambient, table, tracer, polygon):
    """The two kernels' arithmetic, one sample at a time, emitting ``fast_phong_pixel``; the
    forward-difference step and the table look-up come from `scanviz.steps`."""
    step, find_level = steps.get("forward_difference"), steps.get("specular_level")
    count, terms = len(ys), len(quadratics)
    values, differences = np.empty((count, terms)), np.empty((count, terms))
    levels, colors = np.empty(count, np.int64), np.empty((count, 3))
    rows, level = quadratics.tolist(), 0
    for k in range(count):
        x, y = int(xs[k]) - x0, int(ys[k]) - y0
        direct = k == 0 or ys[k] != ys[k - 1] or xs[k] != xs[k - 1] + 1
        for j, (t5, t4, t3, t2, t1, t0) in enumerate(rows):
            if direct:
                values[k, j] = t5 * x * x + t4 * x * y + t3 * y * y + t2 * x + t1 * y + t0
                differences[k, j] = t5 * (2 * x + 1) + t4 * y + t2
            else:
                previous = float(values[k - 1, j]), float(differences[k - 1, j])
                values[k, j], differences[k, j] = step(*previous, t5)
        cos_specular = float(values[k, COS_SPECULAR])
        # a span starts with a binary search, then steps from the previous sample's level
        start = None if direct else level
        level = find_level(table, cos_specular, start)
        # a float level, even 119.0, indexes no table (the walk's next start is this level)
        if isinstance(level, bool) or not isinstance(level, numbers.Integral):
            raise TypeError(
                f"step 'specular_level' must return an int level; got {level!r}, "
                f"a {type(level).__name__}"
            )
        comparisons = level_comparisons(len(table), level, start)
        lit = bool(values[k, COS_THETA] > 0)
        specular = float(level) if lit else 0.0
        for c in range(3):
            diffuse = float(values[k, 2 + c])
            color = (diffuse if diffuse > ambient[c] else float(ambient[c])) + specular
            colors[k, c] = min(max(color, 0.0), LEVELS)
        levels[k] = level
        if tracer is not None and tracer.wants("fast_phong_pixel", polygon=polygon, y=int(ys[k])):
            tracer.emit(
                FastPhongPixel(
                    polygon=polygon,
                    x=int(xs[k]),
                    y=int(ys[k]),
                    direct=bool(direct),
                    cos_theta=float(values[k, COS_THETA]),
                    cos_theta_step=float(differences[k, COS_THETA]),
                    cos_specular=cos_specular,
                    cos_specular_step=float(differences[k, COS_SPECULAR]),
                    ambient_diffuse=_floats(values[k, CHANNELS]),
                    ambient_diffuse_step=_floats(differences[k, CHANNELS]),
                    level=int(level),
                    comparisons=int(comparisons),
                    lit=lit,
                    color=_floats(colors[k]),
                )
            )
    return values, differences, levels, colors


def forward_differences(
    coefficients: object, ys: object, xs: object, origin: object
) -> tuple[np.ndarray, np.ndarray]:
    """Quadratics stepped along spans: direct at each span's first sample, then two additions.

    Parameters
    ----------
    coefficients : (Q, 6) array_like of float
        Each row a quadratic's (x², xy, y², x, y, 1) coefficients.
    ys, xs : (K,) array_like of int
        Samples sorted by y then x; a span is a run of consecutive x on one row.
    origin : (2,) array_like of float
        The expansion point in sample coordinates: sample (xs, ys) is at
        x = xs - origin[0], y = ys - origin[1].

    Returns
    -------
    values, steps : (K, Q) ndarray of float64
        Q and dQ = Q(x + 1) - Q(x) at every sample, as the compiled kernel steps them.

    Examples
    --------
    >>> values, steps = forward_differences([[1, 0, 0, 0, 0, 0]], [0, 0, 0, 0], [0, 1, 2, 3], (0, 0))
    >>> values[:, 0].tolist(), steps[:, 0].tolist()  # x², and 2x + 1
    ([0.0, 1.0, 4.0, 9.0], [1.0, 3.0, 5.0, 7.0])
    """
    quadratics = np.array(coefficients, dtype=np.float64).reshape(-1, 6)
    ys, xs = np.asarray(ys, dtype=np.int64), np.asarray(xs, dtype=np.int64)
    x0, y0 = _vector("origin", origin, 2)
    return _difference_kernel(quadratics, ys, xs, x0, y0)


# --- one triangle ---------------------------------------------------------------------------


@dataclass(frozen=True)
class ShadedTriangle:
    """The samples a screen triangle covers and their shading.

    Attributes
    ----------
    ys, xs : (K,) ndarray of int64
        Covered samples (`scanviz.raster.triangle_samples`), sorted by y then x.
    colors : (K, 3) ndarray of float64
        Levels in [0, 255].
    cos_theta, cos_specular : (K,) ndarray of float64
        cos θ and cos φ (or N̂·Ĥ): the forward-differenced quadratics
        (`fast_phong_triangle`) or the exact values (`exact_phong_triangle`).
    highlight : (K,) ndarray of float64
        The specular term added: the table level (fast) or Isr cos^n φ (exact);
        0 where cos θ <= 0.
    trace : Trace or None
        The recorded events when a recording tracer was given.
    """

    ys: np.ndarray
    xs: np.ndarray
    colors: np.ndarray
    cos_theta: np.ndarray
    cos_specular: np.ndarray
    highlight: np.ndarray
    trace: Trace | None


@dataclass(frozen=True)
class _Setup:
    """What both shaders share: the snapped triangle, the expansion point, the plane and the forms."""

    vertices: np.ndarray  # snapped, pixels, caller's frame
    normals: np.ndarray
    origin: np.ndarray  # the expansion point, pixels, caller's frame
    sample_origin: np.ndarray  # the same in pixel indices: sample (px, py) is at px - origin[0]
    to_light: np.ndarray
    to_viewer: np.ndarray
    plane: tuple[np.ndarray, np.ndarray, np.ndarray]
    forms: RationalForms


def _setup(vertices, normals, to_light, to_viewer, model, expansion, size, sample, bits, tracer):
    """Validate, find the covered samples, set up plane and forms (None for zero area)."""
    vertices = as_coordinates(vertices, "'vertices'", (3, 2))
    normals = _normals(normals)
    light, viewer = _direction("to_light", to_light), _direction("to_viewer", to_viewer)
    if not isinstance(model, ReflectionModel):
        raise TypeError(f"'model' must be a ReflectionModel; got {type(model).__name__}")
    check_choice("expansion", expansion, EXPANSIONS)
    if model.specular == "blinn":
        halfway_vector(light, viewer)  # refuse opposite L and V up front
    covered = triangle_samples(vertices, *size, sample=sample, subpixel_bits=bits, trace=tracer)
    if len(np.unique(vertices, axis=0)) < 3:
        return covered, None
    grid = snap(Polygon(vertices), sample, bits)
    (xu, yu), (xv, yv), (xw, yw) = ((int(x), int(y)) for x, y in grid.units)
    if (xv - xu) * (yw - yu) == (xw - xu) * (yv - yu):  # zero area once snapped (exact ints)
        return covered, None
    snapped = grid.pixel_vertices()
    # the plane through the snapped vertices: every covered sample is inside it, N stays bounded
    origin = snapped[0] if expansion == "vertex" else snapped.mean(axis=0)
    plane = normal_plane(snapped, normals, origin)
    setup = _Setup(
        snapped,
        normals,
        origin,
        origin - sample_offset(sample),
        light,
        viewer,
        plane,
        rational_forms(plane, to_light, to_viewer),  # normalised once, as the batch kernel does
    )
    return covered, setup


def _floats(row) -> tuple[float, ...]:
    return tuple(float(v) for v in row)


def _quadratics(setup: _Setup, model: ReflectionModel) -> np.ndarray:
    """The five stepped quadratics (5, 6): cos θ, the highlight's cosine, the three channels."""
    if setup.forms.i > 0:
        series = taylor_coefficients(setup.forms)
        cos_theta = series.cos_theta
        cos_specular = series.cos_phi if model.specular == "phong" else series.n_dot_h
    else:  # a zero normal at the expansion point: ambient light only, as `illuminate` does
        cos_theta = cos_specular = (0.0,) * 6
    return np.vstack([cos_theta, cos_specular, channel_quadratics(cos_theta, model)])


def _setup_event(setup, model, expansion, quadratics, polygon) -> FastPhongSetup:
    try:
        halfway = _floats(halfway_vector(setup.to_light, setup.to_viewer))
    except ValueError:
        halfway = (0.0, 0.0, 0.0)
    return FastPhongSetup(
        polygon=polygon,
        vertices=tuple(_floats(v) for v in setup.vertices),
        normals=tuple(_floats(n) for n in setup.normals),
        expansion=expansion,
        origin=_floats(setup.origin),
        plane=tuple(_floats(v) for v in setup.plane),
        to_light=_floats(setup.to_light),
        to_viewer=_floats(setup.to_viewer),
        halfway=halfway,
        forms=setup.forms,
        specular=model.specular,
        cos_theta=_floats(quadratics[COS_THETA]),
        cos_specular=_floats(quadratics[COS_SPECULAR]),
        ambient_diffuse=tuple(_floats(row) for row in quadratics[CHANNELS]),
        table=_floats(model.table),
    )


def _result(covered, colors, cos_theta, cos_specular, highlight, tracer) -> ShadedTriangle:
    recorded = tracer.trace() if isinstance(tracer, Recorder) else None
    return ShadedTriangle(
        covered.ys, covered.xs, colors, cos_theta, cos_specular, highlight, recorded
    )


def _nothing(covered, tracer) -> ShadedTriangle:
    return _result(covered, np.empty((0, 3)), np.empty(0), np.empty(0), np.empty(0), tracer)


def fast_phong_triangle(
    vertices: object,
    normals: object,
    to_light: object,
    to_viewer: object,
    model: ReflectionModel,
    *,
    width: int,
    height: int,
    expansion: str = "vertex",
    sample: str = "corner",
    subpixel_bits: int | None = 8,
    trace: object = None,
    polygon: int = 0,
) -> ShadedTriangle:
    """Fast Phong shading of one screen triangle: Taylor quadratics, forward differences, a table.

    Parameters
    ----------
    vertices : (3, 2) array_like of float
        Screen vertices U, V, W in pixels, y up, either winding.
    normals : (3, 3) array_like of float
        Vertex normals Nu, Nv, Nw in the frame of `to_light` and `to_viewer`;
        interpolated linearly in screen space, not renormalised (their lengths
        weight the interpolation; pass unit normals). One-sided: turn them
        toward the viewer first.
    to_light, to_viewer : (3,) array_like of float
        Directions toward the light and the viewer, constant over the triangle.
    model : ReflectionModel
        Intensities, coefficients, exponent, r + r0, Phong or Blinn, and the table.
    width, height : int
        Raster size; only its samples are shaded.
    expansion : {"vertex", "centroid"}
        Expand about vertex U (the dissertation) or the centroid (smaller error).
    sample : {"corner", "center"}
        Sample pixel (x, y) at (x, y) or at (x + 0.5, y + 0.5).
    subpixel_bits : int in 0..16, or None
        Vertex snapping, as for `scanviz.raster.triangle_samples`.
    trace : None, True, or Tracer
        None runs the compiled kernel (the reference loop while a step of
        `scanviz.steps` is replaced). A tracer runs the reference loop and
        receives ``fast_phong_setup`` (the coefficients), one
        ``fast_phong_pixel`` per sample (the differenced values and the table
        index), and `triangle_samples`' events.
    polygon : int
        Index recorded in the events.

    Returns
    -------
    ShadedTriangle
        Colours in levels [0, 255]. Traced and compiled runs give identical arrays.

    Raises
    ------
    TypeError, ValueError
        Bad shapes, non-finite numbers, zero directions, unknown options, and
        (Blinn) opposite `to_light` and `to_viewer`.

    Notes
    -----
    Per sample, with Q = (cos θ, cos φ, W_r, W_g, W_b) stepped by forward
    differences: level = table index of cos φ; colour = clip(max(W, Ia ka) +
    (level if cos θ > 0 else 0), 0, 255). The max keeps the diffuse term >= 0
    past the terminator (one comparison per channel). A zero-area triangle
    (after snapping) covers nothing; a zero normal at the expansion point
    gives ambient light only.

    Examples
    --------
    >>> model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=0.6, ks=0.7, n=8, r_plus_r0=1.5)
    >>> normals = [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)]
    >>> shaded = fast_phong_triangle([(0, 0), (4, 0), (0, 4)], normals, (0, 0, 1), (0, 0, 1),
    ...                              model, width=4, height=4)
    >>> shaded.xs[:4].tolist(), shaded.colors[:4, 0].round(1).tolist()
    ([0, 1, 2, 3], [246.5, 241.4, 228.0, 208.4])
    """
    tracer = as_tracer(trace)
    polygon = check_index("polygon", polygon)
    size = (width, height)
    covered, setup = _setup(
        vertices,
        normals,
        to_light,
        to_viewer,
        model,
        expansion,
        size,
        sample,
        subpixel_bits,
        tracer,
    )
    if setup is None:
        return _nothing(covered, tracer)
    quadratics = _quadratics(setup, model)
    if tracer is not None and tracer.wants("fast_phong_setup", polygon=polygon):
        tracer.emit(_setup_event(setup, model, expansion, quadratics, polygon))
    x0, y0 = setup.sample_origin
    ambient = np.array(model.ambient_term)
    if tracer is None and not steps.replaced():  # the kernels have no step table
        values, _ = _difference_kernel(quadratics, covered.ys, covered.xs, x0, y0)
        levels, colors = _color_kernel(values, ambient, model.table)
    else:
        arguments = (quadratics, covered.ys, covered.xs, x0, y0, ambient, model.table)
        values, _, levels, colors = _shade_reference(*arguments, tracer, polygon)
    lit = values[:, COS_THETA] > 0
    highlight = np.where(lit, levels.astype(np.float64), 0.0)
    return _result(
        covered, colors, values[:, COS_THETA], values[:, COS_SPECULAR], highlight, tracer
    )


def exact_phong_triangle(
    vertices: object,
    normals: object,
    to_light: object,
    to_viewer: object,
    model: ReflectionModel,
    *,
    width: int,
    height: int,
    sample: str = "corner",
    subpixel_bits: int | None = 8,
) -> ShadedTriangle:
    """The same triangle with exact per-sample Phong: the reference `fast_phong_triangle` approximates.

    Same inputs, same samples and the same normal plane; at each sample the
    normal N = A x + B y + C is normalised and the model evaluated directly:
    colour = clip(Ia ka + kk max(cos θ, 0) + (Isr max(cos φ, 0)^n if cos θ > 0), 0, 255)
    with kk = Ip kd / (r + r0), Isr = Ip ks / (r + r0) (no table, no floor).
    A zero normal gets ambient light only.

    Examples
    --------
    >>> model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=0.6, ks=0.7, n=8, r_plus_r0=1.5)
    >>> normals = [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)]
    >>> exact = exact_phong_triangle([(0, 0), (4, 0), (0, 4)], normals, (0, 0, 1), (0, 0, 1),
    ...                              model, width=4, height=4)
    >>> exact.colors[:4, 0].round(1).tolist()
    [246.5, 241.7, 228.4, 209.4]
    """
    size = (width, height)
    covered, setup = _setup(
        vertices, normals, to_light, to_viewer, model, "vertex", size, sample, subpixel_bits, None
    )
    if setup is None:
        return _nothing(covered, None)
    a, b, c = setup.plane
    x = (covered.xs - setup.sample_origin[0])[:, None]
    y = (covered.ys - setup.sample_origin[1])[:, None]
    unit = unit_vectors(a * x + b * y + c)  # zero rows stay zero
    light, viewer = setup.to_light, setup.to_viewer
    cos_theta = unit @ light
    if model.specular == "phong":
        cos_specular = (2 * cos_theta[:, None] * unit - light) @ viewer  # R = 2 (N·L) N - L
    else:
        cos_specular = unit @ halfway_vector(light, viewer)
    lit = cos_theta > 0
    highlight = np.where(lit, model.specular_scale * np.maximum(cos_specular, 0.0) ** model.n, 0.0)
    diffuse = np.asarray(model.diffuse_scale) * np.maximum(cos_theta, 0.0)[:, None]
    colors = np.clip(np.asarray(model.ambient_term) + diffuse + highlight[:, None], 0.0, LEVELS)
    return _result(covered, colors, cos_theta, cos_specular, highlight, None)

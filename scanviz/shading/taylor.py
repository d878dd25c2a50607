"""The algebra of fast Phong over a triangle (S.-L. C. Wang 1989, §3.2-3.5; spec §2.1-2.8).

The reflection model (`ReflectionModel`), the normal as a linear function of
the screen point (`normal_plane`), cos θ, cos φ and N̂·Ĥ as exact rational
functions of it (`rational_forms`), their second-order Taylor coefficients
about the expansion point (`taylor_coefficients`), ambient + diffuse folded
into one quadratic per channel (`channel_quadratics`), and Blinn's N̂·Ĥ
against cos(φ/2) (`half_angle_gap`). `scanviz.shading.fast_phong` steps the
quadratics over a triangle's samples. docs/shading-fast-phong.md has the
derivations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..conventions import as_array, check_choice, check_finite, finite_real
from ..geometry import as_coordinates
from ..trace.events import RationalForms  # the trace's record is the domain record
from .illumination import _vector
from .lut import specular_lut

SPECULAR_MODELS = ("phong", "blinn")
EXPANSIONS = ("vertex", "centroid")
LEVELS = 255.0  # colours are 8-bit levels, clipped to [0, LEVELS]
COS_THETA, COS_SPECULAR, CHANNELS = 0, 1, slice(2, 5)  # rows of the stacked quadratics


# --- validation at the boundary ----------------------------------------------------------


def _rgb(name: str, value: object) -> tuple[float, float, float]:
    """A number or three numbers, each finite and >= 0, as an (r, g, b) tuple."""
    try:
        array = np.broadcast_to(np.asarray(value, dtype=np.float64), (3,))
    except (TypeError, ValueError):
        raise TypeError(
            f"{name!r} must be a number or 3 numbers (r, g, b); got {value!r}"
        ) from None
    if not (np.isfinite(array).all() and (array >= 0).all()):
        raise ValueError(f"{name!r} must be finite and >= 0; got {array.tolist()}")
    return tuple(float(v) for v in array)


@njit(cache=True)
def _unit3(vector):
    """(unit vector, ok): `vector` scaled by its largest component, then by its length.

    Compiled, and called by both the Python functions here and the batch
    kernel of `scanviz.shading.fast_phong_compiled`, so both get the same bits;
    ok is False (and the result zero) for a zero vector.
    """
    unit = np.zeros(3)
    largest = max(abs(vector[0]), abs(vector[1]), abs(vector[2]))
    if not largest > 0:
        return unit, False
    x, y, z = vector[0] / largest, vector[1] / largest, vector[2] / largest
    length = math.sqrt(x * x + y * y + z * z)
    unit[0], unit[1], unit[2] = x / length, y / length, z / length
    return unit, True


@njit(cache=True)
def _dot3(u, v):
    """u·v summed left to right (no BLAS, whose order and fused multiply-adds vary)."""
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


@njit(cache=True)
def _halfway(light, viewer):
    """(Ĥ, ok) for unit L and V; ok is False where they are opposite (|L + V| <= 1e-12)."""
    total = np.empty(3)
    for k in range(3):
        total[k] = light[k] + viewer[k]
    if math.sqrt(_dot3(total, total)) <= 1e-12:  # below this H is rounding noise
        return np.zeros(3), False
    return _unit3(total)


def _direction(name: str, value: object) -> np.ndarray:
    vector = _vector(name, value)
    unit, ok = _unit3(vector)
    if not (ok and np.isfinite(unit).all()):
        raise ValueError(f"{name!r} must be a nonzero direction; got {vector.tolist()}")
    return unit


def _normals(value: object) -> np.ndarray:
    array = as_array(value, "'normals' must be a (3, 3) array of numbers", copy=True, got=repr)
    if array.shape != (3, 3):
        raise ValueError(
            f"'normals' must be a (3, 3) array (one row per vertex); got {array.shape}"
        )
    return check_finite("normals", array)


@dataclass(frozen=True)
class ReflectionModel:
    """The dissertation's reflection model and its constants, with the specular table it needs.

    Parameters
    ----------
    Ia, ka : float or (3,) array_like of float
        Ambient light (in levels) and ambient reflectance, per channel, >= 0.
    Ip : float
        Light-source intensity in levels, > 0 (255 in the dissertation).
    kd : float or (3,) array_like of float
        Diffuse coefficient per channel, >= 0.
    ks : float
        Specular coefficient, >= 0, the same for every channel (white light).
    n : float
        Specular exponent, > 0. Blinn's N̂·Ĥ = cos(φ/2) for coplanar vectors,
        so an exponent about 4 n gives a Blinn highlight as wide as Phong's.
    r_plus_r0 : float
        The distance term r + r0, >= 1, constant over the surface.
    specular : {"phong", "blinn"}
        Highlight cos φ = R̂·V̂ or N̂·Ĥ; each has its own look-up table.
    top_level : int, optional
        Keep only the table's first `top_level` entries (levels above it read
        as `top_level`). Each colour is clipped at 255 levels, so
        ``top_level=255`` changes no colour and bounds the table of a bright
        light (`render` uses it); None keeps all N, as the dissertation does.

    Attributes
    ----------
    table : (min(N, top_level),) ndarray of float64
        ``specular_lut(Ip, ks, r_plus_r0, n, top=top_level)``, built once per surface.

    Examples
    --------
    >>> model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.7, 0.5, 0.2), ks=0.7, n=8)
    >>> len(model.table), model.ambient_term, model.diffuse_scale[0]  # Table 3-4: N = 119
    (119, (25.5, 25.5, 25.5), 119.0)
    """

    Ia: tuple[float, float, float] = (255.0, 255.0, 255.0)
    ka: tuple[float, float, float] = (0.1, 0.1, 0.1)
    Ip: float = 255.0
    kd: tuple[float, float, float] = (0.7, 0.7, 0.7)
    ks: float = 0.7
    n: float = 8.0
    r_plus_r0: float = 1.5
    specular: str = "phong"
    top_level: int | None = None
    table: np.ndarray = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("Ia", "ka", "kd"):
            object.__setattr__(self, name, _rgb(name, getattr(self, name)))
        for name in ("Ip", "ks", "n", "r_plus_r0"):
            object.__setattr__(self, name, finite_real(name, getattr(self, name)))
        check_choice("specular", self.specular, SPECULAR_MODELS)
        # specular_lut checks Ip > 0, ks >= 0, r + r0 >= 1 and n > 0
        table = specular_lut(self.Ip, self.ks, self.r_plus_r0, self.n, top=self.top_level)
        object.__setattr__(self, "table", table)

    @property
    def ambient_term(self) -> tuple[float, float, float]:
        """Ia ka per channel."""
        return tuple(i * k for i, k in zip(self.Ia, self.ka, strict=True))

    @property
    def diffuse_scale(self) -> tuple[float, float, float]:
        """kk = Ip kd / (r + r0) per channel: the factor of cos θ (§2.6)."""
        return tuple(self.Ip * k / self.r_plus_r0 for k in self.kd)

    @property
    def specular_scale(self) -> float:
        """Isr = Ip ks / (r + r0): the factor of cos^n φ (the table has floor(Isr) levels)."""
        return self.Ip * self.ks / self.r_plus_r0


# --- the normal plane and the exact rational forms (§2.2, §2.3) ---------------------------


def normal_plane(
    xy: object, normals: object, origin: object
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The linear normal N(x, y) = A x + B y + C over a screen triangle UVW (Fig. 3-1).

    Parameters
    ----------
    xy : (3, 2) array_like of float
        Screen vertices U, V, W in pixels.
    normals : (3, 3) array_like of float
        Their normals Nu, Nv, Nw (any length: N is not renormalised).
    origin : (2,) array_like of float
        The point x = y = 0 (vertex U, the centroid, ...).

    Returns
    -------
    A, B, C : (3,) ndarray of float64
        N at the point origin + (x, y) is A x + B y + C; C is N at the origin.

    Raises
    ------
    ValueError
        If the triangle has zero area (collinear vertices leave N undetermined
        off their line), or an input has the wrong shape or is not finite.

    Notes
    -----
    With U at the origin, xv = Xv - Xu etc. and D = xv yw - xw yv:
    A = (yv (Nu - Nw) + yw (Nv - Nu)) / D, B = (Nu (xw - xv) + Nw xv - Nv xw) / D,
    and C = Nu + A (Ox - Xu) + B (Oy - Yu) for any other origin O.

    Examples
    --------
    >>> A, B, C = normal_plane([(0, 0), (4, 0), (0, 2)], [(0, 0, 1), (1, 0, 1), (0, 1, 1)], (0, 0))
    >>> A.tolist(), B.tolist(), C.tolist()
    ([0.25, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 1.0])
    """
    vertices = np.ascontiguousarray(as_coordinates(xy, "'xy'", (3, 2)), dtype=np.float64)
    a, b, c, ok = _plane(vertices, _normals(normals), _vector("origin", origin, 2))
    if not ok:
        raise ValueError(
            f"'xy' must span a triangle of nonzero area; got {np.asarray(xy).tolist()}"
        )
    return a, b, c


@njit(cache=True)
def _plane(vertices, normals, origin):
    """(A, B, C, ok) of `normal_plane`; ok is False for zero area (compiled, shared with the kernels)."""
    a, b, c = np.zeros(3), np.zeros(3), np.zeros(3)
    xu, yu = vertices[0, 0], vertices[0, 1]
    xv, yv = vertices[1, 0] - xu, vertices[1, 1] - yu
    xw, yw = vertices[2, 0] - xu, vertices[2, 1] - yu
    determinant = xv * yw - xw * yv
    if determinant == 0:
        return a, b, c, False
    for k in range(3):
        nu, nv, nw = normals[0, k], normals[1, k], normals[2, k]
        a[k] = (yv * (nu - nw) + yw * (nv - nu)) / determinant
        b[k] = (nu * (xw - xv) + nw * xv - nv * xw) / determinant
        c[k] = nu + a[k] * (origin[0] - xu) + b[k] * (origin[1] - yu)
    return a, b, c, True


def halfway_vector(to_light: object, to_viewer: object) -> np.ndarray:
    """Ĥ = (L̂ + V̂) / ‖L̂ + V̂‖, Blinn's halfway vector.

    Raises
    ------
    ValueError
        If L and V are opposite (no halfway direction) or not nonzero directions.

    Examples
    --------
    >>> halfway_vector((1, 0, 1), (-1, 0, 1)).tolist()
    [0.0, 0.0, 1.0]
    """
    halfway, ok = _halfway(_direction("to_light", to_light), _direction("to_viewer", to_viewer))
    if not ok:
        raise ValueError(
            "'to_light' and 'to_viewer' must not be opposite: they have no halfway vector"
        )
    return halfway


def rational_forms(
    plane: tuple[np.ndarray, np.ndarray, np.ndarray],
    to_light: object,
    to_viewer: object,
) -> RationalForms:
    """The scalars of §2.3 for the normal plane (A, B, C), light L and viewer V.

    Parameters
    ----------
    plane : (A, B, C), each (3,) array_like of float
        From `normal_plane`.
    to_light, to_viewer : (3,) array_like of float
        Directions from the surface toward the light and the viewer (normalised here).

    Returns
    -------
    RationalForms
        For L and V opposite, ha = hb = hc = 0 (there is no N̂·Ĥ).

    Examples
    --------
    >>> forms = rational_forms(([0.25, 0, 0], [0, 0.5, 0], [0, 0, 1]), (0, 0, 1), (0, 0, 1))
    >>> float(forms.cos_theta(0, 0)), float(forms.cos_phi(0, 0)), forms.d, forms.k_lv
    (1.0, 1.0, 0.0625, 1.0)
    """
    a, b, c = (_vector(name, v) for name, v in zip("ABC", plane, strict=True))
    light, viewer = _direction("to_light", to_light), _direction("to_viewer", to_viewer)
    halfway, _ = _halfway(light, viewer)  # zero where there is none
    return RationalForms(*(float(v) for v in _forms(a, b, c, light, viewer, halfway)))


@njit(cache=True)
def _forms(a, b, c, light, viewer, halfway):
    """The 22 scalars of `RationalForms`, in field order (compiled, shared with the kernels)."""
    la, lb, lc = _dot3(light, a), _dot3(light, b), _dot3(light, c)
    va, vb, vc = _dot3(viewer, a), _dot3(viewer, b), _dot3(viewer, c)
    return (
        la,
        lb,
        lc,
        va,
        vb,
        vc,
        _dot3(a, a),
        2 * _dot3(a, b),
        _dot3(b, b),
        2 * _dot3(a, c),
        2 * _dot3(b, c),
        _dot3(c, c),
        2 * la * va,
        2 * (la * vb + lb * va),
        2 * lb * vb,
        2 * (la * vc + lc * va),
        2 * (lb * vc + lc * vb),
        2 * lc * vc,
        _dot3(light, viewer),
        _dot3(halfway, a),
        _dot3(halfway, b),
        _dot3(halfway, c),
    )


# --- second-order Taylor coefficients (§2.4) ---------------------------------------------


def _theta_series(a, b, c, d, e, f, g, h, i, root):
    """(T5, T4, T3, T2, T1, T0) of (a x + b y + c) / sqrt(d x² + ... + i); root = sqrt(i).

    Plain arithmetic only (products, not powers), so the same formulas run on
    floats, on sympy symbols and compiled by numba, with the same bits.
    """
    return (
        (3 * c * g * g - 4 * c * d * i - 4 * a * g * i) / (8 * i * i * root),
        (3 * c * g * h - 2 * c * e * i - 2 * b * g * i - 2 * a * h * i) / (4 * i * i * root),
        (3 * c * h * h - 4 * c * f * i - 4 * b * h * i) / (8 * i * i * root),
        (2 * a * i - c * g) / (2 * i * root),
        (2 * b * i - c * h) / (2 * i * root),
        c / root,
    )


def _phi_series(l, m, o, p, q, w, d, e, f, g, h, i, k_lv):  # noqa: E741
    """(T55, T44, T33, T22, T11, T00) of (l x² + ... + w) / (d x² + ... + i) - k_LV."""
    return (
        (l * i * i - d * w * i - g * p * i + g * g * w) / (i * i * i),
        (m * i * i - e * w * i - h * p * i - g * q * i + 2 * g * h * w) / (i * i * i),
        (o * i * i - f * w * i - h * q * i + h * h * w) / (i * i * i),
        (p * i - g * w) / (i * i),
        (q * i - h * w) / (i * i),
        w / i - k_lv,
    )


# The same formulas compiled: `taylor_coefficients` and the batch kernel both evaluate these.
theta_series = njit(cache=True)(_theta_series)
phi_series = njit(cache=True)(_phi_series)


@dataclass(frozen=True)
class TaylorCoefficients:
    """Second-order Taylor polynomials about the expansion point, as (x², xy, y², x, y, 1).

    Attributes
    ----------
    cos_theta : (6,) tuple of float
        T5, T4, T3, T2, T1, T0.
    cos_phi : (6,) tuple of float
        T55, T44, T33, T22, T11, T00.
    n_dot_h : (6,) tuple of float
        Blinn's: `cos_theta`'s formulas with H in place of L.
    """

    cos_theta: tuple[float, ...]
    cos_phi: tuple[float, ...]
    n_dot_h: tuple[float, ...]


def taylor_coefficients(forms: RationalForms) -> TaylorCoefficients:
    """The second-order Taylor coefficients of cos θ, cos φ and N̂·Ĥ at x = y = 0 (§2.4).

    Parameters
    ----------
    forms : RationalForms

    Returns
    -------
    TaylorCoefficients

    Raises
    ------
    ValueError
        If the normal at the expansion point is zero (i = 0): the forms have no series there.

    Examples
    --------
    A flat triangle facing the light and the viewer: cos θ = cos φ = 1 everywhere.

    >>> forms = rational_forms(([0, 0, 0], [0, 0, 0], [0, 0, 2]), (0, 0, 1), (0, 0, 1))
    >>> taylor_coefficients(forms).cos_phi
    (0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
    """
    s = forms
    if not s.i > 0:
        raise ValueError("the normal at the expansion point is zero (i = 0): no Taylor series")
    root = math.sqrt(s.i)
    shape = (s.d, s.e, s.f, s.g, s.h, s.i)
    return TaylorCoefficients(
        cos_theta=theta_series(s.a, s.b, s.c, *shape, root),
        cos_phi=phi_series(s.l, s.m, s.o, s.p, s.q, s.w, *shape, s.k_lv),
        n_dot_h=theta_series(s.ha, s.hb, s.hc, *shape, root),
    )


def channel_quadratics(cos_theta: object, model: ReflectionModel) -> np.ndarray:
    """Ambient + diffuse as one quadratic per channel: W5..W0 (§2.6).

    Wk = Tk kk for k = 5..1 and W0 = T0 kk + Ia ka, with kk = Ip kd / (r + r0).

    Parameters
    ----------
    cos_theta : (6,) array_like of float
        T5..T0.
    model : ReflectionModel

    Returns
    -------
    (3, 6) ndarray of float64
        Row c holds channel c's (x², xy, y², x, y, 1) coefficients.

    Examples
    --------
    >>> model = ReflectionModel(Ia=100, ka=0.2, Ip=255, kd=(1, 0.5, 0), r_plus_r0=1)
    >>> channel_quadratics([0, 0, 0, 0.5, 0, 1], model)[:, 3:]
    array([[127.5 ,   0.  , 275.  ],
           [ 63.75,   0.  , 147.5 ],
           [  0.  ,   0.  ,  20.  ]])
    """
    terms = _vector("cos_theta", cos_theta, 6)
    quadratics = np.asarray(model.diffuse_scale)[:, None] * terms[None, :]
    quadratics[:, 5] += model.ambient_term
    return quadratics


def evaluate_quadratic(coefficients: object, x: object, y: object) -> np.ndarray:
    """Q(x, y) = c0 x² + c1 xy + c2 y² + c3 x + c4 y + c5, evaluated directly.

    Examples
    --------
    >>> float(evaluate_quadratic([1, 2, 3, 4, 5, 6], 1.0, 2.0))  # 1 + 4 + 12 + 4 + 10 + 6
    37.0
    """
    t5, t4, t3, t2, t1, t0 = _vector("coefficients", coefficients, 6)
    x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
    return t5 * x * x + t4 * x * y + t3 * y * y + t2 * x + t1 * y + t0


# --- Blinn's N·H against Phong's R·V (§2.8) ------------------------------------------------


def half_angle_gap(normal: object, to_light: object, to_viewer: object) -> tuple[float, float]:
    """(N̂·Ĥ, cos(φ/2)) with φ the angle between R and V: equal iff N, L, V are coplanar.

    The dissertation says N·H is cos(φ/2), not cos φ = R·V. That holds when N
    lies in the plane of L and V (then H and N are φ/2 apart); off that plane
    the two differ (docs/shading-fast-phong.md has numbers).

    Examples
    --------
    >>> [round(v, 6) for v in half_angle_gap((0, 0, 1), (1, 0, 1), (-0.2, 0, 1))]  # coplanar
    [0.957092, 0.957092]
    >>> [round(v, 6) for v in half_angle_gap((0, 0.3, 1), (1, 0, 1), (-0.2, 0, 1))]
    [0.916728, 0.926701]
    """
    unit = _direction("normal", normal)
    light, viewer = _direction("to_light", to_light), _direction("to_viewer", to_viewer)
    reflected = 2 * (unit @ light) * unit - light
    cos_phi = min(max(float(reflected @ viewer), -1.0), 1.0)
    return float(unit @ halfway_vector(light, viewer)), math.sqrt((1 + cos_phi) / 2)

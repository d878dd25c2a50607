"""Events of shading: illumination (`scanviz.shading.illumination`) and fast Phong
(`scanviz.shading.fast_phong`), whose setup carries the `RationalForms` that
`scanviz.shading.taylor` computes: one record, defined here so the jail has it."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from .base import Event, Record

if TYPE_CHECKING:
    import numpy as np


# --- illumination (scanviz.shading.illumination) -----------------------------------------


@dataclass(frozen=True)
class LightTerm(Record):
    """One light's share of the color of an illuminated point (world space).

    ``to_light`` is L, the unit vector from the point toward the light (zero if
    the point is at a point light). ``n_dot_l`` and ``r_dot_v`` are the cosines
    N.L and R.V with R = 2(N.L)N - L; ``attenuation`` is f_att. ``diffuse`` is
    kd * Od * max(N.L, 0) (RGB), ``specular`` ks * max(R.V, 0)^n where N.L > 0,
    else 0 (white), and ``contribution`` = f_att * Il * (diffuse + specular).
    """

    light: int
    to_light: tuple[float, float, float]
    n_dot_l: float
    r_dot_v: float
    attenuation: float
    diffuse: tuple[float, float, float]
    specular: float
    contribution: tuple[float, float, float]


@dataclass(frozen=True)
class Illumination(Event):
    """The Phong illumination model evaluated at one point, shown at pixel (x, y).

    ``normal`` is the unit normal used: renormalized, and reversed (``flipped``)
    if the surface is seen from behind; zero for a zero normal. ``to_viewer`` is
    V. ``ambient`` is ka * Ia * Od; ``color`` = clip(ambient + sum of the
    lights' contributions, 0, 1), exactly what the untraced shader returns.
    """

    kind: ClassVar[str] = "illumination"
    x: int
    y: int
    polygon: int | None
    position: tuple[float, float, float]
    normal: tuple[float, float, float]
    flipped: bool
    to_viewer: tuple[float, float, float]
    ambient: tuple[float, float, float]
    lights: tuple[LightTerm, ...]
    color: tuple[float, float, float]


# --- fast Phong (scanviz.shading.fast_phong) ----------------------------------------------


@dataclass(frozen=True)
class RationalForms(Record):
    """cos θ, cos φ and N̂·Ĥ over a triangle as exact rational functions of (x, y) (§2.3).

    Built by `scanviz.shading.taylor.rational_forms`; the fields are the
    dissertation's scalars. With N(x, y) = A x + B y + C (x, y from the
    expansion point): a, b, c = L·A, L·B, L·C; aa, bb, cc = V·A, V·B, V·C;
    ‖N‖² = d x² + e xy + f y² + g x + h y + i; l, m, o, p, q, w the
    numerator of 2 (N·L)(N·V); k_lv = L·V; ha, hb, hc = H·A, H·B, H·C
    (L, V, H unit). The methods evaluate the forms at sample offsets.
    """

    a: float
    b: float
    c: float
    aa: float
    bb: float
    cc: float
    d: float
    e: float
    f: float
    g: float
    h: float
    i: float
    l: float  # noqa: E741 -- the dissertation's name
    m: float
    o: float
    p: float
    q: float
    w: float
    k_lv: float
    ha: float
    hb: float
    hc: float

    def norm_squared(self, x: object, y: object) -> np.ndarray:
        """‖N(x, y)‖² = d x² + e xy + f y² + g x + h y + i."""
        _, x, y = _arrays(x, y)
        return self.d * x * x + self.e * x * y + self.f * y * y + self.g * x + self.h * y + self.i

    def cos_theta(self, x: object, y: object) -> np.ndarray:
        """cos θ = (a x + b y + c) / sqrt(‖N‖²)."""
        np, x, y = _arrays(x, y)
        return (self.a * x + self.b * y + self.c) / np.sqrt(self.norm_squared(x, y))

    def cos_phi(self, x: object, y: object) -> np.ndarray:
        """cos φ = R̂·V̂ = (l x² + m xy + o y² + p x + q y + w) / ‖N‖² - k_LV."""
        _, x, y = _arrays(x, y)
        numerator = self.l * x * x + self.m * x * y + self.o * y * y + self.p * x + self.q * y
        return (numerator + self.w) / self.norm_squared(x, y) - self.k_lv

    def n_dot_h(self, x: object, y: object) -> np.ndarray:
        """N̂·Ĥ = (ha x + hb y + hc) / sqrt(‖N‖²): cos θ with H in place of L."""
        np, x, y = _arrays(x, y)
        return (self.ha * x + self.hb * y + self.hc) / np.sqrt(self.norm_squared(x, y))


def _arrays(x: object, y: object) -> tuple:
    """numpy and x, y as float64 arrays (numpy imported here: the jail loads events without it)."""
    import numpy as np

    return np, np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)


@dataclass(frozen=True)
class FastPhongSetup(Event):
    """Fast Phong over triangle `polygon`: the expansion and every coefficient, before any pixel.

    ``vertices`` are the snapped screen vertices, ``origin`` the expansion
    point (``expansion`` "vertex": vertex 0, or "centroid"); ``plane`` is
    (A, B, C) with N(x, y) = A x + B y + C in pixels from the origin.
    ``cos_theta``, ``cos_specular`` and each of ``ambient_diffuse`` (r, g, b)
    hold a quadratic's (x², xy, y², x, y, 1) coefficients: T5..T0, T55..T00
    (``specular`` "phong") or the N·H ones ("blinn"), W5..W0. ``table`` is
    the specular look-up table cos φ_1..cos φ_N.
    """

    kind: ClassVar[str] = "fast_phong_setup"
    polygon: int
    vertices: tuple[tuple[float, float], ...]
    normals: tuple[tuple[float, float, float], ...]
    expansion: str
    origin: tuple[float, float]
    plane: tuple[tuple[float, float, float], ...]
    to_light: tuple[float, float, float]
    to_viewer: tuple[float, float, float]
    halfway: tuple[float, float, float]
    forms: RationalForms
    specular: str
    cos_theta: tuple[float, float, float, float, float, float]
    cos_specular: tuple[float, float, float, float, float, float]
    ambient_diffuse: tuple[tuple[float, float, float, float, float, float], ...]
    table: tuple[float, ...]


@dataclass(frozen=True)
class FastPhongPixel(Event):
    """Fast Phong at sample (x, y): the quadratics' values there and their steps to x + 1.

    ``direct`` is True at a span's first sample (values evaluated from the
    coefficients) and False where they came from one forward-difference step.
    Each ``*_step`` is the difference to the next sample. ``level`` is the
    table index of ``cos_specular`` (``comparisons`` made to find it);
    ``lit`` says whether cos θ > 0 (else no highlight); ``color`` is
    clip(max(ambient_diffuse, Ia ka) + (level if lit else 0), 0, 255).
    """

    kind: ClassVar[str] = "fast_phong_pixel"
    polygon: int
    x: int
    y: int
    direct: bool
    cos_theta: float
    cos_theta_step: float
    cos_specular: float
    cos_specular_step: float
    ambient_diffuse: tuple[float, float, float]
    ambient_diffuse_step: tuple[float, float, float]
    level: int
    comparisons: int
    lit: bool
    color: tuple[float, float, float]

"""Gooch tone shading: cool-to-warm instead of dark-to-light (Gooch et al., SIGGRAPH 1998).

Technical illustrators keep shaded regions light enough for black edge lines
and highlights to stay visible, and show orientation by hue instead: surfaces
facing the light are warm (yellow), surfaces facing away are cool (blue).
With t = (1 + N.L) / 2,

    I = t k_warm + (1 - t) k_cool,
    k_cool = k_blue + alpha kd,   k_blue = (0, 0, b)
    k_warm = k_yellow + beta kd,  k_yellow = (y, y, 0)

where kd is the object's diffuse color. Same conventions as
`scanviz.shading.illumination`: world space, one row per point, normals
renormalized and turned toward the viewer, dot products written out so a
single point gets bit for bit what it gets among many.
"""

from __future__ import annotations

import math

import numpy as np

from ..conventions import short_repr
from ..scene.model import Light
from .illumination import (
    _COLOR,
    _DIFFUSE,
    _dot,
    _facing_viewer,
    _materials,
    _rows,
    _to_viewer,
    _toward_light,
)


def _parameter(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise TypeError(f"{name!r} must be a number; got {value!r}")
    try:
        number = float(value)
    except OverflowError:  # an int past float64
        number = math.inf
    if not (math.isfinite(number) and number >= 0):
        raise ValueError(f"{name!r} must be finite and >= 0; got {short_repr(value)}")
    return number


def gooch(
    positions: object,
    normals: object,
    materials: object,
    eye: object,
    light: Light,
    *,
    view_dir: object = None,
    b: float = 0.4,
    y: float = 0.4,
    alpha: float = 0.2,
    beta: float = 0.6,
) -> np.ndarray:
    """Gooch cool-to-warm tone shading at N points (world space).

    Parameters
    ----------
    positions : (N, 3) array_like of float
    normals : (N, 3) array_like of float
        Any length; normalized here. A zero normal gets the middle tone (N.L = 0).
    materials : (N, 9) array_like of float
        Rows of `material_array`; kd = diffuse * (r, g, b).
    eye : (3,) array_like of float or None
        The viewer's position; None for an orthographic viewer given by `view_dir`.
    light : Light
        The one light whose direction sets the tone.
    view_dir : (3,) array_like of float, optional
        Direction toward an orthographic viewer. Give exactly one of `eye` and `view_dir`.
    b, y : float
        Strength of the pure blue (0, 0, b) and pure yellow (y, y, 0) tones.
    alpha, beta : float
        How much of the object color kd is added to the cool and warm tones.

    Returns
    -------
    (N, 3) ndarray of float64
        RGB clipped to [0, 1]: k_warm where N.L = 1, k_cool where N.L = -1.

    Notes
    -----
    The defaults are the paper's b = 0.4, y = 0.4, alpha = 0.2, beta = 0.6.
    The paper (and the course slides) print the blend with k_cool weighted by
    (1 + l.n)/2, while its text and figures put the warm tone toward the
    light; here L points toward the light, so the warm tone gets that weight.
    Gooch shading ignores distance: a point light sets only the direction.

    Examples
    --------
    >>> from scanviz.shading import material_array
    >>> from scanviz.scene.model import Material
    >>> materials = material_array([Material(color=(1, 0, 0), diffuse=1.0)] * 3)
    >>> normals = [(0, 0, 1), (1, 0, 0), (0, 0, -1)]  # toward, across, away from the light
    >>> gooch(np.zeros((3, 3)), normals, materials, None, Light(), view_dir=(1, 0, 0))
    array([[1. , 0.4, 0. ],
           [0.6, 0.2, 0.2],
           [0.2, 0. , 0.4]])
    """
    positions = _rows("positions", positions, 3)
    normals = _rows("normals", normals, 3, len(positions))
    materials = _materials(materials, len(positions))
    if not isinstance(light, Light):
        raise TypeError(f"'light' must be a Light; got {type(light).__name__}")
    b, y, alpha, beta = (
        _parameter(name, value)
        for name, value in (("b", b), ("y", y), ("alpha", alpha), ("beta", beta))
    )
    view = _to_viewer(positions, eye, view_dir)
    normal, _ = _facing_viewer(normals, view)
    to_light, _ = _toward_light(positions, light)
    kd = materials[:, _DIFFUSE, None] * materials[:, _COLOR]
    cool = np.array([0.0, 0.0, b]) + alpha * kd
    warm = np.array([y, y, 0.0]) + beta * kd
    t = ((1 + _dot(normal, to_light)) / 2)[:, None]  # 1 facing the light, 0 facing away
    return np.clip(t * warm + (1 - t) * cool, 0.0, 1.0)

"""The line anti-aliasers measured side by side: coverage of one line, intensity against angle.

`coverage_methods` gives each method's coverage of one line (the binary
midpoint line, Wu 1991, Gupta and Sproull 1981, 4x4 supersampling, DISLOP_L
of Wang 1989, ch. 4, and the exact band area); `intensity_per_length` the
intensity per unit length of each against the line's angle, the "ropiness"
an area method does not have. The widgets plot what these return.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..conventions import as_array, short_repr
from ..geometry import as_coordinates
from ..raster import midpoint_line
from .line import dislop_line
from .peers import exact_band_line, gupta_sproull_line, supersampled_line, wu_line

__all__ = ["MARGIN", "coverage_methods", "intensity_per_length"]

MARGIN = 2  # columns kept clear of each end when measuring intensity per unit length


def _midpoint_coverage(p0, p1, width: int, height: int) -> np.ndarray:
    """The binary midpoint line between the pixels that hold the endpoints."""
    x0, y0, x1, y1 = (int(v) for v in np.floor([*p0, *p1]))
    xs, ys = midpoint_line(x0, y0, x1, y1)
    image = np.zeros((height, width))
    inside = (xs >= 0) & (xs < width) & (ys >= 0) & (ys < height)
    image[ys[inside], xs[inside]] = 1.0
    return image


def coverage_methods(p0, p1, width: int, height: int) -> dict[str, np.ndarray]:
    """Each method's (height, width) coverage of the line p0-p1, the exact band last.

    >>> list(coverage_methods((1, 1), (5, 3), 6, 4))  # doctest: +NORMALIZE_WHITESPACE
    ['midpoint (binary)', 'Wu', 'Gupta–Sproull', 'supersample 4×4', 'DISLOP_L', 'exact band']
    """
    exact = exact_band_line(p0, p1, width, height)  # checks the arguments
    p0, p1 = as_coordinates(p0, "'p0'", (2,)), as_coordinates(p1, "'p1'", (2,))
    return {
        "midpoint (binary)": _midpoint_coverage(p0, p1, exact.shape[1], exact.shape[0]),
        "Wu": wu_line(p0, p1, width, height),
        "Gupta–Sproull": gupta_sproull_line(p0, p1, width, height),
        "supersample 4×4": supersampled_line(p0, p1, width, height, k=4),
        "DISLOP_L": dislop_line(p0, p1, width, height),
        "exact band": exact,
    }


def _ropiness_methods() -> dict:
    return {
        "supersample 2×2": lambda p0, p1, w, h: supersampled_line(p0, p1, w, h, k=2),
        "supersample 4×4": lambda p0, p1, w, h: supersampled_line(p0, p1, w, h, k=4),
        "Wu": wu_line,
        "Gupta–Sproull": gupta_sproull_line,
        "DISLOP_L": dislop_line,
    }


def _check_angles(angles: object) -> np.ndarray:
    values = as_array(angles, "'angles' must be a 1-D array of degrees")
    if values.ndim != 1 or not np.isfinite(values).all() or ((values < 0) | (values > 90)).any():
        raise ValueError(
            f"'angles' must be a 1-D array of finite degrees in 0..90; got {short_repr(angles)}"
        )
    return values


def intensity_per_length(angles, length: float, width: int, height: int) -> dict[str, np.ndarray]:
    """Intensity per unit length of each method's line, against its angle, away from its ends.

    Parameters
    ----------
    angles : (N,) array_like of float
        Degrees from the x axis, in 0..90.
    length : float
        The segment's length in pixels; it must fit in the raster with
        ``2 * MARGIN + 2`` pixels to spare each side.
    width, height : int
        The raster size; every line is centred at (width/2 + 0.137, height/2 + 0.291).

    Returns
    -------
    dict of str to (N,) ndarray of float64
        For each method (2x2 and 4x4 supersampling, Wu, Gupta-Sproull,
        DISLOP_L): the sum of its image over the segment's middle major-axis
        columns (those whole inside the segment, `MARGIN` columns clear of
        each end, so no method's end treatment counts), divided by the length
        of the segment over them. 1 for an exact area method.

    Raises
    ------
    TypeError, ValueError
        If `angles` is not a 1-D array of degrees in 0..90, or `length` is not
        a positive real number that fits.

    Examples
    --------
    >>> data = intensity_per_length([0, 30, 45], 20, 32, 32)
    >>> data["Wu"].round(4).tolist(), data["DISLOP_L"].round(12).tolist()
    ([1.0, 0.866, 0.7071], [1.0, 1.0, 1.0])
    """
    angles = _check_angles(angles)
    if (
        isinstance(length, bool)
        or not isinstance(length, numbers.Real)
        or not math.isfinite(length)
    ):
        raise TypeError(f"'length' must be a finite real number; got {short_repr(length)}")
    room = min(width, height) - 2 * MARGIN - 4
    if not 2 * MARGIN + 1 < length <= room:
        raise ValueError(
            f"'length' must be in {2 * MARGIN + 1}..{room} (more than {2 * MARGIN + 1} columns, "
            f"the line on the {width}x{height} raster); got {short_repr(length)}"
        )
    centre = np.array([width / 2 + 0.137, height / 2 + 0.291])
    methods = _ropiness_methods()
    data = {name: np.empty(len(angles)) for name in methods}
    for k, angle in enumerate(np.radians(angles)):
        half = 0.5 * length * np.array([math.cos(angle), math.sin(angle)])
        p0, p1 = centre - half, centre + half
        steep = abs(p1[1] - p0[1]) > abs(p1[0] - p0[0])  # the major axis, as every method picks it
        axis = 1 if steep else 0
        first = math.ceil(min(p0[axis], p1[axis])) + MARGIN
        last = math.floor(max(p0[axis], p1[axis])) - MARGIN  # columns first..last - 1
        along = abs(p1[axis] - p0[axis]) / length  # major-axis extent per unit length
        for name, method in methods.items():
            image = method(p0, p1, width, height)
            columns = image[first:last, :] if steep else image[:, first:last]
            data[name][k] = float(columns.sum()) * along / (last - first)
    return data

"""The pixel conventions of scanviz, in one place (DESIGN §2).

* Screen space is y-up: x grows right, y grows up; scanlines run bottom to top.
  Images are arrays ``img[y, x]`` with row 0 at the bottom (show them with
  ``origin="lower"``; PNG export flips rows).
* A pixel is a unit square: pixel (x, y) is [x, x+1) x [y, y+1).
* Sampling: ``sample="corner"`` samples pixel (x, y) at (x, y), its lower-left
  corner; ``sample="center"`` at (x + 0.5, y + 0.5), as GPUs do.
* Ownership: a sample exactly on the boundary is decided as if it were the
  point (sx + eps, sy + eps**2) for an infinitesimal eps > 0. A pixel owns its
  left and lower borders and its lower-left corner; shared edges are covered
  exactly once. Under a y-flip this is the Direct3D/OpenGL top-left rule.
* Inside: nonzero winding (default) or even-odd.
* Sub-pixel precision: vertices snap to a grid of 1/2**bits pixel (default 8,
  round half to even as ``numpy.rint``); every inside/outside decision is made
  with exact integer arithmetic on the snapped values. ``subpixel_bits=None``
  keeps the float64 values and decides them exactly too.
* Coordinates are real numbers (int or float; not bool, str or complex), finite,
  within +-COORD_LIMIT pixels (`scanviz.geometry.as_coordinates` checks them).

The argument checks every package shares live here too, one function a rule,
each raising an error that names the argument and the rule.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable

import numpy as np

SAMPLE_MODES = ("corner", "center")
RULES = ("nonzero", "evenodd")
ARITHMETICS = ("exact", "float32", "float64")
DEFAULT_SUBPIXEL_BITS = 8
MAX_SUBPIXEL_BITS = 16
COORD_LIMIT = 2**20
MAX_RASTER_SIZE = 2**16


def short_repr(value: object) -> str:
    """`value` for an error message: huge ints by their size (their digits may not even print).

    >>> short_repr(10**400), short_repr(-3), short_repr("x" * 80)[-6:]
    ('<an int of 1329 bits>', '-3', 'xxx...')
    """
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > 2**64:
        return f"{'-' if value < 0 else ''}<an int of {value.bit_length()} bits>"
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def sample_offset(sample: str) -> float:
    """Offset of a pixel's sample point from its lower-left corner, in pixels.

    >>> sample_offset("corner"), sample_offset("center")
    (0.0, 0.5)
    """
    return 0.5 if check_choice("sample", sample, SAMPLE_MODES) == "center" else 0.0


def check_choice(name: str, value: object, choices: tuple[str, ...]) -> str:
    """Return `value` if it is one of `choices`, else raise a ValueError naming `name`."""
    if not isinstance(value, str) or value not in choices:
        raise ValueError(
            f"{name!r} must be one of {', '.join(map(repr, choices))}; got {short_repr(value)}"
        )
    return value


def check_subpixel_bits(subpixel_bits: object) -> int | None:
    """Validate `subpixel_bits`: an int in 0..MAX_SUBPIXEL_BITS, or None for unsnapped input."""
    if subpixel_bits is None:
        return None
    if isinstance(subpixel_bits, bool) or not isinstance(subpixel_bits, numbers.Integral):
        raise TypeError(f"'subpixel_bits' must be an int or None; got {short_repr(subpixel_bits)}")
    if not 0 <= subpixel_bits <= MAX_SUBPIXEL_BITS:
        raise ValueError(
            f"'subpixel_bits' must be in 0..{MAX_SUBPIXEL_BITS} or None; "
            f"got {short_repr(subpixel_bits)}"
        )
    return int(subpixel_bits)


def check_index(name: str, value: object) -> int:
    """Validate an index recorded in trace events: an int >= 0 (not a bool)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name!r} must be an int >= 0; got {short_repr(value)}")
    if value < 0:
        raise ValueError(f"{name!r} must be an int >= 0; got {short_repr(value)}")
    return int(value)


def check_int(name: str, value: object, low: int, high: int) -> int:
    """`value` as an int if it is an integer (not a bool) in low..high, else an error naming `name`.

    >>> check_int("k", 3, 1, 64)
    3
    >>> check_int("k", 0, 1, 64)
    Traceback (most recent call last):
    ValueError: 'k' must be in 1..64; got 0
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name!r} must be an int; got {short_repr(value)}")
    if not low <= value <= high:
        raise ValueError(f"{name!r} must be in {low}..{high}; got {short_repr(value)}")
    return int(value)


def check_raster_size(width: object, height: object) -> tuple[int, int]:
    """Validate a raster size: ints in 0..MAX_RASTER_SIZE (zero gives an empty raster)."""
    width = check_int("width", width, 0, MAX_RASTER_SIZE)
    return width, check_int("height", height, 0, MAX_RASTER_SIZE)


def finite_real(name: str, value: object) -> float:
    """`value` as a float if it is a finite real number (not a bool), else an error naming `name`.

    >>> finite_real("ks", 1), finite_real("ks", 0.5)
    (1.0, 0.5)
    >>> finite_real("ks", float("nan"))
    Traceback (most recent call last):
    ValueError: 'ks' must be finite; got nan
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name!r} must be a real number; got {value!r}")
    try:
        finite = math.isfinite(value)
    except OverflowError:  # an int beyond any float
        finite = False
    if not finite:
        raise ValueError(f"{name!r} must be finite; got {short_repr(value)}")
    return float(value)


def check_finite(name: str, array: np.ndarray) -> np.ndarray:
    """Return `array` if all its values are finite, else a ValueError showing them all."""
    if not np.isfinite(array).all():
        raise ValueError(f"{name!r} must be finite; got {array.tolist()}")
    return array


def check_finite_rows(name: str, array: np.ndarray) -> np.ndarray:
    """Return `array` if all its values are finite, else a ValueError naming the first bad row.

    >>> check_finite_rows("points", np.array([[0.0, 1.0], [2.0, np.inf]]))
    Traceback (most recent call last):
    ValueError: 'points' row 1 is not finite: [2.0, inf]
    """
    finite = np.isfinite(array)
    if not finite.all():
        row = int(np.argwhere(~finite)[0][0])
        raise ValueError(f"{name!r} row {row} is not finite: {array[row].tolist()}")
    return array


def check_rows(name: str, array: np.ndarray, broken: np.ndarray, rule: str) -> None:
    """Raise a ValueError naming the first row of `array` where `broken` holds, and its `rule`.

    >>> z = np.array([0.5, np.nan])
    >>> check_rows("z", z, ~np.isfinite(z), "is not finite")
    Traceback (most recent call last):
    ValueError: 'z'[1] = nan is not finite
    """
    if broken.any():
        row = int(np.argwhere(broken)[0][0])
        raise ValueError(f"{name!r}[{row}] = {array[row].tolist()} {rule}")


def type_name(value: object) -> str:
    """The name of `value`'s type, for an error message that must not print `value` itself."""
    return type(value).__name__


def as_array(
    value: object,
    rule: str,
    *,
    dtype: type = np.float64,
    copy: bool = False,
    got: Callable[[object], str] = short_repr,
) -> np.ndarray:
    """`value` as an ndarray of `dtype` (a fresh one if `copy`), else a TypeError stating `rule`.

    >>> as_array([1, 2], "'xs' must be numbers").tolist()
    [1.0, 2.0]
    >>> as_array("ab", "'xs' must be numbers")
    Traceback (most recent call last):
    TypeError: 'xs' must be numbers; got 'ab'
    """
    try:
        return np.array(value, dtype=dtype) if copy else np.asarray(value, dtype=dtype)
    except (TypeError, ValueError):
        raise TypeError(f"{rule}; got {got(value)}") from None

"""Argument checks shared by the DISLOP entry points (DESIGN §6): name the argument and the rule."""

from __future__ import annotations

import math
import numbers

import numpy as np

from ..conventions import COORD_LIMIT, check_raster_size, short_repr
from ..geometry import as_coordinates
from ..limits import check_memory
from ..raster.api import as_tracer
from ..trace import Recorder, Tracer

__all__ = ["as_tracer", "check_flag", "check_point", "check_radius", "new_raster", "finish"]


def check_point(name: str, value: object) -> tuple[float, float]:
    """`value` as a finite (x, y) within +-2**20 pixels."""
    x, y = as_coordinates(value, repr(name), (2,)).tolist()
    return x, y


def check_radius(value: object) -> float:
    """A radius: a real number, finite, in 0..2**20 pixels."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"'radius' must be a real number; got {short_repr(value)}")
    try:
        radius = float(value)
    except OverflowError:  # an int (or Fraction) beyond float64: past the limit below anyway
        radius = math.inf
    if not math.isfinite(radius) or not 0.0 <= radius <= COORD_LIMIT:
        raise ValueError(f"'radius' must be finite and in 0..2**20; got {short_repr(value)}")
    return radius


def check_flag(name: str, value: object) -> bool:
    """A bool option."""
    if not isinstance(value, bool | np.bool_):
        raise TypeError(f"{name!r} must be a bool; got {short_repr(value)}")
    return bool(value)


def new_raster(width: object, height: object, what: str, pixel_bytes: int = 8) -> np.ndarray:
    """A zero (height, width) float64 raster, after the size and memory checks.

    `pixel_bytes` is what the caller needs per pixel in all, the raster included.
    """
    width, height = check_raster_size(width, height)
    check_memory(pixel_bytes * width * height, f"{what}: a {width}x{height} float64 raster")
    return np.zeros((height, width))


def finish(image: np.ndarray, trace: object, tracer: Tracer | None):
    """The image, or (image, Trace) when the caller asked for a new recorder with ``trace=True``."""
    if trace is True and isinstance(tracer, Recorder):
        return image, tracer.trace()
    return image

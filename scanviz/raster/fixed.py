"""Snapping to the sub-pixel grid, and the exact integer view of a polygon.

Internally a polygon lives on an integer grid of ``scale = 2**(bits + 1)``
units per pixel, shifted so that the sample of pixel (x, y) sits at the grid
point (x * scale, y * scale) in both sample modes:

* corner sampling: ``units = 2 * rint(v * 2**bits)``;
* center sampling: ``units = 2 * rint(v * 2**bits) - 2**bits`` (the polygon
  moves half a pixel down-left instead of the samples moving up-right).

The extra factor 2 keeps the half-pixel shift an integer even at ``bits = 0``.
With ``subpixel_bits=None`` nothing is rounded: the grid is the finest power
of two that holds every float64 coordinate exactly (Python ints if needed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
from numba import njit

from ..conventions import MAX_SUBPIXEL_BITS, SAMPLE_MODES, check_choice, check_subpixel_bits
from ..geometry import Polygon


@dataclass(frozen=True)
class SnappedPolygon:
    """A polygon on the integer grid.

    Attributes
    ----------
    units : (M, 2) ndarray of int64, or of object (Python ints) for very fine grids
        Vertex coordinates in grid units, contour after contour.
    offsets : (C + 1,) ndarray of int64
        Start of each contour in `units`, plus the total.
    bits : int
        Sub-pixel bits of the grid actually used (for ``subpixel_bits=None``,
        the finest needed to hold the input exactly).
    sample : str
        "corner" or "center".
    """

    units: np.ndarray
    offsets: np.ndarray
    bits: int
    sample: str

    @property
    def scale(self) -> int:
        """Grid units per pixel."""
        return 2 ** (self.bits + 1)

    @property
    def shift(self) -> int:
        """Grid units subtracted from snapped coordinates to put samples on the grid."""
        return 2**self.bits if self.sample == "center" else 0

    @property
    def compilable(self) -> bool:
        """True when the int64 kernels can take this grid (bits <= MAX_SUBPIXEL_BITS)."""
        return self.units.dtype == np.int64

    def to_pixels(self, value: int) -> Fraction:
        """A grid coordinate as an exact pixel coordinate in the caller's frame."""
        return Fraction(value + self.shift, self.scale)

    def pixel_vertices(self) -> np.ndarray:
        """The snapped vertices in pixels, caller's frame: (M, 2) ndarray of float64."""
        return np.array([[float(self.to_pixels(int(u))) for u in row] for row in self.units])


FLOAT64_FRACTION_BITS = 1074  # the smallest float64, 2**-1074, needs the most


def exact_bits(values: np.ndarray) -> int:
    """Fewest fractional bits that represent every (finite) float64 in `values` exactly.

    >>> exact_bits(np.array([1.0, 0.75, -3.125])), exact_bits(np.array([5e-324]))
    (3, 1074)
    """
    values = np.asarray(values, dtype=np.float64)
    if not np.isfinite(values).all():
        raise ValueError("exact_bits takes finite values only")
    return exact_bits_compiled(values, FLOAT64_FRACTION_BITS)


@njit(cache=True)
def exact_bits_compiled(values, most):
    """`exact_bits` of a float64 array, or `most` + 1 once a value needs more (kernels stop there)."""
    found = 0
    for v in values.flat:
        bits = 0
        while bits <= most and math.floor(v) != v:
            v *= 2.0  # exact: doubling a float64 changes only its exponent
            bits += 1
        found = max(found, bits)
    return found


def snap_units(vertices: np.ndarray, sample: str, bits: int) -> np.ndarray:
    """Grid units of vertices (any shape ending in 2) for `bits` sub-pixel bits, as `snap` does.

    int64 for bits <= MAX_SUBPIXEL_BITS, else exact Python ints (dtype object).
    """
    if bits <= MAX_SUBPIXEL_BITS:
        units = 2 * np.rint(vertices * 2.0**bits).astype(np.int64)
    else:
        exact = [2 * int(Fraction(float(v)) * 2**bits) for v in vertices.ravel()]
        units = np.array(exact, dtype=object).reshape(vertices.shape)
    return units - 2**bits if sample == "center" else units


def snap(polygon: Polygon, sample: str = "corner", subpixel_bits: int | None = 8) -> SnappedPolygon:
    """Snap `polygon` to the grid of DESIGN §2.

    Examples
    --------
    >>> s = snap(Polygon([(0, 0), (1.3, 0), (0, 1)]), subpixel_bits=2)
    >>> s.scale, s.units.tolist()
    (8, [[0, 0], [10, 0], [0, 8]])
    """
    check_choice("sample", sample, SAMPLE_MODES)
    bits = check_subpixel_bits(subpixel_bits)
    vertices = polygon.vertices
    if bits is None:
        bits = exact_bits(vertices)
    units = snap_units(vertices, sample, bits)
    units.setflags(write=False)
    return SnappedPolygon(units, polygon.offsets, bits, sample)

"""Vector lengths and unit vectors that neither overflow nor underflow.

``sqrt(x*x + y*y + z*z)`` overflows to inf for components near 1e155 and
underflows to 0 below 1e-162, so ``v / |v|`` turns valid finite vectors into
zeros or NaN. Here each vector is first divided by its largest absolute
component (exact in binary floating point up to rounding of one division),
which brings the largest component to 1, and only then squared and summed.
"""

from __future__ import annotations

import numpy as np


def vector_norm(vectors: np.ndarray) -> np.ndarray:
    """Euclidean length along the last axis, without intermediate overflow or underflow.

    The result is inf only when the true length exceeds the float64 range.

    >>> float(vector_norm(np.array([1e200, 1e200, 0.0]))) / 1e200
    1.4142135623730951
    >>> float(vector_norm(np.array([3e-300, 4e-300, 0.0]))) / 1e-300
    5.0
    """
    vectors = np.asarray(vectors, dtype=np.float64)
    scale = np.max(np.abs(vectors), axis=-1)
    safe = np.where(scale > 0, scale, 1.0)
    scaled = vectors / safe[..., None]
    with np.errstate(over="ignore"):
        return scale * np.sqrt(np.sum(scaled * scaled, axis=-1))


def unit_vectors(vectors: np.ndarray) -> np.ndarray:
    """Unit vectors along the last axis; a zero vector stays zero (callers decide if that is an error).

    >>> unit_vectors(np.array([[1e308, 1e308, 0.0], [1e-320, 0.0, 0.0], [0.0, 0.0, 0.0]])).round(6).tolist()
    [[0.707107, 0.707107, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    """
    vectors = np.asarray(vectors, dtype=np.float64)
    scale = np.max(np.abs(vectors), axis=-1, keepdims=True)
    nonzero = scale > 0
    scaled = vectors / np.where(nonzero, scale, 1.0)
    length = np.sqrt(np.sum(scaled * scaled, axis=-1, keepdims=True))
    return np.where(nonzero, scaled / np.where(nonzero, length, 1.0), 0.0)

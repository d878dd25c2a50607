"""Vector lengths and unit vectors that neither overflow nor underflow.

``sqrt(x*x + y*y + z*z)`` overflows to inf for components near 1e155 and
underflows to 0 below 1e-162, so ``v / |v|`` turns valid finite vectors into
zeros or NaN. Here each vector is first divided by its largest absolute
component (exact in binary floating point up to rounding of one division),
which brings the largest component to 1, and only then squared and summed.
"""

from __future__ import annotations

import numpy as np

_SAFE_LOW, _SAFE_HIGH = 1e-280, 1e280  # squared lengths between these lost nothing to range


def _squared_lengths(vectors: np.ndarray) -> np.ndarray:
    """x*x + y*y + ... summed in component order, so a compiled loop gets the same bits.

    (``einsum`` pairs the terms differently with the array's size and layout.)
    """
    with np.errstate(over="ignore", under="ignore"):
        total = vectors[..., 0] * vectors[..., 0]
        for k in range(1, vectors.shape[-1]):
            total = total + vectors[..., k] * vectors[..., k]
        return total


def _risky(squares: np.ndarray) -> np.ndarray:
    """Where the direct sum of squares may have overflowed or underflowed (or is 0, inf, NaN)."""
    return ~((squares > _SAFE_LOW) & (squares < _SAFE_HIGH))


def _scaled(vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(largest |component|, vectors divided by it): the slow path, exact in range."""
    scale = np.max(np.abs(vectors), axis=-1)
    return scale, vectors / np.where(scale > 0, scale, 1.0)[..., None]


def vector_norm(vectors: np.ndarray) -> np.ndarray:
    """Euclidean length along the last axis, without intermediate overflow or underflow.

    The result is inf only when the true length exceeds the float64 range.

    >>> float(vector_norm(np.array([1e200, 1e200, 0.0]))) / 1e200
    1.4142135623730951
    >>> float(vector_norm(np.array([3e-300, 4e-300, 0.0]))) / 1e-300
    5.0
    """
    vectors = np.asarray(vectors, dtype=np.float64)
    squares = np.atleast_1d(_squared_lengths(vectors))
    lengths = np.sqrt(squares)
    risky = _risky(squares)
    if risky.any():
        scale, scaled = _scaled(vectors.reshape(-1, vectors.shape[-1])[risky.ravel()])
        with np.errstate(over="ignore"):
            lengths[risky] = scale * np.sqrt(_squared_lengths(scaled))
    return lengths.reshape(vectors.shape[:-1])


def unit_vectors(vectors: np.ndarray) -> np.ndarray:
    """Unit vectors along the last axis; a zero vector stays zero (callers decide if that is an error).

    >>> unit_vectors(np.array([[1e308, 1e308, 0.0], [1e-320, 0.0, 0.0], [0.0, 0.0, 0.0]])).round(6).tolist()
    [[0.707107, 0.707107, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    """
    vectors = np.asarray(vectors, dtype=np.float64)
    squares = _squared_lengths(vectors)
    risky = _risky(squares)
    units = vectors / np.sqrt(np.where(risky, 1.0, squares))[..., None]
    if np.any(risky):
        flat = units.reshape(-1, vectors.shape[-1])
        pick = np.atleast_1d(risky).ravel()
        _, scaled = _scaled(vectors.reshape(-1, vectors.shape[-1])[pick])
        length = np.sqrt(_squared_lengths(scaled))
        flat[pick] = np.where(
            length[:, None] > 0, scaled / np.where(length > 0, length, 1.0)[:, None], 0.0
        )
        units = flat.reshape(vectors.shape)
    return units

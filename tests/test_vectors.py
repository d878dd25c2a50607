"""Overflow-safe lengths and unit vectors against exact rational arithmetic."""

import math
from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.vectors import unit_vectors, vector_norm

finite = st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True)


BIGGEST = 1.7976931348623157e308


def exact_norm(vector) -> float:
    """The length from the exact sum of squares (inf when it is beyond the float range)."""
    squares = sum(Fraction(x) ** 2 for x in vector)
    if squares >= Fraction(BIGGEST) ** 2:
        return math.inf
    # sqrt of the exact sum: split off a power of four so float() stays in range
    shift = (squares.numerator.bit_length() - squares.denominator.bit_length()) // 2
    return math.ldexp(math.sqrt(float(squares / Fraction(4) ** shift)), shift) if squares else 0.0


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.lists(finite, min_size=3, max_size=3))
def test_lengths_match_exact_arithmetic_at_every_magnitude(vector):
    expected = exact_norm(vector)
    got = float(vector_norm(np.array(vector)))
    if math.isinf(expected):  # at the edge of the range: inf or the largest floats
        assert got > BIGGEST * (1 - 4e-16)
    else:
        assert math.isclose(got, expected, rel_tol=4e-16, abs_tol=5e-324 * 4)


@settings(derandomize=True, max_examples=300, deadline=None)
@given(st.lists(st.lists(finite, min_size=3, max_size=3), min_size=1, max_size=5))
def test_unit_vectors_have_length_one_or_stay_zero(vectors):
    units = unit_vectors(np.array(vectors))
    for vector, unit in zip(vectors, units, strict=True):
        if not any(vector):
            assert not unit.any()
        else:
            assert abs(math.hypot(*unit) - 1.0) < 4e-16
            assert all(
                math.copysign(1, u) == math.copysign(1, v)
                for u, v in zip(unit, vector, strict=True)
                if v
            )

"""Plain values cross the sandbox boundary as JSON and come back equal."""

import json
import math
from fractions import Fraction
from typing import NamedTuple

import numpy as np

from scanviz.exercises.plain import Opaque, Record, from_plain, to_plain
from scanviz.trace.events import Span


class Entry(NamedTuple):
    x: Fraction
    winding: int


def _round_trip(value):
    return from_plain(json.loads(json.dumps(to_plain(value), allow_nan=False)))


def test_numbers_fractions_and_non_finite_floats_survive():
    assert _round_trip([1, Fraction(-7, 3), 2.5, None, True, "s"]) == [
        1,
        Fraction(-7, 3),
        2.5,
        None,
        True,
        "s",
    ]
    back = _round_trip([math.inf, -math.inf, math.nan])
    assert back[:2] == [math.inf, -math.inf] and math.isnan(back[2])


def test_records_events_and_arrays_survive():
    assert _round_trip(Entry(Fraction(1, 2), -1)) == Record(
        "Entry", {"x": Fraction(1, 2), "winding": -1}
    )
    assert _round_trip(Span(0, 3, 1, 4, 1)) == Span(0, 3, 1, 4, 1)
    array = _round_trip(np.array([[True, False]]))
    assert array.dtype == bool and array.tolist() == [[True, False]]


def test_unknown_values_become_opaque_and_equal_nothing_else():
    class Weird:
        def __repr__(self):
            raise RuntimeError("no")

    back = _round_trip(Weird())
    assert isinstance(back, Opaque) and "unprintable" in back.repr
    assert _round_trip(object()) != Record("object", {})


def test_malformed_plain_data_is_a_value_error():
    import pytest

    for bad in ({}, {"$what": 1}, {"$fraction": [1]}):
        with pytest.raises((ValueError, TypeError)):
            from_plain(bad)


def test_values_read_back_encode_to_the_same_plain_form():
    for value in ([Entry(Fraction(1, 2), -1), Span(0, 3, 1, 4, 1)], object(), {"a": (1, 2.5)}):
        plain = to_plain(value)
        assert to_plain(from_plain(plain)) == plain

"""Structural comparison: exact numbers, tolerances, aligned traces, raster diffs."""

from fractions import Fraction

import numpy as np

from scanviz.exercises.compare import (
    first_difference,
    raster_difference,
    show,
    trace_difference,
)
from scanviz.exercises.jail.wire import Fields
from scanviz.trace.events import AetEntry, AetSorted, Span


def test_fractions_are_shown_as_the_slides_write_them():
    assert show(Fraction(17, 5)) == "17/5 (3 2/5 = 3.4)"
    assert show(Fraction(-3, 10)) == "-3/10 (-0.3)"
    assert show(Fraction(6, 1)) == "6"


def test_exact_numbers_compare_exactly_and_floats_within_the_tolerance():
    assert first_difference(Fraction(1, 3), 1 / 3) is not None
    assert first_difference(3, Fraction(3)) is None
    assert first_difference(0.1 + 0.2, 0.3) is not None
    assert first_difference(0.1 + 0.2, 0.3, rtol=1e-12) is None
    assert first_difference(True, 1) is not None  # a bool is not a number here


def test_paths_name_the_field_and_index():
    yours = [Fields("E", {"x": Fraction(17, 5), "w": 1})]
    reference = [Fields("E", {"x": Fraction(37, 10), "w": 1})]
    difference = first_difference(yours, reference)
    assert difference.path == "[0].x"
    assert (
        difference.describe() == "[0].x: yours 17/5 (3 2/5 = 3.4), reference 37/10 (3 7/10 = 3.7)"
    )


def test_a_tuple_equals_a_list_with_the_same_items():
    assert first_difference((1, 2), [1, 2]) is None
    assert (
        first_difference([1, 2], [1, 2, 3]).describe() == "[2]: missing in yours; reference has 3"
    )


def test_arrays_report_the_first_differing_index():
    difference = first_difference(np.array([[1, 2], [3, 4]]), np.array([[1, 2], [3, 5]]))
    assert difference.path == "[1, 1]" and (difference.yours, difference.reference) == (4, 5)


def _aet(y, x):
    entry = AetEntry(
        edge=0, x=float(x), x_exact=x, dxdy=0.0, dxdy_exact=Fraction(0), ymax=9.0, winding=1
    )
    return AetSorted(polygon=0, y=y, entries=(entry,), swaps=0)


def test_one_extra_event_does_not_make_every_later_event_differ():
    reference = [
        _aet(0, Fraction(1)),
        Span(0, 0, 1, 3, 1),
        _aet(1, Fraction(2)),
        Span(0, 1, 2, 3, 1),
    ]
    yours = [reference[0], reference[1], Span(0, 0, 4, 5, 1), *reference[2:]]
    difference = trace_difference(yours, reference)
    assert (difference.index, difference.kind, difference.place) == (2, "span", "row 0")
    assert difference.difference.describe().startswith("extra in yours")
    assert difference.later == ()


def test_a_changed_field_is_found_and_later_rows_are_listed():
    reference = [_aet(y, Fraction(y)) for y in range(4)]
    yours = [
        _aet(0, Fraction(0)),
        _aet(1, Fraction(3, 2)),
        _aet(2, Fraction(2)),
        _aet(3, Fraction(7, 2)),
    ]
    difference = trace_difference(yours, reference)
    assert difference.place == "row 1" and difference.difference.path == "entries[0].x"
    assert difference.later == ("row 3",)
    assert trace_difference(reference, reference) is None


def test_raster_difference_draws_the_scotty3d_legend_y_up():
    reference = np.array([[1, 1, 0], [0, 1, 0]], dtype=bool)  # row 0 is the bottom
    yours = np.array([[1, 0, 1], [0, 1, 0]], dtype=bool)
    diff = raster_difference(yours, reference)
    assert (diff.matched, diff.missing, diff.extra) == (2, 1, 1)
    assert diff.art() == ".#.\n#?!"
    assert raster_difference(reference, reference) is None
    assert raster_difference(np.zeros((5, 5)), reference).missing == 3  # wrong shape: empty


def test_an_aet_entry_is_named_by_its_edge_where_the_order_differs():
    def entry(edge, x):
        return AetEntry(
            edge=edge, x=float(x), x_exact=x, dxdy=0.0, dxdy_exact=Fraction(0), ymax=9.0, winding=1
        )

    yours = AetSorted(
        polygon=0, y=2, entries=(entry(2, Fraction(17, 5)), entry(0, Fraction(5))), swaps=1
    )
    reference = AetSorted(
        polygon=0, y=2, entries=(entry(2, Fraction(37, 10)), entry(0, Fraction(5))), swaps=1
    )
    difference = first_difference(yours, reference)
    assert difference.path == "entries[0] (e2).x"
    assert difference.describe() == "entries[0] (e2).x: yours 3.4, reference 3.7"

"""The checks of a replaced edge_table_entry or aet_update (scanviz.exercises.scan_checks).

A replaced step is called through its check wherever it is installed -- by an
exercise or by `steps.using` directly -- so what it returns reaches the
reference loop in the reference's form, or stops with a clear error. Values
are the UMBC slide polygon's, derived by hand in tests/raster/test_scanline.py.
"""

import subprocess
import sys
from fractions import Fraction

import pytest

from scanviz import steps
from scanviz.exercises.scan_checks import checked_aet_update
from scanviz.raster.scanline import AetItem, aet_update, edge_table_entry

from ..raster.test_scanline_steps import _aet_x, _trace

F = Fraction


def test_a_replacement_is_called_through_its_check_and_others_as_they_are():
    def update(active, y, entering):
        return aet_update(active, y, entering)

    def rule(crossings, rule):
        return []

    with steps.using(aet_update=update, span_rule=rule):
        assert steps.get("span_rule") is rule
        checked = steps.get("aet_update")
        assert checked is not update and checked is not steps.get("aet_update")  # one per run
    assert steps.get("aet_update") is aet_update


def test_the_step_table_and_the_reference_import_no_exercise_module():
    code = (
        "import sys, scanviz.steps, scanviz.raster.scanline; "
        "print(any(m.startswith('scanviz.exercises') for m in sys.modules))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


def test_a_check_must_be_listed_for_its_step():
    with pytest.raises(TypeError, match="not listed in CHECKS"):
        steps.check("span_rule")(lambda function: function)


def test_an_entry_may_be_a_plain_tuple_of_lists_and_floats():
    def plain(start, end):
        entry = edge_table_entry(start, end)
        return (
            None
            if entry is None
            else ([float(v) for v in entry.lower], list(entry.upper), *entry[2:])
        )

    assert _trace(edge_table_entry=plain) == _trace()


def test_an_edge_left_out_enters_on_the_next_row_at_that_rows_x():
    # Taking entering edges one row late: edge 0 enters on row 2 at x = 4 - 3/10 = 37/10.
    def late(active, y, entering):
        return aet_update(active, y, [e for e in entering if e.bucket < y])

    trace = _trace(aet_update=late)
    assert [(e.y, list(e.edges)) for e in trace.of_kind("edges_activated")] == [
        (2, [0, 3]),
        (6, [1, 2]),
    ]
    assert _aet_x(trace, 2) == [F(37, 10), 12]


def test_an_edge_left_out_comes_again_as_offered_whatever_the_step_did_to_it():
    offered = []

    def late_and_meddling(active, y, entering):
        offered.append([(e.edge, e.x) for e in entering])
        for e in entering:
            e.x += 100  # changes an item it then leaves out
        return aet_update(active, y, [e for e in entering if e.bucket < y])

    checked = checked_aet_update(late_and_meddling)
    edge = AetItem(0, F(4), F(-3, 10), 1, 11, 1)
    assert checked([], 1, [edge]) == ([], [])
    retired, aet = checked([], 3, [])  # two rows on: x stepped twice, then taken
    assert offered == [[(0, 4)], [(0, F(34, 10))]] and [e.edge for e in aet] == [0]
    checked(aet, 4, [])
    assert offered[-1] == []  # taken: not offered again


@pytest.mark.parametrize(
    ("entry", "error", "message"),
    [
        (lambda s, e: (s, e), TypeError, "must return None or (lower, upper, winding, bucket"),
        (
            lambda s, e: ((s[0] + F(1, 1024), s[1]), e, 1, 0, 9),
            ValueError,
            "off the 1/512 pixel grid",
        ),
        (lambda s, e: (s, e, 1.0, 0, 9), TypeError, "'winding' must be an int; got 1.0 (float)"),
        (lambda s, e: ("s", e, 1, 0, 9), TypeError, "'lower' must be an (x, y) point"),
    ],
)
def test_a_bad_entry_is_a_clear_error(entry, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace(")", r"\)")):
        _trace(edge_table_entry=entry)


@pytest.mark.parametrize(
    ("update", "error", "message"),
    [
        (lambda a, y, e: a + e, TypeError, "must return (retired, active)"),
        (lambda a, y, e: ([], e), ValueError, "dropped edge 0 on row 2"),
        (lambda a, y, e: ([], a + e + a), ValueError, "returned edge 0 twice on row 2"),
        (lambda a, y, e: ([], [1, 2]), TypeError, "must return AET items (with .edge and .x)"),
    ],
)
def test_a_bad_aet_update_is_a_clear_error(update, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace(")", r"\)")):
        _trace(aet_update=update)


def test_an_entering_edge_the_step_retires_leaves_the_edge_table():
    def refuse(active, y, entering):
        return list(entering), []

    trace = _trace(aet_update=refuse)
    assert [(e.y, list(e.edges)) for e in trace.of_kind("edges_retired")] == [
        (1, [0, 3]),
        (5, [1, 2]),
    ]
    assert not trace.of_kind("aet_sorted") and not trace.of_kind("span")

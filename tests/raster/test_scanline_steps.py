"""The replaceable steps of the ET/AET loop: edge_table_entry and aet_update.

A replaced step drives the real loop: its entries set the rows, its AET sets
the x the trace shows and the spans are cut from. Values are the UMBC slide
polygon's, derived by hand in test_scanline.py.
"""

import dataclasses
from fractions import Fraction

import pytest

from scanviz import scan_convert, steps
from scanviz.catalog import get
from scanviz.raster.scanline import aet_update, edge_table_entry

F = Fraction
UMBC = get("umbc_example")


def _trace(**replaced):
    with steps.using(**replaced):
        return scan_convert(UMBC.polygon, UMBC.width, UMBC.height, trace=True).trace


def _aet_x(trace, y):
    (row,) = [e for e in trace.of_kind("aet_sorted") if e.y == y]
    return [entry.x_exact for entry in row.entries]


@pytest.mark.parametrize("arithmetic", ["exact", "float32", "float64"])
def test_the_reference_steps_plugged_in_give_the_default_trace(arithmetic):
    def run():
        return scan_convert(UMBC.polygon, 16, 16, arithmetic=arithmetic, trace=True).trace

    default = run()
    with steps.using(edge_table_entry=edge_table_entry, aet_update=aet_update):
        assert run() == default


def test_an_entrys_rows_decide_when_the_edge_is_active():
    # Edge 3 is the vertical (12, 8)-(12, 1), rows 1..7; an entry saying rows 3..5 drives the loop.
    def short(start, end):
        entry = edge_table_entry(start, end)
        return entry._replace(bucket=3, row_end=6) if entry and entry.lower == (12, 1) else entry

    trace = _trace(edge_table_entry=short)
    activated = {e.y: list(e.edges) for e in trace.of_kind("edges_activated")}
    retired = {e.y: list(e.edges) for e in trace.of_kind("edges_retired")}
    assert activated == {1: [0], 3: [3], 5: [1, 2]}
    assert retired[6] == [3]
    assert trace.of_kind("edge_table_built")[0].edges[3].bucket == 3


def test_the_trace_shows_the_x_the_step_returns():
    def drifting(active, y, entering):
        retired, aet = aet_update(active, y, entering)
        return retired, [dataclasses.replace(e, x=float(e.x) + 1e-9) for e in aet]

    trace = _trace(aet_update=drifting)
    (row,) = [e for e in trace.of_kind("aet_sorted") if e.y == 2]
    # Row 1 enters x = 4 and 12, each returned + 1e-9; row 2 steps by dx/dy = -3/10 and 0.
    expected = [((4 + 1e-9) + F(-3, 10)) + 1e-9, ((12 + 1e-9) + 0) + 1e-9]
    assert [(e.x, e.x_exact) for e in row.entries] == [(x, None) for x in expected]


def test_swaps_count_the_exchanges_from_the_previous_order_to_the_returned_one():
    # Row 1 enters edges 0 (x = 4) and 3 (x = 12) in that order; reversed, that is one exchange.
    def reversed_aet(active, y, entering):
        retired, aet = aet_update(active, y, entering)
        return retired, aet[::-1]

    trace = _trace(aet_update=reversed_aet)
    row = trace.of_kind("aet_sorted")[0]
    assert (row.y, [e.edge for e in row.entries], row.swaps) == (1, [3, 0], 1)
    assert _trace().of_kind("aet_sorted")[0].swaps == 0


def test_a_replaced_step_runs_the_reference_without_a_tracer():
    with steps.using(aet_update=lambda a, y, e: aet_update(a, y, e)):
        result = scan_convert(UMBC.polygon, UMBC.width, UMBC.height)
    assert result.stats.path == "reference"
    assert (result.mask == scan_convert(UMBC.polygon, UMBC.width, UMBC.height).mask).all()

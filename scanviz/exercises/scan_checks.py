"""The checks of a replaced scan-conversion step: what a student's step returned, made usable.

The reference loop (`scanviz.raster.scanline`) trusts its steps. A replaced
``edge_table_entry`` or ``aet_update`` -- a student's, run by an exercise, or
anyone's through `scanviz.steps.using` -- is called through the check
registered here (`scanviz.steps.get`): it raises a clear error naming the
rule a result breaks, and hands the loop the result in the reference's form.

* ``edge_table_entry``: None, or an `EdgeEntry` whose ends are exact points
  on the grid of the vertices (any (x, y) pair of numbers there) and whose
  winding and rows are ints.
* ``aet_update``: (retired, aet), two lists of AET items (an int ``.edge``,
  a number ``.x``); every edge active or entering, none twice, none dropped.
  An entering edge the step neither took in nor retired is offered again on
  each later row the loop scans (it scans every row below the edge's
  ``row_end``), its x stepped by dx/dy, until the step takes or retires it.
"""

from __future__ import annotations

import dataclasses
import numbers
from collections.abc import Callable
from fractions import Fraction

from .. import steps
from ..raster.scanline import AetItem, EdgeEntry
from ..trace.schema import shown

# --- edge_table_entry ------------------------------------------------------------------------


@steps.check("edge_table_entry")
def checked_edge_table_entry(entry_of: Callable, *, scale: int) -> Callable:
    """`entry_of`, its entries checked and exact, ends on the grid of 1/`scale` pixel."""

    def checked(start: tuple, end: tuple) -> EdgeEntry | None:
        entry = entry_of(start, end)
        if entry is None:
            return None
        try:
            lower, upper, winding, bucket, row_end = entry
        except (TypeError, ValueError):
            raise TypeError(
                "edge_table_entry must return None or (lower, upper, winding, bucket, row_end); "
                f"got {shown(entry)}"
            ) from None
        return EdgeEntry(
            _grid_point("lower", lower, (start, end), scale),
            _grid_point("upper", upper, (start, end), scale),
            _entry_int("winding", winding),
            _entry_int("bucket", bucket),
            _entry_int("row_end", row_end),
        )

    return checked


def _grid_point(name: str, point: object, ends: tuple, scale: int) -> tuple:
    """An entry's end, (x, y) in pixels, exactly: it must lie on the sub-pixel grid."""
    for given in ends:
        if type(point) is tuple and point == given:  # one of the edge's endpoints, as given
            return given
    try:
        x, y = point  # type: ignore[misc]
    except (TypeError, ValueError):
        raise TypeError(
            f"edge_table_entry's {name!r} must be an (x, y) point; got {shown(point)}"
        ) from None
    return _on_grid(name, x, scale), _on_grid(name, y, scale)


def _on_grid(name: str, value: object, scale: int) -> Fraction:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"edge_table_entry's {name!r} must hold numbers; got {shown(value)}")
    try:
        exact = Fraction(value if isinstance(value, numbers.Rational) else float(value))
    except (ValueError, OverflowError):  # nan, inf
        raise ValueError(
            f"edge_table_entry's {name!r} must be finite; got {shown(value)}"
        ) from None
    if (exact * scale).denominator != 1:
        raise ValueError(
            f"edge_table_entry's {name!r} has {shown(value)}, off the 1/{scale} pixel grid "
            "of the vertices: the entry's ends must be the edge's endpoints"
        )
    return exact


def _entry_int(name: str, value: object) -> int:
    if type(value) is int:
        return value
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"edge_table_entry's {name!r} must be an int; got {shown(value)}")
    return int(value)


# --- aet_update ------------------------------------------------------------------------------


@steps.check("aet_update")
def checked_aet_update(update: Callable) -> Callable:
    """`update` with its results checked, for one run of the loop (`steps.get` makes one a run).

    An entering edge `update` neither took in nor retired comes again on the next row scanned.
    """
    waiting: list[tuple[AetItem, int]] = []  # (item as offered, its row): neither taken nor retired

    def checked(active: list, y: int, entering: list) -> tuple[list, list]:
        again = [dataclasses.replace(e, x=e.x + (y - row) * e.dxdy) for e, row in waiting]
        offered = again + list(entering)
        as_offered = [(dataclasses.replace(item), y) for item in offered]  # the step may change x
        returned = update(active, y, offered)
        previous, offered_ids = [e.edge for e in active], [e.edge for e in offered]
        retired, aet = _checked_update(returned, previous, offered_ids, y)
        gone = {item.edge for item in retired + aet}  # out of the edge table: in the AET or retired
        waiting[:] = [(item, row) for item, row in as_offered if item.edge not in gone]
        return retired, aet

    return checked


def _checked_update(returned: object, previous: list[int], entering: list[int], y: int):
    """What ``aet_update`` returned, as (retired, AET) lists of items, or a clear error."""
    try:
        retired, updated = returned  # type: ignore[misc]
        retired, updated = list(retired), list(updated)
    except (TypeError, ValueError):
        raise TypeError(
            "aet_update must return (retired, active): two lists of AET items; "
            f"got {shown(returned)}"
        ) from None
    retired_ids = [_item_edge(item, y) for item in retired]
    seen: set[int] = set()
    known = set(previous) | set(entering)
    for edge in retired_ids + [_item_edge(item, y, with_x=True) for item in updated]:
        if edge not in known:
            raise ValueError(
                f"aet_update returned edge {edge} on row {y}; it is neither active nor entering"
            )
        if edge in seen:
            raise ValueError(f"aet_update returned edge {edge} twice on row {y}")
        seen.add(edge)
    dropped = [edge for edge in previous if edge not in seen]
    if dropped:
        raise ValueError(
            f"aet_update dropped edge {dropped[0]} on row {y}: an active edge leaves the AET "
            "only by being retired"
        )
    return retired, updated


def _item_edge(item: object, y: int, with_x: bool = False) -> int:
    """The edge id of an AET item ``aet_update`` returned (whose x must be a number if `with_x`)."""
    edge = getattr(item, "edge", None)
    if isinstance(edge, bool) or not isinstance(edge, int):
        raise TypeError(
            f"aet_update must return AET items (with .edge and .x) on row {y}; got {shown(item)}"
        )
    x = getattr(item, "x", None)
    if with_x and (isinstance(x, bool) or not isinstance(x, numbers.Real)):
        raise TypeError(f"aet_update returned edge {edge} with x = {shown(x)} on row {y}")
    return edge

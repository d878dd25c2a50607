"""How records, stats and traces read in a notebook: HTML tables and plain text.

Rendering is a pure function of the value. A record (an event, a stats
object, a nested entry) is a table of field | value; a tuple of records is a
table with a row per record; a Trace is its counts per kind and its first
few events. Numbers are written as a student reads them:

- a `Fraction` as a mixed number, ``2 1/3`` (``-3/10``, ``7``);
- a float to `SIGNIFICANT` significant digits (``0.1 + 0.2`` reads ``0.3``),
  more only for its integer digits (``12346``), ``∞`` for infinity;
- an int field named like a coverage mask (``mask``, ``mask_a``, ``region``)
  as its sub-sample grid, row 0 at the bottom (bit ``j * cols + i`` is
  sub-sample (i, j), as `scanviz.abuffer.masks`), with its hex value;
- arrays and long lists by shape, type and a few values.

`RichDisplay` gives a class ``_repr_html_`` (what Jupyter shows) and a
readable ``__str__`` (what ``print`` shows); ``repr`` stays the dataclass's.

Examples
--------
>>> from fractions import Fraction
>>> fraction_text(Fraction(7, 3)), fraction_text(Fraction(-3, 10)), float_text(0.1 + 0.2)
('2 1/3', '-3/10', '0.3')
"""

from __future__ import annotations

import dataclasses
import html
import math
import sys
from collections import Counter
from collections.abc import Iterable, Mapping
from fractions import Fraction

SIGNIFICANT = 4  # digits of a float shown
ROWS_SHOWN = 12  # rows of a nested table (or events of a trace) before "... n more"
VALUES_SHOWN = 8  # numbers of a list or array shown inline
DEPTH = 3  # tables nested deeper than this are written on one line
MASK_LAYOUTS = ((4, 4), (8, 4), (8, 8))  # (cols, rows) tried, smallest first, for a mask alone

_TABLE = "border-collapse:collapse;margin:2px 0;font-size:12px"
_CELL = "padding:1px 6px;text-align:left;vertical-align:top;border:1px solid #ddd"
_HEAD = _CELL + ";background:#f3f3f3;font-weight:600"
_CAPTION = "caption-side:top;text-align:left;font-weight:600;padding:2px 0"
_MUTED = "color:#777"


def _numpy(kind: str) -> tuple[type, ...]:
    """numpy's `kind` (``"ndarray"``, ``"generic"``) if numpy is loaded, else no type: a value
    can only be an array once numpy is, and the exercise jail starts faster without it."""
    numpy = sys.modules.get("numpy")
    return (getattr(numpy, kind),) if numpy is not None else ()


# --- numbers ------------------------------------------------------------------------------


def fraction_text(value: Fraction) -> str:
    """A fraction as the slides write it: ``2 1/3``, ``-3/10``, ``7``.

    >>> fraction_text(Fraction(-7, 3)), fraction_text(Fraction(14, 2))
    ('-2 1/3', '7')
    """
    if value.denominator == 1:
        return str(value.numerator)
    whole = int(value)  # toward zero: the part keeps the sign
    part = abs(value - whole)
    if whole == 0:
        return f"{'-' if value < 0 else ''}{part}"
    return f"{whole} {part}"


def float_text(value: float) -> str:
    """A float to `SIGNIFICANT` significant digits (all its integer digits), ``∞`` for infinity.

    >>> float_text(0.6000000000000001), float_text(12345.678), float_text(-2.0), float_text(1e-7)
    ('0.6', '12346', '-2', '1e-07')
    """
    if math.isnan(value):
        return "NaN"
    if math.isinf(value):
        return "∞" if value > 0 else "-∞"
    if value == 0:
        return "0"
    digits = max(SIGNIFICANT, math.floor(math.log10(abs(value))) + 1)
    return f"{value:.{digits}g}" if digits <= 17 else f"{value:.{SIGNIFICANT}g}"


def number_text(value: object) -> str | None:
    """An int, Fraction, float or bool as text; None for anything else."""
    if isinstance(value, _numpy("generic")):
        value = value.item()
    if isinstance(value, bool):
        return str(value)
    if isinstance(value, int):
        return f"{value:,}" if abs(value) >= 10_000 else str(value)
    if isinstance(value, Fraction):
        return fraction_text(value)
    if isinstance(value, float):
        return float_text(value)
    return None


def is_mask(name: str, value: object) -> bool:
    """Whether field `name` holds a coverage mask (sub-sample bits)."""
    if isinstance(value, _numpy("generic")):
        value = value.item()
    return (
        isinstance(value, int)
        and not isinstance(value, bool)
        and value >= 0
        and ("mask" in name or name == "region")
    )


def mask_layout(value: object) -> tuple[int, int] | None:
    """The (cols, rows) of the masks in `value`: its ``layout`` field if any, else the smallest
    of `MASK_LAYOUTS` that holds its widest mask; None if it has no mask (or a wider one).

    >>> mask_layout({"mask": 0xFFFF}), mask_layout({"mask": 0xFFFFFFFF, "region": 1})
    ((4, 4), (8, 4))
    """
    widest, layout = 0, None
    for name, item in _walk(value, ""):
        if name == "layout" and isinstance(item, str) and "x" in item:
            cols, _, rows = item.lower().partition("x")
            if cols.isdigit() and rows.isdigit():
                layout = (int(cols), int(rows))
        elif is_mask(name, item):
            widest = max(widest, int(item).bit_length())
    if layout is not None or widest == 0:
        return layout
    return next(((c, r) for c, r in MASK_LAYOUTS if c * r >= widest), None)


def _walk(value: object, name: str, depth: int = 0) -> Iterable[tuple[str, object]]:
    """(field name, value) of every field in `value`, nested records and lists included."""
    if depth > 6:
        return
    fields = record_fields(value)
    if fields is not None:
        for key, item in fields.items():
            yield key, item
            yield from _walk(item, key, depth + 1)
    elif isinstance(value, Mapping):
        for key, item in list(value.items())[:1000]:
            yield str(key), item
            yield from _walk(item, str(key), depth + 1)
    elif isinstance(value, list | tuple):
        for item in value[:1000]:
            yield name, item
            yield from _walk(item, name, depth + 1)


def record_fields(value: object) -> dict | None:
    """The fields of a dataclass or named tuple by name; None for anything else."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return value._asdict()
    return None


def place(record: object) -> str:
    """Where an event happened: ``polygon 1, row 5``, ``pixel (3, 2)``; empty if it has no place."""
    parts = []
    polygon = getattr(record, "polygon", None)
    if isinstance(polygon, int) and not isinstance(polygon, bool):
        parts.append(f"polygon {polygon}")
    x, y = getattr(record, "x", None), getattr(record, "y", None)
    if isinstance(x, int) and isinstance(y, int) and not isinstance(x, bool):
        parts.append(f"pixel ({x}, {y})")
    elif isinstance(y, int) and not isinstance(y, bool):
        parts.append(f"row {y}")
    return ", ".join(parts)


# --- the formatter ----------------------------------------------------------------------------


class Formatter:
    """Writes values as HTML or text. `fields` finds a value's named fields (a record), or None;
    `opaque` the text of a value with no plain form. Override them for other record types."""

    def __init__(self, layout: tuple[int, int] | None = None) -> None:
        self.layout = layout  # the mask grid, (cols, rows)

    def fields(self, value: object) -> dict | None:
        return record_fields(value)

    def name(self, value: object) -> str:
        kind = getattr(type(value), "kind", None)
        name = type(value).__name__
        return f"{name} · {kind}" if isinstance(kind, str) and kind != "event" else name

    def opaque(self, value: object) -> str:
        text = str(value)
        return text if len(text) <= 120 else text[:117] + "..."

    # -- text --

    def text(self, value: object, name: str = "", limit: int = 120) -> str:
        """`value` on one line."""
        number = number_text(value)
        if number is not None:
            if is_mask(name, value):
                return mask_text(int(value), self.layout)
            return number
        if value is None:
            return "None"
        if isinstance(value, str):
            text = value
        elif (fields := self.fields(value)) is not None:
            inner = ", ".join(f"{k} {self.text(v, k, 40)}" for k, v in fields.items())
            text = f"{self.name(value).split(' ')[0]}({inner})"
        elif isinstance(value, _numpy("ndarray")):
            text = array_text(value)
        elif isinstance(value, Mapping):
            text = ", ".join(f"{k}: {self.text(v, str(k), 40)}" for k, v in value.items())
            text = "{" + text + "}"
        elif isinstance(value, list | tuple):
            text = self._list_text(value, name)
        else:
            text = self.opaque(value)
        return text if len(text) <= limit else text[: limit - 3] + "..."

    def _list_text(self, value: list | tuple, name: str) -> str:
        if not value:
            return "()"
        array = _numeric_array(value)
        if array is not None and array.ndim > 1 and array.size > VALUES_SHOWN:
            return array_text(array)
        records = [self.fields(v) is not None for v in value]
        if all(records):
            return f"{len(value)} × {self.name(value[0]).split(' ')[0]}"
        shown = [self.text(v, name, 40) for v in value[:VALUES_SHOWN]]
        more = f", ... ({len(value)} values)" if len(value) > VALUES_SHOWN else ""
        return "(" + ", ".join(shown) + more + ")"

    def record_text(self, record: object) -> str:
        """`record` as lines: its name, then ``field  value`` per field (tables for lists of records)."""
        fields = self.fields(record) or {}
        title = self.name(record)
        where = place(record) if hasattr(type(record), "kind") else ""
        lines = [title + (f" -- {where}" if where else "")]
        width = max((len(k) for k in fields), default=0)
        for key, item in fields.items():
            rows = self._record_rows(item)
            if rows is None:
                lines.append(f"  {key:<{width}}  {self.text(item, key)}")
                continue
            lines.append(f"  {key:<{width}}  {len(item)} × {self.name(item[0]).split(' ')[0]}")
            lines.extend("    " + line for line in self._table_text(item))
        return "\n".join(lines)

    def _record_rows(self, value: object) -> list[dict] | None:
        if not isinstance(value, list | tuple) or not value:
            return None
        rows = [self.fields(v) for v in value]
        return rows if all(r is not None for r in rows) else None

    def _table_text(self, records: list | tuple) -> list[str]:
        rows = self._record_rows(records) or []
        columns = list(dict.fromkeys(k for r in rows for k in r))
        cells = [[self.text(r.get(c), c, 40) for c in columns] for r in rows[:ROWS_SHOWN]]
        widths = [max([len(c)] + [len(row[i]) for row in cells]) for i, c in enumerate(columns)]
        lines = ["  ".join(c.ljust(w) for c, w in zip(columns, widths, strict=True)).rstrip()]
        lines += [
            "  ".join(v.ljust(w) for v, w in zip(r, widths, strict=True)).rstrip() for r in cells
        ]
        if len(rows) > ROWS_SHOWN:
            lines.append(f"... {len(rows) - ROWS_SHOWN} more")
        return lines

    # -- HTML --

    def html(self, value: object, name: str = "", depth: int = 0) -> str:
        """`value` as an HTML fragment (escaped)."""
        number = number_text(value)
        if number is not None:
            if is_mask(name, value):
                return mask_html(int(value), self.layout)
            if isinstance(value, (Fraction, float, *_numpy("floating"))) and math.isfinite(value):
                return f"<span title='{float(value)!r}'>{html.escape(number)}</span>"
            return html.escape(number)
        if value is None:
            return f"<span style='{_MUTED}'>None</span>"
        if isinstance(value, str):
            return html.escape(value)
        if self.fields(value) is not None:
            if depth >= DEPTH:
                return html.escape(self.text(value, name))
            return self.record_html(value, depth + 1)
        if isinstance(value, _numpy("ndarray")):
            return html.escape(array_text(value))
        if isinstance(value, Mapping):
            return self._mapping_html(value, depth)
        if isinstance(value, list | tuple):
            return self._list_html(value, name, depth)
        return html.escape(self.opaque(value))

    def _list_html(self, value: list | tuple, name: str, depth: int) -> str:
        if not value:
            return f"<span style='{_MUTED}'>none</span>"
        if self._record_rows(value) is not None and depth < DEPTH:
            return self.records_html(value, depth + 1)
        return html.escape(self._list_text(value, name))

    def _mapping_html(self, value: Mapping, depth: int) -> str:
        if not value:
            return f"<span style='{_MUTED}'>none</span>"
        if depth >= DEPTH:
            return html.escape(self.text(value))
        items = list(value.items())
        rows = [
            f"<tr><th style='{_HEAD}'>{html.escape(self.text(k))}</th>"
            f"<td style='{_CELL}'>{self.html(v, str(k), depth + 1)}</td></tr>"
            for k, v in items[:ROWS_SHOWN]
        ]
        rows += _more_row(len(items) - ROWS_SHOWN, 2)
        return f"<table style='{_TABLE}'>{''.join(rows)}</table>"

    def record_html(self, record: object, depth: int = 0) -> str:
        """`record` as a table of field | value, titled with its class (and kind and place)."""
        fields = self.fields(record) or {}
        where = place(record) if hasattr(type(record), "kind") else ""
        title = html.escape(self.name(record) + (f" — {where}" if where else ""))
        doc = (type(record).__doc__ or "").strip().split("\n", 1)[0]
        tip = f" title='{html.escape(doc, quote=True)}'" if doc and depth == 0 else ""
        rows = "".join(
            f"<tr><th style='{_HEAD}'>{html.escape(k)}</th>"
            f"<td style='{_CELL}'>{self.html(v, k, depth)}</td></tr>"
            for k, v in fields.items()
        )
        return (
            f"<table style='{_TABLE}'><caption style='{_CAPTION}'{tip}>{title}</caption>"
            f"{rows}</table>"
        )

    def records_html(self, records: list | tuple, depth: int = 0) -> str:
        """A list of records as one table: a column per field, a row per record."""
        rows = self._record_rows(records) or []
        columns = list(dict.fromkeys(k for r in rows for k in r))
        head = "".join(f"<th style='{_HEAD}'>{html.escape(c)}</th>" for c in columns)
        body = "".join(
            "<tr>"
            + "".join(f"<td style='{_CELL}'>{self.html(r.get(c), c, depth)}</td>" for c in columns)
            + "</tr>"
            for r in rows[:ROWS_SHOWN]
        )
        body += "".join(_more_row(len(rows) - ROWS_SHOWN, len(columns)))
        caption = f"{len(rows)} × {self.name(records[0]).split(' ')[0]}"
        return (
            f"<table style='{_TABLE}'><caption style='{_CAPTION};font-weight:400;{_MUTED}'>"
            f"{html.escape(caption)}</caption><tr>{head}</tr>{body}</table>"
        )


def _more_row(hidden: int, columns: int) -> list[str]:
    if hidden <= 0:
        return []
    return [f"<tr><td colspan='{columns}' style='{_CELL};{_MUTED}'>... {hidden:,} more</td></tr>"]


def _numeric_array(value: list | tuple):
    """`value` as a numeric array if it is a rectangular nest of real numbers, else None."""
    if len(value) > 100_000:
        return None
    import numpy as np

    try:
        array = np.asarray(value)
    except (ValueError, TypeError):
        return None
    return array if array.dtype.kind in "biuf" else None


# --- masks and arrays ---------------------------------------------------------------------


def _grid(mask: int, layout: tuple[int, int]) -> list[list[bool]]:
    """Rows of the mask's bits, top row first."""
    cols, rows = layout
    return [[bool(mask >> (j * cols + i) & 1) for i in range(cols)] for j in reversed(range(rows))]


def mask_text(mask: int, layout: tuple[int, int] | None) -> str:
    """A mask as hex, and as bit rows (top row first) when its layout is known.

    >>> mask_text(0x00FF, (4, 4))
    '0xff (8 of 16: 0000/0000/1111/1111)'
    """
    if layout is None or mask >> (layout[0] * layout[1]):
        return f"{mask:#x}"
    rows = "/".join("".join("1" if bit else "0" for bit in row) for row in _grid(mask, layout))
    return f"{mask:#x} ({mask.bit_count()} of {layout[0] * layout[1]}: {rows})"


def mask_html(mask: int, layout: tuple[int, int] | None) -> str:
    """A mask as its grid of sub-samples (filled: covered), row 0 at the bottom, and its hex."""
    if layout is None or mask >> (layout[0] * layout[1]):
        return html.escape(f"{mask:#x}")
    cols, count = layout[0], layout[0] * layout[1]
    cells = "".join(
        f"<span style='width:7px;height:7px;background:{'#1565c0' if bit else '#fff'}'></span>"
        for row in _grid(mask, layout)
        for bit in row
    )
    grid = (
        f"<span style='display:inline-grid;grid-template-columns:repeat({cols},7px);gap:1px;"
        f"background:#aaa;border:1px solid #aaa;flex:none'>{cells}</span>"
    )
    note = f"{mask:#x}<br><span style='{_MUTED}'>{mask.bit_count()} of {count} ({cols}x{layout[1]})</span>"
    return (
        "<span style='display:inline-flex;gap:6px;align-items:center;white-space:nowrap'>"
        f"{grid}<span>{note}</span></span>"
    )


def array_text(array) -> str:
    """A short description: the values if few, else shape, type, range and the first values.

    >>> import numpy as np
    >>> array_text(np.array([0.1 + 0.2, 1.0]))
    '[0.3, 1]'
    >>> array_text(np.array(["TBL"] * 20 + ["LR"] * 4))
    '(24,) array of str: TBL × 20, LR × 4'
    """
    import numpy as np

    shape = "(" + ", ".join(map(str, array.shape)) + ("," if array.ndim == 1 else "") + ")"
    if array.dtype.kind in "USO":
        counts = Counter(map(str, array.ravel()[:100_000].tolist()))
        if len(counts) <= VALUES_SHOWN:
            listed = ", ".join(f"{k} × {n:,}" for k, n in counts.most_common())
        else:
            listed = ", ".join(map(str, array.ravel()[:VALUES_SHOWN].tolist())) + ", ..."
        return f"{shape} array of {'str' if array.dtype.kind in 'US' else 'objects'}: {listed}"
    flat = array.ravel()
    if array.ndim <= 1 and flat.size <= VALUES_SHOWN:
        return "[" + ", ".join(number_text(v) or str(v) for v in flat.tolist()) + "]"
    first = ", ".join(number_text(v) or str(v) for v in flat[:VALUES_SHOWN].tolist())
    summary = f"{shape} {array.dtype}"
    if flat.size and array.dtype.kind in "biuf":
        finite = flat[np.isfinite(flat)] if array.dtype.kind == "f" else flat
        if finite.size:
            low, high = finite.min().item(), finite.max().item()
            summary += f", from {number_text(low)} to {number_text(high)}"
    return f"{summary}; first values {first}" + (", ..." if flat.size > VALUES_SHOWN else "")


# --- records, stats, traces ---------------------------------------------------------------


def scroll_box(content: str) -> str:
    """`content` (HTML) in a box that scrolls sideways when it is wider than the output, with
    a "scroll →" hint above it: a wide table is never cut off.

    >>> scroll_box("<table></table>").count("overflow-x:auto")
    1
    """
    return (
        "<div style='font-size:11px;color:#777;text-align:right'>scroll →</div>"
        f"<div style='overflow-x:auto;max-width:100%'>{content}</div>"
    )


def record_html(record: object, layout: tuple[int, int] | None = None) -> str:
    """`record` (an event, a record, a stats object) as an HTML table of field | value.

    Masks are drawn in `layout` (cols, rows), by default `mask_layout(record)`.
    """
    formatter = Formatter(layout or mask_layout(record))
    return f"<div style='overflow-x:auto'>{formatter.record_html(record)}</div>"


def record_text(record: object, layout: tuple[int, int] | None = None) -> str:
    """`record` as lines of text: its name (kind, place), then one line per field."""
    return Formatter(layout or mask_layout(record)).record_text(record)


def _counts(events: Iterable) -> Counter:
    return Counter(getattr(e, "kind", type(e).__name__) for e in events)


def trace_html(trace: object, first: int = ROWS_SHOWN) -> str:
    """A trace summarised: how many events of each kind, and the first `first` events.

    The size is bounded whatever the trace's length: index it (``trace[k]``)
    or filter it (``trace.of_kind("span")``) to see the others.
    """
    events = list(trace)  # type: ignore[call-overload]
    counts = _counts(events)
    kinds = "".join(
        f"<tr><td style='{_CELL}'>{html.escape(k)}</td><td style='{_CELL}'>{n:,}</td></tr>"
        for k, n in counts.items()
    )
    formatter = Formatter()
    rows = "".join(
        f"<tr><td style='{_CELL}'>{i}</td><td style='{_CELL}'>{html.escape(e.kind)}</td>"
        f"<td style='{_CELL};white-space:nowrap'>{html.escape(place(e))}</td>"
        f"<td style='{_CELL}'>{html.escape(fields_line(formatter, e))}</td></tr>"
        for i, e in enumerate(events[:first])
    )
    rows += "".join(_more_row(len(events) - first, 4))
    head = "".join(f"<th style='{_HEAD}'>{h}</th>" for h in ("step", "kind", "where", "fields"))
    hint = (
        "<div style='color:#555;font-size:12px'>see one event: <code>trace[k]</code>; "
        'one kind: <code>trace.of_kind("span")</code></div>'
        if len(events) > first
        else ""
    )
    return (
        f"<div style='overflow-x:auto'><b>Trace of {len(events):,} events</b>"
        f"<div style='display:flex;gap:16px;align-items:flex-start;flex-wrap:wrap'>"
        f"<table style='{_TABLE}'><caption style='{_CAPTION}'>events per kind</caption>"
        f"<tr><th style='{_HEAD}'>kind</th><th style='{_HEAD}'>events</th></tr>{kinds}</table>"
        f"<table style='{_TABLE}'><caption style='{_CAPTION}'>"
        f"the first {min(first, len(events))}</caption><tr>{head}</tr>{rows}</table></div>"
        f"{hint}</div>"
    )


def fields_line(formatter: Formatter, event: object) -> str:
    """An event's fields on one line, without those its place already says."""
    fields = formatter.fields(event) or {}
    said = {"polygon", "x", "y"} if place(event) else set()
    parts = [f"{k} {formatter.text(v, k, 48)}" for k, v in fields.items() if k not in said]
    text = ", ".join(parts)
    return text if len(text) <= 160 else text[:157] + "..."


class RichDisplay:
    """Mixin: Jupyter shows the object as `record_html`, ``print`` as `record_text`.

    ``repr`` is left alone (tests and doctests read the dataclass repr).
    """

    __slots__ = ()

    def _repr_html_(self) -> str:
        return record_html(self)

    def __str__(self) -> str:
        return record_text(self)

"""What a check shows a student: differing events as tables, and the raster diff on its pixel grid.

Values are written by `scanviz.trace.display` (mixed numbers, short floats,
masks as grids), never as a Python repr. Two events that differ are shown
field by field, the student's value beside the reference's, the differing
fields highlighted. A raster diff is drawn on the pixel grid (pixel (x, y)
is the square [x, x+1) x [y, y+1), y up), with the case's outline, its
sample points, and the wrong pixels marked: extra (yours only) and missing
(the reference's only) in two colours, with a legend.
"""

from __future__ import annotations

import base64
import hashlib
import html
import io
import pickle
from collections.abc import Mapping

import numpy as np

from ..trace.display import Formatter, fields_line, mask_layout, place, scroll_box
from .compare import MISSING, Difference, RasterDifference, aligned, first_difference, first_places
from .jail.wire import Opaque, record_fields, record_name
from .verdict import NO_MATCH, Verdict

EXTRA = "#d55e00"  # vermillion: a sample yours has and the reference does not
MISSING_COLOR = "#0072b2"  # blue: a sample the reference has and yours does not
MATCHED = "#c9c9c9"
WIDEST = 7.0  # inches of the raster diff's grid, at most (the figure: 8)
INCH = 0.42  # inches of one pixel, at most

_DIFFERS = "background:#ffe0b2"
_CELL = "padding:1px 6px;text-align:left;vertical-align:top;border:1px solid #ddd"
_HEAD = _CELL + ";background:#f3f3f3;font-weight:600"
_TABLE = "border-collapse:collapse;margin:4px 0;font-size:12px"


class ExerciseFormatter(Formatter):
    """`Formatter` for values that crossed the jail: `Fields` records, `Opaque` values, gaps."""

    def fields(self, value: object) -> dict | None:
        if isinstance(value, Opaque) or record_name(value) == "Opaque":
            return None
        return record_fields(value)

    def name(self, value: object) -> str:
        kind = getattr(value, "kind", None)
        name = record_name(value)
        return f"{name} · {kind}" if isinstance(kind, str) else name

    def opaque(self, value: object) -> str:
        if value is MISSING:
            return "(none)"
        if isinstance(value, Opaque):
            return value.repr
        fields = record_fields(value)
        if fields is not None and "repr" in fields:  # an Opaque read back as a record
            return str(fields["repr"])
        return super().opaque(value)


def _formatter(*values: object) -> ExerciseFormatter:
    return ExerciseFormatter(next((mask_layout(v) for v in values if mask_layout(v)), None))


def _records(value: object) -> list[dict] | None:
    if not isinstance(value, list | tuple) or not value:
        return None
    rows = [record_fields(v) for v in value]
    return rows if all(r is not None for r in rows) else None


def _records_against(
    mine: object, theirs: object, formatter: Formatter, rtol: float
) -> tuple[str, str]:
    """Two lists of records (an AET, an edge table) as tables, each cell that differs from the
    other side's cell highlighted; None if either side is not such a list."""
    rows = [_records(mine) or [], _records(theirs) or []]
    columns = list(dict.fromkeys(k for side in rows for r in side for k in r))
    head = "".join(f"<th style='{_HEAD}'>{html.escape(c)}</th>" for c in columns)
    tables = []
    for side, other in ((rows[0], rows[1]), (rows[1], rows[0])):
        body = []
        for index, row in enumerate(side):
            peer = other[index] if index < len(other) else None
            cells = []
            for column in columns:
                value = row.get(column, MISSING)
                differs = peer is None or (
                    first_difference(value, peer.get(column, MISSING), rtol) is not None
                )
                style = _CELL + (";" + _DIFFERS if differs else "")
                cells.append(f"<td style='{style}'>{formatter.html(value, column, 2)}</td>")
            body.append("<tr>" + "".join(cells) + "</tr>")
        if not side:
            body.append(f"<tr><td style='{_CELL}' colspan='{len(columns)}'>none</td></tr>")
        tables.append(f"<table style='{_TABLE}'><tr>{head}</tr>{''.join(body)}</table>")
    return tables[0], tables[1]


def comparison_html(yours: object, reference: object, rtol: float = 0.0) -> str:
    """Two values side by side: for two records a row per field (yours | reference), the
    differing fields highlighted; for others one row. A side that has nothing shows "(none)"."""
    formatter = _formatter(yours, reference)
    mine, theirs = formatter.fields(yours), formatter.fields(reference)
    head = (
        f"<tr><th style='{_HEAD}'>field</th><th style='{_HEAD}'>yours</th>"
        f"<th style='{_HEAD}'>reference</th></tr>"
    )
    if mine is None and theirs is None:
        differs = first_difference(yours, reference, rtol) is not None
        style = _CELL + (";" + _DIFFERS if differs else "")
        return scroll_box(
            f"<table style='{_TABLE}'><tr><th style='{_HEAD}'>yours</th>"
            f"<th style='{_HEAD}'>reference</th></tr><tr><td style='{style}'>"
            f"{formatter.html(yours)}</td><td style='{style}'>{formatter.html(reference)}</td>"
            "</tr></table>"
        )
    mine, theirs = mine or {}, theirs or {}
    rows = []
    for name in dict.fromkeys([*theirs, *mine]):
        a, b = mine.get(name, MISSING), theirs.get(name, MISSING)
        differs = first_difference(a, b, rtol) is not None
        style = _CELL + (";" + _DIFFERS if differs else "")
        mark = " ✗" if differs else ""
        head_cell = f"<th style='{_HEAD}'>{html.escape(name)}{mark}</th>"
        if differs and (_records(a) is not None or _records(b) is not None):
            left, right = _records_against(a, b, formatter, rtol)  # wide: one above the other
            rows.append(
                f"<tr>{head_cell}<td style='{_CELL}' colspan='2'><i>yours</i>{left}"
                f"<i>reference</i>{right}</td></tr>"
            )
            continue
        left, right = formatter.html(a, name, 1), formatter.html(b, name, 1)
        rows.append(
            f"<tr>{head_cell}<td style='{style}'>{left}</td><td style='{style}'>{right}</td></tr>"
        )
    return scroll_box(f"<table style='{_TABLE}'>{head}{''.join(rows)}</table>")


def event_title(event: object) -> str:
    """``span, row 1`` -- the kind and place of an event (``(no event)`` for a gap)."""
    if event is MISSING:
        return "(no event)"
    where = place(event)
    return getattr(event, "kind", record_name(event)) + (f", {where}" if where else "")


def event_fields(event: object) -> str:
    """An event's fields on one line (``x_start 1, x_end 6, winding 1``), its place left out."""
    return fields_line(_formatter(event), event)


def first_diverging(yours: list, reference: list, rtol: float) -> tuple[object, object] | None:
    """The first pair of aligned events that differ (either may be MISSING), or None."""
    for _, mine, theirs in aligned(yours, reference):
        if first_difference(mine, theirs, rtol) is not None:
            return mine, theirs
    return None


def difference_html(difference: Difference, subject: str, rtol: float = 0.0) -> str:
    """A `Difference` (a path and both values there) as ``<subject> differs at <path>:`` and a
    yours | reference table."""
    at = f" at <code>{html.escape(difference.path)}</code>" if difference.path else ""
    table = comparison_html(difference.yours, difference.reference, rtol)
    return f"<div>{html.escape(subject)} differs{at}:</div>{table}"


# --- the raster diff ----------------------------------------------------------------------------


def case_outlines(inputs: Mapping | None) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The case's shapes in pixel coordinates: closed outlines (polygons, triangles) and open
    polylines (a line's two ends), each an (N, 2) array; empty where the inputs have none."""
    closed: list[np.ndarray] = []
    open_: list[np.ndarray] = []
    if not inputs:
        return closed, open_
    shapes = []
    if "polygon" in inputs:
        shapes = [inputs["polygon"]]
    elif "triangles" in inputs:
        shapes = list(inputs["triangles"])
    elif "polygons" in inputs:
        shapes = list(inputs["polygons"])
    for shape in shapes:
        try:
            points = np.asarray(shape, dtype=float)
        except (TypeError, ValueError):
            continue
        if points.ndim == 2 and points.shape[0] >= 2 and points.shape[1] >= 2:
            closed.append(points[:, :2])
    if all(k in inputs for k in ("x0", "y0", "x1", "y1")):
        ends = [[inputs["x0"], inputs["y0"]], [inputs["x1"], inputs["y1"]]]
        open_.append(np.asarray(ends, dtype=float))
    return closed, open_


def raster_figure(raster: RasterDifference, inputs: Mapping | None = None):
    """The raster diff drawn on its pixel grid: a matplotlib Figure, at most `WIDEST` in wide.

    Pixel (x, y) is the square [x, x+1) x [y, y+1), y up. Matched samples are
    grey, extra ones (yours only) vermillion with a "+", missing ones (the
    reference's only) blue with a "−"; the case's outline and its sample
    points (lower-left corners, or centres with ``sample="center"``) are drawn over.
    """
    from matplotlib.collections import PatchCollection
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch, Rectangle

    yours, reference = raster.yours, raster.reference
    height, width = reference.shape
    inch = min(INCH, WIDEST / max(width, 1), 6.0 / max(height, 1))
    figure = Figure(figsize=(width * inch + 1.0, height * inch + 1.3), layout="constrained")
    axes = figure.add_subplot()
    classes = [
        (yours & reference, MATCHED, "matched", raster.matched, ""),
        (yours & ~reference, EXTRA, "extra (yours only)", raster.extra, "+"),
        (reference & ~yours, MISSING_COLOR, "missing (reference only)", raster.missing, "−"),
    ]
    glyph_size = inch * 72 * 0.6
    for cells, color, label, _, glyph in classes:
        ys, xs = np.nonzero(cells)
        squares = [Rectangle((x, y), 1, 1) for x, y in zip(xs, ys, strict=True)]
        axes.add_collection(
            PatchCollection(squares, facecolor=color, edgecolor="none", label=label, gid=label)
        )
        if glyph and glyph_size >= 6:
            for x, y in zip(xs, ys, strict=True):
                axes.text(x + 0.5, y + 0.5, glyph, ha="center", va="center", color="white",
                          fontsize=glyph_size, fontweight="bold")  # fmt: skip
    offset = 0.5 if (inputs or {}).get("sample") == "center" else 0.0
    if width * height <= 64 * 64:
        grid_x, grid_y = np.meshgrid(np.arange(width) + offset, np.arange(height) + offset)
        axes.plot(grid_x.ravel(), grid_y.ravel(), ".", color="#555", markersize=2, zorder=3)
    closed, open_ = case_outlines(inputs)
    for points in [np.vstack([loop, loop[:1]]) for loop in closed] + open_:  # loops drawn closed
        axes.plot(points[:, 0], points[:, 1], color="black", linewidth=1.6, zorder=4, gid="outline")
    axes.set_xlim(0, width)
    axes.set_ylim(0, height)
    axes.set_aspect("equal")
    axes.set_xticks(np.arange(width + 1), minor=True)
    axes.set_yticks(np.arange(height + 1), minor=True)
    step = max(1, int(np.ceil(max(width, height) / 16)))
    axes.set_xticks(np.arange(0, width, step) + 0.5, [str(x) for x in range(0, width, step)])
    axes.set_yticks(np.arange(0, height, step) + 0.5, [str(y) for y in range(0, height, step)])
    axes.tick_params(which="major", length=0, labelsize=8)
    axes.grid(which="minor", color="#888", linewidth=0.6)
    axes.set_axisbelow(False)
    axes.set_xlabel("x", fontsize=9)
    axes.set_ylabel("y", fontsize=9)
    handles = [
        Patch(facecolor=color, label=f"{label}: {count}") for _, color, label, count, _ in classes
    ]
    columns = 3 if width * inch >= 5 else 1  # a narrow grid lists them one under the other
    figure.legend(
        handles=handles, loc="outside lower center", ncols=columns, fontsize=8, frameon=False
    )
    return figure


def raster_png(raster: RasterDifference, inputs: Mapping | None = None, dpi: int = 100) -> bytes:
    """PNG bytes of `raster_figure`; the same difference drawn again comes from a small cache
    (a class's reports show the same few differences hundreds of times)."""
    try:
        key = hashlib.sha256(pickle.dumps((raster, inputs, dpi))).digest()
    except (pickle.PicklingError, TypeError, AttributeError):
        key = None
    if key is not None and key in _PNG_CACHE:
        return _PNG_CACHE[key]
    buffer = io.BytesIO()
    raster_figure(raster, inputs).savefig(buffer, format="png", dpi=dpi)
    if key is not None:
        if len(_PNG_CACHE) >= _PNG_CACHED:
            del _PNG_CACHE[next(iter(_PNG_CACHE))]  # the oldest
        _PNG_CACHE[key] = buffer.getvalue()
    return buffer.getvalue()


_PNG_CACHED = 256  # figures kept by `raster_png` (a few kilobytes each)
_PNG_CACHE: dict[bytes, bytes] = {}


def raster_html(raster: RasterDifference, inputs: Mapping | None = None) -> str:
    """The raster diff as an inline image, with the counts as its alternative text."""
    data = base64.b64encode(raster_png(raster, inputs)).decode("ascii")
    alt = (
        f"raster diff: {raster.matched} matched, {raster.extra} extra (yours only), "
        f"{raster.missing} missing (reference only)"
    )
    return f"<img class='raster' alt='{html.escape(alt)}' src='data:image/png;base64,{data}'>"


# --- a verdict ----------------------------------------------------------------------------------


def verdict_html(verdict: Verdict, yours=None, reference=None, rtol: float = 0.0) -> str:
    """A failed public case as HTML: what raised, the first diverging events side by side, the
    forced calls and result that differ, the raster diff and the likely cause.

    `yours` and `reference` are the two `Outcome`s (for the events themselves); without them
    only the diverging field is shown.
    """
    mark = "passed" if verdict.passed else "FAILED"
    color = "#2e7d32" if verdict.passed else "#c62828"
    which = "hidden" if verdict.hidden else "public"
    parts = [
        f"<div><b>{which} case “{html.escape(verdict.case.label)}”: "
        f"<span style='color:{color}'>{mark}</span></b></div>"
    ]
    if verdict.passed:
        return parts[0]
    if verdict.error:
        parts.append(
            f"<div style='color:#c62828'>your code raised {html.escape(verdict.error)}</div>"
        )
    if verdict.trace is not None:
        t = verdict.trace
        where = f", {t.place}" if t.place else ""
        matched = f"events 1–{t.matched} matched" if t.matched else "no event matched before it"
        parts.append(
            f"<div>first difference at event {t.index + 1} of {t.length} — "
            f"<b>{html.escape(t.kind + where)}</b> ({matched})</div>"
        )
        pair = None
        if yours is not None and reference is not None:
            pair = first_diverging(yours.trace, reference.trace, rtol)
        if pair is not None:
            parts.append(comparison_html(pair[0], pair[1], rtol))
        else:
            parts.append(difference_html(t.difference, "the event", rtol))
        if t.later:
            places = first_places(t.later, " …")
            parts.append(
                f"<div>it also differs at: {html.escape(places)} ({len(t.later)} places)</div>"
            )
    if verdict.calls_total:
        places = f": {first_places(verdict.wrong_calls, ' …')}" if verdict.wrong_calls else ""
        parts.append(f"<div>{html.escape(verdict.calls_summary + places)}</div>")
        if verdict.wrong_calls and verdict.first_call is not None:
            subject = "the first such call's output"
            parts.append(difference_html(verdict.first_call, subject, rtol))
    if verdict.result is not None:
        parts.append(difference_html(verdict.result, "the result", rtol))
    if verdict.raster is not None:
        parts.append(raster_html(verdict.raster, verdict.case.inputs))
    if verdict.variant is not None:
        parts.append(
            f"<div style='background:#fff8e1;padding:4px 8px;border-left:4px solid #f9a825'>"
            f"likely cause: {html.escape(verdict.variant.hint)}</div>"
        )
    elif verdict.unexplained:
        parts.append(f"<div>{html.escape(NO_MATCH)}</div>")
    return "<div style='margin:6px 0'>" + "".join(parts) + "</div>"

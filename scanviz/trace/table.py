"""Plain-text tables of a scan-conversion trace, laid out like the lecture slides.

The edge table comes first (one line per edge, bucket = ceil(ymin)), then one
line per scanned row: edges entering (+) and leaving (-), the sorted active
edge table as ``e<id>: x, dx/dy, ymax, winding``, and the spans emitted.
"""

from __future__ import annotations

from collections.abc import Iterable
from fractions import Fraction

from .events import AetEntry, EdgeRecord, Event


def format_number(value: float, exact: Fraction | None = None) -> str:
    """A coordinate as the slides write it: ``3 7/10`` when exact, else a short decimal.

    >>> format_number(3.7, Fraction(37, 10)), format_number(-0.3, Fraction(-3, 10)), format_number(2.5)
    ('3 7/10', '-3/10', '2.5')
    """
    if exact is None:
        return f"{value:.6g}"
    if exact.denominator == 1:
        return str(exact.numerator)
    whole = int(exact)  # truncates toward zero, so the fraction keeps the sign
    part = abs(exact - whole)
    if whole == 0:
        return f"{'-' if exact < 0 else ''}{part}"
    return f"{whole} {part}"


def _edge_line(edge: EdgeRecord) -> str:
    note = (
        "horizontal: crosses no row, never active"
        if edge.horizontal
        else ("between two rows: crosses none, never active" if edge.kept_for_topology else "")
    )
    return (
        f"  e{edge.edge:<3} ({edge.x0:g},{edge.y0:g})-({edge.x1:g},{edge.y1:g})  bucket {edge.bucket:>4}"
        f"  ymax {edge.ymax:<8g} x {format_number(edge.x, edge.x_exact):<10}"
        f" dx/dy {format_number(edge.dxdy, edge.dxdy_exact):<8} w {edge.winding:+d}  {note}".rstrip()
    )


def _aet_cell(entry: AetEntry) -> str:
    x, dxdy = format_number(entry.x, entry.x_exact), format_number(entry.dxdy, entry.dxdy_exact)
    return f"e{entry.edge}: {x}, {dxdy}, {entry.ymax:g}, {entry.winding:+d}"


def trace_table(events: Iterable[Event]) -> str:
    """Render a scan-conversion trace as text: the edge table, then one line per row.

    Examples
    --------
    >>> from scanviz import scan_convert
    >>> print(trace_table(scan_convert([(0, 0), (2, 0), (0, 2)], 3, 3, trace=True).trace))
    edge table (bucket = ceil(ymin); active for bucket <= y < ymax)
      e0   (0,0)-(2,0)  bucket    0  ymax 0        x 0          dx/dy 0        w +0  horizontal: crosses no row, never active
      e1   (2,0)-(0,2)  bucket    0  ymax 2        x 2          dx/dy -1       w -1
      e2   (0,0)-(0,2)  bucket    0  ymax 2        x 0          dx/dy 0        w +1
    <BLANKLINE>
      row | ET in/out    | AET (edge: x, dx/dy, ymax, winding)             | spans [x_start, x_end)
        0 | +e1 +e2      | e2: 0, 0, 2, +1 | e1: 2, -1, 2, -1                | [0,2) w+1
        1 |              | e2: 0, 0, 2, +1 | e1: 1, -1, 2, -1                | [0,1) w+1
        2 | -e2 -e1      |                                                   |
    """
    lines: list[str] = []
    rows: dict[tuple[int, int], dict[str, list[str]]] = {}
    for event in events:
        if event.kind == "edge_table_built":
            if lines:
                lines.append("")
            lines.append("edge table (bucket = ceil(ymin); active for bucket <= y < ymax)")
            lines.extend(
                _edge_line(e) for e in sorted(event.edges, key=lambda e: (e.bucket, e.edge))
            )
            continue
        if not hasattr(event, "y"):  # not a per-row step of scan conversion
            continue
        key = (getattr(event, "polygon", 0), event.y)
        row = rows.setdefault(key, {"et": [], "aet": [], "spans": []})
        if event.kind == "edges_activated":
            row["et"] += [f"+e{e}" for e in event.edges]
        elif event.kind == "edges_retired":
            row["et"] += [f"-e{e}" for e in event.edges]
        elif event.kind == "aet_sorted":
            row["aet"] = [_aet_cell(entry) for entry in event.entries]
        elif event.kind == "span":
            row["spans"].append(f"[{event.x_start},{event.x_end}) w{event.winding:+d}")
    if rows:
        lines += [
            "",
            "  row | ET in/out    | AET (edge: x, dx/dy, ymax, winding)             | spans [x_start, x_end)",
        ]
        for (_, y), row in sorted(rows.items()):
            aet = " | ".join(row["aet"])
            lines.append(
                f"{y:>5} | {' '.join(row['et']):<12} | {aet:<49} | {' '.join(row['spans'])}".rstrip()
            )
    return "\n".join(lines)

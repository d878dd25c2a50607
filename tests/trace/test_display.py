"""What a student reads of records, stats and traces: tables, mixed numbers, short floats, masks."""

import re
from fractions import Fraction

import numpy as np

from scanviz.trace import AetEntry, AetSorted, PackStep, Span, Trace
from scanviz.trace.display import float_text, mask_text, record_html, record_text, trace_html
from scanviz.trace.events import FragmentRecord
from scanviz.visibility.zbuffer import ZBufferStats


def _entry(x_exact: Fraction, dxdy: float = 0.5) -> AetEntry:
    return AetEntry(edge=2, x=float(x_exact), x_exact=x_exact, dxdy=dxdy, dxdy_exact=None,
                    ymax=5.0, winding=-1)  # fmt: skip


def _cells(page: str) -> list[str]:
    return [re.sub("<[^>]+>", "", cell) for cell in re.findall(r"<td[^>]*>(.*?)</td>", page)]


def test_a_fraction_reads_as_a_mixed_number():
    page = record_html(_entry(Fraction(7, 3)))
    assert "2 1/3" in _cells(page)
    assert "7/3" not in page and "Fraction(" not in page
    assert "-3/10" in _cells(record_html(_entry(Fraction(-3, 10))))


def test_a_float_reads_to_the_digits_that_matter():
    page = record_html(_entry(Fraction(1), dxdy=0.1 + 0.2))
    assert "0.3" in _cells(page) and "0.30000000000000004" not in re.sub("title='[^']*'", "", page)
    assert float_text(0.6000000000000001) == "0.6" and float_text(2 / 3) == "0.6667"
    assert float_text(float("inf")) == "∞" and float_text(123456.7) == "123457"


def test_a_32_bit_mask_shows_its_bits():
    fragment = FragmentRecord(z=0.2, zmax=0.2, area=0.5, mask=0xFFFFFFFF, color=(0.0, 1.0, 0.0),
                              opacity=1.0, object=0)  # fmt: skip
    step = PackStep(level=0, branch="", fragment=fragment, region=0xFFFFFFFF, weight=1.0,
                    mask_a=0x0000000F, a=0.125, mask_q=0xFFFFFFF0, q=0.875, color=(0.0, 0.1, 0.0))  # fmt: skip
    # the widest mask has 32 bits: an 8x4 grid, bit j * 8 + i is sub-sample (i, j), row 0 at the bottom
    assert mask_text(0x0000000F, (8, 4)) == "0xf (4 of 32: 00000000/00000000/00000000/11110000)"
    page = record_html(step)
    row = re.search(r"<th[^>]*>mask_a</th><td[^>]*>(.*?)</td></tr>", page).group(1)
    cells = re.findall(r"width:7px;height:7px;background:(#[0-9a-f]+)", row)
    filled = [k for k, colour in enumerate(cells) if colour != "#fff"]
    assert len(cells) == 32 and filled == [24, 25, 26, 27]  # the bottom row's first four
    assert "0xf" in row and "4 of 32" in row
    assert "4294967295" not in page


def test_nested_records_are_a_table_with_a_row_each():
    event = AetSorted(
        polygon=0, y=3, entries=(_entry(Fraction(5, 2)), _entry(Fraction(9))), swaps=1
    )
    page = record_html(event)
    assert "AetEntry(" not in page
    header = re.findall(r"<th[^>]*>(\w+)</th>", page)
    start = header.index("edge")
    assert header[start : start + 7] == [
        "edge",
        "x",
        "x_exact",
        "dxdy",
        "dxdy_exact",
        "ymax",
        "winding",
    ]
    assert "2 1/2" in _cells(page) and "row 3" in page


def test_repr_stays_the_dataclass_repr_and_print_is_readable():
    span = Span(polygon=0, y=1, x_start=2, x_end=5, winding=1)
    assert repr(span) == "Span(polygon=0, y=1, x_start=2, x_end=5, winding=1)"
    text = str(span)
    assert "Span(" not in text and "x_start  2" in text and "row 1" in text


def test_stats_show_as_a_table_and_print_as_lines():
    stats = ZBufferStats(polygons=3, polygons_drawn=2, fragments=12_345, depth_passed=12_000,
                         depth_failed=345)  # fmt: skip
    assert repr(stats).startswith("ZBufferStats(polygons=3,")
    page = stats._repr_html_()
    assert "12,345" in _cells(page) and "depth_failed" in page
    lines = [line.split() for line in str(stats).splitlines()]
    assert lines[0] == ["ZBufferStats"] and ["fragments", "12,345"] in lines


def test_a_long_array_field_is_summarised():
    from scanviz.trace.events import VerticesTransformed

    vertices = tuple(map(tuple, np.arange(1681 * 3, dtype=float).reshape(1681, 3).tolist()))
    event = VerticesTransformed(object=0, stage="eye", matrix=None, vertices=vertices)
    page = record_html(event)
    assert "(1681, 3) float64" in page and len(page) < 3000


def test_a_trace_display_has_a_bounded_size():
    small = trace_html(Trace([Span(0, y, 0, 4, 1) for y in range(100)]))
    events = [Span(0, y % 500, 0, 4, 1) for y in range(100_000)]
    large = Trace(events)._repr_html_()
    assert "Trace of 100,000 events" in large and "100,000" in _cells(large)  # span: 100,000
    assert "99,988 more" in large  # the first 12 shown
    assert len(large) < 1.1 * len(small) < 20_000
    assert "Span(" not in large


def test_record_text_lists_nested_records_as_rows():
    event = AetSorted(polygon=0, y=3, entries=(_entry(Fraction(5, 2)),), swaps=0)
    lines = record_text(event).splitlines()
    assert lines[0] == "AetSorted · aet_sorted -- polygon 0, row 3"
    assert lines[4].split() == ["edge", "x", "x_exact", "dxdy", "dxdy_exact", "ymax", "winding"]
    assert lines[5].split() == ["2", "2.5", "2", "1/2", "0.5", "None", "5", "-1"]

"""Traces of scan conversion: filtering, recording, step images and the JSON form."""

import json
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Recorder, Trace, scan_convert
from scanviz.catalog import SHAPES, get
from scanviz.conventions import SAMPLE_MODES
from scanviz.trace import AetSorted, EdgeTableBuilt, Span

BASE = settings.default.max_examples
SCAN_KINDS = ("edge_table_built", "edges_activated", "edges_retired", "aet_sorted", "span")
UMBC = get("umbc_example")


def umbc(recorder=True, **options):
    """The slide example scan-converted on its 16 x 16 raster."""
    return scan_convert(UMBC.polygon, UMBC.width, UMBC.height, trace=recorder, **options)


@pytest.fixture(scope="module")
def trace() -> Trace:
    return umbc().trace


# --- a trace is a sequence of events ------------------------------------------------------


def test_trace_is_an_indexable_sequence(trace):
    assert isinstance(trace[0], EdgeTableBuilt)
    assert isinstance(trace[1:4], Trace) and len(trace[1:4]) == 3
    assert list(trace) == [trace[i] for i in range(len(trace))]
    assert {e.kind for e in trace} == set(SCAN_KINDS)
    assert "span" in repr(trace)


def test_events_are_frozen_and_compare_by_value(trace):
    span = trace.of_kind("span")[0]
    assert span == Span(polygon=0, y=1, x_start=4, x_end=12, winding=span.winding)
    with pytest.raises(AttributeError):
        span.y = 2  # type: ignore[misc]
    assert umbc().trace == trace


# --- filtering ----------------------------------------------------------------------------


def test_filter_by_kind(trace):
    spans = trace.of_kind("span")
    assert len(spans) == len(umbc().spans) == 13
    assert all(isinstance(e, Span) for e in spans)
    both = trace.filter(["aet_sorted", "span"])
    assert {e.kind for e in both} == {"aet_sorted", "span"}
    assert len(both) == len(spans) + len(trace.of_kind("aet_sorted"))
    assert trace.filter("aet_sorted") == trace.of_kind("aet_sorted")


def test_filter_by_rows_keeps_events_of_those_rows_and_those_without_a_row(trace):
    kept = trace.filter(rows=(5, 8))
    assert list(kept) == [e for e in trace if not hasattr(e, "y") or 5 <= e.y < 8]
    assert sorted({e.y for e in kept if hasattr(e, "y")}) == [5, 6, 7]
    assert isinstance(kept[0], EdgeTableBuilt)


def test_filter_by_region_keeps_overlapping_spans(trace):
    # Region x in [10, 16), y in [5, 8): on rows 5..7 only the right spans reach x >= 10.
    spans = trace.filter("span", region=(10, 5, 16, 8))
    assert [(e.y, e.x_start, e.x_end) for e in spans] == [(5, 9, 12), (6, 10, 12), (7, 11, 12)]
    rows = {e.y for e in trace.filter("aet_sorted", region=(10, 5, 16, 8))}
    assert rows == {5, 6, 7}


def test_filter_by_polygon(trace):
    assert trace.filter(polygons=[0]) == trace
    assert len(trace.filter(polygons=[1])) == 0


@pytest.mark.parametrize(
    ("filters", "message"),
    [
        ({"kinds": ["spans"]}, r"'kinds' has unknown event kinds \['spans'\]"),
        ({"rows": (1, 2, 3)}, r"'rows' must be a \(start, stop\) pair of ints"),
        ({"region": (0, 0, 4)}, r"'region' must be \(x_start, y_start, x_end, y_end\)"),
    ],
)
def test_bad_filters_raise_naming_the_argument(trace, filters, message):
    with pytest.raises(ValueError, match=message):
        trace.filter(**filters)
    with pytest.raises(ValueError, match=message):
        Recorder(**filters)


# --- the recorder ------------------------------------------------------------------------


def test_recorder_with_rows_records_only_those_rows():
    recorder = Recorder(rows=(2, 6))
    result = umbc(recorder)
    assert result.trace == recorder.trace()
    rows = [e.y for e in result.trace if hasattr(e, "y")]
    assert rows and all(2 <= y < 6 for y in rows)
    assert sorted(set(rows)) == [2, 3, 4, 5]


@settings(max_examples=BASE)
@given(
    st.sampled_from(sorted(SHAPES)),
    st.one_of(st.none(), st.lists(st.sampled_from(SCAN_KINDS), min_size=1, unique=True)),
    st.integers(-2, 40),
    st.integers(0, 20),
    st.sampled_from(SAMPLE_MODES),
)
def test_recording_with_a_filter_equals_filtering_the_full_trace(name, kinds, low, length, sample):
    shape = get(name)
    rows = (low, low + length)
    recorder = Recorder(kinds, rows=rows)
    full = scan_convert(shape.polygon, shape.width, shape.height, sample=sample, trace=True)
    filtered = scan_convert(shape.polygon, shape.width, shape.height, sample=sample, trace=recorder)
    assert filtered.trace == full.trace.filter(kinds, rows=rows)
    np.testing.assert_array_equal(filtered.mask, full.mask)  # filters never change the image


def test_trace_false_or_none_records_nothing():
    assert umbc(None).trace is None
    assert umbc(False).trace is None


# --- step images --------------------------------------------------------------------------


@pytest.mark.parametrize("sample", SAMPLE_MODES)
def test_image_at_the_last_step_is_the_mask(sample):
    result = umbc(sample=sample)
    trace = result.trace
    final = trace.image_at(len(trace), UMBC.width, UMBC.height)
    assert final.shape == (UMBC.height, UMBC.width)
    np.testing.assert_array_equal(final, result.mask.astype(final.dtype))
    assert not trace.image_at(0, UMBC.width, UMBC.height).any()


def test_image_at_grows_row_by_row(trace):
    images = [trace.image_at(step, 16, 16) for step in range(len(trace) + 1)]
    for before, after in zip(images, images[1:], strict=False):
        assert (after >= before).all()
    last_row_5 = max(i for i, e in enumerate(trace) if e.kind == "span" and e.y == 5) + 1
    np.testing.assert_array_equal(
        trace.image_at(last_row_5, 16, 16)[:6], umbc().mask[:6].astype(np.int32)
    )
    assert not trace.image_at(last_row_5, 16, 16)[6:].any()


# --- JSON ---------------------------------------------------------------------------------


@pytest.mark.parametrize("sample", SAMPLE_MODES)
@pytest.mark.parametrize("arithmetic", ["exact", "float32"])
def test_json_round_trip_is_exact(arithmetic, sample):
    trace = umbc(arithmetic=arithmetic, sample=sample).trace
    text = trace.to_json()
    assert Trace.from_json(text) == trace
    assert Trace.from_json(Trace.from_json(text).to_json(indent=1)) == trace


@settings(max_examples=BASE)
@given(
    st.sampled_from(sorted(SHAPES)),
    st.sampled_from(SAMPLE_MODES),
    st.sampled_from(["exact", "float32", "float64"]),
    st.sampled_from([0, 8, 16, None]),
)
def test_json_round_trip_for_every_catalog_shape(name, sample, arithmetic, bits):
    shape = get(name)
    trace = scan_convert(
        shape.polygon,
        shape.width,
        shape.height,
        sample=sample,
        arithmetic=arithmetic,
        subpixel_bits=bits,
        trace=True,
    ).trace
    assert Trace.from_json(trace.to_json()) == trace


def test_json_shape_matches_the_cli_spec(trace):
    data = json.loads(trace.to_json())
    assert list(data) == ["events"]
    events = data["events"]
    assert len(events) == len(trace) and all("kind" in e for e in events)
    for event in events:
        if event["kind"] == "aet_sorted":
            assert {"y", "entries"} <= event.keys()
            for entry in event["entries"]:
                assert {"x", "dxdy", "ymax", "winding"} <= entry.keys()
        if event["kind"] == "span":
            assert {"y", "x_start", "x_end"} <= event.keys()
    row_2 = next(e for e in events if e["kind"] == "aet_sorted" and e["y"] == 2)
    # Exact values travel as "p/q" strings next to their floats: x = 3 7/10 on row 2.
    assert [(a["x"], a["x_exact"]) for a in row_2["entries"]] == [(3.7, "37/10"), (12.0, "12/1")]


def test_json_keeps_every_float_bit():
    trace = umbc(arithmetic="float32").trace
    entries = [a for e in trace.of_kind("aet_sorted") for a in e.entries]
    assert all(a.x_exact is None for a in entries)
    decoded = [a for e in Trace.from_json(trace.to_json()).of_kind("aet_sorted") for a in e.entries]
    assert [a.x.hex() for a in decoded] == [a.x.hex() for a in entries]
    assert isinstance(
        Trace.from_json(umbc().trace.to_json()).of_kind("aet_sorted")[0].entries[0].x_exact,
        Fraction,
    )
    assert isinstance(trace.of_kind("aet_sorted")[0], AetSorted)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('{"events": [{"kind": "teleport"}]}', r"unknown event kind 'teleport'"),
        ("[]", r"trace JSON must be an object with an 'events' list"),
        ('{"events": {}}', r"trace JSON must be an object with an 'events' list"),
    ],
)
def test_bad_json_raises_a_clear_error(text, message):
    with pytest.raises(ValueError, match=message):
        Trace.from_json(text)

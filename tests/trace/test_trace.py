"""Traces of scan conversion: filtering, recording, step images and the JSON form."""

import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz import Recorder, Trace, render, scan_convert
from scanviz.catalog import SHAPES, get
from scanviz.conventions import SAMPLE_MODES
from scanviz.exercises.jail import wire
from scanviz.limits import file_limit, memory_limit
from scanviz.raster.edgefn import triangle_samples
from scanviz.shading.fast_phong import ReflectionModel, fast_phong_triangle
from scanviz.shading.taylor import RationalForms
from scanviz.trace import AetEntry, AetSorted, DepthTest, EdgeTableBuilt, Span, TriangleSetup, codec
from scanviz.trace.codec import FORMAT_VERSION
from scanviz.trace.events import EdgeFunction
from scanviz.trace.schema import validate

BASE = settings.default.max_examples
SCAN_KINDS = ("edge_table_built", "edges_activated", "edges_retired", "aet_sorted", "span")
UMBC = get("umbc_example")
DOCS = Path(__file__).parents[2] / "docs" / "trace-format.md"


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


@pytest.mark.parametrize(
    ("args", "error", "message"),
    [
        (
            (3, 65536, 65536),
            ValueError,
            r"a 65536x65536 step image needs about 16\.0 GiB, over the memory limit",
        ),
        ((3, -1, 4), ValueError, r"'width' must be in 0\.\.65536; got -1"),
        ((3, 4, 2.0), TypeError, r"'height' must be an int; got 2\.0"),
        (("3", 4, 4), TypeError, r"'step' must be an int; got '3'"),
        ((-1, 4, 4), ValueError, r"'step' must be >= 0"),
    ],
)
def test_image_at_checks_its_arguments(trace, args, error, message):
    with pytest.raises(error, match=message):
        trace.image_at(*args)


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
    assert list(data) == ["version", "events"] and data["version"] == FORMAT_VERSION == 2
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


# --- issue 24: the format is versioned; version 1 (no "version" key) still reads ---------

# A version-1 file (what scanviz wrote before issue 24; the triangle is triangle_samples'
# output for (0, 0), (4, 0), (0, 4) on 4 x 4 with subpixel_bits=0): no "version" key, and
# each edge of a triangle_setup carried its index.
V1_TRIANGLE = {
    "kind": "triangle_setup", "polygon": 0, "vertices": [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]],
    "units": [[0, 0], [8, 0], [0, 8]], "scale": 2,
    "edges": [
        {"edge": 0, "a": 0, "b": 8, "c": 0, "owns_boundary": True},
        {"edge": 1, "a": -8, "b": -8, "c": 64, "owns_boundary": False},
        {"edge": 2, "a": 8, "b": 0, "c": 0, "owns_boundary": True},
    ],
    "area2": 64, "orientation": 1, "bbox": [0, 0, 4, 4],
}  # fmt: skip
V1_TRACE = """{"events": [
  {"kind": "span", "polygon": 0, "y": 1, "x_start": 2, "x_end": 5, "winding": 1},
  {"kind": "aet_sorted", "polygon": 0, "y": 2, "swaps": 1, "entries": [
    {"edge": 3, "x": 3.7, "x_exact": "37/10", "dxdy": -0.3, "dxdy_exact": "-3/10",
     "ymax": 11.0, "winding": 1}]},
  {"kind": "depth_test", "polygon": 1, "x": 4, "y": 2, "z": 0.25, "stored": "inf", "passed": true}
]}"""


def test_issue24_a_version_1_trace_reads_to_todays_events():
    entry = AetEntry(3, 3.7, Fraction(37, 10), -0.3, Fraction(-3, 10), 11.0, 1)
    expected = Trace(
        [
            Span(0, 1, 2, 5, 1),
            AetSorted(0, 2, (entry,), 1),
            DepthTest(1, 4, 2, 0.25, math.inf, True),
        ]
    )
    assert Trace.from_json(V1_TRACE) == expected
    assert json.loads(expected.to_json())["version"] == 2
    assert Trace.from_json(expected.to_json()) == expected


def test_issue24_a_version_1_triangle_setup_reads_with_the_edge_records_of_today():
    today = triangle_samples(
        [(0, 0), (4, 0), (0, 4)], 4, 4, subpixel_bits=0, trace=Recorder(["triangle_setup"])
    ).trace
    back = Trace.from_json(json.dumps({"events": [V1_TRIANGLE]}))
    assert back == today and type(back[0].edges[1]) is EdgeFunction
    assert back[0].edges[1] == EdgeFunction(-8, -8, 64, False) and back[0].edges[1].at(1, 1) == 48
    written = json.loads(today.to_json())
    assert written["version"] == 2 and written["events"][0]["edges"][1] == {
        "a": -8, "b": -8, "c": 64, "owns_boundary": False
    }  # fmt: skip


def v1_triangle_with_edge_1(**edge: object) -> dict:
    edges = list(V1_TRIANGLE["edges"])
    edges[1] = {key: value for key, value in {**edges[1], **edge}.items() if value is not None}
    return {**V1_TRIANGLE, "edges": edges}


@pytest.mark.parametrize(
    ("top", "message"),
    [
        (
            {"events": [v1_triangle_with_edge_1(edge=7)]},
            r"events\[0\]\.edges\[1\]\.edge: must be 1, the edge's place in 'edges' "
            r"\(version 1\); got 7 \(int\)",
        ),
        (
            {"events": [v1_triangle_with_edge_1(edge=True)]},
            r"events\[0\]\.edges\[1\]\.edge: must be 1, .*; got True \(bool\)",
        ),
        (
            {"events": [v1_triangle_with_edge_1(edge=None)]},
            r"events\[0\]\.edges\[1\]: is missing field 'edge' \(version 1\)",
        ),
        (  # version 2 has no index: an "edge" key is an unknown field
            {"version": 2, "events": [V1_TRIANGLE]},
            r"events\[0\]\.edges\[0\]\.edge: is not a field of EdgeFunction",
        ),
    ],
)
def test_issue24_triangle_edges_are_checked_in_either_version(top, message):
    with pytest.raises(ValueError, match=r"^trace JSON at " + message):
        Trace.from_json(json.dumps(top))


def test_issue24_version_1_fast_phong_forms_read_as_the_domain_record():
    # Version 2 left this event's shape alone (the fast Phong forms, once a copy of the
    # shading record, are that record now; JSON never named it), so its version-1 text is
    # today's text without the "version" key.
    model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.7, 0.5, 0.2), ks=0.7, n=8, r_plus_r0=1.5)
    normals = [(0, 0, 1), (0.3, 0, 1), (0, 0.3, 1)]
    trace = fast_phong_triangle(
        [(1, 1), (14, 2), (5, 12)], normals, (0.2, 0.3, 1), (0, 0, 1), model,
        width=16, height=16, trace=Recorder(["fast_phong_setup"]),
    ).trace  # fmt: skip
    data = json.loads(trace.to_json())
    del data["version"]
    back = Trace.from_json(json.dumps(data))
    assert back == trace and len(back) == 1
    assert all(type(e.forms) is RationalForms for e in back)


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


# --- issue 8: hostile JSON and wrongly typed events ---------------------------------------

SPAN = {"kind": "span", "polygon": 0, "y": 1, "x_start": 2, "x_end": 5, "winding": 1}
AET = {
    "kind": "aet_sorted",
    "polygon": 0,
    "y": 1,
    "entries": [
        {
            "edge": 0,
            "x": 1.5,
            "x_exact": "3/2",
            "dxdy": 0.5,
            "dxdy_exact": "1/2",
            "ymax": 4.0,
            "winding": 1,
        }
    ],
    "swaps": 0,
}


def events_json(*events: dict) -> str:
    return json.dumps({"events": list(events)})


def strict_loads(text: str) -> object:
    """json.loads refusing the non-standard literals NaN, Infinity and -Infinity."""

    def refuse(literal: str) -> None:
        raise ValueError(f"non-standard JSON literal {literal}")

    return json.loads(text, parse_constant=refuse)


def json_depth(value: object) -> int:
    """Nesting levels of arrays and objects in a parsed JSON value (the oracle for the bound)."""
    if isinstance(value, dict):
        return 1 + max(map(json_depth, value.values()), default=0)
    if isinstance(value, list):
        return 1 + max(map(json_depth, value), default=0)
    return 0


@pytest.mark.parametrize(
    ("text", "path"),
    [
        ("[" * 5000 + "]" * 5000, r"\[0\]\[0\]\[0\]\[0\]\[0\]\[0\]\[0\]"),
        ('{"events": [' + "[" * 100_000, r"events\[0\]\[0\]\[0\]\[0\]\[0\]\[0\]"),
        ('{"events": [' + '{"a": ' * 3000 + "1" + "}" * 3000 + "]}", r"events\[0\]\.a\.a\.a\.a\.a"),
        (events_json({**SPAN, "y": [[[[[[1]]]]]]}), r"events\[0\]\.y\[0\]\[0\]\[0\]\[0\]"),
    ],
)
def test_issue8_d6_deep_json_is_refused_with_its_path(text, path):
    with pytest.raises(ValueError, match=rf"at {path}: nests deeper than 7 levels"):
        Trace.from_json(text)


def test_issue8_d6_the_depth_bound_is_what_the_deepest_events_need():
    from scanviz.scene.builtin import builtin_scene
    from scanviz.trace.codec import MAX_DEPTH

    kinds = ["pixel_packed", "mask_buffer_row"]
    scene = builtin_scene("transparent_cube")
    trace = render(scene, 8, 8, visibility="abuffer", trace=Recorder(kinds)).trace
    assert {e.kind for e in trace} == set(kinds)
    text = trace.to_json()
    assert json_depth(json.loads(text)) == MAX_DEPTH == 7
    assert Trace.from_json(text) == trace
    assert "**Nesting depth: 7 levels**" in DOCS.read_text()


def test_issue8_d6_json_text_size_is_bounded():
    text = events_json(*[SPAN] * 40)  # about 3 KiB
    assert len(Trace.from_json(text)) == 40
    with (
        file_limit("1K"),
        pytest.raises(ValueError, match=r"larger than the file limit of 1\.0 KiB"),
    ):
        Trace.from_json(text)
    with (
        memory_limit("64K"),
        pytest.raises(ValueError, match=r"over the memory limit of 64\.0 KiB"),
    ):
        Trace.from_json(text)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('{"events": [1]}', r"at events\[0\]: must be an event object with a 'kind'; got 1"),
        ('{"events": [{"kind": "span"}]}', r"at events\[0\]: is missing field 'polygon' of Span"),
        (events_json({**SPAN, "kind": ["span"]}), r"at events\[0\]\.kind: must be a str naming"),
        (
            events_json({**SPAN, "kind": "spam"}),
            r"events\[0\]\.kind: .*unknown event kind 'spam' \(did you mean 'span'\?\)",
        ),
        (events_json(SPAN, {**SPAN, "z": 1}), r"at events\[1\]\.z: is not a field of Span"),
        (events_json({**SPAN, "y": 1.0}), r"at events\[0\]\.y: must be int; got 1\.0 \(float\)"),
        (events_json({**SPAN, "y": True}), r"at events\[0\]\.y: must be int; got True \(bool\)"),
        (events_json({**SPAN, "y": "1"}), r"at events\[0\]\.y: must be int; got '1' \(str\)"),
        (events_json({**SPAN, "y": None}), r"at events\[0\]\.y: must be int; got None"),
        (
            events_json(AET).replace('"3/2"', '"1/0"'),
            r"at events\[0\]\.entries\[0\]\.x_exact: .*zero denominator",
        ),
        (
            events_json(AET).replace('"3/2"', '"1.5"'),
            r"at events\[0\]\.entries\[0\]\.x_exact: must be a Fraction",
        ),
        (
            events_json(AET).replace('"3/2"', "1.5"),
            r"at events\[0\]\.entries\[0\]\.x_exact: must be a Fraction",
        ),
        (
            events_json(AET).replace('"3/2"', '"1e999999999/1"'),
            r"entries\[0\]\.x_exact: must be a Fraction",
        ),
        (
            events_json(AET).replace("1.5", "1e400"),
            r"at events\[0\]\.entries\[0\]\.x: must be within the float64 range",
        ),
        (
            events_json(AET).replace("1.5", str(2**1024)),
            r"at events\[0\]\.entries\[0\]\.x: must be a float within",
        ),
        (
            events_json(AET).replace("1.5", "9" * 5000),
            r"at events\[0\]\.entries\[0\]\.x: is a number of more than 4300 digits",
        ),
        (
            events_json(AET).replace("1.5", '"NaN"'),
            r"at events\[0\]\.entries\[0\]\.x: must be a float",
        ),
        (events_json({**AET, "entries": {}}), r"at events\[0\]\.entries: must be a list"),
        (
            events_json({**AET, "entries": [SPAN]}),
            r"at events\[0\]\.entries\[0\]\.kind: is not a field of AetEntry",
        ),
        (
            events_json(
                {
                    "kind": "face_culled",
                    "polygon": 0,
                    "normal": [0, 0],
                    "view": [0, 0, 1],
                    "dot": 0,
                    "culled": False,
                }
            ),
            r"at events\[0\]\.normal: must have 3 items; got 2",
        ),
        ('{"events": [], "meta": 1}', r"unknown top-level keys \['meta'\]"),
        (
            '{"version": 3, "events": []}',
            r"at version: must be one of .* \(1, 2\).*; got 3 \(int\)",
        ),
        ('{"version": "2", "events": []}', r"at version: .*; got '2' \(str\)"),
        ('{"version": true, "events": []}', r"at version: .*; got True \(bool\)"),
        ('{"events": [', r"not valid JSON: Expecting value: line 1 column 13"),
        ('\\"' * 20_000, r"not valid JSON"),  # escaped quotes: the string scan stays linear
    ],
)
def test_issue8_d10_malformed_json_names_the_path_and_the_rule(text, message):
    with pytest.raises(ValueError, match=message):
        Trace.from_json(text)


@pytest.mark.parametrize("text", [5, b'{"events": []}', None])
def test_issue8_d10_json_text_must_be_a_str(text):
    with pytest.raises(TypeError, match=r"'text' must be a str of trace JSON"):
        Trace.from_json(text)


BAD_RECORDS = [  # (a record with a wrong field, the validator's message, its JSON path or None)
    # The wire decoder builds nested records first: it names the innermost record at fault.
    (
        lambda: Span(polygon="x", y=[1], x_start=0, x_end=1, winding=1),
        r"^Span field 'polygon' must be int; got 'x' \(str\)$",
        r"\.polygon: must be int; got 'x' \(str\)$",
    ),
    (
        lambda: Span(polygon=0, y=[1], x_start=0, x_end=1, winding=1),
        r"^Span field 'y' must be int; got \[1\] \(list\)$",
        r"\.y: must be int; got \[1\] \(list\)$",
    ),
    (
        lambda: Span(polygon=0, y=0, x_start=0, x_end=1, winding=True),
        r"Span field 'winding' must be int; got True",
        r"\.winding: must be int; got True",
    ),
    (
        lambda: Span(polygon=0, y=0, x_start=0, x_end=np.int64(1), winding=1),
        r"Span field 'x_end' must be int; got np\.int64\(1\)|got 1 \(int64\)",
        None,  # JSON has no numpy ints
    ),
    (
        lambda: TriangleSetup(0, ((0.0, 1.0), ("a", 2.0)), ((0, 0),), 256, (), 0, 1, (0, 0, 1, 1)),
        r"TriangleSetup field 'vertices'\[1\]\[0\] must be a float",
        r"\.vertices\[1\]\[0\]: must be a float",
    ),
    (
        lambda: TriangleSetup(0, ((0.0, 1.0),), ((0, 0),), 256, (), 0, 1, (0, 0, 1)),
        r"TriangleSetup field 'bbox' must have 4 items; got 3",
        r"\.bbox: must have 4 items; got 3",
    ),
    (
        lambda: AetSorted(0, 1, (Span(0, 1, 2, 3, 1),), 0),
        r"AetSorted field 'entries'\[0\] must be AetEntry",
        r"\.entries\[0\]\.kind: is not a field of AetEntry",
    ),
    (
        lambda: AetEntry(0, 1.5, 1.5, 0.0, None, 2.0, 1),
        r"AetEntry field 'x_exact' must be a Fraction .* or None; got 1\.5",
        None,  # not an event: JSON holds it only inside one (next case)
    ),
    (
        lambda: AetSorted(0, 1, (AetEntry(0, 1.5, 1.5, 0.0, None, 2.0, 1),), 0),
        r"AetSorted field 'entries'\[0\]\.x_exact must be a Fraction .* or None; got 1\.5"
        r"|^not a valid AetEntry: AetEntry field 'x_exact' must be a Fraction .* got 1\.5",
        r"\.entries\[0\]\.x_exact: must be a Fraction .*; got 1\.5",
    ),
    (
        lambda: DepthTest(0, 1, 2, 10**400, None, True),
        r"DepthTest field 'z' must be a float within",
        r"\.z: must be a float within",
    ),
]


@pytest.mark.parametrize(("build", "message", "json_path"), BAD_RECORDS)
def test_issue8_d10_records_are_checked_where_they_enter(build, message, json_path):
    # Issue 24: building a record checks nothing (the traced loops build them hot); the one
    # validator names the field, and it runs where records enter: the JSON reader and the
    # jail's wire decoder (a student's events and a replaced step's records come in there).
    record = build()
    with pytest.raises(TypeError, match=message):
        validate(record)
    plain = wire.encode(record)
    with pytest.raises(wire.WireError, match=message.lstrip("^")):
        wire.decode(plain)
    if json_path is not None:
        with pytest.raises(ValueError, match=r"^trace JSON at events\[0\]" + json_path):
            Trace.from_json(json.dumps({"events": [codec.encode(record)]}))


def test_issue8_d10_the_validator_accepts_equal_values():
    # An int stands for a float (equal by value); None where the annotation allows it.
    validate(DepthTest(0, 1, 2, 3, None, True))
    assert DepthTest(0, 1, 2, 3, None, True) == DepthTest(0, 1, 2, 3.0, None, True)
    assert wire.decode(wire.encode(DepthTest(0, 1, 2, 3, None, True))) == DepthTest(
        0, 1, 2, 3.0, None, True
    )
    with pytest.raises(TypeError, match=r"'events'\[1\] must be an Event; got 1"):
        Trace([Span(0, 1, 2, 3, 1), 1])


def test_issue8_d10_non_finite_floats_are_written_as_strict_json():
    events = [
        DepthTest(0, 1, 2, math.inf, -math.inf, True),
        DepthTest(0, 1, 3, math.nan, None, False),
        DepthTest(0, 1, 4, -0.0, 5e-324, False),
    ]
    text = Trace(events).to_json()
    data = strict_loads(text)["events"]  # no Infinity / NaN literals
    assert [(e["z"], e["stored"]) for e in data] == [("inf", "-inf"), ("nan", None), (-0.0, 5e-324)]
    back = Trace.from_json(text)
    assert back[0] == events[0] and back[2] == events[2]
    assert math.copysign(1, back[2].z) == -1 and math.isnan(back[1].z)
    assert Trace.from_json(json.dumps({"events": [SPAN]}, allow_nan=True)) == Trace(
        [Span(0, 1, 2, 5, 1)]
    )
    legacy = json.dumps(
        {"events": [{**json.loads(text)["events"][0], "z": math.inf}]}
    )  # "Infinity"
    assert "Infinity" in legacy and Trace.from_json(legacy)[0] == events[0]


@pytest.mark.parametrize(
    ("filters", "error", "message"),
    [
        (
            {"kinds": 5},
            TypeError,
            r"'kinds' must be an event kind \(str\) or an iterable of them; got 5",
        ),
        ({"kinds": [3]}, TypeError, r"'kinds'\[0\] must be a str; got 3"),
        (
            {"kinds": ["spam", "aet_srted"]},
            ValueError,
            r"did you mean 'aet_sorted' for 'aet_srted', 'span' for 'spam'\?",
        ),
        (
            {"polygons": "ab"},
            TypeError,
            r"'polygons' must be an iterable of polygon indices \(ints\); got 'ab'",
        ),
        ({"polygons": [0, 1.5]}, TypeError, r"'polygons'\[1\] must be an int; got 1\.5"),
        ({"rows": (0, 2.5)}, TypeError, r"'rows'\[1\] must be an int; got 2\.5"),
        ({"rows": 5}, TypeError, r"'rows' must be a \(start, stop\) pair of ints; got 5"),
        ({"region": (0, 0, "4", 4)}, TypeError, r"'region'\[2\] must be an int; got '4'"),
    ],
)
def test_issue8_d10_recorder_arguments_are_checked(filters, error, message):
    with pytest.raises(error, match=message):
        Recorder(**filters)
    with pytest.raises(error, match=message):
        Trace().filter(**filters)


def test_issue8_d10_recorder_accepts_integer_like_filters():
    recorder = Recorder(kinds="span", polygons=np.array([0]), rows=(np.int64(2), 4))
    assert recorder.polygons == {0} and recorder.rows == (2, 4) and recorder.kinds == {"span"}

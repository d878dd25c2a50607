"""Fuzzing the trace JSON reader: hostile text gets a Trace or a clear error, valid traces round-trip.

Hostile input is random JSON and valid traces mutated at a random place:
deep nesting, wrong types, huge ints, non-finite strings, missing and extra
keys, unknown kinds. The only allowed outcomes are a Trace (which then
round-trips through its own JSON) or a ValueError / TypeError.
"""

import functools
import itertools
import json

from hypothesis import given, settings
from hypothesis import strategies as st

import scanviz
from scanviz import Recorder, Trace
from scanviz.conventions import SAMPLE_MODES
from scanviz.scene.builtin import builtin_scene
from scanviz.trace import EVENT_TYPES

FUZZ = settings(derandomize=True, max_examples=200, deadline=None)
DEEP, HUGE = "\x00deep\x00", "\x00huge\x00"  # placeholders replaced in the text


def strict_loads(text: str) -> object:
    def refuse(literal: str) -> None:
        raise AssertionError(f"non-standard JSON literal {literal} in a trace's JSON")

    return json.loads(text, parse_constant=refuse)


@functools.cache
def valid_traces() -> tuple[str, ...]:
    """JSON of small real traces: scan conversion, edge functions, and two small events of every
    kind that a z-buffer and an a-buffer render emit (the a-buffer's nest the deepest)."""
    triangle = [(0.5, 0.2), (6.3, 1.7), (2.1, 5.9)]
    scan = scanviz.scan_convert(triangle, 8, 8, trace=True).trace
    edge_functions = scanviz.triangle_samples(triangle, 8, 8, trace=True).trace
    sampled = []
    for name, visibility in [("umbc_zbuffer", "zbuffer"), ("transparent_cube", "abuffer")]:
        recorder = Recorder(region=(1, 1, 3, 4))
        trace = scanviz.render(
            builtin_scene(name), 6, 6, visibility=visibility, trace=recorder
        ).trace
        for kind in sorted({e.kind for e in trace}):
            small = (e for e in trace.of_kind(kind) if len(Trace([e]).to_json()) < 2000)
            sampled += itertools.islice(small, 2)
    return tuple(t.to_json() for t in (scan, edge_functions, Trace(sampled)))


scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.sampled_from([10**400, -(2**1024), 2**20 - 1, 2**20 + 1, 2**63, -(2**64)]),
    st.floats(),  # NaN and +-inf become the non-standard literals
    st.sampled_from(
        [-0.0, 5e-324, 1e308, "inf", "-inf", "nan", "NaN", "1/0", "3/2", "-7/4", "0/0"]
    ),
    st.text(max_size=8),
    st.sampled_from(sorted(EVENT_TYPES)),
    st.just(DEEP),
    st.just(HUGE),
)
json_values = st.recursive(
    scalars,
    lambda children: (
        st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=6), children, max_size=4)
    ),
    max_leaves=12,
)


def to_text(value: object, depth: int) -> str:
    """JSON text of `value`, placeholders expanded: `depth`-deep arrays and a 5000-digit number."""
    text = json.dumps(value)
    return text.replace(json.dumps(DEEP), "[" * depth + "]" * depth).replace(
        json.dumps(HUGE), "9" * 5000
    )


def mutate(data: object, draw) -> object:
    """`data` with one random change somewhere inside it."""
    if isinstance(data, dict | list) and data and draw(st.integers(0, 3)):
        keys = list(data) if isinstance(data, dict) else list(range(len(data)))
        key = draw(st.sampled_from(keys))
        copy = dict(data) if isinstance(data, dict) else list(data)
        copy[key] = mutate(data[key], draw)
        return copy
    change = draw(st.sampled_from(["replace", "drop", "extra", "kind", "wrap"]))
    if change == "replace" or not isinstance(data, dict | list):
        return draw(json_values)
    if change == "drop" and data:
        copy = dict(data) if isinstance(data, dict) else list(data)
        del copy[draw(st.sampled_from(list(copy) if isinstance(copy, dict) else range(len(copy))))]
        return copy
    if change == "extra":
        extra = draw(json_values)
        return (
            {**data, draw(st.text(max_size=6)): extra} if isinstance(data, dict) else [*data, extra]
        )
    if change == "kind" and isinstance(data, dict):
        kind = draw(st.sampled_from(sorted(EVENT_TYPES)) | st.text(max_size=12) | json_values)
        return {**data, "kind": kind}
    return [data]


def assert_clear_outcome(text: str) -> None:
    try:
        trace = Trace.from_json(text)
    except (ValueError, TypeError) as error:
        assert str(error)
        return
    again = trace.to_json()
    strict_loads(again)
    assert Trace.from_json(again).to_json() == again  # NaN != NaN, so compare the texts


@FUZZ
@given(json_values, st.sampled_from([1, 6, 8, 1000, 5000]))
def test_random_json_gives_a_trace_or_a_clear_error(value, depth):
    assert_clear_outcome(to_text(value, depth))
    assert_clear_outcome(to_text({"events": value}, depth))
    assert_clear_outcome(to_text({"events": [value]}, depth))


@FUZZ
@given(st.sampled_from(range(3)), st.sampled_from([1, 6, 8, 1000, 5000]), st.data())
def test_mutated_traces_give_a_trace_or_a_clear_error(which, depth, data):
    valid = json.loads(valid_traces()[which])
    assert_clear_outcome(to_text(mutate(valid, data.draw), depth))


@st.composite
def polygons(draw):
    """3 to 8 distinct vertices on a quarter-pixel grid, some outside the raster."""
    points = st.tuples(st.integers(-8, 72), st.integers(-8, 72)).map(lambda p: (p[0] / 4, p[1] / 4))
    return draw(st.lists(points, min_size=3, max_size=8, unique=True))


@settings(derandomize=True, max_examples=100, deadline=None)
@given(
    polygons(),
    st.integers(1, 16),
    st.integers(1, 16),
    st.sampled_from(SAMPLE_MODES),
    st.sampled_from(["exact", "float32", "float64"]),
)
def test_traces_of_random_polygons_round_trip_exactly_as_strict_json(
    poly, width, height, sample, arithmetic
):
    trace = scanviz.scan_convert(
        poly, width, height, sample=sample, arithmetic=arithmetic, trace=True
    ).trace
    text = trace.to_json()
    strict_loads(text)
    assert Trace.from_json(text) == trace

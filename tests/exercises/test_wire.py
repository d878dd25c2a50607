"""The plain-data codec of the jail's boundary (scanviz.exercises.jail.wire)."""

import dataclasses
import json
import math
from collections import namedtuple
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.exercises.jail import wire
from scanviz.exercises.jail.wire import Decoder, Encoder, Fields, Opaque, WireError, decode, encode
from scanviz.raster.scanline import AetItem
from scanviz.trace.events import AetEntry, AetSorted, Span


def _roundtrip(value, classes=None):
    return decode(json.loads(json.dumps(encode(value))), classes)


def test_values_keep_their_types_across():
    value = {
        "ints": [0, -3, 2**200],
        "floats": (0.1, math.inf, -math.inf),
        "exact": Fraction(-37, 10),
        "flags": (True, False, None),
        "text": "héllo",
        "array": np.arange(6, dtype=np.int64).reshape(2, 3),
        "empty": np.zeros((0, 4)),
        "scalar": np.float64(0.25),
        ("a", 1): "tuple key",
    }
    back = _roundtrip(value)
    assert back.keys() == value.keys()
    assert type(back["floats"]) is tuple and back["floats"][1:] == (math.inf, -math.inf)
    assert back["exact"] == Fraction(-37, 10) and type(back["exact"]) is Fraction
    assert back["array"].dtype == np.int64 and back["array"].shape == (2, 3)
    assert back["empty"].shape == (0, 4)
    assert type(back["scalar"]) is np.float64
    assert math.isnan(_roundtrip(math.nan))


def test_trace_records_are_built_for_real_and_checked():
    event = AetSorted(
        0, 2, (AetEntry(3, 3.7, Fraction(37, 10), -0.3, Fraction(-3, 10), 11.0, 1),), 1
    )
    assert _roundtrip(event) == event and type(_roundtrip(event)) is AetSorted
    plain = encode(Span(0, 1, 2, 5, 1))
    plain["fields"][2][1] = "two"  # x_start must be an int
    with pytest.raises(WireError, match="not a valid Span: Span field 'x_start' must be int"):
        decode(plain)


def test_other_records_become_fields_or_tuples_unless_the_decoder_knows_their_class():
    item = AetItem(0, Fraction(4), Fraction(-3, 10), 1, 11, 1)
    assert _roundtrip(item) == Fields("AetItem", dataclasses.asdict(item))
    assert _roundtrip(item).x == Fraction(4)
    assert _roundtrip(item, {"AetItem": AetItem}) == item
    Pair = namedtuple("Pair", "a b")
    assert _roundtrip(Pair(1, 2)) == (1, 2)
    assert _roundtrip({1, 2}) == Opaque("{1, 2}")


def test_a_reply_refers_back_to_the_requests_objects_and_their_changes_apply():
    # What the runner does with `e.x += e.dxdy`: the grader's own item changes.
    item = AetItem(0, Fraction(4), Fraction(-3, 10), 1, 11, 1)
    active = [item]
    request = Encoder(identify=True)
    plain = json.loads(json.dumps(request.encode((active, 2, []))))
    jail = Decoder(make_record=wire.jail_record_class)
    args = jail.decode(plain)
    jail_item = args[0][0]
    jail_item.x += jail_item.dxdy
    arguments = {id(obj): k for k, obj in jail.objects.items()}
    reply = Encoder(arguments=arguments)
    changed = {
        k: reply.state(obj) for k, obj in jail.objects.items() if reply.state(obj) != jail.states[k]
    }
    assert len(changed) == 1  # only the item: the lists are unchanged
    returned = reply.encode(([], args[0]))
    back = Decoder(classes={"AetItem": AetItem}, arguments=request.objects)
    for k, state in changed.items():
        wire.apply_state(request.objects[k], back.decode(state))
    retired, aet = back.decode(returned)
    assert aet is active and aet[0] is item and item.x == Fraction(37, 10)


@pytest.mark.parametrize(
    ("plain", "rule"),
    [
        ({"$q": [1, 0]}, "ZeroDivisionError"),
        ({"$q": [2**5000, 1]}, "more than 4096 bits"),
        (2**5000, "more than 4096 bits"),
        ("x" * 200_000, "longer than 100000"),
        ({"$a": [1, 2], "dtype": "int64", "shape": [3]}, "needs 3 values"),
        ({"$a": [], "dtype": "V1000000000", "shape": [0]}, "dtype must be bool, int or float"),
        ({"$a": ["x"], "dtype": "int64", "shape": [1]}, "values must be numbers"),
        ({"$rec": "os.system", "form": "frozen", "fields": []}, "must be an identifier"),
        ({"$rec": "X", "form": "class", "fields": []}, "form must be one of"),
        ({"$arg": 0}, "names no object of the request"),
        ({"$eval": "1"}, "unknown tag"),
        ({}, "not a plain value"),
        ({"$d": [[[1], 2]]}, "unhashable"),
        ({"$f": "1e999"}, r"'\$f' must be"),
    ],
)
def test_malformed_or_oversized_data_is_refused(plain, rule):
    with pytest.raises(WireError, match=rule):
        decode(plain)


def test_deep_or_huge_messages_are_refused():
    deep = []
    for _ in range(100):
        deep = [deep]
    with pytest.raises(WireError, match="nested more than"):
        decode(deep)
    with pytest.raises(WireError, match="more than 2000000 values"):
        decode([0] * (wire.MAX_NODES + 1))


plain_values = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats()
    | st.text(max_size=20)
    | st.fractions()
    | st.builds(lambda v: {"$f": v}, st.sampled_from(["nan", "inf", "x"])),
    lambda inner: (
        st.lists(inner, max_size=4)
        | st.builds(lambda v: {"$t": v}, st.lists(inner, max_size=4))
        | st.dictionaries(
            st.sampled_from(["$t", "$q", "$rec", "$a", "$d", "$arg", "x"]), inner, max_size=3
        )
    ),
    max_leaves=20,
)


@settings(max_examples=300, deadline=None)
@given(plain_values)
def test_any_json_value_decodes_or_is_refused_cleanly(plain):
    try:
        data = json.loads(json.dumps(plain, default=str))
    except ValueError:
        return
    try:
        decode(data)
    except WireError:
        pass

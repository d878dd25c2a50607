"""The step table: replacing a step changes what the reference loop does, and only inside the block."""

import threading

import pytest

from scanviz import scan_convert, steps
from scanviz.raster.scanline import span_rule


def test_default_table_is_the_reference():
    assert steps.get("span_rule") is span_rule
    assert steps.replaced() == frozenset()


def test_replacement_reaches_the_untraced_entry_point():
    square = [(0, 0), (4, 0), (4, 4), (0, 4)]
    assert scan_convert(square, 4, 4).mask.sum() == 16
    with steps.using(span_rule=lambda crossings, rule: []):
        result = scan_convert(square, 4, 4)
    assert result.mask.sum() == 0 and result.stats.path == "reference"
    assert scan_convert(square, 4, 4).mask.sum() == 16


def test_replacement_is_undone_after_an_error():
    with pytest.raises(RuntimeError), steps.using(span_rule=lambda *a: []):
        raise RuntimeError
    assert steps.get("span_rule") is span_rule


def test_replacement_is_local_to_the_thread():
    seen = []
    with steps.using(span_rule=lambda *a: []):
        thread = threading.Thread(target=lambda: seen.append(steps.get("span_rule")))
        thread.start()
        thread.join()
    assert seen == [span_rule]


def test_unknown_step_is_named_with_a_suggestion():
    with pytest.raises(ValueError, match=r"unknown step 'span_rul' \(did you mean 'span_rule'\?\)"):
        with steps.using(span_rul=print):
            pass


def test_replacement_must_be_callable():
    with pytest.raises(TypeError, match="step 'span_rule' must be replaced by a callable"):
        with steps.using(span_rule=3):
            pass


def test_every_step_is_documented():
    table = steps.table()
    assert {"span_rule"} <= {s.name for s in table}
    for step in table:
        assert step.takes.strip() and step.returns.strip(), step.name
        assert callable(step.reference)


def test_the_table_of_locations_is_what_the_modules_register():
    for name, module in steps.LOCATIONS.items():
        registered = {s.name for s in steps.table() if s.module == module}
        assert name in registered, (name, module)
        assert steps.get(name).__module__ == module
    assert [s.name for s in steps.table()] == list(steps.LOCATIONS)


def test_a_step_must_be_listed_where_it_is_registered():
    with pytest.raises(TypeError, match="'span_rule' is not listed in LOCATIONS as 'tests"):
        steps.step("span_rule", takes="x", returns="y")(lambda: None)
    with pytest.raises(TypeError, match="'no_such_step' is not listed"):
        steps.step("no_such_step", takes="x", returns="y")(lambda: None)

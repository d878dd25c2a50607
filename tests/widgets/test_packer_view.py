"""The packer view steps through pixel_packed events, one pixel per step."""

from scanviz.exercises import public_inputs
from scanviz.exercises.abuffer import case_resolve
from scanviz.widgets import PackerView, Stepper


def test_packer_view_shows_each_packed_pixel_and_its_steps():
    result = case_resolve(public_inputs("pixel_pack"), trace=True)
    packed = result.trace.of_kind("pixel_packed")
    view = PackerView(packed)
    stepper = Stepper(packed, [view])
    assert "step forward" in view.widget.value
    for step, event in enumerate(packed, start=1):
        stepper.slider.value = step
        assert f"pixel ({event.x}, {event.y})" in view.widget.value
        assert view.widget.value.count("<tr") == 1 + len(event.steps)  # header + one row per step

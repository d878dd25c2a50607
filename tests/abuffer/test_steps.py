"""The a-buffer's replaceable steps: insert_fragment and pack_pixel in the reference loop."""

import numpy as np
import pytest

import scanviz as sv
from scanviz import steps
from scanviz.abuffer import FragmentRecord, Fragments, resolve
from scanviz.abuffer.pixelstruct import insert_fragment
from scanviz.trace import Recorder

FULL = 0xF  # a 2x2 mask
LEFT, RIGHT = 0b0101, 0b1010
RED, GREEN = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)


def rows(*fragments):
    return Fragments.from_rows([dict(x=0, y=0, **f) for f in fragments])


def test_a_replaced_step_runs_the_reference_without_a_tracer():
    fragments = rows(dict(mask=LEFT, area=0.5, z=0.5, color=RED))
    grey = lambda *args: ((0.25, 0.25, 0.25), 0.5, ())  # noqa: E731
    assert resolve(fragments, 1, 1, layout=(2, 2)).stats.path == "compiled"
    with steps.using(pack_pixel=grey):
        result = resolve(fragments, 1, 1, layout=(2, 2))
    assert result.stats.path == "reference"
    assert result.image[0, 0].tolist() == [0.25, 0.25, 0.25] and result.alpha[0, 0] == 0.5


def test_the_insertion_step_leaves_its_list_alone():
    stored = FragmentRecord(0.5, 0.5, 0.5, LEFT, RED, 1.0, 0)
    pixel = [stored]
    front = FragmentRecord(0.25, 0.25, 1.0, FULL, GREEN, 1.0, 1)
    assert insert_fragment(pixel, front, FULL) == ([front], None, (stored,))
    assert pixel == [stored]


def test_a_combination_hidden_at_a_depth_tie_is_merged_then_discarded():
    # Red's left half, then a complete green at the same depth (after it: ties keep the
    # earlier), then red's right half: the two halves combine into a complete red at z 0.5,
    # which goes after green (equal z) and is hidden by it.
    fragments = rows(
        dict(mask=LEFT, area=0.5, z=0.5, color=RED, object=0),
        dict(mask=FULL, area=1.0, z=0.5, color=GREEN, object=1),
        dict(mask=RIGHT, area=0.5, z=0.5, color=RED, object=0),
    )
    traced = resolve(fragments, 1, 1, layout=(2, 2), trace=Recorder())
    compiled = resolve(fragments, 1, 1, layout=(2, 2))
    merged = FragmentRecord(0.5, 0.5, 1.0, FULL, RED, 1.0, 0)
    (merge,) = traced.trace.of_kind("fragments_merged")
    (discard,) = traced.trace.of_kind("fragments_discarded")
    assert merge.merged == merged and discard.discarded == (merged,)
    assert discard.front.color == GREEN
    for result in (traced, compiled):
        assert (result.stats.fragments_merged, result.stats.fragments_discarded) == (1, 1)
        assert [f.color for f in result.pixel(0, 0)] == [GREEN]
    np.testing.assert_array_equal(traced.image, compiled.image)


@pytest.mark.parametrize(
    ("step", "wrong", "message"),
    [
        (
            "insert_fragment",
            lambda fragments, incoming, full: fragments,
            "must return (the new list",
        ),
        ("pack_pixel", lambda *args: ((0.0, 0.0, 0.0), 1.0), "must return (color, alpha"),
        ("insert_fragment", lambda f, i, full: ([], None, (i,)), "kept none in front of them"),
    ],
)
def test_a_step_returning_the_wrong_shape_is_named(step, wrong, message):
    fragments = rows(
        dict(mask=LEFT, area=0.5, z=0.5, color=RED), dict(mask=RIGHT, area=0.5, z=0.6, color=GREEN)
    )
    with steps.using(**{step: wrong}), pytest.raises((TypeError, ValueError)) as error:
        resolve(fragments, 1, 1, layout=(2, 2))
    assert f"step {step!r}" in str(error.value) and message in str(error.value)


def test_a_replaced_packer_shows_in_an_untraced_render():
    cube = sv.load_scene("builtin:transparent_cube")
    magenta = lambda *args: ((1.0, 0.0, 1.0), 1.0, ())  # noqa: E731
    with steps.using(pack_pixel=magenta):
        result = sv.render(cube, 16, 16, visibility="abuffer")
    packed = result.abuffer.stats.pixels_list
    assert result.stats.path == "reference" and packed > 0
    assert int((result.image == (1.0, 0.0, 1.0)).all(axis=2).sum()) == packed

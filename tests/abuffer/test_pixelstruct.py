"""Pixelstructs, insertion, combining, discarding and the packer: golden cases and oracles."""

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.abuffer import Fragments, resolve
from scanviz.trace import Recorder, Trace

FULL = (1 << 64) - 1
LEFT = sum(0xF << (8 * j) for j in range(8))  # columns 0..3 of an 8x8 mask
BOTTOM = (1 << 32) - 1  # rows 0..3
RED, GREEN, BLUE, WHITE, BLACK = (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1), (0, 0, 0)


def fragment(mask, area, z, color=WHITE, **more):
    return dict(x=0, y=0, mask=mask, area=area, z=z, color=color, **more)


def both(rows, width=1, height=1, **options):
    """Reference and compiled results of the same fragments."""
    fragments = Fragments.from_rows(rows) if isinstance(rows, list) else rows
    return (
        resolve(fragments, width, height, trace=Recorder(), **options),
        resolve(fragments, width, height, **options),
    )


def assert_same(reference, compiled, tolerance=1e-12):
    np.testing.assert_allclose(reference.image, compiled.image, rtol=0, atol=tolerance)
    np.testing.assert_allclose(reference.alpha, compiled.alpha, rtol=0, atol=tolerance)
    assert {**vars(reference.stats), "path": ""} == {**vars(compiled.stats), "path": ""}
    height, width = reference.alpha.shape
    for y, x in itertools.product(range(height), range(width)):
        assert reference.pixel(x, y) == compiled.pixel(x, y)


def state(result):
    """Pixel (0, 0)'s pixelstruct kind and (z, mask) per fragment."""
    records = result.pixel(0, 0)
    kind = "empty" if not records else ("list" if result.stats.pixels_list else "simple")
    return kind, [(r.z, r.mask) for r in records]


# --- thesis Fig. 6.7 ----------------------------------------------------------------------


@pytest.mark.parametrize("weights", ["area", "mask"])
@pytest.mark.parametrize("order", [(0, 1), (1, 0)])
def test_fig_6_7_front_half_and_back_half(weights, order):
    rows = [fragment(LEFT, 0.5, 0.1, RED), fragment(BOTTOM, 0.5, 0.2, GREEN)]
    for result in both([rows[i] for i in order], weights=weights, background=BLUE):
        assert result.image[0, 0].tolist() == [0.5, 0.25, 0.25]
        assert result.alpha[0, 0] == 0.75


# --- no seam between polygons sharing an edge -------------------------------------------


@pytest.mark.parametrize("objects", [(0, 0), (0, 1)], ids=["combined", "two_objects"])
@pytest.mark.parametrize("weights", ["area", "mask"])
@pytest.mark.parametrize("area", [0.5, 0.3, 0.123456789])
def test_adjacent_polygons_leave_no_seam(objects, weights, area):
    rows = [
        fragment(LEFT, area, 0.5, object=objects[0]),
        fragment(FULL ^ LEFT, 1.0 - area, 0.5, object=objects[1]),
    ]
    for result in both(rows, weights=weights, background=BLACK):
        assert abs(result.alpha[0, 0] - 1.0) <= 1e-9
        np.testing.assert_allclose(result.image[0, 0], WHITE, atol=1e-9)
    flawed = both(rows, mode="flawed", background=BLACK)
    assert_same(*flawed)
    assert (flawed[1].image[0, 0] < 0.9).all()  # the thesis' grey seam


def test_single_fragment_covers_its_exact_area():
    for mask, area in [(LEFT, 0.47), (1, 0.01), (0, 0.002), (FULL ^ 1, 0.99)]:
        for result in both([fragment(mask, area, 0.3)], weights="area"):
            assert result.alpha[0, 0] == pytest.approx(area, abs=1e-15)


def test_three_polygons_around_a_vertex_leave_no_seam():
    masks = (LEFT, BOTTOM & ~LEFT, FULL & ~LEFT & ~BOTTOM)
    rows = [
        fragment(m, a, z, object=i)
        for i, (m, a, z) in enumerate(zip(masks, (0.4, 0.35, 0.25), (0.3, 0.1, 0.2), strict=True))
    ]
    for result in both(rows, weights="area"):
        assert result.alpha[0, 0] == pytest.approx(1.0, abs=1e-12)


# --- the six insertion cases (thesis §6.3.4) ----------------------------------------------

SIMPLE = fragment(FULL, 1.0, 0.5, RED, object=1)
PARTIAL = fragment(LEFT, 0.5, 0.3, GREEN, object=2)


@pytest.mark.parametrize(
    ("before", "incoming", "case", "expected"),
    [
        ([], fragment(FULL, 1.0, 0.2), "complete_empty", ("simple", [(0.2, FULL)])),
        ([], PARTIAL, "partial_empty", ("list", [(0.3, LEFT)])),
        ([SIMPLE], fragment(FULL, 1.0, 0.2), "complete_simple", ("simple", [(0.2, FULL)])),
        ([SIMPLE], fragment(FULL, 1.0, 0.7), "complete_simple", ("simple", [(0.5, FULL)])),
        ([SIMPLE], PARTIAL, "partial_simple", ("list", [(0.3, LEFT), (0.5, FULL)])),
        (
            [PARTIAL],
            fragment(FULL, 1.0, 0.4),
            "complete_list",
            ("list", [(0.3, LEFT), (0.4, FULL)]),
        ),
        (
            [PARTIAL],
            fragment(BOTTOM, 0.5, 0.1),
            "partial_list",
            ("list", [(0.1, BOTTOM), (0.3, LEFT)]),
        ),
    ],
)
def test_six_insertion_cases(before, incoming, case, expected):
    reference, compiled = both([*before, incoming])
    assert_same(reference, compiled)
    inserted = reference.trace.of_kind("fragment_inserted")[-1]
    assert inserted.case == case
    assert inserted.before_kind == (
        before and ("simple" if before[0] is SIMPLE else "list") or "empty"
    )
    assert (inserted.after_kind, [(r.z, r.mask) for r in inserted.after]) == expected
    assert state(compiled) == expected


def test_transparent_complete_fragment_makes_a_list():
    reference, compiled = both([fragment(FULL, 1.0, 0.2, opacity=0.5)], background=BLUE)
    assert_same(reference, compiled)
    assert state(compiled)[0] == "list"
    assert compiled.image[0, 0].tolist() == [0.5, 0.5, 1.0]


# --- combining and discarding (thesis §6.3.5) ---------------------------------------------


def test_same_object_fragments_combine_and_collapse_to_simple():
    rows = [
        fragment(BOTTOM, 0.25, 0.6, BLUE, object=9),  # behind: discarded once the pixel is covered
        fragment(LEFT, 0.5, 0.2, RED, object=3),
        fragment(FULL ^ LEFT, 0.5, 0.3, RED, object=3),
    ]
    reference, compiled = both(rows)
    assert_same(reference, compiled)
    (merged,) = compiled.pixel(0, 0)
    assert (merged.z, merged.zmax, merged.mask, merged.area, merged.color) == (
        0.2,
        0.3,
        FULL,
        1.0,
        RED,
    )
    stats = compiled.stats
    assert (stats.pixels_simple, stats.fragments_merged, stats.fragments_discarded) == (1, 1, 1)
    assert stats.longest_list == 2
    (event,) = reference.trace.of_kind("fragments_merged")
    assert (event.stored.mask, event.incoming.mask, event.merged.mask) == (LEFT, FULL ^ LEFT, FULL)
    (dropped,) = reference.trace.of_kind("fragments_discarded")
    assert [r.z for r in dropped.discarded] == [0.6]


def test_no_combining_across_objects_colors_or_complete_masks():
    for other in (dict(object=4), dict(color=(1, 0, 1e-9)), dict(opacity=0.5)):
        rows = [
            fragment(LEFT, 0.5, 0.2, RED, object=3),
            {**fragment(FULL ^ LEFT, 0.5, 0.3, RED, object=3), **other},
        ]
        assert both(rows)[1].stats.fragments_merged == 0
    rows = [fragment(LEFT, 0.5, 0.2, RED, object=3), fragment(FULL, 1.0, 0.3, RED, object=3)]
    assert both(rows)[1].stats.fragments_merged == 0


def test_discarding_behind_a_complete_opaque_fragment():
    rows = [
        fragment(LEFT, 0.5, 0.8),  # stored, then thrown away
        fragment(FULL, 1.0, 0.5, RED),
        fragment(BOTTOM, 0.5, 0.9),  # arrives behind: thrown away
        fragment(FULL, 1.0, 0.5, GREEN),  # equal z: the earlier one stays
        fragment(BOTTOM, 0.5, 0.1, BLUE),  # in front: kept
    ]
    reference, compiled = both(rows)
    assert_same(reference, compiled)
    assert [(r.z, r.color) for r in compiled.pixel(0, 0)] == [(0.1, BLUE), (0.5, RED)]
    stats = compiled.stats
    assert (stats.fragments_inserted, stats.fragments_discarded, stats.longest_list) == (5, 3, 2)
    assert (stats.pixels_empty, stats.pixels_simple, stats.pixels_list) == (0, 0, 1)


# --- transparency and insertion order -----------------------------------------------------

masks = st.integers(0, FULL)
colors = st.tuples(*[st.sampled_from([0.0, 0.25, 0.5, 1.0])] * 3)


@st.composite
def transparent_pixel(draw):
    count = draw(st.integers(1, 5))
    zs = draw(st.lists(st.integers(0, 100), min_size=count, max_size=count, unique=True))
    rows = [
        fragment(
            draw(st.one_of(masks, st.just(FULL))),
            draw(st.floats(0, 1)),
            z / 100,
            draw(colors),
            opacity=draw(st.sampled_from([1.0, 0.75, 0.5, 0.0])),
            object=i,
        )  # fmt: skip
        for i, z in enumerate(zs)
    ]
    return rows, draw(st.permutations(range(count)))


@settings(max_examples=settings.default.max_examples // 2)
@given(transparent_pixel(), st.sampled_from(["area", "mask"]))
def test_transparency_is_independent_of_insertion_order(case, weights):
    rows, order = case
    first = resolve(Fragments.from_rows(rows), 1, 1, weights=weights, background=(0.1, 0.2, 0.3))
    for result in both([rows[i] for i in order], weights=weights, background=(0.1, 0.2, 0.3)):
        np.testing.assert_allclose(result.image, first.image, rtol=0, atol=1e-12)
        np.testing.assert_allclose(result.alpha, first.alpha, rtol=0, atol=1e-12)
        assert 0.0 <= result.alpha[0, 0] <= 1.0 + 1e-12


def test_transparent_front_over_opaque_back():
    rows = [fragment(LEFT, 0.5, 0.1, RED, opacity=0.5), fragment(BOTTOM, 0.5, 0.2, GREEN)]
    for result in both(rows, weights="mask", background=BLUE):
        # left-bottom: red over green; left-top: red over blue; right: green / blue
        expected = 0.25 * (0.5 * np.array(RED) + 0.5 * np.array(GREEN))
        expected += 0.25 * (0.5 * np.array(RED) + 0.5 * np.array(BLUE))
        expected += 0.25 * np.array(GREEN) + 0.25 * np.array(BLUE)
        np.testing.assert_allclose(result.image[0, 0], expected, atol=1e-15)
        assert result.alpha[0, 0] == pytest.approx(1 - 0.125 - 0.25)


# --- reference == compiled ---------------------------------------------------------------


@st.composite
def scenes(draw):
    count = draw(st.integers(0, 14))
    rows = []
    for _ in range(count):
        mask = draw(st.sampled_from([LEFT, FULL ^ LEFT, BOTTOM, FULL ^ BOTTOM, FULL, 0]) | masks)
        rows.append(
            dict(
                x=draw(st.integers(0, 2)),
                y=draw(st.integers(0, 1)),
                mask=mask,
                area=draw(st.sampled_from([0.0, 0.5, 1.0]) | st.floats(0, 1)),
                zmin=draw(st.sampled_from([0.1, 0.2, 0.3]) | st.floats(0, 1)),
                color=draw(st.sampled_from([WHITE, RED]) | colors),
                opacity=draw(st.sampled_from([1.0, 1.0, 0.5, 0.0])),
                object=draw(st.integers(0, 2)),
            )  # fmt: skip
        )
    for i in draw(st.lists(st.integers(0, max(count - 1, 0)), max_size=4 if count else 0)):
        twin = dict(rows[i], mask=FULL ^ rows[i]["mask"], zmin=draw(st.floats(0, 1)))
        rows.insert(draw(st.integers(i + 1, len(rows))), twin)  # the same surface, other side
    for polygon, row in enumerate(rows):
        row["zmax"] = row["zmin"] + draw(st.sampled_from([0.0, 0.05]))
        row["polygon"] = polygon
    return rows


@given(scenes(), st.sampled_from(["area", "mask"]), st.sampled_from(["abuffer", "flawed"]))
def test_reference_equals_compiled(rows, weights, mode):
    assert_same(*both(rows, 3, 2, weights=weights, mode=mode, background=(0.2, 0.4, 0.6)))


def test_layouts_smaller_than_64_bits():
    rows = [fragment(0b0011, 0.5, 0.1, RED), fragment(0b0101, 0.5, 0.2, GREEN)]
    for result in both(rows, layout=(2, 2), weights="mask", background=BLUE):
        assert result.image[0, 0].tolist() == [0.5, 0.25, 0.25]
    with pytest.raises(ValueError, match="'mask'\\[0\\] = 31 has bits outside"):
        resolve(Fragments.from_rows([fragment(31, 0.5, 0.1)]), 1, 1, layout="2x2")


# --- trace --------------------------------------------------------------------------------


def test_trace_follows_one_pixel_and_round_trips():
    rows = [fragment(LEFT, 0.5, 0.1, RED, opacity=0.5), fragment(BOTTOM, 0.5, 0.2, GREEN)]
    rows += [{**r, "x": 1} for r in rows]
    recorder = Recorder(region=(1, 0, 2, 1))
    result = resolve(Fragments.from_rows(rows), 2, 1, trace=recorder)
    kinds = [e.kind for e in result.trace]
    assert kinds == ["fragment_inserted", "fragment_inserted", "pixel_packed"]
    assert all(e.x == 1 for e in result.trace)
    (packed,) = result.trace.of_kind("pixel_packed")
    assert packed.color == tuple(result.image[0, 1]) and packed.alpha == result.alpha[0, 1]
    top = packed.steps[-1]
    assert (top.level, top.branch, top.region, top.mask_a, top.a) == (0, "", FULL, LEFT, 0.5)
    assert {s.branch for s in packed.steps} == {"", "u", "c"}  # red is transparent
    assert Trace.from_json(result.trace.to_json()) == result.trace
    flawed = resolve(Fragments.from_rows(rows), 2, 1, mode="flawed", trace=True)
    assert [e.passed for e in flawed.trace.of_kind("coverage_blended")] == [True, False] * 2


# --- validation ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (dict(area=1.5), "'area'\\[0\\] = 1.5 is not in \\[0, 1\\]"),
        (dict(opacity=-0.1), "'opacity'\\[0\\] = -0.1 is not in \\[0, 1\\]"),
        (dict(zmin=0.5, zmax=0.4), "'zmax'\\[0\\] = 0.4 is below 'zmin'"),
        (dict(x=3), "'x'\\[0\\] = 3 is not in 0..0"),
        (dict(color=(np.nan, 0, 0)), "'color'\\[0\\] = \\[nan, 0.0, 0.0\\] is not finite"),
    ],
)
def test_bad_fragments_are_named(change, message):
    with pytest.raises(ValueError, match=message):
        resolve(Fragments.from_rows([{**fragment(LEFT, 0.5, 0.1), **change}]), 1, 1)


def test_bad_options_are_named():
    fragments = Fragments.from_rows([fragment(LEFT, 0.5, 0.1)])
    for options, message in [
        (dict(weights="bits"), "'weights' must be one of"),
        (dict(mode="zbuffer"), "'mode' must be one of"),
        (dict(layout=(9, 8)), "'layout' must have 1..64 sub-samples"),
        (dict(background=(0, 0)), "'background' must be an"),
    ]:
        with pytest.raises(ValueError, match=message):
            resolve(fragments, 1, 1, **options)
    with pytest.raises(TypeError, match="'fragments' must be a Fragments"):
        resolve([], 1, 1)

"""Issue 27: raster costs estimated before they are paid; no polygon makes the walk quadratic."""

import operator
from fractions import Fraction

import numpy as np
import pytest

from scanviz import Polygon, scan_convert
from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.raster import api, scanline
from scanviz.raster.fill import ColourWash, Pattern, Solid, fill_polygon
from scanviz.raster.fixed import snap
from scanviz.raster.walk_compiled import CEIL, DEN, Q, R, merge_sort_active, sort_active


def star(points: int, outer: float, inner: float, centre=(12.0, 12.0)) -> np.ndarray:
    """A star whose spikes all cross a small raster: its AET is reordered on every row."""
    angle = np.arange(points) * 2 * np.pi / points
    radius = np.where(np.arange(points) % 2 == 0, outer, inner)
    return np.column_stack([centre[0] + radius * np.cos(angle), centre[1] + radius * np.sin(angle)])


TRIANGLE = [(0, 0), (300, 0), (150, 300)]


def test_fill_polygon_refuses_its_image_before_allocating_it():
    # 300 x 300 x 25 bytes (mask + RGB float64 image) = 2.1 MiB: over 1 MiB, though the
    # scan's own mask (90 KB) is not.
    with memory_limit("1M"), pytest.raises(ResourceLimitError) as refused:
        fill_polygon(TRIANGLE, 300, 300)
    message = str(refused.value)
    assert "fill_polygon: a 300x300 RGB image" in message and "2.1 MiB" in message
    assert "\n" not in message


@pytest.mark.parametrize(
    ("fill", "refused"),
    [(Solid(), False), (Pattern.checker(), True), (ColourWash((1, 0, 0), (0, 0, 1)), True)],
)
def test_each_fill_counts_its_own_buffers(fill, refused):
    # 200 x 200: 25 bytes a pixel fit in 1 MiB (1.0e6 bytes); a pattern's 81 and a wash's 65 do not.
    with memory_limit("1M"):
        if refused:
            with pytest.raises(ResourceLimitError, match=type(fill).__name__):
                fill_polygon(TRIANGLE, 200, 200, fill)
        else:
            assert fill_polygon(TRIANGLE, 200, 200, fill).mask.any()


def test_a_scrambled_star_scans_with_n_log_n_comparisons_in_the_reference(monkeypatch):
    # 4,000 spikes through a 24 x 24 raster, decided exactly (subpixel_bits=None: the reference).
    # Row to row the AET's order changes by 1.4 million exchanges; an insertion sort made at
    # least that many comparisons, a merge sort makes fewer than n log2 n per row.
    compared = []
    less = Fraction.__lt__
    monkeypatch.setattr(Fraction, "__lt__", lambda a, b: compared.append(1) or less(a, b))
    result = scan_convert(star(4000, 1000.0, 3.0), 24, 24, subpixel_bits=None)
    monkeypatch.undo()
    assert result.stats.path == "reference" and result.stats.swaps == 1_403_968
    bound = result.stats.rows_scanned * result.stats.max_active * np.log2(result.stats.max_active)
    assert 0 < len(compared) < bound < result.stats.swaps


@pytest.mark.parametrize("seed", range(5))
def test_exchanges_are_the_insertion_sorts_swaps(seed):
    order = np.random.default_rng(seed).permutation(300).tolist()
    before = sorted(order)
    assert scanline._exchanges(before, order) == scanline._insertion_sort(list(order), operator.lt)


@pytest.mark.parametrize("rule", ["nonzero", "evenodd"])
@pytest.mark.parametrize("sample", ["corner", "center"])
def test_a_scrambled_star_gets_the_references_spans_from_the_compiled_scan(rule, sample):
    polygon = star(600, 400.0, 3.0)
    fast = scan_convert(polygon, 24, 24, rule=rule, sample=sample)
    reference = scan_convert(polygon, 24, 24, rule=rule, sample=sample, trace=True)
    assert fast.stats.path == "compiled" and reference.stats.path == "reference"
    assert np.array_equal(fast.spans, reference.spans) and len(fast.spans) > 24
    assert fast.stats.max_active == reference.stats.max_active > 100


@pytest.mark.parametrize("by_x", [False, True])
@pytest.mark.parametrize("seed", range(4))
def test_the_aet_sort_is_stable_when_it_hands_over_to_the_merge_sort(by_x, seed):
    # A scrambled AET with many ties (equal ceilings, equal x): both sorts must give Python's
    # stable order by the key, the insertion sort's order.
    rng = np.random.default_rng(seed)
    count = 500
    aet = np.zeros((8, count + 1), np.int64)
    aet[Q, :count] = rng.integers(-3, 4, count)
    aet[DEN, :count] = rng.choice([1, 2, 4], count)
    aet[R, :count] = rng.integers(0, 4, count) % aet[DEN, :count]
    aet[CEIL, :count] = aet[Q, :count] + (aet[R, :count] > 0)
    xs, edge_of = np.zeros((2, count + 1)), np.arange(count + 1)
    exact = [
        Fraction(int(aet[Q, e])) + Fraction(int(aet[R, e]), int(aet[DEN, e])) for e in range(count)
    ]
    key = exact if by_x else aet[CEIL, :count].tolist()
    expected = sorted(range(count), key=key.__getitem__)
    merged = (aet.copy(), xs.copy(), edge_of.copy())
    sort_active(aet, xs, edge_of, count, by_x)
    merge_sort_active(*merged, count, by_x)
    assert edge_of[:count].tolist() == expected == merged[2][:count].tolist()
    assert np.array_equal(aet[:, :count], merged[0][:, :count])


def test_scan_convert_refuses_a_walk_past_its_crossing_budget(monkeypatch):
    # Both sides of the box cross all 24 rows; the raster shows only a sliver of it.
    box = [(-100.5, -5), (100.5, -5), (100.5, 30), (-100.5, 30)]
    assert api.active_crossings(snap(Polygon(box)), 24) == 2 * 24
    monkeypatch.setattr(api, "MAX_CROSSINGS", 47)
    with pytest.raises(ValueError, match=r"4 edges cross 48 sample rows of the 24x24 raster"):
        scan_convert(box, 24, 24)
    monkeypatch.setattr(api, "MAX_CROSSINGS", 48)
    assert scan_convert(box, 24, 24).mask.all()

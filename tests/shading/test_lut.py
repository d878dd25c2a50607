"""The specular look-up table: Tables 3-1..3-4, the look-up rule, the searches, bad parameters."""

import math

import numpy as np
import pytest
from hypothesis import given, seed, settings
from hypothesis import strategies as st

from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.shading.lut import (
    lut_level,
    lut_level_coherent,
    lut_level_compiled,
    lut_levels,
    specular_levels_exact,
    specular_lut,
    table_size,
)

# (Ip, ks, r + r0, n) of each table (spec §2.7; the printed tables' column order is Ip, r + r0, ks)
TABLE_3_1 = (255, 1, 1, 6)
TABLE_3_2 = (255, 1, 1, 8)
TABLE_3_3 = (255, 0.5, 1.2, 6)
TABLE_3_4 = (255, 0.7, 1.5, 8)
TABLES = [TABLE_3_1, TABLE_3_2, TABLE_3_3, TABLE_3_4]

GOLDEN = [  # values printed in the dissertation (seed004-spec.md §2.7, §8 item 8)
    (TABLE_3_1, {1: 0.3971, 2: 0.4457, 30: 0.7000, 100: 0.8555, 128: 0.8915, 200: 0.9603,
                 254: 0.9993, 255: 1.0000}),
    (TABLE_3_2, {1: 0.5002, 2: 0.5455, 30: 0.7653, 100: 0.8896, 128: 0.9175, 200: 0.9701,
                 254: 0.9995, 255: 1.0000}),
    (TABLE_3_3, {1: 0.4597, 2: 0.5160, 50: 0.8823, 105: 0.9984, 106: 1.0000}),
    (TABLE_3_4, {1: 0.5502, 2: 0.6000, 60: 0.9180, 118: 0.9989, 119: 1.0000}),
]  # fmt: skip


def specials(table):
    """Every breakpoint, its float neighbours, midpoints and the out-of-range cosines."""
    midpoints = (np.concatenate([[0.0], table[:-1]]) + table) / 2
    below, above = np.nextafter(table, -np.inf), np.nextafter(table, np.inf)
    edges = [-np.inf, -1.0, -0.0, 0.0, 5e-324, 1.0, 1.5, np.inf, np.nan]
    return np.concatenate([table, below, above, midpoints, edges])


# -- the table ------------------------------------------------------------------------------------


@pytest.mark.parametrize(("parameters", "values"), GOLDEN, ids=["3-1", "3-2", "3-3", "3-4"])
def test_the_table_reproduces_the_printed_values(parameters, values):
    table = specular_lut(*parameters)
    for j, printed in values.items():
        assert abs(table[j - 1] - printed) <= 5e-5, (j, table[j - 1], printed)


@pytest.mark.parametrize(
    ("parameters", "size"), list(zip(TABLES, [255, 255, 106, 119], strict=True))
)
def test_the_table_has_floor_of_ip_ks_over_r_plus_r0_entries_and_ends_at_one(parameters, size):
    table = specular_lut(*parameters)
    assert table.shape == (size,) and table.dtype == np.float64
    assert table[-1] == 1.0
    assert np.all(np.diff(table) > 0)


def test_table_3_3_proves_n_is_floored():
    # Isr = 255 * 0.5 / 1.2 = 106.25; unfloored, cos φ_1 would be 0.4595, but 0.4597 is printed
    unfloored = (1 / 106.25) ** (1 / 6)
    assert round(unfloored, 4) == 0.4595 and abs(unfloored - 0.4597) > 5e-5
    assert round(specular_lut(*TABLE_3_3)[0], 4) == 0.4597


def test_the_level_count_is_exact_for_decimal_parameters():
    assert math.floor(100 * 0.29) == 28  # the float trap
    assert table_size(100, 0.29, 1) == 29
    assert len(specular_lut(100, 0.29, 1, 6)) == 29


def test_the_table_is_read_only():
    table = specular_lut(*TABLE_3_1)
    with pytest.raises(ValueError, match="read-only"):
        table[0] = 0.0


@pytest.mark.parametrize("parameters", [(255, 0, 1, 6), (0.5, 1, 1, 6), (255, 0.003, 1, 8)])
def test_fewer_than_one_level_gives_an_empty_table_and_level_zero(parameters):
    table = specular_lut(*parameters)
    assert table.shape == (0,)
    cosines = [-1.0, 0.0, 0.5, 1.0, 2.0, np.nan]
    for cosine in cosines:
        assert lut_level(table, cosine, count=True) == (0, 0)
        assert lut_level_coherent(table, cosine, 0, count=True) == (0, 0)
    np.testing.assert_array_equal(lut_levels(table, cosines), 0)
    np.testing.assert_array_equal(specular_levels_exact(0, 6, cosines), 0)


def test_one_level_is_reached_only_at_cos_phi_one():
    table = specular_lut(1.5, 1, 1, 6)
    np.testing.assert_array_equal(table, [1.0])
    assert [lut_level(table, c) for c in (0.999999, 1.0, 1.1)] == [0, 1, 1]


def test_a_tiny_exponent_keeps_underflowed_entries_above_zero():
    # (1/255)^1000 underflows to 0.0, but cos φ = 0 is still level 0, as floor(N·0^n) says
    table = specular_lut(255, 1, 1, 0.001)
    assert table[0] > 0
    cosines = [-0.0, 0.0, 5e-324, 1e-300, 0.5]
    expected = specular_levels_exact(255, 0.001, cosines)
    assert expected[0] == expected[1] == 0 and expected[2] > 100
    np.testing.assert_array_equal(lut_levels(table, cosines), expected)


# -- the look-up rule -------------------------------------------------------------------------------


def test_the_exact_levels_by_hand():
    # 0.7^6 = 0.117649, * 255 = 30.0005;  0.5^6 * 255 = 3.98;  0.3^8 * 119 = 0.0078
    np.testing.assert_array_equal(
        specular_levels_exact(255, 6, [0.7, 0.5, 1.0, 1.2, -0.3, np.nan]), [30, 3, 255, 255, 0, 0]
    )
    assert specular_levels_exact(119, 8, 0.3) == 0


def test_the_look_up_rule_at_the_printed_values():
    table = specular_lut(*TABLE_3_1)
    assert lut_level(table, table[29]) == 30  # cos φ_30 <= cos φ: level 30
    assert lut_level(table, np.nextafter(table[29], 0)) == 29  # just below: 29
    assert lut_level(table, table[0]) == 1 and lut_level(table, np.nextafter(table[0], 0)) == 0
    assert lut_level(table, -0.5) == 0 and lut_level(table, np.nan) == 0
    assert lut_level(table, 1.0) == 255 and lut_level(table, 7.0) == 255


def distance_to_a_breakpoint(size, n, cosines):
    """|cos φ - (j/N)^(1/n)| for the nearest j, in exact-enough numpy, independent of the module."""
    if size == 0:
        return np.full(len(cosines), np.inf)
    breakpoints = (np.arange(1, size + 1) / size) ** (1 / n)
    above = np.searchsorted(breakpoints, cosines).clip(0, size - 1)
    below = (above - 1).clip(0, size - 1)
    return np.minimum(np.abs(cosines - breakpoints[above]), np.abs(cosines - breakpoints[below]))


@seed(20261202)
@settings(max_examples=60, deadline=None)
@given(
    Ip=st.floats(1, 2000),
    ks=st.floats(0, 2),
    r_plus_r0=st.floats(1, 4),
    n=st.floats(0.5, 300),
    cosines=st.lists(st.floats(0, 1), min_size=1, max_size=20),
    rng_seed=st.integers(0, 2**32 - 1),
)
def test_the_look_up_equals_floor_of_n_cos_to_the_n_except_at_float_ties(
    Ip, ks, r_plus_r0, n, cosines, rng_seed
):
    table = specular_lut(Ip, ks, r_plus_r0, n)
    size = table_size(Ip, ks, r_plus_r0)
    random = np.random.default_rng(rng_seed).uniform(0, 1, 2000)
    cosines = np.concatenate([cosines, random])
    far = distance_to_a_breakpoint(size, n, cosines) > 1e-12
    levels = lut_levels(table, cosines)
    exact = specular_levels_exact(size, n, cosines)
    np.testing.assert_array_equal(levels[far], exact[far])
    assert np.count_nonzero(~far[-len(random) :]) <= 1  # uniform cosines almost never tie
    for cosine, level in zip(cosines[:20], levels[:20], strict=True):
        assert lut_level(table, cosine) == level


def test_on_every_breakpoint_the_oracle_is_off_by_at_most_one_level():
    # the table says j on cos φ_j; floor(N cos_j^n) says j or, when cos_j rounded down, j - 1
    mismatches = 0
    for parameters in TABLES:
        table = specular_lut(*parameters)
        levels = lut_levels(table, table)
        exact = specular_levels_exact(len(table), parameters[3], table)
        np.testing.assert_array_equal(levels, np.arange(1, len(table) + 1))
        assert np.all((levels - exact >= 0) & (levels - exact <= 1))
        mismatches += np.count_nonzero(levels != exact)
    assert mismatches < 0.6 * sum(len(specular_lut(*p)) for p in TABLES)


# -- the searches -----------------------------------------------------------------------------------


@pytest.mark.parametrize("parameters", TABLES, ids=["3-1", "3-2", "3-3", "3-4"])
def test_binary_coherent_compiled_and_vectorised_agree_everywhere(parameters):
    table = specular_lut(*parameters)
    cosines = specials(table)
    vectorised = lut_levels(table, cosines)
    size = len(table)
    for cosine, level in zip(cosines, vectorised, strict=True):
        assert lut_level(table, cosine) == level
        assert lut_level_compiled(table, cosine) == level
        for start in {0, size // 2, size, max(level - 1, 0), level, min(level + 1, size)}:
            assert lut_level_coherent(table, cosine, start) == level


def test_vectorised_keeps_the_shape_and_order():
    table = specular_lut(*TABLE_3_4)
    grid = np.linspace(-0.2, 1.2, 24).reshape(4, 6)
    for cosines in (grid, grid.T, grid[:, ::2], np.float64(0.6)):
        levels = lut_levels(table, cosines)
        assert levels.shape == np.shape(cosines) and levels.dtype == np.int64
        expected = [lut_level(table, float(c)) for c in np.ravel(cosines)]
        np.testing.assert_array_equal(levels.ravel(), expected)


@pytest.mark.parametrize("size", [*range(0, 70), 127, 128, 255, 256, 1000, 4095])
def test_binary_search_makes_at_most_ceil_log2_n_plus_one_comparisons(size):
    table = specular_lut(size or 1, 1 if size else 0, 1, 6)
    bound = math.ceil(math.log2(size + 1))
    counts = {lut_level(table, c, count=True)[1] for c in specials(table)}
    assert max(counts) <= bound
    assert min(counts) >= bound - 1  # balanced: every path is within one of the bound


def test_binary_search_makes_8_comparisons_for_n_255():
    table = specular_lut(*TABLE_3_1)
    assert {lut_level(table, c, count=True)[1] for c in specials(table)} == {8}


def test_the_coherent_step_costs_the_distance_moved_plus_at_most_two():
    table = specular_lut(*TABLE_3_3)
    size = len(table)
    for start in range(0, size + 1, 7):
        for cosine in specials(table)[::5]:
            level, comparisons = lut_level_coherent(table, cosine, start, count=True)
            assert comparisons <= abs(level - start) + 2
            assert comparisons >= 1


def test_along_a_smooth_span_the_coherent_step_beats_the_binary_search():
    table = specular_lut(*TABLE_3_1)
    span = np.cos(np.linspace(-0.6, 0.6, 1000))  # a highlight crossed by a 1000-pixel span
    level, coherent, binary = 0, 0, 0
    for cosine in span:
        level, steps = lut_level_coherent(table, cosine, level, count=True)
        coherent += steps
        binary += lut_level(table, cosine, count=True)[1]
    assert binary == 8 * len(span)
    assert coherent < binary / 2


# -- bad parameters ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("parameters", "message"),
    [
        ((0, 1, 1, 6), "'Ip' .* must be > 0"),
        ((-255, 1, 1, 6), "'Ip' .* must be > 0"),
        ((math.nan, 1, 1, 6), "'Ip' must be finite"),
        ((math.inf, 1, 1, 6), "'Ip' must be finite"),
        ((255, -0.1, 1, 6), "'ks' .* must be >= 0"),
        ((255, math.nan, 1, 6), "'ks' must be finite"),
        ((255, 1, 0.99, 6), r"'r_plus_r0' .* must be >= 1"),
        ((255, 1, 0, 6), r"'r_plus_r0' .* must be >= 1"),
        ((255, 1, math.inf, 6), "'r_plus_r0' must be finite"),
        ((255, 1, 1, 0), "'n' .* must be > 0"),
        ((255, 1, 1, -6), "'n' .* must be > 0"),
        ((255, 1, 1, math.nan), "'n' must be finite"),
    ],
)
def test_bad_parameters_name_the_argument_and_the_rule(parameters, message):
    with pytest.raises(ValueError, match=message):
        specular_lut(*parameters)


@pytest.mark.parametrize("parameters", [("255", 1, 1, 6), (255, None, 1, 6), (255, 1, True, 6)])
def test_parameters_must_be_numbers(parameters):
    with pytest.raises(TypeError, match="must be a real number"):
        specular_lut(*parameters)


def test_a_hostile_intensity_is_refused_before_allocating():
    with pytest.raises(ResourceLimitError, match=r"N = about 10\^300 entries .* memory limit"):
        specular_lut(1e300, 1, 1, 6)
    with pytest.raises(ResourceLimitError, match="memory limit"):
        specular_lut(1.7e308, 1.7e308, 1, 6)
    with memory_limit("1K"), pytest.raises(ResourceLimitError, match="N = 255 entries"):
        specular_lut(*TABLE_3_1)  # 2040 bytes
    with memory_limit("4K"):
        assert len(specular_lut(*TABLE_3_1)) == 255


def test_bad_look_up_arguments():
    table = specular_lut(*TABLE_3_3)
    with pytest.raises(TypeError, match="'table' must be a 1-D float64 array"):
        lut_level(list(table), 0.5)
    with pytest.raises(TypeError, match="'table' must be a 1-D float64 array"):
        lut_levels(table.reshape(2, 53), [0.5])
    with pytest.raises(TypeError, match="'cos_phi' must be a real number"):
        lut_level(table, "0.5")
    with pytest.raises(TypeError, match="'start' must be an int level"):
        lut_level_coherent(table, 0.5, 1.0)
    with pytest.raises(ValueError, match=r"'start' must be a level in \[0, N = 106\]"):
        lut_level_coherent(table, 0.5, 107)
    with pytest.raises(ValueError, match=r"'start' must be a level in \[0, N = 106\]"):
        lut_level_coherent(table, 0.5, -1)
    with pytest.raises(ValueError, match="'N' .* must be >= 0"):
        specular_levels_exact(-1, 6, [0.5])
    with pytest.raises(TypeError, match="'N' must be an int"):
        specular_levels_exact(2.5, 6, [0.5])
    with pytest.raises(ValueError, match="'n' .* must be > 0"):
        specular_levels_exact(255, 0, [0.5])

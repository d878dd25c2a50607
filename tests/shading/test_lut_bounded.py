"""Issue 27: a bright light's specular table is estimated, and render bounds it at 255 levels."""

import numpy as np
import pytest

from scanviz.limits import ResourceLimitError, memory_limit
from scanviz.shading import ReflectionModel, specular_lut
from scanviz.shading.lut import lut_levels, specular_levels_exact


def test_a_table_cut_at_top_is_the_whole_tables_first_entries():
    whole = specular_lut(1000, 0.9, 1.5, 7)  # N = 600
    cut = specular_lut(1000, 0.9, 1.5, 7, top=255)
    assert len(whole) == 600 and len(cut) == 255
    assert np.array_equal(cut, whole[:255])  # bit for bit: the same operations per entry
    assert np.array_equal(specular_lut(1000, 0.9, 1.5, 7, top=1000), whole)


def test_a_cut_table_gives_the_level_clipped_at_top():
    cosines = np.linspace(-0.2, 1.1, 2001)
    cut = specular_lut(1000, 0.9, 1.5, 7, top=255)
    expected = np.minimum(specular_levels_exact(600, 7, cosines), 255)
    # the table's (j/N)^(1/n) may round on either side of an exact boundary: the oracle's
    # floor(N c^n) agrees except within rounding of one of the 255 boundaries
    differs = lut_levels(cut, cosines) != expected
    assert differs.sum() <= 2


def test_a_huge_level_count_is_not_refused_when_cut():
    # Ip ks / (r + r0) = 10^600: only its first 255 entries, taken through logarithms
    table = specular_lut(1e300, 1e300, 1, 4, top=255)
    j = np.arange(1, 256)
    assert len(table) == 255 and np.all(np.diff(table) > 0)
    np.testing.assert_allclose(table, np.exp((np.log(j) - 600 * np.log(10)) / 4), rtol=1e-12)


def test_the_whole_table_of_a_bright_light_is_refused_before_it_is_built():
    with memory_limit("64M"), pytest.raises(ResourceLimitError, match="N = 255000000 entries"):
        specular_lut(255e6, 1, 1, 8)


@pytest.mark.parametrize("top", [-1, 2.5, True, "255"])
def test_top_must_be_a_level(top):
    with pytest.raises(ValueError, match="'top' \\(the highest level kept\\) must be an int >= 0"):
        specular_lut(255, 1, 1, 8, top=top)


def test_a_model_cut_at_255_levels_keeps_255_entries():
    model = ReflectionModel(Ip=255e6, ks=1.0, r_plus_r0=1.0, top_level=255)
    assert len(model.table) == 255 and model.specular_scale == 255e6
    assert len(ReflectionModel(Ip=255, ks=0.7, r_plus_r0=1.5, top_level=255).table) == 119


@pytest.mark.parametrize("name", ["b", "y", "alpha", "beta"])
def test_a_gooch_parameter_past_float64_is_refused_in_one_line(name):
    from scanviz.scene.model import Light, Material
    from scanviz.shading import gooch, material_array

    materials = material_array([Material()])
    with pytest.raises(ValueError, match=f"^'{name}' must be finite and >= 0; got <an int of"):
        gooch(np.zeros((1, 3)), [(0.0, 0.0, 1.0)], materials, None, Light(), view_dir=(1, 0, 0),
              **{name: 10**400})  # fmt: skip

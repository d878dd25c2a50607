"""Issue 27's leftovers: a huge int parameter, a masked line end, and a device as segment file."""

import numpy as np
import pytest

from scanviz.antialias.surfaces import read_segments, write_segments
from scanviz.conventions import finite_real
from scanviz.raster.lines import paint_lines


def test_an_int_beyond_any_float_is_refused_in_one_line():
    with pytest.raises(ValueError, match=r"^'ks' must be finite; got <an int of 1329 bits>$"):
        finite_real("ks", 10**400)
    assert finite_real("ks", 10**300) == 1e300


def test_a_masked_line_end_is_refused_not_read():
    masked = np.ma.masked_array([[0, 0, 5, 2]], mask=[[0, 1, 0, 0]])
    with pytest.raises(ValueError, match="'ends' is a masked array with 1 masked value"):
        paint_lines(masked, 6, 3)
    plain = paint_lines(np.ma.masked_array([[0, 0, 5, 2]]), 6, 3)  # nothing masked: its data
    assert np.array_equal(plain, paint_lines([[0, 0, 5, 2]], 6, 3))


def test_segment_files_are_regular_files(tmp_path):
    with pytest.raises(ValueError, match="'/dev/zero' is a character device, not a regular file"):
        read_segments("/dev/zero")
    path = tmp_path / "lines.dat"
    segments = np.array([[[0.5, 1.0], [3.0, 2.25]]])
    write_segments(path, segments)
    assert np.array_equal(read_segments(path), segments)

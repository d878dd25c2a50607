"""Issue 27: ScreenPolygons.from_polygons takes its arrays through the coordinate gate's rules."""

import numpy as np
import pytest

from scanviz.visibility import ScreenPolygons

TRIANGLE = [[0, 0, 1], [4, 0, 1], [0, 4, 1]]


def test_a_masked_vertex_is_refused_not_read():
    masked = np.ma.masked_array(TRIANGLE, mask=[[0, 0, 0], [0, 1, 0], [0, 0, 0]])
    with pytest.raises(ValueError, match="polygon 0 is a masked array with 1 masked value"):
        ScreenPolygons.from_polygons([masked])
    assert ScreenPolygons.from_polygons([np.ma.masked_array(TRIANGLE)]).count == 1  # none masked


def test_times_and_complex_numbers_are_refused():
    for dtype in ("m8[s]", "M8[s]", complex):
        with pytest.raises(TypeError, match="polygon 0 must hold real numbers"):
            ScreenPolygons.from_polygons([np.array(TRIANGLE).astype(dtype)])


@pytest.mark.filterwarnings("ignore::PendingDeprecationWarning")  # numpy's note on np.matrix
def test_a_matrix_is_its_numbers():
    scene = ScreenPolygons.from_polygons([np.matrix(TRIANGLE)], values=[np.matrix([[1], [2], [3]])])
    assert scene.xy.tolist() == [[0, 0], [4, 0], [0, 4]] and scene.values.ravel().tolist() == [
        1,
        2,
        3,
    ]

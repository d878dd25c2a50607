"""Issue 27: the transform functions' gate (`as_points`) undoes ndarray subclasses, refuses the rest."""

import re
import warnings

import numpy as np
import pytest

from scanviz.transform import ndc_from_clip, outcodes, transform_points

CLIP_POINTS = [[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.5, 2.0]]
ENTRIES = {
    "transform_points": (lambda v: transform_points(np.eye(4), v), "'points'"),
    "ndc_from_clip": (ndc_from_clip, "'points'"),
    "outcodes": (outcodes, "'clip_points'"),
}


@pytest.mark.parametrize(("entry", "name"), ENTRIES.values(), ids=ENTRIES.keys())
@pytest.mark.parametrize(
    ("dtype", "shown"),
    [
        ("m8[s]", "timedelta64[s] (timedelta)"),
        ("M8[s]", "datetime64[s] (datetime)"),
        ("complex128", "complex128 (complex)"),
        ("bool", "bool (bool)"),
        ("object", "object (Python objects)"),
        ("U3", "<U3 (str)"),
    ],
)
def test_issue27_points_of_a_non_real_dtype_are_refused(entry, name, dtype, shown):
    points = np.array(CLIP_POINTS).astype(dtype) if dtype[0] not in "mM" else np.ones((3, 4), dtype)
    rule = re.escape(f"{name} must hold real numbers (int or float); got dtype {shown}")
    with pytest.raises(TypeError, match=f"^{rule}$"):
        entry(points)


@pytest.mark.parametrize(("entry", "name"), ENTRIES.values(), ids=ENTRIES.keys())
def test_issue27_masked_points_are_refused_unless_nothing_is_masked(entry, name):
    mask = np.zeros((3, 4), bool)
    mask[1, 2] = True
    with pytest.raises(ValueError, match=f"^{name} is a masked array with 1 masked value; fill"):
        entry(np.ma.masked_array(CLIP_POINTS, mask=mask))
    assert np.array_equal(entry(np.ma.masked_array(CLIP_POINTS)), entry(np.array(CLIP_POINTS)))


@pytest.mark.parametrize(("entry", "name"), ENTRIES.values(), ids=ENTRIES.keys())
def test_issue27_a_matrix_of_points_gives_a_plain_array(entry, name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PendingDeprecationWarning)
        matrix = np.matrix(CLIP_POINTS)
    result = entry(matrix)
    assert type(result) is np.ndarray and np.array_equal(result, entry(np.array(CLIP_POINTS)))

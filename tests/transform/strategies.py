"""Hypothesis strategies for cameras and eye-space points shared by the transform tests."""

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from scanviz.scene import Camera

coordinate = st.floats(-10, 10, allow_nan=False)
vector = st.tuples(coordinate, coordinate, coordinate)


@st.composite
def cameras(draw, projection=None):
    """A valid, well-conditioned camera (view at least 1e-3 long, up at least 1 degree off it)."""
    eye, look_at, up = draw(vector), draw(vector), draw(vector)
    view = np.subtract(look_at, eye)
    assume(np.linalg.norm(view) > 1e-3 and np.linalg.norm(up) > 1e-3)
    sine = np.linalg.norm(np.cross(view, up)) / (np.linalg.norm(view) * np.linalg.norm(up))
    assume(sine > np.sin(np.radians(1)))
    left, bottom = draw(st.floats(-3, 2.9)), draw(st.floats(-3, 2.9))
    right, top = draw(st.floats(left + 0.1, 3)), draw(st.floats(bottom + 0.1, 3))
    near = draw(st.floats(0.05, 5))
    far = near + draw(st.floats(0.5, 100))
    return Camera(
        eye=eye,
        look_at=look_at,
        up=up,
        window=(left, right, bottom, top),
        near=near,
        far=far,
        projection=projection or draw(st.sampled_from(["perspective", "orthographic"])),
    )

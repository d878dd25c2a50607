"""The fast Phong stepper, headless: built from real traces, stepped sample by sample."""

import re

import matplotlib
import numpy as np
import pytest

from scanviz.shading import ReflectionModel, exact_phong_triangle, fast_phong_triangle
from scanviz.widgets import FastPhongView, fast_phong_stepper
from scanviz.widgets._common import fmt
from scanviz.widgets.fast_phong import DIGITS, UNSHADED

matplotlib.use("Agg")

MODEL = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.75, 0.55, 0.3), ks=0.7, n=32, r_plus_r0=1.5)
TO_LIGHT, TO_VIEWER = (-0.3, 0.4, 1.0), (0.0, 0.0, 1.0)
SIZE = 24


def sphere_triangle(vertices, radius=40.0, centre=(13.0, 1.0)):
    """Vertices and their normals on a sphere: normals that splay, a highlight inside."""
    vertices = np.asarray(vertices, float)
    offsets = (vertices - centre) / radius
    return vertices, np.column_stack([offsets, np.sqrt(1 - (offsets**2).sum(axis=1))])


SMALL = sphere_triangle([(3.3, 3.2), (12.7, 5.1), (6.6, 12.4)])  # about 45 samples


def stepper_for(triangle=SMALL, **options):
    return fast_phong_stepper(
        *triangle, TO_LIGHT, TO_VIEWER, MODEL, width=SIZE, height=SIZE, **options
    )


def compiled(triangle=SMALL, **options):
    return fast_phong_triangle(
        *triangle, TO_LIGHT, TO_VIEWER, MODEL, width=SIZE, height=SIZE, **options
    )


def exact_colors(triangle=SMALL, **options):
    exact = exact_phong_triangle(
        *triangle, TO_LIGHT, TO_VIEWER, MODEL, width=SIZE, height=SIZE, **options
    )
    return {(int(x), int(y)): c for x, y, c in zip(exact.xs, exact.ys, exact.colors, strict=True)}


def test_each_step_shows_its_pixel_and_its_values():
    stepper = stepper_for()
    view = stepper.views[0]
    exact = exact_colors()
    assert isinstance(view, FastPhongView) and stepper.slider.max == len(view.steps) > 20
    seen_direct = seen_stepped = 0
    for step, pixel in enumerate(view.steps, 1):
        stepper.slider.value = step
        text = view.text.value
        assert all(p.get_visible() and p.get_xy() == (pixel.x, pixel.y) for p in view.pixel_patches)
        assert f"sample {step} of {len(view.steps)}</b>: pixel ({pixel.x}, {pixel.y})" in text
        for value in (pixel.cos_theta, pixel.cos_theta_step, pixel.cos_specular):
            assert fmt(value, DIGITS) in text
        for value in (*pixel.ambient_diffuse, pixel.cos_specular_step, *pixel.color):
            assert fmt(value, DIGITS) in text
        assert f"table level {pixel.level}</b>" in text
        assert f"{pixel.comparisons} comparison" in text
        assert ("<b>lit</b>" if pixel.lit else "<b>unlit</b>") in text
        assert fmt(tuple(exact[pixel.x, pixel.y]), DIGITS) in text
        difference = np.abs(np.array(pixel.color) - exact[pixel.x, pixel.y])
        assert f"(max {fmt(difference.max(), DIGITS)})" in text
        if pixel.direct:
            seen_direct += 1
            assert "<b>direct</b>" in text and "binary search at the span's start" in text
        else:
            seen_stepped += 1
            previous = view.steps[step - 2]
            assert (previous.x + 1, previous.y) == (pixel.x, pixel.y)
            assert pixel.cos_theta == previous.cos_theta + previous.cos_theta_step
            assert f"<b>stepped</b> from pixel ({previous.x}, {previous.y})" in text
            assert "Q = Q_prev + dQ_prev" in text
            sign = "−" if previous.cos_theta_step < 0 else "+"
            shown = abs(previous.cos_theta_step)
            assert f"{fmt(previous.cos_theta, DIGITS)} {sign} {fmt(shown, DIGITS)}" in text
            assert f"coherent step from the previous level {previous.level}" in text
    rows = len({p.y for p in view.steps})
    assert seen_direct == rows and seen_stepped == len(view.steps) - rows  # one span per row


@pytest.mark.parametrize(
    "options",
    [{}, {"expansion": "centroid"}, {"sample": "center"}, {"subpixel_bits": None}],
    ids=["vertex", "centroid", "center", "unsnapped"],
)
def test_the_last_step_shows_the_compiled_image_and_the_error_against_exact(options):
    stepper = stepper_for(**options)
    view = stepper.views[0]
    shaded = compiled(**options)
    exact = exact_colors(**{k: v for k, v in options.items() if k != "expansion"})
    stepper.slider.value = stepper.slider.max
    picture, error = view.picture.get_array(), view.error_image.get_array().filled(np.nan)
    np.testing.assert_array_equal(picture[shaded.ys, shaded.xs], shaded.colors / 255)
    expected = [
        np.abs(c - exact[x, y]).max()
        for x, y, c in zip(shaded.xs, shaded.ys, shaded.colors, strict=True)
    ]
    np.testing.assert_array_equal(error[shaded.ys, shaded.xs], expected)
    covered = np.zeros((SIZE, SIZE), bool)
    covered[shaded.ys, shaded.xs] = True
    assert (picture[~covered] == 1.0).all() and np.isnan(error[~covered]).all()
    stepper.slider.value = 0  # back to the start: nothing shaded, every covered sample waiting
    assert (view.picture.get_array()[covered] == UNSHADED).all()
    assert np.isnan(view.error_image.get_array().filled(np.nan)).all()
    assert not any(p.get_visible() for p in view.pixel_patches)


def test_first_and_last_step_controls_and_text():
    stepper = stepper_for()
    view, count = stepper.views[0], len(stepper.views[0].steps)
    assert stepper.prev_button.disabled and not stepper.next_button.disabled
    assert stepper.label.value == f"step 0 / {count}: start"
    assert f"start: {count} samples to shade" in view.text.value
    stepper.next_button.click()
    assert view.step == 1 and view.steps[0].direct and "<b>direct</b>" in view.text.value
    stepper.slider.value = count
    assert stepper.next_button.disabled and not stepper.prev_button.disabled
    assert stepper.label.value == f"step {count} / {count}: fast_phong_pixel"
    assert f"sample {count} of {count}" in view.text.value
    stepper.prev_button.click()
    assert view.step == count - 1


def test_the_coefficients_are_shown_once_from_the_setup():
    view = stepper_for(expansion="centroid").views[0]
    setup = view.setup
    table = view.coefficients.value
    assert "about the centroid" in table
    for quadratic in (setup.cos_theta, setup.cos_specular, *setup.ambient_diffuse):
        for coefficient in quadratic:
            assert fmt(coefficient, 5) in table
    snapped = np.array(setup.vertices)
    np.testing.assert_allclose(setup.origin, snapped.mean(axis=0))
    (star,) = [line for line in view.axes[0].lines if line.get_marker() == "*"]
    assert (star.get_xdata()[0], star.get_ydata()[0]) == setup.origin


def test_blinn_names_the_half_vector_cosine():
    model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=0.6, ks=0.7, n=32, r_plus_r0=1.5,
                            specular="blinn")  # fmt: skip
    stepper = fast_phong_stepper(*SMALL, TO_LIGHT, TO_VIEWER, model, width=SIZE, height=SIZE)
    stepper.slider.value = 1
    text = stepper.views[0].text.value  # the values table's rows; the table keeps cos φ_j
    assert "'>N·H</td>" in text and "'>cos φ</td>" not in text


def test_the_position_from_the_expansion_point_is_shown():
    stepper = stepper_for(sample="center")
    view = stepper.views[0]
    stepper.slider.value = 5
    pixel, (ox, oy) = view.steps[4], view.setup.origin
    x, y = pixel.x + 0.5 - ox, pixel.y + 0.5 - oy
    assert (
        f"at x = {fmt(x, DIGITS)}, y = {fmt(y, DIGITS)} from the expansion point" in view.text.value
    )


def test_a_triangle_off_the_raster_shows_the_whole_raster_and_nothing_to_step():
    stepper = fast_phong_stepper(
        [(100, 100), (120, 100), (100, 130)],
        *SMALL[1:],
        TO_LIGHT,
        TO_VIEWER,
        MODEL,
        width=10,
        height=8,
    )
    view = stepper.views[0]
    assert (
        view.setup is not None and stepper.slider.max == 0 and "nothing to step" in view.text.value
    )
    assert view.axes[0].get_xlim() == (0, 10) and view.axes[0].get_ylim() == (0, 8)


BAD = [
    ({"vertices": [(0, 0), (4, 0)]}, "vertices"),
    ({"vertices": [(0, 0), (4, np.nan), (0, 4)]}, "vertices"),
    ({"normals": [(0, 0, 1), (0, 0, 1)]}, "normals"),
    ({"normals": [(0, 0, 1), (0, 0, 1), (0, np.inf, 1)]}, "normals"),
    ({"to_light": (0, 0, 0)}, "to_light"),
    ({"to_viewer": "up"}, "to_viewer"),
    ({"model": "phong"}, "model"),
    ({"expansion": "corner"}, "expansion"),
    ({"sample": "middle"}, "sample"),
    ({"width": -1}, "width"),
    ({"height": 2.5}, "height"),
    ({"subpixel_bits": 17}, "subpixel_bits"),
]


@pytest.mark.parametrize(("bad", "name"), BAD, ids=[f"{n}-{i}" for i, (_, n) in enumerate(BAD)])
def test_bad_input_raises_what_fast_phong_triangle_raises(bad, name):
    arguments = {
        "vertices": [(1, 1), (9, 2), (3, 8)],
        "normals": [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)],
        "to_light": TO_LIGHT,
        "to_viewer": TO_VIEWER,
        "model": MODEL,
        "width": 10,
        "height": 10,
        **bad,
    }
    with pytest.raises((TypeError, ValueError)) as expected:
        fast_phong_triangle(**arguments)
    assert name in str(expected.value)
    with pytest.raises(expected.type, match=re.escape(str(expected.value))):
        fast_phong_stepper(**arguments)


@pytest.mark.parametrize(
    "vertices",
    [[(1, 1), (5, 3), (9, 5)], [(2, 2), (2, 2), (6, 7)], [(3.2, 3.2), (3.7, 3.2), (3.2, 3.7)]],
    ids=["collinear", "repeated vertex", "covers no sample"],
)
@pytest.mark.parametrize("size", [(10, 10), (0, 10), (0, 0)], ids=["10x10", "0x10", "0x0"])
def test_a_triangle_with_no_samples_says_nothing_to_step(vertices, size):
    normals = [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)]
    stepper = fast_phong_stepper(
        vertices, normals, TO_LIGHT, TO_VIEWER, MODEL, width=size[0], height=size[1]
    )
    view = stepper.views[0]
    assert len(view.steps) == 0 and stepper.slider.max == 0
    assert stepper.next_button.disabled and stepper.prev_button.disabled
    assert "nothing to step" in view.text.value
    assert (view.picture.get_array() == 1.0).all()  # nothing covered

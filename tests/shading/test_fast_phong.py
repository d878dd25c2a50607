"""Fast Phong over one triangle: the normal plane, the exact forms, the Taylor coefficients
(against sympy), forward differencing, the shaded samples, traced == compiled, N·H vs R·V."""

import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.raster import triangle_samples
from scanviz.scene.model import Light, Material
from scanviz.shading import illuminate, material_array
from scanviz.shading.fast_phong import (
    ReflectionModel,
    channel_quadratics,
    evaluate_quadratic,
    exact_phong_triangle,
    fast_phong_triangle,
    forward_differences,
    half_angle_gap,
    halfway_vector,
    normal_plane,
    rational_forms,
    taylor_coefficients,
)
from scanviz.shading.lut import lut_levels, specular_levels_exact
from scanviz.shading.taylor import _phi_series, _theta_series
from scanviz.trace import Recorder, Trace
from scanviz.trace.events import FastPhongPixel, FastPhongSetup

UNIT_ROUNDOFF = 2.0**-53
MONOMIALS = ("x**2", "x*y", "y**2", "x", "y", "1")


def random_triangle(seed: int, size: float = 30.0, tilt: float = 0.4):
    """A well-shaped triangle about size x size pixels, unit normals tilted up to `tilt` from +z,
    and the directions L and V."""
    rng = np.random.default_rng(seed)
    shape = np.array([(0, 0), (1, 0), (0, 1)]) + rng.uniform(-0.2, 0.2, (3, 2))
    vertices = rng.uniform(0, 2, 2) + size * shape
    normals = np.column_stack([rng.uniform(-tilt, tilt, (3, 2)), np.ones(3)])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    to_light = np.array([*rng.uniform(-0.6, 0.6, 2), 1.0])
    to_viewer = np.array([*rng.uniform(-0.3, 0.3, 2), 1.0])
    return vertices, normals, to_light, to_viewer


def forms_of(seed: int, origin: str = "vertex"):
    vertices, normals, to_light, to_viewer = random_triangle(seed)
    point = vertices[0] if origin == "vertex" else vertices.mean(axis=0)
    plane = normal_plane(vertices, normals, point)
    return plane, to_light, to_viewer, rational_forms(plane, to_light, to_viewer)


# --- the normal plane (§2.2, golden check 11) ---------------------------------------------


def test_normal_plane_of_a_small_literal_triangle():
    a, b, c = normal_plane([(1, 1), (5, 1), (1, 3)], [(0, 0, 1), (2, 0, 1), (0, 1, 1)], (1, 1))
    assert a.tolist() == [0.5, 0.0, 0.0] and b.tolist() == [0.0, 0.5, 0.0]
    assert c.tolist() == [0.0, 0.0, 1.0]


@pytest.mark.parametrize("seed", range(20))
@pytest.mark.parametrize("origin", ["vertex", "centroid"])
def test_normal_plane_gives_the_vertex_normals_at_the_vertices(seed, origin):
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-50, 50, (3, 2))
    normals = rng.normal(size=(3, 3))
    point = xy[0] if origin == "vertex" else xy.mean(axis=0)
    a, b, c = normal_plane(xy, normals, point)
    for vertex, normal in zip(xy, normals, strict=True):
        x, y = vertex - point
        np.testing.assert_allclose(a * x + b * y + c, normal, rtol=0, atol=1e-12)
    if origin == "vertex":
        assert c.tolist() == normals[0].tolist()  # C = Nu exactly


def test_normal_plane_refuses_a_zero_area_triangle():
    with pytest.raises(ValueError, match="'xy' must span a triangle of nonzero area"):
        normal_plane([(0, 0), (1, 1), (2, 2)], np.eye(3), (0, 0))


@pytest.mark.parametrize(
    ("normals", "message"),
    [(np.eye(2), r"'normals' must be a \(3, 3\) array"), ([[np.nan] * 3] * 3, "finite")],
)
def test_normal_plane_refuses_bad_normals(normals, message):
    with pytest.raises(ValueError, match=message):
        normal_plane([(0, 0), (1, 0), (0, 1)], normals, (0, 0))


# --- the exact rational forms (§2.3) ------------------------------------------------------


@pytest.mark.parametrize("seed", range(10))
def test_rational_forms_equal_direct_vector_evaluation(seed):
    (a, b, c), to_light, to_viewer, forms = forms_of(seed, "centroid")
    rng = np.random.default_rng(100 + seed)
    x, y = rng.uniform(-20, 20, (2, 50))
    normal = a * x[:, None] + b * y[:, None] + c
    unit = normal / np.linalg.norm(normal, axis=1, keepdims=True)
    light, viewer = to_light / np.linalg.norm(to_light), to_viewer / np.linalg.norm(to_viewer)
    cos_theta = unit @ light
    reflected = 2 * cos_theta[:, None] * unit - light
    halfway = (light + viewer) / np.linalg.norm(light + viewer)
    np.testing.assert_allclose(forms.cos_theta(x, y), cos_theta, rtol=0, atol=1e-13)
    np.testing.assert_allclose(forms.cos_phi(x, y), reflected @ viewer, rtol=0, atol=1e-13)
    np.testing.assert_allclose(forms.n_dot_h(x, y), unit @ halfway, rtol=0, atol=1e-13)
    np.testing.assert_allclose(forms.norm_squared(x, y), (normal**2).sum(axis=1), rtol=1e-13)


def test_rational_forms_of_opposite_light_and_viewer_have_no_halfway_terms():
    forms = rational_forms(([0.1, 0, 0], [0, 0.1, 0], [0, 0, 1]), (0, 0, 1), (0, 0, -1))
    assert (forms.ha, forms.hb, forms.hc) == (0.0, 0.0, 0.0)
    assert forms.k_lv == -1.0


# --- Taylor coefficients against sympy (§2.4, golden check 10) -----------------------------


def sympy_quadratic(expression, x, y):
    """The second-order Taylor polynomial of `expression` at x = y = 0, as the 6 coefficients."""
    t = sp.Symbol("t")
    scaled = expression.subs({x: t * x, y: t * y}, simultaneous=True)
    series = sp.series(scaled, t, 0, 3).removeO().subs(t, 1)
    poly = sp.Poly(sp.expand(series), x, y)
    return [poly.coeff_monomial(sp.sympify(m, locals={"x": x, "y": y})) for m in MONOMIALS]


def sympy_derivatives(expression, x, y):
    """The same coefficients from derivatives at 0 (f_xx/2, f_xy, f_yy/2, f_x, f_y, f): faster."""

    def at_origin(e):
        return e.subs({x: 0, y: 0})

    fx, fy = sp.diff(expression, x), sp.diff(expression, y)
    second = [sp.diff(fx, x) / 2, sp.diff(fx, y), sp.diff(fy, y) / 2]
    return [float(sp.N(at_origin(e), 30)) for e in (*second, fx, fy, expression)]


def test_taylor_formulas_are_the_symbolic_series_of_the_exact_forms():
    a, b, c, d, e, f, g, h, l, m, o, p, q, w, k = sp.symbols(  # noqa: E741
        "a b c d e f g h l m o p q w k_lv", real=True
    )
    i = sp.Symbol("i", positive=True)
    x, y = sp.symbols("x y", real=True)
    norm_squared = d * x**2 + e * x * y + f * y**2 + g * x + h * y + i
    cos_theta = (a * x + b * y + c) / sp.sqrt(norm_squared)
    cos_phi = (l * x**2 + m * x * y + o * y**2 + p * x + q * y + w) / norm_squared - k
    theta = _theta_series(a, b, c, d, e, f, g, h, i, sp.sqrt(i))
    phi = _phi_series(l, m, o, p, q, w, d, e, f, g, h, i, k)
    for series, code in [
        (sympy_quadratic(cos_theta, x, y), theta),
        (sympy_quadratic(cos_phi, x, y), phi),
    ]:
        assert [sp.simplify(s - formula) for s, formula in zip(series, code, strict=True)] == [
            0
        ] * 6


def test_taylor_formulas_match_the_spec_as_printed():
    # §2.4: T5 = (3cg² - 4cdi - 4agi) / (8 i² √i) and T55 = (l i² - d w i - g p i + g² w) / i³
    values = dict(a=0.3, b=-0.2, c=0.9, d=0.01, e=0.004, f=0.02, g=0.1, h=-0.05, i=1.3)
    a, b, c, d, e, f, g, h, i = values.values()
    t5 = _theta_series(*values.values(), math.sqrt(i))[0]
    assert t5 == pytest.approx((3 * c * g**2 - 4 * c * d * i - 4 * a * g * i) / (8 * i**2 * i**0.5))
    l, m, o, p, q, w = 0.5, 0.1, -0.3, 0.2, 0.4, 1.1  # noqa: E741
    t55 = _phi_series(l, m, o, p, q, w, d, e, f, g, h, i, 0.7)[0]
    assert t55 == pytest.approx((l * i**2 - d * w * i - g * p * i + g**2 * w) / i**3)


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("origin", ["vertex", "centroid"])
def test_taylor_coefficients_match_sympy_on_random_triangles(seed, origin):
    """The whole chain (plane, forms, coefficients) against sympy's series of the vectors' formula."""
    (a, b, c), to_light, to_viewer, forms = forms_of(seed, origin)
    series = taylor_coefficients(forms)
    x, y = sp.symbols("x y", real=True)

    def vector(v):
        return sp.Matrix([sp.Rational(float(u)) for u in v])

    normal = vector(a) * x + vector(b) * y + vector(c)
    light = vector(to_light) / sp.sqrt(vector(to_light).dot(vector(to_light)))
    viewer = vector(to_viewer) / sp.sqrt(vector(to_viewer).dot(vector(to_viewer)))
    halfway = (light + viewer) / sp.sqrt((light + viewer).dot(light + viewer))
    length = sp.sqrt(normal.dot(normal))
    exact = {
        "cos_theta": normal.dot(light) / length,
        "cos_phi": 2 * normal.dot(light) * normal.dot(viewer) / length**2 - light.dot(viewer),
        "n_dot_h": normal.dot(halfway) / length,
    }
    for name, expression in exact.items():
        expected = sympy_derivatives(expression, x, y)
        np.testing.assert_allclose(getattr(series, name), expected, rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize("seed", range(5))
def test_taylor_error_is_third_order(seed):
    """Halving the distance from the expansion point divides the error by about 8."""
    _, _, _, forms = forms_of(seed)
    series = taylor_coefficients(forms)
    direction = np.array([0.6, 0.8])
    for name in ("cos_theta", "cos_phi", "n_dot_h"):
        errors = [
            abs(
                float(evaluate_quadratic(getattr(series, name), *(r * direction)))
                - float(getattr(forms, name)(*(r * direction)))
            )
            for r in (0.4, 0.2)
        ]
        assert 4 < errors[0] / errors[1] < 16, (name, errors)


def test_taylor_coefficients_need_a_normal_at_the_expansion_point():
    forms = rational_forms(([1, 0, 0], [0, 1, 0], [0, 0, 0]), (0, 0, 1), (0, 0, 1))
    with pytest.raises(ValueError, match=r"normal at the expansion point is zero \(i = 0\)"):
        taylor_coefficients(forms)


# --- ambient + diffuse as one quadratic per channel (§2.6) --------------------------------


def test_channel_quadratics_fold_ambient_into_the_constant_term():
    model = ReflectionModel(Ia=(100, 50, 0), ka=(0.2, 0.4, 1), Ip=200, kd=(1, 0.5, 0), r_plus_r0=2)
    terms = [0.01, -0.02, 0.03, 0.5, -0.25, 0.8]
    expected = np.array(
        [
            [1, -2, 3, 50, -25, 80 + 20],  # kk = 200 * 1 / 2 = 100; Ia ka = 20
            [0.5, -1, 1.5, 25, -12.5, 40 + 20],  # kk = 50; Ia ka = 20
            [0, 0, 0, 0, 0, 0],  # kk = 0; Ia ka = 0
        ]
    )
    np.testing.assert_allclose(channel_quadratics(terms, model), expected, rtol=1e-15)


# --- forward differencing (§2.5) ----------------------------------------------------------


def difference_bound(coefficients, x, y, k):
    """First-order rounding bound of stepped minus direct, k steps into a span (module docs).

    S bounds every |term| sum the stepping adds (Q's and dQ's along the span): the direct
    start errs by <= 7uS, each dQ step by uS, each Q step by uS plus dQ's error so far.
    """
    t5, t4, t3, t2, t1, t0 = np.abs(coefficients)
    ax, ay = np.abs(x), np.abs(y)
    q_terms = t5 * ax * ax + t4 * ax * ay + t3 * ay * ay + t2 * ax + t1 * ay + t0
    dq_terms = t5 * (2 * ax + 1) + t4 * ay + t2
    s = max(q_terms.max(), dq_terms.max())
    return UNIT_ROUNDOFF * s * (k * k + 5 * k + 16)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    length=st.integers(1, 300),
    scale=st.sampled_from([1e-6, 1e-3, 1.0, 1e3]),
)
def test_forward_differences_equal_direct_evaluation_to_rounding(seed, length, scale):
    rng = np.random.default_rng(seed)
    coefficients = rng.uniform(-1, 1, 6) * np.array([scale, scale, scale, 1, 1, 1])
    origin = rng.uniform(-50, 50, 2)
    row, first = rng.integers(-40, 40), rng.integers(-60, 60)
    xs = np.arange(first, first + length)
    ys = np.full(length, row)
    values, steps = forward_differences([coefficients], ys, xs, origin)
    x, y = xs - origin[0], ys - origin[1]
    direct = evaluate_quadratic(coefficients, x, y)
    assert values[0, 0] == direct[0]  # the span's first sample is evaluated directly
    k = np.arange(length)
    assert (np.abs(values[:, 0] - direct) <= difference_bound(coefficients, x, y, k)).all()
    next_direct = evaluate_quadratic(coefficients, x + 1, y)
    bound = difference_bound(coefficients, x + 1, y, k + 1)
    assert (np.abs(values[:, 0] + steps[:, 0] - next_direct) <= bound).all()


def test_forward_differences_restart_on_every_row_and_gap():
    xs, ys = np.array([0, 1, 2, 5, 6, 0, 1]), np.array([0, 0, 0, 0, 0, 1, 1])
    values, _ = forward_differences([[1, 1, 1, 1, 1, 1]], ys, xs, (0.0, 0.0))
    x, y = xs.astype(float), ys.astype(float)
    assert values[:, 0].tolist() == (x * x + x * y + y * y + x + y + 1).tolist()


# --- one shaded triangle ------------------------------------------------------------------


MODEL = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.7, 0.5, 0.2), ks=0.7, n=8, r_plus_r0=1.5)


def shade(seed, size=30.0, model=MODEL, raster=64, tilt=0.4, **options):
    vertices, normals, to_light, to_viewer = random_triangle(seed, size, tilt)
    arguments = (vertices, normals, to_light, to_viewer, model)
    fast = fast_phong_triangle(*arguments, width=raster, height=raster, **options)
    options.pop("expansion", None)
    options.pop("trace", None)
    exact = exact_phong_triangle(*arguments, width=raster, height=raster, **options)
    return fast, exact


def test_shaded_samples_are_the_triangle_samples():
    vertices, normals, to_light, to_viewer = random_triangle(3)
    fast, exact = shade(3)
    covered = triangle_samples(vertices, 64, 64)
    for shaded in (fast, exact):
        assert shaded.ys.tolist() == covered.ys.tolist()
        assert shaded.xs.tolist() == covered.xs.tolist()
        assert shaded.colors.shape == (len(covered.xs), 3)


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("specular", ["phong", "blinn"])
@pytest.mark.parametrize("sample", ["corner", "center"])
def test_fast_phong_is_close_to_exact_on_a_small_triangle(seed, specular, sample):
    """A 4-pixel triangle, normals 0.1 apart: the Taylor error is tiny, the table floors the
    highlight by less than 1 + frac(Isr) levels."""
    model = ReflectionModel(kd=(0.7, 0.5, 0.2), ks=0.7, n=8, specular=specular)
    fast, exact = shade(
        seed, size=4.0, model=model, raster=8, tilt=0.1, expansion="centroid", sample=sample
    )
    assert len(fast.xs) > 0
    np.testing.assert_allclose(fast.cos_theta, exact.cos_theta, atol=2e-3)
    np.testing.assert_allclose(fast.cos_specular, exact.cos_specular, atol=2e-3)
    floor_loss = 1 + model.specular_scale - len(model.table)
    assert np.abs(fast.colors - exact.colors).max() < floor_loss + 0.1


@pytest.mark.parametrize("seed", range(4))
def test_specular_level_is_the_table_index_of_the_stepped_cosine(seed):
    model = ReflectionModel(n=4)
    fast, _ = shade(seed, model=model)
    lit = fast.cos_theta > 0
    levels = lut_levels(model.table, fast.cos_specular)
    assert fast.highlight[lit].tolist() == levels[lit].astype(float).tolist()
    assert (fast.highlight[~lit] == 0).all()
    # away from float ties the table is floor(N cos^n φ)
    oracle = specular_levels_exact(len(model.table), 4, fast.cos_specular)
    assert (np.abs(levels - oracle) <= 1).all()


def test_exact_phong_equals_illuminate():
    """exact_phong_triangle is `illuminate` (directional light, orthographic viewer) in levels."""
    color = (1.0, 0.6, 0.3)
    material = Material(color=color, ambient=0.2, diffuse=0.6, specular=0.4, exponent=10)
    ka, kd = np.multiply(0.2, color), np.multiply(0.6, color)
    vertices, normals, to_light, to_viewer = random_triangle(7)
    covered = triangle_samples(vertices, 64, 64)
    interpolated = covered.barycentric @ normals  # an independent interpolation of N
    reference = 255 * illuminate(
        np.zeros((len(covered.xs), 3)),
        interpolated,
        material_array([material] * len(covered.xs)),
        None,
        [Light(direction=tuple(-to_light))],
        (1, 1, 1),
        view_dir=to_viewer,
    )
    for specular in ("phong", "blinn"):
        model = ReflectionModel(
            Ia=255, ka=ka, Ip=255, kd=kd, ks=0.4, n=10, r_plus_r0=1, specular=specular
        )
        exact = exact_phong_triangle(
            vertices, normals, to_light, to_viewer, model, width=64, height=64
        )
        error = np.abs(exact.colors - reference).max()
        assert error < 1e-9 if specular == "phong" else error > 1  # Blinn: another highlight
    unit = interpolated / np.linalg.norm(interpolated, axis=1, keepdims=True)
    halfway = halfway_vector(to_light, to_viewer)
    np.testing.assert_allclose(exact.cos_specular, unit @ halfway, rtol=0, atol=1e-12)


# --- traced == compiled, and the trace -----------------------------------------------------


@settings(max_examples=12, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    size=st.sampled_from([3.0, 12.0, 40.0]),
    specular=st.sampled_from(["phong", "blinn"]),
    expansion=st.sampled_from(["vertex", "centroid"]),
    sample=st.sampled_from(["corner", "center"]),
)
def test_traced_equals_compiled(seed, size, specular, expansion, sample):
    model = ReflectionModel(kd=(0.9, 0.4, 0.1), n=16, specular=specular)
    vertices, normals, to_light, to_viewer = random_triangle(seed, size, tilt=0.8)
    arguments = (vertices, normals, to_light, to_viewer, model)
    options = dict(width=48, height=48, expansion=expansion, sample=sample)
    compiled = fast_phong_triangle(*arguments, **options)
    traced = fast_phong_triangle(*arguments, **options, trace=True)
    assert compiled.trace is None
    for name in ("ys", "xs", "colors", "cos_theta", "cos_specular", "highlight"):
        assert np.array_equal(getattr(compiled, name), getattr(traced, name)), name
    pixels = traced.trace.of_kind("fast_phong_pixel")
    assert [(e.x, e.y) for e in pixels] == list(
        zip(compiled.xs.tolist(), compiled.ys.tolist(), strict=True)
    )
    assert [e.color for e in pixels] == [tuple(c) for c in compiled.colors.tolist()]


def test_trace_records_the_coefficients_and_every_step():
    vertices, normals, to_light, to_viewer = random_triangle(11)
    recorder = Recorder(kinds=["fast_phong_setup", "fast_phong_pixel"])
    shaded = fast_phong_triangle(
        vertices, normals, to_light, to_viewer, MODEL, width=64, height=64, trace=recorder,
        polygon=3,
    )  # fmt: skip
    trace = shaded.trace
    setup, pixels = trace[0], trace[1:]
    assert isinstance(setup, FastPhongSetup) and setup.polygon == 3
    assert all(isinstance(e, FastPhongPixel) for e in pixels) and len(pixels) == len(shaded.xs)
    plane = normal_plane(setup.vertices, normals, setup.origin)
    series = taylor_coefficients(rational_forms(plane, to_light, to_viewer))
    assert setup.cos_theta == series.cos_theta and setup.cos_specular == series.cos_phi
    assert setup.table == tuple(MODEL.table.tolist())
    for before, after in zip(pixels[:-1], pixels[1:], strict=True):
        if not after.direct:  # two additions: Q + dQ, dQ + 2 T5
            assert after.x == before.x + 1 and after.y == before.y
            assert after.cos_theta == before.cos_theta + before.cos_theta_step
            assert after.cos_theta_step == before.cos_theta_step + 2 * setup.cos_theta[0]
        else:
            assert after.y != before.y
    assert all(e.comparisons <= 9 for e in pixels if e.direct)  # a binary search of N = 119
    assert Trace.from_json(trace.to_json()) == trace


# --- degenerate and bad input -------------------------------------------------------------


def test_zero_area_triangles_cover_nothing():
    for vertices in ([(0, 0), (4, 4), (8, 8)], [(1, 1), (1, 1), (5, 2)]):
        shaded = fast_phong_triangle(
            vertices, np.eye(3), (0, 0, 1), (0, 0, 1), MODEL, width=10, height=10, trace=True
        )
        assert len(shaded.xs) == 0 and shaded.colors.shape == (0, 3)
        assert not shaded.trace.of_kind("fast_phong_setup")


def test_a_zero_normal_at_the_expansion_point_gives_ambient_light_only():
    normals = [(0, 0, 0), (0, 0, 1), (0, 0, 1)]
    shaded = fast_phong_triangle(
        [(0, 0), (6, 0), (0, 6)], normals, (0, 0, 1), (0, 0, 1), MODEL, width=8, height=8
    )
    assert len(shaded.xs) > 0
    assert (shaded.colors == 25.5).all() and (shaded.highlight == 0).all()


@pytest.mark.parametrize(
    ("parameters", "error", "message"),
    [
        (dict(n=0), ValueError, "'n' .* must be > 0"),
        (dict(ks=-0.1), ValueError, "'ks' .* must be >= 0"),
        (dict(r_plus_r0=0.5), ValueError, "'r_plus_r0' .* must be >= 1"),
        (dict(Ip=0), ValueError, "'Ip' .* must be > 0"),
        (dict(Ia=-1), ValueError, "'Ia' must be finite and >= 0"),
        (dict(kd=(1, 2)), TypeError, "'kd' must be a number or 3 numbers"),
        (dict(ka=math.nan), ValueError, "'ka' must be finite"),
        (dict(n="8"), TypeError, "'n' must be a real number"),
        (dict(specular="torrance"), ValueError, "'specular' must be one of 'phong', 'blinn'"),
    ],
)
def test_reflection_model_refuses_bad_parameters(parameters, error, message):
    with pytest.raises(error, match=message):
        ReflectionModel(**parameters)


@pytest.mark.parametrize(
    ("change", "error", "message"),
    [
        (dict(to_light=(0, 0, 0)), ValueError, "'to_light' must be a nonzero direction"),
        (dict(to_viewer=(0, 1)), ValueError, r"'to_viewer' must have shape \(3,\)"),
        (dict(expansion="middle"), ValueError, "'expansion' must be one of 'vertex', 'centroid'"),
        (dict(model=Material()), TypeError, "'model' must be a ReflectionModel"),
        (dict(vertices=[(0, 0), (1, 0)]), ValueError, "'vertices'"),
        (dict(normals=np.ones((3, 2))), ValueError, r"'normals' must be a \(3, 3\) array"),
        (
            dict(to_viewer=(0, 0, -1), model=ReflectionModel(specular="blinn")),
            ValueError,
            "must not be opposite",
        ),
    ],
)
def test_fast_phong_triangle_refuses_bad_input(change, error, message):
    arguments = dict(
        vertices=[(0, 0), (5, 0), (0, 5)],
        normals=[(0, 0, 1)] * 3,
        to_light=(0, 0, 1),
        to_viewer=(0, 0, 1),
        model=MODEL,
    )
    arguments.update(change)
    with pytest.raises(error, match=message):
        fast_phong_triangle(**arguments, width=8, height=8)


# --- N·H against R·V (§2.8) ---------------------------------------------------------------


@settings(max_examples=30, deadline=None)
@given(
    normal_angle=st.floats(-1.2, 1.2),
    light_angle=st.floats(-1.2, 1.2),
    viewer_angle=st.floats(-1.2, 1.2),
    plane_angle=st.floats(0, math.pi),
)
def test_n_dot_h_is_cos_half_phi_when_coplanar(
    normal_angle, light_angle, viewer_angle, plane_angle
):
    """N, L, V in one plane (any plane through +z): N·H = cos(φ/2) whenever R·V >= -1 + margin."""
    axis = np.array([math.cos(plane_angle), math.sin(plane_angle), 0.0])

    def direction(angle):
        return math.sin(angle) * axis + math.cos(angle) * np.array([0.0, 0.0, 1.0])

    light, viewer = direction(light_angle), direction(viewer_angle)
    if abs(light_angle - viewer_angle) > 2.5:  # nearly opposite L and V: no usable H
        return
    n_dot_h, cos_half_phi = half_angle_gap(direction(normal_angle), light, viewer)
    # φ/2 = |normal_angle - (light_angle + viewer_angle)/2| while that is at most π/2
    if abs(normal_angle - (light_angle + viewer_angle) / 2) <= math.pi / 2 - 0.01:
        assert n_dot_h == pytest.approx(cos_half_phi, abs=1e-12)


@pytest.mark.parametrize("seed", range(10))
def test_n_dot_h_falls_short_of_cos_half_phi_by_the_out_of_plane_part(seed):
    """cos²(φ/2) - (N·H)² = (N·P)² (1 - L·V) / 2, P the unit normal of the plane of L and V."""
    rng = np.random.default_rng(seed)
    normal, light, viewer = rng.normal(size=(3, 3)) * [0.4, 0.4, 0.2] + [0, 0, 1]
    unit, light, viewer = (v / np.linalg.norm(v) for v in (normal, light, viewer))
    across = np.cross(light, viewer) / np.linalg.norm(np.cross(light, viewer))
    n_dot_h, cos_half_phi = half_angle_gap(normal, light, viewer)
    gap = (unit @ across) ** 2 * (1 - light @ viewer) / 2
    assert cos_half_phi**2 - n_dot_h**2 == pytest.approx(gap, rel=1e-9, abs=1e-15)
    assert n_dot_h < cos_half_phi


def test_halfway_vector_of_opposite_directions_is_refused():
    with pytest.raises(ValueError, match="must not be opposite"):
        halfway_vector((1, 0, 0), (-2, 0, 0))

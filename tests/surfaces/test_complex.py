"""Complex surfaces coloured by phase (Wang 1989 §3.4, spec §2.9): F, the grid, the scene."""

import math

import numpy as np
import pytest

from scanviz import render
from scanviz.shading.colour_ring import colour_ring, ring_index
from scanviz.surfaces import FacetOrder, GridSurface, View, enumerate_facets, facet_polygons
from scanviz.surfaces.complex import (
    DEFAULT_CLIP,
    THREE_POLES_TWO_ZEROS,
    ComplexSurface,
    RationalFunction,
    complex_surface,
    phase_scene,
    three_poles_two_zeros,
)

VIEW = View((6.0, -8.0, 9.0), (-6.0, 8.0, -8.0))


def direct(s, zeros, poles, gain):
    """Oracle: numpy's products of all factors at once."""
    s = np.asarray(s, dtype=complex)[..., None]
    return gain * np.prod(s - np.array(zeros), axis=-1) / np.prod(s - np.array(poles), axis=-1)


# --- the rational function --------------------------------------------------------------------


def test_values_equal_direct_numpy_evaluation():
    rng = np.random.default_rng(12)
    zeros = rng.normal(size=3) + 1j * rng.normal(size=3)
    poles = rng.normal(size=4) + 1j * rng.normal(size=4)
    s = rng.normal(size=(5, 7)) * 2 + 2j * rng.normal(size=(5, 7))
    F = RationalFunction(zeros, poles, 1.5 - 0.5j)
    np.testing.assert_allclose(F(s), direct(s, zeros, poles, 1.5 - 0.5j), rtol=1e-12)


def test_hand_values():
    F = RationalFunction(zeros=[1], poles=[-1j], gain=2)  # 2 (s - 1) / (s + i)
    assert F(np.array([0, 1, 1j])).tolist() == [2j, 0j, 1 + 1j]


def test_no_zeros_and_no_poles_is_the_constant_gain():
    F = RationalFunction(gain=-3)
    values = F(np.zeros((2, 3)))
    assert values.shape == (2, 3) and (values == -3).all()
    assert F(5j).shape == ()


def test_zeros_and_poles_are_stored_as_complex_tuples():
    F = RationalFunction(zeros=np.array([1.0, 2.0]), poles=[1j], gain=2)
    assert F.zeros == (1 + 0j, 2 + 0j) and F.poles == (1j,) and F.gain == 2 + 0j


def test_modulus_and_phase_at_zeros_and_near_poles():
    F = THREE_POLES_TWO_ZEROS
    assert (F(np.array(F.zeros)) == 0).all()
    for pole in F.poles:
        near = F(np.array([pole + 1e-9, pole + 1e-9j]))
        assert (np.abs(near) > 1e8).all()
        # A simple pole: F ~ residue / (s - p), so the phase turns by -pi/2 from +1e-9 to +1e-9 i.
        turn = np.angle(near[1] / near[0])
        assert turn == pytest.approx(-math.pi / 2, abs=1e-6)


def test_a_pole_evaluates_to_non_finite():
    assert not np.isfinite(RationalFunction(poles=[1j])(np.array([1j]))).all()


@pytest.mark.parametrize(
    "arguments, error, message",
    [
        ({"gain": 0}, ValueError, "'gain' must be nonzero"),
        ({"gain": math.nan}, ValueError, "'gain' must be finite"),
        ({"gain": True}, TypeError, "'gain' must be a complex number"),
        ({"gain": "1"}, TypeError, "'gain' must be a complex number"),
        ({"zeros": [0, complex(math.nan, 0)]}, ValueError, r"'zeros\[1\]' must be finite"),
        ({"poles": [math.inf]}, ValueError, r"'poles\[0\]' must be finite"),
        ({"poles": ["1j"]}, TypeError, r"'poles\[0\]' must be a complex number"),
        ({"zeros": 3}, TypeError, "'zeros' must be a sequence of complex numbers"),
        (
            {"zeros": [1, 2j], "poles": [2j]},
            ValueError,
            r"2j is in 'zeros' \(index 1\) and 'poles' \(index 0\)",
        ),
    ],
)
def test_bad_function(arguments, error, message):
    with pytest.raises(error, match=message):
        RationalFunction(**arguments)


# --- the sampled surface ----------------------------------------------------------------------


def test_surface_heights_and_phases_of_s():
    result = complex_surface(RationalFunction(zeros=[0]), (-1, 1), (-1, 2), 3, 2)
    s = np.array([[-1 - 1j, -1j, 1 - 1j], [-1 + 2j, 2j, 1 + 2j]])
    np.testing.assert_array_equal(result.surface.x, [-1, 0, 1])
    np.testing.assert_array_equal(result.surface.y, [-1, 2])
    np.testing.assert_allclose(result.surface.z, np.abs(s), rtol=1e-15)
    np.testing.assert_allclose(result.phase, np.arctan2(s.imag, s.real), rtol=1e-15)


def test_zero_on_a_grid_point_has_height_0_and_phase_0():
    result = complex_surface(
        RationalFunction(zeros=[0.5 - 1j], gain=-1), (-0.5, 0.5), (-1, 1), 3, 3
    )
    assert result.surface.z[0, 2] == 0 and result.phase[0, 2] == 0
    assert result.values[0, 2] == 0


def test_phase_is_numpys_angle_elsewhere():
    result = three_poles_two_zeros(21)
    np.testing.assert_array_equal(result.phase, np.angle(result.values))
    assert np.abs(result.phase).max() <= math.pi


def test_arrays_are_read_only():
    result = three_poles_two_zeros(5)
    for array in (result.values, result.phase, result.surface.z):
        with pytest.raises(ValueError, match="read-only"):
            array[0, 0] = 1


def _winding(function, centre, radius=0.05, n=9):
    """Turns of arg F around the boundary of a small grid square about `centre` (counter-clockwise)."""
    result = complex_surface(
        function,
        (centre.real - radius, centre.real + radius),
        (centre.imag - radius, centre.imag + radius),
        n,
        n,
    )
    p = result.phase
    loop = np.concatenate([p[0, :], p[1:, -1], p[-1, -2::-1], p[-2:0:-1, 0], p[:1, 0]])
    steps = np.angle(np.exp(1j * np.diff(loop)))  # each step wrapped into (-pi, pi]
    return steps.sum() / (2 * math.pi), ring_index(loop, 192)


@pytest.mark.parametrize("which", ["zeros", "poles"])
def test_every_colour_appears_once_around_each_zero_and_pole(which):
    F = THREE_POLES_TWO_ZEROS
    for point in getattr(F, which):
        turns, entries = _winding(F, point + 0.003 + 0.002j)  # off-centre: no grid point on it
        assert turns == pytest.approx(1 if which == "zeros" else -1, abs=1e-9)
        assert {e // 64 for e in entries} == {0, 1, 2}  # all three segments of the ring


def test_pole_on_a_grid_point_is_an_error_naming_both():
    F = RationalFunction(zeros=[0.3j], poles=[0.25j, 0.5 - 0.5j])
    with pytest.raises(
        ValueError, match=r"pole 1 \(\(0\.5-0\.5j\)\) lies on grid point \(i, j\) = \(3, 1\)"
    ):
        complex_surface(F, (-1, 1), (-1, 1), 5, 5)


def test_non_finite_values_of_any_callable_are_an_error_naming_the_point():
    with pytest.raises(ValueError, match=r"F must be finite .* \(i, j\) = \(1, 0\), x \+ iy = 0j"):
        with np.errstate(divide="ignore", invalid="ignore"):
            complex_surface(lambda s: 1 / s, (-1, 1), (0, 1), 3, 2)


def test_clip_bounds_the_heights_near_a_pole():
    F = RationalFunction(poles=[1e-6 + 1e-6j])  # 1.4e-6 from the grid point 0
    result = complex_surface(F, (-1, 1), (-1, 1), 3, 3)
    assert result.clip == DEFAULT_CLIP == 4.0
    assert result.surface.z[1, 1] == 4.0 and result.surface.z.max() == 4.0
    assert result.clipped.tolist() == [[False] * 3, [False, True, False], [False] * 3]
    assert abs(result.values[1, 1]) > 7e5  # the values themselves are kept
    assert result.phase[1, 1] == pytest.approx(3 * math.pi / 4)  # arg(-1/p) = pi - pi/4


def test_clip_none_keeps_huge_heights_and_another_clip_cuts_there():
    F = RationalFunction(poles=[1e-6 + 1e-6j])
    unclipped = complex_surface(F, (-1, 1), (-1, 1), 3, 3, clip=None)
    assert unclipped.surface.z[1, 1] == pytest.approx(1 / math.hypot(1e-6, 1e-6))
    assert not unclipped.clipped.any()
    assert complex_surface(F, (-1, 1), (-1, 1), 3, 3, clip=0.5).surface.z.max() == 0.5


def test_clip_none_with_overflowing_modulus_is_an_error():
    with pytest.raises(ValueError, match=r"\|F\| must be finite .* pass clip="):
        complex_surface(
            lambda s: np.full(s.shape, 1.5e308 + 1.5e308j), (0, 1), (0, 1), 2, 2, clip=None
        )


@pytest.mark.parametrize(
    "clip, error, message",
    [
        (0, ValueError, "'clip' must be finite and > 0"),
        (-1.0, ValueError, "'clip' must be finite and > 0"),
        (math.nan, ValueError, "'clip' must be finite and > 0"),
        (math.inf, ValueError, "'clip' must be finite and > 0"),
        (True, TypeError, "'clip' must be a number or None"),
    ],
)
def test_bad_clip(clip, error, message):
    with pytest.raises(error, match=message):
        complex_surface(THREE_POLES_TWO_ZEROS, (-2, 2), (-2, 2), 3, 3, clip=clip)


@pytest.mark.parametrize(
    "function, error, message",
    [
        (3, TypeError, "'function' must be callable"),
        (lambda s: np.zeros(3), ValueError, r"the grid's shape \(Ny, Nx\) = \(2, 2\); got \(3,\)"),
        (lambda s: np.full(s.shape, "x"), TypeError, "'function' must return complex numbers"),
    ],
)
def test_bad_callable(function, error, message):
    with pytest.raises(error, match=message):
        complex_surface(function, (0, 1), (0, 1), 2, 2)


def test_bad_grid_arguments_are_the_grids_errors():
    with pytest.raises(ValueError, match="'nx' must be >= 2"):
        complex_surface(THREE_POLES_TWO_ZEROS, (0, 1), (0, 1), 1, 2)
    with pytest.raises(ValueError, match="'y_range' must be finite with low < high"):
        complex_surface(THREE_POLES_TWO_ZEROS, (0, 1), (1, 0), 2, 2)


# --- the built-in -----------------------------------------------------------------------------


def test_builtin_arrangement():
    F = THREE_POLES_TWO_ZEROS
    assert len(F.poles) == 3 and len(F.zeros) == 2 and F.gain == 2
    np.testing.assert_allclose(np.abs(F.poles), 1.25)
    np.testing.assert_allclose(np.degrees(np.angle(F.poles)), [100, -140, -20])
    np.testing.assert_allclose(F.zeros[0], -F.zeros[1])
    np.testing.assert_allclose(F.zeros[0], 0.55 * np.exp(np.radians(10) * 1j))


def test_builtin_surface():
    result = three_poles_two_zeros()
    assert isinstance(result, ComplexSurface) and isinstance(result.surface, GridSurface)
    assert (result.surface.nx, result.surface.ny) == (41, 41)
    assert result.surface.x[0] == -2 and result.surface.y[-1] == 2
    assert result.surface.z.max() == DEFAULT_CLIP and result.clipped.sum() > 0
    assert result.surface.z.min() < 0.05  # the zeros are valleys near 0


@pytest.mark.parametrize("n", [2, 3, 5, 17, 21, 33, 81, 101, 161, 201, 401])
def test_builtin_has_no_pole_on_uniform_grids(n):
    assert three_poles_two_zeros(n).surface.nx == n


# --- triangles and the scene ------------------------------------------------------------------


def test_triangle_entries_by_hand():
    # F(s) = s on one element of [-1, 1]^2 (faces (0, 1, 3) and (0, 3, 2) of to_mesh):
    # face 0: -3pi/4, -pi/4, pi/4 -> mean -pi/4 -> 7pi/4: 191 * 7/8 = 167.1;
    # face 1: -3pi/4 -> 5pi/4, pi/4, 3pi/4 -> mean 3pi/4: 191 * 3/8 = 71.6.
    result = complex_surface(RationalFunction(zeros=[0]), (-1, 1), (-1, 1), 2, 2)
    assert result.triangle_entries().tolist() == [167, 71]
    assert result.triangle_entries(32).tolist() == [83, 35]  # 95 * 7/8, 95 * 3/8


def test_triangle_entries_count():
    result = three_poles_two_zeros(9)
    entries = result.triangle_entries()
    assert entries.shape == (2 * 64,) and entries.min() >= 0 and entries.max() <= 191


def test_phase_scene_materials():
    result = three_poles_two_zeros(9)
    scene = phase_scene(result, VIEW, 32, 32)
    mesh = scene.objects[0].mesh
    np.testing.assert_array_equal(mesh.face_materials, result.triangle_entries())
    ring = colour_ring(64)
    assert len(mesh.materials) == 192
    assert [m.color for m in mesh.materials] == [tuple(rgb) for rgb in ring.tolist()]
    assert all((m.ambient, m.diffuse, m.specular) == (1, 0, 0) for m in mesh.materials)
    np.testing.assert_array_equal(mesh.positions, result.surface.points())
    assert scene.camera == result.surface.scene(VIEW, 32, 32).camera
    assert scene.background == (0.0, 0.0, 0.0)


def test_phase_scene_marker_and_steps():
    result = three_poles_two_zeros(9)
    scene = phase_scene(result, VIEW, 16, 16, steps=32, marker=40)
    materials = scene.objects[0].mesh.materials
    assert len(materials) == 96 and materials[40].color == (1.0, 1.0, 1.0)
    assert materials[41].color == tuple(colour_ring(32)[41].tolist())


@pytest.mark.parametrize("shading", ["flat", "phong"])
def test_rendered_pixels_are_their_triangles_ring_colours(shading):
    result = three_poles_two_zeros(13)
    scene = phase_scene(result, VIEW, 64, 64)
    rendered = render(scene, 64, 64, shading=shading)
    covered = rendered.polygon >= 0
    expected = colour_ring(64)[result.triangle_entries()[rendered.polygon[covered]]]
    np.testing.assert_array_equal(rendered.image[..., :3][covered], expected)
    assert (rendered.image[..., :3][~covered] == 0).all()


def test_gouraud_interpolates_each_triangles_colour_to_rounding():
    result = three_poles_two_zeros(13)
    rendered = render(phase_scene(result, VIEW, 64, 64), 64, 64, shading="gouraud")
    covered = rendered.polygon >= 0
    expected = colour_ring(64)[result.triangle_entries()[rendered.polygon[covered]]]
    np.testing.assert_allclose(rendered.image[..., :3][covered], expected, rtol=0, atol=1e-14)


def test_marked_pixels_are_white_exactly_where_the_entry_is():
    result = three_poles_two_zeros(13)
    entries = result.triangle_entries()
    marker = int(np.bincount(entries).argmax())
    rendered = render(phase_scene(result, VIEW, 64, 64, marker=marker), 64, 64, shading="flat")
    covered = rendered.polygon >= 0
    white = (rendered.image[..., :3] == 1).all(axis=-1)
    np.testing.assert_array_equal(white[covered], entries[rendered.polygon[covered]] == marker)
    assert white.any()


def test_fpa_painting_of_the_phase_scene_equals_the_zbuffer():
    result = three_poles_two_zeros(13)
    scene = phase_scene(result, VIEW, 64, 64)
    x, y = result.surface.x, result.surface.y
    order = FacetOrder(facet_polygons(enumerate_facets(x, y, VIEW), x, y, VIEW), mode="under")
    fpa = render(scene, 64, 64, shading="flat", visibility=order)
    zbuffer = render(scene, 64, 64, shading="flat")
    np.testing.assert_array_equal(fpa.image, zbuffer.image)


def test_phase_scene_bad_input():
    with pytest.raises(TypeError, match="'result' must be a ComplexSurface"):
        phase_scene(three_poles_two_zeros(3).surface, VIEW, 8, 8)
    with pytest.raises(ValueError, match="'entry' must be >= 0 and < 192"):
        phase_scene(three_poles_two_zeros(3), VIEW, 8, 8, marker=192)
    with pytest.raises(ValueError, match="'steps' must be in 1..4096"):
        phase_scene(three_poles_two_zeros(3), VIEW, 8, 8, steps=0)


def test_the_fpa_paints_the_phase_scene_as_the_zbuffer_does():
    from scanviz import render
    from scanviz.surfaces import View, floating_perimeter, phase_scene, three_poles_two_zeros

    result = three_poles_two_zeros(15)
    view = View((5.0, -6.0, 6.0), (-5.0, 6.0, -5.0))
    scene = phase_scene(result, view, 64, 64)
    fpa = floating_perimeter(result.surface, view, 64, 64, "surface", shading="flat", scene=scene)
    z = render(scene, 64, 64, shading="flat")
    np.testing.assert_array_equal(fpa.image, z.image)
    with pytest.raises(ValueError, match="one object of 2 x 64 faces.*got 1 object of 392 faces"):
        floating_perimeter(three_poles_two_zeros(9).surface, view, 8, 8, "surface", scene=scene)

"""The Phong illumination model: analytic checks, traced == fast bit for bit, and normals."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.scene.model import Light, Material
from scanviz.shading import (
    MATERIAL_FIELDS,
    face_normals,
    illuminate,
    illuminate_traced,
    material_array,
    vertex_normals,
)
from scanviz.trace import Recorder, Trace
from tests.shading import CUBE_FACES, CUBE_POSITIONS, uv_sphere

BASE = settings.default.max_examples
WHITE = (1.0, 1.0, 1.0)


def rows(material: Material, count: int) -> np.ndarray:
    return np.repeat(material_array([material]), count, axis=0)


def unit(vector) -> np.ndarray:
    vector = np.asarray(vector, dtype=float)
    return vector / np.linalg.norm(vector)


def angle_degrees(a, b) -> np.ndarray:
    return np.degrees(np.arccos(np.clip(np.asarray(a) @ unit(b), -1, 1)))


# --- materials ----------------------------------------------------------------------------


def test_material_array_packs_the_fields_in_order():
    material = Material(
        color=(0.1, 0.2, 0.3),
        ambient=0.4,
        diffuse=0.5,
        specular=0.6,
        exponent=7.0,
        transparency=0.8,
        fudge=0.9,
    )
    packed = material_array([Material(), material])
    assert packed.shape == (2, len(MATERIAL_FIELDS)) and packed.dtype == np.float64
    assert dict(zip(MATERIAL_FIELDS, packed[1].tolist(), strict=True)) == {
        "r": 0.1,
        "g": 0.2,
        "b": 0.3,
        "ambient": 0.4,
        "diffuse": 0.5,
        "specular": 0.6,
        "exponent": 7.0,
        "transparency": 0.8,
        "fudge": 0.9,
    }
    assert material_array([]).shape == (0, 9)


def test_material_array_rejects_what_is_not_a_material():
    with pytest.raises(TypeError, match=r"'materials\[1\]' must be a Material"):
        material_array([Material(), (1, 1, 1)])


# --- the model, term by term --------------------------------------------------------------


def sphere_grid(step_degrees: float) -> np.ndarray:
    """Points of the unit sphere on a latitude-longitude grid (they are their own normals)."""
    polar = np.radians(np.arange(step_degrees, 180, step_degrees))
    azimuth = np.radians(np.arange(0, 360, step_degrees))
    polar, azimuth = np.meshgrid(polar, azimuth, indexing="ij")
    return np.stack(
        [np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)], axis=-1
    ).reshape(-1, 3)


@pytest.mark.parametrize(
    ("shine_along", "to_viewer"),
    [((0, 0, -1), (1, 0, 0)), ((-1, -2, -0.5), (0.3, 0.2, 1.0)), ((1, 0, 0), (0, 1, 0.2))],
)
@pytest.mark.parametrize("viewer", ["orthographic", "far eye"])
def test_phong_highlight_on_a_sphere_peaks_at_the_half_way_direction(
    shine_along, to_viewer, viewer
):
    step = 0.5
    points = sphere_grid(step)
    shiny = rows(Material(color=WHITE, ambient=0, diffuse=0, specular=1, exponent=200), len(points))
    view = {"view_dir": to_viewer} if viewer == "orthographic" else {}
    eye = None if viewer == "orthographic" else 1e7 * unit(to_viewer)
    color = illuminate(
        points, points, shiny, eye, [Light(direction=shine_along)], (0, 0, 0), **view
    )
    halfway = unit(-unit(shine_along) + unit(to_viewer))
    # Only the visible half: lit two-sided, the far half would mirror the highlight to -halfway.
    visible = points @ unit(to_viewer) > 0
    peak = points[visible][np.argmax(color[visible, 0])]
    assert angle_degrees(peak, halfway) <= step
    assert color[:, 0].max() > 0.9  # the grid comes close to the mirror direction


def test_lambert_term_is_the_cosine_of_the_angle_of_incidence():
    angle = np.radians(np.linspace(0, 180, 181))
    normals = np.stack([np.sin(angle), np.zeros_like(angle), np.cos(angle)], axis=1)
    matte = rows(Material(color=WHITE, ambient=0, diffuse=1, specular=0), len(angle))
    # Light straight down onto the xy-plane; the viewer on +x sees every normal from the front.
    color = illuminate(
        np.zeros_like(normals), normals, matte, None, [Light()], (0, 0, 0), view_dir=(1, 0, 0)
    )
    np.testing.assert_allclose(
        color, np.maximum(np.cos(angle), 0)[:, None].repeat(3, 1), atol=1e-15
    )


def test_diffuse_and_ambient_take_the_material_color_and_specular_is_white():
    material = Material(color=(1.0, 0.5, 0.0), ambient=0.2, diffuse=0.4, specular=0.3, exponent=5)
    lit = illuminate([(0, 0, 0)], [(0, 0, 1)], rows(material, 1), (0, 0, 3), [Light()], WHITE)
    np.testing.assert_allclose(lit, [[0.9, 0.6, 0.3]], rtol=1e-15)


def test_attenuation_halves_the_light_at_distance_one_over_fudge():
    def lit(fudge: float, distance: float) -> np.ndarray:
        material = Material(color=WHITE, ambient=0, diffuse=0.6, specular=0.2, fudge=fudge)
        light = Light(kind="point", position=(0, 0, distance))
        return illuminate([(0, 0, 0)], [(0, 0, 1)], rows(material, 1), (0, 0, 9), [light], WHITE)

    np.testing.assert_allclose(lit(0.5, 2.0), lit(0.0, 2.0) / 2, rtol=1e-15)
    np.testing.assert_allclose(lit(4.0, 0.25), lit(0.0, 0.25) / 2, rtol=1e-15)
    np.testing.assert_array_equal(lit(0.0, 100.0), lit(0.0, 1.0))  # no fudge, no fall-off


def test_directional_lights_are_not_attenuated():
    material = rows(Material(color=WHITE, ambient=0, specular=0, fudge=10.0), 1)
    color = illuminate([(0, 0, 0)], [(0, 0, 1)], material, (0, 0, 9), [Light()], WHITE)
    np.testing.assert_array_equal(color, [[0.7, 0.7, 0.7]])


def test_without_lights_only_ambient_remains():
    material = Material(color=(0.2, 0.4, 0.8), ambient=0.5)
    points = np.random.default_rng(1).normal(size=(10, 3))
    color = illuminate(points, points, rows(material, 10), (0, 0, 5), [], (1.0, 0.5, 0.25))
    np.testing.assert_array_equal(
        color, np.tile([0.5 * 0.2, 0.5 * 0.5 * 0.4, 0.5 * 0.25 * 0.8], (10, 1))
    )


def test_a_zero_normal_gets_ambient_light_only():
    material = rows(Material(color=WHITE, ambient=0.25, specular=1.0, exponent=0.0), 2)
    color = illuminate(
        np.zeros((2, 3)), [(0, 0, 0), (0, 0, 1)], material, (0, 0, 5), [Light()], WHITE
    )
    assert color[0].tolist() == [0.25] * 3 and color[1].tolist() == [1.0] * 3


def test_a_surface_seen_from_behind_is_lit_on_its_visible_side():
    material = rows(Material(), 1)
    front = illuminate([(0, 0, 0)], [(0, 0, 1)], material, (0, 0, 5), [Light()], WHITE)
    back = illuminate([(0, 0, 0)], [(0, 0, -1)], material, (0, 0, 5), [Light()], WHITE)
    np.testing.assert_array_equal(front, back)


def test_no_highlight_where_the_light_is_behind_the_visible_side():
    # Exponent 0 makes the highlight 1 wherever it exists, so only the N.L > 0 rule can remove it.
    glossy = rows(Material(color=WHITE, ambient=0, diffuse=0, specular=1, exponent=0), 1)

    def shine(along):
        return illuminate(
            [(0, 0, 0)], [(0, 0, 1)], glossy, (0, 0, 5), [Light(direction=along)], WHITE
        )

    assert shine((0, 0, -1)).tolist() == [[1.0] * 3]
    assert shine((0, 0, 1)).tolist() == [[0.0] * 3]


def test_the_color_is_clipped_to_one():
    lights = [Light(color=(5, 5, 5)), Light(kind="point", position=(0, 1, 1))]
    color = illuminate([(0, 0, 0)], [(0, 0, 1)], rows(Material(), 1), (0, 0, 5), lights, WHITE)
    assert color.tolist() == [[1.0, 1.0, 1.0]]


@pytest.mark.parametrize(
    ("arguments", "error", "message"),
    [
        ({"eye": None}, ValueError, "exactly one of 'eye'"),
        ({"view_dir": (0, 0, 1)}, ValueError, "exactly one of 'eye'"),
        ({"eye": None, "view_dir": (0, 0, 0)}, ValueError, "'view_dir' must not be the zero"),
        ({"normals": np.zeros((3, 3))}, ValueError, "'normals' must have one row per position"),
        ({"positions": [(0, 0, np.nan), (0, 0, 0)]}, ValueError, "'positions' row 0 is not finite"),
        ({"materials": np.zeros((2, 8))}, ValueError, r"'materials' must be an \(N, 9\) array"),
        ({"lights": [Light(), "sun"]}, TypeError, r"'lights\[1\]' must be a Light"),
        ({"ambient_light": (1, -1, 1)}, ValueError, "'ambient_light' components must be >= 0"),
    ],
)
def test_bad_arguments_are_named(arguments, error, message):
    call = {
        "positions": np.zeros((2, 3)),
        "normals": [(0, 0, 1)] * 2,
        "materials": rows(Material(), 2),
        "eye": (0, 0, 5),
        "lights": [Light()],
        "ambient_light": WHITE,
    }
    with pytest.raises(error, match=message):
        illuminate(**(call | arguments))


def test_negative_exponent_or_fudge_in_a_material_row_is_rejected():
    material = rows(Material(), 2)
    material[1, MATERIAL_FIELDS.index("fudge")] = -1
    with pytest.raises(ValueError, match="'materials' row 1: fudge must be >= 0"):
        illuminate(np.zeros((2, 3)), [(0, 0, 1)] * 2, material, (0, 0, 5), [], WHITE)


# --- one point alone == the same point among many; traced == fast -------------------------

coordinate = st.floats(-10, 10, allow_nan=False)
vector = st.tuples(coordinate, coordinate, coordinate)
direction = vector.filter(lambda v: any(v))
unit_interval = st.floats(0, 1)
material_row = st.tuples(
    unit_interval, unit_interval, unit_interval, unit_interval, unit_interval, unit_interval,
    st.floats(0, 300), unit_interval, st.floats(0, 3),
)  # fmt: skip
light = st.one_of(
    st.builds(
        Light, kind=st.just("point"), position=vector, color=st.tuples(*[st.floats(0, 2)] * 3)
    ),
    st.builds(Light, direction=direction, color=st.tuples(*[st.floats(0, 2)] * 3)),
)
scene = st.integers(1, 12).flatmap(
    lambda n: st.fixed_dictionaries(
        {
            "positions": st.lists(vector, min_size=n, max_size=n),
            "normals": st.lists(vector, min_size=n, max_size=n),
            "materials": st.lists(material_row, min_size=n, max_size=n),
            "lights": st.lists(light, max_size=3),
            "ambient_light": st.tuples(unit_interval, unit_interval, unit_interval),
            "viewer": st.one_of(
                st.builds(lambda eye: {"eye": eye}, vector),
                st.builds(lambda v: {"eye": None, "view_dir": v}, direction),
            ),
        }
    )
)


def unpack(s: dict) -> tuple[tuple, dict]:
    return (s["positions"], s["normals"], s["materials"]), {
        "lights": s["lights"],
        "ambient_light": s["ambient_light"],
        **s["viewer"],
    }


@settings(max_examples=3 * BASE)
@given(scene)
def test_one_point_alone_gets_bit_for_bit_its_color_among_many(s):
    (positions, normals, materials), options = unpack(s)
    together = illuminate(positions, normals, materials, **options)
    assert together.shape == (len(positions), 3) and ((0 <= together) & (together <= 1)).all()
    for i in range(len(positions)):
        alone = illuminate(
            positions[i : i + 1], normals[i : i + 1], materials[i : i + 1], **options
        )
        assert alone.tobytes() == together[i : i + 1].tobytes()
        recorder = Recorder()
        traced = illuminate_traced(
            positions[i], normals[i], materials[i], **options, trace=recorder, pixel=(i, 0)
        )
        assert traced.tobytes() == together[i].tobytes()
        (event,) = recorder.trace()
        assert event.color == tuple(traced.tolist())
        assert len(event.lights) == len(options["lights"])


def test_traced_event_shows_every_term_and_round_trips_through_json():
    material = Material(
        color=(1.0, 0.5, 0.25), ambient=0.2, diffuse=0.5, specular=0.4, exponent=2, fudge=1
    )
    lights = [
        Light(direction=(0, -1, -1)),
        Light(kind="point", position=(0, 0, 3), color=(0.5, 0.5, 0.5)),
    ]
    recorder = Recorder()
    color = illuminate_traced(
        (0, 0, 0), (0, 0, 3), material_array([material])[0], (0, -3, 3), lights, WHITE,
        trace=recorder, pixel=(7, 2), polygon=4,
    )  # fmt: skip
    (event,) = recorder.trace()
    assert (event.kind, event.x, event.y, event.polygon, event.flipped) == (
        "illumination",
        7,
        2,
        4,
        False,
    )
    assert event.normal == (0.0, 0.0, 1.0) and event.ambient == (0.2, 0.1, 0.05)
    np.testing.assert_allclose(event.to_viewer, unit((0, -1, 1)))
    sun, bulb = event.lights
    np.testing.assert_allclose(sun.to_light, unit((0, 1, 1)))
    assert sun.attenuation == 1.0 and sun.n_dot_l == pytest.approx(np.sqrt(0.5))
    assert sun.r_dot_v == pytest.approx(1.0)  # the viewer sits in the mirror direction R
    assert sun.specular == pytest.approx(0.4)
    assert bulb.to_light == (0.0, 0.0, 1.0) and bulb.n_dot_l == 1.0
    assert bulb.attenuation == 0.25  # 1 / (1 + 1 * 3)
    assert bulb.r_dot_v == pytest.approx(np.sqrt(0.5)) and bulb.specular == pytest.approx(0.4 * 0.5)
    np.testing.assert_allclose(bulb.diffuse, (0.5, 0.25, 0.125))
    np.testing.assert_allclose(
        bulb.contribution, 0.25 * 0.5 * (np.array(bulb.diffuse) + bulb.specular)
    )
    total = np.array(event.ambient) + sun.contribution + np.array(bulb.contribution)
    np.testing.assert_array_equal(color, np.clip(total, 0, 1))
    trace = recorder.trace()
    assert Trace.from_json(trace.to_json()) == trace


def test_traced_events_are_filtered_by_pixel_region_and_polygon():
    material = material_array([Material()])[0]
    recorder = Recorder(kinds=["illumination"], region=(0, 0, 2, 2), polygons=[1])
    for x, y, polygon in [(1, 1, 1), (3, 1, 1), (1, 5, 1), (0, 0, 2)]:
        illuminate_traced((0, 0, 0), (0, 0, 1), material, (0, 0, 5), [Light()], WHITE,
                          trace=recorder, pixel=(x, y), polygon=polygon)  # fmt: skip
    assert [(e.x, e.y, e.polygon) for e in recorder.trace()] == [(1, 1, 1)]


def test_traced_without_a_tracer_still_shades():
    material = material_array([Material()])[0]
    color = illuminate_traced(
        (0, 0, 0), (0, 0, 1), material, (0, 0, 5), [Light()], WHITE, trace=None, pixel=(0, 0)
    )
    expected = illuminate([(0, 0, 0)], [(0, 0, 1)], [material], (0, 0, 5), [Light()], WHITE)[0]
    assert color.tobytes() == expected.tobytes()


def test_traced_rejects_a_bad_pixel():
    material = material_array([Material()])[0]
    with pytest.raises(TypeError, match="'pixel' must be a pair of ints"):
        illuminate_traced(
            (0, 0, 0), (0, 0, 1), material, (0, 0, 5), [], WHITE, trace=None, pixel=(0.5, 1)
        )


# --- normals -------------------------------------------------------------------------------


def test_face_normals_of_a_unit_sphere_point_outward():
    positions, faces = uv_sphere()
    normals = face_normals(positions, faces)
    centroids = np.array([positions[f].mean(axis=0) for f in faces])
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=1e-12)
    assert (np.sum(normals * unit_rows(centroids), axis=1) > 0.99).all()


def unit_rows(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.linalg.norm(vectors, axis=1, keepdims=True)


def test_vertex_normals_of_a_unit_sphere_point_outward():
    rings, segments = 24, 48
    positions, faces = uv_sphere(rings, segments)
    normals = vertex_normals(positions, faces)
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=1e-12)
    assert (np.sum(normals * positions, axis=1) > 0.999).all()
    # By symmetry the poles and the equator get the exact sphere normal.
    equator = 1 + (rings // 2 - 1) * segments + np.arange(segments)
    for vertex in (0, len(positions) - 1, *equator):
        np.testing.assert_allclose(normals[vertex], positions[vertex], atol=1e-12)


def test_face_normals_of_a_cube_are_the_axes():
    expected = [(-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)]
    np.testing.assert_array_equal(face_normals(CUBE_POSITIONS, CUBE_FACES), expected)
    corner = vertex_normals(CUBE_POSITIONS, CUBE_FACES)[7]
    np.testing.assert_allclose(corner, unit((1, 1, 1)), rtol=1e-15)


def test_face_normals_survive_a_far_translation_and_reject_degenerate_faces():
    triangle = np.array([(0, 0, 0), (1e-3, 0, 0), (0, 1e-3, 0), (2e-3, 0, 0)]) + 1e6
    normals = face_normals(triangle, [[0, 1, 2], [0, 1, 3], [0, 0, 2]])
    np.testing.assert_allclose(normals[0], (0, 0, 1), atol=1e-9)
    assert normals[1:].tolist() == [[0, 0, 0], [0, 0, 0]]  # collinear, repeated vertex


def test_collinear_vertices_get_the_zero_normal_despite_rounding():
    # In floating point these points are not exactly collinear: Newell's sums are ~1e-17, not 0.
    start, step = np.random.default_rng(0).random((2, 3))
    line = np.array([start, start + 0.3 * step, start + 0.7 * step])
    assert face_normals(line, [[0, 1, 2]]).tolist() == [[0.0, 0.0, 0.0]]
    assert vertex_normals(line, [[0, 1, 2]]).tolist() == [[0.0, 0.0, 0.0]] * 3


def test_newell_normal_of_a_non_planar_quad_is_the_average_plane():
    saddle = [(1, 0, 0.1), (0, 1, -0.1), (-1, 0, 0.1), (0, -1, -0.1)]
    np.testing.assert_allclose(face_normals(saddle, [[0, 1, 2, 3]]), [(0, 0, 1)], atol=1e-15)


@pytest.mark.parametrize(
    ("faces", "error", "message"),
    [
        ([[0, 1]], ValueError, r"'faces\[0\]' has 2 vertices"),
        ([[0, 1, 2], [0, 1, 9]], ValueError, r"'faces\[1\]' indexes outside 0..3"),
        ([[0.0, 1.0, 2.0]], TypeError, r"'faces\[0\]' must be a 1-D sequence of int indices"),
        ("abc", TypeError, "'faces' must be a sequence"),
    ],
)
def test_bad_faces_are_named(faces, error, message):
    with pytest.raises(error, match=message):
        face_normals(np.zeros((4, 3)), faces)


def test_a_tiny_view_direction_is_still_a_direction():
    # Regression: |view_dir| = 1e-200 underflowed to 0 in sqrt(dot) and was rejected as zero.
    material = material_array([Material(ambient=0.1, diffuse=0.7, specular=0.0)])
    args = (np.zeros((1, 3)), np.array([[0.0, 0.0, 1.0]]), material, None, (Light(),), np.ones(3))
    tiny = illuminate(*args, view_dir=(0.0, 0.0, 1e-200))
    np.testing.assert_array_equal(tiny, illuminate(*args, view_dir=(0.0, 0.0, 1.0)))


# --- issue 8 -----------------------------------------------------------------------------------


def beyond_scene_limits(light: Light, position) -> Light:
    """`light` moved past the scene's own limits (1e99), as a hostile caller could build one."""
    object.__setattr__(light, "position", tuple(float(c) for c in position))
    return light


@pytest.mark.parametrize("fudge", [0.0, 0.5, 1e99])
@pytest.mark.parametrize("distance", [1e99, 1e308])
def test_issue8_d4_a_far_point_light_gives_no_nan(fudge, distance):
    material = Material(color=WHITE, ambient=0.25, diffuse=0.5, specular=0.125, fudge=fudge)
    light = beyond_scene_limits(Light(kind="point", position=(0, 0, 1)), (0, 0, distance))
    positions = [(0, 0, 0), (0, 0, -1e99), (1e99, -1e99, 1e99)]
    normals = [(0, 0, 1), (0, 0, 1e-300), (0, 0, 1e300)]
    lit = illuminate(positions, normals, rows(material, 3), (0, 0, 9e98), [light], WHITE)
    assert np.isfinite(lit).all()
    # Head-on light: N.L = R.V = 1, so Od (ka + f_att kd) + f_att ks with f_att = 1 / (1 + fudge d).
    attenuation = 1 / (1 + fudge * distance)
    np.testing.assert_allclose(lit[0], 0.25 + attenuation * (0.5 + 0.125), rtol=1e-15)


def test_issue8_d4_distances_beyond_float64_attenuate_to_zero_not_nan():
    material = Material(color=WHITE, ambient=0.0, diffuse=1.0, specular=0.0, fudge=1.0)
    light = beyond_scene_limits(Light(kind="point", position=(0, 0, 1)), (0, 0, 1.5e308))
    lit = illuminate(
        [(0, 0, -1.5e308)], [(0, 0, 1)], rows(material, 1), (0, 0, 1.6e308), [light], WHITE
    )  # the distance, 3e308, overflows: f_att = 0
    np.testing.assert_array_equal(lit, [[0.0, 0.0, 0.0]])
    no_fudge = rows(dataclasses.replace(material, fudge=0.0), 1)
    lit = illuminate([(0, 0, -1.5e308)], [(0, 0, 1)], no_fudge, (0, 0, 1.6e308), [light], WHITE)
    np.testing.assert_array_equal(lit, [[1.0, 1.0, 1.0]])  # no fudge: no fall-off, even there


def test_the_highlight_power_has_the_same_bits_in_any_memory_layout():
    # Found by hypothesis: numpy's SIMD power gave this row one ulp apart alone and in a batch.
    positions, normals = np.zeros((7, 3)), np.zeros((7, 3))
    normals[5] = (-3.0, 0.0, 6.0)
    materials = np.zeros((7, 9))
    materials[5] = (0, 0, 0, 0, 0, 1, 2, 0, 0)
    lights = [
        Light(kind="point", position=(0, 0, 0), color=(0, 0, 0)),
        Light(kind="point", position=(0, 0, 0), color=(0, 0, 0)),
        Light(direction=(-1.5, 4.0, 1.75), color=(0.0, 0.0, 1.0)),
    ]
    options = {"lights": lights, "ambient_light": np.zeros(3), "eye": np.array([0.0, 0.0, -1.0])}
    together = illuminate(positions, normals, materials, **options)
    traced = illuminate_traced(
        positions[5], normals[5], materials[5], **options, trace=Recorder(), pixel=(5, 0)
    )
    assert traced.tobytes() == together[5].tobytes()

"""Wang 1989 ch. 5: anti-aliased hidden lines and smoothed surfaces, against DISLOP and the a-buffer."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scanviz.abuffer.area import area_coverage
from scanviz.antialias import dislop_line
from scanviz.antialias.post import post_antialias
from scanviz.antialias.surfaces import (
    antialiased_hidden_lines,
    draw_segments,
    fpa_segments,
    outline,
    outline_loops,
    read_segments,
    screen_triangles,
    smoothed_surface,
    write_segments,
)
from scanviz.cli import _default_view
from scanviz.pipeline import render
from scanviz.surfaces import GridSurface, View, floating_perimeter, gaussian, polynomial

SIZE = 80
FLAT = GridSurface([0.0, 1.0, 2.0], [0.0, 1.0], [[0, 0, 0], [0, 0, 0]])
DEGENERATE_VIEWS = [
    View((1, -5, 0), (0, 1, 0), "parallel"),  # edge-on: the grid projects to a line
    View((1, 0.5, 5), (0, 0, -1)),  # straight down, viewing case 1
    View((0, 0, 3), (0, 0, -1), "parallel"),
]


def cases():
    """The dissertation's two examples, the CLI's default view, and a view from the other side."""
    for surface in (gaussian(), polynomial(12)):
        yield surface, _default_view(surface, None, None, False)
        yield surface, _default_view(surface, (-3.0, -2.5, 2.0), None, False)


CASES = list(cases())


def band_union(segments, width, height):
    """Exact area of the union of the 1-wide rectangles (nonzero winding of counter-clockwise ones)."""
    rectangles = []
    for p0, p1 in segments:
        d = p1 - p0
        normal = np.array([-d[1], d[0]]) / np.hypot(*d) / 2
        rectangles.append([p0 - normal, p1 - normal, p1 + normal, p0 + normal])
    return area_coverage(rectangles, width, height, subpixel_bits=None)


# --- the image data file ---------------------------------------------------------------------


@settings(max_examples=25, derandomize=True)
@given(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=0, max_size=40).map(
    lambda v: np.array(v[: len(v) // 4 * 4]).reshape(-1, 2, 2)
))  # fmt: skip
def test_segments_round_trip_exactly(tmp_path_factory, segments):
    path = tmp_path_factory.mktemp("data") / "lines.txt"
    write_segments(path, segments)
    assert path.read_text().count("\n") == len(segments)
    np.testing.assert_array_equal(read_segments(path), segments)


def test_the_file_holds_one_line_of_four_numbers_per_segment(tmp_path):
    path = tmp_path / "lines.txt"
    write_segments(path, [[(100.3, 150.2), (108.6, 155.8)], [(1, 2), (3, 4)]])
    assert path.read_text() == "100.3 150.2 108.6 155.8\n1.0 2.0 3.0 4.0\n"


def test_a_surface_file_draws_as_the_surface(tmp_path):
    surface, view = CASES[0]
    lines = antialiased_hidden_lines(surface, view, SIZE, SIZE)
    write_segments(tmp_path / "lines.txt", lines.segments)
    np.testing.assert_array_equal(
        draw_segments(read_segments(tmp_path / "lines.txt"), SIZE, SIZE), lines.coverage
    )


@pytest.mark.parametrize(
    ("text", "message"),
    [("1 2 3\n", "line 1 must hold 4 finite numbers"), ("\n1 2 3 x\n", "line 2 must hold 4"),
     ("1 2 3 nan\n", "line 1 must hold 4 finite")],
)  # fmt: skip
def test_a_bad_line_is_named(tmp_path, text, message):
    path = tmp_path / "lines.txt"
    path.write_text(text)
    with pytest.raises(ValueError, match=message):
        read_segments(path)


def test_bad_segments_are_refused():
    with pytest.raises(ValueError, match=r"'segments' must be an \(N, 2, 2\) array"):
        draw_segments([(0, 0, 1, 1)], 4, 4)


# --- hidden lines ----------------------------------------------------------------------------


def test_segments_join_the_centres_of_the_fpa_raster_points():
    surface, view = CASES[0]
    fpa = floating_perimeter(surface, view, SIZE, SIZE)
    segments, points = fpa_segments(fpa)
    long = np.any(fpa.segments[:, :2] != fpa.segments[:, 2:], axis=1)
    np.testing.assert_array_equal(segments[long].reshape(-1, 4), fpa.segments[long] + 0.5)
    assert points == int((~long).sum())
    widened = segments[~long]  # a single point: the unit segment through its centre
    np.testing.assert_allclose(widened.mean(axis=1), fpa.segments[~long, :2] + 0.5)
    np.testing.assert_allclose(np.abs(widened[:, 1] - widened[:, 0]).sum(axis=1), 1.0)


@pytest.mark.parametrize(("surface", "view"), CASES)
@pytest.mark.parametrize(("method", "combine"), [("dislop", "over"), ("dislop", "max"), ("dislop", "sum"), ("post", "over")])  # fmt: skip
def test_every_aliased_pixel_is_covered_and_coverage_is_an_area(surface, view, method, combine):
    lines = antialiased_hidden_lines(surface, view, SIZE, SIZE, method=method, combine=combine)
    assert lines.coverage.min() >= 0.0 and lines.coverage.max() <= 1.0
    aliased = lines.fpa.lines
    assert aliased.sum() > 100
    assert (lines.coverage[aliased] > 0).all()
    assert lines.stats.pixels == int((lines.coverage > 0).sum())


def test_the_aliased_route_is_the_fpa_drawing():
    surface, view = CASES[1]
    lines = antialiased_hidden_lines(surface, view, SIZE, SIZE, method="aliased", background=1.0, intensity=0.0)  # fmt: skip
    np.testing.assert_array_equal(lines.image, lines.fpa.image[..., 0])


def test_one_segment_is_dislop_line_and_the_post_table():
    segment = np.array([[(3.2, 4.7), (40.6, 19.1)]])
    np.testing.assert_array_equal(draw_segments(segment, 48, 24), dislop_line(*segment[0], 48, 24))
    np.testing.assert_array_equal(
        draw_segments(segment, 48, 24, exact=True), dislop_line(*segment[0], 48, 24, exact=True)
    )
    np.testing.assert_array_equal(
        draw_segments(segment, 48, 24, method="post"),
        post_antialias(np.zeros((24, 48)), segment, kind="line")[..., 0],
    )


def test_a_one_facet_surface_is_its_four_sides_by_dislop_line():
    square = GridSurface([0.0, 1.0], [0.0, 1.0], [[0, 0], [0, 0]])
    view = View((0.5, 0.5, 5), (0, 0, -1), "parallel")
    corner = {}
    for combine, join in (("max", np.maximum), ("over", lambda a, b: a + b - a * b)):
        lines = antialiased_hidden_lines(square, view, 12, 12, combine=combine)
        assert lines.stats.segments == 4  # the square's sides, pixel centre to pixel centre
        expected = np.zeros((12, 12))
        for p0, p1 in lines.segments:
            expected = join(expected, dislop_line(p0, p1, 12, 12))
        np.testing.assert_array_equal(lines.coverage, expected)
        corner[combine] = lines.coverage[0, 0]
    # Two half caps meet in the corner pixel; their union is 3/4.
    assert corner == {"max": 0.5, "over": 0.75}
    assert band_union(lines.segments, 12, 12)[0, 0] == pytest.approx(0.75)


def test_over_is_the_closest_combination_to_the_exact_union():
    """Measured: at 80 x 80, RMS against the union of the bands (DESIGN: exact area)."""
    errors = {}
    for surface, view in CASES[:2]:
        for combine in ("over", "max", "sum"):
            lines = antialiased_hidden_lines(surface, view, SIZE, SIZE, combine=combine, exact=True)
            union = band_union(lines.segments, SIZE, SIZE)
            lit = union > 0
            errors[combine] = np.sqrt(((lines.coverage - union)[lit] ** 2).mean())
        assert errors["over"] < errors["max"] and errors["over"] < errors["sum"]


@pytest.mark.parametrize("view", DEGENERATE_VIEWS)
@pytest.mark.parametrize("size", [1, 2, 7])
def test_degenerate_views_draw_without_raising(view, size):
    for method in ("dislop", "post", "aliased"):
        lines = antialiased_hidden_lines(FLAT, view, size, size, method=method)
        assert lines.image.shape == (size, size)
        assert 0.0 <= lines.coverage.min() and lines.coverage.max() <= 1.0


@pytest.mark.parametrize(
    ("options", "error", "message"),
    [({"method": "wu"}, ValueError, "'method' must be one of"),
     ({"combine": "add"}, ValueError, "'combine' must be one of"),
     ({"background": 2.0}, ValueError, r"'background' must be in \[0, 1\]"),
     ({"intensity": True}, TypeError, "'intensity' must be a real number")],
)  # fmt: skip
def test_bad_line_options_are_named(options, error, message):
    with pytest.raises(error, match=message):
        antialiased_hidden_lines(FLAT, DEGENERATE_VIEWS[1], 8, 8, **options)


# --- smoothed surfaces -----------------------------------------------------------------------


@pytest.mark.parametrize("shading", ["fast_phong", "phong"])
def test_no_silhouettes_is_the_fpa_surface_image(shading):
    surface, view = CASES[0]
    smooth = smoothed_surface(surface, view, SIZE, SIZE, shading=shading, silhouettes="none")
    scene = surface.scene(view, SIZE, SIZE, background=(0.0, 0.0, 0.0))
    fpa = floating_perimeter(surface, view, SIZE, SIZE, "surface", shading=shading, sample="center", scene=scene)  # fmt: skip
    np.testing.assert_array_equal(smooth.image, fpa.image)
    np.testing.assert_array_equal(smooth.aliased, fpa.image)


@pytest.mark.parametrize(("surface", "view"), CASES)
def test_the_dislop_outline_area_is_exact(surface, view):
    smooth = smoothed_surface(surface, view, SIZE, SIZE)
    triangles = screen_triangles(surface, view, SIZE, SIZE)
    exact = area_coverage(list(triangles), SIZE, SIZE, subpixel_bits=None)
    np.testing.assert_allclose(smooth.coverage, exact, atol=1e-9)
    assert outline_loops(smooth.silhouettes, smooth.flags) is not None


@pytest.mark.parametrize(("surface", "view"), CASES)
@pytest.mark.parametrize("silhouettes", ["dislop", "post"])
def test_pixels_off_the_outline_are_unchanged(surface, view, silhouettes):
    smooth = smoothed_surface(surface, view, SIZE, SIZE, silhouettes=silhouettes)
    inside = (smooth.coverage == 1.0) & (smooth.fpa.facet >= 0)
    outside = smooth.coverage == 0.0
    np.testing.assert_array_equal(smooth.image[inside], smooth.aliased[inside])
    np.testing.assert_array_equal(smooth.image[outside], 0.0)
    assert (smooth.image != smooth.aliased).any()
    assert smooth.coverage.min() >= 0.0 and smooth.coverage.max() <= 1.0


# Measured RMS over the boundary pixels (0 < exact area < 1), 80 x 80, Phong, black background,
# against render(..., visibility="abuffer"): Gaussian 0.149 (none) / 0.026 (dislop) / 0.084 (post),
# polynomial(12) 0.078 / 0.020 / 0.047. The factors asserted are those, rounded down.
FACTORS = {"dislop": 3.5, "post": 1.6}


@pytest.mark.parametrize(("surface", "view"), CASES[::2])
@pytest.mark.parametrize("silhouettes", ["dislop", "post"])
def test_the_silhouette_moves_toward_the_abuffer(surface, view, silhouettes):
    reference = render(
        surface.scene(view, SIZE, SIZE, background=(0.0, 0.0, 0.0)), SIZE, SIZE,
        shading="phong", visibility="abuffer",
    ).image  # fmt: skip
    exact = area_coverage(list(screen_triangles(surface, view, SIZE, SIZE)), SIZE, SIZE, subpixel_bits=None)  # fmt: skip
    boundary = (exact > 0) & (exact < 1)

    def rms(image):
        return np.sqrt(((image - reference)[boundary] ** 2).mean())

    aliased = smoothed_surface(surface, view, SIZE, SIZE, shading="phong", silhouettes="none")
    smooth = smoothed_surface(surface, view, SIZE, SIZE, shading="phong", silhouettes=silhouettes)
    assert rms(smooth.image) * FACTORS[silhouettes] < rms(aliased.image)


def test_the_outline_of_a_square_and_its_flags():
    square = np.array([[(0, 0), (2, 0), (2, 2)], [(0, 0), (2, 2), (0, 2)]], float)
    pieces, flags = outline(square)
    # bottom: inside above (0); right, steep: inside at -x (1); top: inside below (1); left: +x (0)
    assert pieces.tolist() == [
        [[0, 0], [2, 0]],
        [[2, 0], [2, 2]],
        [[2, 2], [0, 2]],
        [[0, 2], [0, 0]],
    ]
    assert flags.tolist() == [0, 1, 1, 0]
    (loop,) = outline_loops(pieces, flags)
    assert len(loop) == 4


def test_a_fold_splits_the_outline_where_it_leaves_the_image():
    """Two overlapping squares: the outline is the union's 8 sides, the inner parts are dropped."""
    a = np.array([[(0, 0), (2, 0), (2, 2)], [(0, 0), (2, 2), (0, 2)]], float)
    pieces, flags = outline(np.concatenate([a, a + 1]))
    assert len(pieces) == 8
    lengths = np.hypot(*(pieces[:, 1] - pieces[:, 0]).T)
    assert lengths.sum() == pytest.approx(12.0)
    (loop,) = outline_loops(pieces, flags)
    area = 0.5 * np.sum(loop[:, 0] * np.roll(loop[:, 1], -1) - np.roll(loop[:, 0], -1) * loop[:, 1])
    assert area == pytest.approx(7.0)  # counter-clockwise around the inside


def test_inner_silhouettes_are_box_filtered_when_asked():
    surface, view = CASES[2]
    smooth = smoothed_surface(surface, view, SIZE, SIZE, threshold=0.1)
    assert smooth.inner.any() and smooth.stats.inner == int(smooth.inner.sum())
    assert not (smooth.inner & (smooth.coverage < 1)).any()
    changed = np.any(smooth.image != smoothed_surface(surface, view, SIZE, SIZE).image, axis=2)
    assert changed.any() and (changed <= smooth.inner).all()


@pytest.mark.parametrize("view", DEGENERATE_VIEWS)
@pytest.mark.parametrize("silhouettes", ["dislop", "post", "none"])
def test_degenerate_surfaces_do_not_raise(view, silhouettes):
    for size in (2, 7):
        smooth = smoothed_surface(FLAT, view, size, size, silhouettes=silhouettes, threshold=0.1)
        assert smooth.image.shape == (size, size, 3)
        assert np.isfinite(smooth.image).all()


@pytest.mark.parametrize(
    ("options", "message"),
    [({"silhouettes": "wu"}, "'silhouettes' must be one of"),
     ({"background": (0, 0)}, "'background' must be an RGB triple"),
     ({"background": (0, 0, 2)}, r"'background' must be in \[0, 1\]"),
     ({"threshold": 3.0, "silhouettes": "dislop"}, "'threshold' must be in 0..1")],
)  # fmt: skip
def test_bad_surface_options_are_named(options, message):
    with pytest.raises(ValueError, match=message):
        smoothed_surface(FLAT, DEGENERATE_VIEWS[1], 8, 8, **options)

"""The trace views, headless: set a widget's value, check what the view now holds."""

from types import SimpleNamespace

import matplotlib
import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.text import Text

from scanviz import Recorder, render, scan_convert
from scanviz.abuffer.masks import mask_to_grid
from scanviz.scene.builtin import builtin_scene
from scanviz.widgets import (
    ABufferInspector,
    PolygonEditor,
    ViewingPipelineView,
    interpolation_stepper,
    viewing_stepper,
    zbuffer_stepper,
)
from scanviz.widgets.stepper import Stepper

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def slide():
    return builtin_scene("umbc_zbuffer")


# --- z-buffer ------------------------------------------------------------------------------


def depth_from_events(events, height, width):
    """The depth buffer replayed naively from depth_test events: every pass overwrites."""
    depth = np.full((height, width), np.nan)
    for event in events:
        if event.kind == "depth_test" and event.passed:
            depth[event.y, event.x] = event.z
    return depth


def test_zbuffer_slider_replays_the_depth_tests(slide):
    stepper = zbuffer_stepper(slide, 12, 12)
    view, trace = stepper.views[0], stepper.model.trace
    assert stepper.slider.max == len(trace) == sum(e.kind == "depth_test" for e in trace)
    for step in (0, 1, 20, len(trace) // 2, len(trace)):
        stepper.slider.value = step
        np.testing.assert_array_equal(
            view.depth_image.get_array().filled(np.nan), depth_from_events(trace[:step], 12, 12)
        )
    np.testing.assert_array_equal(
        view.depth_image.get_array().filled(np.inf), view.result.depth
    )  # all steps: the final depth buffer
    np.testing.assert_allclose(view.color_image.get_array(), view.result.image)


def test_zbuffer_current_test_is_marked(slide):
    stepper = zbuffer_stepper(slide, 12, 12)
    view, event = stepper.views[0], stepper.model.trace[9]
    stepper.slider.value = 10
    assert view.current_marker.get_visible()
    assert view.current_marker.get_xy() == (event.x, event.y)


def test_zbuffer_pixel_history_follows_picker_and_step(slide):
    stepper = zbuffer_stepper(slide, 12, 12)
    view, trace = stepper.views[0], stepper.model.trace
    # A pixel two polygons fight over: the third slide polygon pierces the first.
    counts = {}
    for e in trace:
        counts[e.x, e.y] = counts.get((e.x, e.y), 0) + 1
    (x, y), n = max(counts.items(), key=lambda item: item[1])
    assert n >= 2
    view.pixel_text.value = f"{x}, {y}"
    assert view.pixel == (x, y) and view.pixel_marker.get_xy() == (x, y)
    assert view.history.value.count("<tr style=") == n
    first = next(i for i, e in enumerate(trace) if (e.x, e.y) == (x, y))
    stepper.slider.value = first + 1
    assert "background:#ffe9a8" in view.history.value  # that test is highlighted
    assert f"{trace[first].z:.4g}" in view.history.value


def test_zbuffer_bad_pixel_shows_error_and_keeps_pixel(slide):
    view = zbuffer_stepper(slide, 12, 12).views[0]
    before = view.pixel
    view.pixel_text.value = "three, 4"
    assert "two integers" in view.status.value and view.pixel == before
    view.pixel_text.value = "40, 4"
    assert "outside" in view.status.value
    view.pick(5, 5)
    assert view.status.value == "" and view.pixel == (5, 5)


def test_zbuffer_click_picks_pixel(slide):
    view = zbuffer_stepper(slide, 12, 12).views[0]
    view._clicked(SimpleNamespace(inaxes=view.axes[0], xdata=3.7, ydata=6.2))
    assert view.pixel == (3, 6) and view.pixel_text.value == "3, 6"


def test_zbuffer_large_trace_is_filtered_and_says_so(monkeypatch):
    monkeypatch.setattr(Stepper, "MAX_STEPS", 60)
    stepper = zbuffer_stepper(builtin_scene("sphere", level=1), 32, 32)
    view = stepper.views[0]
    assert 0 < len(stepper.model.trace) <= 60
    assert "exceed" in view.note.value or "first 60" in view.note.value


# --- interpolation -------------------------------------------------------------------------


def test_interpolation_tables_and_span_follow_slider():
    stepper = interpolation_stepper("umbc_zbuffer")
    view, trace = stepper.views[0], stepper.model.trace
    k = next(i for i, e in enumerate(trace) if e.kind == "span_values")
    span = trace[k]
    stepper.slider.value = k + 1
    assert view.span_patch.get_visible()
    assert view.span_patch.get_xy() == (span.x_start, span.y)
    assert view.span_patch.get_width() == span.x_end - span.x_start
    row = next(e for e in reversed(trace[:k]) if e.kind == "edge_values")
    assert f"row y = {row.y}" in view.edges.value
    assert view.edges.value.count("<tr style=") == len(row.entries)
    assert f"{row.entries[0].x:.4g}" in view.edges.value
    assert "background:#ffe9a8" in view.spans.value
    setup = next(e for e in reversed(trace[:k]) if e.kind == "polygon_setup")
    assert view.outline.get_xdata()[:-1] == [v[0] for v in setup.vertices]
    stepper.slider.value = 1  # polygon set up, no row yet
    assert not view.span_patch.get_visible() and view.edges.value == ""


# --- a-buffer ------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def cube():
    return render(
        builtin_scene("transparent_cube"),
        48,
        48,
        shading="flat",
        visibility="abuffer",
        trace=Recorder(region=(22, 22, 25, 25)),
    )


def test_abuffer_picker_shows_masks_fragments_and_packer(cube):
    inspector = ABufferInspector(cube)
    for x, y in ((22, 22), (24, 23)):
        inspector.x_box.value, inspector.y_box.value = x, y
        fragments = cube.fragments_at(x, y)
        assert inspector.pixel == (x, y) and inspector.marker.get_xy() == (x, y)
        assert f"{len(fragments)} fragments" in inspector.fragments.value
        assert inspector.fragments.value.count("<tr style=") == len(fragments)
        for k, fragment in enumerate(fragments[: len(inspector.grids)]):
            np.testing.assert_array_equal(
                inspector.grids[k].get_array(), mask_to_grid(fragment.mask, "8x8")
            )
        packed = [e for e in cube.trace.of_kind("pixel_packed") if (e.x, e.y) == (x, y)][-1]
        assert inspector.packer.value.count("<tr style=") == len(packed.steps)
        assert f"alpha {packed.alpha:.4g}" in inspector.packer.value


def test_abuffer_insertion_stepper_shows_before_after(cube):
    inspector = ABufferInspector(cube, pixel=(23, 23))
    inserted = [e for e in cube.trace.of_kind("fragment_inserted") if (e.x, e.y) == (23, 23)]
    stepper = inspector.insertions
    assert stepper.slider.max == len(inserted) > 0
    stepper.slider.value = len(inserted)
    html = stepper.views[0].widget.value
    assert f"case {inserted[-1].case}" in html and f"after</b> ({inserted[-1].after_kind}" in html
    inspector.pick(0, 0)  # outside the traced region: said, not raised
    assert inspector.insertions is None
    inspector.x_box.value = 99
    assert "outside" in inspector.status.value and inspector.pixel == (0, 0)


def test_abuffer_needs_an_abuffer_render(slide):
    with pytest.raises(ValueError, match="visibility='abuffer'"):
        ABufferInspector(render(slide, 12, 12, trace=Recorder()))


# --- viewing pipeline ----------------------------------------------------------------------


@pytest.fixture(scope="module")
def viewing():
    from scanviz.transform.examples import viewing_scene

    scene = viewing_scene()
    stepper = viewing_stepper(scene, 64, 64)
    return scene, stepper, stepper.views[0]


def step_of(view, kind, stage=None):
    """The stepper step that shows the event of `kind` (and `stage`), counted from 1."""
    return 1 + next(
        i
        for i, e in enumerate(view.trace)
        if e.kind == kind and getattr(e, "stage", stage) == stage
    )


def test_viewing_stepper_starts_in_world_space_and_ends_on_the_screen(viewing):
    scene, stepper, view = viewing
    stepper.slider.value = 0
    assert view.space == "world" and view.matrix is None
    assert "no matrix" in view.step_table.value
    world = np.array(scene.camera.eye)
    np.testing.assert_allclose(np.array(view.eye_marker.get_data_3d()).T, [world])
    stepper.slider.value = len(view.trace)
    assert view.space == "display"
    assert len(view.screen.get_paths()) == 7  # 3 cube faces and 4 floor tiles reach the screen
    assert not view.screen_note.get_visible()


def test_the_matrix_beside_the_eye_step_is_the_look_at_matrix(viewing):
    scene, stepper, view = viewing
    stepper.slider.value = step_of(view, "polygons_transformed", "eye")
    eye, target = np.array(scene.camera.eye), np.array(scene.camera.look_at)
    backward = (eye - target) / np.linalg.norm(eye - target)
    right = np.cross(scene.camera.up, backward)
    right /= np.linalg.norm(right)
    rows = np.array([right, np.cross(backward, right), backward])
    expected = np.eye(4)
    expected[:3, :3], expected[:3, 3] = rows, -rows @ eye
    np.testing.assert_allclose(view.matrix, expected, atol=1e-12)
    assert "eye_from_world" in view.step_table.value
    assert f"<td style='padding:0 6px;text-align:right'>{expected[2, 3]:.4g}</td>" in (
        view.step_table.value
    )  # -|eye - look_at|, to 4 digits


def test_culling_marks_the_faces_turned_away(viewing):
    scene, stepper, view = viewing
    cube = scene.objects[0]
    world = cube.mesh.positions @ cube.world_from_model[:3, :3].T + cube.world_from_model[:3, 3]
    away = set()
    for number, face in enumerate(cube.mesh.faces):
        corners = world[list(face)]
        normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
        if normal @ (corners.mean(axis=0) - scene.camera.eye) >= 0:
            away.add(number)
    stepper.slider.value = step_of(view, "polygons_transformed", "eye")  # culling is done
    assert view.culled == away
    assert len(view.culled_faces.get_paths()) == len(away)
    assert away.isdisjoint(view.shown)
    first = step_of(view, "face_culled")  # the first test: the culled face is shown with its reason
    stepper.slider.value = first
    assert "N · V" in stepper.narration.value
    assert ("culled" in view.step_table.value) == (0 in away)
    assert len(view.test_vectors.get_segments()) == 2  # V and N are drawn
    stepper.slider.value = len(view.trace)
    assert away.isdisjoint(view.shown) and len(view.culled_faces.get_paths()) == 0


def test_after_the_divide_every_polygon_is_in_the_box_and_new_vertices_on_its_faces(viewing):
    _, stepper, view = viewing
    stepper.slider.value = step_of(view, "polygons_transformed", "ndc")
    assert view.space == "ndc"
    for points in view.shown.values():
        assert np.all(np.abs(points[:, :2]) <= 1 + 1e-12)
        assert np.all((points[:, 2] >= -1e-12) & (points[:, 2] <= 1 + 1e-12))
    marks = np.array(view.markers.get_data_3d()).T
    assert len(marks) > 0
    on_a_face = np.minimum.reduce(
        [np.abs(np.abs(marks[:, 0]) - 1), np.abs(np.abs(marks[:, 1]) - 1), np.abs(marks[:, 2] - 1)]
    )
    np.testing.assert_allclose(on_a_face, 0, atol=1e-12)  # the floor is cut by the sides and far
    np.testing.assert_allclose(np.abs(view.corners[:, :2]), 1, atol=1e-12)  # the box
    assert set(np.round(view.corners[:, 2], 12)) == {0.0, 1.0}


def test_clipping_steps_show_the_cut_pieces_and_say_which_planes(viewing):
    _, stepper, view = viewing
    steps = [i + 1 for i, e in enumerate(view.trace) if e.kind == "polygon_clipped"]
    verdicts = [view.trace[k - 1].verdict for k in steps]
    assert verdicts == ["accepted"] * 3 + ["clipped"] * 4 + ["rejected"]
    stepper.slider.value = steps[3]  # the first floor tile is cut
    assert view.space == "clip"
    assert len(view.cut_off.get_segments()) == 1  # its outline before the cut, dashed
    assert "clipper cuts" in stepper.narration.value and "plane" in stepper.narration.value
    assert "outcode" in view.step_table.value
    assert len(np.array(view.markers.get_data_3d()).T) == len(view.new_vertices[6]) > 0
    stepper.slider.value = steps[-1]
    assert "rejected" in stepper.narration.value and "right plane" in stepper.narration.value
    assert 10 not in view.shown  # the flag is gone


def test_every_step_is_narrated_in_plain_words_and_tables_show_few_rows(viewing):
    _, stepper, view = viewing
    for step in range(len(view.trace) + 1):
        stepper.slider.value = step
        sentence = view.narrate(step)
        assert sentence and sentence.endswith(".")
        for text in (sentence, view.step_table.value, view.vertex_table.value):
            assert "array(" not in text and "np." not in text and "e-1" not in text
        assert view.vertex_table.value.count("<tr style=") <= 6


def drawn_texts(figure, monkeypatch):
    """(text, window box) of every non-empty text drawn, boxes taken while it is drawn.

    mplot3d places its tick labels during the draw only, so the boxes are read then.
    """
    seen = []
    draw = Text.draw

    def recording(text, renderer):
        draw(text, renderer)
        if text.get_visible() and text.get_text():
            seen.append((text, text.get_window_extent(renderer)))

    with monkeypatch.context() as patch:
        patch.setattr(Text, "draw", recording)
        FigureCanvasAgg(figure).draw()  # the widget shows PNGs drawn by Agg
    return seen


def test_viewing_figure_text_is_legible_and_nothing_overlaps(viewing, monkeypatch):
    _, stepper, view = viewing
    for stage in ("world", "eye", "clip", "ndc", "display"):
        stepper.slider.value = (
            0 if stage == "world" else step_of(view, "polygons_transformed", stage)
        )
        texts = drawn_texts(view.figure, monkeypatch)
        assert len(texts) > 15  # titles, axis labels, tick labels
        for text, _ in texts:
            assert text.get_fontsize() >= 9, (stage, text.get_text())
        for i, (a, box_a) in enumerate(texts):
            for b, box_b in texts[i + 1 :]:
                assert not box_a.overlaps(box_b), (stage, a.get_text(), b.get_text())


def test_viewing_view_of_a_scene_still_works_alone():
    view = ViewingPipelineView(builtin_scene("sphere", level=0), 32, 32)
    assert view.space == "world" and len(view.trace) == 1 + 20 + 2 + 8 + 2 - 1
    assert view.widget.children


# --- polygon editor ------------------------------------------------------------------------


def test_editor_text_rescans_and_bad_text_is_reported():
    editor = PolygonEditor([(0, 0), (4, 0), (4, 3)], 6, 5)
    editor.text.value = "1,1 5,1 5,4 1,4"
    expected = scan_convert([(1, 1), (5, 1), (5, 4), (1, 4)], 6, 5).mask
    np.testing.assert_array_equal(editor.coverage.get_array(), expected)
    assert editor.error.value == ""
    assert editor.active_edges.value.count("<tr style=") == 3  # rows 1, 2, 3
    for bad in ("1,1 5,1 x,4", "1,1 2,2", "1,1 5,1 nan,3"):
        editor.text.value = bad
        assert editor.error.value != ""
        np.testing.assert_array_equal(editor.coverage.get_array(), expected)


def test_editor_drag_moves_a_vertex():
    editor = PolygonEditor([(0, 0), (4, 0), (4, 3)], 6, 5)
    at = {"inaxes": editor.ax, "button": 1}
    editor._pressed(SimpleNamespace(xdata=4.2, ydata=2.9, **at))
    editor._moved(SimpleNamespace(xdata=5.5, ydata=4.5, **at))
    editor._released(SimpleNamespace(xdata=6.0, ydata=5.0, **at))
    assert editor.text.value == "0,0 4,0 6,5"
    np.testing.assert_array_equal(
        editor.coverage.get_array(), scan_convert([(0, 0), (4, 0), (6, 5)], 6, 5).mask
    )

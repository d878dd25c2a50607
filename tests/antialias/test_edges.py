"""Anti-aliased feature edges: the runs render(edges=True) paints, post-anti-aliased over the image."""

import dataclasses

import numpy as np
import pytest

from scanviz import render
from scanviz.antialias import dislop_line
from scanviz.antialias.post_edges import antialiased_edges, feature_edge_segments
from scanviz.pipeline.feature_lines import feature_edge_runs
from scanviz.scene.builtin import builtin_scene


def binary_dilation(mask, iterations):
    """`mask` grown by `iterations` pixels in all 8 directions (a square), one step at a time."""
    grown = mask.copy()
    for _ in range(iterations):
        step = grown.copy()
        step[1:] |= grown[:-1]
        step[:-1] |= grown[1:]
        grown = step.copy()
        step[:, 1:] |= grown[:, :-1]
        step[:, :-1] |= grown[:, 1:]
        grown = step
    return grown


WORST_TABLE_ERROR = 0.013527  # the 51 x 51 x 3 line table against DISLOP_L (docs/antialiasing.md)


def white(name):
    return dataclasses.replace(builtin_scene(name), background=(1.0, 1.0, 1.0))


@pytest.mark.parametrize("name", ["sphere", "painter", "umbc_zbuffer"])
def test_every_aliased_edge_pixel_is_darkened_and_nothing_far_from_an_edge_changes(name):
    scene = white(name)
    plain, aliased = render(scene, 120, 96), render(scene, 120, 96, edges=True)
    for method in ("post", "dislop"):
        smooth = antialiased_edges(scene, plain, method=method)
        edges = aliased.record.edges
        darker = (smooth < plain.image - 1e-12).any(axis=2)
        # Between its ends an aliased pixel is within a pixel of the true line, so the band reaches
        # it. An end pixel need not be: the midpoint line runs between floor(ends), up to a pixel
        # past an edge whose end is just below an integer.
        ends = np.zeros_like(edges)
        for run in feature_edge_runs(scene, plain.depth, 120, 96):
            ends[run.ys[[0, -1]], run.xs[[0, -1]]] = len(run.xs) > 0
        lit = edges & ~ends & (plain.image > 1e-9).any(axis=2)
        assert lit.sum() > 50 and darker[lit].all()
        # the band (half a pixel each side of a line within a pixel of the aliased one) stays
        # within two pixels of it, diagonals included
        near = binary_dilation(edges, iterations=2)
        assert np.array_equal(smooth[~near], plain.image[~near])  # the rest is untouched
        assert (smooth <= plain.image + 1e-12).all() and (smooth >= 0).all()


def test_post_is_within_the_table_error_of_dislop_per_covering_segment():
    scene = white("sphere")
    plain = render(scene, 160, 128)
    segments = feature_edge_segments(scene, plain.depth)
    covering = sum((dislop_line(a, b, 160, 128) > 0).astype(int) for a, b in segments)
    post = antialiased_edges(scene, plain, method="post")
    dislop = antialiased_edges(scene, plain, method="dislop")
    gap = np.abs(post - dislop).max(axis=2)
    # |prod(1 - a) - prod(1 - b)| <= sum |a - b|: one table error per segment over the pixel
    assert (gap <= WORST_TABLE_ERROR * covering + 1e-12).all() and gap.max() > 0


def test_a_wholly_visible_edge_keeps_its_sub_pixel_ends():
    scene = builtin_scene("umbc_zbuffer")
    plain = render(scene, 80, 60)
    runs = [
        r for r in feature_edge_runs(scene, plain.depth, 80, 60) if r.shown.all() and len(r.xs) > 5
    ]
    segments = feature_edge_segments(scene, plain.depth)
    assert runs
    for run in runs:
        inside = ((run.ends >= 0) & (run.ends < (80, 60))).all()
        if inside:  # not clipped by the raster: the segment is the edge itself
            assert any(np.allclose(s, run.ends, atol=1e-12) for s in segments)


def test_hidden_parts_of_an_edge_are_left_out():
    scene = white("painter")
    plain = render(scene, 120, 96)
    runs = list(feature_edge_runs(scene, plain.depth, 120, 96))
    split = [r for r in runs if r.shown.any() and not r.shown.all()]
    assert split  # some edges pass behind a nearer polygon
    segments = feature_edge_segments(scene, plain.depth)
    pieces = sum(
        int(np.count_nonzero(np.diff(np.r_[0, r.shown.astype(int), 0]) == 1)) for r in runs
    )
    assert len(segments) == pieces


def test_a_render_with_aliased_edges_and_bad_methods_are_refused():
    scene = builtin_scene("sphere")
    with pytest.raises(ValueError, match="edges=False"):
        antialiased_edges(scene, render(scene, 16, 16, edges=True))
    with pytest.raises(ValueError, match="'method'"):
        antialiased_edges(scene, render(scene, 16, 16), method="wu")


def test_a_scene_with_no_edge_on_the_raster_is_its_image():
    scene = builtin_scene("sphere")
    tiny = render(scene, 1, 1)
    assert np.array_equal(antialiased_edges(scene, tiny), tiny.image)

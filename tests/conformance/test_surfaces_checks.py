"""The conformance category of the FPA fails when the facet order or the edge rule is wrong."""

import numpy as np

from scanviz.conformance.surfaces_checks import fpa_vs_zbuffer
from scanviz.surfaces import perimeter
from scanviz.surfaces.facet_edges import FacetEdges


def test_a_back_to_front_order_is_caught(monkeypatch):
    order = perimeter.facet_polygons
    monkeypatch.setattr(perimeter, "facet_polygons", lambda *args: order(*args)[::-1])
    outcome = fpa_vs_zbuffer(np.random.default_rng(0))
    assert not outcome.passed and "facets: pixel" in outcome.failure


def test_an_edge_processed_twice_is_caught(monkeypatch):
    edges = perimeter.facet_edges

    def twice(enumeration):
        e = edges(enumeration)
        doubled = np.vstack([e.edges, e.edges[-1:]])  # the last facet's last edge again
        return FacetEdges(doubled, np.append(e.facet, e.facet[-1]), e.taken)

    monkeypatch.setattr(perimeter, "facet_edges", twice)
    outcome = fpa_vs_zbuffer(np.random.default_rng(0))
    assert not outcome.passed and "edges processed of" in outcome.failure

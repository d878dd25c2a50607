"""Grid surfaces z = f(x, y) (Wang 1989, ch. 2): grids, the database format, meshes, the view,
the floating horizon, and the Floating Perimeter Algorithm's viewing cases, facet enumeration and
the edges each facet processes."""

from .enumeration import (
    Enumeration,
    enumerate_facets,
    facet_sequence,
    region_classes,
    viewing_case,
    vp_cell,
)
from .facet_edges import FacetEdges, facet_edges
from .grid import (
    BUILTIN_SURFACES,
    GridSurface,
    gaussian,
    gaussian_height,
    polynomial,
    polynomial_height,
    random_surface,
    rogers,
    rogers_height,
)
from .horizon import HorizonResult, HorizonStats, floating_horizon
from .view import View

__all__ = [
    "BUILTIN_SURFACES",
    "Enumeration",
    "FacetEdges",
    "GridSurface",
    "HorizonResult",
    "HorizonStats",
    "View",
    "gaussian",
    "gaussian_height",
    "polynomial",
    "polynomial_height",
    "random_surface",
    "rogers",
    "rogers_height",
    "enumerate_facets",
    "facet_edges",
    "facet_sequence",
    "floating_horizon",
    "region_classes",
    "viewing_case",
    "vp_cell",
]

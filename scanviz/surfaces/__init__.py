"""Grid surfaces z = f(x, y) (Wang 1989, ch. 2): grids, the database format, meshes, the view,
the floating horizon, and the Floating Perimeter Algorithm (viewing cases, facet enumeration, the
edges each facet processes, the perimeter test, hidden lines and hidden surfaces), checked against
the z-buffer."""

from .complex import (
    DEFAULT_CLIP,
    THREE_POLES_TWO_ZEROS,
    ComplexSurface,
    RationalFunction,
    complex_surface,
    phase_scene,
    three_poles_two_zeros,
)
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
from .perimeter import (
    FacetOrder,
    Perimeter,
    PerimeterResult,
    PerimeterStats,
    facet_polygons,
    floating_perimeter,
)
from .reference import SurfaceResults, ZBufferComparison, compare_with_zbuffer, surface_results
from .view import View

__all__ = [
    "DEFAULT_CLIP",
    "THREE_POLES_TWO_ZEROS",
    "ComplexSurface",
    "RationalFunction",
    "complex_surface",
    "phase_scene",
    "three_poles_two_zeros",
    "BUILTIN_SURFACES",
    "Enumeration",
    "FacetEdges",
    "GridSurface",
    "HorizonResult",
    "HorizonStats",
    "FacetOrder",
    "Perimeter",
    "PerimeterResult",
    "PerimeterStats",
    "ZBufferComparison",
    "View",
    "gaussian",
    "gaussian_height",
    "polynomial",
    "polynomial_height",
    "random_surface",
    "rogers",
    "rogers_height",
    "compare_with_zbuffer",
    "surface_results",
    "SurfaceResults",
    "enumerate_facets",
    "facet_edges",
    "facet_polygons",
    "facet_sequence",
    "floating_horizon",
    "floating_perimeter",
    "region_classes",
    "viewing_case",
    "vp_cell",
]

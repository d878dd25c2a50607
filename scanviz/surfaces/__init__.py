"""Grid surfaces z = f(x, y) (Wang 1989, ch. 2): grids, the database format, meshes."""

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

__all__ = [
    "BUILTIN_SURFACES",
    "GridSurface",
    "gaussian",
    "gaussian_height",
    "polynomial",
    "polynomial_height",
    "random_surface",
    "rogers",
    "rogers_height",
]

"""Conformance of the grid-surface algorithms: the FPA's hidden surfaces are the z-buffer's.

On seeded random grid surfaces (uniform and non-uniform planes, rough and
smooth heights) seen from all nine viewing cases, in perspective and
parallel views: the coverage-mask FPA (`floating_perimeter(...,
mode="surface")`) must show the z-buffer's facet at every pixel (its
enumeration is claimed to be a valid occlusion order); every grid edge must
be processed exactly once; and the traced lines-mode reference must decide
every raster point as the compiled pass does.
"""

from __future__ import annotations

import numpy as np

from ..pipeline import render
from ..surfaces import GridSurface, View, floating_perimeter
from .cases import Outcome, Tally, thousands

SURFACES = 18
TRACED = 4  # surfaces whose lines mode also runs traced
OUTSIDE = (-1, 0, 1)  # where the viewpoint lies along each axis: before, over, after the domain


def _surface(rng: np.random.Generator) -> GridSurface:
    nx, ny = (int(n) for n in rng.integers(2, 9, 2))
    x = np.sort(rng.choice(np.arange(40), nx, replace=False)).astype(float) / 10
    y = np.sort(rng.choice(np.arange(40), ny, replace=False)).astype(float) / 10
    rough = rng.random((ny, nx)) * rng.uniform(0.2, 3)
    smooth = np.sin(x[None, :] * rng.uniform(0.5, 3)) * np.cos(y[:, None] * rng.uniform(0.5, 3))
    return GridSurface(x, y, rough if rng.random() < 0.5 else smooth)


def _view(rng: np.random.Generator, surface: GridSurface, case: int) -> View:
    """A viewpoint in the region of `case` (0-8: the nine placements), looking at the grid."""
    low, high = np.array([surface.x[0], surface.y[0]]), np.array([surface.x[-1], surface.y[-1]])
    side = np.array([OUTSIDE[case % 3], OUTSIDE[case // 3]])
    span = (high - low).max()
    inside = rng.uniform(low, high)
    point = np.where(
        side < 0,
        low - span * rng.uniform(1, 3),
        np.where(side > 0, high + span * rng.uniform(1, 3), inside),
    )
    top = float(surface.z.max())
    height = (
        top + span * rng.uniform(2, 4) if (side == 0).all() else top + span * rng.uniform(-0.2, 1.5)
    )
    target = np.array([*(low + high) / 2, float(surface.z.mean())])
    eye = np.array([*point, height])
    projection = "parallel" if rng.random() < 0.3 else "perspective"
    return View(tuple(eye.tolist()), tuple((target - eye).tolist()), projection)


def fpa_vs_zbuffer(rng: np.random.Generator) -> Outcome:
    """The FPA's hidden surfaces against the z-buffer, its edges, and its traced reference."""
    tally, pixels, runs, points = Tally(), 0, 0, 0
    for index in range(SURFACES):
        surface = _surface(rng)
        for case in range(9):
            view = _view(rng, surface, case)
            width, height = (int(n) for n in rng.integers(8, 48, 2))
            label = f"surface {index} ({surface.nx}x{surface.ny}), view {view}, {width}x{height}"
            try:
                fpa = floating_perimeter(surface, view, width, height, "surface", shading="flat")
            except ValueError as error:  # a perspective eye too close to a tall surface: refused
                tally.check("in front of the viewpoint" in str(error), f"{label}: {error}")
                continue
            z = render(surface.scene(view, width, height), width, height, shading="flat")
            runs += 1
            pixels += width * height
            tally.check(
                z.stats.clipped == 0, f"{label}: the scene clipped {z.stats.clipped} polygons"
            )
            tally.same(fpa.facet, np.where(z.polygon >= 0, z.polygon // 2, -1), f"{label}: facets")
            lines = floating_perimeter(surface, view, width, height)
            points += lines.stats.points
            tally.check(
                len(lines.edges.edges) == surface.edges
                and len({tuple(e) for e in lines.edges.edges.tolist()}) == surface.edges,
                f"{label}: {len(lines.edges.edges)} edges processed of {surface.edges}",
            )
            if index < TRACED:
                traced = floating_perimeter(surface, view, width, height, trace=True)
                tally.same(traced.visible, lines.visible, f"{label}: traced point flags")
    return tally.outcome(
        f"{thousands(pixels)} pixels / {thousands(points)} edge points / {runs} views"
    )

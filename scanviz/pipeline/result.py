"""What `render` returns: the image and buffers, the counts of what ran, and the plan."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..scene.model import Light, Material, Scene
from ..trace import Trace
from ..trace.display import RichDisplay


@dataclass(frozen=True)
class Stage:
    name: str
    runs: bool
    why: str


@dataclass(frozen=True)
class RenderPlan:
    """Which stages run for this scene and which are skipped, with the reason."""

    stages: tuple[Stage, ...]

    def __str__(self) -> str:
        width = max(len(s.name) for s in self.stages)
        return "\n".join(
            f"{'run ' if s.runs else 'skip'}  {s.name:<{width}}  {s.why}" for s in self.stages
        )

    def runs(self, name: str) -> bool:
        return any(s.name == name and s.runs for s in self.stages)


@dataclass
class RenderStats(RichDisplay):
    """What ran: polygon counts through the stages, and the z-buffer's work."""

    objects: int = 0
    polygons_in: int = 0
    culled: int = 0
    off_screen: int = 0
    clipped: int = 0
    accepted: int = 0
    polygons_drawn: int = 0
    fragments_estimated: int = 0
    rows_scanned: int = 0
    spans: int = 0
    fragments: int = 0
    depth_passed: int = 0
    depth_failed: int = 0
    shaded_vertices: int = 0
    shaded_pixels: int = 0
    edge_pixels: int = 0
    path: str = "compiled"


@dataclass(frozen=True, eq=False)
class PixelRecord:
    """What the image function needs besides the per-pixel buffers, kept by `render` for `relight`.

    The per-pixel part is the visibility's own buffers: ``RenderResult.polygon``
    and, for Phong and Gooch, ``RenderResult.visibility.values`` (H, W, 15):
    the interpolated normal, world position and material of the visible
    surface (docs/relight.md).
    """

    scene: Scene  # camera, lights, ambient and background of this image
    shading: str
    visibility: str
    polygon_object: np.ndarray  # (P,) int64: the scene object of each drawn polygon
    edges: np.ndarray | None  # (H, W) bool: pixels the feature edges drew black
    stages: tuple[Stage, ...]  # the preparation's stages, for the plan
    materials: Mapping[int, Material] = field(default_factory=dict)  # objects made of one material


@dataclass(frozen=True)
class RenderResult:
    """image (H, W, 3) float64 in [0, 1], row 0 at the bottom; depth (H, W) float64 (+inf: empty);
    polygon (H, W) int64 index into the drawn polygons (-1: background); record what `relight` reads."""

    image: np.ndarray
    depth: np.ndarray
    polygon: np.ndarray
    stats: RenderStats
    plan: RenderPlan
    trace: Trace | None = field(default=None)
    alpha: np.ndarray | None = field(default=None)  # (H, W) packed coverage (a-buffer only)
    abuffer: object = field(default=None)  # the a-buffer's result: .pixel(x, y) lists fragments
    visibility: object = field(
        default=None
    )  # the opaque algorithm's VisibilityResult (order, stats)
    record: PixelRecord | None = field(default=None)  # what `relight` recomputes the image from

    def fragments_at(self, x: int, y: int) -> tuple:
        """The a-buffer's fragment list of pixel (x, y) after insertion (a-buffer renders only)."""
        if self.abuffer is None:
            raise ValueError("fragments_at needs a render with visibility='abuffer' or 'flawed'")
        return self.abuffer.pixel(x, y)

    def relight(
        self,
        lights: Sequence[Light] | None = None,
        materials: Mapping[int, Material] | Sequence[Material | None] | None = None,
        shading: str | None = None,
        ambient: Sequence[float] | None = None,
    ) -> RenderResult:
        """The image again from the kept per-pixel record, under new lights, materials or shading.

        Only the image function runs (thesis ch. 7): no preparation, clipping
        or visibility. The result equals, bit for bit, a fresh `render` of the
        scene with those lights, ambient light and materials (the same size
        and options), except that it has no trace and keeps this render's
        stats; it can be relit again.

        Parameters
        ----------
        lights : sequence of Light, optional
            Replace the scene's lights (an empty tuple: ambient light only).
        materials : mapping of int to Material, or sequence of Material or None, optional
            Make object ``i`` wholly of ``materials[i]``: its own material and
            its mesh's face and vertex materials are replaced by that one.
            A sequence has one entry per scene object, None to keep one.
        shading : {"phong", "gooch"}, optional
            Both shade from the same kept normal, position and material.
        ambient : (3,) sequence of float in [0, 1], optional
            Replace the scene's ambient light.

        Returns
        -------
        RenderResult

        Raises
        ------
        ValueError
            For a render that cannot be relit: flat and Gouraud colors are
            fixed before visibility, and the a-buffer's ('abuffer', 'flawed')
            are packed from every fragment; re-render those with `render`.
        TypeError, ValueError
            On a bad argument, naming it and the rule.
        scanviz.limits.ResourceLimitError
            If the shading's temporaries would go over the memory limit.

        Examples
        --------
        >>> from scanviz import load_scene, render
        >>> from scanviz.scene import Light
        >>> result = render(load_scene("builtin:sphere"), 16, 16)
        >>> dim = result.relight(lights=(Light(color=(0.2, 0.2, 0.2)),))
        >>> bool(dim.image.mean() < result.image.mean())
        True
        >>> bool((result.relight().image == result.image).all())
        True
        """
        from .relight import _relight

        return _relight(self, lights, materials, shading, ambient)

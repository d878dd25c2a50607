"""What `render` returns: the image and buffers, the counts of what ran, and the plan."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..trace import Trace


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
class RenderStats:
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


@dataclass(frozen=True)
class RenderResult:
    """image (H, W, 3) float64 in [0, 1], row 0 at the bottom; depth (H, W) float64 (+inf: empty);
    polygon (H, W) int64 index into the drawn polygons (-1: background)."""

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

    def fragments_at(self, x: int, y: int) -> tuple:
        """The a-buffer's fragment list of pixel (x, y) after insertion (a-buffer renders only)."""
        if self.abuffer is None:
            raise ValueError("fragments_at needs a render with visibility='abuffer' or 'flawed'")
        return self.abuffer.pixel(x, y)

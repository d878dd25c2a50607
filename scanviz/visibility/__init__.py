"""Visibility: the z-buffer (traced reference and compiled twin)."""

from .zbuffer import ScreenPolygons, ZBufferResult, ZBufferStats, zbuffer

__all__ = ["ScreenPolygons", "ZBufferResult", "ZBufferStats", "zbuffer"]

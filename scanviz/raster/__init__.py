"""Rasterization: ET/AET scan conversion, edge functions, midpoint lines, compiled kernels."""

from .api import ScanResult, scan_convert

__all__ = ["ScanResult", "scan_convert"]

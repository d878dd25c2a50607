"""Views of traces for notebooks. They draw what the core computed; they never compute it."""

from .static import plot_scan

__all__ = ["plot_scan"]

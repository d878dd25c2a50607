"""Views of traces for notebooks. They draw what the core computed; they never compute it."""

from .abuffer import ABufferInspector, FragmentInsertionView, PackerView
from .clip import plot_clip
from .editor import PolygonEditor
from .lines import LineView, line_stepper
from .model import StepModel
from .scan import ScanConversionView, scan_conversion_stepper
from .static import plot_scan
from .stepper import Stepper, View, figure_widget, redraw_time, refresh_figure
from .viewing import ViewingPipelineView
from .zbuffer import InterpolationView, ZBufferView, interpolation_stepper, zbuffer_stepper

__all__ = [
    "ABufferInspector",
    "FragmentInsertionView",
    "InterpolationView",
    "LineView",
    "PackerView",
    "PolygonEditor",
    "ScanConversionView",
    "StepModel",
    "Stepper",
    "View",
    "ViewingPipelineView",
    "ZBufferView",
    "figure_widget",
    "interpolation_stepper",
    "line_stepper",
    "plot_clip",
    "plot_scan",
    "redraw_time",
    "refresh_figure",
    "scan_conversion_stepper",
    "zbuffer_stepper",
]

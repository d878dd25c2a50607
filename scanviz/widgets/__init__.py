"""Views of traces for notebooks. They draw what the core computed; they never compute it."""

from .abuffer import ABufferInspector, FragmentInsertionView, PackerView
from .antialias import (
    DislopView,
    dislop_stepper,
    plot_coverage_comparison,
    plot_period_table,
    plot_post_antialias,
    plot_ropiness,
)
from .bsp import BspView, bsp_stepper
from .clip import plot_clip
from .depth_sort import DepthSortView, PainterView, depth_sort_stepper, painter_stepper
from .editor import PolygonEditor
from .fast_phong import FastPhongView, fast_phong_stepper
from .fill import FillView, fill_stepper
from .lines import LineView, line_stepper
from .model import StepModel
from .relight import RelightView, light_direction, relight_widget
from .scan import ScanConversionView, scan_conversion_stepper
from .scanline_visibility import ScanlineVisibilityView, scanline_visibility_stepper
from .static import SamplingView, plot_scan, sampling_view
from .stepper import Stepper, View, figure_widget, redraw_time, refresh_figure
from .surfaces import (
    HorizonView,
    PerimeterView,
    horizon_stepper,
    perimeter_stepper,
    plot_grid,
    plot_mismatch,
    plot_results,
)
from .viewing import ViewingPipelineView, viewing_stepper
from .visibility import algorithm_names, compare_visibility, split_pieces, taxonomy_table
from .warnock import WarnockView, warnock_stepper
from .zbuffer import InterpolationView, ZBufferView, interpolation_stepper, zbuffer_stepper

__all__ = [
    "ABufferInspector",
    "DislopView",
    "dislop_stepper",
    "plot_coverage_comparison",
    "plot_period_table",
    "plot_post_antialias",
    "plot_ropiness",
    "FastPhongView",
    "fast_phong_stepper",
    "FillView",
    "fill_stepper",
    "RelightView",
    "light_direction",
    "relight_widget",
    "BspView",
    "DepthSortView",
    "FragmentInsertionView",
    "HorizonView",
    "InterpolationView",
    "LineView",
    "PackerView",
    "PainterView",
    "PerimeterView",
    "PolygonEditor",
    "ScanConversionView",
    "ScanlineVisibilityView",
    "StepModel",
    "Stepper",
    "View",
    "ViewingPipelineView",
    "WarnockView",
    "ZBufferView",
    "algorithm_names",
    "bsp_stepper",
    "compare_visibility",
    "depth_sort_stepper",
    "figure_widget",
    "horizon_stepper",
    "interpolation_stepper",
    "line_stepper",
    "painter_stepper",
    "perimeter_stepper",
    "plot_clip",
    "plot_grid",
    "plot_mismatch",
    "plot_results",
    "plot_scan",
    "SamplingView",
    "sampling_view",
    "redraw_time",
    "refresh_figure",
    "scan_conversion_stepper",
    "scanline_visibility_stepper",
    "split_pieces",
    "taxonomy_table",
    "viewing_stepper",
    "warnock_stepper",
    "zbuffer_stepper",
]

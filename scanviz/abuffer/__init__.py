"""The a-buffer: exact pixel coverage, pixel masks and fragments (DESIGN §1)."""

from .area import area_coverage, pixel_areas
from .masks import (
    MASK_LAYOUTS,
    MaskResult,
    full_mask,
    mask_buffer_rows,
    mask_to_grid,
    pixel_masks,
    popcount,
    subsample_positions,
)
from .resolve import ABufferResult, ABufferStats, FragmentRecord, Fragments, resolve

__all__ = [
    "ABufferResult",
    "ABufferStats",
    "FragmentRecord",
    "Fragments",
    "resolve",
    "MASK_LAYOUTS",
    "MaskResult",
    "area_coverage",
    "full_mask",
    "mask_buffer_rows",
    "mask_to_grid",
    "pixel_areas",
    "pixel_masks",
    "popcount",
    "subsample_positions",
]

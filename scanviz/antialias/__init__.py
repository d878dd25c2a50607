"""Area-sampling anti-aliasing: Wang's DISLOP algorithms (1989, ch. 4).

`dislop_line` (DISLOP_L), `dislop_edge` (DISLOP_E), `dislop_circle`
(DISLOP_C) and `dislop_disk` (DISLOP_S) return the covered area of every
pixel, computed column by column from the slope and the distance of the line
from the middle pixel's centre. `post_antialias` reads the same areas from the
51 x 51 x 3 tables of `scanviz.antialias.tables` and blends them over an
already rendered image (§4.8). See docs/antialiasing.md.
"""

from ..trace.events import DislopColumn, PostColumn
from .circle import dislop_circle, dislop_disk
from .edge_algorithm import dislop_edge
from .line import dislop_line
from .post import post_antialias, silhouette_mask

__all__ = [
    "DislopColumn",
    "PostColumn",
    "dislop_circle",
    "dislop_disk",
    "dislop_edge",
    "dislop_line",
    "post_antialias",
    "silhouette_mask",
]

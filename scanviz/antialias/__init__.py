"""Area-sampling anti-aliasing: Wang's DISLOP algorithms (1989, ch. 4).

`dislop_line` (DISLOP_L), `dislop_edge` (DISLOP_E), `dislop_circle`
(DISLOP_C) and `dislop_disk` (DISLOP_S) return the covered area of every
pixel, computed column by column from the slope and the distance of the line
from the middle pixel's centre. See docs/antialiasing.md.
"""

from ..trace.events import DislopColumn
from .circle import dislop_circle, dislop_disk
from .edge import dislop_edge
from .line import dislop_line

__all__ = ["DislopColumn", "dislop_circle", "dislop_disk", "dislop_edge", "dislop_line"]

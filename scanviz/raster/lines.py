"""The midpoint line algorithm (UMBC CMSC 435 slides; Bresenham 1965), all eight octants.

For 0 <= slope <= 1 the slides write the line implicitly,

    f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0,

positive above the line, and draw one pixel per column: at each x the next
pixel is east (E) or north-east (NE), whichever is nearer the line, decided by
the sign of f at the midpoint (x + 1, y + 1/2) between them::

    y = y0; d = f(x0 + 1, y0 + 0.5)
    for x = x0 to x1:
        draw (x, y)
        if d < 0: y += 1; d += (x1 - x0) + (y0 - y1)    # NE
        else:     d += (y0 - y1)                         # E

Here d is doubled so that everything is an integer. Other directions map to
this case by symmetry: the axis with the larger extent is the major one
(stepped once per pixel), the other is the minor one, and each moves in the
direction of its sign. E becomes the "axial" step, NE the "diagonal" one.

Endpoints: both are drawn; x0 == x1 and y0 == y1 draws one pixel.
Ties: d == 0 means the line passes exactly through the midpoint. The slides
then step E, keeping the smaller y; scanviz keeps that rule in every octant --
a tie takes the pixel with the smaller minor coordinate -- so the pixels do
not depend on which endpoint comes first.

The decision and its update are the replaceable step ``midpoint_step``
(`scanviz.steps`), written in the first-octant frame: dx = the major extent,
dy = the minor one. Where the minor axis points down, the loop sends a tie to
the diagonal step itself.
"""

from __future__ import annotations

import numbers

import numpy as np
from numba import njit

from .. import steps
from ..conventions import COORD_LIMIT, short_repr
from ..geometry import plain_array
from ..trace import Tracer
from ..trace.events import LineSetup, LineStep


def _check_endpoint(name: str, value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name!r} must be an int; got {short_repr(value)}")
    if not -COORD_LIMIT <= value <= COORD_LIMIT:
        raise ValueError(
            f"{name!r} must be within +-2**20 = {COORD_LIMIT}; got {short_repr(value)}"
        )
    return int(value)


@steps.step(
    "midpoint_step",
    takes="d = 2 f(midpoint) and the first-octant extents dx >= dy >= 0 (ints)",
    returns="(diagonal, next d): diagonal iff d < 0, then d + 2 (dx - dy); else d - 2 dy",
)
def midpoint_step(d: int, dx: int, dy: int) -> tuple[bool, int]:
    """The midpoint decision and update, first octant: NE if the line passes above the midpoint.

    >>> midpoint_step(1, 5, 2), midpoint_step(-3, 5, 2), midpoint_step(0, 4, 2)
    ((False, -3), (True, 3), (False, -4))
    """
    if d < 0:  # the midpoint lies below the line: take the diagonal (NE) step
        return True, d + 2 * (dx - dy)
    return False, d - 2 * dy


def octant(dx: int, dy: int) -> int:
    """The 45-degree sector 0..7 of direction (dx, dy), counter-clockwise from +x.

    Octant 0 is 0 <= angle < 45 degrees; (0, 0) counts as octant 0.

    >>> [octant(5, 2), octant(2, 5), octant(-2, 5), octant(-5, -2), octant(5, -2)]
    [0, 1, 2, 4, 7]
    """
    if dx == 0 and dy == 0:
        return 0
    quadrant = 0
    while not (dx > 0 and dy >= 0):  # rotate by -90 degrees until in [0, 90)
        dx, dy = dy, -dx
        quadrant += 1
    return 2 * quadrant + (dy >= dx)


def midpoint_line(
    x0: int, y0: int, x1: int, y1: int, *, trace: Tracer | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """The pixels of the line from (x0, y0) to (x1, y1) by the midpoint algorithm.

    Parameters
    ----------
    x0, y0, x1, y1 : int
        Endpoints in pixels, within +-2**20. Both endpoints are drawn.
    trace : Tracer, optional
        Receives ``line_setup`` and one ``line_step`` per pixel.

    Returns
    -------
    xs, ys : (N,) ndarray of int64
        The pixels in drawing order, from (x0, y0) to (x1, y1): one per step
        along the major axis, N = max(abs(x1 - x0), abs(y1 - y0)) + 1.

    Notes
    -----
    Each pixel is the one nearest the true line along the minor axis; a tie
    (the line through the midpoint) goes to the smaller minor coordinate, so
    reversing the endpoints gives the same pixels.

    Examples
    --------
    >>> xs, ys = midpoint_line(0, 0, 5, 2)
    >>> image = np.zeros((3, 6), dtype=int)
    >>> image[ys, xs] = 1
    >>> image[::-1]  # top row first
    array([[0, 0, 0, 0, 1, 1],
           [0, 0, 1, 1, 0, 0],
           [1, 1, 0, 0, 0, 0]])
    """
    x0, y0, x1, y1 = (
        _check_endpoint(name, value)
        for name, value in (("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1))
    )
    if trace is not None and not isinstance(trace, Tracer):
        raise TypeError(f"'trace' must be None or a Tracer (wants/emit); got {short_repr(trace)}")
    step_x, step_y = (1 if x1 >= x0 else -1), (1 if y1 >= y0 else -1)
    steep = abs(y1 - y0) > abs(x1 - x0)
    major, minor = sorted((abs(x1 - x0), abs(y1 - y0)), reverse=True)
    axial_step = (0, step_y) if steep else (step_x, 0)
    minor_step = (step_x, 0) if steep else (0, step_y)
    # Doubled f at the first midpoint, and its change after an axial or a diagonal step.
    d, d_axial, d_diagonal = major - 2 * minor, -2 * minor, 2 * (major - minor)
    tie_steps = sum(minor_step) < 0  # a tie takes the smaller minor coordinate
    if trace is not None and trace.wants("line_setup"):
        setup = LineSetup(
            x0=x0,
            y0=y0,
            x1=x1,
            y1=y1,
            octant=octant(x1 - x0, y1 - y0),
            major="y" if steep else "x",
            step_x=step_x,
            step_y=step_y,
            d_start=d,
            d_axial=d_axial,
            d_diagonal=d_diagonal,
            tie_steps=tie_steps,
        )
        trace.emit(setup)
    decide = steps.get("midpoint_step")
    xs, ys = [x0], [y0]
    x, y = x0, y0
    for _ in range(major):
        diagonal, d_next = decide(d, major, minor)
        if tie_steps and d == 0:  # the minor axis points down: a tie takes the diagonal step
            diagonal, d_next = True, d + d_diagonal
        if trace is not None and trace.wants("line_step", y=y):
            trace.emit(LineStep(x, y, d, "diagonal" if diagonal else "axial"))
        x, y = x + axial_step[0], y + axial_step[1]
        if diagonal:
            x, y = x + minor_step[0], y + minor_step[1]
        d = d_next
        xs.append(x)
        ys.append(y)
    if trace is not None and trace.wants("line_step", y=y):
        trace.emit(LineStep(x, y, d, "last"))
    return np.array(xs, dtype=np.int64), np.array(ys, dtype=np.int64)


def paint_lines(ends: object, width: int, height: int) -> np.ndarray:
    """Many midpoint lines at once, compiled: the (height, width) bool raster of their pixels.

    Each row (x0, y0, x1, y1) of `ends` is drawn with exactly the pixels of
    `midpoint_line` (a test checks it); pixels off the raster are dropped.
    There is no trace: step through one line with `midpoint_line`.

    Parameters
    ----------
    ends : (K, 4) array_like of int
        Endpoints in pixels, within +-2**20.
    width, height : int
        Raster size, each at least 0.

    Returns
    -------
    (height, width) ndarray of bool
        Row 0 at the bottom.

    Raises
    ------
    ValueError
        If `ends` is not a (K, 4) integer array within +-2**20, or the size is negative.

    Examples
    --------
    >>> paint_lines([[0, 0, 5, 2], [5, 0, 5, 0]], 6, 3).astype(int)[::-1]
    array([[0, 0, 0, 0, 1, 1],
           [0, 0, 1, 1, 0, 0],
           [1, 1, 0, 0, 0, 1]])
    """
    array = np.asarray(plain_array(ends, "'ends'"))  # a masked end is refused, not read
    if array.size == 0:
        array = array.reshape(0, 4)
    if array.ndim != 2 or array.shape[1] != 4 or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"'ends' must be a (K, 4) array of ints; got {short_repr(ends)}")
    if array.size and np.abs(array).max() > COORD_LIMIT:
        raise ValueError(f"'ends' must be within +-2**20 = {COORD_LIMIT}")
    for name, value in (("width", width), ("height", height)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 0:
            raise ValueError(f"{name!r} must be an int >= 0; got {short_repr(value)}")
    mask = np.zeros((int(height), int(width)), dtype=bool)
    _paint_lines(array.astype(np.int64), mask)
    return mask


@njit(cache=True)
def _paint_lines(ends, mask):  # pragma: no cover - compiled; `midpoint_line` is the reference
    height, width = mask.shape
    for i in range(ends.shape[0]):
        x0, y0, x1, y1 = ends[i, 0], ends[i, 1], ends[i, 2], ends[i, 3]
        step_x = 1 if x1 >= x0 else -1
        step_y = 1 if y1 >= y0 else -1
        dx, dy = abs(x1 - x0), abs(y1 - y0)
        steep = dy > dx
        major, minor = max(dx, dy), min(dx, dy)
        ax, ay = (0, step_y) if steep else (step_x, 0)
        mx, my = (step_x, 0) if steep else (0, step_y)
        d, d_axial, d_diagonal = major - 2 * minor, -2 * minor, 2 * (major - minor)
        tie_steps = mx + my < 0  # a tie takes the smaller minor coordinate
        x, y = x0, y0
        if 0 <= x < width and 0 <= y < height:
            mask[y, x] = True
        for _ in range(major):
            diagonal = d < 0 or (tie_steps and d == 0)
            d += d_diagonal if diagonal else d_axial
            x, y = x + ax, y + ay
            if diagonal:
                x, y = x + mx, y + my
            if 0 <= x < width and 0 <= y < height:
                mask[y, x] = True


def midpoint_line_window(
    x0: int, y0: int, x1: int, y1: int, width: int, height: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pixels of `midpoint_line` (x0, y0)-(x1, y1) on a width x height raster, walked only there.

    The on-raster pixels of a midpoint line are consecutive steps of it (each
    coordinate moves one way), so the walk starts at the first of them, with
    its position and decision variable in closed form, and stops after the
    last: the cost is the pixels returned, not the line's length.

    Parameters
    ----------
    x0, y0, x1, y1 : int
        Endpoints in pixels, within +-2**20.
    width, height : int
        Raster size, each at least 0.

    Returns
    -------
    xs, ys, index : (N,) ndarray of int64
        The pixels with 0 <= x < width and 0 <= y < height, in drawing order,
        and the step of each along the whole line (0 at (x0, y0)): exactly
        ``midpoint_line``'s pixels ``[index]``.

    Notes
    -----
    After k steps the line has taken m_k diagonal steps: the minor offset
    nearest to k minor / major, a tie to the smaller minor coordinate, that is
    m_k = floor((2 minor k + major - 1) / (2 major)), or with ``+ major`` when
    the minor axis points down. The doubled decision variable there is
    d_k = major + 2 major m_k - 2 minor (k + 1). Solving m_k for the raster's
    minor range, and the major coordinate for its major range, gives the
    steps on the raster.

    Examples
    --------
    >>> midpoint_line_window(-3, 0, 5, 2, 4, 3)
    (array([0, 1, 2, 3]), array([1, 1, 1, 1]), array([3, 4, 5, 6]))
    """
    x0, y0, x1, y1 = (
        _check_endpoint(name, value)
        for name, value in (("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1))
    )
    for name, value in (("width", width), ("height", height)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 0:
            raise ValueError(f"{name!r} must be an int >= 0; got {short_repr(value)}")
    ends = np.array([[x0, y0, x1, y1]], dtype=np.int64)
    _, xs, ys, index = line_windows(ends, int(width), int(height))
    return xs, ys, index


@njit(cache=True, inline="always")
def _frame(x0, y0, x1, y1):
    """The line in the first-octant frame: (steep, major, minor, step_x, step_y, tie_steps)."""
    step_x = 1 if x1 >= x0 else -1
    step_y = 1 if y1 >= y0 else -1
    dx, dy = abs(x1 - x0), abs(y1 - y0)
    steep = dy > dx
    tie_steps = (step_x if steep else step_y) < 0  # a tie takes the smaller minor coordinate
    return steep, max(dx, dy), min(dx, dy), step_x, step_y, tie_steps


@njit(cache=True, inline="always")
def _diagonals(k, major, minor, tie_steps):
    """m_k: the diagonal steps among the first k (see `midpoint_line_window`)."""
    if major == 0:
        return 0
    return (2 * minor * k + major - (0 if tie_steps else 1)) // (2 * major)


@njit(cache=True, inline="always")
def _steps_within(start, step, size, last):
    """The steps k in [0, last] with start + step * k in [0, size): (first, stop), maybe empty."""
    if step > 0:
        return max(-start, 0), min(size - start, last + 1)
    return max(start - size + 1, 0), min(start + 1, last + 1)


@njit(cache=True, inline="always")
def _window(x0, y0, x1, y1, width, height):
    """The steps [first, stop) of the line from (x0, y0) to (x1, y1) on the raster."""
    steep, major, minor, step_x, step_y, tie_steps = _frame(x0, y0, x1, y1)
    if steep:
        first, stop = _steps_within(y0, step_y, height, major)
        low, high = _steps_within(x0, step_x, width, minor)  # diagonal counts m_k on it
    else:
        first, stop = _steps_within(x0, step_x, width, major)
        low, high = _steps_within(y0, step_y, height, minor)
    if low >= high:
        return 0, 0
    if minor > 0:  # invert m_k: m_k >= low and m_k <= high - 1
        c = major - (0 if tie_steps else 1)
        first = max(first, -((c - 2 * major * low) // (2 * minor)))
        stop = min(stop, (2 * major * high - c - 1) // (2 * minor) + 1)
    return first, max(stop, first)


@njit(cache=True)
def line_windows(ends, width, height):
    """`midpoint_line_window` of every row (x0, y0, x1, y1) of `ends` (K, 4) int64.

    Returns (offsets, xs, ys, index): line i's pixels are [offsets[i], offsets[i + 1]).
    """
    count = ends.shape[0]
    firsts = np.empty(count, np.int64)
    offsets = np.zeros(count + 1, np.int64)
    for i in range(count):
        first, stop = _window(ends[i, 0], ends[i, 1], ends[i, 2], ends[i, 3], width, height)
        firsts[i] = first
        offsets[i + 1] = offsets[i] + stop - first
    xs = np.empty(offsets[count], np.int64)
    ys = np.empty(offsets[count], np.int64)
    index = np.empty(offsets[count], np.int64)
    for i in range(count):
        x0, y0, x1, y1 = ends[i, 0], ends[i, 1], ends[i, 2], ends[i, 3]
        steep, major, minor, step_x, step_y, tie_steps = _frame(x0, y0, x1, y1)
        k = firsts[i]
        m = _diagonals(k, major, minor, tie_steps)
        d = major + 2 * major * m - 2 * minor * (k + 1)  # the decision at step k
        if steep:
            x, y = x0 + step_x * m, y0 + step_y * k
        else:
            x, y = x0 + step_x * k, y0 + step_y * m
        for j in range(offsets[i], offsets[i + 1]):
            xs[j], ys[j], index[j] = x, y, k
            diagonal = d < 0 or (tie_steps and d == 0)
            d += 2 * (major - minor) if diagonal else -2 * minor
            k += 1
            if steep:
                x, y = x + (step_x if diagonal else 0), y + step_y
            else:
                x, y = x + step_x, y + (step_y if diagonal else 0)
    return offsets, xs, ys, index

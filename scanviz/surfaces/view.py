"""The viewpoint and viewing direction of a grid surface (Step I of the FPA).

Wang (1989, §2.3) views a surface z = f(x, y) "through VP onto a view plane
normal to VA" and defers the details; scanviz uses the standard look-at
(spec §1.6.1 [EXT], derivation in ``docs/surfaces-fpa-enumeration.md``).

Axes
----
forward = direction / |direction|; up = world +z made orthogonal to forward;
right = forward x up. A world point p has view-plane coordinates
``(right . (p - point), up . (p - point))``, divided by its depth
``forward . (p - point)`` in a perspective view (not in a parallel one).
When the direction is vertical (its x and y components are both 0) world +z
cannot serve as up; world +y does, so a view straight down shows +x to the
right and +y up.

Screen
------
A uniform scale and a translation fit the view-plane bounding box of the
fitted points into [0, width - 1] x [0, height - 1], centred on the other
axis: origin bottom-left, y up (DESIGN §2), and every fitted point rounds to
a pixel of the raster, as the FPA's perimeter arrays need. Screen
coordinates count pixels' sample points: `View.camera` gives the scanviz
`Camera` whose display coordinates are screen + 1/2, so ``render(...,
sample="center")`` samples pixel (x, y) at screen (x, y), where the FPA tests
it, and fitted points keep half a pixel from the window's edges (the
clipper never cuts a fitted polygon).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..conventions import check_raster_size
from ..scene import Camera
from ..scene.model import WORLD_LIMIT, _finite_vector
from ..transform._checks import as_points
from ..vectors import unit_vectors

PROJECTIONS = ("perspective", "parallel")


@dataclass(frozen=True)
class View:
    """A viewpoint, a viewing direction and a projection (the VP and VA of Wang 1989).

    Parameters
    ----------
    point : (x, y, z) floats
        The viewpoint VP (centre of projection), finite and within +-1e99. A
        parallel view uses only its x and y, to pick the viewpoint cell on an
        axis the direction does not move along (`scanviz.surfaces.vp_cell`).
    direction : (dx, dy, dz) floats
        The viewing direction VA, finite and nonzero (its length does not matter).
    projection : {"perspective", "parallel"}

    Raises
    ------
    TypeError
        If `point` or `direction` is not three numbers.
    ValueError
        If a coordinate is not finite or out of range, `direction` is zero or
        `projection` is unknown.

    Examples
    --------
    >>> View(point=(6, 8, 3), direction=(-6, -8, -3))
    View(point=(6.0, 8.0, 3.0), direction=(-6.0, -8.0, -3.0), projection='perspective')
    >>> View(point=(0, 0, 1), direction=(0, 0, 0))
    Traceback (most recent call last):
    ...
    ValueError: 'direction' must be nonzero; got (0.0, 0.0, 0.0)
    """

    point: tuple[float, float, float]
    direction: tuple[float, float, float]
    projection: str = "perspective"

    def __post_init__(self) -> None:
        object.__setattr__(self, "point", _finite_vector("point", self.point, 3, WORLD_LIMIT))
        direction = _finite_vector("direction", self.direction, 3)
        if not any(direction):
            raise ValueError(f"'direction' must be nonzero; got {direction}")
        object.__setattr__(self, "direction", direction)
        if self.projection not in PROJECTIONS:
            raise ValueError(
                f"'projection' must be 'perspective' or 'parallel'; got {self.projection!r}"
            )

    def axes(self) -> np.ndarray:
        """The view's right, up and forward unit vectors, as the rows of a (3, 3) array.

        Examples
        --------
        >>> View((0, -5, 0), (0, 1, 0)).axes() + 0.0  # no -0.0
        array([[1., 0., 0.],
               [0., 0., 1.],
               [0., 1., 0.]])
        >>> View((0, 0, 5), (0, 0, -1)).axes() + 0.0  # vertical: world +y is up
        array([[ 1.,  0.,  0.],
               [ 0.,  1.,  0.],
               [ 0.,  0., -1.]])
        """
        forward = unit_vectors(np.array(self.direction))
        fx, fy, fz = forward
        if fx == 0.0 and fy == 0.0:
            up = np.array([0.0, 1.0, 0.0])
        else:
            # z - (z . f) f written out: fx**2 + fy**2 keeps precision that 1 - fz**2 loses.
            up = unit_vectors(np.array([-fz * fx, -fz * fy, fx * fx + fy * fy]))
        right = unit_vectors(np.cross(forward, up))
        return np.array([right, np.cross(right, forward), forward])

    def project(self, points: object) -> tuple[np.ndarray, np.ndarray]:
        """View-plane coordinates and depths of world points, before fitting to a raster.

        Parameters
        ----------
        points : (N, 3) array_like of float
            World points, finite.

        Returns
        -------
        plane : (N, 2) ndarray of float64
            (right, up) coordinates, divided by the depth in a perspective view.
        depth : (N,) ndarray of float64
            Distance along the viewing direction from the viewpoint's plane.

        Raises
        ------
        ValueError
            If `points` is not a finite (N, 3) array, or, in a perspective
            view, a point is not strictly in front of the viewpoint (depth <= 0).

        Examples
        --------
        >>> plane, depth = View((0, -4, 0), (0, 1, 0)).project([[1, 0, 2], [0, 4, 0]])
        >>> plane.tolist(), depth.tolist()
        ([[0.25, 0.5], [0.0, 0.0]], [4.0, 8.0])
        """
        return self._project("points", as_points("points", points, (3,)))

    def _project(self, name: str, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        view = (points - np.array(self.point)) @ self.axes().T
        depth = view[:, 2]
        if self.projection == "parallel":
            return view[:, :2], depth
        behind = np.flatnonzero(~(depth > 0.0))
        if behind.size:
            raise ValueError(
                f"in a perspective view every point must lie in front of the viewpoint "
                f"(depth along 'direction' > 0); {name!r} row {behind[0]} "
                f"{points[behind[0]].tolist()} has depth {depth[behind[0]]}"
            )
        return view[:, :2] / depth[:, None], depth

    def screen_from_world(
        self, points: object, width: int, height: int, fit: object = None
    ) -> tuple[np.ndarray, np.ndarray]:
        """Float screen coordinates and depths of world points in a width x height raster.

        Parameters
        ----------
        points : (N, 3) array_like of float
            World points.
        width, height : int
            Raster size, each at least 1.
        fit : (M, 3) array_like of float, optional
            The points (at least one) whose projected bounding box is fitted to
            the raster (default: `points`), e.g. all grid points while `points` is one edge.

        Returns
        -------
        screen : (N, 2) ndarray of float64
            (x, y) in pixels, origin bottom-left, y up; fitted points lie in
            [0, width - 1] x [0, height - 1].
        depth : (N,) ndarray of float64
            As in `project`: smaller is nearer.

        Raises
        ------
        TypeError, ValueError
            As `project` (for `points` and `fit`), or if width or height is not
            an int >= 1.

        Examples
        --------
        A unit square seen from straight above fills a 5 x 3 raster's height:

        >>> square = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        >>> screen, depth = View((0.5, 0.5, 2), (0, 0, -1)).screen_from_world(square, 5, 3)
        >>> screen.tolist(), depth.tolist()
        ([[1.0, 0.0], [3.0, 0.0], [3.0, 2.0], [1.0, 2.0]], [2.0, 2.0, 2.0, 2.0])
        """
        width, height = _check_size(width, height)
        plane, depth = self.project(points)
        fitted = plane if fit is None else self._project("fit", as_points("fit", fit, (3,), 1))[0]
        if len(fitted) == 0:
            return plane, depth
        centre, scale, room = _fit(fitted, width, height)
        return (plane - centre) * scale + room / 2, depth

    def camera(self, width: int, height: int, fit: object) -> Camera:
        """The scanviz `Camera` whose display coordinates are `screen_from_world`'s plus 1/2.

        For the z-buffer reference: ``render`` of a scene with this camera puts
        every world point half a pixel up and right of where
        ``screen_from_world(points, width, height, fit)`` does, so pixel (x, y)
        is sampled at screen (x, y) with ``sample="center"`` and at
        (x - 1/2, y - 1/2) with the default corner sampling, and every fitted
        point lies at least half a pixel inside the window. Near and far enclose the fitted points' depths with a margin
        (perspective: half the least and twice the largest depth; parallel: the
        depth range widened by its length, or by 1 if it is flat), so nothing
        fitted is clipped.

        Parameters
        ----------
        width, height : int
            Raster size, each at least 2 (a 1-pixel axis would need a zero window).
        fit : (M, 3) array_like of float
            The points fitted to the raster, at least one.

        Returns
        -------
        Camera
            eye = point, look_at = point + direction, up = the view's up axis;
            "orthographic" for a parallel view.

        Examples
        --------
        >>> square = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
        >>> View((0.5, 0.5, 2), (0, 0, -1)).camera(5, 3, square).window  # display 0..5, 0..3
        (-0.625, 0.625, -0.375, 0.375)
        """
        width, height = _check_size(width, height, least=2)
        fit = as_points("fit", fit, (3,), 1)
        plane, depth = self._project("fit", fit)
        centre, scale, room = _fit(plane, width, height)
        size = np.array([width, height])
        low = centre - (room / 2 + 0.5) / scale  # where screen -1/2 (display 0) lands
        high = low + size / scale  # the viewport maps the window to [0, width] x [0, height]
        perspective = self.projection == "perspective"
        if perspective:
            near, far = depth.min() / 2, depth.max() * 2
        else:
            margin = np.ptp(depth) or 1.0
            near, far = depth.min() - margin, depth.max() + margin
        window = np.array([low[0], high[0], low[1], high[1]]) * (near if perspective else 1.0)
        _, up, forward = self.axes()
        reach = 1.0 + max(
            map(abs, self.point)
        )  # a look-at point that rounding cannot merge with VP
        return Camera(
            eye=self.point,
            look_at=tuple((np.array(self.point) + reach * forward).tolist()),
            up=tuple(up.tolist()),
            window=tuple(window.tolist()),  # a perspective window lies on the near plane
            near=float(near),
            far=float(far),
            projection="perspective" if perspective else "orthographic",
        )


def _check_size(width: object, height: object, least: int = 1) -> tuple[int, int]:
    width, height = check_raster_size(width, height)
    if width < least or height < least:
        raise ValueError(f"'width' and 'height' must be at least {least}; got {width} x {height}")
    return width, height


def _fit(plane: np.ndarray, width: int, height: int) -> tuple[np.ndarray, float, np.ndarray]:
    """(box centre, scale, raster room) fitting the box of `plane` into [0, w-1] x [0, h-1]."""
    low, high = plane.min(axis=0), plane.max(axis=0)
    room = np.array([width - 1.0, height - 1.0])
    extent = high - low
    ratios = room[extent > 0] / extent[extent > 0]
    scale = ratios.min() if ratios.size else 1.0  # a single point: any scale fits
    return (low + high) / 2, float(scale), room

"""Viewing transformations: world -> eye -> clip -> NDC -> display -> image.

The stops follow Smith's tutorial as the Rendermatic thesis retells it
(App. D): eye space for lighting, clip space for clipping, then the divide
and the viewport. Derivations are in ``docs/viewing.md``.

Matrix convention
-----------------
Points are column vectors p = (x, y, z, w) and a matrix acts on the left,
``q = M @ p``; transforms compose right to left,
``clip_from_world = clip_from_eye @ eye_from_world``, and are named
``a_from_b`` (they take b coordinates to a coordinates). Point arrays hold one
point per row, so code applies M to all of them as ``points @ M.T``. (Smith
and the thesis use row vectors, ``p' = p M``: their matrices are our
transposes.)

Spaces
------
world
    Right-handed, as the scene.
eye
    Right-handed, the eye at the origin looking down -z, y up (OpenGL).
    `eye_from_world` is a rigid motion, so angles and lengths survive: light here.
clip
    Homogeneous. A point is visible iff ``-w <= x <= w``, ``-w <= y <= w`` and
    ``0 <= z <= w`` (the Direct3D depth range). Clipping happens here.
NDC
    ``clip / w``: x, y in [-1, 1], z in [0, 1] with 0 at the near plane and 1
    at the far plane, so smaller z is nearer (the z-buffer starts at +inf).
display
    Pixels, y up with row 0 at the bottom (no flip):
    ``x = (x_ndc + 1) / 2 * width``, ``y = (y_ndc + 1) / 2 * height``, ``z = z_ndc``.
image
    Display x, y snapped to the 1/2**bits sub-pixel grid, round half to even,
    as the rasterizer does (`scanviz.raster.fixed`).
"""

from __future__ import annotations

import math

import numpy as np

from .. import steps
from ..conventions import DEFAULT_SUBPIXEL_BITS, check_raster_size, check_subpixel_bits
from ..scene import Camera
from ..trace.events import VerticesTransformed
from ..vectors import unit_vectors
from ._checks import as_points, check_camera, check_tracer

STAGES = ("world", "eye", "clip", "ndc", "display", "image")


@steps.step(
    "viewing_matrix",
    takes="the camera's eye, look-at point and up vector: three (x, y, z) tuples of floats",
    returns="eye_from_world, the 4x4 look-at matrix: rows right, up, backward, then -R @ eye",
)
def viewing_matrix(eye: tuple, look_at: tuple, up: tuple) -> np.ndarray:
    """The look-at matrix of a camera at `eye` looking at `look_at`, `up` roughly up.

    The rotation's rows are the eye's right, true up and backward axes in world
    coordinates (backward, because the camera looks down -z); the last column
    moves the eye to the origin: ``eye_from_world = R @ T(-eye)``.

    Examples
    --------
    >>> viewing_matrix((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)) + 0.0  # no -0.0
    array([[ 1.,  0.,  0.,  0.],
           [ 0.,  1.,  0.,  0.],
           [ 0.,  0.,  1., -5.],
           [ 0.,  0.,  0.,  1.]])
    """
    eye = np.array(eye)
    # Unit vectors by scaling first: lengths near 1e-300 or 1e300 neither underflow nor overflow.
    forward, up = unit_vectors(np.array([np.subtract(look_at, eye), up]))
    right = unit_vectors(np.cross(forward, up))
    up = np.cross(right, forward)  # unit: right and forward are orthonormal
    matrix = np.eye(4)
    matrix[:3, :3] = right, up, -forward  # the camera looks down -z
    matrix[:3, 3] = -matrix[:3, :3] @ eye  # move the eye to the origin
    return matrix


def eye_from_world(camera: Camera) -> np.ndarray:
    """The look-at matrix: world to eye space (eye at the origin, looking down -z, y up).

    The matrix comes from the step ``viewing_matrix`` (`scanviz.steps`).

    Returns
    -------
    (4, 4) ndarray of float64
        A rigid motion: rotation rows are the eye's right, up and backward
        axes in world coordinates, then the eye moves to the origin.

    Raises
    ------
    ValueError
        If a replaced ``viewing_matrix`` step returns anything but a 4x4 matrix.

    Examples
    --------
    A camera at (5, 0, 0) looking at the origin: the eye goes to the origin,
    the origin 5 units down -z, and world -z is to the camera's right (+x).

    >>> matrix = eye_from_world(Camera(eye=(5, 0, 0), look_at=(0, 0, 0), up=(0, 1, 0)))
    >>> transform_points(matrix, [[5, 0, 0], [0, 0, 0], [0, 0, -1], [0, 1, 0]])
    array([[ 0.,  0.,  0.,  1.],
           [ 0.,  0., -5.,  1.],
           [ 1.,  0., -5.,  1.],
           [ 0.,  1., -5.,  1.]])
    """
    camera = check_camera(camera)
    matrix = np.asarray(
        steps.get("viewing_matrix")(camera.eye, camera.look_at, camera.up), dtype=np.float64
    )
    if matrix.shape != (4, 4):
        raise ValueError(
            f"the 'viewing_matrix' step must return a 4x4 matrix; got shape {matrix.shape}"
        )
    return matrix


def clip_from_eye(camera: Camera) -> np.ndarray:
    """The projection: eye space to homogeneous clip space (near -> z = 0, far -> z = w).

    Perspective (as ``glFrustum``): the `window` (left, right, bottom, top)
    lies on the near plane z = -near and w = -z_eye. Orthographic (as
    ``glOrtho``): the window is in eye space and w = 1. Both map the window to
    x, y = +-w and depth to ``0 <= z <= w`` (Direct3D range). A perspective
    camera may have ``far = inf`` (the limit matrix); an orthographic one may not.

    Returns
    -------
    (4, 4) ndarray of float64

    Examples
    --------
    >>> clip_from_eye(Camera(near=1.0, far=3.0))
    array([[ 1. ,  0. ,  0. ,  0. ],
           [ 0. ,  1. ,  0. ,  0. ],
           [ 0. ,  0. , -1.5, -1.5],
           [ 0. ,  0. , -1. ,  0. ]])
    >>> clip_from_eye(Camera(near=1.0, far=3.0, projection="orthographic"))
    array([[ 1. ,  0. ,  0. , -0. ],
           [ 0. ,  1. ,  0. , -0. ],
           [ 0. ,  0. , -0.5, -0.5],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    camera = check_camera(camera)
    left, right, bottom, top = camera.window
    near, far = camera.near, camera.far
    width, height = right - left, top - bottom
    if camera.projection == "orthographic":  # Camera guarantees a finite far plane here
        return np.array(
            [
                [2 / width, 0, 0, -(right + left) / width],
                [0, 2 / height, 0, -(top + bottom) / height],
                [0, 0, -1 / (far - near), -near / (far - near)],
                [0, 0, 0, 1],
            ]
        )
    depth = 1.0 if math.isinf(far) else far / (far - near)  # z/w: 0 at -near, 1 at -far
    return np.array(
        [
            [2 * near / width, 0, (right + left) / width, 0],
            [0, 2 * near / height, (top + bottom) / height, 0],
            [0, 0, -depth, -near * depth],
            [0, 0, -1, 0],
        ]
    )


def _apply(matrix: np.ndarray, points: np.ndarray) -> np.ndarray:
    if points.shape[1] == 3:
        return points @ matrix[:, :3].T + matrix[:, 3]  # w = 1
    return points @ matrix.T


def transform_points(matrix: object, points: object) -> np.ndarray:
    """Apply a 4x4 matrix to points given as rows: (N, 3) with w = 1, or homogeneous (N, 4).

    Returns
    -------
    (N, 4) ndarray of float64
        Homogeneous results, w included (still 1 for an affine matrix).

    Examples
    --------
    >>> transform_points(np.diag([2.0, 3.0, 4.0, 1.0]), [[1, 1, 1]])
    array([[2., 3., 4., 1.]])
    """
    matrix = as_points("matrix", matrix, (4,))
    if matrix.shape != (4, 4):
        raise ValueError(f"'matrix' must be 4x4; got shape {matrix.shape}")
    return _apply(matrix, as_points("points", points, (3, 4)))


def _divide(points: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        ndc = points[:, :3] / points[:, 3:]
    ndc[~((points[:, 3] > 0) & np.isfinite(ndc).all(axis=1))] = np.nan
    return ndc


def ndc_from_clip(points: object) -> np.ndarray:
    """The perspective divide: (N, 4) clip-space points to (N, 3) NDC, ``(x, y, z) / w``.

    Rows with ``w <= 0`` (at or behind the eye plane of a perspective camera)
    have no image and come out as NaN, as do rows with w so close to 0 that
    the quotient overflows. Clip first (`clip_polygon`): that leaves only
    points with w >= near > 0.

    Examples
    --------
    >>> ndc_from_clip([[1.0, -2.0, 1.0, 2.0], [1.0, 1.0, -1.0, -1.0]])
    array([[ 0.5, -1. ,  0.5],
           [ nan,  nan,  nan]])
    """
    return _divide(as_points("points", points, (4,)))


def display_from_ndc(width: int, height: int) -> np.ndarray:
    """The viewport matrix: NDC [-1, 1]^2 to pixels [0, width] x [0, height], y up, z kept.

    Examples
    --------
    >>> display_from_ndc(640, 480)
    array([[320.,   0.,   0., 320.],
           [  0., 240.,   0., 240.],
           [  0.,   0.,   1.,   0.],
           [  0.,   0.,   0.,   1.]])
    """
    width, height = check_raster_size(width, height)
    return np.array(
        [
            [width / 2, 0, 0, width / 2],
            [0, height / 2, 0, height / 2],
            [0, 0, 1, 0],
            [0, 0, 0, 1],
        ]
    )


def _snap(points: np.ndarray, bits: int | None) -> np.ndarray:
    image = points.copy()
    if bits is not None:
        image[:, :2] = np.rint(points[:, :2] * 2.0**bits) / 2.0**bits
    return image


def image_from_display(points: object, subpixel_bits: int | None = DEFAULT_SUBPIXEL_BITS):
    """Snap display x, y to the 1/2**subpixel_bits grid (round half to even); other columns kept.

    The rasterizer snaps its input the same way (`scanviz.raster.fixed`);
    this shows the values it will use. ``subpixel_bits=None`` keeps them.

    Parameters
    ----------
    points : (N, k) array_like of float, k >= 2
    subpixel_bits : int in 0..16, or None

    Returns
    -------
    (N, k) ndarray of float64

    Examples
    --------
    >>> image_from_display([[0.3, 0.625, 0.9], [1.25, 2.75, 0.1]], subpixel_bits=1)
    array([[0.5, 0.5, 0.9],
           [1. , 3. , 0.1]])
    """
    bits = check_subpixel_bits(subpixel_bits)
    points = as_points("points", points, None)
    if points.shape[1] < 2:
        raise ValueError(f"'points' must have x and y columns; got shape {points.shape}")
    return _snap(points, bits)


def _stages(camera, world_points, width, height, subpixel_bits):
    """(stage, matrix or None, points) for every stage of `STAGES`."""
    eye_matrix, clip_matrix = eye_from_world(camera), clip_from_eye(camera)
    display_matrix = display_from_ndc(width, height)
    world = as_points("world_points", world_points, (3,))
    bits = check_subpixel_bits(subpixel_bits)
    eye = _apply(eye_matrix, world)[:, :3]
    clip = _apply(clip_matrix, eye)
    ndc = _divide(clip)
    with np.errstate(over="ignore", invalid="ignore"):  # huge NDC values overflow to inf
        display = _apply(display_matrix, ndc)[:, :3]
        image = _snap(display, bits)
    undefined = ~np.isfinite(image).all(axis=1)  # one rule for all three stages
    ndc[undefined] = display[undefined] = image[undefined] = np.nan
    return [
        ("world", None, world),
        ("eye", eye_matrix, eye),
        ("clip", clip_matrix, clip),
        ("ndc", None, ndc),
        ("display", display_matrix, display),
        ("image", None, image),
    ]


def vertex_tables(
    camera: Camera,
    world_points: object,
    width: int,
    height: int,
    subpixel_bits: int | None = DEFAULT_SUBPIXEL_BITS,
) -> dict[str, np.ndarray]:
    """Every vertex at every stage of the viewing pipeline, for tables and plots.

    Parameters
    ----------
    camera : Camera
    world_points : (N, 3) array_like of float
    width, height : int
        Raster size in pixels.
    subpixel_bits : int in 0..16, or None
        Grid of the "image" stage (None: no snapping).

    Returns
    -------
    dict of str to ndarray of float64
        Keys `STAGES`: "world", "eye" (N, 3); "clip" (N, 4); "ndc", "display",
        "image" (N, 3). A vertex with no finite image (clip w <= 0, or w so
        close to 0 that it overflows) is NaN in "ndc", "display" and "image".

    Examples
    --------
    >>> tables = vertex_tables(Camera(near=1.0, far=9.0), [[0, 0, 0], [1, 1, 3]], 8, 8)
    >>> tables["eye"]
    array([[ 0.,  0., -5.],
           [ 1.,  1., -2.]])
    >>> tables["ndc"]
    array([[0.   , 0.   , 0.9  ],
           [0.5  , 0.5  , 0.5625]])
    >>> tables["image"]
    array([[4.    , 4.    , 0.9   ],
           [6.    , 6.    , 0.5625]])
    """
    stages = _stages(camera, world_points, width, height, subpixel_bits)
    return {stage: points for stage, _, points in stages}


def _rows(points: np.ndarray) -> tuple[tuple[float, ...] | None, ...]:
    return tuple(None if np.isnan(row).any() else tuple(row.tolist()) for row in points)


def transform_vertices(
    camera: Camera,
    world_points: object,
    width: int,
    height: int,
    *,
    subpixel_bits: int | None = DEFAULT_SUBPIXEL_BITS,
    trace=None,
    object: int = 0,
) -> dict[str, np.ndarray]:
    """`vertex_tables`, emitting one ``vertices_transformed`` event per stage to `trace`.

    `object` labels the events (which scene object the vertices belong to).

    Examples
    --------
    >>> from scanviz.trace import Recorder
    >>> recorder = Recorder()
    >>> _ = transform_vertices(Camera(), [[0, 0, 0]], 8, 8, trace=recorder)
    >>> [(e.stage, e.matrix is not None) for e in recorder.trace()]  # doctest: +NORMALIZE_WHITESPACE
    [('world', False), ('eye', True), ('clip', True), ('ndc', False), ('display', True),
     ('image', False)]
    """
    trace = check_tracer(trace)
    stages = _stages(camera, world_points, width, height, subpixel_bits)
    if trace is not None and trace.wants("vertices_transformed"):
        for stage, matrix, points in stages:
            flat = None if matrix is None else tuple(matrix.ravel().tolist())
            trace.emit(VerticesTransformed(int(object), stage, flat, _rows(points)))
    return {stage: points for stage, _, points in stages}

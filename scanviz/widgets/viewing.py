"""The viewing pipeline of a scene: vertex tables per space and the view frustum in 3D.

`ViewingPipelineView` traces only the transform stage (``vertices_transformed``
events from `scanviz.pipeline.prepare`) and shows, for the object and space
you pick, the vertex table and the matrix that produced it, beside the
camera's frustum with the scene's vertices in world space.
"""

from __future__ import annotations

import ipywidgets as widgets
import numpy as np

from ..pipeline import prepare
from ..trace import Recorder
from ..transform.viewing import STAGES
from ._common import html_table, new_figure
from .stepper import figure_widget, refresh_figure

COLUMNS = {
    "world": ("x", "y", "z"),
    "eye": ("x", "y", "z"),
    "clip": ("x", "y", "z", "w"),
    "ndc": ("x", "y", "z"),
    "display": ("x", "y", "z"),
    "image": ("x", "y", "z"),
}
MATRIX_NAMES = {"eye": "eye_from_world", "clip": "clip_from_eye", "display": "display_from_ndc"}
# The 12 edges of a frustum between its corners: near face 0-3, far face 4-7 (same order).
FRUSTUM_EDGES = [(i, (i + 1) % 4) for i in range(4)]
FRUSTUM_EDGES += [(4 + i, 4 + (i + 1) % 4) for i in range(4)] + [(i, i + 4) for i in range(4)]


def frustum_corners(camera, eye_from_world: np.ndarray, far: float) -> np.ndarray:
    """The 8 corners of the view volume in world space: near face, then far face.

    Parameters
    ----------
    camera : Camera
    eye_from_world : (4, 4) ndarray of float64
    far : float
        Distance of the far face drawn (the camera's far may be infinite).

    Returns
    -------
    (8, 3) ndarray of float64
    """
    left, right, bottom, top = camera.window
    face = np.array([[left, bottom], [right, bottom], [right, top], [left, top]], float)
    near = camera.near
    # Perspective: the window lies on the near plane and the far face is it scaled by far/near.
    scale = far / near if camera.projection == "perspective" else 1.0
    eye = np.vstack(
        [
            np.column_stack([face, np.full(4, -near)]),
            np.column_stack([face * scale, np.full(4, -far)]),
        ]
    )
    world = np.hstack([eye, np.ones((8, 1))]) @ np.linalg.inv(eye_from_world).T
    return world[:, :3] / world[:, 3:]


class ViewingPipelineView:
    """Vertex tables per space (world ... image) and the view frustum with the scene in 3D.

    Parameters
    ----------
    scene : Scene
    width, height : int
        Raster size (the display and image spaces depend on it).
    max_rows : int, optional
        Vertex rows shown per table.

    Attributes
    ----------
    widget : ipywidgets.VBox
    object_picker : ipywidgets.Dropdown
        Which scene object's vertices are tabled (highlighted in 3D).
    space : ipywidgets.Dropdown
        One of `scanviz.transform.viewing.STAGES`.
    table : ipywidgets.HTML
        The first `max_rows` vertices in that space ("-" where undefined).
    rows_note : ipywidgets.Label
        "N of M rows".
    matrix : ipywidgets.HTML
        The 4x4 matrix that produced the space from the previous one, if any.
    trace : Trace
        The ``vertices_transformed`` events shown.

    Examples
    --------
    >>> from scanviz.scene.builtin import builtin_scene
    >>> view = ViewingPipelineView(builtin_scene("sphere", level=1), 64, 64, max_rows=5)
    >>> view.space.value = "ndc"
    >>> view.rows_note.value
    '5 of 42 rows'
    """

    def __init__(self, scene, width: int, height: int, *, max_rows: int = 20) -> None:
        recorder = Recorder(kinds=["vertices_transformed"])
        prepare(scene, width, height, shading="flat", cull=None, tracer=recorder)
        self.trace, self.scene, self.max_rows = recorder.trace(), scene, int(max_rows)
        self._events = {(e.object, e.stage): e for e in self.trace}
        objects = sorted({e.object for e in self.trace})
        self.object_picker = widgets.Dropdown(
            options=[
                (f"object {k} ({len(self._events[k, 'world'].vertices)} vertices)", k)
                for k in objects
            ],
            description="object",
        )
        self.space = widgets.Dropdown(options=list(STAGES), value="world", description="space")
        self.table, self.matrix = widgets.HTML(), widgets.HTML()
        self.rows_note = widgets.Label()
        self._build_figure()
        for picker in (self.object_picker, self.space):
            picker.observe(lambda _: self.update(), names="value")
        self.widget = widgets.VBox(
            [
                widgets.HBox([self.object_picker, self.space]),
                widgets.HBox(
                    [widgets.VBox([self.rows_note, self.table, self.matrix]), self._canvas]
                ),
            ]
        )
        self.update()

    def _build_figure(self) -> None:
        camera = self.scene.camera
        fig, (ax,) = new_figure(1, width=5.0, height=5.0, subplot_kw={"projection": "3d"})
        worlds = [np.array([v for v in e.vertices]) for e in self.trace if e.stage == "world"]
        points = np.vstack(worlds) if worlds else np.zeros((0, 3))
        eye_matrix = np.reshape(next(e for e in self.trace if e.stage == "eye").matrix, (4, 4))
        far = camera.far
        if not np.isfinite(far):  # draw an infinite frustum just past the scene
            depths = -(np.hstack([points, np.ones((len(points), 1))]) @ eye_matrix.T)[:, 2]
            far = max(camera.near * 2, 1.2 * float(depths.max(initial=0)))
        corners = frustum_corners(camera, eye_matrix, far)
        for a, b in FRUSTUM_EDGES:
            ax.plot(*corners[[a, b]].T, color="tab:blue", lw=1)
        if camera.projection == "perspective":
            for k in range(4, 8):  # rays from the eye through the far corners
                ax.plot(*np.array([camera.eye, corners[k]]).T, color="tab:blue", lw=0.5, ls=":")
        ax.scatter(*np.array(camera.eye)[:, None], color="black", s=30, label="eye")
        ax.plot(*points.T, ".", color="0.7", ms=2)
        (self.highlight,) = ax.plot([], [], [], ".", color="crimson", ms=4, label="object")
        everything = np.vstack([points, corners, [camera.eye]])
        low, high = everything.min(axis=0), everything.max(axis=0)
        middle, half = (low + high) / 2, (high - low).max() / 2
        ax.set_xlim(middle[0] - half, middle[0] + half)
        ax.set_ylim(middle[1] - half, middle[1] + half)
        ax.set_zlim(middle[2] - half, middle[2] + half)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        ax.legend(loc="upper left", fontsize=8)
        ax.set_title(f"{camera.projection} view volume, world space", fontsize=10)
        self.figure, self.ax = fig, ax
        self._canvas = figure_widget(fig)

    def update(self) -> None:
        """Show the picked object's vertices in the picked space."""
        event = self._events[self.object_picker.value, self.space.value]
        vertices = event.vertices
        shown = vertices[: self.max_rows]
        columns = COLUMNS[self.space.value]
        self.table.value = html_table(
            ("vertex", *columns),
            [
                (k, *(row if row is not None else [None] * len(columns)))
                for k, row in enumerate(shown)
            ],
        )
        self.rows_note.value = f"{len(shown)} of {len(vertices)} rows"
        if event.matrix is None:
            why = {"world": "the input", "ndc": "clip / w", "image": "display snapped"}
            self.matrix.value = f"<i>{self.space.value}: {why[self.space.value]}, no matrix</i>"
        else:
            self.matrix.value = f"<b>{MATRIX_NAMES[self.space.value]}</b>" + html_table(
                ("", "", "", ""), np.reshape(event.matrix, (4, 4)).tolist()
            )
        world = np.array(self._events[self.object_picker.value, "world"].vertices)
        self.highlight.set_data_3d(*world.T)
        refresh_figure(self.figure, self._canvas)

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)

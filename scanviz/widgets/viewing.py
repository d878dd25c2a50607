"""Step through the viewing pipeline of a scene: cull, world -> eye -> clip, clip, NDC, display.

`ViewingPipelineView` runs `scanviz.pipeline.viewing.view_scene` with a
recorder and shows, step by step, the scene's polygons and the camera's view
volume in the current space (3-D), the screen at the end (2-D), the matrix or
test of the step beside it and a few vertices of the polygon concerned.
Back faces turn grey and hatched as culling marks them; the clipper's cut
pieces are drawn dashed with the new vertices in red. `viewing_stepper`
wraps the view in a `Stepper`.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.ticker import MaxNLocator

from ..pipeline.viewing import view_scene
from ..trace import Recorder
from ..transform.clip import CLIP_PLANES
from ._common import DisplaysWidget, html_table, listed, new_figure
from .stepper import Stepper, figure_widget, refresh_figure

KINDS = ("polygons_transformed", "face_culled", "polygon_clipped")
SPACE_NAMES = {
    "world": "world space",
    "eye": "eye space",
    "clip": "clip space (x, y, z; w not drawn)",
    "ndc": "normalized device coordinates (NDC)",
    "display": "display space (x, y in pixels; z depth)",
}
MATRICES = {  # stop: (matrix name, what it does, in one line)
    "eye": (
        "eye_from_world",
        "world → eye: moves the eye to the origin and turns it to look down −z, y up",
    ),
    "clip": (
        "clip_from_eye",
        "eye → clip: the window's edges go to x = ±w, y = ±w, near..far to 0 ≤ z ≤ w",
    ),
    "display": (
        "display_from_ndc",
        "NDC → display: [−1, 1]² stretched to the raster in pixels, y up; z kept",
    ),
}
NO_MATRIX = {
    "world": "World space: the scene as built; no matrix yet.",
    "ndc": "clip → NDC: no matrix; every coordinate is divided by w, (x/w, y/w, z/w).",
}
# The 12 edges of the view volume between its corners: near face 0-3, far face 4-7.
VOLUME_EDGES = [(i, (i + 1) % 4) for i in range(4)]
VOLUME_EDGES += [(4 + i, 4 + (i + 1) % 4) for i in range(4)] + [(i, i + 4) for i in range(4)]
CULLED = "#bdbdbd"
CUT = "tab:orange"
NEW_VERTEX = "crimson"
MAX_ROWS = 6  # vertex rows shown for a polygon


def _tidy(rows) -> list[list[float]]:
    """Rows of numbers rounded for a table: 4 decimals, no -0 (rounding noise such as 1e-18 is 0)."""
    return (np.round(np.array(rows, dtype=float), 4) + 0.0).tolist()


def _planes(bits: int) -> list[str]:
    """The names of the clip planes whose bits are set in an outcode."""
    return [plane for i, plane in enumerate(CLIP_PLANES) if bits >> i & 1]


def _plane_words(bits: int) -> str:
    names = _planes(bits)
    return listed(names) + (" plane" if len(names) == 1 else " planes")


class ViewingPipelineView(DisplaysWidget):
    """The scene and the view volume through world, eye, clip, NDC and display space.

    Parameters
    ----------
    scene : Scene
    width, height : int
        Raster size (the display space depends on it).
    cull : bool or None, optional
        As `scanviz.render`: None culls the back faces of closed meshes.
    follow : int, optional
        The polygon whose vertices are tabled at the stops (default: the
        first one the clipper cuts, else the first one kept).

    Attributes
    ----------
    trace : Trace
        The steps: ``face_culled``, ``polygons_transformed`` (eye, clip,
        ndc, display) and ``polygon_clipped`` events of `view_scene`.
    start : PolygonsTransformed
        The world-space event: what step 0 shows.
    viewed : ViewedScene
        `view_scene`'s result.
    widget : ipywidgets.VBox
    space : str
        The space shown at the current step (one of `scanviz.pipeline.viewing.STOPS`).
    matrix : (4, 4) ndarray of float64 or None
        The matrix of the current stop, as the table beside the step shows it.
    culled : frozenset of int
        The polygons culling has marked so far.
    shown : dict of int to (k, 3) ndarray
        The polygons drawn in colour at the current step, by number: x, y, z
        in the current space (as clipped, once the clipper has run on them).
    new_vertices : dict of int to list of int
        Per polygon the clipper cut, the positions in its clipped vertex
        list of the vertices the clipper made (not among its input vertices).
    step_table : ipywidgets.HTML
        The matrix of the current stop with its meaning, or the back-face
        test or the clip of the current polygon.
    vertex_table : ipywidgets.HTML
        A few vertices of the polygon concerned, in the current space.
    polygons, culled_faces, cut_off : Poly3DCollection, Poly3DCollection, Line3DCollection
        The polygons drawn (each object's colour, orange edges where cut), the culled
        ones (grey, hatched) and the outlines of what clipping removed (dashed).
    corners : (8, 3) ndarray of float64
        The view volume's corners drawn, x, y, z in the current space.
    volume : Line3DCollection
        The view volume's 12 edges between `corners`.
    markers : Line3D
        The clipper's new vertices shown (red dots).
    screen : PolyCollection
        The display polygons on the 2-D screen panel (empty before the display step).

    Examples
    --------
    >>> from scanviz.scene.builtin import builtin_scene
    >>> view = ViewingPipelineView(builtin_scene("sphere", level=0), 64, 64)
    >>> stepper = Stepper(view.trace, [view])
    >>> stepper.slider.value = len(view.trace)
    >>> view.space, len(view.culled)
    ('display', 12)
    """

    def __init__(
        self, scene, width: int, height: int, *, cull: bool | None = None, follow=None
    ) -> None:
        recorder = Recorder(kinds=KINDS)
        self.viewed = view_scene(scene, width, height, cull=cull, trace=recorder)
        everything = recorder.trace()
        self.start, self.trace = everything[0], everything[1:]
        self.scene, self.width, self.height = scene, int(width), int(height)
        self.stops = {e.stage: e for e in everything if e.kind == "polygons_transformed"}
        self._clipped = {e.polygon: e for e in self.trace if e.kind == "polygon_clipped"}
        self.new_vertices = {}
        for number, event in self._clipped.items():
            if event.verdict == "clipped":  # the clipper passes kept vertices on unchanged
                given = set(self.stops["clip"].polygons[number])
                made = [i for i, v in enumerate(event.vertices) if v not in given]
                self.new_vertices[number] = made
        cut = [k for k, v in enumerate(self.viewed.verdicts) if v == "clipped"]
        kept = [k for k, v in enumerate(self.viewed.verdicts) if v != "culled"]
        self.follow = int(follow) if follow is not None else (cut or kept or [0])[0]
        self.space, self.matrix, self.culled = "world", None, frozenset()
        # Each object in its material's colour, lightened so edges and hatching show.
        self._fills = [0.45 * np.array(o.material.color) + 0.55 for o in scene.objects]
        self.step_table = widgets.HTML(layout={"margin": "0 28px 0 0"})
        self.vertex_table = widgets.HTML()
        self._limits = {stop: self._bounds(stop) for stop in self.stops}
        self._build_figure()
        tables = widgets.HBox(
            [self.step_table, self.vertex_table], layout={"flex_flow": "row wrap"}
        )
        self.widget = widgets.VBox([tables, self._canvas])
        self.show(0)

    # --- what a step is ---------------------------------------------------------------------

    def _name(self, polygon: int) -> str:
        obj = int(self.viewed.objects[polygon])
        name = self.scene.objects[obj].name or f"object {obj}"
        return f"polygon {polygon} ({name})"

    def _stop_at(self, step: int):
        """The latest ``polygons_transformed`` event among the first `step` steps (or the start)."""
        for event in reversed(self.trace[:step]):
            if event.kind == "polygons_transformed":
                return event
        return self.start

    def narrate(self, step: int) -> str:
        """What step `step` did and why, in one plain sentence."""
        if step == 0:
            return (
                "World space: the scene as built and the camera's view volume (blue edges); "
                "only what lies inside the view volume can reach the screen."
            )
        event = self.trace[step - 1]
        if event.kind == "face_culled":
            if event.culled:
                return (
                    f"{self._name(event.polygon)} turns away from the eye (N · V = "
                    f"{event.dot:.3g} ≥ 0), so it is culled: grey and hatched, never drawn."
                )
            return (
                f"{self._name(event.polygon)} faces the eye (N · V = {event.dot:.3g} < 0), "
                "so it is kept."
            )
        if event.kind == "polygon_clipped":
            name = self._name(event.polygon)
            if event.verdict == "accepted":
                return f"{name} lies inside all six planes (every outcode 0): it passes unchanged."
            if event.verdict == "rejected":
                common = np.bitwise_and.reduce(event.outcodes)
                where = f"the {_plane_words(common)}" if common else "the view volume"
                return f"{name} lies wholly outside {where}: it is rejected, nothing is left."
            outside = _plane_words(np.bitwise_or.reduce(event.outcodes))
            made = len(self.new_vertices[event.polygon])
            return (
                f"{name} pokes out of the {outside}: the clipper cuts it off there, making "
                f"{made} new vertices (red); {len(event.outcodes)} vertices in, "
                f"{len(event.vertices)} out."
            )
        return {
            "eye": "eye_from_world moves the eye to the origin looking down −z: the scene and "
            "the view volume move and turn together, nothing changes shape.",
            "clip": "clip_from_eye makes the view volume the region −w ≤ x, y ≤ w, 0 ≤ z ≤ w, "
            "where w is the distance in front of the eye: now the clipper can test each vertex.",
            "ndc": "Dividing by w makes far things smaller: the view volume becomes the box "
            "−1 ≤ x, y ≤ 1, 0 ≤ z ≤ 1, and every polygon left lies inside it.",
            "display": f"display_from_ndc stretches the box to {self.width} × {self.height} "
            "pixels, y up: the polygons are ready to be scan converted.",
        }[event.stage]

    # --- the figure -------------------------------------------------------------------------

    def _bounds(self, stop: str) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) corners of the box every polygon, the volume and the eye of `stop` fit in."""
        event = self.stops[stop]
        points = [np.array(event.volume)[:, :3]]
        points += [np.array(p)[:, :3] for p in event.polygons if p]
        if event.eye is not None:
            points.append(np.array([event.eye]))
        everything = np.vstack(points)
        return everything.min(axis=0), everything.max(axis=0)

    def _build_figure(self) -> None:
        from matplotlib.collections import PolyCollection
        from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

        fig, (flat, screen) = new_figure(
            2, width=8.4, height=4.3, gridspec_kw={"width_ratios": [1.7, 1]}
        )
        spec = flat.get_subplotspec()
        flat.remove()
        ax = fig.add_subplot(spec, projection="3d", computed_zorder=False)
        fig.subplots_adjust(left=0.0, right=0.97, bottom=0.11, top=0.93, wspace=0.12)
        self.polygons = Poly3DCollection([], linewidths=1.0, alpha=0.8)
        self.culled_faces = Poly3DCollection(
            [], facecolors=CULLED, edgecolors="0.45", linewidths=0.6, hatch="///", alpha=0.35
        )
        self.cut_off = Line3DCollection([], colors="0.3", linestyles="--", linewidths=0.9)
        self.volume = Line3DCollection([], colors="tab:blue", linewidths=1.2)
        self.rays = Line3DCollection([], colors="tab:blue", linewidths=0.7, linestyles=":")
        self.current = Line3DCollection([], colors="black", linewidths=2.2)
        # The back-face test drawn: V from the eye to the face, N out of the face.
        self.test_vectors = Line3DCollection([], colors=["0.2", "tab:purple"], linewidths=1.6)
        self.test_vectors.set_linestyles([":", "-"])
        artists = (self.culled_faces, self.polygons, self.cut_off, self.volume, self.rays)
        for artist in (*artists, self.current, self.test_vectors):
            ax.add_collection3d(artist, autolim=False)
        (self.eye_marker,) = ax.plot([], [], [], "o", color="black", ms=5)
        (self.markers,) = ax.plot([], [], [], "o", color=NEW_VERTEX, ms=4)
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_major_locator(MaxNLocator(3, steps=[1, 2, 2.5, 5, 10]))
        ax.tick_params(labelsize=9, pad=0)
        self.ax = ax

        self.screen = PolyCollection([], linewidths=1.0, alpha=0.6)
        screen.add_collection(self.screen)
        (self.screen_markers,) = screen.plot([], [], "o", color=NEW_VERTEX, ms=4, clip_on=False)
        screen.set_xlim(0, self.width)
        screen.set_ylim(0, self.height)
        screen.set_aspect("equal")
        screen.set_xlabel("x (pixels)", fontsize=9)
        screen.set_ylabel("y (pixels)", fontsize=9)
        screen.tick_params(labelsize=9)
        screen.xaxis.set_major_locator(MaxNLocator(4, integer=True))
        screen.yaxis.set_major_locator(MaxNLocator(4, integer=True))
        self.screen_note = screen.text(
            0.5,
            0.5,
            "the polygons reach\nthe screen at the\nlast step",
            transform=screen.transAxes,
            ha="center",
            va="center",
            fontsize=9,
            color="0.4",
        )
        screen.set_title("screen", fontsize=10)
        self.screen_ax = screen
        self.figure = fig
        self._canvas = figure_widget(fig)

    def _colors(self, numbers: list[int], cut: bool) -> tuple[list[str], list[str]]:
        """Fill and edge colours: the object's fill; orange edges on what the clipper cut."""
        fills = [self._fills[int(self.viewed.objects[k])] for k in numbers]
        edges = [CUT if cut and k in self.new_vertices else "0.25" for k in numbers]
        return fills, edges

    # --- showing a step ---------------------------------------------------------------------

    def show(self, step: int) -> None:
        """Draw the state after the first `step` steps."""
        stop = self._stop_at(step)
        before = self.trace[:step]
        self.space = stop.stage
        self.culled = frozenset(e.polygon for e in before if e.kind == "face_culled" and e.culled)
        clipped = {e.polygon: e for e in before if e.kind == "polygon_clipped"}
        current = self.trace[step - 1] if step else None
        self.matrix = None if stop.matrix is None else np.reshape(stop.matrix, (4, 4))

        drawn, cut_off, marks = self._polygons(stop, clipped)
        self.shown = dict(drawn)
        numbers = list(self.shown)
        self.polygons.set_verts([p for _, p in drawn])
        cut = [k for k in numbers if k in clipped or stop.stage in ("ndc", "display")]
        fills, edges = self._colors(numbers, True)
        edges = [e if k in cut else "0.25" for k, e in zip(numbers, edges, strict=True)]
        self.polygons.set_facecolor(fills)
        self.polygons.set_edgecolor(edges)
        ghosts = [] if stop.stage in ("ndc", "display") else sorted(self.culled)
        self.culled_faces.set_verts([np.array(stop.polygons[k])[:, :3] for k in ghosts])
        self.cut_off.set_segments(cut_off)
        marks = np.array(marks).reshape(-1, 3)
        self.markers.set_data_3d(*marks.T)
        self.corners = volume = np.array(stop.volume)[:, :3]
        self.volume.set_segments([volume[[a, b]] for a, b in VOLUME_EDGES])
        eye = np.array([stop.eye] if stop.eye is not None else []).reshape(-1, 3)
        self.eye_marker.set_data_3d(*eye.T)
        self.rays.set_segments(
            [np.vstack([eye[0], corner]) for corner in volume[:4]] if len(eye) else []
        )
        focus = current.polygon if current is not None and hasattr(current, "polygon") else None
        outline = []
        if focus is not None:
            points = np.array(stop.polygons[focus])[:, :3]
            if focus in clipped and clipped[focus].verdict == "clipped":
                points = np.array(clipped[focus].vertices)[:, :3]
            outline = [np.vstack([points, points[:1]])] if len(points) else []
        self.current.set_segments(outline)
        self.test_vectors.set_segments(self._test_vectors(current, stop))
        self._frame(stop.stage)
        self._show_screen(stop)
        self._show_tables(stop, current, clipped)
        refresh_figure(self.figure, self._canvas)

    def _polygons(self, stop, clipped):
        """(number, vertices) drawn, dashed outlines of what was cut off, new vertices, at `stop`."""
        drawn, cut_off, marks = [], [], []
        for k, vertices in enumerate(stop.polygons):
            if not vertices or (k in self.culled and stop.stage in ("world", "eye", "clip")):
                continue
            points = np.array(vertices)[:, :3]
            event = clipped.get(k)
            if stop.stage == "clip" and event is not None and event.verdict != "accepted":
                cut_off.append(np.vstack([points, points[:1]]))
                if event.verdict == "rejected":
                    continue
                points = np.array(event.vertices)[:, :3]
            after_clipping = stop.stage in ("ndc", "display") or event is not None
            if k in self.new_vertices and after_clipping:
                marks.extend(points[self.new_vertices[k]])
            drawn.append((k, points))
        return drawn, cut_off, marks

    def _test_vectors(self, current, stop) -> list[np.ndarray]:
        """V (eye to face) and N (out of the face, drawn at half V's length) of a back-face test."""
        if current is None or current.kind != "face_culled" or stop.eye is None:
            return []
        eye, view, normal = (np.array(v) for v in (stop.eye, current.view, current.normal))
        face = eye + view  # where V ends: the face's centroid
        length = float(np.linalg.norm(normal)) or 1.0
        arrow = 0.5 * float(np.linalg.norm(view)) * normal / length
        return [np.array([eye, face]), np.array([face, face + arrow])]

    def _frame(self, stage: str) -> None:
        """Axis limits, labels, view angle and title of the 3-D panel for `stage`."""
        ax = self.ax
        low, high = self._limits[stage]
        span = np.maximum(high - low, 1e-9)
        if stage in ("world", "eye"):  # lengths and angles are true here: equal scales
            middle, half = (low + high) / 2, span.max() / 2 * 1.05
            low, high, span = middle - half, middle + half, np.full(3, 2 * half)
        else:
            low, high = low - 0.05 * span, high + 0.05 * span
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[1], high[1])
        ax.set_zlim(low[2], high[2])
        up = "y"
        if stage == "world":
            up = "xyz"[int(np.argmax(np.abs(self.scene.camera.up)))]
        box = {"world": (1, 1, 1), "eye": (1, 1, 1), "display": (1, 1, 0.8)}.get(stage)
        ax.set_box_aspect(box or tuple(span / span.max()), zoom=1.1)
        # From beside the camera, a little above: the eye on the right, the view volume across.
        ax.view_init(
            elev=22, azim=-120 if stage == "world" and up == "y" else -110, vertical_axis=up
        )
        for axis, name in zip((ax.xaxis, ax.yaxis, ax.zaxis), "xyz", strict=True):
            axis.set_label_text(name, fontsize=9)
            axis.labelpad = 0
        ax.set_title(SPACE_NAMES[stage], fontsize=10)

    def _show_screen(self, stop) -> None:
        final = stop.stage == "display"
        numbers = [k for k, p in enumerate(stop.polygons) if p] if final else []
        self.screen.set_verts([np.array(stop.polygons[k])[:, :2] for k in numbers])
        fills, edges = self._colors(numbers, True)
        self.screen.set_facecolor(fills)
        self.screen.set_edgecolor(edges)
        marks = [
            np.array(stop.polygons[k])[self.new_vertices[k], :2]
            for k in numbers
            if k in self.new_vertices
        ]
        marks = np.vstack(marks) if marks else np.zeros((0, 2))
        self.screen_markers.set_data(*marks.T)
        self.screen_note.set_visible(not final)

    def _show_tables(self, stop, current, clipped) -> None:
        if current is not None and current.kind == "face_culled":
            self.step_table.value = _cull_table(current, self._name(current.polygon))
            self.vertex_table.value = self._vertices(current.polygon, "world")
            return
        if current is not None and current.kind == "polygon_clipped":
            self.step_table.value = _clip_table(current, self._name(current.polygon))
            self.vertex_table.value = self._vertices(current.polygon, "clip", current)
            return
        if stop.matrix is None:
            self.step_table.value = f"<i>{html.escape(NO_MATRIX[stop.stage])}</i>"
        else:
            name, meaning = MATRICES[stop.stage]
            rows = _tidy(np.reshape(stop.matrix, (4, 4)))
            self.step_table.value = (
                f"<b>{name}</b><br><span style='font-size:12px'>{html.escape(meaning)}</span>"
                + html_table(("", "", "", ""), rows)
            )
        self.vertex_table.value = self._vertices(self.follow, stop.stage, clipped.get(self.follow))

    def _vertices(self, polygon: int, stage: str, clip_event=None) -> str:
        """A few vertices of `polygon` at `stage` (its clipped vertices once the clipper ran)."""
        event = self.stops[stage]
        rows = list(event.polygons[polygon])
        made = self.new_vertices.get(polygon, [])
        if stage == "clip" and clip_event is not None:
            rows = list(clip_event.vertices)
        elif stage == "clip" or stage not in ("ndc", "display"):
            made = []
        columns = ("x", "y", "z", "w") if stage == "clip" else ("x", "y", "z")
        if not rows:
            gone = "culled" if polygon in self.culled else "clipped away"
            return f"<b>{html.escape(self._name(polygon))}</b>: {gone}, no vertices left."
        shown = rows[:MAX_ROWS]
        more = f"<br><i>… and {len(rows) - len(shown)} more</i>" if len(rows) > len(shown) else ""
        states = ["current" if i in made else "" for i in range(len(shown))]
        note = " (new vertices highlighted)" if made else ""
        return (
            f"<b>{html.escape(self._name(polygon))}</b> in {SPACE_NAMES[stage].split(' (')[0]}"
            f"{note}"
            + html_table(
                ("vertex", *columns), [(i, *r) for i, r in enumerate(_tidy(shown))], states=states
            )
            + more
        )


def _cull_table(event, name: str) -> str:
    """The back-face test of one face: N, V and their dot product, with the verdict."""
    verdict = "culled: it turns away" if event.culled else "kept: it faces the eye"
    normal, view = _tidy([event.normal, event.view])
    rows = [("N (outward normal)", *normal), ("V (eye to face)", *view)]
    return (
        f"<b>back-face test of {html.escape(name)}</b><br>"
        f"<span style='font-size:12px'>N · V = {event.dot:.4g}: {verdict}</span>"
        + html_table(("", "x", "y", "z"), rows)
    )


def _clip_table(event, name: str) -> str:
    """The clip of one polygon: each input vertex's planes outside, the count after each plane."""
    rows = [(i, ", ".join(_planes(code)) or "inside") for i, code in enumerate(event.outcodes)]
    counts = ""
    if event.counts:
        after = ", ".join(f"{p} {n}" for p, n in zip(CLIP_PLANES, event.counts, strict=False))
        counts = f"<br><span style='font-size:12px'>vertices after each plane: {after}</span>"
    return (
        f"<b>clipping {html.escape(name)}</b>: {event.verdict}<br>"
        "<span style='font-size:12px'>outcode of each input vertex: the planes it is outside</span>"
        + html_table(("vertex", "outside"), rows[:MAX_ROWS])
        + counts
    )


def viewing_stepper(
    scene, width: int, height: int, *, cull: bool | None = None, follow=None
) -> Stepper:
    """A `Stepper` over a scene's viewing pipeline (`ViewingPipelineView`).

    Examples
    --------
    >>> from scanviz.scene.builtin import builtin_scene
    >>> stepper = viewing_stepper(builtin_scene("sphere", level=0), 64, 64)
    >>> stepper.next_button.click()
    >>> stepper.label.value
    'step 1 / 32: face_culled'
    """
    view = ViewingPipelineView(scene, width, height, cull=cull, follow=follow)
    return Stepper(view.trace, [view], title="The viewing pipeline")

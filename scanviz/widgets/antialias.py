"""Wang's area-sampled lines, column by column (`dislop_stepper`), and figures beside their peers.

* `dislop_stepper`: DISLOP_L (Wang 1989, §4.2, Figs 4-1..4-3) one column per
  step, drawn from the ``dislop_column`` events of
  `scanviz.antialias.dislop_line`: the band of width 1 around the segment,
  the coverage of the columns done, the current column with its three (or
  four) pixels and their areas; the text gives the slope, dxy, the critical
  values of Fig 4-2 and the branch they select, and the areas against
  sec(a), the constant intensity per column. With the printed formula and a
  slope over 0.75 it also gives the exact areas (``exact=True``) and the
  difference: where Wang's (1989) formula is inexact.
* `plot_coverage_comparison`: the midpoint line, Wu, Gupta-Sproull, 4x4
  supersampling, DISLOP_L and the exact band, each with its error map.
* `plot_ropiness` (data: `scanviz.antialias.compare.intensity_per_length`): intensity per unit length
  against the angle: DISLOP_L's constant intensity against the ropiness of
  the others.
* `plot_period_table`: the per-slope periodic look-up table of §3.7.
* `plot_post_antialias`: an image before and after post-anti-aliasing, with
  a zoomed region.
"""

from __future__ import annotations

import math
import numbers

import ipywidgets as widgets
import numpy as np
from matplotlib.patches import Polygon as PolygonPatch
from matplotlib.patches import Rectangle
from matplotlib.patheffects import withStroke

from ..antialias import dislop_line
from ..antialias.compare import coverage_methods, intensity_per_length
from ..antialias.line import canonical
from ..antialias.peers import band_rectangle
from ..conventions import as_array, short_repr
from ..geometry import as_coordinates
from ..trace import Trace
from ._common import WIDEST, fmt, html_table, new_figure, note_label, pixel_image, pixel_region
from .stepper import Stepper, draw_pixel_grid, figure_widget, refresh_figure, stepper_of

__all__ = [
    "DislopView",
    "dislop_stepper",
    "plot_coverage_comparison",
    "plot_period_table",
    "plot_post_antialias",
    "plot_ropiness",
]

DIGITS = 4  # significant digits of the values in the text
EXACT_SLOPE = 0.75  # up to this slope the printed formula is exact (Wang 1989, ch. 4)
ROLES = ("upper", "middle", "lower", "spill")
OFFSETS = {"upper": 1, "middle": 0, "lower": -1}  # rows from the middle pixel, first octant
BAND_COLOR, LINE_COLOR, COLUMN_COLOR = "tab:orange", "crimson", "#ffd54f"
NOTHING = (
    "<i>nothing to step: the line has zero length, or none of its columns reaches the raster</i>"
)
LABEL_POINTS = 20.0  # a pixel this wide (points) holds a 9 pt area label such as '.87'


# ---------------------------------------------------------------- the stepper


class DislopView:
    """The band, the coverage of the columns done and the current column's arithmetic.

    Parameters
    ----------
    p0, p1 : (2,) array_like of float
        The segment's endpoints, as given to `dislop_line`.
    trace : Trace
        The ``dislop_column`` events of ``dislop_line(..., trace=True)`` (others are ignored).
    exact_trace : Trace or None
        The same line's events with ``exact=True``, to compare with (None: no comparison).
    width, height : int
        The raster size.
    exact : bool
        Whether `trace` is of the exact run.
    note : str, optional
        Shown above the figure.

    Attributes
    ----------
    steps : Trace
        The ``dislop_column`` events with a pixel on the raster: one step each
        (give it to the `Stepper`).
    exact_steps : list of DislopColumn or None
        The exact run's event of each step's column, when there is a comparison.
    widget : ipywidgets.VBox
    figure : matplotlib Figure
    coverage : matplotlib AxesImage
        The areas written by the columns done (greys, 1 black), row 0 at the bottom.
    column_patch, pixel_patch : matplotlib Rectangle
        The current column (row, for a steep line) and its middle pixel.
    labels : dict of str to matplotlib Text
        The areas of the current column's pixels, by role (`ROLES`).
    text : ipywidgets.HTML
        The current column.
    """

    def __init__(
        self,
        p0,
        p1,
        trace: Trace,
        exact_trace: Trace | None,
        *,
        width: int,
        height: int,
        exact: bool = False,
        note: str = "",
    ) -> None:
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        if exact_trace is not None and not isinstance(exact_trace, Trace):
            raise TypeError(f"'exact_trace' must be a scanviz Trace or None; got {exact_trace!r}")
        p0, p1 = as_coordinates(p0, "'p0'", (2,)), as_coordinates(p1, "'p1'", (2,))
        self.width, self.height, self.exact = max(width, 1), max(height, 1), exact
        _, _, _, _, self.steep, self.flip = canonical(p0, p1)
        minor = -1 if self.flip else 1  # the raster step of one first-octant row up
        self._up = (minor, 0) if self.steep else (0, minor)
        events = [e for e in trace if e.kind == "dislop_column"]
        exact_events = [e for e in exact_trace if e.kind == "dislop_column"] if exact_trace else []
        pairs = zip(events, exact_events or [None] * len(events), strict=True)
        kept = [(e, x) for e, x in pairs if self._on_raster(e)]
        self.steps = Trace(e for e, _ in kept)
        self.exact_steps = [x for _, x in kept] if exact_events else None
        self._skipped = len(events) - len(kept)
        self._read_columns()
        self._build_figure(p0, p1)
        self.text = widgets.HTML(layout={"flex": "1 1 380px"})
        self.note = note_label(note)
        self._canvas = figure_widget(self.figure)
        self.widget = widgets.VBox(
            [
                self.note,
                widgets.HBox(
                    [self._canvas, self.text],
                    layout={"align_items": "flex-start", "flex_flow": "row wrap"},
                ),
            ]
        )
        self.step = 0
        self.show(0)

    def _build_figure(self, p0: np.ndarray, p1: np.ndarray) -> None:
        """The coverage so far over the pixel grid, the band, the line and the step's markers."""
        fig, (ax,) = new_figure(1, width=6.0, height=5.4)
        self.region = pixel_region(np.vstack([p0, p1]), self.width, self.height, 2)
        blank = np.zeros((self.height, self.width))
        self.coverage = pixel_image(ax, blank, cmap="Greys", vmin=0.0, vmax=1.0)
        draw_pixel_grid(ax, self.region)
        corners = band_rectangle(p0, p1, self.width, self.height)
        if corners is not None:
            ax.add_patch(PolygonPatch(corners, fc=BAND_COLOR, alpha=0.18, ec="none", zorder=2))
            ax.add_patch(PolygonPatch(corners, fill=False, ec=BAND_COLOR, lw=1.4, zorder=3))
        ax.plot(*np.vstack([p0, p1]).T, color=LINE_COLOR, lw=1.0, zorder=3)
        self.column_patch = Rectangle(
            (0, 0), 1, 1, fc=COLUMN_COLOR, alpha=0.35, ec="none", zorder=1.8, visible=False
        )
        self.pixel_patch = Rectangle(
            (0, 0), 1, 1, fill=False, ec="tab:blue", lw=2.2, zorder=4, visible=False
        )
        ax.add_patch(self.column_patch)
        ax.add_patch(self.pixel_patch)
        ax.set(xlim=self.region[:2], ylim=self.region[2:], aspect="equal")
        ax.tick_params(labelsize=9)
        ax.set_title(
            f"DISLOP_L ({'exact band' if self.exact else 'printed formula'}): coverage so far",
            fontsize=9,
        )
        fig.tight_layout()
        self._labelled = _pixel_points(fig, ax, self.region) >= LABEL_POINTS
        halo = [withStroke(linewidth=2.5, foreground="white")]
        self.labels = {
            role: ax.text(0, 0, "", ha="center", va="center", fontsize=9, zorder=5,
                          path_effects=halo, visible=False)
            for role in ROLES
        }  # fmt: skip
        self.figure, self.ax = fig, ax

    def _pixels(self, event) -> dict[str, tuple[int, int]]:
        """The raster pixel of each role in `event`'s column (the spill on the side of dxy)."""
        rows = {**OFFSETS, "spill": 2 if event.dxy > 0.0 else -2}
        ux, uy = self._up
        return {role: (event.x + r * ux, event.y + r * uy) for role, r in rows.items()}

    def _on_raster(self, event) -> bool:
        return any(
            0 <= x < self.width and 0 <= y < self.height for x, y in self._pixels(event).values()
        )

    def _read_columns(self) -> None:
        """Each step's four pixels and areas, once: (N, 4) arrays in `ROLES` order."""
        pixels = [[self._pixels(e)[role] for role in ROLES] for e in self.steps]
        grid = np.array(pixels, np.int64).reshape(-1, len(ROLES), 2)
        self._xs, self._ys = grid[..., 0], grid[..., 1]
        areas = [[e.up, e.mid, e.low, e.spill] for e in self.steps]
        self._areas = np.array(areas).reshape(-1, len(ROLES))

    def image(self, step: int) -> np.ndarray:
        """(height, width) float64: the areas the first `step` columns wrote, on the raster."""
        image = np.zeros((self.height, self.width))
        xs, ys, areas = self._xs[:step], self._ys[:step], self._areas[:step]
        inside = (xs >= 0) & (xs < self.width) & (ys >= 0) & (ys < self.height) & (areas != 0.0)
        image[ys[inside], xs[inside]] = areas[inside]  # each pixel is in one column only
        return image

    def show(self, step: int) -> None:
        """Show the coverage after the first `step` columns, and column `step`."""
        self.step = int(step)
        self.coverage.set_data(self.image(self.step))
        column = self.steps[self.step - 1] if self.step else None
        for artist in (self.column_patch, self.pixel_patch, *self.labels.values()):
            artist.set_visible(
                column is not None and (artist not in self.labels.values() or self._labelled)
            )
        if column is not None:
            self._mark(column)
        self.text.value = self._describe(column)
        refresh_figure(self.figure, self._canvas)

    def _mark(self, column) -> None:
        x_start, x_end, y_start, y_end = self.region
        if self.steep:  # a row of pixels
            self.column_patch.set_bounds(x_start, column.y, x_end - x_start, 1)
        else:
            self.column_patch.set_bounds(column.x, y_start, 1, y_end - y_start)
        self.pixel_patch.set_xy((column.x, column.y))
        exact = self.exact_steps[self.step - 1] if self._compares() else None
        for role, (x, y) in self._pixels(column).items():
            area = _role_area(column, role)
            label = self.labels[role]
            text = _short(area)
            if exact is not None and role == "spill":  # the area the printed formula leaves out
                text = f"0\n(ex {_short(_role_area(exact, role))})"
            label.set_position((x + 0.5, y + 0.5))
            label.set_text(text)
            label.set_visible(
                self._labelled and (bool(area) or role != "spill" or exact is not None)
            )

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the column, its slope and dxy, the branch they
        select and the areas written."""
        if not self.steps:
            return "Nothing to step: the line has zero length or misses the raster."
        if step == 0:
            return (
                f"The start: {len(self.steps)} {'rows' if self.steep else 'columns'} to walk; each "
                "writes the band's area in the pixels it crosses, three (or four) per column."
            )
        column = self.steps[step - 1]
        where = f"Row y = {column.y}" if self.steep else f"Column x = {column.x}"
        branch = {
            "flat": "the line is flat, so only the middle and upper pixels are met",
            "two": f"|dxy| > fcv = {fmt(column.fcv, 3)}, so the band meets two pixels",
            "three": f"|dxy| ≤ fcv = {fmt(column.fcv, 3)} and scv = {fmt(column.scv, 3)} > m/2,"
            " so the band meets three pixels (a trapezoid beyond the middle one)",
            "three_triangle": f"|dxy| ≤ fcv = {fmt(column.fcv, 3)} and scv = "
            f"{fmt(column.scv, 3)} ≤ m/2, so the band meets three pixels (a triangle beyond)",
            "cap": "it is an end column, so the band is clipped exactly against each pixel",
            "exact": "the exact band area is taken, up to four pixels",
        }.get(column.branch, f"branch {column.branch}")
        areas = ", ".join(
            f"{role} {_role_area(column, role):.3f}"
            for role in ROLES
            if role != "spill" or column.spill
        )
        total = sum(_role_area(column, role) for role in ROLES)
        return (
            f"{where}: slope m = {fmt(column.slope, 3)}, dxy = {fmt(column.dxy, 3)}; {branch}: "
            f"{areas} (sum {total:.3f})."
        )

    def _role_name(self, role: str, dxy: float) -> str:
        """The first-octant role and where it lies on the raster: 'upper (right)' for a steep line."""
        sides = {(0, 1): ("above", "below"), (0, -1): ("below", "above"),
                 (1, 0): ("right", "left"), (-1, 0): ("left", "right")}[self._up]  # fmt: skip
        if role == "middle":
            return role
        if role == "spill":
            return f"spill (2 {sides[0] if dxy > 0.0 else sides[1]})"
        return f"{role} ({sides[0] if role == 'upper' else sides[1]})"

    def _compares(self) -> bool:
        """Show the exact areas: the printed formula on a slope where it can be inexact."""
        return (
            self.exact_steps is not None and bool(self.steps) and self.steps[0].slope > EXACT_SLOPE
        )

    def _describe(self, column) -> str:
        if not self.steps:
            return NOTHING
        skipped = f" ({self._skipped} more lie wholly off the raster)" if self._skipped else ""
        if column is None:
            axis = "row by row (y is the major axis)" if self.steep else "column by column"
            return (
                f"<i>start: {len(self.steps)} columns to walk{skipped}, {axis}; "
                "press next for the first</i>"
            )
        m, dxy = column.slope, column.dxy
        thickness = math.sqrt(1.0 + m * m)
        angle = math.degrees(math.atan(m))
        where = f"row y = {column.y}" if self.steep else f"column x = {column.x}"
        head = (
            f"<b>column {self.step} of {len(self.steps)}</b>{skipped}: {where}, "
            f"middle pixel ({column.x}, {column.y})<br>"
            f"in the first-octant frame the centre line is y = dxy + m x about the middle "
            f"pixel's centre{_frame(self.steep, self.flip)}<br>"
            f"slope <b>m = {fmt(m, DIGITS)}</b> (a = {angle:.2f}°), "
            f"<b>dxy = {fmt(dxy, DIGITS)}</b>, Ta = sec a = √(1 + m²) = {fmt(thickness, DIGITS)}, "
            f"dw = Ta − 1 = {fmt(thickness - 1.0, DIGITS)}<br>"
        )
        return head + self._critical(column) + self._areas_table(column, thickness)

    def _critical(self, column) -> str:
        m, ad, fcv, scv = column.slope, abs(column.dxy), column.fcv, column.scv
        values = (
            f"<b>fcv = (m + dw)/2 = {fmt(fcv, DIGITS)}</b>: the first critical value; "
            f"the band reaches the pixel on the far side of the middle one from the centre line "
            "(lower if dxy &ge; 0) only while |dxy| &le; fcv<br>"
            f"<b>scv = |dxy| + dw/2 = {fmt(scv, DIGITS)}</b>: the second; the band's mean "
            "height beyond the middle pixel on the near side (upper if dxy &ge; 0), "
            f"a trapezoid while scv &gt; m/2 = {fmt(m / 2, DIGITS)}, else a triangle<br>"
        )
        if m == 0.0:
            interval, branch = "m = 0", "flat"
        elif ad > fcv:
            interval, branch = f"|dxy| = {fmt(ad, DIGITS)} &gt; fcv", "two"
        elif scv > 0.5 * m:
            interval, branch = f"|dxy| = {fmt(ad, DIGITS)} &le; fcv and scv &gt; m/2", "three"
        else:
            interval, branch = (
                f"|dxy| = {fmt(ad, DIGITS)} &le; fcv and scv &le; m/2",
                "three_triangle",
            )
        meaning = {
            "flat": "upper = |dxy|, lower = 0",
            "two": "two pixels: upper = scv, lower = 0",
            "three": "three pixels: upper = scv (a trapezoid), lower = (fcv − |dxy|)²/(2m)",
            "three_triangle": "three pixels: upper = (|dxy| + fcv)²/(2m), lower = (fcv − |dxy|)²/(2m)",
        }[branch]
        swap = "; dxy &lt; 0, so upper and lower swap" if column.dxy < 0.0 else ""
        taken = f"{interval} &rarr; <b>{branch}</b>: {meaning}{swap}; middle = Ta − upper − lower"
        if column.branch == "cap":
            taken = (
                "<b>cap</b>: an end column (Fig 4-3): the rectangle is clipped exactly against "
                f"each pixel (the middle formula would take: {taken})"
            )
        elif column.branch == "exact":
            taken = (
                "<b>exact</b>: the exact band area in five rows, the fourth pixel included "
                f"(the printed formula would take: {taken})"
            )
        else:
            taken = f"branch taken: {taken}"
        return values + taken + "<br>"

    def _areas_table(self, column, thickness: float) -> str:
        exact = self.exact_steps[self.step - 1] if self._compares() else None
        pixels = self._pixels(column)
        areas = [_role_area(column, role) for role in ROLES]
        columns = ("pixel", "raster (x, y)", "area")
        rows = [
            [self._role_name(role, column.dxy), pixels[role], area]
            for role, area in zip(ROLES, areas, strict=True)
        ]
        if exact is not None:
            columns += ("exact", "formula − exact")
            for row, role, area in zip(rows, ROLES, areas, strict=True):
                row += [_role_area(exact, role), area - _role_area(exact, role)]
        total = sum(areas)
        rows.append(
            ["sum", "", total] + ([sum(_role_area(exact, r) for r in ROLES), ""] if exact else [])
        )
        if column.branch == "cap":
            summary = (
                f"sum = {fmt(total, DIGITS)}: an end column holds only the part of the band "
                f"it spans (a full column holds Ta = {fmt(thickness, DIGITS)})"
            )
        else:
            summary = (
                f"sum = {fmt(total, DIGITS)} = sec a = Ta = {fmt(thickness, DIGITS)}: "
                "every column holds the same area, so the intensity per unit length is constant"
            )
        if exact is not None and column.branch != "cap":
            worst = max(abs(a - _role_area(exact, r)) for a, r in zip(areas, ROLES, strict=True))
            summary += (
                f"<br>m &gt; {EXACT_SLOPE}: the band can reach a fourth pixel, whose area the "
                f"printed formula credits to its neighbour; here it is off by up to "
                f"{fmt(worst, DIGITS)} of a pixel (at most 0.0214, at m = 1)"
            )
        elif self.exact_steps is not None and column.branch != "cap":
            summary += f"<br>m &le; {EXACT_SLOPE}: the printed formula is exact here"
        return html_table(columns, rows) + summary


def _frame(steep: bool, flip: bool) -> str:
    """How the raster reaches the first-octant frame (§3.1), as a parenthesis."""
    moves = (["x and y swapped (a steep line)"] if steep else []) + (
        ["the minor axis negated (a falling line)"] if flip else []
    )
    return f" ({'; '.join(moves)})" if moves else ""


def _role_area(event, role: str) -> float:
    return {"upper": event.up, "middle": event.mid, "lower": event.low, "spill": event.spill}[role]


def _pixel_points(figure, axes, region) -> float:
    """The side of one pixel of `region` on `axes`, in points."""
    box = axes.get_window_extent().transformed(figure.dpi_scale_trans.inverted())
    pixels = max(region[1] - region[0], region[3] - region[2])
    return float(min(box.width, box.height) * 72 / pixels)


def _short(area: float) -> str:
    """An area in a pixel label: '.87', '1', '0'.

    >>> [_short(a) for a in (0.0, 0.8712, 0.004, 1.0)]
    ['0', '.87', '0', '1']
    """
    text = f"{area:.2f}".rstrip("0").rstrip(".")
    return text.removeprefix("0") if text not in ("0", "1") else text


def dislop_stepper(p0, p1, width: int, height: int, *, exact: bool = False) -> Stepper:
    """Draw a line with traced DISLOP_L and step through its columns in a `DislopView`.

    Parameters
    ----------
    p0, p1, width, height, exact
        As for `scanviz.antialias.dislop_line` (and its errors). With
        ``exact=False`` the exact run is traced too, to compare with.

    Returns
    -------
    Stepper
        ``.views[0]`` is the `DislopView`; one step per column (per row for a
        steep line) that has a pixel on the raster.

    Examples
    --------
    >>> stepper = dislop_stepper((1.2, 1.7), (9.6, 9.1), 12, 11)
    >>> stepper.slider.max, stepper.views[0].steps[4].branch
    (11, 'three_triangle')
    >>> stepper.slider.value = 5
    >>> "m &gt; 0.75" in stepper.views[0].text.value
    True
    """
    _, trace = dislop_line(p0, p1, width, height, trace=True, exact=exact)
    exact_trace = None if exact else dislop_line(p0, p1, width, height, trace=True, exact=True)[1]
    view = DislopView(p0, p1, trace, exact_trace, width=width, height=height, exact=exact)
    return stepper_of(view, "DISLOP_L: one column per step", "columns")


# ---------------------------------------------------------------- the peers side by side


def plot_coverage_comparison(p0, p1, width: int, height: int):
    """The line p0-p1 by six methods, each above its error against the exact band area.

    Parameters
    ----------
    p0, p1 : (2,) array_like of float
        Endpoints (x, y) in pixels, within +-2**20.
    width, height : int
        Raster size in pixels, in 1..2**16.

    Returns
    -------
    matplotlib.figure.Figure
        Three methods to a row: the coverage of the midpoint line (binary,
        between the pixels holding the endpoints), Wu, Gupta-Sproull, 4x4
        supersampling, DISLOP_L and the exact band, each titled with its
        intensity per unit length (the image's sum over the segment's length),
        above its error: method − exact, on one scale (the binary line's larger
        errors saturate; its title gives them).

    Raises
    ------
    TypeError, ValueError
        As `scanviz.antialias.peers.exact_band_line`.

    Examples
    --------
    >>> figure = plot_coverage_comparison((1.3, 2.2), (13.6, 8.1), 16, 11)
    >>> figure.axes[8].get_title()  # each method's coverage, then its error
    'DISLOP_L\\nI/length = 1'
    """
    from matplotlib.figure import Figure

    images = coverage_methods(p0, p1, width, height)
    p0, p1 = as_coordinates(p0, "'p0'", (2,)), as_coordinates(p1, "'p1'", (2,))
    length = float(np.hypot(*(p1 - p0)))
    exact = images["exact band"]
    errors = {name: image - exact for name, image in images.items()}
    scale = max(
        (float(np.abs(e).max(initial=0.0)) for n, e in errors.items() if n != "midpoint (binary)"),
        default=0.0,
    )
    scale = scale or 1.0  # all exact: any scale shows zeros
    per_row = 3  # methods side by side: a 9 pt title fits a panel a third of the figure wide
    blocks = math.ceil(len(images) / per_row)
    aspect = min(max(exact.shape[0] / max(exact.shape[1], 1), 0.4), 1.5)
    side = (WIDEST - 0.9) / per_row  # inches per panel, the colour bars aside
    figure = Figure(figsize=(WIDEST, 2 * blocks * (side * aspect + 0.55) + 0.5))
    grid = figure.add_gridspec(2 * blocks, per_row + 1, width_ratios=[1] * per_row + [0.06])
    for k, (name, image) in enumerate(images.items()):
        row, column = 2 * (k // per_row), k % per_row
        top = figure.add_subplot(grid[row, column])
        picture = pixel_image(top, image, cmap="Greys", vmin=0.0, vmax=1.0)
        intensity = fmt(float(image.sum()) / length, 4) if length else "–"
        top.set_title(f"{name}\nI/length = {intensity}", fontsize=9)
        bottom = figure.add_subplot(grid[row + 1, column])
        error = pixel_image(bottom, errors[name], cmap="RdBu_r", vmin=-scale, vmax=scale)
        bottom.set_title(
            f"max |error| {fmt(float(np.abs(errors[name]).max(initial=0.0)), 3)}", fontsize=9
        )
        for axes in (top, bottom):
            axes.set_xticks([])
            axes.set_yticks([])
    figure.colorbar(picture, cax=figure.add_subplot(grid[0, per_row])).ax.tick_params(labelsize=9)
    bar = figure.colorbar(error, cax=figure.add_subplot(grid[1, per_row]))
    bar.ax.tick_params(labelsize=9)
    bar.set_label("method − exact", fontsize=9)
    figure.suptitle(
        f"({fmt(p0[0])}, {fmt(p0[1])})–({fmt(p1[0])}, {fmt(p1[1])}), length {fmt(length)}: "
        "coverage,\nand below it the error against the exact band area",
        fontsize=10,
    )
    figure.tight_layout()
    return figure


# ---------------------------------------------------------------- ropiness


def plot_ropiness(angles, length: float, width: int, height: int):
    """Intensity per unit length against the line's angle: DISLOP_L's constant intensity and the others' ropiness.

    Parameters
    ----------
    angles, length, width, height
        As for `intensity_per_length` (and its errors).

    Returns
    -------
    matplotlib.figure.Figure
        One line per method; the exact band's 1 dashed.

    Examples
    --------
    >>> figure = plot_ropiness(range(0, 91, 15), 20, 32, 32)
    >>> [line.get_label() for line in figure.axes[0].lines][-1]
    'DISLOP_L'
    """
    from matplotlib.figure import Figure

    data = intensity_per_length(angles, length, width, height)
    angles = np.asarray(angles, dtype=np.float64)  # checked by intensity_per_length
    figure = Figure(figsize=(7.0, 4.2))
    axes = figure.add_subplot()
    axes.axhline(1.0, color="0.6", ls="--", lw=1, label="exact area (1)")
    styles = {"DISLOP_L": {"lw": 2.2, "color": "black"}, "Wu": {"lw": 1.4}}
    for name, values in data.items():
        axes.plot(angles, values, marker=".", ms=3, label=name, **styles.get(name, {"lw": 1.0}))
    axes.set_xlim(0, 90)
    axes.set_xticks(range(0, 91, 15))
    axes.set_xlabel("angle of the line (degrees)")
    axes.set_ylabel("intensity per unit length")
    axes.set_title(
        f"a {fmt(float(length))}-px line, its middle columns: DISLOP_L is constant, "
        "the others are ropy",
        fontsize=9,
    )
    axes.legend(fontsize=9, loc="lower left")
    axes.grid(alpha=0.3)
    figure.tight_layout()
    return figure


# ---------------------------------------------------------------- the periodic table of §3.7


def plot_period_table(m: float, levels: int = 64, period: int | None = None):
    """The per-slope periodic look-up table of §3.7: the three areas over one period, and their levels.

    Parameters
    ----------
    m, levels, period
        As for `scanviz.antialias.tables.periodic_table` (a line's table):
        the first-octant slope, the intensity levels (the dissertation: 16,
        64 or 256) and the period p (default: the printed one, else scanviz's rule).

    Returns
    -------
    matplotlib.figure.Figure
        Left, the upper, middle and lower areas of the table's entries
        dxy_j = -1/2 + j/p, j = 0..p, over the formula between them; right,
        their intensities floor(A (levels - 1) + 1/2). The title gives the
        period, m·p, the nearest integer n and the residual abs(m·p - n).

    Raises
    ------
    TypeError, ValueError
        As `periodic_table`.

    Examples
    --------
    >>> from scanviz.antialias.tables import degree_slope
    >>> figure = plot_period_table(degree_slope(5), 64)  # Table 4-5
    >>> figure.axes[1].get_title()
    'intensities floor(A·63 + 1/2): 58 × 3 entries'
    """
    from matplotlib.figure import Figure

    from ..antialias.columns import line_column
    from ..antialias.tables import periodic_table

    table = periodic_table(m, levels, period)
    p = table.period
    fine = np.linspace(-0.5, 0.5, 401)
    curves = np.array([line_column(table.m, d)[:3] for d in fine])
    figure = Figure(figsize=(WIDEST, 3.8))
    left, right = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    colors = ("tab:red", "black", "tab:blue")
    for k, (role, color) in enumerate(zip(("upper", "middle", "lower"), colors, strict=True)):
        left.plot(fine, curves[:, k], color=color, lw=0.8, alpha=0.45)
        left.plot(table.dxy, table.areas[:, k], ".", color=color, ms=5, label=role)
        right.step(np.arange(p + 1), table.intensities[:, k], where="mid",
                   color=color, lw=1.2, label=role)  # fmt: skip
    left.set_xlabel("dxy (distance of the centre line from the middle pixel centre)")
    left.set_ylabel("area")
    left.set_xlim(-0.5, 0.5)
    left.set_title(
        f"areas at dxy_j = −1/2 + j/{p}, j = 0..{p} (dots); the formula (lines)", fontsize=9
    )
    right.set_xlabel("table entry j")
    right.set_ylabel(f"intensity level (0..{table.levels - 1})")
    right.set_ylim(-0.5, table.levels - 0.5)
    right.set_title(
        f"intensities floor(A·{table.levels - 1} + 1/2): {p + 1} × 3 entries", fontsize=9
    )
    for axes in (left, right):
        axes.legend(fontsize=9)
        axes.grid(alpha=0.3)
        axes.tick_params(labelsize=9)
    figure.suptitle(
        f"m = {fmt(table.m)} (a = {math.degrees(math.atan(table.m)):.2f}°), {table.levels} levels: "
        f"period p = {p}, m·p = {fmt(table.value, 6)}, n = {table.n}, "
        f"residual |m·p − n| = {fmt(table.residual, 3)} ({fmt(table.precision, 3)} levels)",
        fontsize=9,
    )
    figure.tight_layout()
    return figure


# ---------------------------------------------------------------- post-anti-aliasing


def _check_image(name: str, image: object) -> np.ndarray:
    values = as_array(image, f"{name!r} must be an (H, W) or (H, W, 3) float array")
    if not (values.ndim == 2 or (values.ndim == 3 and values.shape[2] == 3)):
        raise ValueError(f"{name!r} must be an (H, W) or (H, W, 3) array; got shape {values.shape}")
    if not np.isfinite(values).all() or ((values < 0) | (values > 1)).any():
        raise ValueError(f"{name!r} must hold finite values in [0, 1]")
    return values


def _check_zoom(zoom: object, width: int, height: int) -> tuple[int, int, int, int]:
    if (
        not isinstance(zoom, tuple | list)
        or len(zoom) != 4
        or not all(isinstance(v, numbers.Integral) and not isinstance(v, bool) for v in zoom)
    ):
        raise TypeError(
            f"'zoom' must be (x_start, y_start, x_end, y_end), 4 ints; got {short_repr(zoom)}"
        )
    x_start, y_start, x_end, y_end = (int(v) for v in zoom)
    if not (0 <= x_start < x_end <= width and 0 <= y_start < y_end <= height):
        raise ValueError(
            f"'zoom' must satisfy 0 <= x_start < x_end <= {width} and "
            f"0 <= y_start < y_end <= {height}; got {short_repr(zoom)}"
        )
    return x_start, y_start, x_end, y_end


def _default_zoom(before: np.ndarray, after: np.ndarray) -> tuple[int, int, int, int]:
    """A square of side about a quarter of the image around the pixel that changed most."""
    height, width = before.shape[:2]
    change = np.abs(after - before).reshape(height, width, -1).max(axis=2)
    y, x = np.unravel_index(int(np.argmax(change)), change.shape)
    side = max(min(width, height) // 4, 1)
    x_start = min(max(int(x) - side // 2, 0), width - side)
    y_start = min(max(int(y) - side // 2, 0), height - side)
    return x_start, y_start, x_start + side, y_start + side


def plot_post_antialias(before, after, *, zoom=None):
    """An image before and after post-anti-aliasing, side by side, each with a zoomed region.

    Parameters
    ----------
    before, after : (H, W) or (H, W, 3) array_like of float in [0, 1]
        The same height and width (a grey one beside a colour one is shown
        as colour); row 0 at the bottom.
    zoom : (x_start, y_start, x_end, y_end) of int, optional
        The region magnified (half-open pixel ranges); by default a square of
        a quarter of the image's side around the pixel that changed most.

    Returns
    -------
    matplotlib.figure.Figure
        Before, its zoomed region, after, its zoomed region (the region outlined in the whole images).

    Raises
    ------
    TypeError, ValueError
        If an image is not an (H, W) or (H, W, 3) array of values in [0, 1],
        the shapes differ, or `zoom` is not 4 ints inside the image.

    Examples
    --------
    >>> before = np.zeros((8, 8)); before[2:6, 2:6] = 1.0
    >>> after = before.copy(); after[2:6, 1] = 0.5
    >>> figure = plot_post_antialias(before, after, zoom=(0, 0, 4, 8))
    >>> [axes.get_title() for axes in figure.axes]
    ['before', 'before, x 0..4, y 0..8', 'after', 'after, x 0..4, y 0..8']
    """
    from matplotlib.figure import Figure

    before, after = _check_image("before", before), _check_image("after", after)
    if before.ndim != after.ndim:  # grey beside colour (post_antialias gives RGB): both RGB
        before, after = (np.dstack([i] * 3) if i.ndim == 2 else i for i in (before, after))
    if before.shape != after.shape:
        raise ValueError(
            f"'before' and 'after' must have one shape; got {before.shape} and {after.shape}"
        )
    height, width = before.shape[:2]
    region = _default_zoom(before, after) if zoom is None else _check_zoom(zoom, width, height)
    x_start, y_start, x_end, y_end = region
    grey = {"cmap": "gray", "vmin": 0.0, "vmax": 1.0} if before.ndim == 2 else {}
    ratio = min(max(height / width, 0.5), 2.0)
    figure = Figure(figsize=(WIDEST, WIDEST / 4 * ratio + 0.45))
    grid = figure.add_gridspec(1, 4)
    outline = {"fill": False, "ec": "tab:orange", "lw": 1.5}
    for k, (name, image) in enumerate((("before", before), ("after", after))):
        whole = figure.add_subplot(grid[0, 2 * k])
        pixel_image(whole, image, **grey)
        whole.add_patch(Rectangle((x_start, y_start), x_end - x_start, y_end - y_start, **outline))
        whole.set_title(name, fontsize=9)
        part = figure.add_subplot(grid[0, 2 * k + 1])
        part.imshow(image[y_start:y_end, x_start:x_end], origin="lower",
                    extent=(x_start, x_end, y_start, y_end), interpolation="nearest", **grey)  # fmt: skip
        part.set_title(f"{name}, x {x_start}..{x_end}, y {y_start}..{y_end}", fontsize=9)
        for spine in part.spines.values():
            spine.set_edgecolor("tab:orange")
            spine.set_linewidth(1.5)
    for axes in figure.axes:
        axes.tick_params(labelsize=9)
    figure.tight_layout()
    return figure

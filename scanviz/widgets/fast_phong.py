"""Wang's fast Phong over one triangle, sample by sample (`fast_phong_stepper`).

Drawn from the trace of `scanviz.shading.fast_phong_triangle`: its
``fast_phong_setup`` event (the Taylor coefficients, shown once in a table)
and one ``fast_phong_pixel`` event per sample, each a step. Left, the image
shaded so far with the expansion point and the current pixel; right, how far
each sample shaded so far is from exact per-pixel Phong
(`scanviz.shading.exact_phong_triangle`), in 8-bit levels. The text says how
the current sample's quadratics were obtained (directly at a span's start,
else Q = Q_prev + dQ_prev), how its table level was found, and its colour
against the exact one.
"""

from __future__ import annotations

import html

import ipywidgets as widgets
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle
from matplotlib.patheffects import withStroke

from ..conventions import sample_offset
from ..geometry import as_coordinates
from ..shading.fast_phong import ShadedTriangle, exact_phong_triangle, fast_phong_triangle
from ..trace import Recorder, Trace
from ..trace.display import scroll_box
from ._common import (
    WIDEST,
    draw_outline,
    fmt,
    html_table,
    new_figure,
    note_label,
    pixel_image,
    pixel_region,
    swatch,
)
from .stepper import Stepper, draw_pixel_grid, figure_widget, refresh_figure, stepper_of

KINDS = ("fast_phong_setup", "fast_phong_pixel")
UNSHADED = (0.85, 0.85, 0.85)  # covered samples not shaded yet
OUTSIDE = (1.0, 1.0, 1.0)
DIGITS = 6  # significant digits of the values in the text
TERMS = ("x²", "xy", "y²", "x", "y", "1")
CHANNEL_NAMES = ("W_r", "W_g", "W_b")
NOTHING = (
    "<i>nothing to step: the triangle covers no sample "
    "(zero area once its vertices are snapped, or too small to reach a sample)</i>"
)


class FastPhongView:
    """The triangle shaded so far, its error against exact Phong, and the current sample's arithmetic.

    Parameters
    ----------
    vertices : (3, 2) array_like of float
        The screen triangle (its outline is drawn).
    trace : Trace
        ``fast_phong_setup`` and ``fast_phong_pixel`` events of
        ``fast_phong_triangle(..., trace=True)`` (others are ignored).
    exact : ShadedTriangle
        `exact_phong_triangle` on the same triangle and samples.
    width, height : int
        The raster size.
    sample : {"corner", "center"}
        Where the traced run sampled each pixel (the current sample's dot).
    note : str, optional
        Shown above the figure.

    Attributes
    ----------
    setup : FastPhongSetup or None
        None when the triangle has zero area (nothing was shaded).
    steps : Trace
        The ``fast_phong_pixel`` events: one step each (give it to the `Stepper`).
    widget : ipywidgets.VBox
    figure : matplotlib Figure
    picture : matplotlib AxesImage
        The fast colours of the samples shaded so far, `UNSHADED` on the
        covered samples still to come, `OUTSIDE` elsewhere.
    error_image : matplotlib AxesImage
        max over r, g, b of abs(fast − exact) in levels on the samples shaded so far (NaN elsewhere).
    pixel_patches : list of matplotlib Rectangle
        Around the current pixel, one per panel.
    text : ipywidgets.HTML
        The current sample.
    coefficients : ipywidgets.HTML
        The triangle's quadratics (from the setup event), shown once.
    """

    def __init__(
        self,
        vertices,
        trace: Trace,
        exact: ShadedTriangle,
        *,
        width: int,
        height: int,
        sample: str = "corner",
        note: str = "",
    ) -> None:
        if not isinstance(trace, Trace):
            raise TypeError(f"'trace' must be a scanviz Trace; got {trace!r}")
        if not isinstance(exact, ShadedTriangle):
            raise TypeError(f"'exact' must be a ShadedTriangle; got {type(exact).__name__}")
        vertices = as_coordinates(vertices, "'vertices'", (3, 2))
        self.setup = next((e for e in trace if e.kind == "fast_phong_setup"), None)
        self.steps = Trace(e for e in trace if e.kind == "fast_phong_pixel")
        self.width, self.height = max(width, 1), max(height, 1)  # an empty raster: one blank pixel
        self._offset = sample_offset(sample)
        self._read_samples(exact)
        self._build_figure(vertices)
        self.text = widgets.HTML()
        self.coefficients = widgets.HTML(self._coefficients_table())
        self.note = note_label(note)
        self._canvas = figure_widget(self.figure)
        self.widget = widgets.VBox([self.note, self._canvas, self.text, self.coefficients])
        self.step = 0
        self.show(0)

    def _build_figure(self, vertices: np.ndarray) -> None:
        """Fast Phong so far beside its error, over the pixel grid, with the pixel markers."""
        fig, (ax_fast, ax_error) = new_figure(2, width=WIDEST, height=4.4)
        region = pixel_region(vertices, self.width, self.height, 1)
        self.picture = pixel_image(ax_fast, self._background)
        self.error_image = pixel_image(
            ax_error,
            np.full((self.height, self.width), np.nan),
            cmap="magma_r",
            vmin=0.0,
            vmax=max(float(self._errors.max(initial=0.0)), 1.0),
        )
        fig.colorbar(self.error_image, ax=ax_error, fraction=0.046, pad=0.03).set_label(
            "levels", fontsize=9
        )
        self.pixel_patches, self.sample_dots = [], []
        for ax in (ax_fast, ax_error):
            draw_pixel_grid(ax, region)
            draw_outline(ax, [vertices], linewidth=1.2, zorder=3)
            if self.setup is not None:
                ax.plot(*self.setup.origin, "*", color="deepskyblue", mec="black", ms=12, zorder=5)
            patch = Rectangle((0, 0), 1, 1, fill=False, ec="black", lw=2, zorder=4, visible=False)
            halo = withStroke(linewidth=4, foreground="white")  # seen on dark errors too
            patch.set_path_effects([halo])
            ax.add_patch(patch)
            (dot,) = ax.plot([], [], ".", color="black", ms=5, zorder=4)
            self.pixel_patches.append(patch)
            self.sample_dots.append(dot)
            ax.set(xlim=region[:2], ylim=region[2:], aspect="equal")
            ax.tick_params(labelsize=9)
        expansion = self.setup.expansion if self.setup is not None else "vertex"
        ax_fast.set_title(f"fast Phong so far (expansion about the {expansion})", fontsize=9)
        ax_error.set_title("|fast − exact Phong|, max over r, g, b", fontsize=9)
        _add_legend(fig)
        fig.tight_layout(rect=(0, 0.07, 1, 1))
        self.figure, self.axes = fig, (ax_fast, ax_error)

    def _read_samples(self, exact: ShadedTriangle) -> None:
        """Index the samples once: position, fast colour, exact colour, error, per step."""
        self._xs = np.array([e.x for e in self.steps], np.int64)
        self._ys = np.array([e.y for e in self.steps], np.int64)
        self._fast = np.array([e.color for e in self.steps], np.float64).reshape(-1, 3)
        exact_image = np.full((self.height, self.width, 3), np.nan)
        exact_image[exact.ys, exact.xs] = exact.colors
        self._exact = exact_image[self._ys, self._xs]
        self._errors = np.abs(self._fast - self._exact).max(axis=1, initial=0.0)
        self._background = np.broadcast_to(OUTSIDE, (self.height, self.width, 3)).copy()
        self._background[exact.ys, exact.xs] = UNSHADED

    def show(self, step: int) -> None:
        """Show the image and the error after the first `step` samples, and sample `step`."""
        self.step = int(step)
        done = slice(0, self.step)
        picture = self._background.copy()
        picture[self._ys[done], self._xs[done]] = self._fast[done] / 255.0
        self.picture.set_data(picture)
        error = np.full((self.height, self.width), np.nan)
        error[self._ys[done], self._xs[done]] = self._errors[done]
        self.error_image.set_data(error)
        current = self.steps[self.step - 1] if self.step else None
        for patch, dot in zip(self.pixel_patches, self.sample_dots, strict=True):
            patch.set_visible(current is not None)
            if current is None:
                dot.set_data([], [])
                continue
            patch.set_xy((current.x, current.y))
            dot.set_data([current.x + self._offset], [current.y + self._offset])
        self.text.value = self._describe(current)
        refresh_figure(self.figure, self._canvas)

    def narrate(self, step: int) -> str:
        """Step `step` in one plain sentence: the sample, how its quadratics were found, its
        table level and its colour against exact Phong."""
        if not self.steps:
            return "Nothing to step: the triangle covers no sample."
        if step == 0:
            return (
                f"The start: {len(self.steps)} samples to shade row by row from the bottom, "
                "each from quadratics set up once for the triangle."
            )
        pixel, k = self.steps[step - 1], step - 1
        how = (
            "a span's first sample, so its quadratics are evaluated directly"
            if pixel.direct
            else "its quadratics are stepped from the sample before with two additions each"
        )
        lit = (
            f"cos θ = {fmt(pixel.cos_theta, 3)} > 0, so the highlight is added: its cosine "
            f"{fmt(pixel.cos_specular, 4)} is at table level {pixel.level} of "
            f"{len(self.setup.table)} "
            f"({_count(pixel.comparisons, 'comparison')})"
            if pixel.lit
            else f"cos θ = {fmt(pixel.cos_theta, 3)} ≤ 0, so it is unlit (no highlight)"
        )
        colour = ", ".join(f"{c:.0f}" for c in self._fast[k])
        return (
            f"Pixel ({pixel.x}, {pixel.y}): {how}; {lit}; colour ({colour}) is "
            f"{fmt(self._errors[k], 3)} levels from exact Phong."
        )

    def _describe(self, pixel) -> str:
        if not self.steps:
            return NOTHING
        if pixel is None:
            return (
                f"<i>start: {len(self.steps)} samples to shade, row by row from the bottom; "
                "press next for the first</i>"
            )
        k = self.step - 1
        previous = self.steps[k - 1] if not pixel.direct else None
        ox, oy = self.setup.origin
        x, y = pixel.x + self._offset - ox, pixel.y + self._offset - oy
        head = (
            f"<b>sample {self.step} of {len(self.steps)}</b>: pixel ({pixel.x}, {pixel.y}), "
            f"at x = {fmt(x, DIGITS)}, y = {fmt(y, DIGITS)} from the expansion point<br>"
        )
        if pixel.direct:
            how = (
                "<b>direct</b> (a span's first sample): each Q = T5 x² + T4 xy + T3 y² + T2 x "
                "+ T1 y + T0 and dQ = T5 (2x + 1) + T4 y + T2 from its coefficients<br>"
            )
        else:
            how = (
                f"<b>stepped</b> from pixel ({previous.x}, {previous.y}): Q = Q_prev + dQ_prev, "
                "dQ = dQ_prev + 2 T5 (two additions per quadratic)<br>"
            )
        return (
            head
            + how
            + self._values_table(pixel, previous)
            + self._level(pixel, previous)
            + self._colour(pixel, k)
        )

    def _values_table(self, pixel, previous) -> str:
        specular = "cos φ" if self.setup.specular == "phong" else "N·H"
        names = ("cos θ", specular, *CHANNEL_NAMES)
        values, steps = _quadratics(pixel)
        if previous is None:
            sources = ["direct"] * len(names)
        else:
            sources = [_sum(q, d) for q, d in zip(*_quadratics(previous), strict=True)]
        rows = [
            (name, fmt(q, DIGITS), fmt(d, DIGITS), source)
            for name, q, d, source in zip(names, values, steps, sources, strict=True)
        ]
        return html_table(("", "Q", "dQ", "Q from"), rows)

    def _level(self, pixel, previous) -> str:
        table, level = self.setup.table, pixel.level
        entries = len(table)
        if entries == 0:
            where = "the table is empty (no highlight)"
        elif level == 0:
            where = f"below cos φ_1 = {fmt(table[0], DIGITS)}"
        elif level == entries:
            where = f"at least cos φ_{entries} = 1"
        else:
            where = (
                f"cos φ_{level} = {fmt(table[level - 1], DIGITS)} &le; Q &lt; "
                f"cos φ_{level + 1} = {fmt(table[level], DIGITS)}"
            )
        search = (
            "binary search at the span's start"
            if previous is None
            else f"coherent step from the previous level {previous.level}"
        )
        lit = (
            "cos θ &gt; 0: <b>lit</b>, the level is added"
            if pixel.lit
            else "cos θ &le; 0: <b>unlit</b>, no highlight"
        )
        return (
            f"<br><b>table level {level}</b> of {entries}: {where}; "
            f"{search}: {_count(pixel.comparisons, 'comparison')}<br>{lit}<br>"
        )

    def _colour(self, pixel, k: int) -> str:
        fast, exact = self._fast[k], self._exact[k]
        difference = np.abs(fast - exact)
        return (
            f"fast colour {swatch(fast / 255)} {html.escape(fmt(tuple(fast), DIGITS))} "
            "= max(W, Ia ka) + level<br>"
            f"exact Phong {swatch(exact / 255)} {html.escape(fmt(tuple(exact), DIGITS))}<br>"
            f"|fast − exact| = {html.escape(fmt(tuple(difference), DIGITS))} levels "
            f"(max {fmt(self._errors[k], DIGITS)})"
        )

    def _coefficients_table(self) -> str:
        if self.setup is None:
            return ""
        s = self.setup
        specular = "cos φ (T55..T00)" if s.specular == "phong" else "N·H"
        names = ("cos θ (T5..T0)", specular, *(f"{c} (W5..W0)" for c in CHANNEL_NAMES))
        quadratics = (s.cos_theta, s.cos_specular, *s.ambient_diffuse)
        rows = [(name, *(fmt(t, 5) for t in q)) for name, q in zip(names, quadratics, strict=True)]
        origin = fmt(s.origin, DIGITS)
        return scroll_box(
            f"<b>the triangle's quadratics</b>, about the {s.expansion} {html.escape(origin)}, "
            f"{s.specular}; the table has {len(s.table)} levels<br>"
            + html_table(("quadratic", *TERMS), rows)
        )


def _quadratics(pixel) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """(Q, dQ) of cos θ, the highlight's cosine and the three channels at a sample."""
    values = (pixel.cos_theta, pixel.cos_specular, *pixel.ambient_diffuse)
    steps = (pixel.cos_theta_step, pixel.cos_specular_step, *pixel.ambient_diffuse_step)
    return values, steps


def _sum(value: float, step: float) -> str:
    """'Q_prev + dQ_prev' with the step's sign as the operator: '0.5 − 0.25'."""
    return f"{fmt(value, DIGITS)} {'−' if step < 0 else '+'} {fmt(abs(step), DIGITS)}"


def _count(number: int, noun: str) -> str:
    return f"{number} {noun}" + ("" if number == 1 else "s")


def fast_phong_stepper(
    vertices,
    normals,
    to_light,
    to_viewer,
    model,
    *,
    width: int,
    height: int,
    expansion: str = "vertex",
    sample: str = "corner",
    subpixel_bits: int | None = 8,
) -> Stepper:
    """Shade a triangle with traced fast Phong and step through its samples in a `FastPhongView`.

    Parameters
    ----------
    vertices, normals, to_light, to_viewer, model, width, height, expansion, sample, subpixel_bits
        As for `scanviz.shading.fast_phong_triangle` (and its errors).

    Returns
    -------
    Stepper
        ``.views[0]`` is the `FastPhongView`; one step per sample.

    Examples
    --------
    >>> from scanviz.shading import ReflectionModel
    >>> model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=0.6, ks=0.7, n=8, r_plus_r0=1.5)
    >>> normals = [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)]
    >>> stepper = fast_phong_stepper([(0, 0), (4, 0), (0, 4)], normals, (0, 0, 1), (0, 0, 1),
    ...                              model, width=4, height=4)
    >>> stepper.slider.max, stepper.views[0].steps[1].direct
    (10, False)
    >>> stepper.slider.value = 2
    >>> "Q = Q_prev + dQ_prev" in stepper.views[0].text.value
    True
    """
    arguments = (vertices, normals, to_light, to_viewer, model)
    options = {"width": width, "height": height, "sample": sample, "subpixel_bits": subpixel_bits}
    shaded = fast_phong_triangle(
        *arguments, expansion=expansion, trace=Recorder(kinds=KINDS), **options
    )
    exact = exact_phong_triangle(*arguments, **options)
    view = FastPhongView(vertices, shaded.trace, exact, width=width, height=height, sample=sample)
    return stepper_of(view, "fast Phong: one sample per step", "samples")


def _add_legend(fig) -> None:
    """The legend under both panels: triangle, expansion point, current pixel, unshaded."""
    handles = [
        Line2D([], [], color="crimson", lw=1.2, label="triangle"),
        Line2D(
            [],
            [],
            ls="",
            marker="*",
            ms=10,
            mfc="deepskyblue",
            mec="black",
            label="expansion point",
        ),
        Patch(fc="none", ec="black", lw=2, label="current pixel (dot: its sample)"),
        Patch(fc=UNSHADED, ec="0.7", label="covered, not shaded yet"),
    ]
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=9)

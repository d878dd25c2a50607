"""Shading benchmark: run time against error for flat, Gouraud, fast Phong and Phong on the same scenes.

Every mode renders the same scene through `render` (z-buffer, untraced) at
the same size; exact per-pixel Phong is the reference. The error of a mode is
taken over the pixels both show (the visibility is the same), per pixel the
largest channel difference, in 8-bit levels: its maximum and its RMS. Time is
the median of `repeat` renders after one warm-up render (numba compiles or
loads its kernels).

Scenes: builtin:sphere at tessellation levels 1..4 (its triangles shrink on
the screen, so the error of the interpolating modes falls) and
builtin:function_surface. Each row also gives the mean side of the visible
triangles in pixels (√(2 · visible pixels / triangles)), the scale the
dissertation's Taylor error depends on.
"""

from __future__ import annotations

import statistics
from time import perf_counter

import numpy as np

from ..pipeline import render
from ..progress import progress
from ..scene.builtin import builtin_scene

MODES = ("flat", "gouraud", "fast_phong", "fast_phong_centroid", "phong")
# a mode is a shading, or fast_phong with its Taylor expansion about each triangle's centroid
RENDER_OPTIONS = {"fast_phong_centroid": {"shading": "fast_phong", "expansion": "centroid"}}
SIZE = 256
REPEAT = 3


def scenes(quick: bool) -> list[tuple[str, object]]:
    """(label, Scene) of the benchmark: the sphere at several tessellations, and a function surface."""
    levels = (1, 2) if quick else (1, 2, 3, 4)
    rows = [(f"sphere level {level}", builtin_scene("sphere", level=level)) for level in levels]
    if not quick:
        rows.append(("function_surface", builtin_scene("function_surface")))
    return rows


def _timed(scene, size: int, shading: str, repeat: int):
    options = RENDER_OPTIONS.get(shading, {"shading": shading})
    render(scene, 16, 16, **options)  # warm-up: compile or load the kernels
    times, result = [], None
    for _ in range(repeat):
        start = perf_counter()
        result = render(scene, size, size, **options)
        times.append(perf_counter() - start)
    return statistics.median(times), result


def error_levels(
    image: np.ndarray, reference: np.ndarray, shown: np.ndarray
) -> tuple[float, float]:
    """(max, RMS) over `shown` pixels of the largest channel difference, in 8-bit levels.

    >>> a, b = np.zeros((1, 2, 3)), np.full((1, 2, 3), 1 / 255)
    >>> error_levels(a, b, np.array([[True, False]]))
    (1.0, 1.0)
    """
    if not shown.any():
        return 0.0, 0.0
    levels = 255.0 * np.abs(image - reference)[shown].max(axis=1)
    return float(levels.max()), float(np.sqrt((levels**2).mean()))


def run_shading(
    *,
    quick: bool = False,
    size: int | None = None,
    repeat: int | None = None,
    plot: str | None = None,
) -> list[dict]:
    """Time every mode on every scene, print time against error, return the rows.

    ``quick``: 64 x 64, the sphere at levels 1 and 2, one render each.
    `plot` is a file for the time-against-error plot (log-log).
    """
    size = (64 if quick else SIZE) if size is None else size
    repeat = (1 if quick else REPEAT) if repeat is None else repeat
    rows = []
    chosen = scenes(quick)
    print(
        f"shading benchmark: {size}x{size}, z-buffer, untraced, median of {repeat} render(s); "
        "error against per-pixel Phong over the pixels shown, max channel, 8-bit levels"
    )
    header = f"{'scene':<18} {'tri side':>8} {'mode':<19} {'ms':>9} {'max err':>8} {'RMS err':>8}"
    lines = [header]
    with progress(len(chosen) * len(MODES), "shading bench") as bar:
        for label, scene in chosen:
            phong_time, reference = _timed(scene, size, "phong", repeat)
            shown = reference.polygon >= 0
            triangles = max(len(np.unique(reference.polygon[shown])), 1)
            side = float(np.sqrt(2.0 * shown.sum() / triangles))
            for mode in MODES:
                seconds, result = (
                    (phong_time, reference)
                    if mode == "phong"
                    else _timed(scene, size, mode, repeat)
                )
                worst, rms = error_levels(result.image, reference.image, shown)
                row = {"scene": label, "side": side, "mode": mode, "seconds": seconds, "max": worst, "rms": rms}  # fmt: skip
                rows.append(row)
                lines.append(
                    f"{label:<18} {side:>8.1f} {mode:<19} {1e3 * seconds:>9.1f} {worst:>8.1f} {rms:>8.2f}"
                )
                bar.update(1)
    print("\n".join(lines))
    print(
        "fast_phong: Taylor quadratics about each triangle's first vertex, forward differences and the "
        "specular table, all triangles in one compiled pass (pipeline/fast_shade.py)"
    )
    if plot:
        _plot(rows, plot)
        print(f"plot: {plot}")
    return rows


def _plot(rows: list[dict], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    fig, axes = plt.subplots(1, 2, figsize=(9.5, 4))
    for mode in MODES[:-1]:
        mine = [r for r in rows if r["mode"] == mode]
        axes[0].loglog(
            [r["seconds"] for r in mine], [max(r["rms"], 1e-3) for r in mine], "o-", label=mode
        )
        axes[1].loglog(
            [r["side"] for r in mine], [max(r["rms"], 1e-3) for r in mine], "o-", label=mode
        )
    axes[0].set_xlabel("render time (s)")
    axes[1].set_xlabel("mean visible triangle side (pixels)")
    for axis in axes:
        axis.xaxis.set_minor_formatter(NullFormatter())  # log minor labels collide
        axis.set_ylabel("RMS error against Phong (8-bit levels)")
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)

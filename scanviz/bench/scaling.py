"""Scaling benchmark: how the z-buffer, the a-buffer and the scan converter grow with the work.

One scalable scene, a height field z = h(x, y) over [-1, 1]^2 on an n x n
grid of cells (2 n^2 triangles) seen from straight above through an
orthographic camera, so that it covers the whole raster at every n: the
triangle sweep (10^3..10^6 triangles at 1024 x 1024) changes only the
triangle count, the resolution sweep (256^2..4096^2 at 10^4 triangles) only
the pixels. Each method is called through its public function only:

* ``render phong`` -- ``render(scene, w, h, shading="phong")``, the whole
  z-buffer pipeline (prepare, rasterize, z-buffer, shade);
* ``zbuffer`` -- ``scanviz.visibility.zbuffer`` on the same grid as
  `ScreenPolygons` made once in screen space (depth and 3 values per vertex);
* ``abuffer`` -- ``render(scene, w, h, shading="phong", visibility="abuffer")``;
* ``rasterize_triangles`` and ``fill_polygons`` -- the scan converter on the
  grid's (T, 3, 2) screen triangles.

Every point runs in a fresh subprocess: it compiles (or loads) the kernels on
a tiny scene, builds the point's input, resets the kernel's peak-RSS mark
(``/proc/self/clear_refs``) and reports the time (median of up to `REPEAT`
runs, none repeated after BUDGET / 3 s) and the peak resident memory above
the RSS before the first run (``VmHWM - VmRSS``): numba's allocations are
invisible to tracemalloc, RSS sees them. ``--quick`` runs tiny points in
this process (the same RSS measure, not isolated from earlier points).

Before a point runs, its time is extrapolated from the method's earlier
points of the sweep (the growth exponent between the last two, at least 1;
linear after one): a point predicted over `BUDGET`, and every larger one, is
skipped and says so, and a point still running after `TIMEOUT` seconds is
killed. A point the memory limit (`scanviz.limits`) refuses is reported with
the limit's message. The growth exponent of each method is the least-squares
slope of log time on log triangles (or pixels), over runs longer than 1 ms.

A last table (`run_output_cases`, in this process) times the cases whose
cost once grew faster than their output: a-buffer lists n fragments long,
`area_coverage` of an n-vertex self-crossing polygon, and feature edges
that lie off the raster as the view zooms n times in.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from ..limits import ResourceLimitError, current_memory_limit, format_size
from ..progress import progress
from .visibility import growth_exponent

METHODS = ("render phong", "zbuffer", "abuffer", "rasterize_triangles", "fill_polygons")
TRIANGLES = (10**3, 10**4, 10**5, 10**6)  # at SIZE x SIZE
RESOLUTIONS = (256, 512, 1024, 2048, 4096)  # at MESH_TRIANGLES
SIZE = 1024
MESH_TRIANGLES = 10**4
QUICK_TRIANGLES = (32, 128, 512)  # at QUICK_SIZE x QUICK_SIZE
QUICK_RESOLUTIONS = (32, 64, 128)  # at QUICK_MESH_TRIANGLES
QUICK_SIZE = 64
QUICK_MESH_TRIANGLES = 128
REPEAT = 3
BUDGET = 15.0  # seconds one run of a point may take (predicted); no repeat after BUDGET / 3
TIMEOUT = 30.0 + 3 * BUDGET  # seconds a point's subprocess may run (start-up, input, runs)
MEMORY_METHOD = "peak RSS above the RSS before the first run (VmHWM - VmRSS, after clear_refs)"


def height(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The height field: gentle waves, so every triangle is seen and none is edge-on."""
    return 0.15 * np.sin(3.0 * x + 0.5) * np.cos(2.0 * y)


def cells_for(triangles: int) -> int:
    """Cells per side of the grid whose 2 n^2 triangles are nearest to `triangles`."""
    return max(1, round(math.sqrt(triangles / 2)))


def height_field_scene(cells: int):
    """The height field on `cells` x `cells` cells, filling an orthographic view from above."""
    from ..scene.builtin import function_surface_mesh
    from ..scene.model import Camera, Light, Material, Scene, SceneObject

    mesh = function_surface_mesh(height, (-1.0, 1.0), (-1.0, 1.0), cells)
    return Scene(
        (SceneObject(mesh, Material(color=(0.8, 0.7, 0.5), specular=0.3), name="height field"),),
        Camera(eye=(0, 0, 3), up=(0, 1, 0), near=1.0, far=5.0, projection="orthographic"),
        lights=(Light("directional", direction=(-0.3, -0.5, -1.0)),),
        name=f"height field {cells}x{cells}",
    )


def screen_triangles(cells: int, size: int) -> tuple[np.ndarray, np.ndarray]:
    """The height field's triangles on a size x size raster: (T, 3, 2) xy and (T, 3) depth."""
    axis = np.linspace(-1.0, 1.0, cells + 1)
    x, y = np.meshgrid(axis, axis)
    xy = np.stack([(x + 1.0) * size / 2, (y + 1.0) * size / 2], axis=-1).reshape(-1, 2)
    depth = (0.5 - height(x, y)).reshape(-1)  # nearer where higher, as seen from above
    row, column = np.divmod(np.arange(cells * cells), cells)
    a = row * (cells + 1) + column  # the cell's lower-left corner, then counter-clockwise
    b, c, d = a + 1, a + cells + 2, a + cells + 1
    corners = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return xy[corners], depth[corners]


def _prepared(method: str, cells: int, size: int):
    """The input `method` draws, made before it is timed."""
    if method in ("render phong", "abuffer"):
        return height_field_scene(cells)
    xy, depth = screen_triangles(cells, size)
    if method != "zbuffer":
        return xy
    from ..visibility import ScreenPolygons

    count = len(xy)  # 3 values per vertex to interpolate: one grey per triangle
    values = np.repeat(np.linspace(0.0, 1.0, count)[:, None], 9, axis=1).reshape(-1, 3)
    return ScreenPolygons(
        xy.reshape(-1, 2),
        depth.reshape(-1),
        np.ones(3 * count),
        values,
        np.arange(0, 3 * count + 1, 3),
    )


def _draw(method: str, prepared, size: int) -> None:
    from ..pipeline import render
    from ..raster import fill_polygons, rasterize_triangles
    from ..visibility import zbuffer

    if method == "render phong":
        render(prepared, size, size, shading="phong")
    elif method == "abuffer":
        render(prepared, size, size, shading="phong", visibility="abuffer")
    elif method == "zbuffer":
        zbuffer(prepared, size, size)
    elif method == "rasterize_triangles":
        rasterize_triangles(prepared, size, size)
    elif method == "fill_polygons":
        fill_polygons(prepared, size, size)
    else:
        raise ValueError(f"'method' must be one of {METHODS}; got {method!r}")


def _status_bytes(field: str) -> int:
    """A field of /proc/self/status ("VmRSS", "VmHWM") in bytes."""
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    raise OSError(f"/proc/self/status has no {field}")


def _reset_peak() -> int:
    """Reset the kernel's peak-RSS mark of this process; return the RSS now, in bytes."""
    with open("/proc/self/clear_refs", "w") as refs:
        refs.write("5")  # 5: reset the peak resident set size (Linux >= 4.0)
    return _status_bytes("VmRSS")


def measure(method: str, cells: int, size: int, *, repeat: int, budget: float) -> dict:
    """Draw `method` on the grid of `cells` at size x size: time (median) and peak memory.

    The first call, on a 2 x 2 grid at 16 x 16, compiles or loads the kernels
    and is not counted; runs repeat while they have taken less than budget / 3. Peak memory is None where /proc cannot be read.
    """
    _draw(method, _prepared(method, 2, 16), 16)
    prepared = _prepared(method, cells, size)
    try:
        before = _reset_peak()
    except OSError:
        before = None
    times: list[float] = []
    started = time.perf_counter()
    while len(times) < repeat and (not times or time.perf_counter() - started < budget / 3):
        tick = time.perf_counter()
        _draw(method, prepared, size)
        times.append(time.perf_counter() - tick)
        if len(times) == 1 and before is not None:
            peak = _status_bytes("VmHWM") - before
    return {
        "seconds": statistics.median(times),
        "runs": len(times),
        "peak_bytes": None if before is None else max(peak, 0),
    }


def _child() -> None:
    """Entry of a point's subprocess: ``METHOD CELLS SIZE REPEAT BUDGET`` -> one JSON line."""
    method, cells, size, repeat, budget = sys.argv[1:6]
    try:
        result = measure(method, int(cells), int(size), repeat=int(repeat), budget=float(budget))
    except ResourceLimitError as error:
        result = {"refused": str(error)}
    print(json.dumps(result))


def _in_subprocess(method: str, cells: int, size: int) -> dict:
    """`measure` in a fresh interpreter (its memory its own), killed after `TIMEOUT` seconds."""
    root = str(Path(__file__).resolve().parents[2])
    environment = os.environ | {
        "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")])),
        "SCANVIZ_MEMORY_LIMIT": str(current_memory_limit()),
    }
    command = [sys.executable, "-c", "from scanviz.bench.scaling import _child; _child()"]
    try:
        done = subprocess.run(
            [*command, method, str(cells), str(size), str(REPEAT), str(BUDGET)],
            capture_output=True,
            text=True,
            timeout=TIMEOUT,
            env=environment,
        )
    except subprocess.TimeoutExpired:
        return {"failed": f"killed after {TIMEOUT:g} s (the time limit of a point)"}
    lines = done.stdout.strip().splitlines()
    if done.returncode != 0 or not lines:
        last = (done.stderr.strip().splitlines() or [f"exit status {done.returncode}"])[-1]
        return {"failed": last}
    return json.loads(lines[-1])


def _predicted(history: list[tuple[int, float]], size: int) -> float:
    """One run's seconds at `size`, from (size, seconds) measured so far in the sweep.

    Linear after one point (each sweep scales the work linearly by
    construction), then the exponent between the last two points, at least 1.
    """
    if not history:
        return 0.0
    (last_size, last_seconds), exponent = history[-1], 1.0
    if len(history) > 1:
        (n0, s0), (n1, s1) = history[-2:]
        exponent = max(1.0, math.log(max(s1, 1e-9) / max(s0, 1e-9)) / math.log(n1 / n0))
    return last_seconds * max(size / last_size, 1.0) ** exponent


def _points(quick: bool) -> list[tuple[str, int, int]]:
    """(sweep, cells, size) of every point, the triangle sweep first, each in ascending size."""
    counts, side = (QUICK_TRIANGLES, QUICK_SIZE) if quick else (TRIANGLES, SIZE)
    sizes, mesh = (QUICK_RESOLUTIONS, QUICK_MESH_TRIANGLES) if quick else (RESOLUTIONS, MESH_TRIANGLES)  # fmt: skip
    return [("triangles", cells_for(n), side) for n in counts] + [
        ("pixels", cells_for(mesh), s) for s in sizes
    ]


def _point_row(sweep: str, method: str, cells: int, size: int, measured: dict) -> dict:
    triangles, pixels = 2 * cells * cells, size * size
    row = {"sweep": sweep, "method": method, "triangles": triangles, "width": size, "height": size}
    if "seconds" not in measured:
        ((status, reason),) = measured.items()  # "refused", "failed" or "skipped": why
        return row | {"status": status, "reason": reason}
    seconds = measured["seconds"]
    return row | {
        "status": "ok",
        "ms": seconds * 1e3,
        "triangles_per_s": triangles / seconds,
        "pixels_per_s": pixels / seconds,
        "peak_bytes": measured["peak_bytes"],
        "runs": measured["runs"],
    }


def _line(row: dict) -> str:
    head = f"{row['method']:<21}{row['triangles']:>10,}{row['width']:>6}²"
    if row["status"] != "ok":
        return f"{head}  {row['status']}: {row['reason']}"
    peak = "n/a" if row["peak_bytes"] is None else format_size(row["peak_bytes"])
    return (
        f"{head}{_three_digits(row['ms']):>11}{row['triangles_per_s'] / 1e6:>9.3g}"
        f"{row['pixels_per_s'] / 1e6:>9.3g}{peak:>11}"
    )


def _three_digits(value: float) -> str:
    """At least 3 significant digits, never an exponent for 1 and above.

    >>> _three_digits(14119.74), _three_digits(6.136), _three_digits(0.1346)
    ('14,120', '6.14', '0.135')
    """
    return f"{value:,.0f}" if value >= 100 else f"{value:.3g}"


def fits(rows: list[dict]) -> list[dict]:
    """Per method: the growth exponent against triangles and against pixels (None: too few runs)."""
    out = []
    for method in dict.fromkeys(r["method"] for r in rows if "sweep" in r):
        row = {"sweep": "fit", "method": method}
        for sweep in ("triangles", "pixels"):
            fit = growth_exponent(*_measured(rows, sweep, method))
            row[f"k_{sweep}"] = None if fit is None else fit[0]
        out.append(row)
    return out


def _measured(rows: list[dict], sweep: str, method: str) -> tuple[list[int], list[float]]:
    """(sizes, seconds) of the points of `sweep` that `method` ran; size = triangles or pixels."""
    done = [r for r in rows if r.get("sweep") == sweep and r["method"] == method]
    done = [r for r in done if r["status"] == "ok"]
    sizes = [r["triangles"] if sweep == "triangles" else r["width"] * r["height"] for r in done]
    return sizes, [r["ms"] / 1e3 for r in done]


def power_law(sizes, seconds, exponent: float) -> float:
    """The least-squares factor c of seconds = c * size**exponent for a given exponent.

    >>> round(power_law([10, 100], [0.02, 2.0], 2.0), 12)
    0.0002
    """
    logs = np.log(np.asarray(seconds, float)) - exponent * np.log(np.asarray(sizes, float))
    return float(np.exp(logs.mean()))


def run_scaling(*, quick: bool = False, plot: str | None = None) -> list[dict]:
    """Run both sweeps for every method, print the rows and the exponents, return the rows.

    ``quick``: grids of 32..512 triangles at 64², and 32²..128² at 128
    triangles, measured in this process.
    """
    import numba

    points = _points(quick)
    where = ", in this process (--quick)" if quick else ", a fresh subprocess per point"
    print(
        "scaling benchmark: a height field filling an orthographic view from above, corner "
        f"sampling, median of up to {1 if quick else REPEAT} runs per point, "
        f"{numba.get_num_threads()} numba threads"
    )
    print(f"peak memory: {MEMORY_METHOD}{where}")
    print(f"skipped: a point predicted over {BUDGET:g} s per run, and every larger one")
    rows: list[dict] = []
    with progress(len(points) * len(METHODS), "scaling bench") as bar:
        for sweep in ("triangles", "pixels"):
            swept = [(cells, size) for s, cells, size in points if s == sweep]
            cells, size = swept[0]
            fixed = f"{size}²" if sweep == "triangles" else f"{2 * cells * cells:,} triangles"
            bar.write(f"\nsweep over {sweep} at {fixed}")
            bar.write(
                f"{'method':<21}{'triangles':>10}{'size':>7}{'ms':>11}{'Mtri/s':>9}"
                f"{'Mpx/s':>9}{'peak mem':>11}"
            )
            for method in METHODS:
                rows += _sweep(sweep, method, swept, quick, bar)
    fitted = fits(rows)
    print("\ngrowth exponent k: time ~ size^k, least squares on log-log over runs > 1 ms")
    print(f"{'method':<21}{'k(triangles)':>13}{'k(pixels)':>11}")
    for row in fitted:
        shown = [
            f"{row[k]:.2f}" if row[k] is not None else "n/a" for k in ("k_triangles", "k_pixels")
        ]
        print(f"{row['method']:<21}{shown[0]:>13}{shown[1]:>11}")
    if plot:
        save_plot(rows + fitted, plot)
        print(f"plot: {plot}")
    return rows + fitted + run_output_cases(quick=quick)


def _sweep(sweep: str, method: str, swept: list[tuple[int, int]], quick: bool, bar) -> list[dict]:
    """`method` at each (cells, size) of `sweep` in turn, until one is predicted over budget."""
    rows, history, stop = [], [], ""
    for cells, size in swept:
        work = 2 * cells * cells if sweep == "triangles" else size * size
        guess = _predicted(history, work)
        if not stop and guess > BUDGET:
            stop = f"predicted {guess:.0f} s per run > {BUDGET:g} s (the growth so far)"
        if stop:
            measured = {"skipped": stop}
        elif quick:
            measured = _in_process(method, cells, size)
        else:
            measured = _in_subprocess(method, cells, size)
        row = _point_row(sweep, method, cells, size, measured)
        if row["status"] == "ok":
            history.append((work, row["ms"] / 1e3))
        elif not stop:
            stop = f"a smaller point was {row['status']}"
        rows.append(row)
        bar.write(_line(row))
        bar.update()
    return rows


def _in_process(method: str, cells: int, size: int) -> dict:
    try:
        return measure(method, cells, size, repeat=1, budget=BUDGET)
    except ResourceLimitError as error:
        return {"refused": str(error)}


def save_plot(rows: list[dict], path: str) -> None:
    """Log-log plot of time against triangles and against pixels, with the fitted power laws."""
    from matplotlib.figure import Figure  # no pyplot: leaves the caller's backend alone

    figure = Figure(figsize=(11, 4.5))
    panels = dict(zip(("triangles", "pixels"), figure.subplots(1, 2), strict=True))
    exponents = {r["method"]: r for r in rows if r.get("sweep") == "fit"}
    for sweep, axes in panels.items():
        for method in METHODS:
            sizes, seconds = _measured(rows, sweep, method)
            if not sizes:
                continue
            k = exponents.get(method, {}).get(f"k_{sweep}")
            label = method if k is None else f"{method} (k = {k:.2f})"
            (points,) = axes.loglog(sizes, seconds, "o", label=label)
            if k is not None:
                line = np.geomspace(min(sizes), max(sizes), 20)
                axes.loglog(line, power_law(sizes, seconds, k) * line**k, "-", color=points.get_color())  # fmt: skip
        axes.set_xlabel(f"{sweep}")
        axes.set_ylabel("time per run (s)")
        axes.grid(True, which="both", alpha=0.3)
        axes.legend(fontsize="small")
    panels["triangles"].set_title("time against triangles (fixed raster)")
    panels["pixels"].set_title("time against pixels (fixed mesh)")
    figure.tight_layout()
    figure.savefig(path, dpi=120)


# --- cost in proportion to the output: the cases that once grew faster than their work -------

OUTPUT_CASES = {
    "abuffer lists": "n translucent triangles over one 32² raster: lists n long (render abuffer)",
    "area_coverage": "a random n-vertex self-crossing polygon on 16² (~n²/4 crossings)",
    "edges off raster": "render(terrain, 8, 8, edges=True) zoomed n x in (--quick: a 8 x 8 grid)",
}
OUTPUT_SIZES = {
    "abuffer lists": (250, 500, 1000, 2000, 4000),
    "area_coverage": (125, 250, 500, 1000, 2000),
    "edges off raster": (1, 4, 16, 64, 256),
}
QUICK_OUTPUT_SIZES = {
    "abuffer lists": (16, 32, 64),
    "area_coverage": (16, 32, 64),
    "edges off raster": (1, 2, 4),
}


def _translucent_stack(count: int):
    """`count` random large triangles over [-1, 1]², each half transparent, seen from above."""
    from ..scene.model import Camera, Light, Material, Mesh, Scene, SceneObject

    rng = np.random.default_rng(count)
    corners = rng.uniform(-1.5, 1.5, (count, 3, 2))
    depth = np.repeat(np.linspace(0.0, 1.0, count)[:, None, None], 3, axis=1)
    positions = np.concatenate([corners, depth], axis=2).reshape(-1, 3)
    faces = np.arange(3 * count).reshape(-1, 3)
    mesh = Mesh(positions, [np.asarray(f) for f in faces], smooth=False, closed=False)
    material = Material(color=(0.8, 0.4, 0.2), transparency=0.5)
    camera = Camera(eye=(0, 0, 3), near=1.0, far=5.0, projection="orthographic")
    return Scene((SceneObject(mesh, material),), camera, lights=(Light(),))


def _zoomed_terrain(zoom: int, quick: bool):
    import dataclasses

    from ..scene.builtin import builtin_scene

    scene = builtin_scene("terrain", **({"n": 8} if quick else {}))
    window = tuple(v / zoom for v in scene.camera.window)
    return dataclasses.replace(scene, camera=dataclasses.replace(scene.camera, window=window))


def _output_case(case: str, n: int, quick: bool):
    """(draw, description of the output) for case `case` at size n; draw() does the work."""
    from ..abuffer import area_coverage
    from ..pipeline import render

    if case == "abuffer lists":
        scene = _translucent_stack(n)
        return lambda: render(scene, 32, 32, shading="flat", visibility="abuffer")
    if case == "area_coverage":
        polygon = np.random.default_rng(0).uniform(0, 16, (n, 2))
        return lambda: area_coverage(polygon, 16, 16)
    scene = _zoomed_terrain(n, quick)
    return lambda: render(scene, 8, 8, shading="flat", edges=True)


def run_output_cases(*, quick: bool = False) -> list[dict]:
    """Time each case over its sizes (skipping past the budget), print rows and exponents."""
    sizes_of = QUICK_OUTPUT_SIZES if quick else OUTPUT_SIZES
    print("\ncost against the size n of cases that used to grow faster than their output")
    for case, what in OUTPUT_CASES.items():
        print(f"  {case}: {what}")
    print(f"{'case':<18}{'n':>7}{'ms':>11}")
    rows = []
    with progress(sum(len(s) for s in sizes_of.values()), "output cases") as bar:
        for case, sizes in sizes_of.items():
            history, stop = [], ""
            for n in sizes:
                guess = _predicted(history, n)
                if not stop and guess > BUDGET:
                    stop = f"predicted {guess:.0f} s per run > {BUDGET:g} s"
                row = {"sweep": "output", "method": case, "n": n}
                if stop:
                    row |= {"status": "skipped", "reason": stop}
                    bar.write(f"{case:<18}{n:>7}  skipped: {stop}")
                else:
                    draw = _output_case(case, n, quick)
                    draw()  # compiles or loads the kernels; not counted
                    seconds = _median_run(draw)
                    history.append((n, seconds))
                    row |= {"status": "ok", "ms": seconds * 1e3}
                    bar.write(f"{case:<18}{n:>7}{_three_digits(seconds * 1e3):>11}")
                rows.append(row)
                bar.update()
    print(f"{'case':<18}{'k(n)':>7}   (time ~ n^k, least squares over runs > 1 ms)")
    for case in sizes_of:
        done = [r for r in rows if r["method"] == case and r["status"] == "ok"]
        fit = growth_exponent([r["n"] for r in done], [r["ms"] / 1e3 for r in done])
        rows.append({"sweep": "output fit", "method": case, "k_n": None if fit is None else fit[0]})
        print(f"{case:<18}{'n/a' if fit is None else f'{fit[0]:.2f}':>7}")
    return rows


def _median_run(draw) -> float:
    times: list[float] = []
    started = time.perf_counter()
    while len(times) < REPEAT and (not times or time.perf_counter() - started < BUDGET / 3):
        tick = time.perf_counter()
        draw()
        times.append(time.perf_counter() - tick)
    return statistics.median(times)

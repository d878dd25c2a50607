"""Visibility benchmark: every algorithm of `scanviz.visibility.ALGORITHMS` against the z-buffer.

Scenes (seeded; 256 x 256 raster by default, corner sampling, 8 sub-pixel
bits, no attributes to interpolate):

* n random triangles, n = 10, 100, 1,000, 10,000 (`random_triangles`):
  centers uniform over the raster, vertices uniform within r of the center,
  r chosen so that the triangles' expected summed area is
  `DEPTH_COMPLEXITY` times the raster's whatever n (the same fragment work
  at every n: the growth measured is the algorithms' own). Each triangle is
  a plane z = z0 + a (x - cx) + b (y - cy) with z0 uniform in [0.1, 0.9]
  and slopes that move z by at most `DEPTH_SPREAD` over the triangle. Pairs
  are not kept apart in depth (testing every overlapping pair is too slow
  at 10,000): overlapping triangles whose z0 are close interpenetrate, which
  the painter's algorithm gets wrong and the splitting algorithms must not.
* meshes, as `render` prepares them (flat shading): builtin:sphere without
  culling (every back face behind a front face) and builtin:terrain
  (n = 60, a height field that hides much of itself).

Every algorithm runs untraced (its compiled path) through
`scanviz.visibility.solve`, once on a small scene first (numba compiles or
loads its kernels), then `repeat` times per scene: the median is printed.
Agreement with the z-buffer is measured on the samples either covers:
"agree" is the fraction showing the z-buffer's polygon, "unique" the
fraction whose nearest surface is unique by more than `TOLERANCE` in depth,
"agree@unique" the agreement over those (1 for an exact algorithm);
"holes" counts the samples the z-buffer covers and the algorithm leaves
empty, ">slack" those shown farther than the nearest surface by more than
the algorithm's own promise (`VisibilityResult.depth_slack`; "-": none
made). Both are 0 for a correct algorithm.

Each algorithm has a time `budget` (seconds of solve calls, warm-up not
counted). Before a scene, its time is predicted from the growth measured so
far (the exponent between the last two sizes, at least 1; 2 after one
size); a scene predicted to overrun the budget, and every larger one, is
reported "over budget" instead of run, so a quadratic algorithm at 10,000
polygons cannot hang the bench.
"""

from __future__ import annotations

import statistics
from dataclasses import dataclass, field
from time import perf_counter

import numpy as np

from ..progress import progress
from ..visibility import ALGORITHMS, ScreenPolygons, solve, zbuffer

SIZES = (10, 100, 1_000, 10_000)
WIDTH = HEIGHT = 256
REPEAT = 3
BUDGET = 30.0  # seconds of solve calls per algorithm
DEPTH_COMPLEXITY = 4.0  # expected summed triangle area / raster area
DEPTH_SPREAD = 0.01  # largest change of z over one triangle (z0 spans 0.8)
TOLERANCE = 1e-7  # depth gap below which either surface may be shown
FIT_FLOOR = 1e-3  # seconds: shorter runs are overhead, left out of the growth fit
_TRIANGLE_AREA = 11 / 144  # expected area of a triangle of 3 uniform points in a unit square


@dataclass(frozen=True)
class BenchScene:
    """A scene of the benchmark: its label ("random", "sphere (no cull)", ...) and polygons."""

    label: str
    polygons: ScreenPolygons
    random: bool  # a random-triangle scene: part of the growth fit


def random_triangles(count: int, width: int, height: int, seed: int = 0) -> ScreenPolygons:
    """`count` random slanted triangles over a width x height raster (see the module).

    >>> random_triangles(100, 64, 64).count
    100
    """
    rng = np.random.default_rng(seed)
    radius = np.sqrt(DEPTH_COMPLEXITY * width * height / (count * 4 * _TRIANGLE_AREA))
    centers = rng.uniform(0, (width, height), (count, 1, 2))
    xy = centers + rng.uniform(-radius, radius, (count, 3, 2))
    slopes = rng.uniform(-1, 1, (count, 1, 2)) * DEPTH_SPREAD / (4 * radius)  # |dz| <= spread / 2
    z = rng.uniform(0.1, 0.9, (count, 1)) + ((xy - centers) * slopes).sum(axis=2)
    return ScreenPolygons(
        xy=xy.reshape(-1, 2),
        z=z.reshape(-1),
        inv_w=np.ones(3 * count),
        values=np.zeros((3 * count, 0)),
        offsets=np.arange(0, 3 * count + 1, 3),
    )


def mesh_scenes(width: int, height: int, quick: bool = False) -> list[BenchScene]:
    """builtin:sphere without culling and builtin:terrain (n = 60; not if `quick`), prepared."""
    from ..pipeline import prepare
    from ..scene.builtin import builtin_scene

    scenes = []
    for label, scene, cull in (
        ("sphere (no cull)", builtin_scene("sphere"), False),
        *(() if quick else (("terrain n=60", builtin_scene("terrain", n=60), None),)),
    ):
        prepared = prepare(scene, width, height, shading="flat", cull=cull)
        scenes.append(BenchScene(label, prepared.polygons, False))
    return scenes


def _subset(polygons: ScreenPolygons, chosen: np.ndarray) -> ScreenPolygons:
    """The polygons `chosen` (indices) of `polygons`, without attributes."""
    starts, ends = polygons.offsets[chosen], polygons.offsets[chosen + 1]
    rows = np.concatenate([np.arange(s, e) for s, e in zip(starts, ends, strict=True)])
    return ScreenPolygons(
        xy=polygons.xy[rows],
        z=polygons.z[rows],
        inv_w=polygons.inv_w[rows],
        values=np.zeros((len(rows), 0)),
        offsets=np.concatenate([[0], np.cumsum(ends - starts)]),
    )


def disjoint_groups(polygons: ScreenPolygons, width: int, height: int) -> list[np.ndarray]:
    """Polygon indices in groups whose pixel bounding boxes (1-pixel margin) do not overlap.

    Drawn together, the polygons of a group cover disjoint samples, so one
    z-buffer per group gives every polygon's depth as drawing it alone does.
    Each polygon goes one group above the highest group already over its box.
    """
    if not polygons.count:
        return []
    starts = polygons.offsets[:-1]
    low = np.floor(np.minimum.reduceat(polygons.xy, starts, axis=0)).astype(np.int64) - 1
    high = np.ceil(np.maximum.reduceat(polygons.xy, starts, axis=0)).astype(np.int64) + 2
    low, high = np.clip(low, 0, (width, height)), np.clip(high, 0, (width, height))
    level = np.zeros((height, width), np.int64)  # per pixel: the lowest group free there
    group = np.zeros(polygons.count, np.int64)
    for p, ((x0, y0), (x1, y1)) in enumerate(zip(low.tolist(), high.tolist(), strict=True)):
        box = level[y0:y1, x0:x1]
        if box.size:  # off the raster: it draws nothing, any group will do
            group[p] = box.max()
            box[...] = group[p] + 1
    return [np.flatnonzero(group == g) for g in range(int(group.max()) + 1)]


def unique_nearest(
    polygons: ScreenPolygons, width: int, height: int, tol: float = TOLERANCE, **options
) -> np.ndarray:
    """(H, W) bool: the nearest covering polygon is unique by more than `tol` (or none covers).

    `options` are those of `zbuffer`. There every correct visibility
    algorithm shows the z-buffer's polygon. The two nearest depths per
    sample are kept over the z-buffers of `disjoint_groups`.

    >>> scene = ScreenPolygons.from_polygons([
    ...     [(0, 0, 0.5), (3, 0, 0.5), (3, 2, 0.5), (0, 2, 0.5)],
    ...     [(2, 0, 0.5), (4, 0, 0.5), (4, 2, 0.5), (2, 2, 0.5)],  # coplanar over column 2
    ... ])
    >>> unique_nearest(scene, 4, 2).astype(int)
    array([[1, 1, 0, 1],
           [1, 1, 0, 1]])
    """
    nearest = np.full((height, width), np.inf)
    second = np.full((height, width), np.inf)
    for group in disjoint_groups(polygons, width, height):
        depth = zbuffer(_subset(polygons, group), width, height, **options).depth
        second = np.minimum(second, np.maximum(nearest, depth))
        nearest = np.minimum(nearest, depth)
    with np.errstate(invalid="ignore"):  # inf - inf where fewer than two polygons cover
        gap = second - nearest
    return np.isinf(nearest) | np.isinf(second) | (gap > tol)


def agreement(polygon: np.ndarray, reference: np.ndarray, unique: np.ndarray) -> tuple:
    """(agree, unique, agree@unique) over the samples `polygon` or the z-buffer's `reference` cover."""
    covered = (polygon >= 0) | (reference >= 0)
    total = max(int(covered.sum()), 1)
    same = covered & (polygon == reference)
    decided = covered & unique
    return (
        int(same.sum()) / total,
        int(decided.sum()) / total,
        int((same & decided).sum()) / max(int(decided.sum()), 1),
    )


def growth_exponent(counts, seconds) -> tuple[float, int, int] | None:
    """(k, smallest n, largest n): least-squares slope of log time on log n over runs > 1 ms.

    None when fewer than two polygon counts took longer than `FIT_FLOOR`.

    >>> k, low, high = growth_exponent([10, 100, 1000, 10000], [1e-4, 2e-3, 2e-2, 2e-1])
    >>> round(k, 6), low, high
    (1.0, 100, 10000)
    """
    kept = [(n, s) for n, s in zip(counts, seconds, strict=True) if s > FIT_FLOOR]
    if len({n for n, _ in kept}) < 2:
        return None
    counts_kept = [n for n, _ in kept]
    slope = float(np.polyfit(np.log(counts_kept), np.log([s for _, s in kept]), 1)[0])
    return slope, min(counts_kept), max(counts_kept)


def predicted_seconds(history: list[tuple[int, float]], count: int) -> float:
    """One run's time at `count` polygons, extrapolated from (polygons, seconds) measured so far."""
    if not history:
        return 0.0
    n, s = max(history)
    if len(history) == 1:
        return s * max(count / n, 1.0) ** 2
    (n0, s0), (n1, s1) = sorted(history)[-2:]  # distinct counts: `run_visibility` dedups sizes
    exponent = max(1.0, np.log(max(s1, 1e-9) / max(s0, 1e-9)) / np.log(n1 / n0))
    return s * max(count / n, 1.0) ** exponent


@dataclass
class _Bench:
    """One run of the benchmark: its scenes and settings, the z-buffer's images and times."""

    scenes: list[BenchScene]
    width: int
    height: int
    repeat: int
    budget: float
    column: int = 11  # width of the algorithm column
    references: dict = field(default_factory=dict)  # scene index -> (z-buffer ids, depth, unique)
    zbuffer_seconds: dict = field(default_factory=dict)  # scene index -> seconds

    def reference(self, index: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The z-buffer's polygon and depth per sample, and where the nearest is unique."""
        if index not in self.references:
            polygons = self.scenes[index].polygons
            drawn = zbuffer(polygons, self.width, self.height)
            unique = unique_nearest(polygons, self.width, self.height)
            self.references[index] = (drawn.polygon, drawn.depth, unique)
        return self.references[index]

    def measure(self, name: str, bar) -> list[dict]:
        """Time `name` on every scene within its budget; print and return one row per scene."""
        solve(name, random_triangles(10, self.width, self.height, seed=1), self.width, self.height)
        history: list[tuple[int, float]] = []  # (polygons, seconds) of the random scenes
        rows, spent, over = [], 0.0, False
        for index, scene in enumerate(self.scenes):
            count = scene.polygons.count
            row = {
                "algorithm": name,
                "scene": scene.label,
                "polygons": count,
                "random": scene.random,
            }
            guess = predicted_seconds(history, count)
            over = over or spent + guess > self.budget
            if over:
                bar.write(
                    f"{name:<{self.column}}{scene.label:<17}{count:>9,}  over budget "
                    f"(predicted {guess:.3g} s per run, {spent:.3g} s spent)"
                )
                rows.append(row | {"over_budget": True, "predicted_s": guess})
            else:
                rows.append(row | self.timed_row(name, index, self.budget - spent, bar.write))
                spent += rows[-1]["spent_s"]
                if scene.random:
                    history.append((count, rows[-1]["ms"] / 1e3))
            bar.update(1)
        return rows

    def timed_row(self, name: str, index: int, left: float, say=print) -> dict:
        """Time `name` on scene `index` with `left` seconds of budget; `say` its line."""
        scene, width, height = self.scenes[index], self.width, self.height
        times: list[float] = []
        while len(times) < self.repeat and (not times or sum(times) < left):
            tick = perf_counter()
            result = solve(name, scene.polygons, width, height)
            times.append(perf_counter() - tick)
        seconds = statistics.median(times)
        if name == "zbuffer":
            self.zbuffer_seconds[index] = seconds
        ratio = seconds / self.zbuffer_seconds.get(index, np.nan)
        ids, depth, unique_mask = self.reference(index)
        agree, unique, agree_unique = agreement(result.polygon, ids, unique_mask)
        holes, beyond = _holes_and_beyond(result, ids, depth)
        count = scene.polygons.count
        say(
            f"{name:<{self.column}}{scene.label:<17}{count:>9,}{seconds * 1e3:>10.2f}"
            f"{count / seconds:>12,.0f}{ratio:>11.2f}{agree:>8.4f}{unique:>8.4f}{agree_unique:>13.6f}"
            f"{holes:>7}{'-' if beyond is None else beyond:>8}"
        )
        return {
            "over_budget": False,
            "ms": seconds * 1e3,
            "runs": len(times),
            "spent_s": sum(times),
            "ratio": ratio,
            "agree": agree,
            "unique": unique,
            "agree_unique": agree_unique,
            "holes": holes,
            "beyond_slack": beyond,
        }


def _holes_and_beyond(result, ids: np.ndarray, depth: np.ndarray) -> tuple[int, int | None]:
    """(samples the z-buffer covers left empty, samples farther than the result's depth_slack)."""
    holes = int(((ids >= 0) & (result.polygon < 0)).sum())
    if result.depth_slack is None:
        return holes, None
    both = (ids >= 0) & (result.polygon >= 0)
    return holes, int((result.depth[both] - depth[both] > result.depth_slack).sum())


def run_visibility(
    *,
    quick: bool = False,
    sizes: tuple[int, ...] | None = None,
    width: int | None = None,
    height: int | None = None,
    repeat: int | None = None,
    algorithms: tuple[str, ...] | None = None,
    budget: float | None = None,
    plot: str | None = None,
) -> list[dict]:
    """Time every algorithm on every scene, print the table and growth exponents, return the rows.

    `algorithms` default to every name in `ALGORITHMS` (the z-buffer, the
    reference, always runs first); `budget` defaults to `BUDGET` seconds per
    algorithm; ``quick`` means 10 and 100 triangles and the sphere on 64 x 64,
    one run each. `plot` is a file for the log-log plot of time against
    polygons.
    """
    names = tuple(ALGORITHMS) if algorithms is None else algorithms
    for name in names:
        if name not in ALGORITHMS:
            raise ValueError(f"'algorithms': {name!r} is not one of {', '.join(ALGORITHMS)}")
    names = ("zbuffer", *dict.fromkeys(n for n in names if n != "zbuffer"))
    sizes = tuple(sorted(set(((10, 100) if quick else SIZES) if sizes is None else sizes)))
    width = (64 if quick else WIDTH) if width is None else width
    height = (64 if quick else HEIGHT) if height is None else height
    repeat = (1 if quick else REPEAT) if repeat is None else repeat
    budget = BUDGET if budget is None else budget
    scenes = [BenchScene("random", random_triangles(n, width, height), True) for n in sizes]
    column = max(11, 1 + max(map(len, names)))
    bench = _Bench(
        scenes + mesh_scenes(width, height, quick), width, height, repeat, budget, column
    )
    print(
        f"visibility benchmark: {width}x{height}, corner sampling, subpixel_bits=8, no attributes, "
        f"untraced (compiled paths), median of {repeat} runs, budget {budget:g} s per algorithm"
    )
    print(
        f"random: triangles of summed area {DEPTH_COMPLEXITY:g}x the raster, depth slopes "
        f"within {DEPTH_SPREAD:g} per triangle (seed 0); meshes as render prepares them"
    )
    header = f"{'algorithm':<{column}}{'scene':<17}{'polygons':>9}{'ms':>10}{'polygons/s':>12}"
    print(
        header
        + f"{'x z-buffer':>11}{'agree':>8}{'unique':>8}{'agree@unique':>13}{'holes':>7}{'>slack':>8}"
    )
    rows = []
    cells = len(names) * len(bench.scenes)
    with progress(cells, "visibility bench", enabled=max(sizes) >= 1000) as bar:
        for name in names:
            rows += bench.measure(name, bar)
    _print_growth(names, rows, column)
    print(
        "agree: covered samples showing the z-buffer's polygon; unique: covered samples whose "
        f"nearest surface is unique by > {TOLERANCE:g} in depth;"
    )
    print(
        "agree@unique: agree over the unique ones (1 for an exact algorithm); "
        "x z-buffer: time / the z-buffer's time (> 1: slower)"
    )
    print(
        "holes: samples the z-buffer covers left empty; >slack: samples shown farther than the "
        "nearest by more than the algorithm's depth_slack (-: no promise); 0 when correct"
    )
    if plot:
        save_plot(rows, plot)
        print(f"plot: {plot}")
    return rows


def _random_rows(rows: list[dict], name: str) -> list[dict]:
    return [r for r in rows if r["algorithm"] == name and not r["over_budget"] and r["random"]]


def _print_growth(names, rows, column) -> None:
    print(f"growth: time ~ polygons^k, least squares on log-log over random scenes > {FIT_FLOOR * 1e3:g} ms")  # fmt: skip
    for name in names:
        measured = _random_rows(rows, name)
        counts, seconds = [r["polygons"] for r in measured], [r["ms"] / 1e3 for r in measured]
        fit = growth_exponent(counts, seconds)
        skipped = [r["polygons"] for r in rows if r["algorithm"] == name and r["over_budget"]]
        over = f"; over budget from {min(skipped):,} polygons" if skipped else ""
        if fit is None:
            print(
                f"  {name:<{column}}k = n/a (fewer than two sizes over {FIT_FLOOR * 1e3:g} ms){over}"
            )
            continue
        last = growth_exponent(counts[-2:], seconds[-2:])  # the largest step: least overhead
        step = (
            f", k = {last[0]:.2f} from {last[1]:,} to {last[2]:,}"
            if last and fit[1] < last[1]
            else ""
        )
        print(f"  {name:<{column}}k = {fit[0]:.2f}  ({fit[1]:,}..{fit[2]:,} polygons{step}){over}")


def save_plot(rows: list[dict], path: str) -> None:
    """Log-log plot of time against polygons, one line per algorithm (random scenes)."""
    from matplotlib.figure import Figure  # no pyplot: leaves the caller's backend alone

    figure = Figure(figsize=(7, 5))
    axes = figure.subplots()
    for name in dict.fromkeys(r["algorithm"] for r in rows):
        measured = _random_rows(rows, name)
        if measured:
            counts = [r["polygons"] for r in measured]
            axes.loglog(counts, [r["ms"] for r in measured], "o-", label=name)
    axes.set_xlabel("polygons (random triangles)")
    axes.set_ylabel("time per solve (ms)")
    axes.set_title("Visibility algorithms: time against polygon count")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=120)

"""Compile every numba kernel once, before a student or a test waits for it.

numba compiles a kernel the first time it is called with new argument types
and keeps the machine code in its on-disk cache (``__pycache__`` beside the
source, or ``NUMBA_CACHE_DIR``). `warmup()` calls each family of the package
on a tiny input of every kind the lessons and the tests use, with a progress
bar, so that later runs only load the cache.

numba keys a cached kernel by its own file's time stamp, not by the files
whose functions it inlines. `drop_stale_kernels()` therefore keeps a hash of
every source file and, for the files that changed, drops the cached kernels
of those files and of every module that imports them (directly or not), and
nothing else.

`scanviz.progress.announce_compiling()` prints a one-line note the first time
a kernel compiles in a process, so a cold cache is never a silent stall.
"""

from __future__ import annotations

import ast
import hashlib
import json
import time
from collections.abc import Callable
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent
STAMP_NAME = "warmup-sources.json"


def _raster() -> None:
    import scanviz as sv
    from scanviz.raster import ColourWash, Pattern, Solid, VertexColours, fill_polygon

    polygon = [(4, 1), (1, 11), (9, 5), (12, 8), (12, 1)]
    for sample in ("corner", "center"):
        for rule in ("nonzero", "evenodd"):
            sv.scan_convert(polygon, 14, 13, sample=sample, rule=rule)
    for arithmetic in ("float32", "float64"):
        sv.scan_convert(polygon, 14, 13, arithmetic=arithmetic)
    sv.scan_convert(polygon, 14, 13, subpixel_bits=None)
    sv.fill_polygons([polygon, [(0, 0), (5, 0), (0, 5)]], 14, 13)
    sv.rasterize_triangles([[(0, 0), (9, 1), (3, 8)]], 14, 13)
    sv.triangle_samples([(0, 0), (9, 1), (3, 8)], 14, 13)
    sv.midpoint_line(0, 0, 9, 4)
    sv.area_coverage(polygon, 14, 13)
    for fill in (
        Solid((1, 0, 0)),
        Pattern.checker(),
        ColourWash((1, 0, 0), (0, 0, 1)),
        VertexColours([(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, 1, 1)]),
    ):
        fill_polygon(polygon, 14, 13, fill)


def _render(shadings: tuple[str, ...], visibilities: tuple[str, ...]) -> Callable[[], None]:
    def run() -> None:
        from scanviz import render
        from scanviz.io import load_scene

        scene = load_scene("builtin:sphere")
        for shading in shadings:
            for visibility in visibilities:
                render(scene, 24, 24, shading=shading, visibility=visibility)

    return run


def _render_options() -> None:
    from scanviz import Recorder, render
    from scanviz.io import load_scene
    from scanviz.scene import Camera, Mesh, Scene, SceneObject

    cube = load_scene("builtin:transparent_cube")
    for mask in ("4x4", "8x4", "8x8"):
        render(cube, 24, 24, visibility="abuffer", mask=mask)
    render(cube, 24, 24, visibility="abuffer", weights="mask", merge="object")
    render(cube, 48, 48, visibility="abuffer", trace=Recorder(region=(24, 24, 28, 28)))
    sphere = load_scene("builtin:sphere")
    render(sphere, 24, 24, shading="gouraud", perspective_correct=False, edges=True)
    render(sphere, 24, 24, sample="center", subpixel_bits=None)
    for shading in ("flat", "gouraud", "phong"):
        render(sphere, 12, 12, shading=shading, trace=True)
    render(sphere, 24, 24, shading="phong").relight(ambient=(0.2, 0.2, 0.2))
    # rasters and fragment counts above the thresholds where numba's threads take over
    for shading in ("flat", "gouraud", "phong"):
        render(sphere, 300, 300, shading=shading)
    render(sphere, 160, 160, visibility="abuffer")
    # a floor that crosses the near plane: the clipper's outcodes
    floor = Mesh([(-1, 0, 1), (1, 0, 1), (1, 0, -4), (-1, 0, -4)], [[0, 1, 2], [0, 2, 3]])
    camera = Camera(eye=(0, 0.6, 2), look_at=(0, 0, -1), window=(-0.5, 0.5, -0.5, 0.5))
    render(Scene([SceneObject(floor)], camera=camera), 24, 24, shading="gouraud")


def _fast_phong() -> None:
    import numpy as np

    from scanviz.shading import (
        ReflectionModel,
        exact_phong_triangle,
        fast_phong_triangle,
        lut_levels,
        specular_lut,
    )

    model = ReflectionModel(Ia=255, ka=0.1, Ip=255, kd=(0.75, 0.55, 0.3), ks=0.7, n=8)
    normals = [(0, 0, 1), (0.2, 0, 1), (0, 0.2, 1)]
    for expansion in ("vertex", "centroid"):
        fast_phong_triangle(
            [(1, 1), (20, 3), (6, 18)], normals, (0, 0, 1), (0, 0, 1), model,
            width=24, height=24, expansion=expansion,
        )  # fmt: skip
    exact_phong_triangle(
        [(1, 1), (20, 3), (6, 18)], normals, (0, 0, 1), (0, 0, 1), model, width=24, height=24
    )
    lut_levels(specular_lut(255, 0.7, 1.5, 8), np.linspace(-1, 1, 9))


def _visibility() -> None:
    from scanviz.visibility import examples, solve

    for name in ("zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock"):
        for scene in (examples.slides_painter(), examples.cyclic_overlap()):
            solve(name, scene, 24, 24)


def _surfaces() -> None:
    from scanviz.surfaces import GridSurface, View, floating_horizon, floating_perimeter

    surface = GridSurface.from_function(lambda x, y: x * y, (-1, 1), (-1, 1), 6, 6)
    view = View((3.0, 2.0, 2.5), (-3.0, -2.0, -2.5))
    for family in ("x", "y"):
        floating_horizon(surface, view, 32, 32, family=family)
    floating_perimeter(surface, view, 32, 32, "lines")
    for shading in ("flat", "phong"):
        floating_perimeter(surface, view, 32, 32, "surface", shading=shading)


def _antialias() -> None:
    import numpy as np

    from scanviz.antialias import (
        dislop_circle,
        dislop_disk,
        dislop_edge,
        dislop_line,
        post_antialias,
    )
    from scanviz.antialias.peers import gupta_sproull_line, supersampled_line, wu_line

    for line in (wu_line, gupta_sproull_line, supersampled_line):
        line((1.2, 1.5), (20.3, 9.1), 24, 24)
    dislop_line((1.2, 1.5), (20.3, 9.1), 24, 24)
    dislop_line((1.2, 1.5), (20.3, 9.1), 24, 24, exact=True)
    dislop_edge([(2, 2), (20, 5), (9, 20)], 24, 24)
    dislop_circle((12, 12), 7.5, 24, 24)
    dislop_disk((12, 12), 7.5, 24, 24)
    segments = np.array([[[1.0, 1.0], [20.0, 15.0]]])
    post_antialias(np.zeros((24, 24)), segments, kind="line")
    post_antialias(np.zeros((24, 24, 3)), segments, kind="edge", flags=[1])


TASKS: dict[str, Callable[[], None]] = {
    "scan conversion and fills": _raster,
    "render: flat, Gouraud": _render(("flat", "gouraud"), ("zbuffer",)),
    "render: Phong, Gooch, fast Phong": _render(("phong", "gooch", "fast_phong"), ("zbuffer",)),
    "render: a-buffer and the flawed blend": _render(("phong",), ("abuffer", "flawed")),
    "render: painter, depth sort, BSP": _render(
        ("flat", "gouraud"), ("painter", "depth_sort", "bsp")
    ),
    "render: scanline, Warnock": _render(("flat", "gouraud"), ("scanline", "warnock")),
    "render options": _render_options,
    "fast Phong and its table": _fast_phong,
    "visibility algorithms": _visibility,
    "grid surfaces": _surfaces,
    "anti-aliasing": _antialias,
}


def warmup(*, quiet: bool = False) -> float:
    """Compile (or load) every kernel family once; returns the seconds it took.

    Stale kernels are dropped first (`drop_stale_kernels`).
    """
    from tqdm.auto import tqdm

    began = time.perf_counter()
    dropped = drop_stale_kernels()
    if dropped and not quiet:
        print(f"scanviz: {dropped} changed source files: their kernels will be compiled again")
    with tqdm(TASKS.items(), desc="warming up numba kernels", unit="family", disable=quiet) as bar:
        for name, task in bar:
            bar.set_postfix_str(name)
            task()
    record_sources()
    return time.perf_counter() - began


def source_hashes(package: Path = PACKAGE) -> dict[str, str]:
    """{path relative to `package`: sha256} of every Python source of the package."""
    return {
        str(path.relative_to(package)): hashlib.sha256(path.read_bytes()).hexdigest()
        for path in sorted(package.rglob("*.py"))
    }


def importers(package: Path = PACKAGE) -> dict[str, set[str]]:
    """{source: the sources that import it, directly or through others} inside `package`."""
    imported_by: dict[str, set[str]] = {}
    for path in package.rglob("*.py"):
        source = str(path.relative_to(package))
        for target in _imports(path, package):
            imported_by.setdefault(target, set()).add(source)
    closure: dict[str, set[str]] = {}
    for source in imported_by:
        seen, todo = set(), [source]
        while todo:
            for user in imported_by.get(todo.pop(), ()):
                if user not in seen:
                    seen.add(user)
                    todo.append(user)
        closure[source] = seen
    return closure


def _imports(path: Path, package: Path) -> set[str]:
    """The package's own sources that `path` imports (absolute or relative, any depth)."""
    module = path.relative_to(package).with_suffix("").parts
    here = module[:-1]  # the package the module is in (a package's __init__ too)
    targets = set()
    for node in ast.walk(ast.parse(path.read_bytes())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = here[: len(here) - (node.level - 1)] if node.level > 1 else here
            elif node.module and node.module.split(".")[0] == package.name:
                base = ()
            else:
                continue
            parts = (*base, *(node.module.split(".") if node.module else ()))
            if not node.level:
                parts = parts[1:]
            for alias in node.names:  # a submodule, or else a name the module defines
                module = _source((*parts, alias.name), package)
                targets.add(module if module else _source(parts, package))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] == package.name:
                    targets.add(_source(tuple(parts[1:]), package))
    return targets - {None}


def _source(parts: tuple[str, ...], package: Path) -> str | None:
    """The source file of module `parts` (a package's ``__init__.py``), or None."""
    for candidate in (
        Path(*parts, "__init__.py"),
        Path(*parts).with_suffix(".py") if parts else None,
    ):
        if candidate is not None and (package / candidate).is_file():
            return str(candidate)
    return None


def cache_folder(source_folder: Path) -> Path:
    """Where numba caches the kernels of the sources in `source_folder` (as numba computes it)."""
    from numba.core import config
    from numba.core.caching import _CacheLocator

    if config.CACHE_DIR:
        subpath = _CacheLocator.get_suitable_cache_subpath(str(source_folder / "module.py"))
        return Path(config.CACHE_DIR) / subpath
    return source_folder / "__pycache__"


def _stamp(package: Path) -> Path:
    return cache_folder(package) / STAMP_NAME


def drop_stale_kernels(package: Path = PACKAGE) -> int:
    """Drop the cached kernels of changed sources and of their importers; the count changed.

    Without a record of the sources (a fresh cache, or one from before this
    rule) every cached kernel is dropped once.
    """
    stamp = _stamp(package)
    now = source_hashes(package)
    try:
        before = json.loads(stamp.read_text())
    except (OSError, ValueError):
        before = None
    if before is None:
        stale = set(now)
    else:
        stale = {source for source, digest in now.items() if before.get(source) != digest}
        stale |= set(before) - set(now)
    users = importers(package)
    drop = set(stale).union(*(users.get(source, set()) for source in stale))
    for source in drop:
        path = package / source
        for cached in cache_folder(path.parent).glob(f"{path.stem}.*.nb[ic]"):
            cached.unlink(missing_ok=True)
    return len(stale) if before is not None else 0


def record_sources(package: Path = PACKAGE) -> None:
    """Remember the sources the cache was built from (see `drop_stale_kernels`)."""
    stamp = _stamp(package)
    stamp.parent.mkdir(parents=True, exist_ok=True)
    stamp.write_text(json.dumps(source_hashes(package), indent=0, sort_keys=True))

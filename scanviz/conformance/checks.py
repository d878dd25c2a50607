"""The fuzz campaign's checks: call one entry point on a generated input and judge the result.

Each ``check_*`` takes the input dict of its strategy
(`scanviz.conformance.strategies`), calls the entry point and returns '' when
the result is correct (the exact oracle for the raster entry points, finite
values in range elsewhere) or what is wrong with it. An exception it raises
is judged by `scanviz.conformance.fuzz.classify`.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import numbers
import tempfile
import time
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import numpy as np

from .. import (
    Polygon,
    Trace,
    area_coverage,
    fill_polygons,
    midpoint_line,
    rasterize_triangles,
    scan_convert,
    triangle_samples,
)
from ..limits import current_memory_limit, format_size, memory_limit
from ..vectors import vector_norm
from . import exact
from .pipeline_checks import RENDER_MODES
from .strategies import base_scene


def _finite(name: str, array: np.ndarray) -> str:
    array = np.asarray(array)
    if array.dtype.kind in "fc" and not np.isfinite(array).all():
        return f"NaN or inf in {name}"
    return ""


def wrong_type(value: object) -> str:
    """The type name of the first coordinate in `value` that is not a real number, or ''.

    Complex numbers, strings, bytes, booleans, None and other objects are not
    coordinates: an entry point that returns for one has accepted it silently.
    """
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "bcUSV":
            return f"array of {value.dtype}"
        return wrong_type(value.tolist()) if value.dtype.kind == "O" else ""
    if isinstance(value, list | tuple):
        return next((w for w in map(wrong_type, value) if w), "")
    if isinstance(value, str | bytes | dict | set) and not value:
        return ""  # empty: it holds no coordinate
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real | Decimal):
        return type(value).__name__
    return ""


def _accepted(value: object) -> str:
    kind = wrong_type(value)
    return f"accepted a {kind} coordinate" if kind else ""


def _contours(polygon_input) -> list[list]:
    return [c.tolist() for c in Polygon(polygon_input).contours]


def _oracle(contours: list, args: dict) -> np.ndarray:
    """The exact oracle's mask of `contours` on the raster and with the options of `args`."""
    options = args["options"]
    return exact.oracle_mask(
        contours, args["width"], args["height"], options.get("sample", "corner"),
        options.get("rule", "nonzero"), options.get("subpixel_bits", 8),
    )  # fmt: skip


def check_scan_convert(args: dict):
    result = scan_convert(args["polygon"], args["width"], args["height"], **args["options"])
    problem = _accepted(args["polygon"])
    if problem:
        return problem
    if result.mask.shape != (args["height"], args["width"]) or result.mask.dtype != bool:
        return f"mask of shape {result.mask.shape}, dtype {result.mask.dtype}"
    if args["options"].get("arithmetic", "exact") != "exact":
        return ""  # the textbook float DDA may drift by design
    want = _oracle(_contours(args["polygon"]), args)
    return "" if np.array_equal(result.mask, want) else "mask differs from the exact oracle"


def check_fill_polygons(args: dict):
    counts = fill_polygons(args["polygons"], args["width"], args["height"], **args["options"])
    if counts.shape != (args["height"], args["width"]) or counts.dtype != np.int32:
        return f"counts of shape {counts.shape}, dtype {counts.dtype}"
    polygons = args["polygons"]
    if _accepted(polygons) or len(list(polygons)) > 6:
        return _accepted(polygons)
    want = sum((_oracle(_contours(item), args) for item in polygons), np.zeros(counts.shape, int))
    return "" if np.array_equal(counts, want) else "counts differ from the exact oracle"


def check_rasterize_triangles(args: dict):
    counts = rasterize_triangles(
        args["triangles"], args["width"], args["height"], **args["options"]
    )
    if counts.shape != (args["height"], args["width"]):
        return f"counts of shape {counts.shape}"
    triangles = args["triangles"]
    if _accepted(triangles):
        return _accepted(triangles)
    triangles = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 2)
    if len(triangles) > 6:
        return ""
    want = sum((_oracle([t.tolist()], args) for t in triangles), np.zeros(counts.shape, int))
    return "" if np.array_equal(counts, want) else "counts differ from the exact oracle"


def check_triangle_samples(args: dict):
    found = triangle_samples(args["triangle"], args["width"], args["height"], **args["options"])
    problem = _accepted(args["triangle"]) or _finite("barycentric", found.barycentric)
    if not problem and not isinstance(args["options"].get("polygon", 0), numbers.Integral):
        problem = f"accepted polygon={args['options']['polygon']!r}"
    if problem:
        return problem
    image = np.zeros((args["height"], args["width"]), bool)
    image[found.ys, found.xs] = True
    want = _oracle([np.asarray(args["triangle"], dtype=np.float64).tolist()], args)
    if not np.array_equal(image, want):
        return "samples differ from the exact oracle"
    if len(found.xs) and np.abs(found.barycentric.sum(axis=1) - 1).max() > 1e-9:
        return "barycentric weights do not sum to 1"
    return ""


def check_area_coverage(args: dict):
    options = {k: v for k, v in args["options"].items() if k != "sample"}  # it has no samples
    image = area_coverage(args["polygon"], args["width"], args["height"], **options)
    problem = _accepted(args["polygon"]) or _finite("area_coverage", image)
    if problem:
        return problem
    if (
        image.shape != (args["height"], args["width"])
        or image.size
        and (image.min() < 0 or image.max() > 1)
    ):
        return f"coverage of shape {image.shape} outside [0, 1]"
    return ""


def check_polygon(args: dict):
    polygon = Polygon(args["contours"])
    if _accepted(args["contours"]):
        return _accepted(args["contours"])
    vertices = polygon.vertices
    if vertices.dtype != np.float64 or not np.isfinite(vertices).all():
        return "non-finite or non-float vertices accepted"
    if np.abs(vertices).max() > 2**20:
        return "a vertex beyond 2**20 accepted"
    return ""


def check_midpoint_line(args: dict):
    x0, y0, x1, y1 = args["ends"]
    xs, ys = midpoint_line(x0, y0, x1, y1)
    return check_line_pixels(int(x0), int(y0), int(x1), int(y1), xs, ys)


def check_line_pixels(x0, y0, x1, y1, xs, ys) -> str:
    """Endpoints, one pixel per major step, and the nearest minor coordinate (ties to the smaller)."""
    dx, dy = x1 - x0, y1 - y0
    if len(xs) != max(abs(dx), abs(dy)) + 1 or (xs[0], ys[0], xs[-1], ys[-1]) != (x0, y0, x1, y1):
        return "wrong pixel count or endpoints"
    if len(xs) > 64:
        return ""
    steep = abs(dy) > abs(dx)
    for x, y in zip(xs.tolist(), ys.tolist(), strict=True):
        major, minor = (y, x) if steep else (x, y)
        m0, n0, dm, dn = (y0, x0, dy, dx) if steep else (x0, y0, dx, dy)
        exact_minor = n0 + Fraction(dn * (major - m0), dm) if dm else Fraction(n0)
        nearest = math.ceil(exact_minor - Fraction(1, 2))  # ties to the smaller
        if minor != nearest:
            return f"pixel ({x}, {y}) is not the nearest to the line"
    return ""


def _render_checked(scene, mode: int) -> str:
    from ..pipeline import render

    shading, visibility = RENDER_MODES[mode % len(RENDER_MODES)]
    result = render(scene, 6, 5, shading=shading, visibility=visibility, mask="4x4")
    image = result.image
    problem = _finite(f"the {shading}/{visibility} image", image)
    if problem:
        return problem
    if image.shape != (5, 6, 3) or image.min() < 0 or image.max() > 1:
        return f"the {shading}/{visibility} image is outside [0, 1]"
    return ""


def check_scene_dict(args: dict):
    from ..io import load_scene

    return _render_checked(load_scene(args["scene"]), args["mode"])


def check_scene_file(args: dict):
    from ..io import load_scene

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / args["name"]
        if args["kind"] == "file":
            path.write_bytes(args["data"])
        elif args["kind"] == "directory":
            path.mkdir()
        return _render_checked(load_scene(str(path)), args["mode"])  # "missing": no file


def check_obj(args: dict):
    from ..io import load_obj

    mesh = load_obj("\n".join(args["lines"]) + "\n")
    problem = _finite("positions", mesh.positions)
    if not problem and mesh.normals is not None:
        problem = _finite("normals", mesh.normals)
        if not problem and len(mesh.normals):
            lengths = vector_norm(mesh.normals)  # no overflow for huge components
            if np.abs(lengths - 1).max() > 1e-9:
                return "normals are not unit vectors"
    return problem


def check_trace(args: dict):
    trace = Trace.from_json(args["text"])
    text = trace.to_json()
    json.loads(text, parse_constant=_reject_constant)  # strict JSON: no NaN or Infinity
    return "" if Trace.from_json(text) == trace else "to_json/from_json does not round-trip"


def _reject_constant(name: str):
    raise ValueError(f"to_json wrote the non-JSON constant {name}")


MAX_CLI_LINE = 300  # characters: echoed input must be shortened


def check_cli(args: dict):
    from ..cli import main

    with tempfile.TemporaryDirectory() as folder:
        (Path(folder) / "scene.json").write_text(json.dumps(base_scene()))
        (Path(folder) / "bad.json").write_bytes(b'{"camera": [' + b"[" * 3000)
        (Path(folder) / "model.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        (Path(folder) / "huge.obj").write_text("v 1e308 0 0\nv -1e308 0 0\nv 0 1e308 0\nf 1 2 3\n")
        argv = [t.replace("OUT", folder) for t in args["argv"]]
        stderr, stdout = io.StringIO(), io.StringIO()
        with (
            contextlib.redirect_stderr(stderr),
            contextlib.redirect_stdout(stdout),
            warnings.catch_warnings(),
        ):
            warnings.simplefilter("default")  # what a user sees, not the campaign's silence
            try:
                status = main(argv)
            except SystemExit as exit_:
                status = exit_.code if isinstance(exit_.code, int) else 2
    lines = stderr.getvalue().strip().splitlines()
    if status not in (0, 2):
        return f"exit status {status}"
    if "Traceback" in stderr.getvalue() or len(lines) > 1:
        return f"stderr has {len(lines)} lines: {' | '.join(lines[:3])[:200]}"
    if lines and len(lines[0]) > MAX_CLI_LINE:
        return f"a stderr line of {len(lines[0]):,} characters: {lines[0][:100]}..."
    if status == 2:
        raise _CliError(lines[0] if lines else "")
    return ""


class _CliError(ValueError):
    """A CLI exit 2 with its one-line message, judged by the clear-error rule."""


def limit_cases() -> dict[str, Callable[[], object]]:
    """Requests the documented limits allow but 1G of memory does not (issue 8, defect 7)."""
    from ..pipeline import render
    from ..scene import builtin_scene, terrain, torus, uv_sphere

    big, tri = 2**16, [(0, 0), (2**16, 0), (0, 2**16)]
    zigzag = [(x % 64 + 0.5 * (i % 2), i % 2) for i, x in enumerate(range(100_000))]
    return {
        "scan_convert 65536x65536": lambda: scan_convert(tri, big, big),
        "fill_polygons 65536x65536": lambda: fill_polygons([tri], big, big),
        "rasterize_triangles 65536x65536": lambda: rasterize_triangles([tri], big, big),
        "area_coverage 65536x65536": lambda: area_coverage(tri, big, big),
        "triangle_samples 65536x65536": lambda: triangle_samples(tri, big, big).xs.size,
        "render 65536x65536": lambda: render(builtin_scene("painter"), big, big).image.shape,
        "scan_convert 10,000 tall edges on 4x65536": lambda: (
            scan_convert([(0, 0), (1, big)] * 10000 + [(2, 0)], 4, big).mask.shape
        ),
        "area_coverage 100,000-vertex zigzag on 64x1": lambda: area_coverage(zigzag, 64, 1),
        "uv_sphere(4096, 4096)": lambda: uv_sphere(4096, 4096).positions.shape,
        "torus 4096 x 4096": lambda: torus(n_major=4096, n_minor=4096).positions.shape,
        "terrain(n=2048)": lambda: terrain(n=2048).positions.shape,
    }


def check_limit(args: dict):
    """A limit case must refuse (a clear ResourceLimitError) unless its output fits in the limit."""
    name = args["case"]
    limit_cases()[name]()
    if "65536x65536" in name:
        return "returned a 65536x65536 result under a 1G memory limit"
    return ""


# --- time and memory against size ----------------------------------------------------------------

SCALING_MEMORY = "64M"  # the memory limit of the scaling cases: small, so that "over" stays cheap
BASE_SECONDS = 1.0  # in every time bound: a cold page cache, a busy machine
MEMORY_ALLOWANCE = 2  # a call may add this many times the memory limit to the peak RSS (+ 32 MiB)


@dataclass(frozen=True)
class ScalingCase:
    """An entry point on an input that scales: ``run(size)``, judged against time and memory.

    The time bound is ``BASE_SECONDS + size * seconds_per_unit``: generous for
    the linear (or n log n) cost the entry point should have, far under a
    quadratic one at `size`. ``run(warm)`` runs first, untimed (kernels
    compiled, caches filled). With `refuses`, the input is over the memory
    limit: a clear error is right and an answer is a failure.
    """

    run: Callable[[int], object]
    size: int
    unit: str
    seconds_per_unit: float
    warm: int = 3
    refuses: bool = False

    @property
    def seconds(self) -> float:
        return BASE_SECONDS + self.size * self.seconds_per_unit


def _star(count: int) -> np.ndarray:
    """A simple star polygon of `count` vertices inside a 256x256 raster."""
    from .cases import star_polygon

    return star_polygon(np.random.default_rng(count), (128.0, 128.0), 120.0, max(count, 4))


def _triangles(count: int, extent: float = 256.0) -> np.ndarray:
    """`count` random small triangles in [0, extent)^2: (count, 3, 2)."""
    rng = np.random.default_rng(count)
    corners = rng.uniform(0, extent - 8, (count, 1, 2))
    return np.round((corners + rng.uniform(0, 8, (count, 3, 2))) * 256) / 256


def _soup_scene(count: int) -> dict:
    """A scene dict of `count` random intersecting triangles in front of the camera."""
    rng = np.random.default_rng(count)
    centres = rng.uniform((-4, -4, -1), (4, 4, 1), (count, 1, 3))  # the camera sees [-5, 5]^2
    positions = (centres + rng.uniform(-1, 1, (count, 3, 3))).reshape(-1, 3)
    scene = base_scene()
    scene["objects"] = [
        {
            "mesh": {
                "positions": positions.tolist(),
                "faces": np.arange(3 * count).reshape(-1, 3).tolist(),
                "closed": False,
            }
        }  # fmt: skip
    ]
    return scene


def _render_soup(visibility: str, shading: str = "flat") -> Callable[[int], object]:
    def run(count: int):
        from ..io import load_scene
        from ..pipeline import render

        return render(load_scene(_soup_scene(count)), 64, 64, visibility=visibility, shading=shading, mask="4x4")  # fmt: skip

    return run


def _obj_text(count: int) -> str:
    """OBJ text of a `count` x `count` grid of vertices, two triangles per cell."""
    xs, ys = np.meshgrid(np.arange(count), np.arange(count))
    vertices = "".join(f"v {x} {y} {(x * y) % 7}\n" for x, y in zip(xs.ravel(), ys.ravel(), strict=True))  # fmt: skip
    i = (ys[:-1, :-1] * count + xs[:-1, :-1] + 1).ravel()
    faces = "".join(
        f"f {a} {a + 1} {a + count}\nf {a + 1} {a + count + 1} {a + count}\n" for a in i
    )
    return vertices + faces


def _trace_text(count: int) -> str:
    span = {"kind": "span", "polygon": 0, "y": 1, "x_start": 0, "x_end": 3, "winding": 1}
    return json.dumps({"events": [span] * count})


def _load_fifo(size: int):
    """load_scene of a named pipe no one writes to: refused, not a wait."""
    import os

    from ..io import load_scene

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "scene.json"
        os.mkfifo(path)
        return load_scene(str(path))


def _load_json_text(text: str):
    from ..io import load_scene

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "scene.json"
        path.write_text(text)
        return load_scene(str(path))


def _surface(algorithm: str) -> Callable[[int], object]:
    def run(points: int):
        from ..surfaces import View, floating_horizon, floating_perimeter, gaussian

        surface, view = gaussian(points), View((6, 8, 3), (-6, -8, -3), "perspective")
        if algorithm == "fha":
            return floating_horizon(surface, view, 128, 128)
        return floating_perimeter(surface, view, 128, 128, "surface")

    return run


def scaling_cases() -> dict[str, ScalingCase]:
    """Inputs that scale, each with the time its size allows (under `SCALING_MEMORY`)."""
    from ..io import load_obj, load_scene
    from ..pipeline import render
    from ..raster import fill_polygon
    from ..scene import builtin_scene

    tri, star = [(0, 0), (40, 0), (0, 40)], _star
    cases = {
        "Polygon: 100,000-vertex star": (lambda n: Polygon(star(n)), 100_000, "vertices", 2e-5),
        "scan_convert: 20,000-vertex star": (lambda n: scan_convert(star(n), 256, 256), 20_000, "vertices", 1e-4),
        "fill_polygons: 20,000-vertex star": (lambda n: fill_polygons([star(n)], 256, 256), 20_000, "vertices", 1e-4),
        "fill_polygon: 20,000-vertex star": (lambda n: fill_polygon(star(n), 256, 256).image.shape, 20_000, "vertices", 1e-4),
        "area_coverage: 20,000-vertex star": (lambda n: area_coverage(star(n), 256, 256), 20_000, "vertices", 1e-4),
        "fill_polygons: 2,000 triangles": (lambda n: fill_polygons(list(_triangles(n)), 256, 256), 2_000, "polygons", 1e-3),
        "rasterize_triangles: 50,000 triangles": (lambda n: rasterize_triangles(_triangles(n), 256, 256), 50_000, "triangles", 2e-5),
        "midpoint_line: 1,000,000 pixels": (lambda n: midpoint_line(0, 0, n, n // 3), 1_000_000, "pixels", 2e-6),
        "scan_convert: 1024x1024": (lambda n: scan_convert(tri, n, n).mask.shape, 1024, "pixels per side", 1e-3),
        "render: 256x256": (lambda n: render(builtin_scene("painter"), n, n).image.shape, 256, "pixels per side", 4e-3),
        "load_scene: 20,000 triangles": (lambda n: load_scene(_soup_scene(n)), 20_000, "triangles", 2e-4),
        "load_scene: JSON nested 200,000 deep": (lambda n: _load_json_text("[" * n + "]" * n), 200_000, "brackets", 1e-5),
        "load_scene: a named pipe": (_load_fifo, 1, "pipe", 0.0),
        "load_obj: 200x200 grid mesh": (lambda n: load_obj(_obj_text(n)), 200, "vertices per side", 0.02),
        "Trace.from_json: 10,000 events": (lambda n: Trace.from_json(_trace_text(n)), 10_000, "events", 2e-4),
        "floating_horizon: 200x200 grid": (_surface("fha"), 200, "points per side", 0.02),
        "floating_perimeter: 100x100 grid": (_surface("fpa"), 100, "points per side", 0.02),
        "render fast_phong: 2,000 triangles": (_render_soup("zbuffer", "fast_phong"), 2_000, "triangles", 2e-3),
    }  # fmt: skip
    for visibility in ("zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock", "abuffer"):
        cases[f"render {visibility}: 300 triangles"] = (_render_soup(visibility), 300, "triangles", 1e-2)  # fmt: skip
    for visibility in ("depth_sort", "bsp"):  # splitting: answer or refuse by the budget, soon
        cases[f"render {visibility}: 2,000 triangles"] = (_render_soup(visibility), 2_000, "triangles", 1e-3)  # fmt: skip
    refused = {  # output alone over the memory limit: a clear error, at once
        f"{name}: {side}x{side} (over the limit)": (run, side, "pixels per side", 0.0, 3, True)
        for name, side, run in (
            ("scan_convert", 16384, lambda n: scan_convert(tri, n, n)),  # 1 byte per pixel
            ("fill_polygons", 8192, lambda n: fill_polygons([tri], n, n)),
            ("rasterize_triangles", 8192, lambda n: rasterize_triangles([tri], n, n)),
            ("area_coverage", 8192, lambda n: area_coverage(tri, n, n)),
            ("fill_polygon", 8192, lambda n: fill_polygon(tri, n, n)),
            ("render", 8192, lambda n: render(builtin_scene("painter"), n, n)),
        )
    }
    return {name: ScalingCase(*fields) for name, fields in {**cases, **refused}.items()}


def _status_bytes(field: str) -> int | None:
    """A VmRSS/VmHWM figure of this process in bytes (Linux), or None."""
    try:
        with open("/proc/self/status") as status:
            line = next(line for line in status if line.startswith(field + ":"))
    except (OSError, StopIteration):
        return None
    return int(line.split()[1]) * 1024


@contextlib.contextmanager
def peak_memory() -> Iterator[list[int | None]]:
    """``[bytes]``: how far the peak resident size rose over the block (None where unknown).

    Linux resets the peak (``VmHWM``) on a write of 5 to ``/proc/self/clear_refs``:
    the measure costs nothing while the block runs.
    """
    found: list[int | None] = [None]
    start = _status_bytes("VmRSS")
    try:
        with open("/proc/self/clear_refs", "w") as clear:
            clear.write("5")
    except OSError:
        start = None
    try:
        yield found
    finally:
        peak = _status_bytes("VmHWM")
        if start is not None and peak is not None:
            found[0] = max(peak - start, 0)


def check_scaling(args: dict):
    """Answer or a clear error within the case's time bound, the peak within the allowance.

    Returns "too slow: ..." or "over memory: ..." when a bound is passed (whatever
    the call did); else raises what the call raised, for the clear-error rule.
    """
    case = scaling_cases()[args["case"]]
    with memory_limit(SCALING_MEMORY):
        with contextlib.suppress(ValueError, TypeError, OSError):
            case.run(case.warm)  # compile the kernels, fill the caches: untimed
        error = None
        with peak_memory() as peak:
            start = time.perf_counter()
            try:
                case.run(case.size)
            except (ValueError, TypeError, OSError) as raised:
                error = raised
            seconds = time.perf_counter() - start
        allowance = MEMORY_ALLOWANCE * current_memory_limit() + 32 * 2**20
    size = f"{case.size:,} {case.unit}"
    if seconds > case.seconds:
        return f"too slow: {seconds:.2f} s for {size}, over the bound of {case.seconds:.2f} s"
    if peak[0] is not None and peak[0] > allowance:
        return f"over memory: the peak rose by {format_size(peak[0])} for {size}, over {format_size(allowance)}"  # fmt: skip
    if error is not None:
        raise error
    return "answered a request over the memory limit" if case.refuses else ""

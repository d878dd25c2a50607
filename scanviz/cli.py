"""Command line: ``python -m scanviz trace|fill|render|surface|bench|conformance|exercises|check|grade``.

Bad input exits with status 2 and exactly one line on stderr, never a
traceback: a ValueError, TypeError or OSError (a refused resource limit is a
ValueError) is the user's error, reported with newlines and other control
characters escaped as in a Python string literal and long echoed input
shortened (`one_line`); Python's and numpy's warnings wait until the command
ends and are dropped when it fails (the error says what went wrong), else
shown one line each. Ctrl-C prints
``interrupted`` (``bench: interrupted``, with where ``bench all`` wrote its
partial report) and exits with 130. Any other exception is a bug and shows
its traceback. Reference: ``docs/cli.md``, ``docs/benchmarks.md``.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np

from .bench import SUITES
from .geometry import Polygon
from .limits import check_memory

IMAGE_FORMATS = {".png": "png", ".jpg": "jpeg", ".jpeg": "jpeg", ".tif": "tiff", ".tiff": "tiff"}
"""Output file extensions (any case) and their formats: PNG by matplotlib, the rest by Pillow."""
_OUTPUT_HELP = f"image file to write: {', '.join(IMAGE_FORMATS)}"
# `render --visibility`: the opaque algorithms (names fixed by the issue), then the a-buffer's two.
VISIBILITY_NAMES = ("zbuffer", "painter", "depth_sort", "bsp", "scanline", "warnock", "abuffer", "flawed")  # fmt: skip
_EXPORT_BYTES_PER_PIXEL = 40  # float RGBA and 8-bit copies while matplotlib encodes the image
_SHOWN = 60  # longest argument quoted whole in a message
_ECHOED = 160  # longest echoed input a message keeps whole (a long path, say); else its start
MAX_LINE = 1000  # longest message line: echoed input is shortened first, lists are kept
# Echoed input in a message: a quoted string (not an apostrophe inside a word) or a run of
# non-blank characters, longer than _ECHOED.
_LONG_INPUT = re.compile(
    rf"(?<!\w)'[^']{{{_ECHOED + 1},}}'(?!\w)|(?<!\w)\"[^\"]{{{_ECHOED + 1},}}\"(?!\w)"
    rf"|[^\s'\"]{{{_ECHOED + 1},}}"
)


def escaped(text: str) -> str:
    """`text` on one line: control characters (newlines, tabs, ...) escaped as in a str literal.

    >>> escaped("a\\nb\\tc é")
    'a\\\\nb\\\\tc é'
    """
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def _shortened(match: re.Match) -> str:
    text = match.group()
    quote = text[0] if text[0] in "'\"" else ""
    inner = text[1:-1] if quote else text
    return f"{quote}{inner[:_SHOWN]}...{quote} ({len(inner):,} characters)"


def one_line(message: str) -> str:
    """`message` escaped onto one line, echoed input over 160 characters shortened, at most 1,000.

    >>> one_line("no such file: '" + "ab" * 2500 + "'")
    "no such file: 'abababababababababababababababababababababababababababababab...' (5,000 characters)"
    """
    line = _LONG_INPUT.sub(_shortened, escaped(message))
    if len(line) > MAX_LINE:
        line = f"{line[: MAX_LINE - 40]}... ({len(line):,} characters)"
    return line


def _shown(text: str) -> str:
    """`text` quoted for a message, shortened if long."""
    if len(text) <= _SHOWN:
        return repr(text)
    return f"{text[:_SHOWN]!r}... ({len(text):,} characters)"


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (the usage is what --help prints); a subcommand's parser
    takes ``run=function``, what `main` calls with the parsed arguments."""

    def __init__(self, *args, run=None, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        if run is not None:
            self.set_defaults(run=run)

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        parsed, extras = self.parse_known_args(args, namespace)
        if extras:  # argparse would list them whole, however long
            listed = " ".join(extras)
            if len(listed) > _ECHOED:
                count = f"{len(listed):,} characters in {len(extras)} arguments"
                listed = f"{listed[:_SHOWN]!r}... ({count})"
            self.error(f"unrecognized arguments: {listed}")
        return parsed

    def error(self, message: str):  # type: ignore[override]
        self.exit(2, f"{self.prog}: error: {one_line(message)} (see --help)\n")


# The type functions of the options raise ArgumentTypeError only, naming the rule (argparse
# would report another ValueError as "invalid <function name> value").


def _integer(text: str, minimum: int | None = None) -> int:
    """A decimal integer of at most 30 digits (ASCII), >= `minimum` if given."""
    rule = "an integer" if minimum is None else f"an integer >= {minimum}"
    digits = text.strip()
    digits = digits[1:] if digits[:1] in ("-", "+") else digits
    if not (digits.isascii() and digits.isdigit()) or len(digits) > 30:
        raise argparse.ArgumentTypeError(f"must be {rule} of at most 30 digits; got {_shown(text)}")
    value = int(text)
    if minimum is not None and value < minimum:
        raise argparse.ArgumentTypeError(f"must be >= {minimum}; got {value}")
    return value


def _at_least_zero(text: str) -> int:
    return _integer(text, 0)


def _at_least_one(text: str) -> int:
    return _integer(text, 1)


def _at_least_two(text: str) -> int:
    return _integer(text, 2)


def _counts(text: str, minimum: int = 1) -> tuple[int, ...]:
    """A comma-separated list of integers >= `minimum`."""
    parts = [part.strip() for part in text.split(",")]
    if not all(parts):
        raise argparse.ArgumentTypeError(
            f"must be integers >= {minimum} separated by commas; got {_shown(text)}"
        )
    return tuple(_integer(part, minimum) for part in parts)


def _sides(text: str) -> tuple[int, ...]:
    """A comma-separated list of integers >= 2 (grid points or pixels per side)."""
    return _counts(text, 2)


def _names(text: str) -> tuple[str, ...]:
    """A comma-separated list of names."""
    names = tuple(part.strip() for part in text.split(",") if part.strip())
    if not names:
        raise argparse.ArgumentTypeError("must name at least one")
    return names


def _seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value < math.inf:
        raise argparse.ArgumentTypeError(f"must be a number of seconds > 0; got {_shown(text)}")
    return value


def _image_format(path: str) -> str:
    """The image format `path`'s extension names; ValueError listing the supported ones."""
    if not path:
        raise ValueError("-o/--output must be a file name; got ''")
    suffix = Path(path).suffix.lower()
    if suffix not in IMAGE_FORMATS:
        raise ValueError(
            f"-o/--output {_shown(path)}: unsupported image file extension "
            f"{suffix or '(none)'!r}; supported: {', '.join(IMAGE_FORMATS)}"
        )
    return IMAGE_FORMATS[suffix]


def _save_image(path: str, image: np.ndarray, **style: object) -> None:
    """Write `image` (rows bottom-up, y up) to `path`, its format from the extension."""
    import matplotlib.pyplot as plt

    image_format = _image_format(path)
    height, width = image.shape[:2]
    check_memory(_EXPORT_BYTES_PER_PIXEL * width * height, f"a {width}x{height} image file")
    if image_format == "jpeg" and image.ndim == 3:
        image = image[..., :3]  # JPEG has no alpha channel
    with open(path, "wb") as file:
        plt.imsave(file, image[::-1], format=image_format, **style)  # files run top-down


def parse_vertices(text: str) -> Polygon:
    """Parse ``"x,y x,y ..."`` into a Polygon; ``;`` separates contours.

    >>> parse_vertices("0,0 4,0 0,4; 1,1 1,2 2,1").contour_count
    2
    """
    contours = []
    for c, part in enumerate(text.split(";")):
        points = []
        for token in part.split():
            try:
                x, y = (float(v) for v in token.split(","))
            except ValueError:
                raise ValueError(
                    f"--vertices: contour {c} point {_shown(token)} is not of the form x,y"
                ) from None
            points.append((x, y))
        contours.append(points)
    return Polygon(contours)


def _subpixel_bits(text: str) -> int | None:
    if text.strip().lower() == "none":
        return None
    try:
        value = _integer(text)
    except argparse.ArgumentTypeError:
        value = None
    if value is None or not 0 <= value <= 16:
        raise argparse.ArgumentTypeError(
            f"must be an integer in 0..16 or 'none'; got {_shown(text)}"
        )
    return value


def _default_size(polygon: Polygon) -> tuple[int, int]:
    _, _, xmax, ymax = polygon.bounds()
    return max(math.floor(xmax) + 2, 1), max(math.floor(ymax) + 2, 1)


def _add_scan_options(parser: argparse.ArgumentParser, least: int = 0) -> None:
    """The options of trace and fill; --width and --height must be >= `least` (0 or 1)."""
    size = _at_least_one if least else _at_least_zero
    parser.add_argument("--vertices", required=True, help='"x,y x,y ..."; ";" separates contours')
    parser.add_argument("--width", type=size, help=f"raster width, >= {least} (default: fits the polygon)")  # fmt: skip
    parser.add_argument("--height", type=size, help=f"raster height, >= {least} (default: fits the polygon)")  # fmt: skip
    parser.add_argument("--sample", default="corner", choices=["corner", "center"])
    parser.add_argument("--rule", default="nonzero", choices=["nonzero", "evenodd"])
    parser.add_argument("--subpixel-bits", type=_subpixel_bits, default=8, metavar="N|none")
    parser.add_argument("--arithmetic", default="exact", choices=["exact", "float32", "float64"])


def _scan_arguments(args: argparse.Namespace) -> tuple:
    """(polygon, width, height, options) of the scan commands' arguments."""
    polygon = parse_vertices(args.vertices)
    default_width, default_height = _default_size(polygon)
    width = default_width if args.width is None else args.width
    height = default_height if args.height is None else args.height
    options = {n: getattr(args, n) for n in ("sample", "rule", "subpixel_bits", "arithmetic")}
    return polygon, width, height, options


def _scan(args: argparse.Namespace, trace: bool):
    from .raster import scan_convert

    polygon, width, height, options = _scan_arguments(args)
    return scan_convert(polygon, width, height, trace=trace, **options)


def _cmd_trace(args: argparse.Namespace) -> None:
    from .trace.table import trace_table

    if args.gif is None:
        result = _scan(args, trace=True)
        print(result.trace.to_json() if args.json else trace_table(result.trace))
        return
    if Path(args.gif).suffix.lower() != ".gif":
        raise ValueError(f"--gif must name a .gif file; got {_shown(args.gif)}")
    from .widgets import scan_conversion_stepper

    polygon, width, height, options = _scan_arguments(args)
    stepper = scan_conversion_stepper(polygon, width, height, **options)
    written = stepper.save(args.gif)
    print(f"{written[0]}: {len(stepper.model)} steps, drawn as the stepper shows them")


def _cmd_fill(args: argparse.Namespace) -> None:
    _image_format(args.output)  # before the work
    result = _scan(args, trace=False)
    height, width = result.mask.shape
    check_memory(
        _EXPORT_BYTES_PER_PIXEL * width * height * args.scale**2,
        f"a {width * args.scale}x{height * args.scale} image (--scale {args.scale})",
    )
    image = np.kron(result.mask, np.ones((args.scale, args.scale), dtype=bool))
    _save_image(args.output, image, cmap="gray", vmin=0, vmax=1)
    print(f"{args.output}: {width}x{height}, {int(result.mask.sum())} samples covered")


_BENCH_OPTIONS = {
    "visibility": ("sizes", "width", "height", "repeat", "algorithms", "budget"),
    "surfaces": ("grids", "images", "repeat", "algorithms"),
    "shading": ("repeat",),
}
"""The options of the suites that take any: a suite gets those given of its own."""


_ALL_OPTIONS = ("report", "plot_dir")
"""The options of 'bench all' (and 'bench compare' takes two report files)."""


def _check_bench_options(args: argparse.Namespace) -> None:
    """Refuse an option of another suite (or of 'bench all') with one line naming its takers."""
    own = _BENCH_OPTIONS.get(args.suite, ())
    others = dict.fromkeys(n for names in _BENCH_OPTIONS.values() for n in names if n not in own)
    given = [name for name in others if getattr(args, name) is not None]
    if given:
        suites = [s for s, names in _BENCH_OPTIONS.items() if set(given) <= set(names)]
        takers = " or ".join(f"'bench {s}'" for s in suites) or "different bench suites"
        flags = ", ".join(f"--{name}" for name in given)
        raise ValueError(f"{flags}: options of {takers} only")
    given = [f"--{n.replace('_', '-')}" for n in _ALL_OPTIONS if getattr(args, n) is not None]
    if given and args.suite != "all":
        raise ValueError(f"{', '.join(given)}: options of 'bench all' only")
    if args.suite == "all" and args.plot is not None:
        raise ValueError("--plot: 'bench all' takes --plot-dir DIR (a plot per suite)")
    if (args.suite == "compare") != bool(args.reports) or len(args.reports) not in (0, 2):
        raise ValueError("'bench compare' takes two report files (A.md B.md); no other suite does")


def _cmd_bench(args: argparse.Namespace) -> int:
    from .bench import run

    _check_bench_options(args)
    if args.suite == "compare":
        from .bench.report import compare

        print(compare(*args.reports))
        return 0
    if args.suite == "all":
        return _bench_all(args)
    options = {n: getattr(args, n) for n in _BENCH_OPTIONS.get(args.suite, ()) if getattr(args, n) is not None}  # fmt: skip
    try:
        run(args.suite, quick=args.quick, plot=args.plot, **options)
    except KeyboardInterrupt:
        print("bench: interrupted", file=sys.stderr)
        return 130
    return 0


def _bench_all(args: argparse.Namespace) -> int:
    """Every suite into one report; 130 on Ctrl-C (the report of the finished suites is kept)."""
    from .bench.report import run_all

    report = args.report or "bench-report.md"
    command = "python -m scanviz bench all" + " --quick" * args.quick + f" --report {report}"
    if args.plot_dir is not None:
        command += f" --plot-dir {args.plot_dir}"
    try:
        runs = run_all(report, quick=args.quick, plot_dir=args.plot_dir, command=command)
    except KeyboardInterrupt:
        print(f"bench: interrupted (partial report written to {report})", file=sys.stderr)
        return 130
    failed = [r.suite for r in runs if r.status != "ok"]
    seconds = sum(r.seconds for r in runs)
    print(f"{report}: {len(runs)} suites in {seconds:.0f} s" + (f", failed: {', '.join(failed)}" if failed else ""))  # fmt: skip
    if failed:
        print(f"bench all: {len(failed)} suites failed (tracebacks in {report})", file=sys.stderr)
        return 1
    return 0


def _load(source: str, width: int, height: int):
    """The scene `source` names; an OBJ model is framed for a width x height raster."""
    from .io import frame_model, is_obj_path, load_obj, load_scene

    if is_obj_path(source):
        return frame_model(load_obj(source), aspect=width / height, name=Path(source).stem)
    return load_scene(source)


_RENDER_OPTIONS = ("shading", "visibility", "sample", "perspective_correct", "cull", "edges", "mask", "weights", "expansion")  # fmt: skip
"""The options of 'render' that are `scanviz.pipeline.render`'s keyword arguments of the same name."""


def _cmd_render(args: argparse.Namespace) -> None:
    from .pipeline import render

    if args.output is not None:
        _image_format(args.output)  # refuse a bad name before the work
    scene = _load(args.scene, args.width, args.height)
    options = {name: getattr(args, name) for name in _RENDER_OPTIONS}
    result = render(scene, args.width, args.height, **options)
    if args.plan:
        print(result.plan)
    if args.output is not None:
        _save_image(args.output, np.clip(result.image, 0.0, 1.0))
    s = result.stats
    print(
        f"{args.output or args.scene}: {args.width}x{args.height}, {s.polygons_in} polygons "
        f"({s.culled} culled, {s.off_screen} off-screen, {s.clipped} clipped), "
        f"{s.fragments} fragments, {s.depth_passed} depth tests passed, {s.depth_failed} failed"
    )


SURFACE_ALGORITHMS = ("fpa", "fha", "zbuffer")
PHASE_SURFACE = "three_poles"  # the complex built-in of §2.9


def _vector3(text: str) -> tuple[float, float, float]:
    """``"x,y,z"`` as three finite floats."""
    parts = text.split(",")
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"must be three finite numbers x,y,z; got {_shown(text)}")
    return values  # type: ignore[return-value]


def _load_surface(name: str, points: int | None):
    """A built-in grid surface by name (with `points` per side) or a Table 2-1 database file."""
    from .surfaces import BUILTIN_SURFACES, GridSurface

    if name in BUILTIN_SURFACES:
        return BUILTIN_SURFACES[name]() if points is None else BUILTIN_SURFACES[name](points)
    if points is not None:
        raise ValueError(
            f"--points applies to the built-in surfaces {sorted(BUILTIN_SURFACES)} only"
        )
    if not Path(name).is_file():
        raise ValueError(
            f"surface {_shown(name)} is neither a built-in ({', '.join(BUILTIN_SURFACES)}) "
            "nor a database file"
        )
    return GridSurface.from_database(name)


def _load_phase(args: argparse.Namespace):
    """`three_poles_two_zeros` for the surface name ``three_poles`` (None for any other)."""
    from .surfaces import three_poles_two_zeros

    if args.surface != PHASE_SURFACE:
        if args.marker is not None or args.ring_steps != 64:
            raise ValueError(f"--marker and --ring-steps apply to {PHASE_SURFACE} only")
        return None
    return three_poles_two_zeros() if args.points is None else three_poles_two_zeros(args.points)


def _default_view(surface, point, direction, parallel: bool):
    """The dissertation's (6, 8, 3) for [-2, 2]^2, scaled to the domain, looking at its centre."""
    from .surfaces import View

    size = max(surface.x[-1] - surface.x[0], surface.y[-1] - surface.y[0])
    centre = np.array([surface.x.mean(), surface.y.mean(), surface.z.mean()])
    if point is None:
        point = (centre[0] + 1.5 * size, centre[1] + 2.0 * size, surface.z.min() + 0.75 * size)
    if direction is None:
        direction = tuple((centre - np.array(point)).tolist())
    return View(point, direction, "parallel" if parallel else "perspective")


def _cmd_surface(args: argparse.Namespace) -> None:
    from .pipeline import render
    from .surfaces import floating_horizon, floating_perimeter

    if args.output is not None:
        _image_format(args.output)  # refuse a bad name before the work
    phase = _load_phase(args)  # the complex built-in, coloured by its phase; else None
    surface = phase.surface if phase is not None else _load_surface(args.surface, args.points)
    view = _default_view(surface, args.viewpoint, args.direction, args.parallel)
    w, h = args.width, args.height
    if args.antialias != "none" and args.algorithm != "fpa":
        raise ValueError(f"--antialias applies to --algorithm fpa only; got {args.algorithm}")
    if args.antialias != "none" and phase is not None:
        raise ValueError(f"--antialias does not apply to {PHASE_SURFACE} (coloured by phase)")
    scene = None
    if phase is not None:
        from .surfaces import phase_scene

        scene = phase_scene(phase, view, w, h, args.ring_steps, args.marker)
    if args.algorithm == "fha":
        result = floating_horizon(surface, view, w, h, family=args.family)
        image = result.image
        summary = f"{result.stats.curves} curves, {result.stats.segments} parts"
    elif args.antialias != "none":
        image, summary = _antialiased_surface(surface, view, w, h, args)
    elif args.algorithm == "fpa":
        result = floating_perimeter(
            surface, view, w, h, args.mode, shading=args.shading, scene=scene
        )
        s = result.stats
        image = result.image
        summary = (
            f"case {result.case}, {s.edges} edges, {s.visible} of {s.points} points visible"
            if args.mode == "lines"
            else f"case {result.case}, {s.facets} facets, {s.samples} samples painted front to back"
        )
    else:
        z = render(scene or surface.scene(view, w, h), w, h, shading=args.shading)
        image, summary = z.image, f"{z.stats.polygons_drawn} triangles, {z.stats.clipped} clipped"
    if args.output is not None:
        _save_image(args.output, np.clip(image, 0.0, 1.0))
    print(
        f"{args.output or args.surface}: {surface.nx}x{surface.ny} grid, {w}x{h}, "
        f"{args.algorithm}: {summary}"
    )


def _antialiased_surface(surface, view, w: int, h: int, args: argparse.Namespace):
    """Wang's ch. 5 on the FPA: DISLOP or post-AA lines, or a surface with a smoothed silhouette."""
    from .antialias.surfaces import antialiased_hidden_lines, smoothed_surface

    if args.mode == "lines":  # black lines on white, as the aliased drawing
        lines = antialiased_hidden_lines(
            surface, view, w, h, method=args.antialias, background=1.0, intensity=0.0
        )
        summary = f"{lines.stats.segments} segments, {lines.stats.pixels} pixels touched"
        return np.repeat(lines.image[..., None], 3, axis=-1), f"{args.antialias}: {summary}"
    smooth = smoothed_surface(
        surface, view, w, h, shading=args.shading, silhouettes=args.antialias,
        background=(1.0, 1.0, 1.0),
    )  # fmt: skip
    summary = f"{smooth.stats.pieces} outline pieces, {smooth.stats.boundary} pixels blended"
    return smooth.image, f"{args.antialias}: {summary}"


def _add_surface_command(commands) -> None:
    summary = "a grid surface by the FPA, the floating horizon or the z-buffer"
    add = commands.add_parser("surface", help=summary, run=_cmd_surface).add_argument
    add(
        "surface",
        help="gaussian, polynomial, rogers, random, a database file (Table 2-1), or "
        f"{PHASE_SURFACE}: |F| of three poles and two zeros, coloured by arg F through the colour ring",
    )
    add("-o", "--output", help=f"image file: {', '.join(IMAGE_FORMATS)}")
    add("--algorithm", choices=SURFACE_ALGORITHMS, default="fpa")
    add(
        "--mode",
        choices=("lines", "surface"),
        default="lines",
        help="fpa: hidden lines or surfaces",
    )
    add("--family", choices=("x", "y"), default="x", help="fha: which curves")
    add(
        "--antialias",
        choices=("dislop", "post", "none"),
        default="none",
        help="fpa (Wang ch. 5): lines by DISLOP_L or the line LUT; surface: the silhouette by area",
    )
    add("--shading", choices=("flat", "gouraud", "phong", "gooch"), default="phong")
    add("--points", type=_at_least_two, metavar="N", help="built-ins: points per side, >= 2")
    add("--viewpoint", type=_vector3, metavar="X,Y,Z", help="default: (6, 8, 3) scaled")
    add("--direction", type=_vector3, metavar="DX,DY,DZ", help="default: towards the centre")
    add("--parallel", action="store_true", help="parallel projection")
    add(
        "--ring-steps",
        type=_at_least_one,
        default=64,
        metavar="S",
        help=f"{PHASE_SURFACE}: a ring of 3 S colours (64)",
    )
    add(
        "--marker",
        type=_at_least_zero,
        metavar="K",
        help=f"{PHASE_SURFACE}: ring entry K (0 <= K < 3 S) shown white (the colour replacement)",
    )
    add("--width", type=_at_least_one, default=400, metavar="N")
    add("--height", type=_at_least_one, default=400, metavar="N")


def _cmd_conformance(args: argparse.Namespace) -> int:
    from .conformance import main as conformance_main  # imported only when asked for

    return conformance_main(fuzz=args.fuzz, seed=args.seed, scenes=args.scenes)


def _cmd_exercises_list(args: argparse.Namespace) -> None:
    from .exercises.catalog import exercises

    rows = [("no", "id", "stage", "kind", "points", "title")]
    rows += [
        (f"{e.number:02d}", e.id, e.stage, e.kind, str(e.points), e.title) for e in exercises()
    ]
    widths = [max(len(row[c]) for row in rows) for c in range(len(rows[0]) - 1)]
    for row in rows:
        print("  ".join([*(cell.ljust(w) for cell, w in zip(row, widths, strict=False)), row[-1]]))


def _cmd_exercises_release(args: argparse.Namespace) -> None:
    from .exercises.release import write_notebooks

    paths = write_notebooks(args.out_dir, with_solutions=args.with_solutions)
    for path in paths:
        print(path)
    what = (
        "solved notebooks (the teacher's copies: do not hand them out)"
        if args.with_solutions
        else "student notebooks"
    )
    print(f"{args.out_dir}: {len(paths)} {what}")


def _exercise_ids(text: str) -> list[str]:
    """A comma-separated list of exercise ids of the catalog."""
    from .exercises.catalog import get

    ids = [part.strip() for part in text.split(",") if part.strip()]
    if not ids:
        raise argparse.ArgumentTypeError("must name at least one exercise id")
    for exercise_id in ids:
        try:
            get(exercise_id)
        except ValueError as error:
            raise argparse.ArgumentTypeError(str(error)) from None
    return ids


def _cmd_exercises_key_new(args: argparse.Namespace) -> None:
    from .exercises.key import new_key, write_key

    key = new_key(args.exercises)
    write_key(key, args.key)
    total = sum(e.points for e in key.exercises.values())
    hidden = sum(e.hidden_cases for e in key.exercises.values())
    print(
        f"{args.key}: a new course key for {len(key.exercises)} exercises ({total} points, "
        f"{hidden} hidden cases), reveal = {key.reveal!r}; edit it to change them or the limits"
    )
    print("keep it private: the hidden cases are derived from its secret")


def _cmd_check(args: argparse.Namespace) -> None:
    from .exercises.grading import check_notebook

    student = check_notebook(args.notebook)
    if not student.grades:
        print(
            f"{args.notebook}: no answer cells (a code cell whose first line is "
            "'# scanviz: answer <exercise-id>')"
        )
        return
    for grade in student.grades:
        passed, total = grade.public_passed
        head = f"{grade.exercise} -- "
        if grade.verdicts:
            head += f"public cases {passed} of {total}"
        if grade.status not in ("passed", "failed"):
            head += f" -- {grade.status}" if grade.verdicts else grade.status
        print(head + (f": {escaped(grade.message)}" if grade.message else ""))
        for verdict in grade.verdicts:
            if not verdict.passed:
                print(verdict.describe())
    passed = sum(g.public_passed[0] for g in student.grades)
    total = sum(g.public_passed[1] for g in student.grades)
    answered = f"{len(student.grades)} exercise{'s' * (len(student.grades) != 1)}"
    print(
        f"{args.notebook}: {answered}, public cases {passed} of {total} "
        "-- hidden cases are graded later"
    )


def _shard(text: str) -> tuple[int, int]:
    """K/N: part K of N (1 <= K <= N)."""
    try:
        part, parts = (int(n) for n in text.split("/"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be K/N, e.g. 1/4; got {_shown(text)}") from None
    if not 1 <= part <= parts:
        raise argparse.ArgumentTypeError(f"must be K/N with 1 <= K <= N; got {_shown(text)}")
    return part, parts


def _cmd_grade(args: argparse.Namespace) -> None:
    if args.submissions[0] == "merge" and len(args.submissions) > 1:
        return _cmd_grade_merge(args)
    if len(args.submissions) != 1:
        raise ValueError("give one SUBMISSIONS_DIR (or: grade merge PART_DIR... -o OUT_DIR)")
    if args.key is None:
        raise ValueError("the following arguments are required: --key")
    from .exercises import report
    from .exercises.grading import grade_submissions
    from .exercises.key import load_key

    submissions = args.submissions[0]
    out_dir = report.output_folder(args.out_dir)
    if out_dir.resolve().is_relative_to(Path(submissions).resolve()):
        raise ValueError("-o/--output must be a folder outside SUBMISSIONS_DIR")
    key = load_key(args.key)
    grades = grade_submissions(
        submissions,
        args.key,
        jobs=args.jobs,
        exercises=args.exercises,
        progress=True,
        shard=args.shard,
        jail="none" if args.no_jail else args.jail,
    )
    report.write_reports(grades, key, out_dir)
    folders = report.folder_names(s.student for s in grades)
    rows = sum(len(s.grades) for s in grades)
    print(f"{out_dir / 'grades.csv'}: {rows} rows (one per student and exercise)")
    print(
        f"{out_dir}/STUDENT/feedback.html, feedback.md, results.json (Gradescope): "
        f"for each of {len(grades)} students"
    )
    for student, folder in zip(grades, folders, strict=True):
        if folder != student.student:
            print(f"  student {student.student!r}: folder {folder!r} (sanitized)")
    print(f"{out_dir / 'summary.txt'}, {out_dir / 'summary.html'}: the class summary")
    if args.shard is not None:
        print(f"part {args.shard[0]} of {args.shard[1]}: join the parts with `grade merge`")
    print(report.summary_line(report.grade_rows(grades)))


def _cmd_grade_merge(args: argparse.Namespace) -> None:
    from .exercises.report import merge_reports, output_folder, summary_line

    parts = args.submissions[1:]
    out_dir = output_folder(args.out_dir)
    rows = merge_reports(parts, out_dir)
    students = len({r.student for r in rows})
    print(f"{out_dir}: {len(parts)} parts joined, {students} students, {len(rows)} rows")
    print(summary_line(rows))


def _cmd_exercises_gradescope(args: argparse.Namespace) -> None:
    from .exercises.platforms import gradescope_zip

    names = gradescope_zip(args.zip, args.key)
    print(
        f"{args.zip}: a Gradescope autograder ({len(names)} files: setup.sh, run_autograder, "
        "key.toml and scanviz); upload it as the assignment's autograder"
    )


def _cmd_exercises_prairielearn(args: argparse.Namespace) -> None:
    from .exercises.platforms import prairielearn_tests

    for path in prairielearn_tests(args.out_dir, args.key):
        print(path)
    print(f"{args.out_dir}: the question's tests/ files for PrairieLearn (see README.txt)")


def _cmd_exercises_autograde(args: argparse.Namespace) -> None:
    from .exercises.platforms import autograde

    results = autograde(args.submission, args.key, args.platform, args.out, jail=args.jail)
    print(f"{args.out}: {args.platform} results, score {results.get('score', 0):g}")


def _add_exercise_commands(commands) -> None:
    """The teacher's commands (exercises ...) and the grading ones (check, grade)."""
    exercises = commands.add_parser(
        "exercises", help="the exercise catalog: list it, release notebooks, make a course key"
    )
    what = exercises.add_subparsers(
        dest="exercises_command",
        required=True,
        metavar="list|release|key|gradescope|prairielearn|autograde",
    )
    summary = "number, id, stage, kind, points and title of each"
    what.add_parser("list", help=summary, run=_cmd_exercises_list)
    summary = "write the student notebooks into OUT_DIR"
    release = what.add_parser("release", help=summary, run=_cmd_exercises_release)
    release.add_argument("out_dir", metavar="OUT_DIR")
    release.add_argument(
        "--with-solutions", action="store_true", help="the teacher's solved copies instead"
    )
    _add_key_commands(what)
    _add_platform_commands(what)
    _add_grading_commands(commands)


def _add_key_commands(what) -> None:
    """exercises key new: a course key with a fresh secret."""
    key = what.add_parser("key", help="course keys: key new KEY.toml").add_subparsers(
        dest="key_command", required=True, metavar="new"
    )
    summary = "write a course key with a fresh random secret"
    new = key.add_parser("new", help=summary, run=_cmd_exercises_key_new)
    new.add_argument("key", metavar="KEY.toml", help="the file to write (never overwritten)")
    _add_exercises_option(new, "the assignment's exercises (default: all of them)")


def _add_exercises_option(parser: argparse.ArgumentParser, which: str) -> None:
    parser.add_argument("--exercises", type=_exercise_ids, metavar="ID,ID,...", help=which)


def _add_key_option(parser: argparse.ArgumentParser, required: bool = True) -> None:
    parser.add_argument("--key", required=required, metavar="KEY.toml", help="the course key")


def _add_platform_commands(what) -> None:
    """exercises gradescope|prairielearn|autograde: a course key on a grading platform."""
    summary = "build a Gradescope autograder zip for a course key"
    gradescope = what.add_parser("gradescope", help=summary, run=_cmd_exercises_gradescope)
    gradescope.add_argument("zip", metavar="AUTOGRADER.zip")
    _add_key_option(gradescope)
    summary = "write the tests/ files of PrairieLearn's external grader"
    prairielearn = what.add_parser("prairielearn", help=summary, run=_cmd_exercises_prairielearn)
    prairielearn.add_argument("out_dir", metavar="OUT_DIR")
    _add_key_option(prairielearn)
    summary = "grade one submission into a platform's results.json (the entrypoint)"
    autograde = what.add_parser("autograde", help=summary, run=_cmd_exercises_autograde)
    autograde.add_argument("submission", metavar="SUBMISSION", help="a notebook or a folder")
    _add_key_option(autograde)
    autograde.add_argument("--platform", required=True, choices=["gradescope", "prairielearn"])
    autograde.add_argument("-o", "--output", dest="out", required=True, metavar="RESULTS.json")
    autograde.add_argument("--jail", default="auto", choices=["auto", "bwrap", "user", "none"])


def _add_grading_commands(commands) -> None:
    """check (a student's notebook) and grade (a class's folder)."""
    summary = "a student's check: the public cases of a notebook's answers"
    check = commands.add_parser("check", help=summary, run=_cmd_check)
    check.add_argument("notebook", metavar="NOTEBOOK")
    summary = "grade a folder of notebooks (one per student); grade merge PART_DIR...: join shards"
    grade = commands.add_parser("grade", help=summary, run=_cmd_grade)
    add = grade.add_argument
    add(
        "submissions",
        nargs="+",
        metavar="SUBMISSIONS_DIR",
        help="the class's folder; or: merge PART_DIR... (folders graded with --shard)",
    )
    _add_key_option(grade, required=False)
    add("-o", "--output", dest="out_dir", required=True, metavar="OUT_DIR")
    add("--jobs", type=_at_least_one, default=1, metavar="N", help="submissions graded at once")
    _add_exercises_option(
        grade, "grade only these exercises of the key (default: all of the key's)"
    )
    add("--shard", type=_shard, metavar="K/N", help="grade part K of N of the students (by id)")
    add(
        "--jail",
        default="bwrap",
        choices=["bwrap", "user", "auto"],
        help="where answers run: bubblewrap (default), the user nobody (root only), "
        "auto: the first that starts",
    )
    add(
        "--no-jail",
        action="store_true",
        help="run answers without a jail: only for submissions you trust",
    )


def _add_render_command(commands) -> None:
    summary = "render a scene (JSON file, OBJ model or builtin:NAME) to an image"
    add = commands.add_parser("render", help=summary, run=_cmd_render).add_argument
    add("scene", help="SCENE.json, MODEL.obj (framed automatically) or builtin:NAME")
    add("-o", "--output", help=_OUTPUT_HELP)
    add("--width", type=_at_least_one, default=512, help="pixels, >= 1")
    add("--height", type=_at_least_one, default=512, help="pixels, >= 1")
    add("--shading", default="phong", choices=["flat", "gouraud", "phong", "gooch", "fast_phong"])
    add("--visibility", default="zbuffer", choices=VISIBILITY_NAMES)
    add("--edges", action="store_true", help="draw feature edges")
    add("--mask", default="8x8", choices=["4x4", "8x4", "8x8"], help="a-buffer")
    add("--weights", default="area", choices=["area", "mask"], help="a-buffer")
    add(
        "--expansion",
        default="vertex",
        choices=["vertex", "centroid"],
        help="fast_phong: the Taylor expansion point of each triangle",
    )
    add(
        "--perspective-correct",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="interpolate with 1/w (default) or affinely in screen space",
    )
    add(
        "--affine",
        dest="perspective_correct",
        action="store_false",
        help="= --no-perspective-correct",
    )
    add(
        "--cull",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="cull back faces (default: the scene's own, closed meshes only)",
    )
    add("--sample", default="corner", choices=["corner", "center"])
    add("--plan", action="store_true", help="print which stages run and why")


def _add_bench_command(commands) -> None:
    """bench: the suite, 'bench all' and 'bench compare' options, then the suites' own."""
    summary = "benchmarks: run time against peers and error"
    add = commands.add_parser("bench", help=summary, run=_cmd_bench).add_argument
    add(
        "suite",
        choices=(*SUITES, "all", "compare"),
        help="a suite; all: every suite into one report; compare A.md B.md: two reports' times",
    )
    add("reports", nargs="*", metavar="REPORT.md", help="compare: the two reports")
    add("--quick", action="store_true", help="smaller scenes, for a smoke test")
    add(
        "--plot",
        metavar="PATH",
        help="coverage: error-vs-time plot file (default coverage.png); "
        "visibility: time-vs-polygons, surfaces: time-vs-grid and -image, "
        "antialias: error-vs-time, scaling: time-vs-triangles and -pixels plot file "
        "(default: none)",
    )
    add("--report", metavar="PATH.md", help="all: the Markdown report (default bench-report.md)")
    add("--plot-dir", metavar="DIR", help="all: save each suite's plot as DIR/SUITE.png")
    add("--sizes", type=_counts, metavar="N,N,...", help="visibility: random triangles per scene")
    count = {"type": _at_least_one, "metavar": "N"}
    add("--width", **count, help="visibility: raster width (256)")
    add("--height", **count, help="visibility: raster height (256)")
    add("--repeat", **count, help="visibility, surfaces, shading: runs per scene (3)")
    add(
        "--algorithms",
        type=_names,
        metavar="NAME,NAME,...",
        help="visibility: which algorithms besides the z-buffer (default: all); "
        "surfaces: which of fha, fpa-lines, fpa-flat, fpa-phong, zbuf-flat, zbuf-phong",
    )
    add("--budget", type=_seconds, metavar="SECONDS", help="visibility: time per algorithm (30)")
    add("--grids", type=_sides, metavar="N,N,...", help="surfaces: grid points per side (10..200)")
    add("--images", type=_sides, metavar="N,N,...", help="surfaces: image sides (100..600)")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="python -m scanviz", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    summary = "print the ET/AET/spans table of a polygon (or --json)"
    trace = commands.add_parser("trace", help=summary, run=_cmd_trace)
    _add_scan_options(trace)
    trace.add_argument("--json", action="store_true", help='print {"events": [...]} instead')
    trace.add_argument(
        "--gif", metavar="OUT.gif", help="save the steps as an animated GIF (as the stepper shows)"
    )
    fill = commands.add_parser("fill", help="scan-convert a polygon into a PNG", run=_cmd_fill)
    _add_scan_options(fill, least=1)  # an image file has at least one pixel
    fill.add_argument("-o", "--output", required=True, help=_OUTPUT_HELP)
    fill.add_argument(
        "--scale", type=_at_least_one, default=1, help="magnify each pixel to N x N in the image"
    )
    _add_render_command(commands)
    _add_surface_command(commands)
    _add_bench_command(commands)
    summary = "the stress suite: PASS/FAIL per category"
    conformance = commands.add_parser("conformance", help=summary, run=_cmd_conformance)
    conformance.add_argument(
        "--fuzz", type=_at_least_zero, default=0, metavar="N", help="N more fuzz inputs (>= 0)"
    )
    conformance.add_argument(
        "--seed", type=_at_least_zero, default=0, metavar="S", help="fuzz seed (>= 0)"
    )
    conformance.add_argument(
        "--scenes", type=_at_least_one, default=None, metavar="N",
        help="random scenes of 'visibility agrees with the z-buffer' (default 64)",
    )  # fmt: skip
    summary = "compile every numba kernel now (make lab and make test do it once)"
    commands.add_parser("warmup", help=summary, run=_cmd_warmup)
    _add_exercise_commands(commands)
    return parser


def _cmd_warmup(args: argparse.Namespace) -> int:
    from .warmup import warmup

    print(f"scanviz warmup: kernels ready in {warmup():.0f} s")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Run the command line on `argv` (default ``sys.argv[1:]``); return the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as stop:  # --help (0) or a one-line usage error (2)
        return stop.code if isinstance(stop.code, int) else 2
    command = f"{parser.prog} {args.command}"
    with warnings.catch_warnings(record=True) as caught:  # shown once the command has succeeded
        warnings.simplefilter("default")
        try:
            status = args.run(args)
        except KeyboardInterrupt:
            print("interrupted", file=sys.stderr)
            return 130
        except BrokenPipeError:  # the reader went away (`... | head`): stop quietly, as cat does
            sys.stdout = open(os.devnull, "w")  # noqa: SIM115 - so the interpreter's final flush is silent
            return 141
        except (ValueError, TypeError, OSError) as error:
            print(f"{command}: error: {one_line(str(error))}", file=sys.stderr)
            return 2
    for warning in caught:
        print(f"{command}: warning: {one_line(str(warning.message))}", file=sys.stderr)
    return status if isinstance(status, int) else 0

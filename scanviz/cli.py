"""Command line: ``python -m scanviz trace|fill|bench ...``.

Bad input exits with status 2 and a one-line message, never a traceback.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from .geometry import Polygon


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
                    f"--vertices: contour {c} point {token!r} is not of the form x,y"
                ) from None
            points.append((x, y))
        contours.append(points)
    return Polygon(contours)


def _subpixel_bits(text: str) -> int | None:
    if text.lower() == "none":
        return None
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be an int in 0..16 or 'none'; got {text!r}"
        ) from None


def _default_size(polygon: Polygon) -> tuple[int, int]:
    _, _, xmax, ymax = polygon.bounds()
    return max(math.floor(xmax) + 2, 1), max(math.floor(ymax) + 2, 1)


def _add_scan_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--vertices", required=True, help='"x,y x,y ..."; ";" separates contours')
    parser.add_argument("--width", type=int, help="raster width (default: fits the polygon)")
    parser.add_argument("--height", type=int, help="raster height (default: fits the polygon)")
    parser.add_argument("--sample", default="corner", choices=["corner", "center"])
    parser.add_argument("--rule", default="nonzero", choices=["nonzero", "evenodd"])
    parser.add_argument("--subpixel-bits", type=_subpixel_bits, default=8, metavar="N|none")
    parser.add_argument("--arithmetic", default="exact", choices=["exact", "float32", "float64"])


def _scan(args: argparse.Namespace, trace: bool):
    from .raster import scan_convert

    polygon = parse_vertices(args.vertices)
    default_width, default_height = _default_size(polygon)
    return scan_convert(
        polygon,
        default_width if args.width is None else args.width,
        default_height if args.height is None else args.height,
        sample=args.sample,
        rule=args.rule,
        subpixel_bits=args.subpixel_bits,
        arithmetic=args.arithmetic,
        trace=trace,
    )


def _cmd_trace(args: argparse.Namespace) -> None:
    from .trace.table import trace_table

    result = _scan(args, trace=True)
    print(result.trace.to_json() if args.json else trace_table(result.trace))


def _cmd_fill(args: argparse.Namespace) -> None:
    import matplotlib.pyplot as plt

    if args.scale < 1:
        raise ValueError(f"--scale must be >= 1; got {args.scale}")
    result = _scan(args, trace=False)
    image = np.kron(
        result.mask[::-1], np.ones((args.scale, args.scale), dtype=bool)
    )  # PNG rows top-down
    plt.imsave(args.output, image, cmap="gray", vmin=0, vmax=1)
    print(
        f"{args.output}: {result.mask.shape[1]}x{result.mask.shape[0]}, {int(result.mask.sum())} samples covered"
    )


def _cmd_bench(args: argparse.Namespace) -> None:
    from .bench import run

    run(args.suite, quick=args.quick, plot=args.plot)


def _cmd_render(args: argparse.Namespace) -> None:
    import matplotlib.pyplot as plt

    from .io import load_scene
    from .pipeline import render

    scene = load_scene(args.scene)
    result = render(scene, args.width, args.height, shading=args.shading, sample=args.sample)
    if args.plan:
        print(result.plan)
    if args.output:
        plt.imsave(args.output, result.image[::-1])  # PNG rows run top-down
    s = result.stats
    print(
        f"{args.output or args.scene}: {args.width}x{args.height}, {s.polygons_in} polygons "
        f"({s.culled} culled, {s.off_screen} off-screen, {s.clipped} clipped), "
        f"{s.fragments} fragments, {s.depth_passed} depth tests passed, {s.depth_failed} failed"
    )


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="python -m scanviz", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True)
    trace = commands.add_parser(
        "trace", help="print the ET/AET/spans table of a polygon (or --json)"
    )
    _add_scan_options(trace)
    trace.add_argument("--json", action="store_true", help='print {"events": [...]} instead')
    trace.set_defaults(run=_cmd_trace)
    fill = commands.add_parser("fill", help="scan-convert a polygon into a PNG")
    _add_scan_options(fill)
    fill.add_argument("-o", "--output", required=True, help="PNG file to write")
    fill.add_argument("--scale", type=int, default=1, help="magnify each pixel to N x N in the PNG")
    fill.set_defaults(run=_cmd_fill)
    render = commands.add_parser("render", help="render a scene (JSON file or builtin:NAME) to PNG")
    render.add_argument("scene", help="SCENE.json or builtin:NAME")
    render.add_argument("-o", "--output", help="PNG file to write")
    render.add_argument("--width", type=int, default=512)
    render.add_argument("--height", type=int, default=512)
    render.add_argument("--shading", default="phong", choices=["flat", "gouraud", "phong", "gooch"])
    render.add_argument("--sample", default="corner", choices=["corner", "center"])
    render.add_argument("--plan", action="store_true", help="print which stages run and why")
    render.set_defaults(run=_cmd_render)
    bench = commands.add_parser("bench", help="benchmarks: run time against peers and error")
    bench.add_argument("suite", choices=["raster", "render", "coverage"])
    bench.add_argument("--quick", action="store_true", help="smaller scenes, for a smoke test")
    bench.add_argument(
        "--plot", default="coverage.png", metavar="PATH", help="coverage: error-vs-time plot file"
    )
    bench.set_defaults(run=_cmd_bench)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        args.run(args)
    except (ValueError, TypeError, OSError) as error:
        print(f"{parser.prog} {args.command}: error: {error}", file=sys.stderr)
        return 2
    return 0

"""One benchmark report: every suite's table, the machine and the peers, in one Markdown file.

``python -m scanviz bench all --report PATH.md`` runs each suite of
`scanviz.bench.SUITES` in turn. A suite's printed table is captured (and
still printed: its output goes to a tee) into a fenced block under its own
heading; the rows its ``run_*`` returns go, as JSON, into the last section,
so that two reports can be compared by a program (`read_rows`, ``bench
compare``). The header names the machine (CPU, cores, RAM, OS), the versions
of Python, numpy and numba, the peers found (OpenCV, moderngl with Mesa's
renderer string, skia-python, cairo) and the date.

The report is rewritten after every suite, so a run that is interrupted
(Ctrl-C) or killed leaves the report of the suites finished so far; the
suite interrupted is reported with its output up to then. A suite that
raises is reported with its traceback and the run goes on.
"""

from __future__ import annotations

import contextlib
import dataclasses
import datetime
import io
import json
import os
import platform
import re
import subprocess
import sys
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..limits import read_bounded
from ..progress import progress
from . import PLOTTING, SUITES, suite_function

ROWS_HEADING = "## Rows (JSON)"


@dataclass
class SuiteRun:
    """One suite's run: what it printed, the rows it returned, how long, and how it ended.

    status : "ok", "failed" (`error` holds the traceback) or "interrupted"
    """

    suite: str
    output: str
    rows: object = None
    seconds: float = 0.0
    status: str = "ok"
    error: str = ""


class _Tee(io.TextIOBase):
    """A text stream writing to `stream` and keeping a copy."""

    def __init__(self, stream) -> None:
        self.stream = stream
        self.copy = io.StringIO()

    def write(self, text: str) -> int:
        self.stream.write(text)
        self.copy.write(text)
        return len(text)

    def flush(self) -> None:
        self.stream.flush()


def _first(path: str, pattern: str) -> str | None:
    """The first group of `pattern` in the file at `path`, or None."""
    try:
        text = Path(path).read_text()
    except OSError:
        return None
    match = re.search(pattern, text, re.MULTILINE)
    return match.group(1).strip() if match else None


def _version(module: str, attribute: str = "__version__") -> str | None:
    try:
        return str(getattr(__import__(module), attribute))
    except Exception:  # not installed, or broken: either way not a peer here
        return None


def _mesa() -> str | None:
    """moderngl's version and the renderer string of its EGL context (Mesa llvmpipe), or None."""
    version = _version("moderngl")
    if version is None:
        return None
    try:
        import moderngl

        context = moderngl.create_standalone_context(backend="egl")
        renderer = context.info["GL_RENDERER"]
        context.release()
    except Exception as error:  # no EGL, no driver
        renderer = f"no EGL context ({type(error).__name__})"
    return f"{version} ({renderer})"


def _commit() -> str | None:
    """The scanviz checkout's commit, with "+ changes" if its tree differs, or None."""
    root = Path(__file__).resolve().parents[2]
    try:
        head = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
            capture_output=True, text=True, timeout=10, check=True,
        ).stdout.strip()  # fmt: skip
        dirty = subprocess.run(
            ["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
            capture_output=True, text=True, timeout=10, check=True,
        ).stdout.strip()  # fmt: skip
    except (OSError, subprocess.SubprocessError):
        return None
    return head + (" + changes" if dirty else "")


def machine() -> dict:
    """The machine, the versions and the peers found, and the date (UTC), for a report's header."""
    import numba

    from .. import __version__

    memory = _first("/proc/meminfo", r"^MemTotal:\s*(\d+)")
    cores = os.cpu_count()
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else cores
    return {
        "date": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        "cpu": _first("/proc/cpuinfo", r"^model name\s*:(.*)$") or platform.processor() or "?",
        "cores": cores,
        "usable cores": usable,
        "ram": f"{int(memory) / 2**20:.1f} GiB" if memory else "?",
        "os": platform.platform(),
        "python": f"{platform.python_implementation()} {platform.python_version()}",
        "numpy": np.__version__,
        "numba": f"{numba.__version__} ({numba.get_num_threads()} threads)",
        "scanviz": f"{__version__}" + (f" ({commit})" if (commit := _commit()) else ""),
        "peers": {
            "OpenCV": _version("cv2"),
            "moderngl": _mesa(),
            "skia-python": _version("skia"),
            "cairo": _version("cairo", "version") or _version("cairocffi"),
        },
    }


def _jsonable(value: object) -> object:
    """`json.dumps`'s fallback: numpy values and arrays, dataclasses, sets."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return dataclasses.asdict(value)
    if isinstance(value, set | frozenset):
        return sorted(value, key=repr)
    return repr(value)


def markdown(info: dict, runs: list[SuiteRun], *, command: str, quick: bool) -> str:
    """The report: the header, each suite's output in a fenced block, then the rows as JSON."""
    peers = ", ".join(f"{name} {v}" if v else f"{name}: not found" for name, v in info["peers"].items())  # fmt: skip
    lines = [
        "# scanviz benchmark report",
        "",
        f"- date: {info['date']}",
        f"- command: `{command}`"
        + (" (quick mode: smoke-test sizes, not for comparison)" if quick else ""),  # fmt: skip
        f"- machine: {info['cpu']}, {info['cores']} cores ({info['usable cores']} usable), "
        f"{info['ram']} RAM",
        f"- OS: {info['os']}",
        f"- Python {info['python']}, numpy {info['numpy']}, numba {info['numba']}, "
        f"scanviz {info['scanviz']}",
        f"- peers: {peers}",
        "",
    ]
    left = [s for s in SUITES if s not in {r.suite for r in runs}]
    if left:
        lines += [f"Not run (the run was stopped first): {', '.join(left)}.", ""]
    for run in runs:
        lines += [f"## {run.suite}", "", f"{run.status}, {run.seconds:.1f} s", "", "```text"]
        lines += [run.output.rstrip("\n"), "```", ""]
        if run.error:
            lines += ["```text", run.error.rstrip("\n"), "```", ""]
    rows = {
        "machine": info,
        "quick": quick,
        "suites": {
            r.suite: {"status": r.status, "seconds": r.seconds, "rows": r.rows} for r in runs
        },
    }
    lines += [ROWS_HEADING, "", "```json", json.dumps(rows, indent=1, default=_jsonable), "```", ""]
    return "\n".join(lines)


def read_rows(path: str | os.PathLike) -> dict:
    """The JSON section of a report written by `run_all`: machine, quick, suites."""
    text = read_bounded(path)  # a regular file within the file limit: /dev/zero is refused
    _, found, rest = text.partition(ROWS_HEADING + "\n\n```json\n")
    if not found:
        raise ValueError(f"{str(path)!r} is not a scanviz bench report (no {ROWS_HEADING!r})")
    return json.loads(rest.rsplit("\n```", 1)[0])


def run_all(
    report: str | os.PathLike,
    *,
    quick: bool = False,
    plot_dir: str | os.PathLike | None = None,
    suites: tuple[str, ...] = SUITES,
    command: str = "python -m scanviz bench all",
) -> list[SuiteRun]:
    """Run `suites` one after another, rewriting the report at `report` after each.

    A suite of `PLOTTING` saves its plot as ``<plot_dir>/<suite>.png`` when
    `plot_dir` is given (no plot otherwise). Ctrl-C (KeyboardInterrupt) stops
    the run after the report of the suites finished so far (and of the one
    interrupted) is written, and is raised again.
    """
    info = machine()
    runs: list[SuiteRun] = []
    if plot_dir is not None:
        Path(plot_dir).mkdir(parents=True, exist_ok=True)

    def write() -> None:
        Path(report).write_text(
            markdown(info, runs, command=command, quick=quick), encoding="utf-8"
        )

    write()  # the path is writable before the first suite runs
    with progress(len(suites), "bench all", enabled=True) as bar:
        for suite in suites:
            options = {}
            if suite in PLOTTING:
                options["plot"] = None if plot_dir is None else str(Path(plot_dir) / f"{suite}.png")
            tee = _Tee(sys.stdout)
            started = time.perf_counter()
            run = SuiteRun(suite, "")
            try:
                with contextlib.redirect_stdout(tee):
                    run.rows = suite_function(suite)(quick=quick, **options)
            except KeyboardInterrupt:
                run.status = "interrupted"
                raise
            except Exception:  # a broken suite is reported, the others still run
                run.status, run.error = "failed", traceback.format_exc()
            finally:
                run.output, run.seconds = tee.copy.getvalue(), time.perf_counter() - started
                runs.append(run)
                write()
            bar.update()
    return runs


def compare(a: str | os.PathLike, b: str | os.PathLike) -> str:
    """A table of the time fields of every row two reports share: A, B and B / A.

    Rows are matched by suite and by their text fields (scene, method, ...)
    plus their integer sizes; a time field is one named ``ms``, ``*_ms`` or
    ``seconds``.
    """
    first, second = read_rows(a), read_rows(b)
    lines = [f"A = {a} ({first['machine']['date']}), B = {b} ({second['machine']['date']})"]
    lines.append(f"{'suite':<11}{'row':<52}{'field':<12}{'A':>11}{'B':>11}{'B/A':>8}")
    for suite, entry in first["suites"].items():
        theirs = second["suites"].get(suite)
        if theirs is None:
            continue
        matched = {_row_key(r): r for r in _rows_of(theirs["rows"])}
        for row in _rows_of(entry["rows"]):
            other = matched.get(_row_key(row))
            if other is None:
                continue
            for field in (f for f in row if f == "seconds" or f == "ms" or f.endswith("_ms")):
                x, y = row[field], other.get(field)
                if isinstance(x, int | float) and isinstance(y, int | float) and x > 0:
                    label = " ".join(str(v) for v in _row_key(row))[:51]
                    lines.append(f"{suite:<11}{label:<52}{field:<12}{x:>11.3f}{y:>11.3f}{y / x:>8.2f}")  # fmt: skip
    return "\n".join(lines)


def _rows_of(rows: object) -> list[dict]:
    """The dict rows of a suite's result (a list of rows, or a dataclass of lists of rows)."""
    if isinstance(rows, list):
        return [r for r in rows if isinstance(r, dict)]
    if isinstance(rows, dict):
        return [r for value in rows.values() for r in _rows_of(value)]
    return []


def _row_key(row: dict) -> tuple:
    return tuple(
        v for k, v in row.items() if isinstance(v, str) or (isinstance(v, int) and k != "runs")
    )

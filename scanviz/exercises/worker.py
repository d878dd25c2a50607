"""The process that runs one submission's answer cells: ``python -m scanviz.exercises.worker ROOT``.

Started by `scanviz.exercises.sandbox.run_submission`, one per submission,
with its working directory a fresh copy of the submission's folder
(``ROOT/work``). It reads ``ROOT/request.json`` (the setup and answer
sources and each case's *inputs* as plain JSON; never the key, a secret or
an expected result) and deletes it, limits itself (`resource`: CPU time,
address space, file size), and then, per exercise, runs the setup and
answer cells in a fresh namespace and `core.run_case` on every case.

It talks to the grader over a private copy of its original stdout, one JSON
line per message (``{"ready"}``, ``{"start": id}``, ``{"done": id, "status",
"message", "outcomes"}``, ``{"restart"}``); while student code runs, fds 1
and 2 go to capture files in ``ROOT/capture``, so nothing a student prints
can corrupt the channel. Statuses are keys of `results.STATUSES`; here
``"passed"`` only means that every case ran -- the grader judges.
"""

from __future__ import annotations

import ast
import builtins
import contextlib
import difflib
import json
import math
import os
import posix
import resource
import signal
import site
import sys
import traceback
from pathlib import Path

import scanviz

from .catalog import get
from .core import Case, Exercise, Outcome, run_case
from .plain import Opaque, from_plain

OUTPUT_FILE_LIMIT = 64 * 2**20  # bytes a submission may write to one file (prints included)
ALWAYS_BANNED = ("scanviz.steps", "scanviz.exercises")  # the step table and the solutions
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_APPEND | os.O_CREAT | os.O_TRUNC
_REFUSED_EVENTS = {
    "os.system": "runs a shell command",
    "os.exec": "replaces the process",
    "os.posix_spawn": "starts a process",
    "os.spawn": "starts a process",
    "os.fork": "forks the process",
    "os.forkpty": "forks the process",
    "subprocess.Popen": "starts a process",
    "pty.spawn": "starts a process",
    "os.kill": "sends a signal",
    "os.killpg": "sends a signal",
    "signal.pthread_kill": "sends a signal",
    "resource.setrlimit": "changes the resource limits",
    "resource.prlimit": "changes the resource limits",
    "socket.connect": "opens a network connection",
    "socket.bind": "opens a network socket",
    "socket.sendto": "sends over the network",
}
_PATH_EVENTS = {  # audited events that change the file system: which arguments are paths
    "os.remove": (0,),
    "os.rmdir": (0,),
    "os.mkdir": (0,),
    "os.rename": (0, 1),
    "os.chmod": (0,),
    "os.chown": (0,),
    "os.link": (1,),
    "os.symlink": (1,),
    "os.truncate": (0,),
    "os.utime": (0,),
    "shutil.rmtree": (0,),
}


class Timeout(BaseException):
    """Raised inside student code when an exercise's wall-clock or CPU time is up."""


class NotAllowed(BaseException):
    """Raised inside student code that does what an answer may not do (see `Guard`)."""


# --- what the answer cell may not name --------------------------------------------------------


def banned_use(source: str, banned: tuple[str, ...]) -> str | None:
    """Where `source` names a banned module or function, as a message; None if it does not.

    `banned` holds dotted module paths (``"scanviz.raster.scanline"``: no
    import of it, no attribute chain through it) and function names
    (``"span_rule"``: not imported from scanviz, not taken as an attribute);
    the step table and the exercise catalog are always banned.

    >>> banned_use("from scanviz.raster.scanline import span_rule", ("span_rule",))
    "line 1 imports 'scanviz.raster.scanline.span_rule'"
    >>> banned_use("def span_rule(crossings, rule):\\n    return []", ("span_rule",)) is None
    True
    """
    modules = tuple(b for b in banned if "." in b) + ALWAYS_BANNED
    names = {b for b in banned if "." not in b} | {b.rsplit(".", 1)[1] for b in banned if "." in b}

    def is_banned(dotted: str) -> bool:
        return any(dotted == m or dotted.startswith(m + ".") for m in modules)

    for node in ast.walk(ast.parse(source)):
        used = None
        if isinstance(node, ast.Import):
            used = next((a.name for a in node.names if is_banned(a.name)), None)
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            full = [f"{node.module}.{a.name}" for a in node.names]
            used = next(
                (
                    f
                    for f, a in zip(full, node.names, strict=True)
                    if is_banned(f) or (f.startswith("scanviz") and a.name in names)
                ),
                None,
            )
        elif isinstance(node, ast.Attribute):
            chain = _dotted(node)
            if node.attr in names or (chain and is_banned(chain)):
                used = chain or f"….{node.attr}"
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            used = node.value if is_banned(node.value) else None  # importlib.import_module(...)
        if used is not None:
            verb = "imports" if isinstance(node, ast.Import | ast.ImportFrom) else "uses"
            return f"line {node.lineno} {verb} {used!r}"
    return None


def _dotted(node: ast.AST) -> str | None:
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    return ".".join([node.id, *reversed(parts)])


# --- the guard around student code ------------------------------------------------------------


class Guard:
    """An audit hook and exit stubs, active only inside ``with guard:`` (student code).

    Inside, opening a file outside `folder` (reading is also allowed inside
    Python's own and scanviz's installation), changing files outside it,
    starting processes, sending signals, network access, changing the
    resource limits and ``os._exit``/``os.abort`` raise `NotAllowed`; the
    first such attempt is kept in ``violation`` even if the student's code
    catches the exception.
    """

    def __init__(self, folder: Path) -> None:
        self.folder = os.path.realpath(folder)
        roots = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix}
        roots.update(site.getsitepackages())
        roots.add(str(Path(scanviz.__file__).parent))
        self.readable = tuple(os.path.realpath(r) for r in roots) + (self.folder,)
        self.active = False
        self.violation: str | None = None
        self._saved: list = []
        sys.addaudithook(self._hook)

    def __enter__(self) -> Guard:
        self.violation = None
        for module in (os, posix):
            for name in ("_exit", "abort"):
                self._saved.append((module, name, getattr(module, name)))
                setattr(module, name, self._refuse_exit)
        self.active = True
        return self

    def __exit__(self, *exc_info) -> None:
        self.active = False
        for module, name, function in self._saved:
            setattr(module, name, function)
        self._saved.clear()

    def _refuse_exit(self, *args) -> None:
        self._refuse("calls os._exit or os.abort (the grader runs the other exercises too)")

    def _refuse(self, what: str) -> None:
        self.violation = self.violation or f"the answer {what}"
        raise NotAllowed(f"the answer {what}")

    def _hook(self, event: str, args: tuple) -> None:
        if not self.active:
            return
        if event == "open":
            self._check_open(*args[:3])
        elif event in _REFUSED_EVENTS:
            self._refuse(_REFUSED_EVENTS[event])
        elif event in _PATH_EVENTS:
            for index in _PATH_EVENTS[event]:
                path = args[index] if index < len(args) else None
                if isinstance(path, str | bytes | os.PathLike) and not self._inside(path):
                    self._refuse(f"changes {os.fsdecode(path)!r}, outside its folder")

    def _check_open(self, path, mode, flags) -> None:
        if isinstance(path, int):
            if path > 2:
                self._refuse(f"opens file descriptor {path}")
            return
        writing = any(c in (mode or "") for c in "wax+") or bool((flags or 0) & _WRITE_FLAGS)
        if not self._inside(path, () if writing else self.readable):
            action = "writes" if writing else "opens"
            self._refuse(f"{action} {os.fsdecode(path)!r}, outside its folder")

    def _inside(self, path, roots: tuple[str, ...] = ()) -> bool:
        real = os.path.realpath(os.fsdecode(path))
        return any(
            real == r or real.startswith(r.rstrip("/") + "/") for r in roots or (self.folder,)
        )


# --- scanviz must look the same after an exercise ---------------------------------------------


class State:
    """A snapshot of every scanviz module's namespace, and of its classes' and dicts' contents.

    `changed()` names the first entry that is now a different object or is
    gone (new entries are fine: submodules imported later, caches growing).
    """

    def __init__(self) -> None:
        self.modules = {n: m for n, m in sys.modules.items() if n.split(".")[0] == "scanviz"}
        self.saved = []  # (where, the namespace, class or dict, a shallow copy of its contents)
        for name, module in self.modules.items():
            self.saved.append((name, vars(module), dict(vars(module))))
            for key, value in vars(module).items():
                if (isinstance(value, type) and value.__module__ == name) or type(value) is dict:
                    self.saved.append(
                        (
                            f"{name}.{key}",
                            value,
                            dict(vars(value)) if isinstance(value, type) else dict(value),
                        )
                    )

    def changed(self) -> str | None:
        for name, module in self.modules.items():
            if sys.modules.get(name) is not module:
                return f"replaces the module {name!r}"
        for where, holder, contents in self.saved:
            now = vars(holder) if isinstance(holder, type) else holder
            for key, value in contents.items():
                if key not in now or now[key] is not value:
                    return f"changes {where}.{key}"
        return None


# --- running one exercise ---------------------------------------------------------------------


class _Alarm:
    """Raise `Timeout` in the running code after `seconds` of wall time (and again every 50 ms)."""

    armed = False

    def __init__(self, seconds: float) -> None:
        self.seconds = seconds

    def __enter__(self) -> None:
        _Alarm.armed = True
        signal.setitimer(signal.ITIMER_REAL, self.seconds, 0.05)

    def __exit__(self, *exc_info) -> None:
        _Alarm.armed = False
        signal.setitimer(signal.ITIMER_REAL, 0)


def _on_alarm(signum, frame) -> None:
    if _Alarm.armed:
        raise Timeout("wall")


def _on_cpu_limit(signum, frame) -> None:
    _Limits.cpu_exhausted = True
    if _Alarm.armed:
        raise Timeout("cpu")


class _Limits:
    cpu_exhausted = False


def _syntax_message(error: SyntaxError, what: str) -> str:
    text = (error.text or "").strip()
    shown = f": {text!r}" if text else ""
    return f"{what}, line {error.lineno}: {error.msg}{shown}"


def _raised_message(error: BaseException, filename: str, what: str) -> str:
    lines = [f.lineno for f in traceback.extract_tb(error.__traceback__) if f.filename == filename]
    where = f" (line {lines[-1]})" if lines else ""
    return f"{what} raised {type(error).__name__}: {error}{where}"


def _not_defined(exercise: Exercise, namespace: dict) -> str:
    defined = [k for k, v in namespace.items() if callable(v) and not k.startswith("__")]
    close = difflib.get_close_matches(exercise.answer, defined, n=1)
    hint = f" (it defines {close[0]!r}: rename it?)" if close else ""
    return f"the answer cell does not define a function {exercise.answer!r}{hint}"


def _memory(outcome: Outcome) -> bool:
    raised = [outcome.error or ""] + [c.repr for c in outcome.calls if isinstance(c, Opaque)]
    return any(r.startswith(("MemoryError", "raised MemoryError")) for r in raised)


def run_exercise(
    exercise: Exercise, answer: str, setup: list[str], inputs: list, seconds: float, guard: Guard
) -> tuple[str, str, list[Outcome], bool]:
    """(status, message, outcomes, restart) of one exercise; `restart`: this process is spoiled."""
    sources = [(s, f"<answer setup {n}>", f"setup cell {n}") for n, s in enumerate(setup, 1)]
    sources.append((answer, f"<answer {exercise.id}>", "the answer cell"))
    codes = []
    for source, filename, what in sources:
        try:
            codes.append((compile(source, filename, "exec"), filename, what))
            used = banned_use(source, exercise.banned)
        except SyntaxError as error:
            return "syntax error", _syntax_message(error, what), [], False
        if used:
            message = f"{what}, {used}: answers may not use the reference implementation"
            return "not allowed", message, [], False
    outcomes: list[Outcome] = []
    status, message = _run(exercise, codes, inputs, seconds, guard, outcomes)
    if status == "passed" and any(_memory(o) for o in outcomes):
        status, message = "memory", "the answer ran out of memory (MemoryError)"
    elif status == "passed" and any(o.error for o in outcomes):
        first = next(o.error for o in outcomes if o.error)
        count = sum(bool(o.error) for o in outcomes)
        status, message = "error", f"your code raised {first} ({count} of {len(outcomes)} cases)"
    restart = status in ("not allowed", "memory") or _Limits.cpu_exhausted
    return status, message, outcomes, restart


def _run(exercise, codes, inputs, seconds, guard, outcomes) -> tuple[str, str]:
    namespace = {"__name__": "__main__", "__builtins__": builtins}
    state = State()
    status, message = "passed", ""
    running = codes[0]  # (code, filename, what): the cell that runs, to say which one raised
    try:
        with _Alarm(seconds), guard:
            for running in codes:  # noqa: B007 - read in the handler below
                exec(running[0], namespace)  # noqa: S102 - student code, in the sandboxed worker
            function = namespace.get(exercise.answer)
            if callable(function):
                for case_inputs in inputs:
                    outcomes.append(run_case(exercise, function, Case("", case_inputs)))
            else:
                status, message = "not defined", _not_defined(exercise, namespace)
    except Timeout as error:
        limit = "CPU time of the submission" if str(error) == "cpu" else f"{seconds:g} s"
        status, message = "timeout", f"the answer ran out of time ({limit})"
    except NotAllowed as error:
        status, message = "not allowed", str(error)
    except SystemExit:
        status, message = "not allowed", "the answer calls sys.exit (or exit/quit)"
    except MemoryError:
        status, message = "memory", "the answer ran out of memory (MemoryError)"
    except BaseException as error:  # the cell itself raised while it ran
        status, message = "error", _raised_message(error, running[1], running[2])
    changed = state.changed()
    if guard.violation:
        return "not allowed", guard.violation
    if changed:
        return "not allowed", f"the answer {changed} (answers may not patch scanviz)"
    return status, message


# --- the process ------------------------------------------------------------------------------


@contextlib.contextmanager
def _captured(capture: Path, name: str, worker_stderr: int):
    """Point fds 1 and 2 at the capture files of one exercise, then back (1 at /dev/null)."""
    out = os.open(capture / f"{name}.stdout", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    err = os.open(capture / f"{name}.stderr", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.dup2(out, 1)
    os.dup2(err, 2)
    try:
        yield
    finally:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, 1)
        os.dup2(worker_stderr, 2)
        for fd in (out, err, null):
            os.close(fd)


def _limit(limits: dict) -> None:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    cpu = math.ceil(usage.ru_utime + usage.ru_stime + float(limits["cpu_seconds"]))
    memory = int(limits["memory_mb"]) * 2**20
    resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu + 2))
    resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    resource.setrlimit(resource.RLIMIT_FSIZE, (OUTPUT_FILE_LIMIT, OUTPUT_FILE_LIMIT))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    signal.signal(signal.SIGXCPU, _on_cpu_limit)
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails instead
    signal.signal(signal.SIGALRM, _on_alarm)


def main(root: Path) -> None:
    """Run the request in `root` (see the module docstring)."""
    channel = os.fdopen(os.dup(1), "w", encoding="utf-8")
    worker_stderr = os.dup(2)  # the grader keeps it: tracebacks if this process fails
    null = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1):
        os.dup2(null, fd)
    dumps = json.dumps

    def send(message: dict) -> None:
        channel.write(dumps(message) + "\n")
        channel.flush()

    request_path = root / "request.json"
    request = json.loads(request_path.read_text(encoding="utf-8"))
    request_path.unlink()
    for item in request["exercises"]:
        # The reference on a public case, unguarded and before the limits: lazy imports, numba
        # kernel loads (or compiles) and caches happen now, not inside student code, where
        # they would look like file access or patching.
        exercise = get(item["id"])
        for case in exercise.public:  # every public case: each may take other kernels
            run_case(exercise, exercise.reference, case)
    _limit(request["limits"])
    guard = Guard(Path.cwd())
    send({"ready": True})
    for item in request["exercises"]:
        send({"start": item["id"]})
        exercise = get(item["id"])
        inputs = [from_plain(plain) for plain in item["cases"]]
        with _captured(root / "capture", item["capture"], worker_stderr):
            status, message, outcomes, restart = run_exercise(
                exercise,
                item["answer"],
                request["setup"],
                inputs,
                float(request["limits"]["case_seconds"]),
                guard,
            )
        plain = [o.to_plain() for o in outcomes]
        send({"done": item["id"], "status": status, "message": message, "outcomes": plain})
        if restart:
            send({"restart": True})
            return


if __name__ == "__main__":
    main(Path(sys.argv[1]))

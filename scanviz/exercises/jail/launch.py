"""How the runner is started: the files it can see, the jail's command line, whether a jail works.

The runner sees a *runtime*: ``runner.py`` and ``wire.py``, and a package
``scanviz`` that holds only ``scanviz.trace.events`` (the records a loop
exercise emits, one module per stage) and the ``schema`` that checks them,
written once per grading process into a temporary folder (`runtime`).
Beside it, numpy, and Python's own standard library: nothing else of
scanviz (which holds the reference), no other package.

`jail_command` puts it in bubblewrap (Debian's ``bubblewrap``): new user,
PID, network, IPC, UTS and cgroup namespaces (no network, no other process
visible, all of them gone when the runner ends); a read-only view of the
system libraries, the Python runtime (its site-packages hidden), numpy and
the runtime; a private 16 MiB ``/tmp`` as working folder; no other file of
the machine (no key, no submission, no home); an empty environment; no
capabilities; and the system-call filter of `scanviz.exercises.jail.seccomp`,
which forbids new processes. The runner then sets its own resource limits
(CPU, memory, file size, open files).

Three jails (`JAILS`), chosen by `choose`:

- ``"bwrap"``: the above; what grading needs by default.
- ``"user"``: where bubblewrap cannot make namespaces but the grader is root
  (a Gradescope container), the runner runs as the unprivileged user
  ``nobody`` in a private folder, with the same runtime (numpy copied in),
  limits and system-call filter, which the runner loads itself (so no
  process and no network socket either). What it can read is what
  ``nobody`` may read: the key, the submissions and scanviz must be closed
  to others, which grading checks first (`readable_by_nobody`).
- ``"none"``: the same runner, runtime, limits and (on Linux) filter, but no
  other barrier: a student's own check, or a teacher's run on submissions
  they trust (``--no-jail``).
"""

from __future__ import annotations

import atexit
import functools
import glob
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from . import seccomp

JAIL_LIB = "/jail/lib"  # the runtime, inside the jail
JAIL_SITE = "/jail/site"  # numpy, inside the jail
TMP_BYTES = 16 * 2**20  # the jail's /tmp
PROBE_SECONDS = 60.0
_HERE = Path(__file__).resolve().parent
_PACKAGE = _HERE.parent.parent  # scanviz/
_RUNTIME_SCANVIZ = '"""scanviz inside the jail: only `scanviz.trace.events` is here."""\n'


class JailUnavailable(OSError):
    """The jail cannot start on this machine; the message says why and what to do."""


JAILS = ("bwrap", "user", "none")
NOBODY = 65534  # the unprivileged user of the "user" jail (and the uid inside bubblewrap)
AS_NOBODY = {"user": NOBODY, "group": NOBODY, "extra_groups": []}  # Popen's arguments for it


@functools.cache
def runtime(copy_numpy: bool = False) -> Path:
    """The runtime folder of this process (made once, removed at exit): ``lib/`` and ``site/``.

    ``lib`` holds the runner, wire and the events-only scanviz; ``site``
    links to numpy (the plain runner's view of what the jail binds), or holds
    a copy of it (`copy_numpy`: for ``nobody``, who may not read the grader's
    environment).
    """
    root = Path(tempfile.mkdtemp(prefix="scanviz-runtime-"))
    atexit.register(shutil.rmtree, root, ignore_errors=True)
    lib = root / "lib"
    (lib / "scanviz" / "trace").mkdir(parents=True)
    for name in ("runner.py", "wire.py"):
        shutil.copyfile(_HERE / name, lib / name)
    for name in ("schema.py", "display.py"):
        shutil.copyfile(_PACKAGE / "trace" / name, lib / "scanviz" / "trace" / name)
    shutil.copytree(
        _PACKAGE / "trace" / "events",
        lib / "scanviz" / "trace" / "events",
        ignore=shutil.ignore_patterns("__pycache__"),
    )
    (lib / "scanviz" / "__init__.py").write_text(_RUNTIME_SCANVIZ, encoding="utf-8")
    (lib / "scanviz" / "trace" / "__init__.py").write_text(_RUNTIME_SCANVIZ, encoding="utf-8")
    site = root / "site"
    site.mkdir()
    for name, path in _numpy_dirs().items():
        if copy_numpy:
            shutil.copytree(
                path, site / name, ignore=shutil.ignore_patterns("tests", "__pycache__")
            )
        else:
            (site / name).symlink_to(path)
    for path in [root, *root.rglob("*")]:
        if not path.is_symlink():
            path.chmod(0o755 if path.is_dir() else 0o644)
    return root


def _numpy_dirs() -> dict[str, str]:
    """numpy's package folder and, if it has one, its folder of bundled libraries."""
    import numpy

    package = Path(numpy.__file__).resolve().parent
    dirs = {"numpy": str(package)}
    libs = package.parent / "numpy.libs"
    if libs.is_dir():
        dirs["numpy.libs"] = str(libs)
    return dirs


def python_executable() -> str:
    """The real interpreter (not a virtual environment's link to it)."""
    return os.path.realpath(sys.executable)


def runner_arguments(limits: dict, lib: str, site: str) -> list[str]:
    import json

    return ["-I", "-S", "-B", f"{lib}/runner.py", json.dumps(limits), site]


def plain_command(limits: dict, copy_numpy: bool = False) -> list[str]:
    """The runner without bubblewrap (same runtime, same limits, Python's flags to isolate it);
    the runner loads the system-call filter itself where it can."""
    root = runtime(copy_numpy)
    if seccomp.supported() and sys.platform == "linux":
        limits = {**limits, "seccomp": seccomp.program().hex()}
    return [python_executable(), *runner_arguments(limits, f"{root}/lib", f"{root}/site")]


def _bound_roots() -> list[str]:
    """Host folders the jail sees read-only: the system's libraries and the Python runtime."""
    roots = ["/usr"]
    prefix = os.path.realpath(sys.base_prefix)
    if not any(prefix == r or prefix.startswith(r + "/") for r in roots):
        roots.append(prefix)
    return roots


def hidden_inside(roots: list[str]) -> list[str]:
    """Folders inside `roots` the jail must not see: site-packages (scanviz may be there) and
    scanviz itself, wherever it is installed."""
    patterns = (
        "lib*/python3*/site-packages",
        "lib*/python3*/dist-packages",
        "lib/python3/dist-packages",
        "local/lib*/python3*/*-packages",
    )
    found = {p for r in roots for pattern in patterns for p in glob.glob(f"{r}/{pattern}")}
    found.add(str(_PACKAGE))
    inside = sorted(
        os.path.realpath(p)
        for p in found
        if os.path.isdir(p) and any(os.path.realpath(p).startswith(r + "/") for r in roots)
    )
    outermost: list[str] = []
    for path in inside:  # sorted: a folder comes before the folders inside it
        if not any(path.startswith(o + "/") for o in outermost):
            outermost.append(path)
    return outermost


def visible(path: str | os.PathLike) -> bool:
    """Whether the jail would see the host file or folder `path` (the key must not be)."""
    real = os.path.realpath(path)
    roots = _bound_roots()
    inside = any(real == r or real.startswith(r + "/") for r in roots)
    return inside and not any(real == h or real.startswith(h + "/") for h in hidden_inside(roots))


def jail_command(limits: dict, filter_fd: int) -> list[str]:
    """The bubblewrap command line that runs the runner (see the module docstring)."""
    bwrap = shutil.which("bwrap")
    roots = _bound_roots()
    argv = [
        bwrap,
        "--unshare-all",
        "--unshare-user",
        "--disable-userns",
        "--uid", "65534",
        "--gid", "65534",
        "--die-with-parent",
        "--new-session",
        "--clearenv",
        "--cap-drop", "ALL",
        "--proc", "/proc",
        "--dev", "/dev",
    ]  # fmt: skip
    for root in roots:
        argv += ["--ro-bind", root, root]
    for name in ("bin", "lib", "lib64", "lib32", "libx32", "sbin"):
        path = Path("/") / name
        if path.is_symlink():
            argv += ["--symlink", os.readlink(path), str(path)]
        elif path.is_dir():
            argv += ["--ro-bind", str(path), str(path)]
    argv += ["--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache"]
    for hidden in hidden_inside(roots):
        argv += ["--tmpfs", hidden, "--remount-ro", hidden]
    for name, path in _numpy_dirs().items():
        argv += ["--ro-bind", path, f"{JAIL_SITE}/{name}"]
    argv += ["--ro-bind", str(runtime() / "lib"), JAIL_LIB]
    argv += ["--size", str(TMP_BYTES), "--tmpfs", "/tmp", "--remount-ro", "/", "--chdir", "/tmp"]
    for name, value in ENVIRONMENT.items():
        argv += ["--setenv", name, value]
    argv += ["--seccomp", str(filter_fd), "--", python_executable()]
    return argv + runner_arguments(limits, JAIL_LIB, JAIL_SITE)


ENVIRONMENT = {
    "HOME": "/tmp",
    "TMPDIR": "/tmp",
    "PATH": "/usr/bin:/bin",
    "LANG": "C.UTF-8",
    "PYTHONIOENCODING": "utf-8",
    "OPENBLAS_NUM_THREADS": "1",
    "OMP_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
}
"""The runner's whole environment (nothing of the grader's: no secret can be in it)."""


def process(jail: str, limits: dict, folder: str) -> dict:
    """Popen's arguments that start the runner in `jail`, working in the private `folder`
    (bubblewrap gives it a /tmp instead); the caller closes the ``pass_fds`` once started."""
    if jail == "bwrap":
        fd = filter_file()
        return {"args": jail_command(limits, fd), "pass_fds": [fd], "env": {}}
    environment = {**ENVIRONMENT, "HOME": folder, "TMPDIR": folder}
    if jail == "none":
        return {"args": plain_command(limits), "cwd": folder, "env": environment}
    os.chown(folder, NOBODY, NOBODY)
    arguments = {
        "args": plain_command(limits, copy_numpy=True),
        "cwd": folder,
        "env": environment,
        **AS_NOBODY,
    }
    return arguments


def filter_file() -> int:
    """A file descriptor holding the system-call filter, positioned at its start (caller closes)."""
    fd = os.memfd_create("scanviz-seccomp", 0) if hasattr(os, "memfd_create") else None
    if fd is None:
        file = tempfile.TemporaryFile()
        fd = os.dup(file.fileno())
        file.close()
    os.write(fd, seccomp.program())
    os.lseek(fd, 0, os.SEEK_SET)
    return fd


@functools.cache
def unavailable(jail: str = "bwrap") -> str | None:
    """Why `jail` cannot start here (None if it can): tried once per process."""
    if jail == "none":
        return None
    if sys.platform != "linux":
        return f"the jail needs Linux (this is {sys.platform})"
    if not seccomp.supported():
        import platform

        return f"the system-call filter does not know this architecture ({platform.machine()})"
    return _bwrap_unavailable() if jail == "bwrap" else _user_unavailable()


def _bwrap_unavailable() -> str | None:
    if shutil.which("bwrap") is None:
        return "bubblewrap is not installed (Debian and Ubuntu: apt-get install bubblewrap)"
    fd = filter_file()
    try:
        argv = jail_command({}, fd)
        probe = argv[: argv.index("--") + 2] + ["-I", "-S", "-c", "import os; os.fork()"]
        done = subprocess.run(
            probe, pass_fds=(fd,), capture_output=True, timeout=PROBE_SECONDS, check=False
        )
    except (OSError, subprocess.SubprocessError) as error:
        return f"bubblewrap could not be started: {error}"
    finally:
        os.close(fd)
    return _probe_failure(done, "bubblewrap cannot make the jail on this machine")


def _user_unavailable() -> str | None:
    if os.geteuid() != 0:
        return "the 'user' jail runs answers as the user nobody, which needs the grader to be root"
    root = runtime(copy_numpy=True)
    check = "import numpy, os; os.fork()"
    try:
        done = subprocess.run(
            plain_command({}, copy_numpy=True)[:1]
            + ["-I", "-S", "-c", _PROBE.format(program=seccomp.program().hex(), check=check)],
            capture_output=True,
            timeout=PROBE_SECONDS,
            check=False,
            cwd="/",
            env={**ENVIRONMENT, "SCANVIZ_RUNTIME": str(root)},
            **AS_NOBODY,
        )
    except (OSError, subprocess.SubprocessError) as error:
        return f"the user nobody cannot run Python here: {error}"
    return _probe_failure(done, "the 'user' jail cannot start on this machine")


_PROBE = (  # as the runner does: the runtime on the path, the filter loaded, then `check`
    "import os, sys; root = os.environ['SCANVIZ_RUNTIME']; sys.path[:0] = [root + '/lib', "
    "root + '/site']; import runner; runner.load_filter(bytes.fromhex({program!r})); {check}"
)


def _probe_failure(done: subprocess.CompletedProcess, what: str) -> str | None:
    """None if the probe failed to fork as it should, else why the jail cannot start."""
    stderr = done.stderr.decode("utf-8", "replace").strip()
    if done.returncode == 1 and stderr.endswith(
        "PermissionError: [Errno 1] Operation not permitted"
    ):
        return None
    last = stderr.splitlines()[-1] if stderr else f"exit status {done.returncode}"
    return f"{what}: {last}"


def readable_by_nobody(path: str | os.PathLike) -> bool:
    """Whether the user nobody could read `path` (the kernel is asked, with test(1) as nobody)."""
    done = subprocess.run(
        ["test", "-r", os.fspath(path)], timeout=PROBE_SECONDS, check=False, cwd="/", **AS_NOBODY
    )
    return done.returncode == 0


def reference_file() -> Path:
    """A file of the reference (the scan converter): nothing in a jail may read it."""
    return _PACKAGE / "raster" / "scanline.py"

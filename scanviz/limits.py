"""Resource limits: estimate before allocating, refuse with the figure and the limit.

Every entry point that allocates in proportion to its input (rasters, meshes,
a-buffers, files) estimates the bytes first and calls `check_memory`; a
request over the limit raises `ResourceLimitError` (a `ValueError`) naming
what was asked for, the estimate and the limit, before anything is allocated.

The memory limit is 4 GiB by default. Raise or lower it for one block with
``with scanviz.limits.memory_limit("16G"): ...``, or for a whole process with
the environment variable ``SCANVIZ_MEMORY_LIMIT`` (bytes, or a number with a
K/M/G/T suffix). File reads are bounded the same way by `file_limit`
(256 MiB, ``SCANVIZ_FILE_LIMIT``), and `read_bounded` reads regular files
only, so a FIFO or a device never blocks a reader.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import stat
import threading
from collections.abc import Iterator
from contextvars import ContextVar
from pathlib import Path

import numpy as np

DEFAULT_MEMORY_LIMIT = 4 * 2**30
DEFAULT_FILE_LIMIT = 256 * 2**20
MEMORY_ENV = "SCANVIZ_MEMORY_LIMIT"
FILE_ENV = "SCANVIZ_FILE_LIMIT"
_UNITS = {"": 1, "K": 2**10, "M": 2**20, "G": 2**30, "T": 2**40}

JSON_STRING = r'"[^"\\]*(?:\\.[^"\\]*)*(?:"|\\?\Z)'  # to the end if unterminated: linear time
_JSON_STRINGS = re.compile(JSON_STRING, re.DOTALL)
_NOT_BRACKETS = re.compile(r"[^\[\]{}]+")

_memory_override: ContextVar[int | None] = ContextVar("scanviz_memory_limit", default=None)
_file_override: ContextVar[int | None] = ContextVar("scanviz_file_limit", default=None)


class ResourceLimitError(ValueError):
    """A request whose estimated memory (or file size) is over the configured limit."""


def parse_size(text: object, name: str = "size") -> int:
    """Parse a byte count: an int, or a string like ``"512M"``, ``"4G"``, ``"1.5G"``.

    >>> parse_size("4G"), parse_size(1024), parse_size("1.5K")
    (4294967296, 1024, 1536)
    """
    if isinstance(text, bool):
        raise TypeError(f"{name!r} must be a byte count; got {text!r}")
    if isinstance(text, int):
        value = text
    elif isinstance(text, str):
        match = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*([KMGT]?)i?B?\s*", text, re.IGNORECASE)
        if match is None:
            raise ValueError(
                f"{name!r} must be a byte count such as 1073741824, '512M' or '4G'; got {text!r}"
            )
        value = int(float(match.group(1)) * _UNITS[match.group(2).upper()])
    else:
        raise TypeError(f"{name!r} must be a byte count (int or str like '4G'); got {text!r}")
    if value <= 0:
        raise ValueError(f"{name!r} must be > 0 bytes; got {text!r}")
    return value


def format_size(nbytes: float) -> str:
    """Bytes in a human unit.

    >>> format_size(3 * 2**30), format_size(1536), format_size(12)
    ('3.0 GiB', '1.5 KiB', '12 B')
    """
    for unit, factor in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if nbytes >= factor:
            return f"{nbytes / factor:.1f} {unit}"
    return f"{int(nbytes)} B"


def _configured(override: ContextVar[int | None], env: str, default: int) -> int:
    value = override.get()
    if value is not None:
        return value
    text = os.environ.get(env)
    return default if not text else parse_size(text, env)


def current_memory_limit() -> int:
    """The memory limit in force, in bytes."""
    return _configured(_memory_override, MEMORY_ENV, DEFAULT_MEMORY_LIMIT)


def current_file_limit() -> int:
    """The limit on the size of a file read, in bytes."""
    return _configured(_file_override, FILE_ENV, DEFAULT_FILE_LIMIT)


@contextlib.contextmanager
def memory_limit(limit: int | str) -> Iterator[int]:
    """Set the memory limit for the enclosed block (this thread / task only).

    >>> with memory_limit("1M"):
    ...     current_memory_limit()
    1048576
    """
    token = _memory_override.set(parse_size(limit, "limit"))
    try:
        yield _memory_override.get()
    finally:
        _memory_override.reset(token)


@contextlib.contextmanager
def file_limit(limit: int | str) -> Iterator[int]:
    """Set the limit on file reads for the enclosed block."""
    token = _file_override.set(parse_size(limit, "limit"))
    try:
        yield _file_override.get()
    finally:
        _file_override.reset(token)


def check_memory(nbytes: float, what: str) -> None:
    """Raise `ResourceLimitError` if allocating about `nbytes` for `what` is over the limit.

    >>> with memory_limit("1M"):
    ...     check_memory(2**30, "a 16384x16384 raster")
    Traceback (most recent call last):
    ...
    scanviz.limits.ResourceLimitError: a 16384x16384 raster needs about 1.0 GiB, over the memory limit of 1.0 MiB (raise it with scanviz.limits.memory_limit(...) or SCANVIZ_MEMORY_LIMIT)
    """
    limit = current_memory_limit()
    if nbytes > limit:
        raise ResourceLimitError(
            f"{what} needs about {format_size(nbytes)}, over the memory limit of "
            f"{format_size(limit)} (raise it with scanviz.limits.memory_limit(...) or {MEMORY_ENV})"
        )


_FILE_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def read_bounded(path: str | os.PathLike, *, binary: bool = False) -> str | bytes:
    """Read a regular file whole, refusing one larger than `current_file_limit()`.

    Only regular files are read: a FIFO, device, socket or directory raises a
    ValueError naming it, without blocking (the file is opened non-blocking
    and checked with ``fstat`` on the open descriptor, so nothing can be
    swapped in between). The read itself is bounded too, in case the file
    grows. Text is decoded as UTF-8 (a leading byte-order mark is dropped); an
    undecodable file raises a ValueError naming the file and the byte offset.

    >>> read_bounded("/dev/zero")
    Traceback (most recent call last):
    ...
    ValueError: '/dev/zero' is a character device, not a regular file; only regular files are read
    """
    limit = current_file_limit()
    name = str(Path(path))
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)  # a FIFO opens at once
    try:
        mode = os.fstat(descriptor).st_mode  # of the file opened: no race with a rename
        if not stat.S_ISREG(mode):
            kind = next((kind for test, kind in _FILE_KINDS if test(mode)), "a special file")
            raise ValueError(f"{name!r} is {kind}, not a regular file; only regular files are read")
        with open(descriptor, "rb", closefd=False) as file:
            data = file.read(limit + 1)
    finally:
        os.close(descriptor)
    if len(data) > limit:
        raise ResourceLimitError(
            f"{name!r} is larger than the file limit of {format_size(limit)} "
            f"(raise it with scanviz.limits.file_limit(...) or {FILE_ENV})"
        )
    if binary:
        return data
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise ValueError(
            f"{name!r} is not UTF-8 text: byte {error.start} is {data[error.start]:#04x}"
        ) from None


_NESTING_CHUNK = 2**18  # characters scanned at once: about 2 MiB of temporaries


def json_nesting(text: str) -> tuple[int, str]:
    """(deepest nesting of arrays and objects, `text` without its strings), before any parse.

    Python's JSON parser recurses, so deep text must be refused before it is
    parsed; this scan runs at C speed and in linear time, a chunk of
    `_NESTING_CHUNK` characters at a time with the running depth carried
    over, so its temporaries stay a few MiB whatever the length. Unbalanced
    text gives its deepest point too (the parser then says where it breaks).

    >>> json_nesting('{"a": [[1], "[[["], {}}')[0]
    3
    """
    outside_strings = _JSON_STRINGS.sub("", text)
    depth = deepest = 0
    for start in range(0, len(outside_strings), _NESTING_CHUNK):
        chunk = _NOT_BRACKETS.sub("", outside_strings[start : start + _NESTING_CHUNK])
        brackets = np.frombuffer(chunk.encode("ascii"), np.uint8)
        opening = ((brackets == ord("[")) | (brackets == ord("{"))).astype(np.int8)
        running = np.cumsum(2 * opening - 1, dtype=np.int32)  # steps +-1; |sum| <= 2**18
        if running.size:
            deepest = max(deepest, depth + int(running.max()))
            depth += int(running[-1])
    return deepest, outside_strings


@contextlib.contextmanager
def wall_clock_limit(seconds: float, error: type[BaseException], message: str) -> Iterator[None]:
    """Raise ``error(message)`` inside the running code once `seconds` have passed.

    It is raised again every 50 ms until the block ends, so code that catches
    it once cannot run on. Use a BaseException subclass, which ``except
    Exception`` lets by. A no-op outside the main thread (signals go there only).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def expire(signum, frame):
        raise error(message)

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, seconds, 0.05)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)

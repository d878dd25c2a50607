"""The grader's end of the jail: start the runner, send it requests, check every reply.

A `Session` is one runner process for one submission, in one of the jails
of `launch` (``jail="bwrap"``, ``"user"`` or ``"none"``). `load` runs an answer cell in it; `RemoteAnswer`
is the answer's function as the grader's algorithm calls it: each call's
arguments go over as plain data (`wire`), and what comes back is decoded
and checked -- a value the answer returned, the text of what it raised,
the new state of the arguments it changed, the events it emitted. Nothing in
a reply can set a status or a score: the grader judges the values.

Deadlines are the grader's: `deadline` bounds the time a request may take;
a runner that misses it, dies, or writes anything but a well-formed reply
to the request at hand is killed, and `JailStopped` says how it ended
(``timeout``, ``crashed`` or ``not allowed``), with the signal if one
killed it.
"""

from __future__ import annotations

import contextlib
import json
import os
import resource
import select
import signal
import subprocess
import tempfile
import time
from collections.abc import Iterator
from dataclasses import dataclass

from ...trace.events import Event
from ...trace.recorder import Recorder
from . import launch, wire

STARTUP_SECONDS = 60.0  # the runner starts in well under a second; a loaded machine is slow
MESSAGE_BYTES = 16 * 2**20  # longest reply line read
OUTPUT_LIMIT = 20_000  # characters of an exercise's printed output kept
FILE_BYTES = 64 * 2**20  # largest file the runner may write (its printed output included)
BATCH = 500  # forced calls sent in one request
EXIT_SECONDS = 5.0  # a runner whose channel closed has this long to exit before it is killed


class TraceOverflow(BaseException):
    """A case emitted more events than it may (a BaseException: no loop's except catches it)."""


@dataclass(frozen=True)
class Limits:
    """The runner's limits (a `CourseKey` has the same three fields).

    ``cpu_seconds``: CPU time of one runner process (one submission);
    ``memory_mb``: its address space; ``case_seconds``: wall time of one
    exercise's cases, the grader's own work on them included.
    """

    cpu_seconds: float = 60.0
    memory_mb: int = 1024
    case_seconds: float = 10.0


class AnswerRaised(BaseException):
    """The answer raised an exception (its text, made in the jail, is `text`).

    A BaseException, so that no ``except Exception`` in an algorithm between
    the call and `scanviz.exercises.core.run_case` takes it for its own.
    """

    def __init__(self, text: str) -> None:
        super().__init__(text)
        self.text = text


class JailStopped(BaseException):
    """The runner is gone: ``status`` is a grade status, ``message`` says what happened."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status = status
        self.message = message


class Session:
    """One runner process: started lazily, restarted after it stops (see the module docstring)."""

    def __init__(self, limits: Limits = Limits(), *, jail: str = "bwrap") -> None:
        if jail not in launch.JAILS:
            raise ValueError(f"'jail' must be one of {launch.JAILS}; got {jail!r}")
        if (reason := launch.unavailable(jail)) is not None:
            raise launch.JailUnavailable(reason)
        self.limits = limits
        self.jail = jail
        self.process: subprocess.Popen | None = None
        self.deadline: float | None = None
        self.timeout_seconds = 0.0
        self.number = 0
        self._buffer = b""

    # --- starting and stopping -------------------------------------------------------------

    def start(self) -> None:
        self.close()
        self.capture = tempfile.TemporaryFile()
        self.folder = tempfile.TemporaryDirectory(prefix="scanviz-answer-")
        request_read, self.requests = os.pipe()
        self.replies, reply_write = os.pipe()
        limits = {
            "cpu_seconds": self.limits.cpu_seconds,
            "memory_mb": self.limits.memory_mb,
            "file_bytes": FILE_BYTES,
            "requests": request_read,
            "replies": reply_write,
        }
        passed = [request_read, reply_write]
        arguments = launch.process(self.jail, limits, self.folder.name)
        passed += arguments.pop("pass_fds", [])
        self._cpu_before = _children_cpu()
        try:
            self.process = subprocess.Popen(
                **arguments,
                stdin=subprocess.DEVNULL,
                stdout=self.capture,
                stderr=self.capture,
                pass_fds=passed,
                start_new_session=True,
            )
        finally:
            for fd in passed:
                os.close(fd)
        for fd in (self.requests, self.replies):
            os.set_blocking(fd, False)
        self._buffer = b""
        with self.time_limit(STARTUP_SECONDS):
            ready = self._read_line()
        if ready != {"ready": True}:
            self._stop()
            raise JailStopped("crashed", "the process running the answer did not start properly")

    def close(self) -> None:
        """End the runner (if one runs) and free what it held."""
        if self.process is None:
            return
        self._stop()
        for fd in (self.requests, self.replies):
            with contextlib.suppress(OSError):
                os.close(fd)
        self.capture.close()
        self.folder.cleanup()
        self.process = None

    def _stop(self) -> None:
        if self.process.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.process.pid, signal.SIGKILL)  # bubblewrap takes its namespace along
        self.process.wait()

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc_info) -> None:
        self.close()

    @property
    def running(self) -> bool:
        return self.process is not None and self.process.poll() is None

    @contextlib.contextmanager
    def time_limit(self, seconds: float) -> Iterator[None]:
        """Requests inside the block must be answered within `seconds` in all."""
        saved = self.deadline, self.timeout_seconds
        self.deadline, self.timeout_seconds = time.monotonic() + seconds, seconds
        try:
            yield
        finally:
            self.deadline, self.timeout_seconds = saved

    # --- the channel ---------------------------------------------------------------------

    def request(self, message: dict) -> dict:
        """Send `message`, return the reply to it (checked to be a JSON object answering it)."""
        if not self.running:
            self.start()
        self.number += 1
        data = (json.dumps({"n": self.number, **message}) + "\n").encode()
        self._write(data)
        reply = self._read_line()
        if not isinstance(reply, dict) or reply.get("n") != self.number:
            self._broken(f"a reply that answers no request ({_short(reply)})")
        del reply["n"]
        return reply

    def _remaining(self) -> float | None:
        if self.deadline is None:
            return None
        return max(0.0, self.deadline - time.monotonic())

    def _write(self, data: bytes) -> None:
        view = memoryview(data)
        while view:
            _, writable, _ = select.select([], [self.requests], [], self._remaining())
            if not writable:
                self._timed_out()
            try:
                view = view[os.write(self.requests, view) :]
            except BrokenPipeError:
                raise self._death() from None

    def _read_line(self) -> object:
        while b"\n" not in self._buffer:
            if len(self._buffer) > MESSAGE_BYTES:
                self._broken(f"a reply longer than {MESSAGE_BYTES} bytes")
            readable, _, _ = select.select([self.replies], [], [], self._remaining())
            if not readable:
                self._timed_out()
            chunk = os.read(self.replies, 2**16)
            if not chunk:
                raise self._death()
            self._buffer += chunk
        line, self._buffer = self._buffer.split(b"\n", 1)
        try:
            return json.loads(line, parse_constant=_not_json)
        except (ValueError, RecursionError):
            self._broken(f"a line that is not JSON ({_short(line)})")

    def _timed_out(self):
        self._stop()
        raise JailStopped(
            "timeout",
            f"the answer ran out of time ({self.timeout_seconds:g} s) and was stopped",
        )

    def _broken(self, what: str):
        self._stop()
        raise JailStopped(
            "not allowed",
            f"the process running the answer wrote {what} on its channel to the grader",
        )

    def _death(self) -> JailStopped:
        """How the runner ended, as a JailStopped (it is waited for a moment, then killed)."""
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.process.wait(EXIT_SECONDS)  # its channel closed: it is on its way out
        self._stop()
        code = self.process.returncode
        cpu = _children_cpu() - self._cpu_before
        if (
            self.jail == "bwrap" and code > 128
        ):  # bubblewrap exits with 128 + the signal that killed its child
            code = -(code - 128)
        if code < 0:
            name = _signal_name(-code)
            if -code == signal.SIGXCPU or (
                -code == signal.SIGKILL and cpu >= self.limits.cpu_seconds
            ):
                return JailStopped(
                    "timeout",
                    f"the answer used up the CPU time of the submission "
                    f"({self.limits.cpu_seconds:g} s) and was killed ({name})",
                )
            return JailStopped("crashed", f"the process running the answer was killed by {name}")
        return JailStopped(  # no quote of what it printed: that may come from a hidden case
            "crashed", f"the process running the answer exited (status {code}) before replying"
        )

    # --- what the answer printed ---------------------------------------------------------

    def output_offset(self) -> int:
        return os.fstat(self.capture.fileno()).st_size if self.process is not None else 0

    def output(self, start: int, end: int | None) -> str:
        """What the runner printed between two offsets (`output_offset`), shortened."""
        if self.process is None:
            return ""
        end = self.output_offset() if end is None else end
        data = os.pread(self.capture.fileno(), min(end - start, OUTPUT_LIMIT + 1), start)
        text = data[:OUTPUT_LIMIT].decode("utf-8", "replace")
        rest = end - start - OUTPUT_LIMIT
        return text + (f"\n... ({rest} more bytes)" if rest > 0 else "")

    # --- answers ---------------------------------------------------------------------------

    def load(self, exercise_id: str, name: str, source: str) -> RemoteAnswer:
        """Run an answer cell in a fresh namespace and return its function `name`.

        Raises `LoadFailed` if the cell is not valid Python, raises, or does not
        define `name`; `JailStopped` if the runner stops.
        """
        reply = self.request({"load": {"id": exercise_id, "name": name, "source": source}})
        if reply == {"loaded": True}:
            return RemoteAnswer(self)
        why, message = reply.get("failed"), reply.get("message")
        if why not in ("syntax", "raised", "undefined") or not isinstance(message, str):
            self._broken(f"a reply that answers no request ({_short(reply)})")
        if why == "undefined":
            try:
                defined = [d for d in json.loads(message) if isinstance(d, str)]
            except (ValueError, TypeError):
                defined = []
            raise LoadFailed(why, _not_defined(name, defined))
        raise LoadFailed(why, message[: wire.MAX_TEXT])


class LoadFailed(Exception):
    """An answer cell that cannot be used: ``why`` is "syntax", "raised" or "undefined"."""

    def __init__(self, why: str, message: str) -> None:
        super().__init__(message)
        self.why = why
        self.message = message


def _not_defined(name: str, defined: list[str]) -> str:
    import difflib

    close = difflib.get_close_matches(name, defined, n=1)
    hint = f" (it defines {close[0]!r}: rename it?)" if close else ""
    return f"the answer cell does not define a function {name!r}{hint}"


class RemoteAnswer:
    """The answer's function, as the grader's algorithm calls it (see the module docstring)."""

    def __init__(self, session: Session) -> None:
        self.session = session

    def __call__(self, *args, **kwargs):
        tracer = next((a for a in args if isinstance(a, Recorder)), None)
        call, encoder = _call_request(args, kwargs, tracer)
        reply = self.session.request({"call": call})
        ok, value = self._result(reply, encoder, tracer)
        if not ok:
            raise AnswerRaised(value)
        return value

    def call_each(self, calls: list[tuple[tuple, dict]]) -> list[tuple[bool, object]]:
        """(True, returned) or (False, raised text) for each call, sent in batches; the calls'
        arguments take the answer's changes."""
        results = []
        for start in range(0, len(calls), BATCH):
            requests = [
                _call_request(args, kwargs, None) for args, kwargs in calls[start : start + BATCH]
            ]
            reply = self.session.request({"batch": [call for call, _ in requests]})
            replies = reply.get("results")
            if (
                set(reply) != {"results"}
                or not isinstance(replies, list)
                or len(replies) != len(requests)
            ):
                self.session._broken(
                    f"a batch reply that does not fit its request ({_short(reply)})"
                )
            for (_, encoder), each in zip(requests, replies, strict=True):
                results.append(self._result(each, encoder, None))
        return results

    def _result(self, reply: object, encoder: wire.Encoder, tracer) -> tuple[bool, object]:
        """(True, the decoded return value) or (False, the raised text); changes applied, events
        emitted into `tracer`."""
        if (
            not isinstance(reply, dict)
            or not set(reply) <= _CALL_KEYS
            or (("returned" in reply) == ("raised" in reply))
        ):
            self.session._broken(f"a reply that is not a call's ({_short(reply)})")
        decoder = wire.Decoder(
            classes={**wire.TRACE_RECORDS, **encoder.classes}, arguments=encoder.objects
        )
        try:
            for k, state in _changed(reply.get("changed", {})).items():
                if k not in encoder.objects:
                    raise wire.WireError(f"'changed' names no argument: {k}")
                wire.apply_state(encoder.objects[k], decoder.decode(state))
            if tracer is not None:
                self._emit(reply, decoder, tracer)
            if "raised" in reply:
                raised = reply["raised"]
                if not isinstance(raised, str):
                    raise wire.WireError("'raised' must be a string")
                return False, raised[: wire.MAX_TEXT]
            return True, decoder.decode(reply["returned"])
        except wire.WireError as error:
            return False, f"ValueError: the grader cannot take what the answer gave: {error}"

    def _emit(self, reply: dict, decoder: wire.Decoder, tracer) -> None:
        events = reply.get("events", [])
        if not isinstance(events, list):
            raise wire.WireError("'events' must be a list")
        for plain in events:
            event = decoder.decode(plain)
            if not isinstance(event, Event):
                raise wire.WireError(f"the tracer was given {_short(event)}, which is not an event")
            tracer.emit(event)
        if reply.get("overflow") is True:
            raise TraceOverflow(f"more than {tracer.limit} events in one case")


_CALL_KEYS = {"returned", "raised", "changed", "events", "overflow"}


def _call_request(args: tuple, kwargs: dict, tracer) -> tuple[dict, wire.Encoder]:
    encoder = wire.Encoder(identify=True)
    position = next((i for i, a in enumerate(args) if a is tracer), None) if tracer else None
    plain_args = encoder.encode(tuple(a for a in args if a is not tracer or tracer is None))
    call = {"args": plain_args, "kwargs": encoder.encode(dict(kwargs))}
    if tracer is not None:
        kinds = getattr(tracer, "kinds", None)
        call.update(
            tracer=position,
            kinds=None if kinds is None else sorted(kinds),
            limit=getattr(tracer, "limit", None),
        )
    return call, encoder


def _changed(changed: object) -> dict[int, object]:
    if not isinstance(changed, dict):
        raise wire.WireError("'changed' must be an object")
    try:
        return {int(k): v for k, v in changed.items()}
    except ValueError:
        raise wire.WireError("'changed' must be keyed by argument ids") from None


def _not_json(name: str) -> None:
    raise ValueError(f"{name} is not JSON")


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return f"signal {number}"


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 120 else text[:117] + "..."

"""The program that runs a student's answer cell, inside the jail: ``python -I -S runner.py``.

It is the only code of scanviz in the jailed process, with `wire` beside it
and the trace events (``scanviz.trace.events``): no reference algorithm, no
grader, no key, no case but the arguments of the call at hand. It sets its
resource limits, says ``ready``, then answers requests, one JSON line each
way on the two file descriptors the grader passed (named in its first argument):

- ``{"n": k, "load": {"id", "name", "source"}}``: run the answer cell in a
  fresh namespace and find the function ``name`` in it; the reply is
  ``{"n": k, "loaded": true}`` or ``{"n": k, "failed": why, "message": text}``
  (why: ``"syntax"``, ``"raised"`` or ``"undefined"``).
- ``{"n": k, "call": {"args", "kwargs", "tracer", "kinds"}}``: call it; the
  reply has what it ``returned`` (or the text of what it ``raised``), the
  state of every argument it ``changed``, and, if a tracer was passed
  (``tracer``: its position among the arguments), the ``events`` it emitted.
- ``{"n": k, "batch": [call, ...]}``: several independent calls, one reply
  holding a list of call replies.

Everything is plain JSON (`wire`). Whatever the answer prints goes to fds 1
and 2, which the grader captured. Nothing here is trusted by the grader:
the answer can rewrite this process, so the grader checks every reply and
takes from it only what an answer could return anyway.
"""

from __future__ import annotations

import json
import os
import resource
import signal
import sys
import traceback

sys.path[:0] = [os.path.dirname(os.path.abspath(__file__))] + sys.argv[2:]

import wire  # noqa: E402 - the jail's own copy, beside this file

EVENT_LIMIT_DEFAULT = 100_000
MESSAGE_TEXT = 2000  # characters of an exception's message kept


class TooManyEvents(Exception):
    """The answer emitted more events than a case may."""


class JailTracer:
    """The tracer an answer's loop is given: it keeps what is emitted, up to a limit."""

    def __init__(self, kinds: list | None, limit: int) -> None:
        self.kinds = None if kinds is None else frozenset(kinds)
        self.limit = limit
        self.events: list = []
        self.overflow = False

    def wants(self, kind: str, *, polygon: int | None = None, y: int | None = None) -> bool:
        return self.kinds is None or kind in self.kinds

    def emit(self, event: object) -> None:
        if len(self.events) >= self.limit:
            self.overflow = True
            raise TooManyEvents(f"more than {self.limit} events in one case")
        self.events.append(event)


def raised_text(error: BaseException, filename: str) -> str:
    """``ValueError: message (in span_rule, line 5)``: the error and the answer's innermost line."""
    frames = [f for f in traceback.extract_tb(error.__traceback__) if f.filename == filename]
    where = ""
    if frames:
        name = "" if frames[-1].name == "<module>" else f"in {frames[-1].name}, "
        where = f" ({name}line {frames[-1].lineno})"
    try:
        message = str(error)
    except Exception:  # a student's exception whose __str__ raises
        message = "(its message cannot be printed)"
    if len(message) > MESSAGE_TEXT:
        message = message[: MESSAGE_TEXT - 3] + "..."
    return f"{type(error).__name__}{': ' + message if message else ''}{where}"


class Runner:
    """One answer at a time: loaded from its source, called with decoded arguments."""

    def __init__(self, event_limit: int) -> None:
        self.function = None
        self.filename = "<answer>"
        self.event_limit = event_limit

    def load(self, request: dict) -> dict:
        self.function = None
        self.filename = f"<answer {request['id']}>"
        namespace = {"__name__": "__main__", "__builtins__": __builtins__}
        try:
            code = compile(request["source"], self.filename, "exec")
        except SyntaxError as error:
            text = (error.text or "").strip()
            shown = f": {text!r}" if text else ""
            return {"failed": "syntax", "message": f"line {error.lineno}: {error.msg}{shown}"}
        try:
            exec(code, namespace)  # noqa: S102 - the student's cell, in the jail
        except BaseException as error:  # SystemExit and KeyboardInterrupt too: the cell failed
            return {"failed": "raised", "message": raised_text(error, self.filename)}
        function = namespace.get(request["name"])
        if not callable(function):
            defined = sorted(
                k for k, v in namespace.items() if callable(v) and not k.startswith("__")
            )
            return {"failed": "undefined", "message": json.dumps(defined)}
        self.function = function
        return {"loaded": True}

    def call(self, request: dict) -> dict:
        decoder = wire.Decoder(make_record=wire.jail_record_class)
        args = list(decoder.decode(request["args"]))
        kwargs = decoder.decode(request["kwargs"])
        tracer = None
        if request.get("tracer") is not None:
            tracer = JailTracer(request.get("kinds"), int(request.get("limit") or self.event_limit))
            args.insert(request["tracer"], tracer)
        reply: dict = {}
        try:
            returned = self.function(*args, **kwargs)
            if type(returned).__name__ == "generator":  # a loop written with yield
                returned = list(returned)
        except BaseException as error:  # SystemExit too: an answer cannot end the runner
            reply["raised"] = raised_text(error, self.filename)
        else:
            arguments = {id(obj): k for k, obj in decoder.objects.items()}
            reply["returned"] = wire.Encoder(arguments=arguments).encode(returned)
        arguments = {id(obj): k for k, obj in decoder.objects.items()}
        encoder = wire.Encoder(arguments=arguments)
        changed = {}
        for k, obj in decoder.objects.items():
            state = encoder.state(obj)
            if state != decoder.states[k]:
                changed[str(k)] = state
        if changed:
            reply["changed"] = changed
        if tracer is not None:
            reply["events"] = [wire.encode(event) for event in tracer.events]
            reply["overflow"] = tracer.overflow
        return reply


def _limit(limits: dict) -> None:
    """The resource limits of this process (inherited by nothing: it cannot start processes)."""
    used = resource.getrusage(resource.RUSAGE_SELF)
    cpu = int(used.ru_utime + used.ru_stime + float(limits["cpu_seconds"])) + 1
    memory = int(limits["memory_mb"]) * 2**20
    for which, value in (
        (resource.RLIMIT_CPU, (cpu, cpu + 2)),  # SIGXCPU, then SIGKILL two seconds later
        (resource.RLIMIT_AS, (memory, memory)),
        (resource.RLIMIT_FSIZE, (int(limits["file_bytes"]),) * 2),
        (resource.RLIMIT_NOFILE, (64, 64)),
        (resource.RLIMIT_NPROC, (16, 16)),  # the seccomp filter forbids new processes anyway
        (resource.RLIMIT_CORE, (0, 0)),
    ):
        resource.setrlimit(which, value)
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails instead


def load_filter(program: bytes) -> None:
    """Load the system-call filter into this process for good (where bubblewrap did not)."""
    import ctypes

    class Program(ctypes.Structure):  # struct sock_fprog
        _fields_ = [("len", ctypes.c_ushort), ("filter", ctypes.c_char_p)]

    libc = ctypes.CDLL(None, use_errno=True)
    code = ctypes.create_string_buffer(program, len(program))
    fprog = Program(len(program) // 8, ctypes.cast(code, ctypes.c_char_p))
    pr_set_no_new_privs, pr_set_seccomp, seccomp_mode_filter = 38, 22, 2
    if libc.prctl(pr_set_no_new_privs, 1, 0, 0, 0) or libc.prctl(
        pr_set_seccomp, seccomp_mode_filter, ctypes.byref(fprog), 0, 0
    ):
        raise OSError(ctypes.get_errno(), "the system-call filter cannot be loaded")


def main() -> None:
    limits = json.loads(sys.argv[1])
    requests = os.fdopen(int(limits["requests"]), "rb")
    replies = os.fdopen(int(limits["replies"]), "w", encoding="utf-8")
    _limit(limits)
    if "seccomp" in limits:
        load_filter(bytes.fromhex(limits["seccomp"]))
    runner = Runner(int(limits.get("event_limit", EVENT_LIMIT_DEFAULT)))

    def send(message: dict) -> None:
        replies.write(json.dumps(message) + "\n")
        replies.flush()

    send({"ready": True})
    for line in requests:
        request = json.loads(line)
        number = request.pop("n")
        if "load" in request:
            reply = runner.load(request["load"])
        elif "call" in request:
            reply = runner.call(request["call"])
        elif "batch" in request:
            reply = {"results": [runner.call(call) for call in request["batch"]]}
        else:
            return
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:  # the answer may have replaced or closed them
                pass
        send({"n": number, **reply})


if __name__ == "__main__":
    main()

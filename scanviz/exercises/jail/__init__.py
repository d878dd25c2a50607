"""The jail: where a student's answer runs, apart from the grader, the reference and the key.

The grader (`scanviz.exercises.grading`, and `check` in a notebook) owns the
algorithm, the tracer, the comparison, the cases and the key. The student's
answer cell runs in a separate process, the runner (`runner`), which sees
only Python's standard library, numpy and the trace events; on Linux with
bubblewrap it is jailed (`launch`: namespaces, a read-only view, no network,
no processes, resource limits). Every call of the answer crosses between the
two as plain JSON (`wire`), and the grader checks every reply (`session`).
"""

from .launch import JailUnavailable, unavailable
from .session import AnswerRaised, JailStopped, Limits, LoadFailed, RemoteAnswer, Session

__all__ = [
    "AnswerRaised",
    "JailStopped",
    "JailUnavailable",
    "Limits",
    "LoadFailed",
    "RemoteAnswer",
    "Session",
    "unavailable",
]

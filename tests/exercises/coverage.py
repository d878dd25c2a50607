"""Which lines of an exercise's step run on a set of cases (for the hidden cases' coverage test).

The step is the reference step of a step exercise (a function in scanviz) or,
for a loop exercise, the catalog's solution, compiled here. Lines are counted
with `sys.settrace` in the step's own code and the code nested in it.
"""

import dis
import inspect
import sys

from scanviz.exercises.core import compile_answer


def _code_lines(code) -> set[int]:
    lines = {line for _, line in dis.findlinestarts(code) if line is not None}
    for const in code.co_consts:
        if inspect.iscode(const):
            lines |= _code_lines(const)
    return lines


def step_lines(exercise):
    """(the lines of the step that must run, the function to run the cases with)."""
    if exercise.kind == "loop":
        function = compile_answer(exercise.solution, exercise.answer, "<solution>")
    else:
        function = exercise.reference
    code = inspect.unwrap(function).__code__
    lines = _code_lines(code) - {code.co_firstlineno}
    return lines, function


def lines_run(exercise, function, cases) -> set[int]:
    """The step's lines that ran while `function` answered `cases`."""
    code = inspect.unwrap(function).__code__
    filename, first = code.co_filename, code.co_firstlineno
    last = max(_code_lines(code))
    ran: set[int] = set()

    def tracer(frame, event, arg):
        if frame.f_code.co_filename != filename or not first <= frame.f_lineno <= last:
            return None
        if event == "line":
            ran.add(frame.f_lineno)
        return tracer

    from scanviz.trace import Recorder

    previous = sys.gettrace()
    sys.settrace(tracer)
    try:
        for case in cases:
            try:
                exercise.call(function, dict(case.inputs), Recorder(exercise.kinds))
            except Exception:
                pass
    finally:
        sys.settrace(previous)
    return ran

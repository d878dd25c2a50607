"""What grading produces: one `ExerciseGrade` per student and exercise, gathered per student.

The grader (`scanviz.exercises.grading`) fills these; the reports
(`scanviz.exercises.report`) only read them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .verdict import Verdict

STATUSES = {
    "passed": "every case passed",
    "failed": "some cases differ from the reference",
    "error": "the answer raised an exception",
    "timeout": "the answer ran out of time",
    "memory": "the answer ran out of memory",
    "too many events": "a case emitted far more events than the reference's (a loop that never ends?)",
    "no answer": "no cell starts with the exercise's answer marker",
    "not defined": "the answer cell does not define the function the exercise asks for",
    "syntax error": "the answer cell is not valid Python",
    "not allowed": "the process running the answer wrote something other than a reply on its "
    "channel to the grader",
    "crashed": "the process running the answer died",
    "malformed notebook": "the notebook file is not a readable notebook",
    "grader error": "the grader could not judge what the answer produced (a bug: please report it)",
}
"""Every status an exercise grade can have, with what it means."""


@dataclass
class ExerciseGrade:
    """One student's grade on one exercise."""

    student: str
    exercise: str
    score: float
    max_score: float
    status: str  # a key of STATUSES
    message: str = ""  # one line saying why, for every status but "passed" (and notes)
    verdicts: list[Verdict] = field(default_factory=list)  # public cases first, then hidden
    output: str = ""  # what the answer printed during its public cases

    @property
    def attempted(self) -> bool:
        """Whether the student answered (a class's pass rates count only those who did)."""
        return self.status not in ("no answer", "malformed notebook")

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(f"unknown grade status {self.status!r}; known: {sorted(STATUSES)}")

    @property
    def public_passed(self) -> tuple[int, int]:
        public = [v for v in self.verdicts if not v.hidden]
        return sum(v.passed for v in public), len(public)

    @property
    def hidden_passed(self) -> tuple[int, int]:
        hidden = [v for v in self.verdicts if v.hidden]
        return sum(v.passed for v in hidden), len(hidden)


@dataclass
class StudentGrade:
    """Every exercise grade of one submission (a notebook; the student id is its name)."""

    student: str
    notebook: str
    grades: list[ExerciseGrade] = field(default_factory=list)
    seconds: float = 0.0  # wall time grading took

    @property
    def score(self) -> float:
        return sum(g.score for g in self.grades)

    @property
    def max_score(self) -> float:
        return sum(g.max_score for g in self.grades)

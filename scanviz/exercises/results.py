"""What grading produces: one `ExerciseGrade` per student and exercise, gathered per student.

The grader (`scanviz.exercises.grading`) fills these; the reports
(`scanviz.exercises.report`) only read them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .core import Verdict

STATUSES = {
    "passed": "every case passed",
    "failed": "some cases differ from the reference",
    "error": "the answer raised an exception",
    "timeout": "the answer ran out of time",
    "memory": "the answer ran out of memory",
    "no answer": "no cell starts with the exercise's answer marker",
    "duplicate answer": "more than one cell starts with the exercise's answer marker",
    "not defined": "the answer cell does not define the function the exercise asks for",
    "syntax error": "the answer cell is not valid Python",
    "not allowed": "the answer uses the reference implementation, patches scanviz, "
    "exits the process or touches files outside its folder",
    "crashed": "the process running the answer died",
    "grader error": "the grader could not compare what the answer produced (a bug: please report it)",
    "malformed notebook": "the notebook file is not a readable notebook",
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
    message: str = ""  # one line saying why, for every status but "passed"
    verdicts: list[Verdict] = field(default_factory=list)  # public cases first, then hidden

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

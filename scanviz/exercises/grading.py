"""Grade a folder of student notebooks against the course key, or check one notebook.

`find_submissions` finds one notebook (or folder of notebooks) per student.
`grade_submissions` grades each in turn, `jobs` at once in separate judging
processes: for each exercise the answer cell runs in the student's jailed
runner (`scanviz.exercises.jail`; one per submission), and everything else
happens in the judging process -- the reference, the known-wrong variants,
the hidden cases from the key, the algorithm the answer is plugged into,
the comparison and the score (`scanviz.exercises.judging`). `check_notebook`
does the same with the public cases only (``python -m scanviz check``).

A class can be split across machines with one key: ``shard=(k, n)`` grades
the submissions whose student id hashes to part k of n, and
`scanviz.exercises.report.merge_reports` joins the parts.

Scores: an exercise's points times the fraction of its cases that pass
(public and hidden alike); the statuses of `judging.ZERO_STATUSES` score 0.
Nothing a submission does stops the batch, and the same key and the same
submissions give the same grades.
"""

from __future__ import annotations

import difflib
import hashlib
import multiprocessing
import os
import time
from collections.abc import Iterable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path

from ..progress import progress as progress_bar
from .catalog import exercises as catalog
from .catalog import get
from .core import Case, Exercise, hidden_cases
from .jail import JailStopped, JailUnavailable, Limits, Session, launch
from .judging import ZERO_STATUSES, References, judge_answer
from .key import CourseKey, load_key
from .notebook import (
    ANSWER_MARKER,
    Answers,
    NotebookError,
    find_answers,
    merge_answers,
    read_notebook,
)
from .results import ExerciseGrade, StudentGrade


def find_submissions(folder: str | os.PathLike) -> list[tuple[str, Path]]:
    """(student id, notebook) for every submission in `folder`, sorted by student id.

    A ``.ipynb`` file is one student (the id is the file's stem); a folder is
    one student (the id is its name) holding one notebook at any depth, so
    nbgrader's ``submitted/<student>/<assignment>/x.ipynb`` works, or several
    (the released notebooks, one per exercise): their answers are merged, and
    the folder is the path. Hidden entries and ``.ipynb_checkpoints`` are
    skipped; a folder with no notebook is graded "malformed notebook". If a
    file and a folder give the same id, the file keeps its full name as id.
    """
    root = Path(folder)
    if not root.is_dir():
        raise ValueError(f"'folder' must be a folder of submissions; {str(root)!r} is not one")
    found: dict[str, Path] = {}
    entries = sorted(p for p in root.iterdir() if not p.name.startswith("."))
    for entry in sorted(entries, key=lambda p: not p.is_dir()):  # folders first
        if entry.is_dir():
            notebooks = _notebooks(entry)
            found[entry.name] = notebooks[0] if len(notebooks) == 1 else entry  # merged
        elif entry.suffix == ".ipynb":
            found[entry.name if entry.stem in found else entry.stem] = entry
    return sorted(found.items())


def _notebooks(folder: Path) -> list[Path]:
    return sorted(
        path
        for path in folder.rglob("*.ipynb")
        if not any(part.startswith(".") for part in path.relative_to(folder).parts)
    )


def in_shard(student: str, shard: tuple[int, int]) -> bool:
    """Whether `student` is graded by part k of n (a hash of the id: the same on every machine).

    >>> sum(in_shard(f"s{i}", (1, 2)) for i in range(100)) + sum(in_shard(f"s{i}", (2, 2)) for i in range(100))
    100
    """
    part, parts = shard
    digest = hashlib.sha256(student.encode("utf-8", "surrogatepass")).digest()
    return int.from_bytes(digest[:8], "big") % parts == part - 1


@dataclass(frozen=True)
class Plan:
    """What grading needs, as plain values (each judging process makes its `Grader` from it)."""

    exercises: tuple[str, ...]
    points: dict[str, int]
    hidden: dict[str, int]
    secret: str
    per_student: bool
    limits: Limits
    jail: str  # one of scanviz.exercises.jail.launch.JAILS


class Grader:
    """Grades submissions one at a time; keeps the reference's outcomes of every case it met."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan
        self.exercises = [get(e) for e in plan.exercises]
        self.references = References()
        self._hidden: dict[tuple[str, str], list[Case]] = {}

    def cases(self, exercise: Exercise, student: str) -> list[tuple[Case, bool]]:
        """(case, hidden) of `exercise` for `student`: the public cases, then the hidden ones."""
        public = [(c, False) for c in exercise.public]
        count = self.plan.hidden.get(exercise.id, 0)
        if not count:
            return public
        who = student if self.plan.per_student else ""
        if (exercise.id, who) not in self._hidden:  # drawn once for a class (without per_student)
            self._hidden[exercise.id, who] = hidden_cases(exercise, self.plan.secret, count, who)
        return public + [(c, True) for c in self._hidden[exercise.id, who]]

    def grade(self, student: str, path: Path) -> StudentGrade:
        """One submission's grades, timed; nothing the submission holds or does raises."""
        started = time.perf_counter()
        grade = StudentGrade(student, path.name)
        answers, problem = _read_answers(path)
        if answers is None:
            grade.grades = [
                self._zero(student, e, "malformed notebook", problem) for e in self.exercises
            ]
        else:
            session = Session(self.plan.limits, jail=self.plan.jail)
            try:
                grade.grades = [
                    self._exercise(session, student, e, answers) for e in self.exercises
                ]
            finally:
                session.close()
        grade.seconds = time.perf_counter() - started
        return grade

    def _zero(self, student: str, exercise: Exercise, status: str, message: str) -> ExerciseGrade:
        points = float(self.plan.points[exercise.id])
        return ExerciseGrade(student, exercise.id, 0.0, points, status, message)

    def _exercise(
        self, session: Session, student: str, exercise: Exercise, answers: Answers
    ) -> ExerciseGrade:
        source = answers.answers.get(exercise.id)
        if source is None:
            problem = answers.problems.get(exercise.id)
            marker = ANSWER_MARKER + exercise.id
            return self._zero(
                student, exercise, "no answer", problem or f"no code cell starts with {marker!r}"
            )
        cases = self.cases(exercise, student)
        try:
            judged = judge_answer(
                session, exercise, source, cases, self.references, self.plan.limits.case_seconds
            )
        except JailStopped as stopped:  # the runner could not even start
            judged_status, message, runs, output = stopped.status, stopped.message, [], ""
        except Exception as error:  # a bug of the grader's: one grade, never the batch
            session.close()
            judged_status, runs, output = "grader error", [], ""
            message = f"the grader failed on this answer: {type(error).__name__}: {error}"
        else:
            judged_status, message, runs, output = (
                judged.status,
                judged.message,
                judged.runs,
                judged.output,
            )
        points = float(self.plan.points[exercise.id])
        passed = sum(r.verdict.passed for r in runs)
        zero = judged_status in ZERO_STATUSES or not cases
        score = 0.0 if zero else points * passed / len(cases)
        note = answers.notes.get(exercise.id)
        if note:
            message = f"{message} ({note})" if message else note
        return ExerciseGrade(
            student,
            exercise.id,
            score,
            points,
            judged_status,
            message,
            [r.verdict for r in runs],
            output,
        )


def _read_answers(path: Path) -> tuple[Answers | None, str]:
    """(answers, problem) of a submission: one notebook, or a folder whose notebooks are merged.

    A folder's unreadable notebook spoils the whole submission only if it is
    its only one; otherwise it is skipped and named in the problem.
    """
    notebooks = [path] if path.is_file() else _notebooks(path)
    if not notebooks:
        return None, f"the folder {path.name!r} holds no notebook"
    parts, unreadable = [], []
    for notebook in notebooks:
        try:
            parts.append((notebook.name, find_answers(read_notebook(notebook))))
        except NotebookError as error:
            unreadable.append(str(error))
    if not parts:
        return None, "; ".join(unreadable)
    return merge_answers(parts), "; ".join(unreadable)


def _chosen(key: CourseKey, exercises: Iterable[str] | None) -> list[Exercise]:
    ids = list(key.exercises) if exercises is None else list(exercises)
    for exercise_id in ids:
        if exercise_id not in key.exercises:
            close = difflib.get_close_matches(exercise_id, key.exercises, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(
                f"'exercises': {exercise_id!r} is not in the course key{hint}; "
                f"the key has {sorted(key.exercises)}"
            )
    order = {e.id: k for k, e in enumerate(catalog())}
    return [get(e) for e in sorted(set(ids), key=order.__getitem__)]


def jail_or_refuse(jail: str, *private: str | os.PathLike) -> str:
    """The jail grading will use (``"auto"``: bubblewrap if it starts, else the user jail), or
    a refusal: `JailUnavailable` if it cannot start (saying why and that ``--no-jail``
    exists for submissions one trusts), ValueError if a jailed answer could read one of the
    `private` paths (the key, the submissions) or the reference."""
    if jail not in (*launch.JAILS, "auto"):
        raise ValueError(f"'jail' must be one of {(*launch.JAILS, 'auto')}; got {jail!r}")
    if jail == "none":
        return jail
    tried = ("bwrap", "user") if jail == "auto" else (jail,)
    reasons = {name: launch.unavailable(name) for name in tried}
    chosen = next((name for name in tried if reasons[name] is None), None)
    if chosen is None:
        why = "; ".join(f"{name}: {reason}" for name, reason in reasons.items())
        raise JailUnavailable(
            f"grading runs each answer in a jail, which cannot start here ({why}). "
            "Pass --no-jail only for submissions you trust"
        )
    for path in private:
        if chosen == "bwrap" and launch.visible(path):
            raise ValueError(
                f"{os.fspath(path)!r} lies inside what the jail shows of this machine "
                "(the system's and Python's folders): move it elsewhere"
            )
    if chosen == "user":
        for path in [*private, launch.reference_file()]:
            if launch.readable_by_nobody(path):
                raise ValueError(
                    f"the 'user' jail runs answers as the user nobody, who can read "
                    f"{os.fspath(path)!r}: close it to others (chmod o-rwx on it or a folder above)"
                )
    return chosen


_GRADER: Grader | None = None  # the judging process's grader


def _start_judge(plan: Plan) -> None:
    global _GRADER
    _GRADER = Grader(plan)


def _judge(submission: tuple[str, Path]) -> StudentGrade:
    return _GRADER.grade(*submission)


def grade_submissions(
    folder: str | os.PathLike,
    key: CourseKey | str | os.PathLike,
    *,
    jobs: int = 1,
    exercises: Iterable[str] | None = None,
    progress: bool = True,
    shard: tuple[int, int] | None = None,
    jail: str = "bwrap",
) -> list[StudentGrade]:
    """Grade every submission in `folder` (see `find_submissions`) with the course `key`.

    `jobs` submissions are graded at once, each in a judging process of its
    own; `exercises` restricts the grading to some of the key's exercises;
    `shard` = (k, n) grades only part k of n of the students (`in_shard`);
    `progress` shows a bar over the students. The answers run in `jail`
    (``"bwrap"``, ``"user"``, ``"auto"`` for the first of the two that starts,
    or ``"none"``), and grading refuses to start if it cannot
    (`jail_or_refuse`). The result is in student order.
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"'jobs' must be an integer >= 1; got {jobs!r}")
    if shard is not None and not (
        isinstance(shard, tuple) and len(shard) == 2 and 1 <= shard[0] <= shard[1]
    ):
        raise ValueError(f"'shard' must be (k, n) with 1 <= k <= n; got {shard!r}")
    private = [folder] if isinstance(key, CourseKey) else [folder, key]
    key = key if isinstance(key, CourseKey) else load_key(key)
    jail = jail_or_refuse(jail, *private)
    chosen = _chosen(key, exercises)
    submissions = find_submissions(folder)
    if shard is not None:
        submissions = [s for s in submissions if in_shard(s[0], shard)]
    plan = Plan(
        tuple(e.id for e in chosen),
        {e.id: key.exercises[e.id].points for e in chosen},
        {e.id: key.exercises[e.id].hidden_cases for e in chosen},
        key.secret,
        key.per_student,
        Limits(key.cpu_seconds, key.memory_mb, key.case_seconds),
        jail,
    )
    with progress_bar(len(submissions), "students", enabled=progress) as bar:
        if jobs == 1 or len(submissions) <= 1:
            grader = Grader(plan)
            grades = []
            for submission in submissions:
                grades.append(grader.grade(*submission))
                bar.update(1)
            return grades
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(
            jobs, mp_context=context, initializer=_start_judge, initargs=(plan,)
        ) as pool:
            grades = []
            for grade in pool.map(_judge, submissions):
                grades.append(grade)
                bar.update(1)
            return grades


def check_notebook(
    path: str | os.PathLike,
    exercises: Iterable[str] | None = None,
    limits: Limits | None = None,
    jail: str | None = None,
) -> StudentGrade:
    """The public cases of `path`'s answers, as grading runs them (``python -m scanviz check``).

    `exercises` (ids) are checked, by default those the notebook has answer
    cells (or marker problems) for. The answers run in bubblewrap's jail where
    it starts (`jail` None), else in a plain runner (a student's own machine). A notebook that cannot be
    read raises `NotebookError`; the student id is the file's stem.
    """
    path = Path(path)
    answers = find_answers(read_notebook(path))
    known = {e.id for e in catalog()}
    ids = (
        list(exercises)
        if exercises is not None
        else [e for e in list(answers.answers) + list(answers.problems) if e in known]
    )
    chosen = [get(e) for e in dict.fromkeys(ids)]
    plan = Plan(
        tuple(e.id for e in chosen),
        {e.id: e.points for e in chosen},
        {},
        "",
        False,
        limits or Limits(),
        jail or ("bwrap" if launch.unavailable("bwrap") is None else "none"),
    )
    return Grader(plan).grade(path.stem, path)

"""Grade a folder of student notebooks against the course key, or check one notebook.

`find_submissions` finds one notebook per student; `grade_submissions` runs
each in the sandbox (`scanviz.exercises.sandbox`: a fresh subprocess per
submission that sees only the answer sources and the case inputs), computes
the reference and the known-wrong variants' outcomes here, in the grading
process, once per case, and judges every case. `check_notebook` does the
same with the public cases only (``python -m scanviz check``).

Scores: an exercise's points times the fraction of its cases that pass
(public and hidden alike). An answer that times out, runs out of memory,
does what is not allowed, crashes, is not valid Python or does not define the
function scores 0 with that status. Nothing a submission does stops the
batch. The same key and the same submissions give the same grades.
"""

from __future__ import annotations

import difflib
import json
import os
import threading
import time
from collections.abc import Iterable, Iterator, Mapping
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from ..progress import progress as progress_bar
from .catalog import exercises as catalog
from .catalog import get
from .core import (
    Case,
    Exercise,
    Outcome,
    Verdict,
    builtin_error_name,
    hidden_cases,
    judge,
    reference_outcome,
    variant_outcomes,
)
from .key import CourseKey, load_key
from .notebook import (
    ANSWER_MARKER,
    Answers,
    NotebookError,
    find_answers,
    merge_answers,
    read_notebook,
)
from .plain import from_plain, to_plain
from .results import ExerciseGrade, StudentGrade
from .sandbox import Limits, WorkerResult, run_submission

_ZERO_STATUSES = ("syntax error", "not defined", "timeout", "memory", "not allowed", "crashed")


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


class _References:
    """The reference's and the variants' outcomes of each case, computed once (thread-safe)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._references: dict[tuple[str, str], Outcome] = {}
        self._variants: dict[tuple[str, str], dict[str, Outcome]] = {}

    @staticmethod
    def _key(exercise: Exercise, case: Case) -> tuple[str, str]:
        return exercise.id, json.dumps(to_plain(dict(case.inputs)), sort_keys=True)

    def reference(self, exercise: Exercise, case: Case) -> Outcome:
        key = self._key(exercise, case)
        with self._lock:
            if key not in self._references:
                self._references[key] = reference_outcome(exercise, case)
            return self._references[key]

    def variants(self, exercise: Exercise, case: Case) -> dict[str, Outcome]:
        key = self._key(exercise, case)
        with self._lock:
            if key not in self._variants:
                self._variants[key] = variant_outcomes(exercise, case)
            return self._variants[key]


def _as_sent(case: Case) -> Case:
    """`case` with its inputs as the worker reads them (tuples become lists, ...)."""
    return Case(case.label, from_plain(to_plain(dict(case.inputs))), case.category)


def _error_message(verdicts: list[Verdict]) -> str:
    """What the answer raised, quoting a public case's error only (hidden inputs stay hidden)."""
    raised = [v for v in verdicts if v.error]
    public = next((v for v in raised if not v.hidden), None)
    if public is not None:
        return f"your code raised {public.error} (in {len(raised)} of {len(verdicts)} cases)"
    kind = builtin_error_name(raised[0].error) if raised else "an exception"
    return f"your code raised {kind} in {len(raised)} of {len(verdicts)} cases (hidden ones)"


class _Grader:
    """Everything one grading run shares: the exercises, the limits, the case cache."""

    def __init__(
        self,
        chosen: list[Exercise],
        points: dict[str, int],
        limits: Limits | CourseKey,
        hidden: dict[str, int],
        secret: str = "",
        per_student: bool = False,
    ) -> None:
        self.exercises = chosen
        self.points = points
        self.limits = limits
        self.hidden = hidden
        self.secret = secret
        self.per_student = per_student
        self.cache = _References()

    def cases(self, exercise: Exercise, student: str) -> list[tuple[Case, bool]]:
        """(case, hidden) of `exercise` for `student`: the public cases, then the hidden ones."""
        public = [(_as_sent(c), False) for c in exercise.public]
        count = self.hidden.get(exercise.id, 0)
        if not count:
            return public
        who = student if self.per_student else ""
        hidden = hidden_cases(exercise, self.secret, count, who)
        return public + [(_as_sent(c), True) for c in hidden]

    def grade(self, student: str, path: Path, folder: Path | None) -> StudentGrade:
        """One submission's grades, timed; nothing the submission holds or does raises."""
        started = time.perf_counter()
        grade = self._grade(student, path, folder)
        grade.seconds = time.perf_counter() - started
        return grade

    def _grade(self, student: str, path: Path, folder: Path | None) -> StudentGrade:
        grade = StudentGrade(student, str(path))
        answers, problem = _read_answers(path)
        if answers is None:
            grade.grades = [
                self._zero(student, e, "malformed notebook", problem) for e in self.exercises
            ]
            return grade
        cases = {e.id: self.cases(e, student) for e in self.exercises}
        try:
            ran = run_submission(
                answers, {k: [c for c, _ in v] for k, v in cases.items()}, self.limits, folder
            )
        except OSError as error:  # the machine, not the submission: no temporary folder, ...
            ran = {
                e: WorkerResult("crashed", f"the grader could not run it: {error}") for e in cases
            }
        for exercise in self.exercises:
            grade.grades.append(
                self._exercise(student, exercise, answers, cases[exercise.id], ran.get(exercise.id))
            )
        return grade

    def _zero(self, student: str, exercise: Exercise, status: str, message: str) -> ExerciseGrade:
        return ExerciseGrade(
            student, exercise.id, 0.0, float(self.points[exercise.id]), status, message
        )

    def _exercise(
        self,
        student: str,
        exercise: Exercise,
        answers: Answers,
        cases: list[tuple[Case, bool]],
        result: WorkerResult | None,
    ) -> ExerciseGrade:
        if result is None:
            problem = answers.problems.get(exercise.id)
            if exercise.id in answers.duplicated:
                return self._zero(student, exercise, "duplicate answer", problem)
            marker = ANSWER_MARKER + exercise.id
            return self._zero(
                student, exercise, "no answer", problem or f"no code cell starts with {marker!r}"
            )
        try:
            verdicts = [
                self._judge(exercise, case, hidden, outcome)
                for (case, hidden), outcome in zip(cases, result.outcomes, strict=False)
            ]
        except Exception as error:  # a worker that sent odd but well-formed data
            return self._zero(
                student, exercise, "grader error", f"its outcomes cannot be compared: {error}"
            )
        points = float(self.points[exercise.id])
        if result.status in _ZERO_STATUSES:
            grade = ExerciseGrade(student, exercise.id, 0.0, points, result.status, result.message)
            grade.verdicts = verdicts
            return grade
        passed = sum(v.passed for v in verdicts)
        score = points * passed / len(cases) if cases else 0.0
        if passed == len(cases):
            status, message = "passed", ""
        elif result.status == "error":
            status, message = "error", _error_message(verdicts)
        else:
            first = next((v for v in verdicts if not v.passed), None)
            status = "failed"
            message = f"{len(cases) - passed} of {len(cases)} cases differ from the reference"
            if first is not None and first.variant is not None:
                message += f"; likely cause: {first.variant.hint}"
        grade = ExerciseGrade(student, exercise.id, score, points, status, message)
        grade.verdicts = verdicts
        return grade

    def _judge(self, exercise: Exercise, case: Case, hidden: bool, outcome: Outcome):
        reference = self.cache.reference(exercise, case)
        variants = _LazyVariants(self.cache, exercise, case)
        return judge(exercise, case, outcome, reference, hidden=hidden, variants=variants)


class _LazyVariants(Mapping):
    """The variants' outcomes of a case, computed (once, in the cache) only if `judge` reads them:
    a case that passes never needs them."""

    def __init__(self, cache: _References, exercise: Exercise, case: Case) -> None:
        self.cache, self.exercise, self.case = cache, exercise, case

    def __len__(self) -> int:
        return len(self.exercise.variants)

    def __iter__(self) -> Iterator[str]:
        return iter(self.cache.variants(self.exercise, self.case))

    def __getitem__(self, name: str) -> Outcome:
        return self.cache.variants(self.exercise, self.case)[name]


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


def grade_submissions(
    folder: str | os.PathLike,
    key: CourseKey | str | os.PathLike,
    *,
    jobs: int = 1,
    exercises: Iterable[str] | None = None,
    progress: bool = True,
) -> list[StudentGrade]:
    """Grade every submission in `folder` (see `find_submissions`) with the course `key`.

    `jobs` submissions run at once (each in its own worker process);
    `exercises` restricts the grading to some of the key's exercises;
    `progress` shows a bar over the students. The result is in student order.
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"'jobs' must be an integer >= 1; got {jobs!r}")
    key = key if isinstance(key, CourseKey) else load_key(key)
    chosen = _chosen(key, exercises)
    submissions = find_submissions(folder)
    grader = _Grader(
        chosen,
        {e.id: key.exercises[e.id].points for e in chosen},
        key,
        {e.id: key.exercises[e.id].hidden_cases for e in chosen},
        key.secret,
        key.per_student,
    )

    def grade_one(submission: tuple[str, Path]) -> StudentGrade:
        student, path = submission
        top = Path(folder) / path.relative_to(folder).parts[0]  # the student's folder or file
        return grader.grade(student, path, top)

    with progress_bar(len(submissions), "students", enabled=progress) as bar:
        with ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(grade_one, s) for s in submissions]
            grades = []
            for future in futures:
                grades.append(future.result())
                bar.update(1)
    return grades


def check_notebook(
    path: str | os.PathLike, exercises: Iterable[str] | None = None, limits: Limits | None = None
) -> StudentGrade:
    """The public cases of `path`'s answers, in the sandbox (``python -m scanviz check``).

    `exercises` (ids) are checked, by default those the notebook has answer
    cells (or marker problems) for. A notebook that cannot be read raises
    `NotebookError`; the student id is the file's stem.
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
    grader = _Grader(chosen, {e.id: e.points for e in chosen}, limits or Limits(), {})
    return grader.grade(path.stem, path, path.parent)

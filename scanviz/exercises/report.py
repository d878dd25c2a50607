"""The reports of a graded class: grades.csv, feedback per student, Gradescope JSON, class summary.

`write_reports(grades, key, out_dir)` writes into ``out_dir``:

- ``grades.csv``: one row per student and exercise, with the columns
  ``student, exercise, score, max_score, status``;
- ``<student>/feedback.html`` and ``<student>/feedback.md``: per exercise the
  score, the status, how many public and hidden cases passed, every case's
  diagnostics, the raster diff images (HTML only) and the likely cause;
- ``<student>/results.json``: Gradescope's autograder results (two tests per
  exercise: its public cases, visible, and its hidden cases, shown after the
  grades are published);
- ``summary.txt`` and ``summary.html``: per exercise the pass rate, the mean
  score, the most common first divergence and the most common known-wrong
  variant, with a plot in the HTML.

What a student's code produced (messages, diagnostics, what it printed) and
the student ids are untrusted text: HTML escapes it, Markdown fences or
backslash-escapes it, and a CSV cell that a spreadsheet would read as a
formula (``=``, ``+``, ``-``, ``@``) is quoted with a leading ``'``. A hidden
case's inputs are shown only when the key's ``reveal`` is ``"always"``.
Otherwise a failed hidden case is reported by its category, where it first
differs, the counts and the likely cause -- no values, no raster, and no
error message, which a student's code could fill with the inputs it was
given (`case_report`); grade messages quote public cases only, and the
printed output shown is that of the public cases.

``grades.json`` holds what the class summary and ``grades.csv`` need;
`merge_reports` joins the folders of a class graded in shards
(``grade --shard K/N``) into one, as if it had been graded at once.

Student ids come from file names, so a student's folder is a sanitized
copy of the id (`folder_names`): only letters, digits, ``.``, ``_`` and
``-`` are kept (others become ``_``), leading dots go, and a clash gets a
``-2``, ``-3``, ... suffix. ``grades.csv`` keeps the ids as they are.
"""

from __future__ import annotations

import base64
import csv
import dataclasses
import html
import io
import json
import re
import shutil
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..limits import read_bounded
from .catalog import exercises
from .compare import RasterDifference
from .display import raster_html
from .key import CourseKey
from .results import STATUSES, ExerciseGrade, StudentGrade
from .verdict import Verdict

CSV_COLUMNS = ("student", "exercise", "score", "max_score", "status")
PRINTED = "What your code printed during the public cases:"
FOLDER_LENGTH = 80  # longest folder name made from a student id
_UNSAFE = re.compile(r"[^A-Za-z0-9._-]")

_STYLE = (
    "body{font-family:system-ui,sans-serif;max-width:60em;margin:1em auto;padding:0 1em}"
    "pre{background:#f6f6f6;padding:.5em;overflow-x:auto;white-space:pre-wrap}"
    "img.raster{max-width:100%}"
    "table{border-collapse:collapse}td,th{padding:2px 8px;text-align:left;vertical-align:top}"
    ".passed{color:#2e7d32}.failed{color:#c62828}"
)


def folder_names(students: Iterable[str]) -> list[str]:
    """A safe folder name for each student id, all different (see the module docstring).

    >>> folder_names(["alice", "../bob", "a/b", "a\\\\b", "", "Alice"])
    ['alice', '_bob', 'a_b', 'a_b-2', 'student', 'Alice-2']
    """
    names: list[str] = []
    taken: set[str] = set()
    for student in students:
        base = _UNSAFE.sub("_", student).lstrip(".")[:FOLDER_LENGTH] or "student"
        name, suffix = base, 2
        while name.lower() in taken:  # case-insensitive file systems
            name, suffix = f"{base}-{suffix}", suffix + 1
        taken.add(name.lower())
        names.append(name)
    return names


def points(value: float) -> str:
    """Points as written in the reports: at most 4 decimals, no trailing zeros.

    >>> points(4.0), points(1.6), points(4 * 2 / 3)
    ('4', '1.6', '2.6667')
    """
    return f"{round(value, 4):g}"


# --- one case -------------------------------------------------------------------------------


@dataclass(frozen=True)
class CaseReport:
    """One case as a report shows it: its text and, if shown, its raster diff."""

    verdict: Verdict
    text: str
    raster: RasterDifference | None  # drawn on its pixel grid with the case's outline


def case_report(verdict: Verdict, reveal: bool) -> CaseReport:
    """How `verdict` is shown: in full, or redacted for a hidden case if not `reveal`."""
    if verdict.hidden and not reveal and not verdict.passed:
        return CaseReport(verdict, verdict.describe(reveal=False), None)
    return CaseReport(verdict, verdict.describe(reveal=reveal), verdict.raster)


# --- one exercise ---------------------------------------------------------------------------


def _titles() -> dict[str, str]:
    return {e.id: f"{e.number:02d} {e.id} -- {e.title}" for e in exercises()}


def _counts(grade: ExerciseGrade) -> str:
    public, hidden = grade.public_passed, grade.hidden_passed
    return f"public cases {public[0]} of {public[1]}, hidden cases {hidden[0]} of {hidden[1]}"


def _status_line(grade: ExerciseGrade) -> str:
    line = f"{points(grade.score)} of {points(grade.max_score)} points -- {grade.status}"
    if grade.status != "passed":
        line += f": {STATUSES[grade.status]}"
    return line


def _fenced(text: str) -> str:
    """`text` as a Markdown code block no backtick run inside it can close."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, longest + 1)
    return f"{fence}\n{text}\n{fence}"


def _exercise_markdown(grade: ExerciseGrade, title: str, reveal: bool) -> str:
    parts = [f"## {title}", _status_line(grade)]
    if grade.message:
        parts.append(_fenced(grade.message))
    if grade.verdicts:
        parts.append(_counts(grade))
        parts.extend(_fenced(case_report(v, reveal).text) for v in grade.verdicts)
    if grade.output:
        parts += [PRINTED, _fenced(grade.output)]
    return "\n\n".join(parts)


def _exercise_html(grade: ExerciseGrade, title: str, reveal: bool) -> str:
    mark = "passed" if grade.status == "passed" else "failed"
    parts = [
        f"<section id='{html.escape(grade.exercise)}'><h2>{html.escape(title)}</h2>",
        f"<p class='{mark}'><b>{html.escape(_status_line(grade))}</b></p>",
    ]
    if grade.message:
        parts.append(f"<pre>{html.escape(grade.message)}</pre>")
    if grade.verdicts:
        parts.append(f"<p>{html.escape(_counts(grade))}</p>")
    for verdict in grade.verdicts:
        report = case_report(verdict, reveal)
        parts.append(f"<pre>{html.escape(report.text)}</pre>")
        if report.raster is not None:
            parts.append(f"<p>{raster_html(report.raster, verdict.case.inputs)}</p>")
    if grade.output:
        parts.append(f"<p>{PRINTED}</p><pre>{html.escape(grade.output)}</pre>")
    parts.append("</section>")
    return "\n".join(parts)


def _page(title: str, body: str) -> str:
    return (
        "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
        f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head>\n"
        f"<body>\n{body}\n</body></html>\n"
    )


def _student_headline(student: StudentGrade) -> str:
    return (
        f"{points(student.score)} of {points(student.max_score)} points "
        f"(notebook {student.notebook})"
    )


def _markdown_text(text: str) -> str:
    """Untrusted `text` as literal Markdown: punctuation and HTML characters backslash-escaped."""
    return re.sub(r"([\\`*_{}\[\]()#+\-.!|<>&~])", r"\\\1", text)


def _overview_markdown(student: StudentGrade) -> str:
    """The student's total, then a line per exercise."""
    lines = [
        f"- {g.exercise}: {points(g.score)} of {points(g.max_score)} ({g.status})"
        for g in student.grades
    ]
    return f"{_markdown_text(_student_headline(student))}\n\n" + "\n".join(lines)


def feedback_markdown(student: StudentGrade, reveal: bool) -> str:
    """A student's feedback as Markdown (the text of feedback.html, without images)."""
    titles = _titles()
    sections = [
        _exercise_markdown(g, titles.get(g.exercise, g.exercise), reveal) for g in student.grades
    ]
    head = f"# Feedback for {_markdown_text(student.student)}\n\n{_overview_markdown(student)}"
    return "\n\n".join([head, *sections]) + "\n"


def _overview_html(student: StudentGrade) -> str:
    rows = "".join(
        f"<tr><td><a href='#{html.escape(g.exercise)}'>{html.escape(g.exercise)}</a></td>"
        f"<td>{points(g.score)} of {points(g.max_score)}</td><td>{html.escape(g.status)}</td></tr>"
        for g in student.grades
    )
    return f"<table><tr><th>exercise</th><th>points</th><th>status</th></tr>{rows}</table>"


def feedback_html(student: StudentGrade, reveal: bool) -> str:
    """A student's feedback as one self-contained HTML page (images inline)."""
    titles = _titles()
    body = [
        f"<h1>Feedback for {html.escape(student.student)}</h1>",
        f"<p>{html.escape(_student_headline(student))}</p>",
        _overview_html(student),
        "<p>Raster images: grey matched, vermillion + extra (yours only), blue − missing "
        "(reference only); the case's outline in black.</p>",
        *(_exercise_html(g, titles.get(g.exercise, g.exercise), reveal) for g in student.grades),
    ]
    return _page(f"Feedback for {student.student}", "\n".join(body))


# --- Gradescope -----------------------------------------------------------------------------


def _test(name: str, score: float, max_score: float, passed: bool, output: str, visible: bool):
    return {
        "name": name,
        "score": score,
        "max_score": max_score,
        "status": "passed" if passed else "failed",
        "output": output,
        "output_format": "md",
        "visibility": "visible" if visible else "after_published",
    }


def gradescope_tests(grade: ExerciseGrade, reveal: bool) -> list[dict]:
    """The Gradescope tests of one exercise grade: its public cases, then its hidden cases.

    The exercise's score is split between the two in proportion to the cases
    each passed (its maximum in proportion to their numbers), so the tests
    add up to the exercise's score and maximum. The hidden cases' test is
    shown after the grades are published, unless the key reveals them. A
    grade with no cases run (no answer, a syntax error, ...) is one test.
    """
    if not grade.verdicts:
        output = _fenced(f"{STATUSES[grade.status]}\n{grade.message}".rstrip())
        name = f"{grade.exercise}: {grade.status}"
        return [_test(name, grade.score, grade.max_score, grade.status == "passed", output, True)]
    ran = grade.status in ("passed", "failed", "error")  # any other status scores 0 regardless
    public = [v for v in grade.verdicts if not v.hidden]
    hidden = [v for v in grade.verdicts if v.hidden]
    passed = sum(v.passed for v in grade.verdicts)
    public_score = grade.score * sum(v.passed for v in public) / passed if passed else 0.0
    public_max = grade.max_score * len(public) / len(grade.verdicts)
    parts = [
        ("public", public, public_score, public_max, True),
        ("hidden", hidden, grade.score - public_score, grade.max_score - public_max, reveal),
    ]
    tests = []
    for which, verdicts, score, max_score, visible in parts:
        if verdicts:
            won = sum(v.passed for v in verdicts)
            name = f"{grade.exercise}: {which} cases ({won} of {len(verdicts)})"
            output = "\n\n".join(_fenced(case_report(v, reveal).text) for v in verdicts)
            ok = ran and won == len(verdicts)
            tests.append(_test(name, score, max_score, ok, output, visible))
    if grade.message:
        tests[0]["output"] = _fenced(grade.message) + "\n\n" + tests[0]["output"]
    if grade.output:
        tests[0]["output"] += f"\n\n{PRINTED}\n\n{_fenced(grade.output)}"
    return tests


def gradescope_results(student: StudentGrade, reveal: bool, execution_time: float = 0.0) -> dict:
    """A student's ``results.json`` in Gradescope's autograder format.

    `execution_time` is the seconds grading took, 0 when unknown.
    """
    return {
        "score": student.score,
        "execution_time": execution_time,
        "output": _overview_markdown(student),
        "output_format": "md",
        "tests": [test for g in student.grades for test in gradescope_tests(g, reveal)],
    }


# --- the class ------------------------------------------------------------------------------


@dataclass(frozen=True)
class GradeRow:
    """What the class summary and grades.csv read of one exercise grade (also grades.json's rows).

    ``divergence`` and ``variant``: the most common first divergence
    (`Verdict.signature`) and known-wrong variant among its failed cases.
    """

    student: str
    exercise: str
    score: float
    max_score: float
    status: str
    attempted: bool
    divergence: str | None
    variant: str | None


def grade_rows(grades: list[StudentGrade]) -> list[GradeRow]:
    """One row per student and exercise, in order."""
    rows = []
    for student in grades:
        for g in student.grades:
            failed = [v for v in g.verdicts if not v.passed]
            rows.append(
                GradeRow(
                    student.student,
                    g.exercise,
                    g.score,
                    g.max_score,
                    g.status,
                    g.attempted,
                    _mode([v.signature for v in failed]),
                    _mode([v.variant.name for v in failed if v.variant]),
                )
            )
    return rows


@dataclass(frozen=True)
class ExerciseSummary:
    """One exercise across the class.

    Rates and means are over the students who `attempted` it (an answer cell
    was found); ``students`` counts everyone. ``divergence`` and ``variant``
    are (what, students): each student counts once, with their most common
    first divergence or known-wrong variant.
    """

    exercise: str
    students: int
    attempted: int
    passed: int  # students with every case passed
    mean_score: float  # over those who attempted it
    max_score: float
    statuses: dict[str, int]
    divergence: tuple[str, int] | None
    variant: tuple[str, int] | None

    @property
    def pass_rate(self) -> float:
        return self.passed / self.attempted if self.attempted else 0.0


def _most_common(items: list[str | None]) -> tuple[str, int] | None:
    counts = Counter(item for item in items if item)
    return counts.most_common(1)[0] if counts else None


def _mode(items: list[str]) -> str | None:
    return Counter(items).most_common(1)[0][0] if items else None


def class_summary(rows: list[GradeRow]) -> list[ExerciseSummary]:
    """Every exercise's summary across the class, in the order the exercises first appear."""
    by_exercise: dict[str, list[GradeRow]] = {}
    for row in rows:
        by_exercise.setdefault(row.exercise, []).append(row)
    summaries = []
    for exercise, items in by_exercise.items():
        tried = [r for r in items if r.attempted]
        summaries.append(
            ExerciseSummary(
                exercise,
                len(items),
                len(tried),
                sum(r.status == "passed" for r in tried),
                sum(r.score for r in tried) / len(tried) if tried else 0.0,
                max(r.max_score for r in items),
                dict(Counter(r.status for r in items).most_common()),
                _most_common([r.divergence for r in tried]),
                _most_common([r.variant for r in tried]),
            )
        )
    return summaries


def _totals(rows: list[GradeRow]) -> dict[str, tuple[float, float]]:
    totals: dict[str, tuple[float, float]] = {}
    for row in rows:
        score, best = totals.get(row.student, (0.0, 0.0))
        totals[row.student] = (score + row.score, best + row.max_score)
    return totals


def summary_line(rows: list[GradeRow]) -> str:
    """One line about the class: students, mean total, full marks."""
    totals = _totals(rows)
    if not totals:
        return "no submissions graded"
    mean = sum(score for score, _ in totals.values()) / len(totals)
    best = max(best for _, best in totals.values())
    full = sum(score >= best > 0 for score, best in totals.values())
    share = f" ({mean / best:.0%})" if best else ""
    return (
        f"{len(totals)} students: mean {points(mean)} of {points(best)} points{share}, "
        f"{full} with full marks"
    )


def _of(count_of: tuple[str, int] | None, students: int) -> str:
    return "none" if count_of is None else f"{count_of[1]} of {students}: {count_of[0]}"


def _tried(s: ExerciseSummary) -> str:
    missing = s.students - s.attempted
    return f" ({missing} did not answer it)" if missing else ""


def summary_text(rows: list[GradeRow]) -> str:
    """The class summary as plain text."""
    lines = [f"Class summary -- {summary_line(rows)}", ""]
    for s in class_summary(rows):
        statuses = ", ".join(f"{status} {n}" for status, n in s.statuses.items())
        lines += [
            f"{s.exercise}: passed {s.passed} of {s.attempted} who answered it "
            f"({s.pass_rate:.0%}){_tried(s)}, mean score {points(s.mean_score)} of "
            f"{points(s.max_score)}",
            f"  statuses: {statuses}",
            f"  most common first divergence: {_of(s.divergence, s.attempted)}",
            f"  most common known-wrong variant: {_of(s.variant, s.attempted)}",
        ]
    return "\n".join(lines) + "\n"


def summary_plot(summaries: list[ExerciseSummary]) -> bytes:
    """PNG bytes of a bar chart: per exercise the pass rate and the mean score (% of points)."""
    from matplotlib.figure import Figure

    figure = Figure(figsize=(7, 1.5 + 0.45 * max(len(summaries), 1)), layout="constrained")
    axes = figure.add_subplot()
    rows = np.arange(len(summaries))
    rates = [100 * s.pass_rate for s in summaries]
    means = [100 * s.mean_score / s.max_score if s.max_score else 0.0 for s in summaries]
    axes.barh(
        rows - 0.2, rates, height=0.4, label="passed, of those who answered (%)", color="#2e7d32"
    )
    axes.barh(rows + 0.2, means, height=0.4, label="mean score (% of points)", color="#1565c0")
    axes.set_yticks(rows, [s.exercise for s in summaries])
    axes.invert_yaxis()
    axes.set_xlim(0, 100)
    axes.set_xlabel("percent")
    figure.legend(loc="outside upper center", ncols=2, fontsize="small")
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100)
    return buffer.getvalue()


def summary_html(rows: list[GradeRow]) -> str:
    """The class summary as one self-contained HTML page, with the plot inline."""
    summaries = class_summary(rows)
    plot = base64.b64encode(summary_plot(summaries)).decode("ascii")
    table = "\n".join(
        "<tr>"
        + "".join(
            f"<td>{html.escape(cell)}</td>"
            for cell in (
                s.exercise,
                f"{s.passed} of {s.attempted} ({s.pass_rate:.0%}){_tried(s)}",
                f"{points(s.mean_score)} of {points(s.max_score)}",
                ", ".join(f"{status} {n}" for status, n in s.statuses.items()),
                _of(s.divergence, s.attempted),
                _of(s.variant, s.attempted),
            )
        )
        + "</tr>"
        for s in summaries
    )
    body = (
        f"<h1>Class summary</h1><p>{html.escape(summary_line(rows))}</p>\n"
        f"<p><img alt='pass rate and mean score per exercise' src='data:image/png;base64,{plot}'>"
        "</p>\n<table><tr><th>exercise</th><th>passed, of those who answered</th>"
        "<th>mean score</th><th>statuses</th><th>most common first divergence</th>"
        f"<th>most common known-wrong variant</th></tr>\n{table}\n</table>"
    )
    return _page("Class summary", body)


# --- writing --------------------------------------------------------------------------------


def csv_cell(text: str) -> str:
    """`text` as a CSV cell no spreadsheet runs as a formula (OWASP's rule: a leading quote).

    >>> csv_cell("=HYPERLINK(1)"), csv_cell("ann")
    ("'=HYPERLINK(1)", 'ann')
    """
    return f"'{text}" if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def write_grades_csv(rows: list[GradeRow], path: Path) -> None:
    """``grades.csv``: one row per student and exercise (`CSV_COLUMNS`)."""
    with open(path, "w", newline="", encoding="utf-8") as file:
        writer = csv.writer(file)
        writer.writerow(CSV_COLUMNS)
        writer.writerows(
            (csv_cell(r.student), r.exercise, points(r.score), points(r.max_score), r.status)
            for r in rows
        )


def output_folder(out_dir: str | Path) -> Path:
    """`out_dir` as a Path; NotADirectoryError if it exists and is not a folder."""
    out_dir = Path(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise NotADirectoryError(f"OUT_DIR {str(out_dir)!r} exists and is not a folder")
    return out_dir


def _write_class(rows: list[GradeRow], out_dir: Path) -> None:
    write_grades_csv(rows, out_dir / "grades.csv")
    data = {"format": "scanviz grades 1", "rows": [dataclasses.asdict(r) for r in rows]}
    (out_dir / "grades.json").write_text(json.dumps(data, indent=1), encoding="utf-8")
    (out_dir / "summary.txt").write_text(summary_text(rows), encoding="utf-8")
    (out_dir / "summary.html").write_text(summary_html(rows), encoding="utf-8")


def write_reports(grades: list[StudentGrade], key: CourseKey, out_dir: str | Path) -> None:
    """Write every report of a graded class into `out_dir` (see the module docstring).

    Parameters
    ----------
    grades : list of StudentGrade
        What `scanviz.exercises.grading.grade_submissions` returned.
    key : CourseKey
        The course key; its ``reveal`` says whether hidden inputs are shown.
    out_dir : str or Path
        Created if needed; files already there are overwritten.
    """
    out_dir = output_folder(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    reveal = key.reveal == "always"
    for student, name in zip(grades, folder_names(s.student for s in grades), strict=True):
        folder = out_dir / name
        folder.mkdir(exist_ok=True)
        (folder / "feedback.html").write_text(feedback_html(student, reveal), encoding="utf-8")
        (folder / "feedback.md").write_text(feedback_markdown(student, reveal), encoding="utf-8")
        results = gradescope_results(student, reveal, student.seconds)
        (folder / "results.json").write_text(json.dumps(results, indent=1), encoding="utf-8")
    _write_class(grade_rows(grades), out_dir)


def read_rows(folder: str | Path) -> list[GradeRow]:
    """The rows of a graded folder's ``grades.json``; ValueError if it has none or it is not one."""
    path = Path(folder) / "grades.json"
    try:
        data = json.loads(read_bounded(path))
        if data.get("format") != "scanviz grades 1":
            raise ValueError("it is not a scanviz grades file")
        return [GradeRow(**row) for row in data["rows"]]
    except (OSError, ValueError, TypeError, KeyError, AttributeError) as error:
        raise ValueError(
            f"{str(path)!r} cannot be read as a graded folder's grades: {error}"
        ) from None


def merge_reports(parts: list[str | Path], out_dir: str | Path) -> list[GradeRow]:
    """Join folders graded in shards into `out_dir`, as one grading of the whole class writes it.

    Each part's student folders are copied (renamed where two parts gave the
    same folder name); grades.csv, grades.json and the summary are written
    for the whole class, students in id order. A student in two parts is an
    error (the parts overlap).
    """
    out_dir = output_folder(out_dir)
    students: dict[str, tuple[Path, str, list[GradeRow]]] = {}
    for part in map(Path, parts):
        rows = read_rows(part)
        ids = list(dict.fromkeys(r.student for r in rows))
        for student, name in zip(ids, folder_names(ids), strict=True):
            if student in students:
                raise ValueError(
                    f"student {student!r} is in {str(students[student][0])!r} and {str(part)!r}: "
                    "the parts overlap"
                )
            students[student] = (part, name, [r for r in rows if r.student == student])
    out_dir.mkdir(parents=True, exist_ok=True)
    ordered = sorted(students)
    for student, name in zip(ordered, folder_names(ordered), strict=True):
        part, old, _ = students[student]
        if (part / old).is_dir():
            shutil.copytree(part / old, out_dir / name, dirs_exist_ok=True)
    rows = [row for student in ordered for row in students[student][2]]
    _write_class(rows, out_dir)
    return rows

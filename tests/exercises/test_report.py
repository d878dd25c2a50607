"""The teacher's reports: grades.csv, feedback HTML/Markdown, Gradescope JSON, class summary.

The grades are built here from real verdicts (`core.judge`) of the committed
`span_rule` exercise: a correct answer, known-wrong variants, a hostile answer
that tries to leak the hidden inputs through its error message, and a missing
answer.
"""

import base64
import csv
import json
import re
from dataclasses import replace
from fractions import Fraction

import pytest

from scanviz.exercises import judging, report
from scanviz.exercises.catalog import get
from scanviz.exercises.core import (
    VariantRuns,
    compile_answer,
    hidden_cases,
    reference_outcome,
    run_case,
    score,
)
from scanviz.exercises.key import new_key
from scanviz.exercises.results import ExerciseGrade, StudentGrade
from scanviz.exercises.verdict import judge

LEAKER = """\
def span_rule(crossings, rule):
    raise ValueError("LEAK " + repr(crossings))
"""


def key_with(reveal):
    """A course key for span_rule with `reveal` (the one field the reports read)."""
    return replace(new_key(["span_rule"]), reveal=reveal)


@pytest.fixture(scope="module")
def span_rule():
    return get("span_rule")


@pytest.fixture(scope="module")
def judged(span_rule):
    """(case, hidden, reference outcome, variant outcomes) of the public and 3 hidden cases."""
    cases = [(c, False) for c in span_rule.public]
    cases += [(c, True) for c in hidden_cases(span_rule, "report-test-secret", 3)]
    return [
        (
            c,
            h,
            reference_outcome(span_rule, c),
            VariantRuns(span_rule, c, reference_outcome(span_rule, c)),
        )
        for c, h in cases
    ]


def _grade(span_rule, judged, student, source):
    function = compile_answer(source, span_rule.answer, f"<answer {student}>")
    verdicts = [
        judge(span_rule, c, run_case(span_rule, function, c), ref, hidden=h, variants=variants)
        for c, h, ref, variants in judged
    ]
    passed = all(v.passed for v in verdicts)
    status = "passed" if passed else "failed"
    return ExerciseGrade(
        student, "span_rule", score(span_rule, verdicts), span_rule.points, status, "", verdicts
    )


def _variant(span_rule, name):
    return next(v.source for v in span_rule.variants if v.name == name)


@pytest.fixture(scope="module")
def grades(span_rule, judged):
    answers = {
        "alice": span_rule.solution,
        "<script>alert(1)</script>": _variant(span_rule, "floor_for_ceil"),
        "bob": _variant(span_rule, "floor_for_ceil"),
        "carol": _variant(span_rule, "closed_span"),
        "../mallory": LEAKER,
    }
    students = [
        StudentGrade(name, f"{name}.ipynb", [_grade(span_rule, judged, name, source)])
        for name, source in answers.items()
    ]
    # The grader's message quotes a public case's error only, never a hidden one's inputs.
    leaker = students[-1].grades[0]
    errors = [v for v in leaker.verdicts if v.error]
    students[-1].grades[0] = replace(
        leaker, status="error", message=judging._error_message(errors, len(leaker.verdicts))
    )
    students[0].grades[0] = replace(students[0].grades[0], output="debugging <b>print</b>\n")
    missing = ExerciseGrade("dave", "span_rule", 0.0, span_rule.points, "no answer", "no marker")
    students.append(StudentGrade("dave", "dave.ipynb", [missing]))
    return students


@pytest.fixture(scope="module")
def written(grades, tmp_path_factory):
    """Reports written under reveal "never" and "always"."""
    out = {}
    for reveal in ("never", "always"):
        out[reveal] = tmp_path_factory.mktemp(reveal)
        report.write_reports(grades, key_with(reveal), out[reveal])
    return out


def _folder(out, student, grades):
    students = [s.student for s in grades]
    return out / report.folder_names(students)[students.index(student)]


def test_csv_has_the_columns_and_one_row_per_student_and_exercise(written, grades):
    with open(written["never"] / "grades.csv", newline="", encoding="utf-8") as file:
        rows = list(csv.reader(file))
    assert rows[0] == ["student", "exercise", "score", "max_score", "status"]
    passed_floor = sum(v.passed for v in grades[1].grades[0].verdicts)
    expected_floor = Fraction(4 * passed_floor, len(grades[1].grades[0].verdicts))
    body = {row[0]: row[1:] for row in rows[1:]}
    assert len(rows) == 1 + 6 and len(body) == 6
    assert body["alice"] == ["span_rule", "4", "4", "passed"]
    assert body["dave"] == ["span_rule", "0", "4", "no answer"]
    assert body["<script>alert(1)</script>"][0] == "span_rule"
    assert Fraction(body["bob"][1]) == pytest.approx(expected_floor, abs=1e-4)
    assert body["bob"][2:] == ["4", "failed"]
    assert body["../mallory"][1:] == ["0", "4", "error"]


def test_student_folders_are_sanitized_and_stay_inside(written):
    out = written["never"]
    folders = sorted(p.name for p in out.iterdir() if p.is_dir())
    assert folders == sorted(["alice", "_script_alert_1___script_", "bob", "carol", "_mallory",
                              "dave"])  # fmt: skip
    for folder in folders:
        assert {p.name for p in (out / folder).iterdir()} == {
            "feedback.html", "feedback.md", "results.json"
        }  # fmt: skip
    assert not (out.parent / "mallory").exists()


def test_html_escapes_the_student_id_and_shows_a_raster_diff_image(written, grades):
    page = (
        _folder(written["never"], "<script>alert(1)</script>", grades) / "feedback.html"
    ).read_text()
    assert "<script>" not in page and "&lt;script&gt;alert(1)&lt;/script&gt;" in page
    for name in ("feedback.md", "results.json"):
        text = (_folder(written["never"], "<script>alert(1)</script>", grades) / name).read_text()
        assert "<script>" not in text and r"\<script\>alert\(1\)" in text.replace("\\\\", "\\")
    images = re.findall(r"src='data:image/png;base64,([A-Za-z0-9+/=]+)'", page)
    assert images, "a failed public case with a raster diff has an image"
    png = base64.b64decode(images[0])
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    # the public triangle's 8x6 raster on its grid: at least 40 px a sample, at most 8 in at 100 dpi
    assert 8 * 40 <= width <= 800 and 6 * 40 <= height
    assert "likely cause: floor instead of ceil" in page
    assert f"public cases 0 of {len(get('span_rule').public)}, hidden cases" in page


def test_html_escapes_messages_and_diagnostics(grades, tmp_path):
    grade = ExerciseGrade("eve", "span_rule", 0.0, 4, "syntax error", "line 1: <b>oops</b> & co")
    report.write_reports([StudentGrade("eve", "eve.ipynb", [grade])], key_with("never"), tmp_path)
    page = (tmp_path / "eve" / "feedback.html").read_text()
    assert "<b>oops</b>" not in page and "&lt;b&gt;oops&lt;/b&gt; &amp; co" in page


def test_markdown_has_the_same_diagnostics(written, grades):
    text = (_folder(written["always"], "bob", grades) / "feedback.md").read_text()
    for verdict in grades[2].grades[0].verdicts:
        assert verdict.describe(reveal=True) in text
    assert "4 of 4 points" in (written["always"] / "alice" / "feedback.md").read_text()


def test_results_json_has_gradescope_fields_and_sums(written, grades):
    for student, reveal in [(s, r) for s in grades for r in ("never", "always")]:
        data = json.loads(
            (_folder(written[reveal], student.student, grades) / "results.json").read_text()
        )
        assert {"score", "execution_time", "output", "output_format", "tests"} <= set(data)
        assert data["output_format"] == "md"
        tests = data["tests"]
        fields = {"name", "score", "max_score", "status", "output", "output_format", "visibility"}
        assert all(fields <= set(t) for t in tests)
        assert data["score"] == pytest.approx(student.score)
        assert sum(t["score"] for t in tests) == pytest.approx(student.score)
        assert sum(t["max_score"] for t in tests) == pytest.approx(student.max_score)
        assert {t["status"] for t in tests} <= {"passed", "failed"}
    bob = json.loads((written["never"] / "bob" / "results.json").read_text())["tests"]
    assert [t["visibility"] for t in bob] == ["visible", "after_published"]
    cases, public = len(grades[2].grades[0].verdicts), len(get("span_rule").public)
    assert bob[0]["max_score"] == pytest.approx(4 * public / cases)  # public cases' share
    public_passed = sum(v.passed for v in grades[2].grades[0].verdicts if not v.hidden)
    assert bob[0]["status"] == ("passed" if public_passed == 4 else "failed")
    always = json.loads((written["always"] / "bob" / "results.json").read_text())["tests"]
    assert [t["visibility"] for t in always] == ["visible", "visible"]


def _hidden_secrets(grades):
    """Texts that would give a hidden case's inputs away: the leaked crossings, the polygon
    and the reference raster of every failed hidden case."""
    secrets = set()
    for student in grades:
        for verdict in (v for g in student.grades for v in g.verdicts):
            if not verdict.hidden:
                continue
            secrets.add(repr(verdict.case.inputs["polygon"]))
            if verdict.error is not None:
                secrets.add(verdict.error.split("LEAK ")[-1][:40])
            if verdict.raster is not None:
                secrets.add(verdict.raster.art())
    return secrets


def _all_text(out):
    return "\n".join(p.read_text() for p in out.rglob("*") if p.suffix in {".html", ".md", ".json"})


def test_hidden_inputs_are_absent_unless_the_key_reveals_them(written, grades):
    secrets = _hidden_secrets(grades)
    leaked = [v for v in grades[4].grades[0].verdicts if v.hidden and v.error]
    assert leaked and all("LEAK [(Fraction(" in v.error for v in leaked)  # the attack is real
    never = _all_text(written["never"])
    assert [s for s in secrets if s in never] == []
    assert "messages are not shown for hidden cases" in never
    assert "your code raised ValueError: LEAK [(Fraction(" in never  # a public case's, in full
    total = len(grades[4].grades[0].verdicts)
    assert f"(in {total} of {total} cases)" in never
    always = _all_text(written["always"])
    assert any(s in always for s in secrets)


def test_summary_names_the_most_common_variant_and_divergence(written, grades):
    # Rates are over the 5 students who answered: dave, who did not, counts apart.
    text = (written["never"] / "summary.txt").read_text()
    assert "span_rule: passed 1 of 5 who answered it (20%) (1 did not answer it)" in text
    assert "most common known-wrong variant: 2 of 5: floor_for_ceil" in text
    floor_signatures = [v.signature for v in grades[1].grades[0].verdicts if not v.passed]
    signature = max(set(floor_signatures), key=floor_signatures.count)
    assert f"most common first divergence: 2 of 5: {signature}" in text
    assert "statuses: failed 3, passed 1, error 1, no answer 1" in text
    page = (written["never"] / "summary.html").read_text()
    assert "2 of 5: floor_for_ceil" in page and "data:image/png;base64," in page


def test_summary_line():
    empty = ExerciseGrade("x", "span_rule", 0.0, 4, "no answer")
    full = ExerciseGrade("y", "span_rule", 4.0, 4, "passed")
    grades = [StudentGrade("x", "x.ipynb", [empty]), StudentGrade("y", "y.ipynb", [full])]
    rows = report.grade_rows(grades)
    assert report.summary_line(rows) == "2 students: mean 2 of 4 points (50%), 1 with full marks"


def test_csv_cells_cannot_be_formulas(tmp_path):
    # Issue 22: a student id starting with '=' went into grades.csv as it was.
    ids = ['=HYPERLINK("http://x")', "+1", "-2", "@SUM(A1)", "ann"]
    grades = [
        StudentGrade(i, f"{i}.ipynb", [ExerciseGrade(i, "span_rule", 4.0, 4, "passed")])
        for i in ids
    ]
    report.write_reports(grades, key_with("never"), tmp_path)
    with open(tmp_path / "grades.csv", newline="", encoding="utf-8") as file:
        cells = [row[0] for row in csv.reader(file)][1:]
    assert cells == ['\'=HYPERLINK("http://x")', "'+1", "'-2", "'@SUM(A1)", "ann"]


def test_what_the_public_cases_printed_is_in_the_feedback_escaped(written):
    page = (written["never"] / "alice" / "feedback.html").read_text()
    assert "debugging &lt;b&gt;print&lt;/b&gt;" in page
    assert "debugging <b>print</b>" in (written["never"] / "alice" / "feedback.md").read_text()


def test_shards_merge_into_the_reports_of_one_grading(grades, tmp_path):
    ordered = sorted(grades, key=lambda s: s.student)  # grading lists students in id order
    whole = tmp_path / "whole"
    report.write_reports(ordered, key_with("never"), whole)
    parts = [tmp_path / "part1", tmp_path / "part2"]
    report.write_reports(ordered[::2], key_with("never"), parts[0])
    report.write_reports(ordered[1::2], key_with("never"), parts[1])
    merged = tmp_path / "merged"
    report.merge_reports(parts, merged)
    for name in ("grades.csv", "grades.json", "summary.txt"):
        assert (merged / name).read_text() == (whole / name).read_text(), name
    files = sorted(str(p.relative_to(merged)) for p in merged.rglob("*") if p.is_file())
    assert files == sorted(str(p.relative_to(whole)) for p in whole.rglob("*") if p.is_file())
    with pytest.raises(ValueError, match="the parts overlap"):
        report.merge_reports([parts[0], parts[0]], tmp_path / "twice")

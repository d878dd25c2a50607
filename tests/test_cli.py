"""The command line: the slide example's table, JSON shape, PNG output, clean errors."""

import csv
import json
import re
import subprocess
import sys

import matplotlib.image
import pytest
from PIL import Image

from scanviz.cli import main

SLIDE = "4,1 1,11 9,5 12,8 12,1"


def test_trace_prints_the_slide_table(capsys):
    assert main(["trace", "--vertices", SLIDE]) == 0
    out = capsys.readouterr().out
    rows = {line.split("|")[0].strip(): line for line in out.splitlines() if "|" in line}
    assert "e0: 3 7/10, -3/10, 11, -1" in rows["2"]
    assert "e0: 2 4/5" in rows["5"] and "e1: 9, -1 1/3, 11, +1" in rows["5"]
    assert rows["5"].rstrip().endswith("[3,9) w-1 [9,12) w-1")
    assert "e1: 7 2/3" in rows["6"] and "[3,8) w-1 [10,12) w-1" in rows["6"]
    assert "horizontal: crosses no row, never active" in out


def test_trace_json_shape(capsys):
    assert main(["trace", "--vertices", SLIDE, "--json"]) == 0
    events = json.loads(capsys.readouterr().out)["events"]
    assert all("kind" in e for e in events)
    aet = {e["y"]: e["entries"] for e in events if e["kind"] == "aet_sorted"}
    assert [entry["x"] for entry in aet[6]] == pytest.approx([2.5, 23 / 3, 10, 12])
    assert set(aet[6][0]) >= {"x", "dxdy", "ymax", "winding"}
    spans = [(e["y"], e["x_start"], e["x_end"]) for e in events if e["kind"] == "span"]
    assert spans[:2] == [(1, 4, 12), (2, 4, 12)]


def test_trace_gif_saves_every_step_as_the_stepper_shows_it(capsys, tmp_path):
    out, triangle = tmp_path / "slide.gif", "0,0 4,0 4,3"
    assert main(["trace", "--vertices", triangle, "--gif", str(out)]) == 0
    said = capsys.readouterr().out
    assert main(["trace", "--vertices", triangle, "--json"]) == 0
    events = json.loads(capsys.readouterr().out)["events"]
    with Image.open(out) as gif:
        assert gif.n_frames == len(events) + 1  # the start, then one frame per event
    assert said.startswith(str(out)) and f"{len(events)} steps" in said
    assert main(["trace", "--vertices", SLIDE, "--gif", str(tmp_path / "x.png")]) == 2
    assert "--gif must name a .gif file" in capsys.readouterr().err


def test_center_sampling_and_rules_are_options(capsys):
    assert (
        main(
            [
                "trace",
                "--vertices",
                SLIDE,
                "--sample",
                "center",
                "--rule",
                "evenodd",
                "--subpixel-bits",
                "none",
            ]
        )
        == 0
    )
    assert "e0: 3 17/20" in capsys.readouterr().out  # row 1 is the scanline y = 1.5


def test_fill_writes_a_png_with_y_up(tmp_path):
    out = tmp_path / "fill.png"
    assert (
        main(["fill", "--vertices", "0,0 4,0 0,4", "--width", "6", "--height", "5", "-o", str(out)])
        == 0
    )
    image = matplotlib.image.imread(out)[..., 0]
    assert image.shape == (5, 6)
    assert image[-1, :4].all() and not image[0].any()  # bottom row full, top row empty


@pytest.mark.parametrize(
    "args, message",
    [
        (["trace", "--vertices", "4,1 1,nan 9,5"], "not finite"),
        (["trace", "--vertices", "4,1 1,2"], "at least 3"),
        (["trace", "--vertices", "4,1 1,2 x"], "not of the form x,y"),
        (["trace", "--vertices", SLIDE, "--width", "-3"], "argument --width: must be >= 0; got -3"),
        (["fill", "--vertices", SLIDE, "-o", "/nonexistent/dir/out.png"], "error"),
    ],
)
def test_bad_input_is_one_line_without_traceback(args, message):
    run = subprocess.run([sys.executable, "-m", "scanviz", *args], capture_output=True, text=True)
    assert run.returncode != 0
    assert message in run.stderr
    assert "Traceback" not in run.stderr and len(run.stderr.strip().splitlines()) == 1


def test_bad_option_value_exits_nonzero():
    run = subprocess.run(
        [sys.executable, "-m", "scanviz", "trace", "--vertices", SLIDE, "--subpixel-bits", "17"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 2 and "--subpixel-bits: must be an integer in 0..16" in run.stderr
    assert "Traceback" not in run.stderr


def test_bench_quick_runs(capsys):
    assert main(["bench", "raster", "--quick"]) == 0
    out = capsys.readouterr().out
    assert "100,000 small triangles" in out and "scanviz ms" in out


# --- issue 8 -------------------------------------------------------------------------------

TRIANGLE_OBJ = "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n"


def one_error_line(capsys, argv, status=2):
    assert main(argv) == status
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err


@pytest.mark.parametrize(
    "argv, message",
    [
        (["render", "builtin:sphere", "-o", "f.qqq"], "unsupported image file extension '.qqq'; supported: .png, .jpg"),
        (["render", "builtin:sphere", "-o", "/tmp"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", "/dev/full"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", "noext"], "unsupported image file extension '(none)'"),
        (["render", "builtin:sphere", "-o", ""], "-o/--output must be a file name; got ''"),
        (["render", "builtin:sphere", "--width", "0"], "argument --width: must be >= 1; got 0"),
        (["render", "builtin:sphere", "--height", "1" * 5000], "must be an integer >= 1 of at most 30 digits"),
        (["render", "builtin:sphere", "--visibility", "x\ny"], r"invalid choice: 'x\ny'"),
        (["render", "no\nsuch.json"], r"No such file or directory: 'no\nsuch.json'"),
        (["render", "builtin:sphere", "--bogus"], "unrecognized arguments: --bogus"),
        (["fill", "--vertices", "0,0 4,0 0,4", "--scale", "100000", "-o", "x.png"], "over the memory limit"),
        ([], "the following arguments are required: command"),
    ],
)  # fmt: skip
def test_issue8_d11_every_cli_error_is_one_line(capsys, argv, message):
    assert message in one_error_line(capsys, argv)


def test_issue8_d11_bad_files_are_one_line_naming_the_file(capsys, tmp_path):
    scene = tmp_path / "scene.json"
    scene.write_bytes(b"\xff\xfe{}")
    assert "scene.json' is not UTF-8 text" in one_error_line(capsys, ["render", str(scene)])
    scene.write_text('{"version": ' + "9" * 5000 + "}")
    assert "integer literal of 5000 digits" in one_error_line(capsys, ["render", str(scene)])
    from scanviz.limits import file_limit

    with file_limit("1M"):
        err = one_error_line(capsys, ["render", "/dev/zero"])  # refused, not read forever
        assert "'/dev/zero' is a character device, not a regular file" in err or "larger than the file limit" in err  # fmt: skip


def test_issue8_d6_deep_json_is_one_line(capsys, tmp_path):
    scene = tmp_path / "deep.json"
    scene.write_text("[" * 5000 + "]" * 5000)
    assert "nested 5000 deep" in one_error_line(capsys, ["render", str(scene)])


def test_issue8_d11_interrupt_is_one_line_and_130(capsys, monkeypatch):
    import scanviz.pipeline

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(scanviz.pipeline, "render", interrupted)
    assert one_error_line(capsys, ["render", "builtin:painter"], status=130) == "interrupted\n"


@pytest.mark.parametrize("suffix", [".png", ".jpg", ".JPEG", ".tif"])
def test_issue8_d11_image_formats(tmp_path, suffix):
    out = tmp_path / f"painter{suffix}"
    assert (
        main(["render", "builtin:painter", "--width", "16", "--height", "12", "-o", str(out)]) == 0
    )
    image = matplotlib.image.imread(out)
    assert image.shape[:2] == (12, 16)
    # Pixel (x, y) = (3, 3) of the slide (y up) is in the second polygon: green, opaque.
    pixel = image[12 - 1 - 3, 3, :3] / (255 if image.dtype.kind == "u" else 1)
    assert pixel.tolist() == pytest.approx([0, 1, 0], abs=0.02)


def test_issue8_d13_render_an_obj_model_with_every_option(tmp_path, capsys):
    model = tmp_path / "tri.OBJ"
    model.write_text(TRIANGLE_OBJ)
    out = tmp_path / "tri.png"
    for options in (
        [],
        ["--visibility", "abuffer", "--mask", "4x4", "--weights", "mask", "--edges"],
        ["--visibility", "flawed", "--affine", "--no-cull", "--shading", "flat"],
        [
            "--perspective-correct",
            "--cull",
            "--shading",
            "gooch",
            "--width",
            "32",
            "--height",
            "16",
        ],
    ):
        assert (
            main(
                ["render", str(model), "-o", str(out), "--width", "24", "--height", "24", *options]
            )
            == 0
        )
        image = matplotlib.image.imread(out)
        assert image[..., :3].std() > 0  # the model shows against the background
    assert capsys.readouterr().err == ""


def test_issue8_d13_render_options_reach_the_renderer(monkeypatch):
    import scanviz.pipeline

    seen = {}
    real = scanviz.pipeline.render

    def spy(scene, width, height, **options):
        seen.update(options)
        return real(scene, width, height, **options)

    monkeypatch.setattr(scanviz.pipeline, "render", spy)
    argv = ["render", "builtin:painter", "--width", "16", "--height", "12"]
    assert main(argv) == 0 and seen["cull"] is None and seen["perspective_correct"] is True
    assert main([*argv, "--affine", "--cull", "--visibility", "abuffer", "--mask", "8x4"]) == 0
    assert seen["cull"] is True and seen["perspective_correct"] is False
    assert seen["visibility"] == "abuffer" and seen["mask"] == "8x4"
    assert main([*argv, "--no-cull", "--weights", "mask", "--edges"]) == 0
    assert seen["cull"] is False and seen["weights"] == "mask" and seen["edges"] is True
    assert seen["expansion"] == "vertex"
    assert main([*argv, "--shading", "fast_phong", "--expansion", "centroid"]) == 0
    assert seen["shading"] == "fast_phong" and seen["expansion"] == "centroid"


def test_conformance_command_parses_its_arguments():
    from scanviz.cli import build_parser

    args = build_parser().parse_args(["conformance", "--fuzz", "50", "--seed", "7"])
    assert (args.command, args.fuzz, args.seed) == ("conformance", 50, 7)


# --- issue 9: the teacher's and the student's commands ---------------------------------------


def fake_module(monkeypatch, name, **functions):
    """Put a module `name` with `functions` in place of the real one for one test."""
    import types

    module = types.ModuleType(name)
    module.__dict__.update(functions)
    monkeypatch.setitem(sys.modules, name, module)


def span_rule_grade(student, variant):
    """A real ExerciseGrade of span_rule's public cases answered by a known-wrong variant."""
    from scanviz.exercises import core, verdict
    from scanviz.exercises.catalog import get
    from scanviz.exercises.results import ExerciseGrade

    exercise = get("span_rule")
    source = next(v.source for v in exercise.variants if v.name == variant)
    function = core.compile_answer(source, exercise.answer)
    verdicts = []
    for case in exercise.public:
        yours = core.run_case(exercise, function, case)
        reference = core.reference_outcome(exercise, case)
        variants = core.VariantRuns(exercise, case, reference)
        verdicts.append(verdict.judge(exercise, case, yours, reference, variants=variants))
    points = core.score(exercise, verdicts)
    return ExerciseGrade(student, "span_rule", points, 4, "failed", "", verdicts)


def test_issue9_exercises_list_is_a_table_of_the_catalog(capsys):
    from scanviz.exercises.catalog import exercises

    assert main(["exercises", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["no", "id", "stage", "kind", "points", "title"]
    assert len(lines) == 1 + len(exercises())
    for line, exercise in zip(lines[1:], exercises(), strict=True):
        assert line.split()[:2] == [f"{exercise.number:02d}", exercise.id]
        assert f" {exercise.kind} " in line and line.endswith(exercise.title)


@pytest.mark.parametrize("solutions", [False, True])
def test_issue9_exercises_release_writes_a_notebook_per_exercise(capsys, tmp_path, solutions):
    import nbformat

    from scanviz.exercises.catalog import exercises

    argv = ["exercises", "release", str(tmp_path / "out")] + ["--with-solutions"] * solutions
    assert main(argv) == 0
    written = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert written == sorted(f"{e.number:02d}_{e.id}.ipynb" for e in exercises())
    exercise = exercises()[0]
    notebook = nbformat.read(tmp_path / "out" / f"{exercise.number:02d}_{exercise.id}.ipynb", 4)
    answers = [c.source for c in notebook.cells if c.source.startswith("# scanviz: answer ")]
    assert len(answers) == 1
    assert (exercise.solution.strip() in answers[0]) is solutions
    assert f"{len(written)} " in capsys.readouterr().out


def test_issue9_release_into_a_file_is_one_line(capsys, tmp_path):
    (tmp_path / "file").write_text("")
    assert "is not a folder" in one_error_line(
        capsys, ["exercises", "release", str(tmp_path / "file")]
    )


@pytest.mark.parametrize(
    "argv, message",
    [
        (["exercises"], "required: list|release|key"),
        (["exercises", "key"], "required: new"),
        (["grade", "subs", "-o", "out"], "required: --key"),
        (["grade", "subs", "--key", "k.toml", "-o", "out", "--jobs", "0"], "must be >= 1; got 0"),
        (["check"], "required: NOTEBOOK"),
    ],
)
def test_issue9_usage_errors_are_one_line(capsys, argv, message):
    assert message in one_error_line(capsys, argv)


def test_issue9_check_prints_public_diagnostics_and_says_hidden_cases_come_later(
    capsys, monkeypatch
):
    from scanviz.exercises.results import ExerciseGrade, StudentGrade

    grade = span_rule_grade("me", "positive_winding_only")
    missing = ExerciseGrade(
        "me", "aet_update", 0.0, 4, "no answer", "no cell starts with the marker"
    )
    student = StudentGrade("me", "me.ipynb", [grade, missing])
    seen = []
    fake_module(
        monkeypatch,
        "scanviz.exercises.grading",
        check_notebook=lambda path: seen.append(path) or student,
    )
    assert main(["check", "me.ipynb"]) == 0
    out = capsys.readouterr().out
    passed, public = sum(v.passed for v in grade.verdicts), len(grade.verdicts)
    assert 0 < passed < public, "the variant passes some public cases and fails others"
    assert seen == ["me.ipynb"]
    assert f"span_rule -- public cases {passed} of {public}" in out
    assert "aet_update -- no answer: no cell starts with the marker" in out
    assert out.rstrip().endswith(
        f"me.ipynb: 2 exercises, public cases {passed} of {public} -- hidden cases are graded later"
    )
    for verdict in grade.verdicts:
        assert (verdict.describe() in out) is not verdict.passed
    assert "likely cause: inside only when the count is positive" in out
    assert "all tests passed" not in out.lower()


def test_issue9_check_of_a_missing_notebook_is_one_line(capsys, monkeypatch):
    def refuse(path):
        raise FileNotFoundError(f"NOTEBOOK {path!r} does not exist")

    fake_module(monkeypatch, "scanviz.exercises.grading", check_notebook=refuse)
    assert "NOTEBOOK 'nope.ipynb' does not exist" in one_error_line(capsys, ["check", "nope.ipynb"])


def test_issue9_grade_writes_the_reports_and_says_where(capsys, monkeypatch, tmp_path):
    from dataclasses import dataclass

    from scanviz.exercises.results import StudentGrade

    @dataclass
    class Key:
        reveal: str = "never"

    calls = []

    def grade_submissions(folder, key, *, jobs=1, exercises=None, progress=True, **options):
        calls.append((folder, key, jobs, progress, options))
        return [
            StudentGrade("ann", "ann.ipynb", [span_rule_grade("ann", "floor_for_ceil")]),
            StudentGrade("a/b", "a/b.ipynb", [span_rule_grade("a/b", "floor_for_ceil")]),
        ]

    key = Key()
    import scanviz.exercises.report  # noqa: F401 -- imports the real key module before it is faked

    fake_module(monkeypatch, "scanviz.exercises.key", load_key=lambda path: key)
    fake_module(monkeypatch, "scanviz.exercises.grading", grade_submissions=grade_submissions)
    out = tmp_path / "graded"
    argv = ["grade", str(tmp_path / "subs"), "--key", "k.toml", "-o", str(out), "--jobs", "2"]
    assert main(argv) == 0
    printed = capsys.readouterr().out
    options = {"shard": None, "jail": "bwrap"}
    assert calls == [(str(tmp_path / "subs"), "k.toml", 2, True, options)]
    assert f"{out / 'grades.csv'}: 2 rows" in printed
    assert "student 'a/b': folder 'a_b' (sanitized)" in printed
    assert printed.rstrip().splitlines()[-1].startswith("2 students: mean ")
    assert (out / "a_b" / "results.json").exists() and (out / "ann" / "feedback.html").exists()
    assert (out / "summary.html").exists()
    assert "2 of 2: floor_for_ceil" in (out / "summary.txt").read_text()
    argv += ["--shard", "2/3", "--no-jail"]
    assert main(argv) == 0
    assert calls[-1][-1] == {"shard": (2, 3), "jail": "none"}
    assert "part 2 of 3: join the parts with `grade merge`" in capsys.readouterr().out


@pytest.mark.parametrize("inside", ["", "graded"])
def test_issue9_grade_refuses_to_write_into_the_submissions(capsys, monkeypatch, tmp_path, inside):
    import scanviz.exercises.report  # noqa: F401 -- imported for real before `key` is faked

    fake_module(monkeypatch, "scanviz.exercises.key", load_key=lambda path: None)
    fake_module(monkeypatch, "scanviz.exercises.grading", grade_submissions=None)
    argv = ["grade", str(tmp_path), "--key", "k.toml", "-o", str(tmp_path / inside)]
    assert "must be a folder outside SUBMISSIONS_DIR" in one_error_line(capsys, argv)


def test_issue9_key_new_writes_a_key_once(capsys, tmp_path):
    from scanviz.exercises.catalog import exercises
    from scanviz.exercises.key import load_key

    path = tmp_path / "course.toml"
    assert main(["exercises", "key", "new", str(path)]) == 0
    out = capsys.readouterr().out
    key = load_key(path)
    assert sorted(key.exercises) == sorted(e.id for e in exercises())
    assert key.secret not in out and "keep it private" in out
    assert "never overwritten" in one_error_line(capsys, ["exercises", "key", "new", str(path)])
    assert load_key(path).secret == key.secret


def test_issue9_release_then_grade_solved_and_blank_copies(capsys, tmp_path):
    import shutil

    from scanviz.exercises.catalog import get
    from scanviz.exercises.key import new_key, write_key
    from scanviz.exercises.release import notebook_name

    name = notebook_name(get("span_rule"))
    assert main(["exercises", "release", str(tmp_path / "handout")]) == 0
    assert main(["exercises", "release", str(tmp_path / "solved"), "--with-solutions"]) == 0
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    shutil.copy(tmp_path / "solved" / name, submissions / "solved.ipynb")
    shutil.copy(tmp_path / "handout" / name, submissions / "blank.ipynb")
    write_key(new_key(["span_rule"]), tmp_path / "key.toml")
    out = tmp_path / "graded"
    argv = ["grade", str(submissions), "--key", str(tmp_path / "key.toml"), "-o", str(out)]
    assert main(argv) == 0
    assert (
        capsys.readouterr()
        .out.rstrip()
        .endswith("2 students: mean 2 of 4 points (50%), 1 with full marks")
    )
    with open(out / "grades.csv", newline="") as file:
        rows = {row["student"]: row for row in csv.DictReader(file)}
    assert (rows["solved"]["score"], rows["solved"]["max_score"], rows["solved"]["status"]) == (
        "4", "4", "passed"
    )  # fmt: skip
    assert rows["blank"]["score"] == "0" and rows["blank"]["status"] == "error"
    results = json.loads((out / "solved" / "results.json").read_text())
    assert results["score"] == 4 and all(t["status"] == "passed" for t in results["tests"])
    assert "NotImplementedError" in (out / "blank" / "feedback.md").read_text()
    assert main(["check", str(submissions / "blank.ipynb")]) == 0
    printed = capsys.readouterr().out
    public = len(get("span_rule").public)
    assert f"span_rule -- public cases 0 of {public} -- error" in printed
    assert printed.rstrip().endswith(f"public cases 0 of {public} -- hidden cases are graded later")
    assert "public case 'triangle': FAILED" in printed and "samples: 0 matched (#)" in printed


def test_issue9_check_a_notebook_without_answers(capsys, tmp_path):
    import nbformat

    path = tmp_path / "empty.ipynb"
    nbformat.write(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = 1")]), path)
    assert main(["check", str(path)]) == 0
    assert "no answer cells" in capsys.readouterr().out
    path.write_text("{not json")
    assert "not valid JSON" in one_error_line(capsys, ["check", str(path)])


def test_issue9_bench_grading_grades_a_synthetic_class_with_each_jobs(capsys, monkeypatch):
    from pathlib import Path

    from scanviz.exercises.catalog import exercises
    from scanviz.exercises.notebook import find_answers, read_notebook
    from scanviz.exercises.results import ExerciseGrade, StudentGrade

    catalog = {e.id: e for e in exercises()}
    seen_jobs = []

    def grade_submissions(folder, key, *, jobs=1, exercises=None, progress=True, jail="bwrap"):
        """Grade by the answers' sources: the solution scores its points, anything else 0."""
        seen_jobs.append(jobs)
        grades = []
        for path in sorted(Path(folder).glob("*.ipynb")):
            answers = find_answers(read_notebook(path)).answers
            assert sorted(answers) == sorted(catalog)
            student = StudentGrade(path.stem, str(path))
            for exercise_id, source in answers.items():
                e = catalog[exercise_id]
                solved = source.split("\n", 1)[1].strip() == e.solution.strip()
                student.grades.append(
                    ExerciseGrade(path.stem, e.id, e.points * solved, e.points,
                                  "passed" if solved else "failed")
                )  # fmt: skip
            grades.append(student)
        return grades

    fake_module(monkeypatch, "scanviz.exercises.grading", grade_submissions=grade_submissions)
    assert main(["bench", "grading", "--quick"]) == 0
    out = capsys.readouterr().out
    total = sum(e.points for e in catalog.values())
    assert seen_jobs == [1, 2]
    assert "students/min" in out and "s/student" in out
    assert f"student-00 (every solution): {total} of {total} points" in out
    assert "same grades with every --jobs: yes" in out


def test_surface_draws_each_algorithm_and_reads_a_database(capsys, tmp_path):
    from scanviz.surfaces import floating_perimeter, gaussian
    from scanviz.surfaces.perimeter import View

    database = tmp_path / "gaussian.txt"
    gaussian(9).to_database(database, z_decimals=None)
    image = tmp_path / "lines.png"
    argv = ["surface", str(database), "--viewpoint", "3,4,3", "--width", "60", "--height", "40"]
    assert main([*argv, "-o", str(image)]) == 0
    lines = floating_perimeter(
        gaussian(9), View((3, 4, 3), (-3, -4, -3 + gaussian(9).z.mean())), 60, 40
    )
    drawn = matplotlib.image.imread(image)[::-1, :, 0] < 0.5  # black lines on white, rows y up
    assert (drawn == lines.lines).all()
    assert f"case 9, {lines.stats.edges} edges, {lines.stats.visible} of" in capsys.readouterr().out
    for extra in (
        ["--algorithm", "fha", "--family", "y"],
        ["--mode", "surface", "--shading", "flat"],
        ["--algorithm", "zbuffer", "--parallel"],
    ):
        assert (
            main(["surface", "rogers", "--points", "9", "--width", "32", "--height", "32", *extra])
            == 0
        )
    out = capsys.readouterr().out
    assert "fha: 9 curves" in out and "64 facets" in out and "0 clipped" in out


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["surface", "nosuch"], "is neither a built-in (gaussian, polynomial, rogers, random)"),
        (["surface", "gaussian", "--viewpoint", "1,2"], "must be three finite numbers x,y,z"),
        (
            ["surface", "gaussian", "--viewpoint", "0,0,0.5", "--direction", "1,0,0"],
            "in front of the viewpoint",
        ),
        (["surface", "gaussian", "-o", "x.bmp"], "unsupported image file extension '.bmp'"),
    ],
)
def test_surface_errors_are_one_line(capsys, argv, message):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_the_complex_surface_is_coloured_by_phase_with_a_marker_entry(tmp_path, capsys):
    plain, marked = tmp_path / "plain.png", tmp_path / "marked.png"
    argv = ["surface", "three_poles", "--mode", "surface", "--points", "21"]
    size = ["--width", "80", "--height", "80"]
    assert main([*argv, *size, "-o", str(plain)]) == 0
    assert main([*argv, *size, "--ring-steps", "16", "--marker", "5", "-o", str(marked)]) == 0
    assert "21x21 grid" in capsys.readouterr().out

    def white(path):
        image = matplotlib.image.imread(path)[..., :3]
        return int((image > 0.99).all(axis=2).sum())

    # the ring mixes two primaries at a time: no entry is white but the marker
    assert white(plain) == 0 < white(marked)
    colours = matplotlib.image.imread(plain)[..., :3].reshape(-1, 3)
    lit = colours[colours.max(axis=1) > 0.05]
    assert len(lit) > 1000 and (lit.min(axis=1) < 0.01).all()  # one primary is always off
    assert main(["surface", "gaussian", "--marker", "3"]) == 2
    assert "--marker and --ring-steps apply to three_poles only" in capsys.readouterr().err


def test_grade_in_shards_then_merge_is_one_grading(capsys, tmp_path):
    import nbformat
    from nbformat import v4

    from scanviz.exercises.catalog import get
    from scanviz.exercises.key import new_key, write_key

    exercise = get("span_rule")
    class_dir = tmp_path / "class"
    class_dir.mkdir()
    for k, name in enumerate(("ann", "ben", "cat", "dan")):
        body = exercise.solution if k % 2 else exercise.variants[0].source
        cell = v4.new_code_cell(f"# scanviz: answer span_rule\n{body}")
        nbformat.write(v4.new_notebook(cells=[cell]), class_dir / f"{name}.ipynb")
    write_key(new_key(["span_rule"]), tmp_path / "key.toml")
    grade = ["grade", str(class_dir), "--key", str(tmp_path / "key.toml")]
    assert main([*grade, "-o", str(tmp_path / "whole")]) == 0
    for part in (1, 2):
        assert main([*grade, "-o", str(tmp_path / f"part{part}"), "--shard", f"{part}/2"]) == 0
    merged = tmp_path / "merged"
    parts = [str(tmp_path / "part1"), str(tmp_path / "part2")]
    assert main(["grade", "merge", *parts, "-o", str(merged)]) == 0
    assert "2 parts joined, 4 students, 4 rows" in capsys.readouterr().out
    for name in ("grades.csv", "summary.txt"):
        assert (merged / name).read_text() == (tmp_path / "whole" / name).read_text()


# --- issue 27: every failure one short line, every numeric option checked ----------------------

HUGE_OBJ = "v 1e308 0 0\nv -1e308 0 0\nv 0 1e308 0\nf 1 2 3\n"


def test_issue27_a_warning_before_an_error_is_not_printed(tmp_path):
    model = tmp_path / "huge.obj"
    model.write_text(HUGE_OBJ)  # framing it overflows: numpy warns, then the loader refuses
    run = subprocess.run(
        [sys.executable, "-m", "scanviz", "render", str(model)], capture_output=True, text=True
    )
    assert run.returncode == 2 and "cannot frame the model" in run.stderr
    assert len(run.stderr.splitlines()) == 1, run.stderr


def test_issue27_a_warning_of_a_command_that_succeeds_is_one_line(capsys, monkeypatch):
    import warnings

    import scanviz.pipeline

    real = scanviz.pipeline.render

    def warns(*args, **kwargs):
        warnings.warn("overflow encountered in multiply\n  eye = ...", RuntimeWarning, stacklevel=1)
        return real(*args, **kwargs)

    monkeypatch.setattr(scanviz.pipeline, "render", warns)
    assert main(["render", "builtin:painter", "--width", "8", "--height", "6"]) == 0
    err = capsys.readouterr().err
    assert (
        err == "python -m scanviz render: warning: overflow encountered in multiply\\n  eye = ...\n"
    )


LONG = "a" * 5000


@pytest.mark.parametrize(
    "argv",
    [
        ["render", LONG + ".json"],
        ["render", "builtin:" + LONG],
        ["render", "builtin:painter", "--visibility", LONG],
        ["render", "builtin:painter", "--bogus" + LONG],
        ["render", "builtin:painter", "-o", LONG + ".png"],
        ["render", "builtin:painter", "-o", "/nonexistent/" + LONG + ".png"],
        ["trace", "--vertices", "0,0 4,0 0,4 " + "1," * 3000],
        ["trace", "--vertices", "0,0 4,0 0,4", "--subpixel-bits", LONG],
        ["grade", "x", "-o", "y", "--shard", "1" * 5000 + "/2"],
        ["surface", LONG],
    ],
)
def test_issue27_echoed_input_is_shortened(capsys, argv):
    err = one_error_line(capsys, argv)
    assert len(err) < 300 and re.search(r"\.\.\.'? \(\d,\d{3} characters", err), err


def test_issue27_long_unrecognized_arguments_are_counted_not_listed(capsys):
    argv = ["trace", "--vertices", SLIDE, "0,0 4,0 " * 700, "x " * 500]
    err = one_error_line(capsys, argv)
    assert "unrecognized arguments: '0,0 4,0 0,0 4,0 " in err
    assert "'... (6,601 characters in 2 arguments) (see --help)" in err
    assert len(err) < 200
    assert "unrecognized arguments: a b (see --help)" in one_error_line(
        capsys, [*argv[:3], "a", "b"]
    )


@pytest.mark.parametrize(
    "argv, message",
    [
        (["conformance", "--fuzz", "-1"], "argument --fuzz: must be >= 0; got -1"),
        (["conformance", "--seed", "-1"], "argument --seed: must be >= 0; got -1"),
        (["conformance", "--scenes", "0"], "argument --scenes: must be >= 1; got 0"),
        (["conformance", "--fuzz", "\u00b2"], "argument --fuzz: must be an integer >= 0 of at most 30 digits; got '\u00b2'"),
        (["trace", "--vertices", SLIDE, "--height", "-1"], "argument --height: must be >= 0; got -1"),
        (["fill", "--vertices", SLIDE, "--width", "0", "-o", "x.png"], "argument --width: must be >= 1; got 0"),
        (["fill", "--vertices", SLIDE, "--scale", "0", "-o", "x.png"], "argument --scale: must be >= 1; got 0"),
        (["trace", "--vertices", SLIDE, "--subpixel-bits", "-1"], "argument --subpixel-bits: must be an integer in 0..16 or 'none'; got '-1'"),
        (["trace", "--vertices", SLIDE, "--subpixel-bits", "17"], "argument --subpixel-bits: must be an integer in 0..16"),
        (["surface", "gaussian", "--points", "1"], "argument --points: must be >= 2; got 1"),
        (["surface", "three_poles", "--marker", "-1"], "argument --marker: must be >= 0; got -1"),
        (["surface", "gaussian", "--ring-steps", "0"], "argument --ring-steps: must be >= 1; got 0"),
        (["bench", "surfaces", "--grids", "1"], "argument --grids: must be >= 2; got 1"),
        (["bench", "surfaces", "--images", "50,-1"], "argument --images: must be >= 2; got -1"),
        (["bench", "visibility", "--repeat", "-2"], "argument --repeat: must be >= 1; got -2"),
        (["grade", "x", "-o", "y", "--jobs", "0"], "argument --jobs: must be >= 1; got 0"),
    ],
)  # fmt: skip
def test_issue27_numeric_options_refuse_bad_values_in_one_line(capsys, argv, message):
    assert message in one_error_line(capsys, argv)


HOSTILE = [
    "",
    " ",
    "-1",
    "-+5",
    "+-5",
    "--5",
    "0",
    "x",
    "\u00b2",
    "\u0663",
    "1e400",
    "nan",
    "1/0",
    "a\nb",
    ",",
    "1,,2",
    "9" * 5000,
]


def test_issue27_every_option_type_names_its_rule():
    """argparse says "invalid <function name> value" for a ValueError: the types raise none."""
    import argparse

    from scanviz.cli import build_parser

    def parsers(parser):
        yield parser
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for sub in action.choices.values():
                    yield from parsers(sub)

    types = {
        action.type
        for parser in parsers(build_parser())
        for action in parser._actions
        if callable(action.type) and getattr(action.type, "__module__", "") == "scanviz.cli"
    }
    assert len(types) >= 8
    for kind in types:
        for text in HOSTILE:
            try:
                kind(text)
            except argparse.ArgumentTypeError:  # any other exception fails the test
                pass

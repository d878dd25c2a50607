"""Gradescope and PrairieLearn: the autograder zip run in a local /autograder, results files."""

import json
import os
import shutil
import stat
import subprocess
import zipfile
from pathlib import Path

import nbformat
import pytest
from nbformat import v4

from scanviz.exercises import get
from scanviz.exercises.key import new_key, write_key
from scanviz.exercises.notebook import ANSWER_MARKER
from scanviz.exercises.platforms import autograde, gradescope_zip, prairielearn_tests

SPAN, AET = get("span_rule"), get("aet_update")


def _key(tmp_path: Path) -> Path:
    path = tmp_path / "key.toml"
    write_key(new_key(["span_rule", "aet_update"]), path)
    return path


def _submission(folder: Path, *cells: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    notebook = v4.new_notebook(cells=[v4.new_code_cell(c) for c in cells])
    nbformat.write(notebook, folder / "homework.ipynb")
    return folder


def test_the_zip_holds_the_scripts_the_key_and_scanviz_without_caches(tmp_path):
    key = _key(tmp_path)
    names = gradescope_zip(tmp_path / "ag.zip", key)
    with zipfile.ZipFile(tmp_path / "ag.zip") as archive:
        modes = {i.filename: i.external_attr >> 16 for i in archive.infolist()}
        setup = archive.read("setup.sh").decode()
        assert archive.read("key.toml") == key.read_bytes()
    assert names[:3] == ["setup.sh", "run_autograder", "key.toml"]
    assert modes["setup.sh"] == modes["run_autograder"] == 0o755 and modes["key.toml"] == 0o600
    assert "package/scanviz/raster/scanline.py" in names
    assert not [n for n in names if "__pycache__" in n or n.endswith((".nbi", ".nbc", ".pyc"))]
    assert "'numba" in setup and "bubblewrap" in setup and 'chmod 700 "$SOURCE"' in setup


def test_autograde_writes_both_platforms_results_and_a_result_even_when_it_fails(tmp_path):
    key = _key(tmp_path)
    submission = _submission(
        tmp_path / "upload",
        f"{ANSWER_MARKER}span_rule\n{SPAN.solution}",
        f"{ANSWER_MARKER}aet_update\n{AET.variants[0].source}",
    )
    gradescope = autograde(submission, key, "gradescope", tmp_path / "gs.json")
    scores = {"span_rule": 0.0, "aet_update": 0.0}
    for test in gradescope["tests"]:
        scores[test["name"].split(":")[0]] += test["score"]
    assert set(scores) == {"span_rule", "aet_update"}
    # The key's secret is fresh, so the hidden cases are too: the wrong variant may pass a
    # hidden case its bug does not touch (every edge starting below row 0), never them all.
    assert scores["span_rule"] == SPAN.points and 0 <= scores["aet_update"] < AET.points
    assert gradescope["score"] == pytest.approx(sum(scores.values()))
    prairielearn = autograde(submission, key, "prairielearn", tmp_path / "pl.json")
    assert prairielearn["gradable"] is True
    total = SPAN.points + AET.points
    assert prairielearn["score"] == pytest.approx(gradescope["score"] / total)
    tests = {t["name"]: t for t in prairielearn["tests"]}
    assert tests["span_rule"]["points"] == tests["span_rule"]["max_points"] == SPAN.points
    assert tests["aet_update"]["message"].startswith("failed: ")
    assert json.loads((tmp_path / "pl.json").read_text()) == prairielearn
    broken = autograde(submission, tmp_path / "missing.toml", "gradescope", tmp_path / "x.json")
    assert broken["score"] == 0 and "The autograder failed, not your code" in broken["output"]


def test_prairielearn_tests_folder(tmp_path):
    paths = prairielearn_tests(tmp_path / "tests", _key(tmp_path))
    assert [p.name for p in paths] == ["run.sh", "key.toml", "README.txt"]
    assert "--platform prairielearn" in paths[0].read_text() and os.access(paths[0], os.X_OK)
    assert stat.S_IMODE(paths[1].stat().st_mode) == 0o600


def test_the_autograder_zip_runs_in_a_local_autograder_from_nothing(tmp_path):
    # Gradescope's steps, here: unzip into source/, run setup.sh (Python, bubblewrap, a fresh
    # virtual environment from PyPI, numba's cache, permissions), then run_autograder on a
    # submission. PATH is a plain system's, as in Gradescope's image.
    root = tmp_path / "autograder"
    (root / "source").mkdir(parents=True)
    gradescope_zip(tmp_path / "ag.zip", _key(tmp_path))
    with zipfile.ZipFile(tmp_path / "ag.zip") as archive:
        for info in archive.infolist():
            archive.extract(info, root / "source")
            os.chmod(root / "source" / info.filename, info.external_attr >> 16)
    key_path = root / "source" / "key.toml"
    thief = f"try:\n    print(open({str(key_path)!r}).read())\nexcept OSError as error:\n    print(error)\n"
    _submission(
        root / "submission",
        f"{ANSWER_MARKER}span_rule\n{SPAN.solution}",
        f"{ANSWER_MARKER}aet_update\n{thief}{AET.solution}",
    )
    env = {"AUTOGRADER": str(root), "PATH": "/usr/sbin:/usr/bin:/sbin:/bin", "HOME": str(tmp_path)}
    setup = subprocess.run(
        ["bash", "setup.sh"], cwd=root / "source", env=env, capture_output=True, text=True
    )
    assert setup.returncode == 0, setup.stderr[-2000:]
    assert stat.S_IMODE((root / "source").stat().st_mode) == 0o700
    run = subprocess.run(
        ["bash", str(root / "source" / "run_autograder")], cwd=root, env=env, capture_output=True
    )
    assert run.returncode == 0, run.stderr[-2000:]
    text = (root / "results" / "results.json").read_text()
    assert json.loads(text)["score"] == SPAN.points + AET.points
    secret = next(line for line in key_path.read_text().splitlines() if line.startswith("secret"))
    assert secret.split('"')[1] not in text and "No such file or directory" in text
    shutil.rmtree(root / "venv", ignore_errors=True)

"""Grading on Gradescope and PrairieLearn: one submission in, the platform's results file out.

`autograde` grades one student's submission (a notebook or a folder of them)
with the course key and writes the platform's results file -- Gradescope's
``results.json`` (`scanviz.exercises.report.gradescope_results`) or
PrairieLearn's external-grader ``results.json`` (`prairielearn_results`) --
and writes one even when grading itself fails, as both platforms ask, so a
student always sees something.

`gradescope_zip` builds an autograder zip: ``setup.sh`` (Python >= 3.11,
bubblewrap, a virtual environment with scanviz and what it needs, numba's
cache warmed on the solved notebooks, the key and scanviz closed to other
users), ``run_autograder`` and the key. `prairielearn_tests` writes the files
of a question's ``tests/`` folder for PrairieLearn's external grader. In both,
the answers run in the jail (`scanviz.exercises.jail`): bubblewrap where the
container allows namespaces, else the user jail (the user nobody, the
system-call filter), which cannot read the key.
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
import traceback
import zipfile
from importlib import metadata
from pathlib import Path

from .key import load_key
from .report import gradescope_results, points

PLATFORMS = ("gradescope", "prairielearn")
_PACKAGE = Path(__file__).resolve().parent.parent


def prairielearn_results(student, reveal: bool) -> dict:
    """A graded submission in PrairieLearn's external-grader format (``/grade/results``).

    One test per exercise: its points, its status and message, and every
    case's diagnostics as output (hidden cases redacted unless `reveal`).
    """
    from .report import case_report

    tests = []
    for grade in student.grades:
        cases = "\n\n".join(case_report(v, reveal).text for v in grade.verdicts)
        message = f"{grade.status}: {grade.message}" if grade.message else grade.status
        tests.append(
            {
                "name": grade.exercise,
                "description": f"public cases {grade.public_passed[0]} of {grade.public_passed[1]}, "
                f"hidden cases {grade.hidden_passed[0]} of {grade.hidden_passed[1]}",
                "points": grade.score,
                "max_points": grade.max_score,
                "message": message,
                "output": cases,
            }
        )
    best = student.max_score
    return {
        "gradable": True,
        "score": student.score / best if best else 0.0,
        "message": f"{points(student.score)} of {points(best)} points",
        "output": "",
        "tests": tests,
    }


def _failure(platform: str, error: BaseException) -> dict:
    """The results file of a grading that failed (the student sees that it was not their code)."""
    text = f"The autograder failed, not your code: {type(error).__name__}: {error}"
    if platform == "gradescope":
        return {"score": 0.0, "output": text, "tests": []}
    return {"gradable": False, "message": text, "output": traceback.format_exc()[-4000:]}


def autograde(
    submission: str | os.PathLike,
    key_path: str | os.PathLike,
    platform: str,
    out: str | os.PathLike,
    *,
    jail: str = "auto",
) -> dict:
    """Grade one submission and write `platform`'s results file to `out`; return its contents.

    The submission is copied into a private folder first (the student's id
    is "student"). Whatever goes wrong, a results file is written.
    """
    from .grading import grade_submissions

    if platform not in PLATFORMS:
        raise ValueError(f"'platform' must be one of {PLATFORMS}; got {platform!r}")
    started = time.perf_counter()
    try:
        key = load_key(key_path)
        with tempfile.TemporaryDirectory(prefix="scanviz-class-") as folder:
            student = Path(folder) / "student"
            source = Path(submission)
            if source.is_dir():
                shutil.copytree(source, student, symlinks=True)
            else:
                student.mkdir()
                shutil.copyfile(source, student / source.name)
            grades = grade_submissions(folder, key_path, jail=jail, progress=False)
        reveal = key.reveal == "always"
        if platform == "gradescope":
            results = gradescope_results(grades[0], reveal, time.perf_counter() - started)
        else:
            results = prairielearn_results(grades[0], reveal)
    except Exception as error:  # any failure still gives the student a results file
        results = _failure(platform, error)
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text(json.dumps(results, indent=1), encoding="utf-8")
    return results


def requirements() -> list[str]:
    """The packages scanviz needs at run time (its metadata's requirements without extras)."""
    try:
        needed = metadata.requires("scanviz") or []
    except metadata.PackageNotFoundError:
        needed = []
    return [r.split(";")[0].strip() for r in needed if "extra ==" not in r]


_SETUP = """\
#!/usr/bin/env bash
# scanviz autograder setup (Gradescope runs it once, as root, when the image is built).
set -euo pipefail
ROOT=${AUTOGRADER:-/autograder}  # a test runs it elsewhere
SOURCE=$ROOT/source
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends bubblewrap python3 python3-venv ca-certificates
PYTHON=""
for candidate in python3.14 python3.13 python3.12 python3.11 python3; do
  if command -v "$candidate" >/dev/null && "$candidate" -c 'import sys; sys.exit(sys.version_info < (3, 11))'; then
    PYTHON=$(command -v "$candidate"); break
  fi
done
if [ -z "$PYTHON" ]; then  # an older image: Python 3.11 from the distribution, or say why not
  apt-get install -y -qq --no-install-recommends python3.11 python3.11-venv \\
    || { echo "scanviz needs Python >= 3.11; install it in setup.sh" >&2; exit 1; }
  PYTHON=$(command -v python3.11)
fi
"$PYTHON" -m venv "$ROOT/venv"
"$ROOT/venv/bin/python" -m pip install --quiet --upgrade pip
"$ROOT/venv/bin/python" -m pip install --quiet {requirements}
SITE=$("$ROOT/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
echo "$SOURCE/package" > "$SITE/scanviz.pth"
# numba compiles each kernel once: do it now, grading the solved notebooks unjailed (trusted)
WARM=$(mktemp -d)
"$ROOT/venv/bin/python" -m scanviz exercises release "$WARM/class/solved" --with-solutions >/dev/null
"$ROOT/venv/bin/python" -m scanviz grade "$WARM/class" --key "$SOURCE/key.toml" \\
  -o "$WARM/graded" --no-jail >/dev/null 2>&1
rm -rf "$WARM"
# nothing a jailed answer may read: the key, scanviz (the reference), the environment
chmod 700 "$SOURCE" "$ROOT/venv"
chmod 600 "$SOURCE/key.toml"
"""

_RUN = """\
#!/usr/bin/env bash
# scanviz autograder (Gradescope runs it for each submission, as root).
# The answers run jailed: bubblewrap if the container allows it, else as the user nobody.
set -uo pipefail
ROOT=${AUTOGRADER:-/autograder}  # a test runs it elsewhere
mkdir -p "$ROOT/results"
"$ROOT/venv/bin/python" -m scanviz exercises autograde "$ROOT/submission" \\
  --key "$ROOT/source/key.toml" --platform gradescope \\
  -o "$ROOT/results/results.json" --jail auto
"""


def gradescope_zip(path: str | os.PathLike, key_path: str | os.PathLike) -> list[str]:
    """Write a Gradescope autograder zip for the course key at `key_path`; return its names.

    It holds ``setup.sh``, ``run_autograder``, ``key.toml`` and the scanviz
    package as it is installed here (``package/scanviz``), without caches.
    """
    load_key(key_path)  # a key that does not load is refused here, not on Gradescope
    names = []
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:

        def add(name: str, data: bytes, mode: int) -> None:
            info = zipfile.ZipInfo(name, date_time=(2026, 1, 1, 0, 0, 0))
            info.external_attr = mode << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, data)
            names.append(name)

        requirements_text = " ".join(f"'{r}'" for r in requirements())
        add("setup.sh", _SETUP.replace("{requirements}", requirements_text).encode(), 0o755)
        add("run_autograder", _RUN.encode(), 0o755)
        add("key.toml", Path(key_path).read_bytes(), 0o600)
        for file in sorted(_PACKAGE.rglob("*")):
            if file.is_file() and not _cache(file):
                add(f"package/scanviz/{file.relative_to(_PACKAGE)}", file.read_bytes(), 0o644)
    return names


def _cache(path: Path) -> bool:
    return "__pycache__" in path.parts or path.suffix in (".pyc", ".nbi", ".nbc")


_PL_RUN = """\
#!/usr/bin/env bash
# scanviz: PrairieLearn's external grader entrypoint (externalGradingOptions.entrypoint).
# The image needs Python >= 3.11 with scanviz installed and bubblewrap (or runs as root).
set -uo pipefail
mkdir -p /grade/results
python3 -m scanviz exercises autograde /grade/student --key /grade/tests/key.toml \\
  --platform prairielearn -o /grade/results/results.json --jail auto
"""

_PL_README = """\
scanviz for PrairieLearn's external grader
==========================================

Copy `run.sh` and `key.toml` into the question's `tests/` folder, and in the
question's `info.json`:

    "gradingMethod": "External",
    "externalGradingOptions": {
        "enabled": true,
        "image": "<an image with Python >= 3.11, scanviz and bubblewrap>",
        "entrypoint": "/grade/tests/run.sh",
        "timeout": 300
    }

Students submit their notebook (`fileUpload` or the workspace); the grader
writes `/grade/results/results.json` with one test per exercise. Keep
`key.toml` private: the hidden cases derive from its secret.
"""


def prairielearn_tests(out_dir: str | os.PathLike, key_path: str | os.PathLike) -> list[Path]:
    """Write ``run.sh``, ``key.toml`` and a README for a PrairieLearn question's ``tests/``."""
    load_key(key_path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    run = out / "run.sh"
    run.write_text(_PL_RUN, encoding="utf-8")
    run.chmod(0o755)
    key = out / "key.toml"
    shutil.copyfile(key_path, key)
    key.chmod(0o600)
    readme = out / "README.txt"
    readme.write_text(_PL_README, encoding="utf-8")
    return [run, key, readme]

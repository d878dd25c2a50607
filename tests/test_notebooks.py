"""Every lesson and exercise notebook runs top to bottom without errors and without editing.

Where Debian's chromium is installed (``make test`` installs it),
``tests/browser/test_lab.py`` runs every lesson and a sample of the exercise
notebooks (`IN_CHROMIUM`) in JupyterLab and checks all of this and more; those
kernel-only runs are then not repeated.
"""

import os
import shutil
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

IN_THE_BROWSER = pytest.mark.skipif(
    bool(shutil.which("chromium")) or os.access("/usr/bin/chromium", os.X_OK),
    reason="tests/browser/test_lab.py runs every lesson in Chromium and checks the same",
)

NOTEBOOKS = sorted((Path(__file__).parent.parent / "notebooks").glob("*.ipynb"))


def test_there_is_a_tour():
    assert NOTEBOOKS and NOTEBOOKS[0].name == "00_tour.ipynb"


def test_the_browser_sample_names_exercise_notebooks_that_exist():
    assert set(IN_CHROMIUM) <= {p.name for p in EXERCISES} and len(IN_CHROMIUM) < len(EXERCISES)


@IN_THE_BROWSER
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs(path):
    notebook = nbformat.read(path, as_version=4)
    resources = {"metadata": {"path": str(path.parent)}}
    NotebookClient(notebook, timeout=600, kernel_name="python3", resources=resources).execute()
    outputs = [o for c in notebook.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    assert any("image/png" in o.get("data", {}) for o in outputs), f"{path.name} shows no image"


EXERCISES = sorted((Path(__file__).parent.parent / "notebooks" / "exercises").glob("*.ipynb"))
IN_CHROMIUM = (
    "01_midpoint_decision.ipynb",
    "03_edge_table_entry.ipynb",
    "07_scan_loop.ipynb",
    "10_zbuffer_depth.ipynb",
    "14_abuffer_insert.ipynb",
    "16_depth_sort_tests.ipynb",
    "18_perimeter_test.ipynb",
    "21_forward_difference.ipynb",
    "22_dislop_column.ipynb",
)
"""The exercise notebooks tests/browser/test_lab.py opens in JupyterLab: one of each stage's
stepper (lines, a scan step, the whole loop, the z-buffer, the a-buffer, depth sort, the
perimeter, shading, DISLOP). The others are the same template (`scanviz.exercises.release`)
over another exercise; they run here with a kernel only, as every one does without chromium."""
CHROMIUM = bool(shutil.which("chromium")) or os.access("/usr/bin/chromium", os.X_OK)
KERNEL_ONLY = [p for p in EXERCISES if not (CHROMIUM and p.name in IN_CHROMIUM)]


@pytest.mark.parametrize("path", KERNEL_ONLY, ids=lambda p: p.name)
def test_exercise_notebook_runs_as_released(path):
    """The blank notebook runs: the stepper shows the reference, the check cell reports the stub."""
    notebook = nbformat.read(path, as_version=4)
    resources = {"metadata": {"path": str(path.parent)}}
    NotebookClient(notebook, timeout=600, kernel_name="python3", resources=resources).execute()
    outputs = [o for c in notebook.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    check = notebook.cells[-1].outputs
    text = "".join(o.get("data", {}).get("text/plain", "") + o.get("text", "") for o in check)
    html = "".join(o.get("data", {}).get("text/html", "") for o in check)
    assert "public cases 0 of" in text + html and "hidden cases are graded later" in text + html
    assert "NotImplementedError" in text + html

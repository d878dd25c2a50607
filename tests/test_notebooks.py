"""Every lesson notebook runs top to bottom without errors and without editing.

Where Debian's chromium is installed (``make test`` installs it),
``tests/browser/test_lab.py`` runs every notebook in JupyterLab and checks all
of this and more; these kernel-only runs are then not repeated.
"""

import os
import shutil
from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

IN_THE_BROWSER = pytest.mark.skipif(
    bool(shutil.which("chromium")) or os.access("/usr/bin/chromium", os.X_OK),
    reason="tests/browser/test_lab.py runs every notebook in Chromium and checks the same",
)

NOTEBOOKS = sorted((Path(__file__).parent.parent / "notebooks").glob("*.ipynb"))


def test_there_is_a_tour():
    assert NOTEBOOKS and NOTEBOOKS[0].name == "00_tour.ipynb"


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


@IN_THE_BROWSER
@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.name)
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

"""The site builds offline with no warning, and has what a reader comes for (issue 25).

One `sphinx-build -n -W` of docs/ (the pages, the lessons executed, the
gallery run, the API reference from the docstrings) into a temporary folder,
as ``make docs`` builds it into docs/_build/html.
"""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

# One worker builds the site, once: with `--dist loadgroup` an unmarked module's tests are
# shared out one by one, and two workers would each build it, at the same time, in one docs/
# (conf.py writes docs/lessons, docs/api.md, docs/generated and docs/gallery).
pytestmark = pytest.mark.xdist_group("docs")


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    sphinx = [sys.executable, "-m", "sphinx", "-n", "-W", "--keep-going", "-q", "-b", "html"]
    run = subprocess.run(
        [*sphinx, "-d", str(out / "doctrees"), str(ROOT / "docs"), str(out / "html")],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    # Sphinx's messages read "WARNING: ..." (-W makes any of them fail the build); the lessons'
    # kernels log on the same stderr in their own format ("[IPKernelApp] WARNING | ...").
    warnings = re.findall(r"^(?:\S+: )?(?:WARNING|ERROR|CRITICAL): .*", run.stderr, re.M)
    assert run.returncode == 0 and not warnings, run.stderr[-4000:]
    return out / "html"


def test_the_front_page_says_what_scanviz_is_with_a_picture(site):
    front = (site / "index.html").read_text()
    assert "Step through the classic polygon rendering pipeline" in front
    assert re.search(r"<img[^>]+sphx_glr_plot_01", front)


def test_the_gallery_has_twenty_examples_each_with_its_picture(site):
    pages = sorted((site / "gallery").glob("plot_*.html"))
    assert len(pages) >= 20
    for page in pages:
        assert re.search(r'<img[^>]+src="\.\./_images/sphx_glr_plot_', page.read_text()), page.name
    stepping = (site / "gallery" / "plot_23_scan_conversion_steps.html").read_text()
    assert re.search(r'<img[^>]+\.gif"', stepping)  # a stepper, saved as a GIF by the gallery


def test_the_lessons_are_rendered_with_their_outputs_and_stills(site):
    for lesson in sorted((ROOT / "notebooks").glob("[01]*.ipynb")):
        page = (site / "lessons" / lesson.with_suffix(".html").name).read_text()
        pictures = re.findall(r"<img[^>]+src=[\"'](data:image/(?:png|gif)|\.\./_images/)", page)
        assert pictures, lesson.name  # the figures it drew, inline or as files
        assert "Traceback" not in page and "Loading widget" not in page, lesson.name
    scan = (site / "lessons" / "02_scan_conversion.html").read_text()
    assert "data:image/gif;base64," in scan  # a stepper's still: its steps as a short GIF


def test_the_api_reference_documents_every_public_name_with_its_examples(site):
    import scanviz

    for name in scanviz.__all__:
        assert (site / "generated" / f"scanviz.{name}.html").exists(), name
    page = (site / "generated" / "scanviz.scan_convert.html").read_text()
    assert "Parameters" in page and "Examples" in page and "scan_convert" in page

"""Sphinx configuration of the scanviz site: `make docs` builds it into docs/_build/html.

The pages are the markdown files of this folder (MyST), the lessons are the
notebooks of ../notebooks executed at build time (myst-nb; a stepper shows a
static frame where its widget would be), the gallery is ../examples
(sphinx-gallery) and the API reference is generated from the docstrings
(autosummary + numpydoc). Nothing is fetched from the network.
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(HERE / "_ext"))  # scanviz_gallery: the gallery's scraper of steppers

import scanviz  # noqa: E402

project = "scanviz"
author = "the scanviz authors"
copyright = "2026, the scanviz authors"
version = release = getattr(scanviz, "__version__", "")

extensions = [
    "myst_nb",
    "numpydoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
]

# The lessons live in ../notebooks (where JupyterLab opens them); the build copies them here.
LESSONS = HERE / "lessons"


def _copy_lessons() -> None:
    """Copy the lessons here, their links to ../docs/ pointing at the pages beside them."""
    shutil.rmtree(LESSONS, ignore_errors=True)
    LESSONS.mkdir()
    (LESSONS / "exercises").mkdir()
    for notebook in (ROOT / "notebooks").glob("**/*.ipynb"):
        if ".ipynb_checkpoints" in notebook.parts:
            continue
        up = "../" * (len(notebook.relative_to(ROOT / "notebooks").parts) - 1)
        text = notebook.read_text().replace(f"]({up}../docs/", f"]({up}../")
        text = text.replace("](exercises/)", "](../exercise-notebooks.md)")
        (LESSONS / notebook.relative_to(ROOT / "notebooks")).write_text(text)


def _site_links(app, docname: str, source: list[str]) -> None:
    """A page's links to ../notebooks/ (right on GitHub) point at the rendered lessons here."""
    source[0] = source[0].replace("](../notebooks/", "](lessons/")


def setup(app) -> None:
    app.connect("source-read", _site_links)


_copy_lessons()

# The API reference: every name in the __all__ of scanviz and of its public packages.
PACKAGES = (
    "scanviz", "scanviz.raster", "scanviz.transform", "scanviz.shading", "scanviz.visibility",
    "scanviz.abuffer", "scanviz.antialias", "scanviz.surfaces", "scanviz.pipeline",
    "scanviz.scene", "scanviz.io", "scanviz.trace", "scanviz.widgets", "scanviz.exercises",
)  # fmt: skip


def _write_api_page() -> None:
    """api.md: an autosummary per package, each object under the first package that exports it."""
    import importlib

    lines = [
        "# API reference",
        "",
        "Every public name, by package: the names each package's `__all__` lists,",
        "each documented once, where it is first exported. Each page is the",
        "docstring, with its examples.",
        "",
    ]
    first: dict[object, str] = {}
    for name in PACKAGES:
        module = importlib.import_module(name)
        doc = (module.__doc__ or "").strip()
        own, elsewhere = [], []
        for entry in sorted(module.__all__):
            value = getattr(module, entry)
            key = id(value) if callable(value) else f"{name}.{entry}"  # not constants: 3 is 3
            where = first.setdefault(key, f"{name}.{entry}")
            (own if where == f"{name}.{entry}" else elsewhere).append((entry, where))
        lines += [f"## `{name}`", "", doc.splitlines()[0] if doc else "", ""]
        if own:
            lines += ["```{eval-rst}", f".. currentmodule:: {name}", "", ".. autosummary::"]
            lines += ["   :toctree: generated", "", *(f"   {entry}" for entry, _ in own), "```", ""]
        if elsewhere:
            also = ", ".join(f"{{py:obj}}`{entry} <{where}>`" for entry, where in elsewhere)
            lines += [f"Also exported here: {also}.", ""]
    (HERE / "api.md").write_text("\n".join(lines))


_write_api_page()

exclude_patterns = ["_build", "README.md", "**/.ipynb_checkpoints", "gallery/*.ipynb"]
# .rst first: autosummary writes its stubs with the first suffix, and they are reST.
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}

myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

os.environ["SCANVIZ_STILLS"] = "1"  # the executed lessons' widgets also give a still (a GIF)
nb_execution_mode = os.environ.get("SCANVIZ_DOCS_EXECUTE", "force")
nb_execution_timeout = 600
nb_execution_excludepatterns = ["lessons/exercises/*"]  # their answers raise until written
nb_execution_raise_on_error = True
nb_execution_show_tb = True
# Where a widget would be, the static frame it also gives (text/html): no kernel in a page.
nb_mime_priority_overrides = [
    ("html", "text/html", 0),
    ("html", "application/vnd.jupyter.widget-view+json", 100),
]

templates_path = ["_templates"]
autosummary_generate = True
autodoc_typehints = "none"  # the numpydoc sections say the types, in words
autodoc_member_order = "bysource"
autosummary_imported_members = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib", "scanviz_gallery"),
    "matplotlib_animations": False,
}

html_theme = "pydata_sphinx_theme"
html_title = "scanviz"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 6,
}
html_sidebars = {"index": []}

"""sphinx-gallery's scraper of steppers: each new `Stepper` of an example is saved as a GIF.

``image_scrapers = ("matplotlib", "scanviz_gallery")`` in conf.py; sphinx-gallery
imports this module and calls `_get_sg_image_scraper`. The GIF is the stepper's
steps drawn by `Stepper.save`, from the trace the widget shows, so a page
without a kernel shows the steps.
"""

from __future__ import annotations

from pathlib import Path

_SAVED: set[int] = set()


def _scrape_steppers(block, block_vars, gallery_conf) -> str:
    from sphinx_gallery.scrapers import figure_rst

    from scanviz.widgets import Stepper

    paths = []
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Stepper) and id(value) not in _SAVED:
            _SAVED.add(id(value))
            path = Path(next(block_vars["image_path_iterator"])).with_suffix(".gif")
            value.save(path)
            paths.append(str(path))
    return figure_rst(paths, gallery_conf["src_dir"])


def _get_sg_image_scraper():
    return _scrape_steppers

"""The warm-up: which cached kernels an edit drops, and the note instead of a silent compile."""

import os
import subprocess
import sys
import textwrap

import pytest

from scanviz import warmup
from scanviz.progress import NOTE

SOURCES = {
    "__init__.py": "",
    "a.py": "def f():\n    return 1\n",
    "b.py": "from .a import f\n",
    "sub/__init__.py": "",
    "sub/c.py": "from ..b import f\n",
    "sub/e.py": "import pkg.sub.c\n",
    "d.py": "import numpy\n",
}


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A package `pkg` with a fake numba cache entry beside every module."""
    from numba.core import config

    monkeypatch.setattr(config, "CACHE_DIR", "")
    root = tmp_path / "pkg"
    for name, text in SOURCES.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        cache = path.parent / "__pycache__"
        cache.mkdir(exist_ok=True)
        (cache / f"{path.stem}.kernel-1.py311.nbi").write_text("index")
        (cache / f"{path.stem}.kernel-1.py311.1.nbc").write_text("code")
    return root


def cached(root):
    return sorted(
        str(p.relative_to(root)).replace("__pycache__/", "").split(".")[0]
        for p in root.rglob("*.nbi")
    )


def test_importers_follow_relative_and_absolute_imports_transitively(package):
    users = warmup.importers(package)
    assert users["a.py"] == {"b.py", "sub/c.py", "sub/e.py"}
    assert users["b.py"] == {"sub/c.py", "sub/e.py"}
    assert users["sub/c.py"] == {"sub/e.py"}
    assert "d.py" not in users


def test_an_edit_drops_the_edited_module_and_its_importers_only(package):
    warmup.record_sources(package)
    (package / "a.py").write_text("def f():\n    return 2\n")
    assert warmup.drop_stale_kernels(package) == 1
    assert cached(package) == ["__init__", "d", "sub/__init__"]


def test_nothing_is_dropped_when_nothing_changed(package):
    warmup.record_sources(package)
    assert warmup.drop_stale_kernels(package) == 0
    assert len(cached(package)) == len(SOURCES)


def test_without_a_record_every_kernel_is_dropped_once(package):
    warmup.drop_stale_kernels(package)
    assert cached(package) == []


def test_a_compile_prints_one_line_instead_of_silence(tmp_path):
    program = textwrap.dedent(
        """
        import scanviz
        from numba import njit

        @njit(cache=True)
        def twice(x):
            return 2 * x

        @njit(cache=True)
        def thrice(x):
            return 3 * x

        print(twice(2) + thrice(1))
        """
    )
    (tmp_path / "probe.py").write_text(program)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    first = subprocess.run(
        [sys.executable, "probe.py"], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    again = subprocess.run(
        [sys.executable, "probe.py"], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert first.stdout == again.stdout == "7\n"
    assert first.stderr.count(NOTE) == 1
    assert NOTE not in again.stderr  # loaded from the cache: nothing compiles

# The two commands of the README: `make lab` and `make test`. Both build .venv from nothing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp

.PHONY: lab test lint bench docs clean chromium jail

# numba's on-disk cache is keyed by each kernel's own file, not by the modules it calls:
# `scanviz warmup` drops the kernels of changed files and of their importers (nothing else)
# and compiles what is missing, with a progress bar, so no lesson or test waits in silence.
WARMUP := $(BIN)/python -m scanviz warmup

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev,lab,bench,docs]"
	touch $(STAMP)

# .jupyter/labconfig holds the project's JupyterLab setting defaults (no news popup, no kernel dialog).
LAB_ENV := JUPYTER_CONFIG_PATH=$(CURDIR)/.jupyter$${JUPYTER_CONFIG_PATH:+:$$JUPYTER_CONFIG_PATH}

# Jupyter refuses to start as root without --allow-root (containers, CI machines): pass it only then.
ALLOW_ROOT := $(if $(filter 0,$(shell id -u)),--allow-root,)

lab: $(STAMP)
	$(WARMUP)
	cd notebooks && $(LAB_ENV) ../$(BIN)/jupyter lab $(ALLOW_ROOT) 00_tour.ipynb

# Debian's chromium for tests/browser (Playwright drives it; no browser is downloaded).
# Never fails: without chromium the browser test skips and says why.
chromium:
	@command -v chromium >/dev/null \
	|| (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends chromium) \
	|| echo "scanviz: could not install chromium; the browser test will skip"

# Debian's bubblewrap: grading runs every student answer in its jail (the tests need it).
jail:
	@command -v bwrap >/dev/null \
	|| (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends bubblewrap)

lint: $(STAMP)
	$(BIN)/ruff check scanviz tests examples docs/conf.py docs/_ext

test: lint chromium jail
	$(WARMUP)
	$(BIN)/python -m scanviz conformance
	$(BIN)/python -m pytest -n 2 --dist loadgroup -q

# Every bench suite into one report (docs/benchmarks.md); its plots into bench-plots/.
bench: $(STAMP)
	$(WARMUP)
	$(BIN)/python -m scanviz bench all --report bench-report.md --plot-dir bench-plots

# The site: docs/_build/html/index.html. Offline; warnings are errors (-n: every reference resolves).
docs: $(STAMP)
	$(WARMUP)
	$(BIN)/sphinx-build -n -W --keep-going -q -b html docs docs/_build/html
	@echo "scanviz: the site is docs/_build/html/index.html"

clean:
	rm -rf $(VENV) .pytest_cache .hypothesis docs/_build docs/lessons docs/gallery docs/generated docs/api.md
	find . -name __pycache__ -prune -exec rm -rf {} +

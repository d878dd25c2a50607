# The two commands of the README: `make lab` and `make test`. Both build .venv from nothing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp

.PHONY: lab test lint bench clean

# numba's on-disk cache is keyed by each kernel's own file, not by the modules it calls:
# drop every cached kernel whenever any package source changes.
NUMBA_STAMP := $(VENV)/.numba-cache-stamp
$(NUMBA_STAMP): $(shell find scanviz -name '*.py') | $(STAMP)
	find scanviz -name '*.nbi' -delete -o -name '*.nbc' -delete
	touch $@

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev,lab,bench]"
	touch $(STAMP)

lab: $(STAMP) $(NUMBA_STAMP)
	cd notebooks && ../$(BIN)/jupyter lab 00_tour.ipynb

lint: $(STAMP)
	$(BIN)/ruff check scanviz tests

test: lint $(NUMBA_STAMP)
	$(BIN)/python -m pytest -n 2 -q

bench: $(STAMP) $(NUMBA_STAMP)
	$(BIN)/python -m scanviz bench raster
	$(BIN)/python -m scanviz bench render

clean:
	rm -rf $(VENV) .pytest_cache .hypothesis
	find . -name __pycache__ -prune -exec rm -rf {} +

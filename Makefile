# tumble: two commands do everything on a fresh machine (see README.md).
#   make demo   creates .venv if needed, installs tumble, runs the T-handle study
#   make test   same set-up, then the import-layer contract, mypy --strict on mass and dynamics
#               ([tool.mypy] in pyproject.toml) and the whole test suite (on every core:
#               pytest-xdist, one file to a worker so module fixtures run once)
#   make docs   same set-up, then the API reference and guides built offline into site/
#   make bench  same set-up plus the benchmark-only extra (MuJoCo), then the benchmarks (ratios
#               against a baseline in the same run)

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.tumble-installed

.PHONY: demo test bench docs clean

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test,cluster,docs]'
	touch $(STAMP)

demo: $(STAMP)
	$(VENV)/bin/tumble demo

test: $(STAMP)
	$(VENV)/bin/lint-imports --no-cache
	$(VENV)/bin/mypy
	$(PY) -m pytest -n auto --dist loadfile

docs: $(STAMP)
	$(VENV)/bin/mkdocs build --strict --site-dir site

bench: $(STAMP)
	$(PY) -m pip install --quiet -e '.[bench]'
	$(PY) benchmarks/run.py

clean:
	rm -rf $(VENV) build site src/*.egg-info .pytest_cache .hypothesis

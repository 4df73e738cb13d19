# tumble: two commands do everything on a fresh machine (see README.md).
#   make demo   creates .venv if needed, installs tumble with what the demo needs (the video
#               extra: an ffmpeg for the MP4s), runs the T-handle study
#   make test   same set-up plus the test, cluster and docs tool chains, then the whole test
#               suite (on every core: pytest-xdist, one file to a worker so module fixtures run
#               once) with, beside it, the import-layer contracts and mypy --strict on mass and
#               dynamics ([tool.mypy] in pyproject.toml; ~10 CPU-s, printed after the suite, and
#               either failing fails make test). The suite writes Python's bytecode caches even
#               where PYTHONDONTWRITEBYTECODE is set: without them each of the suite's subprocesses
#               compiled tumble's modules again, and each run rewrote every test module's asserts
#               (collection 8.6 CPU-s a worker, 4.2 with the caches of an earlier run). So pip
#               does not byte-compile what it installs (--no-compile: 40 -> 28 s): the suite
#               compiles, once, only the modules it imports
#   make docs   creates .venv if needed, installs tumble with the docs extra only (Sphinx and its
#               extensions; the mesh and cluster extras the gallery's scripts run and the
#               notebook extra whose IPython the API pages name), then
#               builds the site (guides, galleries, API reference) offline into site/, every
#               warning an error (open site/index.html)
#   make bench  the test set-up plus the benchmark-only extra (MuJoCo), then the campaigns
#               (benchmarks/campaigns: the many-seed checks too slow for make test) and the
#               benchmarks (ratios against a baseline in the same run)
# Each set-up is a stamp in .venv, remade when pyproject.toml changes; the test set-up holds the
# demo's and the docs' too (the test extra has imageio-ffmpeg; it installs the docs extra, as the
# tests build the site), so it stamps all three.

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
DEMO_STAMP := $(VENV)/.tumble-demo
TEST_STAMP := $(VENV)/.tumble-test
DOCS_STAMP := $(VENV)/.tumble-docs

.PHONY: demo test bench docs clean

$(DEMO_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[video]'
	touch $(DEMO_STAMP)

$(TEST_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet --no-compile -e '.[test,cluster,docs]'
	touch $(DEMO_STAMP) $(DOCS_STAMP) $(TEST_STAMP)

$(DOCS_STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[docs]'
	touch $(DOCS_STAMP)

demo: $(DEMO_STAMP)
	$(VENV)/bin/tumble demo

test: $(TEST_STAMP)
	( $(VENV)/bin/lint-imports --no-cache && $(VENV)/bin/mypy ) > $(VENV)/static-checks.log 2>&1 & checks=$$!; \
	PYTHONDONTWRITEBYTECODE= $(PY) -m pytest -n auto --dist loadfile --no-loadscope-reorder; suite=$$?; \
	wait $$checks; static=$$?; cat $(VENV)/static-checks.log; \
	if [ $$static -ne 0 ]; then echo "make test: the import contracts or mypy failed (above)" >&2; fi; \
	[ $$suite -eq 0 ] && [ $$static -eq 0 ]

docs: $(DOCS_STAMP)
	$(VENV)/bin/sphinx-build -W --keep-going -j 2 -q -b html docs site

bench: $(TEST_STAMP)
	$(PY) -m pip install --quiet -e '.[bench]'
	$(PY) -m pytest -q -p no:cacheprovider benchmarks/campaigns
	$(PY) benchmarks/run.py

clean:
	rm -rf $(VENV) build site src/*.egg-info .pytest_cache .hypothesis

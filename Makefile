# img2logo: the whole set-up is `make figures` and `make test` on a machine with Python >= 3.11.
# Both create the virtual environment .venv/ and install the package into it on first use.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
KIT    := $(VENV)/.installed-kit
LAB    := $(VENV)/.installed-lab
BROWSER := $(VENV)/.installed-browser
STUDIO := $(VENV)/.installed-studio
PORT   ?= 8866
HTMLKIT := $(VENV)/.installed-html
DOCSKIT := $(VENV)/.installed-docs
LIB    := $(shell find img2logo -name '*.py') pyproject.toml
DATA   := $(wildcard data/*.png)
NB     ?= $(basename $(notdir $(wildcard notebooks/*.ipynb)))
RUNS   := $(patsubst %,build/notebooks/%.ipynb,$(NB))

.DELETE_ON_ERROR:
.PHONY: install test test-browser test-wheel lab studio lint format bench quality figures figures-smoke html docs clean FORCE

install: $(STAMP)

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	$(BIN)/python -m img2logo._compiled.kernels  # compiles the kernels once (about 20 s), so that no run waits for it
	$(BIN)/python -m compileall -q img2logo  # the bytecode, as pip writes it for a wheel: no run compiles the sources
	@touch $@

test: $(KIT)
	$(BIN)/python -m pytest -m "not browser and not wheel"

# Optional extras, installed on first use: [kit] (papermill, ipywidgets: the notebooks) for make test,
# make figures and make lab, and [dask] for make test (the batch on a dask LocalCluster); [lab] (JupyterLab)
# for make lab; [browser] (JupyterLab and playwright) for make test-browser. The library (make install, the
# img2logo command) needs none of them.
$(KIT): pyproject.toml $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[dev,kit,dask]'
	@touch $@

# JupyterLab's settings for make lab (its app settings, inside .venv/): no news pop-up, no update check.
LAB_OVERRIDES := $(VENV)/share/jupyter/lab/settings/overrides.json

$(LAB): pyproject.toml $(KIT)
	$(BIN)/python -m pip install --quiet -e '.[dev,kit,lab]'
	@mkdir -p $(dir $(LAB_OVERRIDES))
	@echo '{"@jupyterlab/apputils-extension:notification": {"fetchNews": "false", "checkForUpdates": false}}' > $(LAB_OVERRIDES)
	@touch $@

# The extras each of these installs beside [dev,kit].
$(HTMLKIT): EXTRAS := html
$(DOCSKIT): EXTRAS := docs
$(BROWSER): EXTRAS := browser,docs
$(STUDIO): EXTRAS := studio
$(HTMLKIT) $(DOCSKIT) $(BROWSER) $(STUDIO): pyproject.toml $(KIT)
	$(BIN)/python -m pip install --quiet -e '.[dev,kit,$(EXTRAS)]'
	@touch $@

# The level explorer (notebook 11) in JupyterLab, the studio (notebook 14) in Voila and the docs site (make docs's
# pages at 1366 px: no sideways scroll, math typeset), driven by Debian's
# chromium (apt-get install chromium) through playwright; skipped, with the reason, where chromium is missing.
test-browser: $(BROWSER)
	$(BIN)/python -m pytest -m browser -rs tests/experiments/test_explore_browser.py tests/studio/test_browser.py \
	  tests/studio/test_server.py tests/test_docs_browser.py

# The wheel as a user gets it: built (with its compiled kernels), installed in a fresh venv outside the
# repository, its first run checked (tests/test_wheel.py; needs a C compiler and PyPI, minutes).
test-wheel: $(KIT)
	$(BIN)/python -m pytest -m wheel -rs tests/test_wheel.py

# The designer's studio (notebook 14) as a page, served by Voila on this machine only; Ctrl-C stops it.
# Another port: make studio PORT=8870
studio: $(STUDIO)
	@$(BIN)/python -m img2logo.studio.serve --port $(PORT)

# JupyterLab on the notebooks; Ctrl-C stops it. Options: make lab LAB_ARGS="--no-browser --port 8890"
lab: $(LAB)
	$(BIN)/jupyter lab --notebook-dir=notebooks $(if $(filter 0,$(shell id -u)),--allow-root) \
	  --LabApp.news_url= --LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate $(LAB_ARGS)

# mypy (the [tool.mypy] settings of pyproject.toml) fails when a file has more errors than
# tools/mypy-baseline.txt allows; fewer pass, with "lower the baseline to N" (tools/mypy_baseline.py --write).
lint: $(STAMP)
	$(BIN)/ruff check img2logo tests benchmarks tools
	$(BIN)/ruff format --check img2logo tests benchmarks tools
	$(BIN)/python tools/mypy_baseline.py
	$(BIN)/python -m pytest -q tests/test_notebooks.py -m "not notebook"

format: $(STAMP)
	$(BIN)/ruff format img2logo tests benchmarks tools
	$(BIN)/ruff check --fix img2logo tests benchmarks tools

# Speed against vtracer (and Debian's potrace on drawings, when installed), growth with the drawing; writes
# docs/performance.md. vtracer runs from its own venv, build/bench-venv/ (made on first use, pip install vtracer),
# started as a user starts it (python -I), not from the project's.
bench: $(STAMP)
	$(BIN)/python -m compileall -q img2logo  # the edited sources' bytecode: what an installed copy runs
	$(BIN)/python benchmarks/bench.py

# What the logos keep of the evaluation set's features (benchmarks/data/): a table,
# build/quality/quality.csv and contact sheets. ARGS="--only 'clipart-*'" runs a part.
quality: $(STAMP)
	$(BIN)/python benchmarks/quality.py $(ARGS)

# Every notebook is executed by papermill with its full parameters; its outputs
# go to figures/<notebook>/, the executed copy to build/notebooks/. Only the
# notebooks whose source, library or data changed run again. One alone:
# make figures NB=00_segment_graphs
# Other parameter values (a name the notebook does not have is refused):
# make figures NB=04_tolerance_sweep PARAMS="-p images '[clipart-cat.png]'"
figures: $(RUNS)

build/notebooks/%.ipynb: notebooks/%.ipynb $(LIB) $(DATA) $(if $(PARAMS),FORCE) | $(KIT)
	@mkdir -p $(dir $@)
	@echo "== $< $(if $(PARAMS),($(PARAMS)),(full parameters))"
	@# On failure the runner says why in one line (and where the executed copy with the traceback is).
	@$(BIN)/python -m img2logo.experiments $< $(@:.ipynb=.part.ipynb) $(PARAMS)
	@mv $(@:.ipynb=.part.ipynb) $@
	@$(BIN)/python -c "from img2logo.experiments import write_provenance; write_provenance('$@')"

# The executed notebooks as HTML pages that read offline (figures embedded, math by a local
# MathJax, nothing loaded from the network): build/html/<notebook>.html. One alone:
# make html NB=01_overview (it runs the notebook first if make figures would).
html: $(patsubst %,build/html/%.html,$(NB))

build/html/%.html: build/notebooks/%.ipynb | $(HTMLKIT)
	@mkdir -p $(dir $@)
	@$(BIN)/python -m img2logo.experiments.html $< $(dir $@)

# The docs site in build/docs/ (Sphinx, numpydoc, myst-parser: the extra [docs]): the guide, how it
# works, the design notes, the quality and performance pages, the API reference from the docstrings,
# and the pages of make html when they exist. A warning fails the build.
docs: | $(DOCSKIT)
	@# autosummary writes docs/generated/ anew: a page of a module that no longer exists would fail -W
	@rm -rf docs/generated
	$(BIN)/sphinx-build -q -W --keep-going -b html docs build/docs
	@echo "wrote build/docs/index.html"

# The same notebooks with their smoke parameters (img2logo.experiments.runner.SMOKE): small and
# fast, outputs in build/smoke/ (never over figures/).
figures-smoke: $(KIT)
	@mkdir -p build/smoke/notebooks
	@for nb in $(NB); do echo "== notebooks/$$nb.ipynb (smoke)"; \
	  $(BIN)/python -m img2logo.experiments notebooks/$$nb.ipynb build/smoke/notebooks/$$nb.ipynb --smoke $(PARAMS) \
	    || exit 1; done

clean:
	rm -rf build .pytest_cache .ruff_cache

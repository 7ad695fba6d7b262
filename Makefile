# img2logo: the whole set-up is `make figures` and `make test` on a machine with Python >= 3.11.
# Both create the virtual environment .venv/ and install the package into it on first use.

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
LIB    := $(wildcard img2logo/*.py img2logo/*/*.py) pyproject.toml
DATA   := $(wildcard data/*.png)
NB     ?= $(basename $(notdir $(wildcard notebooks/*.ipynb)))
RUNS   := $(patsubst %,build/notebooks/%.ipynb,$(NB))

.DELETE_ON_ERROR:
.PHONY: install test lint format bench quality figures figures-smoke clean

install: $(STAMP)

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	@touch $@

test: $(STAMP)
	$(BIN)/python -m pytest

lint: $(STAMP)
	$(BIN)/ruff check img2logo tests benchmarks
	$(BIN)/ruff format --check img2logo tests benchmarks
	$(BIN)/python -m pytest -q tests/test_notebooks.py -m "not notebook"

format: $(STAMP)
	$(BIN)/ruff format img2logo tests benchmarks
	$(BIN)/ruff check --fix img2logo tests benchmarks

bench: $(STAMP)
	$(BIN)/python benchmarks/bench.py

# What the logos keep of the evaluation set's features (benchmarks/data/): a table,
# build/quality/quality.csv and contact sheets. ARGS="--only 'clipart-*'" runs a part.
quality: $(STAMP)
	$(BIN)/python benchmarks/quality.py $(ARGS)

# Every notebook is executed by papermill with its full parameters; its outputs
# go to figures/<notebook>/, the executed copy to build/notebooks/. Only the
# notebooks whose source, library or data changed run again. One alone:
# make figures NB=00_segment_graphs
figures: $(RUNS)

build/notebooks/%.ipynb: notebooks/%.ipynb $(LIB) $(DATA) | $(STAMP)
	@mkdir -p $(dir $@)
	@echo "== $< (full parameters)"
	@$(BIN)/papermill --cwd notebooks --kernel python3 --no-progress-bar --stdout-file /dev/null $< $(@:.ipynb=.part.ipynb) \
	  || { echo "make figures: notebook $< failed; the failing cell is shown above, the executed copy is $(@:.ipynb=.part.ipynb)"; exit 1; }
	@mv $(@:.ipynb=.part.ipynb) $@
	@$(BIN)/python -c "from img2logo.experiments import write_provenance; write_provenance('$@')"

# The same notebooks with smoke=True: small and fast, outputs in build/smoke/ (never over figures/).
figures-smoke: $(STAMP)
	@mkdir -p build/smoke/notebooks
	@for nb in $(NB); do echo "== notebooks/$$nb.ipynb (smoke)"; \
	  $(BIN)/papermill --cwd notebooks --kernel python3 --no-progress-bar -p smoke True \
	    notebooks/$$nb.ipynb build/smoke/notebooks/$$nb.ipynb > /dev/null || exit 1; done

clean:
	rm -rf build .pytest_cache .ruff_cache

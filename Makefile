# springlab: `make figures` runs every notebook, `make test` runs the tests.
# The first run creates .venv and installs the project with the pinned versions.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
# One thread for BLAS everywhere: results and timings do not depend on the machine's cores.
export OMP_NUM_THREADS := 1
export OPENBLAS_NUM_THREADS := 1
export MKL_NUM_THREADS := 1

.PHONY: figures test check-all bench lab format clean

$(STAMP): pyproject.toml constraints.txt
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -c constraints.txt -e '.[dev,dask,robots]'
	touch $@

figures: $(STAMP)
	$(BIN)/python -m springlab.workbench.notebooks --out build/notebooks
	$(BIN)/python -m springlab.workbench.site --notebooks build/notebooks --site build/site --figures figures

test: $(STAMP)
	$(BIN)/python -m pytest -q -n auto -m "not extended"

# Everything CI runs: the tests, the extended checks, and every notebook on another CPU.
check-all: test
	$(BIN)/python -m pytest -q -n auto -m extended
	$(BIN)/python -m springlab.workbench.cpu

$(VENV)/.bench-installed: $(STAMP)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -c constraints.txt -e '.[dev,dask,robots,bench]'
	touch $@

bench: $(VENV)/.bench-installed
	$(BIN)/python benchmarks/run_all.py

lab: $(STAMP)
	$(BIN)/jupyter lab notebooks/

# The chapters' code, formatted to the book's column (notebooks/ruff.toml); `make test` checks it.
format: $(STAMP)
	$(BIN)/ruff format notebooks

clean:
	rm -rf $(VENV) build .pytest_cache .hypothesis
	find . -name __pycache__ -type d -prune -exec rm -rf {} +

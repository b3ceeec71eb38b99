# Two commands for a fresh clone:  `make demo` runs the main job, `make test` runs the tests.
# Each creates .venv on first use and installs what it needs.
PYTHON  ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed
EXAMPLE := examples/pick_place.rmot
OUT     := out
TARGETS := --target rapid --target krl --target fanuc --target urscript --target inform --target val3 --target csv --target json

.PHONY: demo test bench clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# The main job: verify the pick-and-place example on the built-in default cell, compile it for
# every controller, and render a picture of it.
demo: $(STAMP)
	$(BIN)/rmot check $(EXAMPLE)
	$(BIN)/rmot compile $(EXAMPLE) $(TARGETS) -o $(OUT)/pick_place
	$(BIN)/rmot render $(EXAMPLE) -o $(OUT)/pick_place.png
	@echo "demo: vendor programs in $(OUT)/pick_place/, picture in $(OUT)/pick_place.png"

test: $(STAMP)
	$(BIN)/python -m pytest -q

# Benchmarks run on their own (never in `make test`): medians and ratios against peers.
bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[bench]'
	$(BIN)/python -m pytest tests/benchmarks -q -p no:cacheprovider -o python_files='bench_*.py test_*.py' -o addopts='' --benchmark-columns=median,iqr,rounds

clean:
	rm -rf $(VENV) build *.egg-info $(OUT)

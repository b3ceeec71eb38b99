# Two commands for a fresh clone:  `make demo` runs the main job, `make test` runs the tests.
# Each creates .venv on first use and installs what it needs.
PYTHON  ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed
EXAMPLE := examples/pick_place.rmot
OUT     := out
TARGETS := --target rapid --target krl --target fanuc --target urscript --target inform --target val3 --target csv --target json

.PHONY: demo test lint bench clean fuzz mutation

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test,cad]'
	touch $(STAMP)

# The main job: verify the pick-and-place example on the built-in default cell, compile it for
# every controller, and render a picture of it.
demo: $(STAMP)
	$(BIN)/rmot check $(EXAMPLE)
	$(BIN)/rmot compile $(EXAMPLE) $(TARGETS) -o $(OUT)/pick_place
	$(BIN)/rmot render $(EXAMPLE) -o $(OUT)/pick_place.png
	@echo "demo: vendor programs in $(OUT)/pick_place/, picture in $(OUT)/pick_place.png"

# lint, types and the layer contract first (settings in pyproject.toml, how to fix:
# lint19.md), then the tests: one worker per core (pytest-xdist), each test module on one worker
# so its module-scoped fixtures are computed once
test: lint
	$(BIN)/python -m pytest -q -n auto --dist loadfile

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/mypy
	$(BIN)/lint-imports

# Mutation testing, never part of `make test`: mutmut over backends/base.py,
# lang/diagnostics.py and compiler/plan/timing.py, each with only its own test files
# (tests/mutation/mutate.py; MUTATE=base|diagnostics|timing for one). Prints each score.
MUTATE ?= all
mutation: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[mutation]'
	nice -n 10 $(BIN)/python -m tests.mutation.mutate $(MUTATE)

# Benchmarks run on their own (never in `make test`): medians and ratios against peers.
bench: $(STAMP)
	$(BIN)/python -m pip install --quiet -e '.[bench]'
	$(BIN)/python -m pytest tests/benchmarks -q -p no:cacheprovider -o python_files='bench_*.py test_*.py' -o addopts='' --benchmark-columns=median,iqr,rounds

# Fuzzing: FUZZ_N generated projects (tests/robust/gen.py) through the whole
# pipeline, each under a 2 GB memory cap and a 30 s limit in a worker process; counts of
# tracebacks / hangs / memory / crashes go to stdout and $(FUZZ_REPORT). `make test` runs a
# small Hypothesis budget of the same generator (tests/robust/test_fuzz.py). FUZZ_MIX=1 mixes
# in example programs mutated and hostile files (meshes, URDFs, damaged cache entries, attacked
# reports for merge-reports; tests/robust/hostile.py): seed % 4 = 0 generated, 1 mutated, 2-3 hostile.
FUZZ_N      ?= 100000
FUZZ_START  ?= 0
FUZZ_JOBS   ?= 1
FUZZ_MIX    ?=
export FUZZ_MIX
FUZZ_REPORT ?= fuzz-report.json
fuzz: $(STAMP)
	$(BIN)/python -m tests.robust.fuzz --n $(FUZZ_N) --start $(FUZZ_START) --jobs $(FUZZ_JOBS) --timeout 30 --memory-gb 2 --report $(FUZZ_REPORT)

clean:
	rm -rf $(VENV) build *.egg-info $(OUT)

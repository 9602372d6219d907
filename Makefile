# Two entry points for a fresh clone (see README):
#   make demo   set up .venv, then run descgen on the example robot
#   make test   set up .venv, then lint, type-check and run the whole test suite
VENV ?= .venv
PY := $(VENV)/bin/python
BIN := $(VENV)/bin
SPEC ?= specs/warehouse_arm.yaml

.PHONY: setup system-deps demo test lint bench clean

setup: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $@

demo: setup
	$(PY) -m pip install --quiet -e '.[sim,view,collision]'
	$(BIN)/descgen validate $(SPEC)
	$(BIN)/descgen generate $(SPEC)
	$(BIN)/descgen check $(SPEC)
	$(BIN)/descgen simulate $(SPEC) --pose ready
	$(BIN)/descgen report $(SPEC)
	@echo "descgen is installed in $(VENV): run $(BIN)/descgen --help, or . $(BIN)/activate first"

lint: setup
	$(BIN)/ruff check descgen tests benchmarks scripts
	$(BIN)/ruff format --check descgen tests benchmarks scripts
	$(BIN)/mypy descgen
	$(BIN)/lint-imports
	$(PY) scripts/check_import_cycles.py

# the system tools the tests use as oracles (check_urdf, tf2, Graphviz, a headless Chromium),
# installed with apt-get where missing (sudo when not root); where that is impossible it says
# which packages are missing and stops: the oracle tests never skip quietly
system-deps:
	@scripts/install-system-deps.sh

# every test, slow and end-to-end ones included, on every core (pytest-xdist); tests write
# only to their tmp_path, so workers share nothing but the read-only repository. The oracles
# are required (DESCGEN_REQUIRE_TOOLS=1): a missing one fails its tests instead of skipping them
test: lint system-deps
	DESCGEN_REQUIRE_TOOLS=1 $(BIN)/pytest -q -n auto --durations=10

# every benchmark beside its anchor, timed by one harness (benchmarks/harness.py: descgen and the
# anchor interleaved, CPU time of the process tree, median and min of 7 pairs), then one table
# (benchmarks/summary.py) under the machine line; about 30 minutes on 2 cores (bench_tf audits a
# 10-minute recording here; --minutes 30 by hand). `make bench QUICK=1`: 3 pairs and smaller
# workloads, for CI; it fails on nothing and prints the table. Without QUICK a benchmark that
# fails makes the target fail, after the table.
QUICK ?=
bench: setup
	@mkdir -p build && rm -f build/bench-rows.jsonl build/bench-failed
	@$(PY) benchmarks/harness.py
	@for b in benchmarks/bench_*.py; do echo "== $$b"; \
		args="$(if $(QUICK),--quick,)"; \
		if [ $$b = benchmarks/bench_tf.py ]; then args="$$args --minutes 10"; fi; \
		BENCH_ROWS=build/bench-rows.jsonl $(PY) $$b $$args || { echo "!! $$b failed"; echo $$b >> build/bench-failed; }; \
	done
	@$(PY) benchmarks/summary.py build/bench-rows.jsonl
	@if [ -z "$(QUICK)" ] && [ -s build/bench-failed ]; then echo "failed: $$(cat build/bench-failed)"; exit 1; fi

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .mypy_cache .ruff_cache

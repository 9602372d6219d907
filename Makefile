# Two entry points for a fresh clone (see README):
#   make demo   set up .venv, then run descgen on the example robot
#   make test   set up .venv, then lint, type-check and run the whole test suite
VENV ?= .venv
PY := $(VENV)/bin/python
BIN := $(VENV)/bin
SPEC ?= specs/warehouse_arm.yaml

.PHONY: setup demo test lint bench clean

setup: $(VENV)/.installed

$(VENV)/.installed: pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $@

demo: setup
	$(BIN)/descgen validate $(SPEC)
	$(BIN)/descgen generate $(SPEC)
	$(BIN)/descgen check $(SPEC)

lint: setup
	$(BIN)/ruff check descgen tests benchmarks
	$(BIN)/ruff format --check descgen
	$(BIN)/mypy descgen

test: lint
	$(BIN)/pytest -q

bench: setup
	@for b in benchmarks/*.py; do echo "== $$b"; $(PY) $$b; done

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .mypy_cache .ruff_cache

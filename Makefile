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
	$(PY) -m pip install --quiet -e '.[sim,view,collision]'
	$(BIN)/descgen validate $(SPEC)
	$(BIN)/descgen generate $(SPEC)
	$(BIN)/descgen check $(SPEC)
	$(BIN)/descgen simulate $(SPEC) --pose ready
	$(BIN)/descgen report $(SPEC)

lint: setup
	$(BIN)/ruff check descgen tests benchmarks
	$(BIN)/ruff format --check descgen tests benchmarks
	$(BIN)/mypy descgen

# every test, slow and end-to-end ones included, on every core (pytest-xdist); tests write
# only to their tmp_path, so workers share nothing but the read-only repository
test: lint
	$(BIN)/pytest -q -n auto

bench: setup
	@for b in benchmarks/*.py; do echo "== $$b"; $(PY) $$b; done

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .mypy_cache .ruff_cache

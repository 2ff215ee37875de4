# Two commands a fresh machine needs: `make demo` and `make test`. Each builds .venv by itself.
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin

.PHONY: demo test test-fast lint types suite bench bench-reproduce-all serve system clean example-bags architecture docs-numbers docs-results docs-verify

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(VENV)/.core: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet --disable-pip-version-check -e '.[language]'
	touch $@

$(VENV)/.dev: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet --disable-pip-version-check -e '.[dev,planning,distributed,plot,bench,envs,language,espresso,embeddings,server,ros]'
	touch $(VENV)/.core $(VENV)/.demo $(VENV)/.server $@

# Every extra a README command needs: all but the sentence-embedding one (torch).
$(VENV)/.demo: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet --disable-pip-version-check -e '.[language,planning,distributed,plot,envs,espresso,server,ros]'
	touch $(VENV)/.core $(VENV)/.server $@

$(VENV)/.server: pyproject.toml | $(BIN)/python
	$(BIN)/pip install --quiet --disable-pip-version-check -e '.[language,server]'
	touch $(VENV)/.core $@

# The browser and database the service tests drive: Debian's chromium and PostgreSQL (installed once, as root;
# apt-get needs root). Not root and not installed: one line says so, and the suite skips the tests needing them.
system:
	@if [ "$$(id -u)" = 0 ]; then \
		command -v chromium >/dev/null 2>&1 || (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null); \
		ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1 || (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq postgresql >/dev/null); \
	elif ! command -v chromium >/dev/null 2>&1 || ! ls /usr/lib/postgresql/*/bin/initdb >/dev/null 2>&1; then \
		echo "make: not root, so chromium and PostgreSQL are not installed (apt-get needs root): the browser and PostgreSQL tests are skipped"; \
	fi

demo: $(VENV)/.demo
	$(BIN)/supportive demo

RUFF := $(BIN)/ruff check src tests benchmarks tools conftest.py

# Lint and the import-layer contract first (a second), then the types (src and tests) beside the suite: mypy
# takes half a minute from a cold cache, spent on the core the suite leaves idle while its tests wait on
# servers and processes. Each one's output is shown whole when it ends; either failing fails `make test`.
test: $(VENV)/.dev system
	$(RUFF)
	$(BIN)/lint-imports
	@$(MAKE) --no-print-directory -j 2 --output-sync=target types suite

types: $(VENV)/.dev
	$(BIN)/mypy

# The suite keeps bytecode in __pycache__ (git-ignored) even where the machine sets PYTHONDONTWRITEBYTECODE:
# its workers, and the hundreds of commands and servers it starts, would otherwise compile every module they
# import (and pytest rewrite every test module) again, each time. The package is compiled once, before the
# workers start, so that they do not both compile it.
SUITE := PYTHONDONTWRITEBYTECODE= $(BIN)/pytest -q -n auto --dist worksteal
COMPILE := $(BIN)/python -m compileall -q src

# The whole suite on every core; an idle worker takes queued tests from a busy one (docs/architecture.md).
# It ends with its 30 slowest tests and their seconds: where the suite's minutes go, in every run's log.
suite: $(VENV)/.dev
	@$(COMPILE)
	$(SUITE) --durations=30

# The edit-test loop: the suite without the tests marked slow (by a marker, or in SLOW in conftest.py), on every core.
test-fast: $(VENV)/.dev
	@$(COMPILE)
	$(SUITE) -m "not slow"

serve: $(VENV)/.server
	$(BIN)/supportive serve --task examples/ikea-chair.yaml --db sqlite:///board.db --host 127.0.0.1 --port 8000

lint: $(VENV)/.dev
	$(RUFF)
	$(BIN)/mypy
	$(BIN)/lint-imports

bench: $(VENV)/.dev
	$(BIN)/python benchmarks/bench_learn.py
	$(BIN)/python benchmarks/bench_admission.py
	$(BIN)/python benchmarks/bench_detector_demos.py
	$(BIN)/python benchmarks/bench_clean_slips.py
	$(BIN)/python benchmarks/bench_order_penalty.py
	$(BIN)/python benchmarks/bench_habits.py
	$(BIN)/python benchmarks/bench_sweep.py
	$(BIN)/python benchmarks/bench_backoff.py
	$(BIN)/python benchmarks/bench_generate.py
	$(BIN)/python benchmarks/bench_inference.py
	$(BIN)/python benchmarks/bench_experiments.py --skip-all
	$(BIN)/python benchmarks/bench_caregiver.py
	$(BIN)/python benchmarks/bench_language.py
	$(BIN)/python benchmarks/bench_cover.py
	$(BIN)/python benchmarks/bench_support.py
	$(BIN)/python benchmarks/bench_service.py
	$(BIN)/python benchmarks/bench_social.py
	$(BIN)/python benchmarks/bench_rosbag.py
	$(BIN)/python benchmarks/bench_load.py

# Issue 18's wall time of `supportive reproduce all --workers 2` (every experiment's full run: 40 minutes or
# more), with the active-learning timing of `make bench`; into benchmarks/results/experiments.json.
bench-reproduce-all: $(VENV)/.dev
	$(BIN)/python benchmarks/bench_experiments.py

# The numbers the docs quote between <!-- numbers:NAME --> markers, written again from the recorded results
# (docs/results/, benchmarks/results/) and quick commands; `make test` fails while one is out of date.
docs-numbers: $(VENV)/.dev
	$(BIN)/python tools/docs_numbers.py

# The docs-numbers tests with every recorded full run made again and compared (minutes).
docs-verify: $(VENV)/.dev
	SUPPORTIVE_DOCS_VERIFY=1 $(BIN)/pytest -q -n 0 tests/test_docs_numbers.py

# The recorded results those numbers come from, made again (minutes: every experiment's full run, CaptainCook4D).
docs-results: $(VENV)/.dev
	$(BIN)/supportive reproduce all --workers 2 --output out/reproduce
	cp out/reproduce/summary.json docs/results/summary.json
	cp out/reproduce/edge-reduction/metrics.json docs/results/edge-reduction.json
	cp out/reproduce/active-learning-blocks/metrics.json docs/results/active-learning-blocks.json
	cp out/reproduce/captaincook/metrics.json docs/results/captaincook-curves.json
	cp out/reproduce/goal-inference/metrics.json docs/results/goal-inference.json
	cp out/reproduce/goal-inference/timing.json docs/results/goal-inference-timing.json
	cp out/reproduce/transfer/metrics.json docs/results/transfer.json
	cp out/reproduce/caregiver/metrics.json docs/results/caregiver.json
	cp out/reproduce/captaincook-prediction/metrics.json docs/results/captaincook-prediction.json
	cp out/reproduce/active-learning/metrics.json docs/results/active-learning.json
	cp out/reproduce/active-learning/run.json docs/results/active-learning-run.json
	cp out/reproduce/support-tamp/metrics.json docs/results/support-tamp.json
	cp out/reproduce/support-tamp/run.json docs/results/support-tamp-run.json
	cp out/reproduce/generalisation/metrics.json docs/results/generalisation.json
	cp out/reproduce/generalisation/run.json docs/results/generalisation-run.json
	cp out/reproduce/learner-settings/metrics.json docs/results/learner-settings.json
	cp out/reproduce/learner-settings/run.json docs/results/learner-settings-run.json
	cp out/reproduce/mistake-detection/metrics.json docs/results/mistake-detection.json
	cp out/reproduce/selection-settings/metrics.json docs/results/selection-settings.json
	cp out/reproduce/selection-settings/run.json docs/results/selection-settings-run.json
	$(BIN)/supportive captaincook --json > out/captaincook.json
	mv out/captaincook.json docs/results/captaincook.json
	$(BIN)/python tools/docs_numbers.py

# The example bags in examples/bags/, made again from the bundled task files (the same messages every time).
example-bags: $(VENV)/.dev
	rm -rf examples/bags/ikea-chair examples/bags/workbench-blocks
	$(BIN)/python -m supportive.inference.example_bags examples/bags

# docs/architecture.md's layers, contracts and import graph, drawn again from pyproject.toml and the code.
architecture: $(VENV)/.dev
	$(BIN)/python tools/architecture.py

clean:
	rm -rf $(VENV) .pytest_cache .mypy_cache .ruff_cache .hypothesis

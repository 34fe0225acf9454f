# flexmm-mi: every target that needs Python depends on `setup`, so each works on a fresh machine.
#
#   setup                    venv + `pip install -e '.[dev]'` (again when pyproject.toml changes)
#   derive                   always re-derive generated/ and update its source stamp
#   run, figures             re-derive first only when the derivation's sources changed
#   lint                     ruff check . (ruff.toml: pyflakes, import order, pyupgrade, bugbear)
#   test / test-all          fast tests / every test, slow ones included
#   docs                     the HTML site into build/docs/ (Sphinx -W, the tutorial executed)
#   bench, bench-quick       results + PNGs into out/bench/ (gitignored): the git tree stays clean
#   bench-update             the same as bench, rewriting the committed bench/results.json + PNGs
#   stress, stress-quick     bench/stress.py into out/bench/
#   stress-update            the same as stress, rewriting the committed bench/stress.json/.md
#   bench-gpu                bench/gpu.py, gpu_occupancy.py -> bench/results_gpu.json (needs a GPU and .[gpu])
PY ?= python3
VENV := .venv
VPY := $(VENV)/bin/python
STAMP := $(VENV)/.setup-stamp
GENERATED := generated/coefficients.py generated/lattice_coefficients.py generated/lattice_model.py generated/soliton.py generated/derivation.md \
	$(patsubst energy/models/%.toml,generated/models/%.py,$(subst -,_,$(wildcard energy/models/*.toml)))

# The derivation's inputs by content, not by mtime (a fresh clone gives every file a new
# mtime): sha256 of derivation/*.py, the model layer energy/ (its code and built-in
# models/*.toml), the common/ modules it imports (DERIVATION_COMMON;
# tests/test_derivation.py checks the list against derivation's imports) and the SymPy pin
# (generated/ is SymPy's printed output). `make derive` records them in the committed
# generated/SOURCES.sha256; run/figures re-derive only when they differ from it (or a
# generated file is missing).
SOURCES_STAMP := generated/SOURCES.sha256
DERIVATION_COMMON := common/__init__.py common/files.py common/paper.py
SOURCES = LC_ALL=C sha256sum derivation/*.py energy/*.py energy/models/*.toml $(DERIVATION_COMMON) && sed -n 's/^[[:space:]]*"\(sympy[^"]*\)".*/\1/p' pyproject.toml
STALE := $(shell { $(SOURCES); } | cmp -s - $(SOURCES_STAMP) || echo sources-changed)$(filter-out $(wildcard $(GENERATED)),$(GENERATED))

# Bench output: out/bench/ unless BENCH_ARGS=--update (or --out DIR); see bench/README.md.
BENCH_ARGS ?=

.PHONY: setup derive generated lint test test-all run figures bench bench-quick bench-update \
	stress stress-quick stress-update bench-gpu clean docs

setup: $(STAMP)

# PYTHONWARNINGS hides only setuptools' informational "Editable installation." banner.
$(STAMP): pyproject.toml
	@test -x $(VPY) || $(PY) -m venv $(VENV)
	$(VPY) -m pip install -q --upgrade pip
	PYTHONWARNINGS='ignore:Editable installation' $(VPY) -m pip install -q -e '.[dev]'
	@touch $(STAMP)

derive: $(STAMP)
	$(VPY) -m derivation --out generated
	{ $(SOURCES); } > $(SOURCES_STAMP).tmp && mv $(SOURCES_STAMP).tmp $(SOURCES_STAMP)

# generated/ up to date: derive only when its sources changed since the stamp.
ifneq ($(strip $(STALE)),)
generated: derive
else
generated: ;
endif

lint: $(STAMP)
	$(VENV)/bin/ruff check .

# HTML documentation into build/docs/: Sphinx with -W (a warning fails the build), numpydoc
# for the API reference, myst-nb executing docs/tutorial.ipynb (~30 s); the `docs` extra.
DOCS_STAMP := $(VENV)/.docs-stamp
$(DOCS_STAMP): $(STAMP)
	PYTHONWARNINGS='ignore:Editable installation' $(VPY) -m pip install -q -e '.[dev,docs]'
	@touch $(DOCS_STAMP)

docs: $(DOCS_STAMP)
	$(VPY) -m sphinx -W --keep-going -q -b html docs build/docs
	@echo "wrote build/docs/index.html"

# Both cores: the tests that are safe in parallel on TEST_WORKERS pytest-xdist workers, then,
# one at a time, those that start Dask clusters (a paper-chain map, theory-only included; the
# scenes, whose session fixture quick_scenes every xdist worker would compute again), send
# signals, kill processes or time the machine (SERIAL_TESTS: two at once would fight for the
# same cores and ports).
# Both runs always happen; the target fails if either did.
TEST_WORKERS ?= 2
SERIAL_TESTS := tests/test_cluster_faults.py tests/test_faults.py tests/test_faults_cli.py \
	tests/test_maps.py tests/test_tutorial.py tests/test_docs.py tests/test_models_exact.py \
	tests/test_first_hour.py tests/test_threads.py tests/test_bench.py tests/test_gpu.py \
	tests/test_gpu_models.py tests/test_engine95.py \
	tests/test_scenes.py tests/test_figures.py tests/test_cli_help.py tests/test_model_walk.py
PYTEST_PARALLEL = $(VPY) -m pytest -q -n $(TEST_WORKERS) $(addprefix --ignore=,$(SERIAL_TESTS))
PYTEST_SERIAL = $(VPY) -m pytest -q $(SERIAL_TESTS)

test: $(STAMP)
	@rc=0; $(PYTEST_PARALLEL) || rc=1; $(PYTEST_SERIAL) || rc=1; exit $$rc

# -m '' replaces pyproject's addopts -m 'not slow' (the last -m wins): every test runs.
test-all: $(STAMP)
	@rc=0; $(PYTEST_PARALLEL) -m '' || rc=1; $(PYTEST_SERIAL) -m '' || rc=1; exit $$rc

# The main job: coefficients at the test points, then every scene (quick) and out/report.md.
run: $(STAMP) generated
	$(VENV)/bin/flexmm table
	$(VENV)/bin/flexmm run --quick

# Full-size figures (about a minute), copied small into docs/figures/ for the README.
figures: $(STAMP) generated
	$(VENV)/bin/flexmm run --out out/full
	mkdir -p docs/figures
	for d in out/full/*/; do n=$$(basename $$d); \
	  [ -f $$d/figure.png ] && cp $$d/figure.png docs/figures/$$n.png; done; true
	cp out/full/report.md docs/figures/report.md

# Work-precision, long-time energy, scaling, derive/import cost, kernel speed and time to
# 1e-6 against scipy (bench/speed.py), maps -> out/bench/results.json, PNGs
bench: $(STAMP)
	$(VPY) -m bench.simulator $(BENCH_ARGS)
	$(VPY) -m bench.work_precision $(BENCH_ARGS)
	$(VPY) -m bench.speed $(BENCH_ARGS)
	$(VPY) -m bench.error_budget $(BENCH_ARGS)
	$(VPY) -m bench.maps $(BENCH_ARGS)
	$(VPY) -m bench.exact_maps $(BENCH_ARGS)
	$(VPY) -m bench.models $(BENCH_ARGS)

bench-quick: $(STAMP)
	$(VPY) -m bench.simulator --quick $(BENCH_ARGS)
	$(VPY) -m bench.work_precision --quick $(BENCH_ARGS)
	$(VPY) -m bench.speed --quick $(BENCH_ARGS)
	$(VPY) -m bench.error_budget --quick $(BENCH_ARGS)
	$(VPY) -m bench.maps --quick $(BENCH_ARGS)
	$(VPY) -m bench.exact_maps --quick $(BENCH_ARGS)
	$(VPY) -m bench.models --quick $(BENCH_ARGS)

# The committed numbers: bench/results.json, bench/simulator.json, bench/*.png
bench-update:
	$(MAKE) --no-print-directory bench BENCH_ARGS=--update

# Where numerical stability ends -> out/bench/stress.json, stress.md
stress: $(STAMP)
	$(VPY) -m bench.stress $(BENCH_ARGS)

stress-quick: $(STAMP)
	$(VPY) -m bench.stress --quick $(BENCH_ARGS)

# The committed bench/stress.json, bench/stress.md
stress-update:
	$(MAKE) --no-print-directory stress BENCH_ARGS=--update

# The GPU's cell kernel, every model's kernel (ps per site-evaluation) and maps against this
# machine's CPU cores -> bench/results_gpu.json; without a GPU (or the gpu extra) one line
# "no GPU: ..." says which is missing, nothing is written, exit 0.
bench-gpu: $(STAMP)
	command -v nvidia-smi >/dev/null && $(VPY) -m pip install -q -e '.[gpu]' || true
	$(VPY) -m bench.gpu --update $(BENCH_ARGS)
	$(VPY) -m bench.gpu_occupancy --update

clean:
	rm -rf $(VENV) out .pytest_cache

# flexmm-mi: every target that needs Python depends on `setup`, so each works on a fresh machine.
PY ?= python3
VENV := .venv
VPY := $(VENV)/bin/python
STAMP := $(VENV)/.setup-stamp
GENERATED := generated/coefficients.py generated/lattice_coefficients.py generated/lattice_model.py generated/derivation.md

.PHONY: setup derive test test-all run figures bench bench-quick stress stress-quick clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	@test -x $(VPY) || $(PY) -m venv $(VENV)
	$(VPY) -m pip install -q --upgrade pip
	$(VPY) -m pip install -q -e '.[dev]'
	@touch $(STAMP)

# Regenerate only when the derivation sources changed (make's own staleness check).
$(GENERATED) &: $(wildcard derivation/*.py) $(wildcard common/*.py) pyproject.toml | $(STAMP)
	$(VPY) -m derivation --out generated

derive: $(STAMP)
	$(VPY) -m derivation --out generated

test: $(STAMP)
	$(VPY) -m pytest -q

test-all: $(STAMP)
	$(VPY) -m pytest -q -m ''

# The main job: coefficients at the test points, then every scene (quick) and out/report.md.
run: $(STAMP) $(GENERATED)
	$(VENV)/bin/flexmm table
	$(VENV)/bin/flexmm run --quick

# Full-size figures (about a minute), copied small into docs/figures/ for the README.
figures: $(STAMP) $(GENERATED)
	$(VENV)/bin/flexmm run --out out/full
	mkdir -p docs/figures
	for d in out/full/*/; do n=$$(basename $$d); \
	  [ -f $$d/figure.png ] && cp $$d/figure.png docs/figures/$$n.png; done; true
	cp out/full/report.md docs/figures/report.md

# Work-precision, long-time energy, scaling, derive/import cost, kernel speed and time to
# 1e-6 against scipy (bench/speed.py) -> bench/results.json, PNGs
bench: $(STAMP)
	$(VPY) bench/simulator.py
	$(VPY) bench/work_precision.py
	$(VPY) bench/speed.py
	$(VPY) bench/maps.py
	$(VPY) bench/exact_maps.py

bench-quick: $(STAMP)
	$(VPY) bench/simulator.py --quick
	$(VPY) bench/work_precision.py --quick
	$(VPY) bench/speed.py --quick
	$(VPY) bench/maps.py --quick
	$(VPY) bench/exact_maps.py --quick

# Where numerical stability ends -> bench/stress.json, bench/stress.md
stress: $(STAMP)
	$(VPY) bench/stress.py

stress-quick: $(STAMP)
	$(VPY) bench/stress.py --quick

clean:
	rm -rf $(VENV) out .pytest_cache

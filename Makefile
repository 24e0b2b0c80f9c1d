# Single entry point. `make campaign` and `make test` are the README's quick start.
PYTHON ?= python3.11
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
CORES  ?= 2
# one BLAS/OpenMP thread per process: jobs run side by side on a 2-core machine
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

.PHONY: campaign test bench studies report lint clean

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV) || python3 -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	@touch $(STAMP)

# the whole campaign, then its report (every figure and table, from the results alone)
campaign: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --keep-going
	$(BIN)/snakemake --cores $(CORES) --report results/report.html

test: $(STAMP)
	$(BIN)/python -m pytest -q

bench: $(STAMP)
	$(BIN)/python -m ringdamper.bench --out results/benchmarks

# the studies behind the model's choices (config.yaml `studies:`), then their committed tables and figures
studies: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --keep-going studies
	cp results/studies/contact_calibration/*.csv docs/calibration/
	cp results/studies/contact_calibration/*.png docs/figures/
	cp results/studies/contact_state/*.csv docs/calibration/
	cp results/studies/contact_state/*.png docs/figures/

report: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --report results/report.html

lint: $(STAMP)
	$(BIN)/snakemake --lint

clean:
	rm -rf results .snakemake

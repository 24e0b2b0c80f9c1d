# Single entry point. `make campaign` and `make test` are the README's quick start.
PYTHON ?= python3.11
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
CORES  ?= 2
# one BLAS/OpenMP thread per process: jobs run side by side on a 2-core machine
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1

.PHONY: check-import campaign test test-explorer test-cluster bench performance studies fidelity explorer paper-design report lint clean

$(STAMP): pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV) || python3 -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[test]"
	@touch $(STAMP)

# the whole campaign (profiles/default: 2 cores), then its report (every figure and table, from the
# results alone, and the charts of the studies run into results/).
# On a SLURM cluster: pip install -e ".[cluster]"; snakemake --workflow-profile profiles/slurm
campaign: $(STAMP)
	$(BIN)/snakemake --workflow-profile profiles/default --cores $(CORES)
	$(BIN)/snakemake --cores $(CORES) --report results/report.html all study_charts

test: $(STAMP)
	$(BIN)/python -m pytest -q -n 2 --dist loadgroup --durations=15

# the design explorer in a real browser (Debian's chromium + chromium-driver, driven by selenium): the tests
# of marker `browser`, which `make test` deselects (pyproject.toml addopts; docs/explorer.md)
test-explorer: $(STAMP)
	$(BIN)/python -m pytest -q -m browser tests/explorer

# the test campaign on a real single-node SLURM of this machine (root: installs and starts it), its
# arrays against a local run of the same configuration; the daemons are stopped on exit
test-cluster: $(STAMP)
	$(BIN)/python -m pip install --quiet -e ".[test,cluster]"
	.ci/slurm/test_cluster.sh $(BIN) $(or $(WORKDIR),$(CURDIR)/results/test-cluster)

# the import report of a user's own blisk sector (docs/imported.md): checks, counts, mass and the blisk's ND
# frequencies into <results>/imported/; CONFIG is a configuration with geometry.source: imported
CONFIG ?= docs/examples/imported/config.yaml
check-import: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) check_import --configfile $(CONFIG)

bench: $(STAMP)
	$(BIN)/python -m ringdamper.bench --out results/benchmarks

# the performance page docs/performance.md (docs/artifacts.yaml, route `performance`): the figures of the
# campaign in results/ (its tables and job records) and of `make bench` (results/benchmarks/*.json), by
# the generator the workflow's rule `performance_table` runs, without asking Snakemake about the campaign
performance: $(STAMP)
	$(BIN)/python -m ringdamper.performance --results results --out results/tables/performance.md
	$(BIN)/python -m ringdamper.publish performance

# the studies behind the model's choices (config.yaml `studies:`), then their committed tables and figures
# (docs/artifacts.yaml, route `studies`)
studies: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --keep-going studies
	$(BIN)/python -m ringdamper.publish studies

# the fidelity study (config.yaml `fidelity:`; not part of `campaign`), then its committed figures and tables
# (docs/artifacts.yaml, route `fidelity`)
fidelity: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --keep-going fidelity
	$(BIN)/python -m ringdamper.publish fidelity

# a screenshot of the design explorer at the optimum (headless chromium, after the campaign), then its
# committed copy docs/figures/explorer.png (docs/artifacts.yaml, route `explorer`)
explorer: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) results/figures/explorer.png
	$(BIN)/python -m ringdamper.publish explorer

# the campaign with the paper's fixed design (sampling.design: paper) into results/paper-design, then
# its row of the design comparison (docs/artifacts.yaml, route `paper-design`), which the report of an
# adaptive campaign shows beside its own
paper-design: $(STAMP)
	$(BIN)/snakemake --workflow-profile profiles/default --cores $(CORES) \
		--config "sampling={design: paper}" results=results/paper-design
	$(BIN)/python -m ringdamper.publish paper-design --results results/paper-design

# the report of the campaign, with the charts of the studies run into results/ (target study_charts)
report: $(STAMP)
	$(BIN)/snakemake --cores $(CORES) --report results/report.html all study_charts

# ruff (pyproject.toml [tool.ruff]) on the Python, Snakemake's linter on the rules
lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/snakemake --lint
	$(BIN)/python -m tools.function_lengths

clean:
	rm -rf results .snakemake

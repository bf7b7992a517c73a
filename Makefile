# hubbeam: the two commands of README.md.
#   make reproduce   set up .venv (if needed) and run the whole workflow with Snakemake
#   make test        set up .venv (if needed) and run the test suite (with the import contracts and ruff, and
#                    the independent Exudyn and pyBModes checks of the `validation` extra) on two workers,
#                    each test file on one of them (its module fixtures built once)
#   make test-fast   the same without the tests that run Snakemake or kill processes, or are slow
#                    (-m "not workflow and not slow", see tests/conftest.py), on two workers (pytest-xdist)
#   make test-studies  the generated studies (tests/test_generated_studies.py) over HUBBEAM_STUDIES seeds
#                    (default 24: seeds 0-23; or a list, HUBBEAM_STUDIES=4,17), each study's whole workflow
#   make test-slurm  bring up the one-node SLURM cluster (profiles/slurm/local-cluster.sh, as root),
#                    run the workflow on it (pytest -m slurm, tests/test_slurm.py), bring it down
#   make benchmark   set up .venv (if needed) and time hubbeam against scipy (benchmarks/, results/benchmarks)
#   make lock        (maintainers) re-resolve pyproject.toml's dependencies into requirements.lock
# Setup installs hubbeam (editable, with its `test` and `validation` extras: the suite runs the independent
# Exudyn and pyBModes checks) constrained to the exact versions of requirements.lock; it reruns only when
# pyproject.toml or requirements.lock change, or the extras below (the stamp file names them).

PYTHON ?= python3
VENV := .venv
VENV_PYTHON := $(VENV)/bin/python
EXTRAS := test,validation
STAMP := $(VENV)/.hubbeam-installed-$(EXTRAS)

.PHONY: reproduce test test-fast test-studies test-slurm benchmark setup lock

reproduce: $(STAMP)
	PATH="$(CURDIR)/$(VENV)/bin:$$PATH" $(VENV)/bin/snakemake

test: $(STAMP)
	$(VENV_PYTHON) -m pytest -q -n 2 --dist loadfile

test-fast: $(STAMP)
	$(VENV_PYTHON) -m pytest -q -n 2 -m "not workflow and not slow"

HUBBEAM_STUDIES ?= 24
test-studies: $(STAMP)
	HUBBEAM_STUDIES=$(HUBBEAM_STUDIES) $(VENV_PYTHON) -m pytest -q tests/test_generated_studies.py

# The cluster comes down (by the PIDs `up` recorded) even when the tests fail.
test-slurm: $(STAMP)
	$(VENV_PYTHON) -m pip install --quiet --constraint requirements.lock --editable ".[test,cluster]"
	profiles/slurm/local-cluster.sh up
	PATH="$(CURDIR)/$(VENV)/bin:$$PATH" HUBBEAM_TEST_SLURM=1 $(VENV_PYTHON) -m pytest -q -m slurm; \
		status=$$?; profiles/slurm/local-cluster.sh down; exit $$status

benchmark: $(STAMP)
	$(VENV_PYTHON) -m benchmarks

setup: $(STAMP)

$(VENV_PYTHON):
	@$(PYTHON) -c 'import sys; sys.exit(sys.version_info < (3, 11))' || \
		{ echo "hubbeam needs Python >= 3.11; run: make PYTHON=/path/to/python3.11 ..." >&2; exit 1; }
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml requirements.lock | $(VENV_PYTHON)
	$(VENV_PYTHON) -m pip install --quiet --constraint requirements.lock --editable ".[$(EXTRAS)]"
	$(VENV_PYTHON) -m pip check
	touch $@

# Resolve in a throw-away environment (no constraints: this is where versions may move).
LOCK_VENV := .lock-venv
lock:
	rm -rf $(LOCK_VENV)
	$(PYTHON) -m venv $(LOCK_VENV)
	$(LOCK_VENV)/bin/python -m pip install --quiet ".[test,validation]"
	$(LOCK_VENV)/bin/python -m pip check
	{ sed -n '/^#/p' requirements.lock; $(LOCK_VENV)/bin/python -m pip freeze --exclude hubbeam; } > requirements.lock.new
	mv requirements.lock.new requirements.lock
	rm -rf $(LOCK_VENV)

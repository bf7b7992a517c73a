"""The workflow on a SLURM cluster through ``snakemake --profile profiles/slurm``.

Skipped unless ``HUBBEAM_TEST_SLURM=1``: it needs a running cluster, such as the one-node cluster
of ``profiles/slurm/local-cluster.sh`` that ``make test-slurm`` brings up and down. The account and
partition come from ``HUBBEAM_SLURM_ACCOUNT`` and ``HUBBEAM_SLURM_PARTITION`` (default ``local``).
Job states come from squeue (the local cluster keeps no accounting database for sacct).

* a tiny study builds its products on the cluster, as it does on one machine
  (tests/test_study.py);
* a tiny map in four chunks, one cluster job each, gathered on the submitting machine, equals the
  same map run in one process.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from hubbeam.configuration.load import load_config
from hubbeam.configuration.settings import from_config
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.io import open_result
from hubbeam.simulation.sweep import n_chunks, run_sweep

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_study import TINY_STUDY  # noqa: E402

pytestmark = [
    pytest.mark.slurm,
    pytest.mark.skipif(os.environ.get("HUBBEAM_TEST_SLURM") != "1",
                       reason="needs a SLURM cluster: make test-slurm (HUBBEAM_TEST_SLURM=1)"),
]

#: a map of 2 models x 3 x 2 points in chunks of 3 simulations: four cluster jobs
TINY_MAP = {
    "models": ["TLAM", "FOAM"],
    "maneuver": {"kind": "prescribed"},
    "grid": {"wf": {"start": 1.0, "stop": 3.5, "num": 3}, "tf": {"start": 4.0, "stop": 8.0, "num": 2}},
    "t_after": 2.0,
    "modes": 3,
    "outputs": ["peak_tip_deflection", "residual_amplitude"],
    "figure": {"kind": "peak"},
    "chunk_size": 3,
    "in_all": False,
}


def on_cluster(directory: Path, *arguments: str) -> subprocess.CompletedProcess:
    """``snakemake --profile profiles/slurm`` in ``directory`` with the workflow of this
    repository; fails the test with the end of its output unless it succeeds."""
    env = dict(os.environ)
    env.setdefault("HUBBEAM_SLURM_ACCOUNT", "local")
    env.setdefault("HUBBEAM_SLURM_PARTITION", "local")
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"),
               "--directory", str(directory), "--profile", str(REPO / "profiles" / "slurm"),
               "--slurm-status-command", "squeue", *arguments]
    run = subprocess.run(command, cwd=directory, env=env, capture_output=True, text=True,
                         timeout=3600, check=False)
    assert run.returncode == 0, run.stdout[-4000:] + run.stderr[-4000:]
    return run


def cluster_rules(run: subprocess.CompletedProcess) -> list[str]:
    """The rule of every job Snakemake submitted to the cluster, from its log lines
    ``Job N has been submitted with SLURM jobid M (log: .../slurm_logs/rule_<name>/...)``
    (the plugin deletes the logs of successful jobs)."""
    return re.findall(r"submitted with SLURM jobid \d+ \(log: \S*/slurm_logs/rule_(\w+)/",
                      run.stdout + run.stderr)


def test_a_tiny_study_runs_on_the_cluster(tmp_path):
    config = tmp_path / "studies" / "tiny.yaml"
    config.parent.mkdir()
    config.write_text(yaml.safe_dump(TINY_STUDY))
    run = on_cluster(tmp_path, "--configfile", str(config))
    folder = tmp_path / "results" / "tiny"
    for case in TINY_STUDY["cases"]:
        ds = open_result(folder / "simulations" / f"{case}.nc")
        assert ds.attrs["diverged"] == 0 and np.isfinite(ds["tip_transverse"].values).all()
    for product in ("report/report.html", "report/summary.csv", "tiny-results.tar.gz",
                    "figures/compare_models.png"):
        assert (folder / product).stat().st_size > 0, product
    # the computing rules ran as cluster jobs; figures, reports and the archive ran locally
    rules = set(cluster_rules(run))
    assert {"simulate", "matrices", "simulation_kernel"} <= rules
    assert not any("report" in rule or "figure" in rule or "archive" in rule for rule in rules)


def test_a_chunked_map_on_the_cluster_equals_one_run(tmp_path):
    config = tmp_path / "tiny_map.yaml"
    # the order of the grid keys is the order of the axes
    config.write_text(yaml.safe_dump({"sweeps": {"maps": {"tiny_map": TINY_MAP}}}, sort_keys=False))
    run = on_cluster(tmp_path, "results/sweeps/tiny_map.nc", "results/figures/sweep_tiny_map.png",
                     "--configfile", str(REPO / "config" / "config.yaml"), str(config))
    cfg = load_config(REPO / "config" / "config.yaml")
    cfg["sweeps"]["maps"] = {"tiny_map": TINY_MAP}
    sweep = from_config(cfg).sweeps["tiny_map"]
    assert n_chunks(sweep) == 4
    rules = cluster_rules(run)
    assert rules.count("sweep_chunk") == 4  # one cluster job per chunk
    assert "sweep" not in rules and "figure_sweep" not in rules  # gathered and drawn locally
    gathered = open_result(tmp_path / "results" / "sweeps" / "tiny_map.nc")
    alone = run_sweep(sweep, BeamParameters.from_config(cfg))
    for name in alone.variables:
        xr.testing.assert_identical(gathered[name], alone[name])
    assert (tmp_path / "results" / "figures" / "sweep_tiny_map.png").stat().st_size > 0

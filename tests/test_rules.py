"""The rule files with Snakemake itself, for the paper and for a study (tests marked `workflow`):

* `snakemake --lint` finds nothing but the documented notice (no `conda:` or `container:` directive:
  every rule runs in the one environment of requirements.lock, README "The pipeline");
* a dry run lists exactly the jobs of the plan (hubbeam.pipeline.plan.Plan.jobs), each with the
  outputs its step names: the rule files take their files from the plan and nothing else.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from synthetic_results import CONFIG_FILE, REPO

from hubbeam.pipeline.plan import build_plan
from hubbeam.pipeline.steps import file_paths

#: the one lint the workflow keeps, on purpose (README, "The pipeline")
NO_SOFTWARE_DIRECTIVE = "Specify a conda environment or container for each rule."
STUDY = "controller_trust.yaml"


@pytest.fixture
def workdir(tmp_path, monkeypatch) -> Path:
    """A working directory with the paper's configuration and the studies, as in the repository."""
    (tmp_path / "config").mkdir()
    shutil.copy(CONFIG_FILE, tmp_path / "config" / "config.yaml")
    shutil.copytree(REPO / "studies", tmp_path / "studies")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def snakemake_run(workdir: Path, study: str | None, *args: str) -> str:
    """The output of Snakemake on the paper's configuration or on ``studies/<study>``."""
    config = ["--configfile", f"studies/{study}"] if study else []
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"), "--directory",
               str(workdir), "--cores", "1", *args, *config]
    run = subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=600, check=False)
    return run.stdout + run.stderr


@pytest.mark.parametrize("study", [None, STUDY])
def test_snakemake_lint_finds_nothing_but_the_documented_notice(workdir, study):
    output = snakemake_run(workdir, study, "--lint")
    assert "Traceback" not in output, output[-3000:]
    titles = re.findall(r"^    \* (.+?):$", output, re.M)
    assert titles and set(titles) == {NO_SOFTWARE_DIRECTIVE}, sorted(set(titles))
    assert "Lints for snakefile" not in output


def dry_run_jobs(output: str) -> set[tuple[str, frozenset]]:
    """(rule, its outputs) of every job a dry run lists."""
    jobs = set()
    for block in re.split(r"\n(?=(?:local)?rule \S+:\n)", output):
        rule = re.match(r"(?:local)?rule (\S+):\n", block)
        if rule:
            found = re.search(r"^    output: (.*)$", block, re.M)
            jobs.add((rule.group(1), frozenset(found.group(1).split(", ") if found else ())))
    return jobs


@pytest.mark.parametrize("study", [None, STUDY])
def test_a_dry_run_lists_the_jobs_of_the_plan(workdir, study):
    output = snakemake_run(workdir, study, "--dry-run")
    assert "This was a dry-run" in output, output[-3000:]
    config_file = workdir / ("studies/" + study if study else "config/config.yaml")
    plan = build_plan(yaml.safe_load(config_file.read_text()), [config_file.relative_to(workdir)], REPO)
    planned = {(job.rule, frozenset(file_paths(job.job.output))) for job in plan.jobs()} | {("all", frozenset())}
    assert dry_run_jobs(output) == planned

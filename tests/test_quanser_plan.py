"""The Quanser study's plan: the control section's products, what the report reads (seconds: the plan
checks every case's controller, so the module is slow, tests/conftest.py)."""

from __future__ import annotations

import copy

import pytest
import yaml

from hubbeam.configuration.load import read_config_file
from hubbeam.pipeline.plan import build_plan

STUDY = "studies/quanser_rotflex.yaml"


@pytest.fixture(scope="module")
def raw(repo_root) -> dict:
    return read_config_file(repo_root / STUDY)


def test_the_plan_builds_the_control_products_of_the_sampled_cases(raw, tmp_path, monkeypatch, repo_root):
    """A reduced study (two sampled cases and the held hub): the control section's datasets, their
    figures and two implementation files per sampled case are targets, archived and read by the
    report; without the section none of them is."""
    monkeypatch.chdir(tmp_path)
    cfg = copy.deepcopy(raw)
    cfg.pop("case_grids")
    cfg["cases"] = {name: cfg["cases"][name] for name in ("held_oscillation", "lumped_exact", "lumped_kalman")}
    cfg["control"]["sample_time"]["cases"] = ["lumped_exact"]
    cfg["control"]["robustness"]["cases"] = ["lumped_exact", "lumped_kalman"]
    cfg["study"]["comparisons"] = {"lumped": ["lumped_exact", "lumped_kalman"]}
    path = tmp_path / "study.yaml"
    path.write_text(yaml.safe_dump(cfg, sort_keys=False))
    plan = build_plan(yaml.safe_load(path.read_text()), [path], repo_root)
    folder = "results/quanser_rotflex"
    exported = {f"{folder}/control/{case}.{ext}" for case in ("lumped_exact", "lumped_kalman")
                for ext in ("mat", "json")}
    analyses = {f"{folder}/control/sample_time.nc", f"{folder}/control/robustness.nc"}
    figures = {f"{folder}/figures/{key}.{ext}" for key in ("sample_time_sweep", "robustness") for ext in ("pdf", "png")}
    assert exported | analyses | figures <= set(plan.targets)
    report = plan.steps["study_report"].job()
    assert set(report.input["controllers"]) == exported and report.input["sample_time"].endswith("sample_time.nc")
    assert [job.rule for job in plan.jobs() if job.rule.startswith("control_")].count("control_export") == 2
    del cfg["control"]
    path.write_text(yaml.safe_dump(cfg, sort_keys=False))
    plain = build_plan(yaml.safe_load(path.read_text()), [path], repo_root)
    assert not {target for target in plain.targets if "/control/" in target or "sample_time" in target}
    assert "controllers" not in plain.steps["study_report"].job().input

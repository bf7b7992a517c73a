"""Budgets checked before anything runs: the memory a case, a validation run or a sweep would
take (``numerics.memory_budget_mb``) and the smallest step budget that can cover a span."""

from __future__ import annotations

import dataclasses

import pytest

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.configuration.settings import simulation_settings
from hubbeam.core import radau
from hubbeam.model.limits import MEMORY_BUDGET_MB, MIN_STEPS
from hubbeam.model.parameters import BeamParameters
from hubbeam.results.variables import simulation_bytes
from hubbeam.simulation.simulate import simulate


def problems_at(cfg: dict, path: str) -> list[str]:
    with pytest.raises(ConfigError) as caught:
        check_schema(cfg)
    return [str(p) for p in caught.value.problems if p.path == path]


@pytest.mark.parametrize("t_end, size", [(1.0e12, "17.76 PiB"), (1.0e9, "18.19 TiB"), (1.0e6, "18.63 GiB")])
def test_a_case_whose_outputs_exceed_the_memory_budget_is_rejected_naming_case_size_and_limit(
        study_config, t_end, size):
    study_config["cases"]["fig04_foam"]["t_end"] = t_end
    [problem] = problems_at(study_config, "cases.fig04_foam.t_end")
    # 5 modes: 12 scalars + q1, q2 (5 each) + work, dissipated energy + time = 25 values per time
    count = int(t_end / 0.01) + 1
    assert f"case fig04_foam (FOAM, 5 modes) would store {count} output times x 25 values" in problem
    assert size in problem and f"numerics.memory_budget_mb = {MEMORY_BUDGET_MB:g} MiB" in problem


def test_the_memory_budget_is_a_config_key(study_config):
    study_config["cases"]["fig04_foam"]["t_end"] = 1.0e6  # 1e8 times x 25 x 8 bytes = 18.6 GiB
    study_config["numerics"]["memory_budget_mb"] = 19 * 1024
    check_schema(study_config)
    study_config["numerics"]["memory_budget_mb"] = 18 * 1024
    assert problems_at(study_config, "cases.fig04_foam.t_end")


def test_a_validation_run_over_the_budget_is_rejected(study_config):
    study_config["validation"]["cases"]["spinup_wf2p0"]["t_end"] = 1.0e6
    [problem] = problems_at(study_config, "validation.cases.spinup_wf2p0.t_end")
    # the largest run: CFOAM with the most modes of mode_study (10): 12 + 2 * 10 + 2 + 2 * 10 + 2 + 1
    assert "validation run spinup_wf2p0 (CFOAM, 10 modes)" in problem and "57 values" in problem
    assert "GiB" in problem and "2048 MiB" in problem


@pytest.mark.parametrize("change", ["grid", "t_after"])
def test_a_sweep_over_the_budget_is_rejected(study_config, change):
    spec = study_config["sweeps"]["maps"]["spinup_peak"]
    if change == "grid":
        spec["grid"]["wf"]["num"] = spec["grid"]["tf"]["num"] = 10**5  # 2e10 runs
    else:
        spec["t_after"] = 1.0e9  # one run's dense output alone: 2e10 times x 23 values
    [problem] = problems_at(study_config, "sweeps.maps.spinup_peak")
    assert "sweep spinup_peak would take" in problem and "2048 MiB" in problem


def test_the_paper_config_fits_the_default_budget(study_config):
    check_schema(study_config)


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_the_estimate_is_the_size_of_the_dataset(model):
    """simulation_bytes counts exactly what a dataset holds (variables and coordinates)."""
    params = BeamParameters(L=8.0, rho=2766.7, A=7.2968e-5, E=6.8952e10, I=8.2189e-9, Jh=200.0, rA=0.5)
    case = {"name": "short", "model": model, "modes": 2, "t_end": 0.3,
            "maneuver": {"kind": "prescribed", "wf": 1.0, "tf": 1.0}, "tip_mass": {"mass": 0.0, "position": 8.0}}
    numerics = {"rtol": 1e-8, "atol": 1e-10, "output_step": 0.1, "max_steps": 10_000, "step_warning": 10_000,
                "divergence_limit": 1.0, "quadrature_points": 16}
    ds = simulate(case, params, numerics)
    assert ds.nbytes == simulation_bytes(model, 2, 0.3, 0.1)
    with pytest.raises(ConfigError, match=r"cases\.short\.t_end: got 0\.3 s: .*memory_budget_mb = 0\.0001 MiB; "
                       r"allowed: a larger numerics\.memory_budget_mb"):
        simulate(case, params, dict(numerics, memory_budget_mb=0.0001))


def test_a_step_budget_below_the_fewest_steps_is_rejected_and_cannot_finish(study_config):
    study_config["numerics"]["max_steps"] = study_config["numerics"]["step_warning"] = MIN_STEPS - 1
    study_config["sweeps"]["numerics"]["max_steps"] = MIN_STEPS - 1
    for path in ("numerics.max_steps", "sweeps.numerics.max_steps"):
        [problem] = problems_at(study_config, path)
        assert f"got {MIN_STEPS - 1}" in problem and f"an integer >= {MIN_STEPS}" in problem
    # the bound is necessary: the gentlest run (no forcing at all) stops on MIN_STEPS - 1 steps ...
    params = BeamParameters(L=8.0, rho=2766.7, A=7.2968e-5, E=6.8952e10, I=8.2189e-9, Jh=200.0, rA=0.5)
    case = {"name": "at_rest", "model": "FOAM", "modes": 1, "t_end": 1.0,
            "maneuver": {"kind": "torque", "tau_max": 1e-300, "tf": 100.0},
            "tip_mass": {"mass": 0.0, "position": 8.0}}
    numerics = {"rtol": 1e-3, "atol": 1.0, "output_step": 0.5, "step_warning": 1,
                "divergence_limit": 1.0, "quadrature_points": 8}
    # (the objects of hubbeam.configuration.settings are not checked again, so the run can be made below the bound)
    checked_case, checked_numerics = simulation_settings(case, dict(numerics, max_steps=1000), params.L)
    short = simulate(checked_case, params, dataclasses.replace(checked_numerics, max_steps=MIN_STEPS - 1))
    assert short.attrs["integrator_status"] == radau.STATUS_NAMES[radau.TOO_MANY_STEPS]
    # ... and a run that finishes takes at least MIN_STEPS
    done = simulate(case, params, dict(numerics, max_steps=1000))
    assert done.attrs["integrator_status"] == "success" and done.attrs["n_steps"] >= MIN_STEPS

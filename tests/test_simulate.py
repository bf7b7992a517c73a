"""Simulations of the hub-beam (``hubbeam.simulation.simulate``) checked against physics and against itself.

* energy and angular momentum stay constant once the torque pulse has ended (FOAM, TLAM, CFOAM
  are Lagrangian with a free hub), to within the tolerance;
* the tip deflection converges as the tolerance tightens;
* CFOAM and FOAM agree at w_f = 3 rad/s to within the relative size of the terms FOAM drops;
* TLAM above its critical speed is recorded as diverged, without an exception;
* the dataset follows the contract of docs/architecture.md (the synthetic fixtures' table);
* the step budget, the step warning and bad input are reported as documented;
* the kernels compiled without reference counting leave numba's allocation books balanced.

Runs use 2 modes where the purpose allows (the kernel is the same for every mode count).
"""

import dataclasses
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from synthetic_results import HIGH_ORDER_VARIABLES, SIMULATION_VARIABLES, case_of

from hubbeam.configuration.load import ConfigError
from hubbeam.model.parameters import BeamParameters
from hubbeam.simulation.simulate import simulate


@pytest.fixture(scope="module")
def setup(_study_config):
    return BeamParameters.from_config(_study_config), _study_config["numerics"], _study_config


def torque_case(model, modes=2):
    return {"name": f"pulse_{model}", "model": model, "t_end": 12.0, "modes": modes,
            "maneuver": {"kind": "torque", "tau_max": 100.0, "tf": 5.0},
            "tip_mass": {"mass": 0.0, "position": 8.0}}


@pytest.mark.parametrize("model", ["FOAM", "TLAM", "CFOAM"])
@pytest.mark.parametrize("rtol", [1e-7, 1e-10])
def test_energy_and_angular_momentum_are_conserved_after_the_pulse(setup, model, rtol):
    params, numerics, _ = setup
    ds = simulate(torque_case(model), params, dict(numerics, rtol=rtol, atol=1e-2 * rtol))
    assert_conserved_after(ds, 5.0, rtol)


def assert_conserved_after(ds, t_pulse: float, rtol: float) -> None:
    """After a rest-to-rest torque pulse ending at ``t_pulse`` the run ``ds`` did not diverge, its
    energy is constant to ``rtol`` and its angular momentum is zero to ``rtol`` of its scale during
    the pulse (the pulse leaves no net momentum)."""
    assert ds.attrs["diverged"] == 0
    after = ds.time >= t_pulse
    energy = ds.energy[after].values
    momentum = ds.angular_momentum[after].values
    assert np.ptp(energy) <= rtol * np.max(abs(energy))
    assert np.ptp(momentum) <= rtol * float(abs(ds.angular_momentum).max())
    assert abs(momentum[0]) <= rtol * float(abs(ds.angular_momentum).max())


def test_tip_deflection_converges_as_the_tolerance_tightens(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_foam_wf2p8", modes=2)
    tight = simulate(case, params, dict(numerics, rtol=1e-11, atol=1e-13)).tip_transverse
    errors = []
    for rtol in (1e-5, 1e-7, 1e-9):
        tip = simulate(case, params, dict(numerics, rtol=rtol, atol=1e-2 * rtol)).tip_transverse
        errors.append(float(abs(tip - tight).max()))
        assert errors[-1] <= 10 * rtol * float(abs(tight).max())
    assert errors[0] > errors[1] > errors[2]


def test_cfoam_and_foam_agree_within_the_dropped_terms(setup):
    """The tip deflections differ by at most ten times the relative size of the high-order terms
    (dropped transverse force over elastic force, both along the CFOAM run)."""
    from hubbeam.model.matrices import assemble

    params, numerics, config = setup
    cfoam = simulate(case_of(config, "fig04_cfoam", modes=2), params, numerics)
    foam = simulate(case_of(config, "fig04_foam", modes=2), params, numerics)
    K2 = assemble(params, None, 2, numerics["quadrature_points"]).K2
    size = (np.linalg.norm(cfoam.dQ_q2.values, axis=1).max()
            / np.linalg.norm(cfoam.q2.values @ K2.T, axis=1).max())
    assert 0.0 < size < 1e-2
    difference = float(abs(cfoam.tip_transverse - foam.tip_transverse).max())
    assert 0.0 < difference <= 10 * size * float(abs(foam.tip_transverse).max())
    assert set(HIGH_ORDER_VARIABLES) <= set(cfoam.data_vars)
    assert not set(HIGH_ORDER_VARIABLES) & set(foam.data_vars)


def test_tlam_above_its_critical_speed_is_recorded_as_diverged(setup):
    params, numerics, config = setup
    ds = simulate(case_of(config, "fig05_tlam_wf3p5", modes=2), params, numerics)
    assert ds.attrs["diverged"] == 1 and ds.attrs["integrator_status"] == "left_range"
    t_stop = ds.attrs["diverged_at_s"]
    assert 0.0 < t_stop < 50.0 and "diverged" in ds.attrs["warnings"]
    before = ds.time <= t_stop
    assert np.all(np.isnan(ds.tip_transverse[~before])) and np.all(np.isnan(ds.q2[~before]))
    assert np.all(np.isfinite(ds.tip_transverse[before]))
    # it stopped because the tip passed the limit (divergence_limit * L = 8 m) within a step
    limit = numerics["divergence_limit"] * params.L
    assert float(abs(ds.tip_transverse[before]).max()) > 0.5 * limit
    foam = simulate(case_of(config, "fig05_foam_wf3p5", modes=2), params, numerics)
    assert foam.attrs["diverged"] == 0 and math.isnan(foam.attrs["diverged_at_s"])


def test_dataset_follows_the_contract(setup):
    params, numerics, config = setup
    case = case_of(config, "fig10_foam_mt0p1", modes=2, t_end=1.0)
    ds = simulate(case, params, numerics)
    for name, (dims, units, _) in SIMULATION_VARIABLES.items():
        assert ds[name].dims == dims and ds[name].attrs["units"] == units
        assert ds[name].attrs["long_name"]
    for coord, units in (("time", "s"), ("mode", "1")):
        assert ds[coord].attrs["units"] == units and ds[coord].attrs["long_name"]
    assert np.allclose(ds.time, np.arange(101) * numerics["output_step"])
    assert list(ds.mode.values) == [1, 2]
    for key in ("model", "maneuver", "tip_mass_kg", "tip_position_m", "n_modes", "length",
                "hub_inertia", "diverged", "diverged_at_s", "case_config", "Conventions", "title",
                "source", "history", "references", "hubbeam_version", "git_commit", "n_steps",
                "n_rejected", "n_rhs", "rtol", "atol", "warnings"):
        assert key in ds.attrs, key
    assert ds.attrs["tip_mass_kg"] == 0.1 and ds.attrs["tip_position_m"] == 8.0
    assert ds.attrs["rtol"] == numerics["rtol"] and ds.attrs["warnings"] == ""
    # initial state: rest, undeformed; the prescribed hub follows Eq. 43 exactly
    assert float(abs(ds.q2[0]).max()) == 0.0 and float(ds.theta_dot[0]) == 0.0
    t = ds.time.values
    wf, tf = 2.0, 30.0
    assert np.allclose(ds.theta_dot, wf / tf * t - wf / (2 * np.pi) * np.sin(2 * np.pi * t / tf))


def test_step_budget_and_step_warning_are_recorded(setup):
    params, numerics, config = setup
    case = case_of(config, "fig05_foam_wf2p8", modes=2, t_end=5.0)
    ds = simulate(case, params, dict(numerics, max_steps=50, step_warning=10))
    assert ds.attrs["integrator_status"] == "too_many_steps" and ds.attrs["diverged"] == 0
    assert "max_steps = 50" in ds.attrs["warnings"] and "step_warning = 10" in ds.attrs["warnings"]
    assert np.isnan(float(ds.tip_transverse[-1])) and float(ds.tip_transverse[1]) != 0.0


@pytest.mark.parametrize("change, key, fragments", [
    ({"model": "XFOAM"}, "model", ["got 'XFOAM'", "allowed: one of TLAM, FOAM, SFOAM, CFOAM"]),
    ({"maneuver": {"kind": "prescribed", "wf": 2.0}}, "maneuver.tf",
     ["missing (required when kind is 'prescribed')", "allowed: a number > 0"]),
    ({"modes": 0}, "modes", ["got 0", "allowed: an integer >= 1 and <= 20"]),
    ({"modes": 21}, "modes", ["got 21", "allowed: an integer >= 1 and <= 20"]),
    ({"t_end": 1.0e6}, "t_end", ["got 1e+06 s", "allowed: t_end <= "]),
])
def test_bad_cases_are_rejected_naming_the_key(setup, change, key, fragments):
    """simulate checks a bare case by the configuration's one pass: one problem, at the key."""
    params, numerics, config = setup
    with pytest.raises(ConfigError) as error:
        simulate(case_of(config, "fig05_foam_wf2p8").to_dict() | change, params, numerics)
    (problem,) = error.value.problems
    assert problem.path == "cases.fig05_foam_wf2p8." + key, problem
    assert all(fragment in problem.text for fragment in fragments), problem


@pytest.mark.parametrize("change, key, fragments", [
    ({"rtol": -1.0}, "rtol", ["got -1.0", "allowed: a number >= 2.22"]),
    ({"rtol": 1e-15}, "rtol", ["got 1e-15", "allowed: a number >= 2.22"]),
    ({"quadrature_points": 7}, "quadrature_points", ["got 7", "allowed: an integer >= 8 and <= 1000"]),
    ({"step_warning": 10**9}, "step_warning", ["got 1000000000", "allowed: at most numerics.max_steps"]),
])
def test_bad_numerics_are_rejected_naming_the_key(setup, change, key, fragments):
    params, numerics, config = setup
    with pytest.raises(ConfigError) as error:
        simulate(case_of(config, "fig05_foam_wf2p8"), params, dict(numerics, **change))
    (problem,) = error.value.problems
    assert problem.path == "numerics." + key and all(fragment in problem.text for fragment in fragments), problem


def test_the_objects_of_a_configuration_run_unchecked_and_give_the_mapping_result(setup):
    """simulate takes the objects of hubbeam.configuration.settings as well; they give the run of the mapping."""
    from hubbeam.configuration.settings import from_config

    params, numerics, config = setup
    settings = from_config(config)
    case = dataclasses.replace(settings.cases["fig05_foam_wf2p8"], modes=2, t_end=1.0)
    assert case == case_of(config, "fig05_foam_wf2p8", modes=2, t_end=1.0)
    by_objects = simulate(case, settings.beam, settings.numerics)
    by_mapping = simulate(case.to_dict(), params, numerics)
    xr.testing.assert_identical(by_objects.drop_attrs(), by_mapping.drop_attrs())
    assert by_objects.attrs["case_config"] == by_mapping.attrs["case_config"]


def test_workflow_script_writes_the_case_from_the_leading_matrix_blocks(setup, tmp_path):
    """simulate_case.py reads the case's matrices file (more modes than the case uses), writes
    the dataset atomically, and gives what simulate() gives with matrices of its own."""
    import xarray as xr
    from synthetic_results import run_script, simulation_params

    from hubbeam.model.matrices import assemble, to_dataset
    from hubbeam.results.io import open_result, write_netcdf

    params, numerics, config = setup
    case = case_of(config, "fig10_tlam_mt0p1", modes=2, t_end=2.0)
    tip = case.tip_mass
    stored = write_netcdf(to_dataset(assemble(params, tip, 3, numerics["quadrature_points"]),
                                     params, tip), tmp_path / "matrices.nc")
    output = tmp_path / "simulations" / "case.nc"
    run_script("hubbeam.pipeline.jobs.simulation:simulate", input={"matrices": str(stored)}, output={"nc": str(output)},
               params=simulation_params(config, case),
               log=str(tmp_path / "case.log"))
    written = open_result(output)
    direct = simulate(case, params, numerics)
    xr.testing.assert_allclose(written, direct, rtol=1e-10, atol=1e-14)
    assert written.attrs["n_modes"] == 2 and written.attrs["model"] == "TLAM"
    assert "fig10_tlam_mt0p1" in (tmp_path / "case.log").read_text()


def test_runs_free_every_allocation_of_the_numba_runtime():
    """``jit.borrowing_kernel`` kernels leave the reference counts of the arrays they are given to
    their callers; if a count went wrong, an array would be freed twice or never. In a fresh
    process with numba's allocation statistics on, CFOAM and FOAM runs of both maneuver kinds
    (with a tip mass) must free every block the runtime allocated for them."""
    script = textwrap.dedent("""
        from numba.core.runtime import rtsys
        from hubbeam.configuration.load import load_config
        from hubbeam.model.parameters import BeamParameters
        from hubbeam.simulation.simulate import simulate
        config = load_config("config/config.yaml")
        params = BeamParameters.from_config(config)
        maneuvers = [{"kind": "prescribed", "wf": 3.0, "tf": 4.0},
                     {"kind": "torque", "tau_max": 100.0, "tf": 4.0}]
        runs = [{"name": f"{model}_{m['kind']}", "model": model, "t_end": 6.0, "modes": 2,
                 "maneuver": m, "tip_mass": {"mass": 0.2, "position": 8.0}}
                for model in ("CFOAM", "FOAM") for m in maneuvers]
        simulate(runs[0], params, config["numerics"])   # loads the kernels (their constants)
        before = rtsys.get_allocation_stats()
        for case in runs:
            simulate(case, params, config["numerics"])
        after = rtsys.get_allocation_stats()
        print(after.alloc - before.alloc, after.free - before.free,
              after.mi_alloc - before.mi_alloc, after.mi_free - before.mi_free)
    """)
    environment = dict(os.environ, NUMBA_NRT_STATS="1")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=environment, cwd=Path(__file__).resolve().parents[1], timeout=900)
    assert run.returncode == 0, run.stderr[-2000:]
    alloc, free, mi_alloc, mi_free = (int(x) for x in run.stdout.split()[-4:])
    assert alloc > 0 and mi_alloc > 0  # the statistics are on and the runs allocated
    assert (alloc, mi_alloc) == (free, mi_free)

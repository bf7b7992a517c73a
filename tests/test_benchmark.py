"""Smoke test of the benchmark machinery (``benchmarks/``) on a tiny case; no timings.

The tolerance search finds the loosest rung that meets the error target (and none when the
target is out of reach), errors are measured against the reference on the whole grid, slow
scipy runs are aborted at their cap, the first-order right-hand side equals the accelerations
kernel, its plain-Python version computes the same, the command line writes the CSV files and
the benchmark's settings are checked against the study config.
"""

import json
import math

import numpy as np
import pandas as pd
import pytest
import yaml

from benchmarks import cases as bm
from benchmarks.run import main
from benchmarks.search import reference_solution, search_tolerance
from benchmarks.settings import BENCHMARK_CONFIG, load_settings
from benchmarks.timing import warm_timing
from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import case_from_config
from hubbeam.core.first_order import first_order_jacobian, first_order_rhs
from hubbeam.model.parameters import BeamParameters

TINY = {"model": "FOAM", "maneuver": {"kind": "prescribed", "wf": 0.5, "tf": 1.0}, "t_end": 2.0,
        "modes": 1}
LADDER = [1e-2, 1e-4, 1e-6, 1e-8]


@pytest.fixture(scope="module")
def tiny(_study_config):
    case = case_from_config({**_study_config, "cases": {"tiny": TINY}}, "tiny")
    params = BeamParameters.from_config(_study_config)
    return bm.prepare_case("tiny", case, params, _study_config["numerics"], 0.01)


@pytest.fixture(scope="module")
def reference(tiny):
    # no wall-time cap: a loaded machine is slower, not wrong
    tip, info = reference_solution(tiny, 1e-12, 1e-2, cap=None)
    return tip, info


def test_reference_is_converged(reference):
    tip, info = reference
    assert info["max_abs_tip_m"] > 1e-4  # the case deflects the beam
    assert info["change_to_10x_looser_m"] < 1e-9
    assert info["scipy_radau_difference_m"] < 1e-9


def test_first_order_rhs_is_velocity_and_acceleration(tiny):
    from hubbeam.core.eom import accelerations

    rng = np.random.default_rng(3)
    z = rng.normal(scale=1e-2, size=2 * tiny.free.size)
    dz = first_order_rhs(0.4, z, tiny.problem)
    n = tiny.case.modes
    y, v, a = np.zeros(1 + 2 * n), np.zeros(1 + 2 * n), np.zeros(1 + 2 * n)
    y[tiny.free], v[tiny.free] = z[:tiny.free.size], z[tiny.free.size:]
    accelerations(tiny.inputs, 0.4, y, v, tiny.free, a)
    np.testing.assert_array_equal(dz[:tiny.free.size], z[tiny.free.size:])
    np.testing.assert_allclose(dz[tiny.free.size:], a[tiny.free], rtol=1e-14)
    # the plain-Python version computes the same numbers
    np.testing.assert_allclose(bm.python_rhs(tiny.problem)(0.4, z, tiny.problem), dz, rtol=1e-12)
    # and the Jacobian's acceleration rows are the derivative of f
    jac = first_order_jacobian(0.4, z, tiny.problem)
    step = 1e-6
    for j in range(z.size):
        dzj = np.zeros_like(z)
        dzj[j] = step
        central = (first_order_rhs(0.4, z + dzj, tiny.problem)
                   - first_order_rhs(0.4, z - dzj, tiny.problem)) / (2 * step)
        np.testing.assert_allclose(jac[:, j], central, rtol=1e-5, atol=1e-5 * abs(jac).max())


@pytest.mark.parametrize("method", [bm.Method(bm.HUBBEAM), bm.Method("Radau", jacobian=True),
                                    bm.Method("RK45")])
def test_tolerance_search_returns_the_loosest_passing_rung(tiny, reference, method):
    tip, _ = reference
    target = 1e-6
    search = search_tolerance(tiny, method, tip, LADDER, 1e-2, target, cap=60.0)
    assert search.rtol is not None and search.error <= target
    assert search.error == bm.max_error(search.run.tip, tip)
    # every looser rung tried first failed the target, the passing one is the last tried
    assert [r for r, _, _ in search.tried] == sorted(LADDER, reverse=True)[:len(search.tried)]
    assert all(error > target for _, error, _ in search.tried[:-1])
    assert search.tried[-1][0] == search.rtol


def test_unreachable_target_and_cap_are_reported(tiny, reference):
    tip, _ = reference
    search = search_tolerance(tiny, bm.Method(bm.HUBBEAM), tip, [1e-2, 1e-3], 1e-2, 1e-15,
                                 cap=None)
    assert search.rtol is None and search.error > 1e-15 and len(search.tried) == 2
    aborted = search_tolerance(tiny, bm.Method("RK45"), tip, LADDER, 1e-2, 1e-6, cap=1e-9)
    assert aborted.rtol is None and "cap" in aborted.note and math.isinf(aborted.error)


def test_max_error_and_warm_timing():
    reference = np.array([0.0, 1.0, -2.0])
    assert bm.max_error(np.array([0.0, 1.5, -2.0]), reference) == 0.5
    assert math.isinf(bm.max_error(np.array([0.0, np.nan, -2.0]), reference))
    calls = []
    median, count = warm_timing(lambda: calls.append(1) or 2.0, 1.0, repeats=5, budget=100.0)
    assert count == 5 and len(calls) == 4 and median == 2.0
    median, count = warm_timing(lambda: 1.0, 30.0, repeats=5, budget=10.0)
    assert (median, count) == (30.0, 1)


def test_command_line_writes_the_tables(_study_config, tmp_path):
    settings = {"benchmark": {
        "cases": {"tiny": TINY}, "output_step": 0.01, "error_target": 1e-6,
        "tolerances": LADDER, "atol_ratio": 1e-2, "reference_rtol": 1e-12,
        "methods": ["RK45", "Radau"], "jacobian_methods": ["Radau"], "scipy_cases": ["tiny"],
        "python_rhs_case": "tiny", "scaling": {"case": "tiny", "modes": [1], "t_end": [2.0]},
        "sweep_check": {"points": 2, "rtol": 1e-8}}}
    study, bench = tmp_path / "config.yaml", tmp_path / "benchmark.yaml"
    study.write_text(yaml.safe_dump(_study_config))
    bench.write_text(yaml.safe_dump(settings))
    assert main(["--configfile", str(study), "--benchmark-config", str(bench), "--output",
                 str(tmp_path / "out"), "--repeats", "2", "--skip-compilation", "--skip-extras"]) == 0
    table = pd.read_csv(tmp_path / "out" / "integrators.csv")
    assert list(table.columns[:6]) == ["method", "settings", "wall_s", "compile_s", "rhs_calls",
                                       "max_err_m"]
    python_rows = table[table.method.str.endswith("(plain-Python RHS)")]
    assert len(python_rows) == 1 and (python_rows.compile_s == 0).all()
    assert set(table.method) - set(python_rows.method) == {
        "hubbeam radau5", "hubbeam simulate_kernel", "scipy RK45", "scipy Radau",
        "scipy Radau (jitted Jacobian)"}
    by_method = table.set_index("method")
    assert by_method.loc["hubbeam simulate_kernel", "outputs_ratio"] == pytest.approx(
        by_method.loc["hubbeam simulate_kernel", "wall_s"] / by_method.loc["hubbeam radau5", "wall_s"])
    assert by_method.drop(index="hubbeam simulate_kernel").outputs_ratio.isna().all()
    passed = table[table.passed]
    assert (passed.max_err_m <= 1e-6).all() and (passed.wall_s > 0).all()
    assert (passed.rhs_calls > 0).all()
    machine = json.loads((tmp_path / "out" / "machine.json").read_text())
    assert machine["logical_cpus"] >= 1 and machine["numba"]


def test_benchmark_settings_are_checked(repo_root, tmp_path):
    """The shipped settings load; a wrong case reference and a misplaced key are named."""
    study = repo_root / "config" / "config.yaml"
    assert load_settings([study], BENCHMARK_CONFIG)["benchmark"]["cases"]
    settings = yaml.safe_load(BENCHMARK_CONFIG.read_text())
    settings["benchmark"]["python_rhs_case"] = "nowhere"
    settings["benchmark"]["output_step"] = -1.0
    path = tmp_path / "benchmark.yaml"
    path.write_text(yaml.safe_dump(settings))
    with pytest.raises(ConfigError, match=r"benchmark\.output_step: got -1\.0.*allowed: a number > 0"):
        load_settings([study], path)
    settings["benchmark"]["output_step"] = 0.01
    path.write_text(yaml.safe_dump(settings))
    with pytest.raises(ConfigError, match=r"benchmark\.python_rhs_case: got 'nowhere'; allowed: a name of "
                       r"benchmark\.cases"):
        load_settings([study], path)
    settings["benchmark"]["python_rhs_case"] = settings["benchmark"]["scipy_cases"][0]
    settings["benchmark"]["reference_rtol"] = 1e-15  # below hubbeam.model.limits.MIN_RTOL
    path.write_text(yaml.safe_dump(settings))
    with pytest.raises(ConfigError, match=r"benchmark\.reference_rtol: got 1e-15.*a number >= 2\.22"):
        load_settings([study], path)


def test_first_call_counts_the_family_kernels(repo_root):
    """The cold-start measurement runs and reads numba's cache statistics of the kernels of
    both families (a first simulate call loads or compiles one of them in this process)."""
    from benchmarks.fresh_process import first_call

    result = first_call([str(repo_root / "config" / "config.yaml")], TINY)
    assert result["first_call_s"] > 0 and result["second_call_s"] > 0
    assert result["cache_misses"] + result["cache_hits"] >= 1


def test_sweep_rows_of_a_map_without_residuals(study_config):
    """A map that stores only the peak (the three-axis one) gets a throughput row with no
    residual error instead of stopping the benchmark."""
    from benchmarks.extras import sweep_rows

    maps = study_config["sweeps"]["maps"]
    study_config["sweeps"]["maps"] = {"tlam_vs_foam_3d": maps["tlam_vs_foam_3d"]}
    rows = sweep_rows(study_config, BeamParameters.from_config(study_config), 2, 1e-8)
    assert [row["sweep"] for row in rows] == ["tlam_vs_foam_3d"]
    assert rows[0]["simulations"] == 2 * 2 ** 3 and math.isnan(rows[0]["max_abs_err_residual_m"])
    assert rows[0]["max_rel_err_peak"] < 1e-3


def test_campbell_rows_time_every_model_and_the_dataset(study_config, monkeypatch):
    """The tracked-Campbell benchmark (shrunk to 5 speeds, 2 modes) times every model's phases
    and the whole dataset; the state sizes are those of the models."""
    from benchmarks import linear_modes

    monkeypatch.setattr(linear_modes, "SPEEDS", 5)
    monkeypatch.setattr(linear_modes, "MODES", 2)
    rows = linear_modes.campbell_rows(study_config, BeamParameters.from_config(study_config), 1, 1.0)
    assert [row["model"] for row in rows] == ["TLAM", "FOAM", "SFOAM", "CFOAM", "all"]
    assert [row.get("states") for row in rows[:4]] == [10, 10, 6, 10]
    assert all(row["wall_s"] > 0 for row in rows)


def test_the_identification_routes_fit_the_same_problem_to_the_truth():
    """Both routes of the identification benchmark fit the same five parameters to the same 500
    frequencies and recover the truth the response was computed at (a timing of two different
    problems would say nothing)."""
    from benchmarks.identification import identification_rows

    rows = identification_rows(1, 0.0)
    assert [row["route"] for row in rows] == ["hubbeam fit (batched solve)", "scipy least_squares + python-control"]
    for row in rows:
        assert row["max_relative_error"] < 1e-6 and row["parameters"] == 5 and row["frequencies"] == 500
    assert rows[0]["ratio_to_hubbeam"] == 1.0 and rows[1]["ratio_to_hubbeam"] > 0.0


def test_the_time_series_routes_fit_the_same_problem_to_the_truth():
    """Both routes of the time-series benchmark fit the same three parameters to the same doublet's
    record (here 2 s at 200 Hz, 401 samples, so that the test takes seconds) and recover the truth
    within 1 % (the noise's spread is about 0.3 % at most; the starts are 9-33 % off), and agree with
    each other within 1e-3 (they differ by the linearisation and the integrators, 4e-5 when
    written): scipy's linear equations are hubbeam's nonlinear model for this small motion (with a
    1.5 V doublet, noise scaled alike, they differed by 8e-3 and this test failed)."""
    from benchmarks.identification import time_series_rows

    rows = time_series_rows(1, 0.0, duration=2.0, rate=200.0)
    assert [row["route"] for row in rows] == ["hubbeam fit (jitted nonlinear CFOAM)",
                                              "scipy least_squares + solve_ivp (linear equations)"]
    for row in rows:
        assert row["parameters"] == 3 and row["samples"] == 401 and row["evaluations"] > 3
        assert row["max_relative_error"] < 1e-2
    assert rows[0]["max_relative_difference_to_hubbeam"] == 0.0
    assert rows[1]["max_relative_difference_to_hubbeam"] < 1e-3
    assert rows[0]["ratio_to_hubbeam"] == 1.0 and rows[1]["ratio_to_hubbeam"] > 0.0

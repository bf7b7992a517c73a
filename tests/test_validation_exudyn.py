"""The Exudyn ANCF reference (optional dependency) on small models, and its error handling.

The Exudyn tests are skipped when exudyn is not importable; install it with
``pip install -e .[validation]``. Each runs a few-element model in seconds.
"""

import builtins

import numpy as np
import pytest

from hubbeam.core.maneuver import hub_motion
from hubbeam.model.eigen import tip_mass_frequency_roots
from hubbeam.model.modes import clamped_free_roots
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.validation import exudyn_model

TABLE1 = BeamParameters(L=8.0, rho=2.7667e3, A=7.2968e-5, E=6.8952e10, I=8.2189e-9, Jh=200.0,
                        rA=0.5)
NUMERICS = {"rtol": 1e-9, "atol": 1e-11, "output_step": 0.01, "max_steps": 1_000_000,
            "step_warning": 200_000, "divergence_limit": 1.0, "quadrature_points": 64}

requires_exudyn = pytest.mark.skipif(
    not exudyn_model.exudyn_available(),
    reason="exudyn is not installed (optional dependency: pip install -e .[validation])",
)


def _bending_scale(params):
    return np.sqrt(params.EI / (params.rhoA * params.L**4))


@requires_exudyn
def test_non_rotating_first_frequency_converges_to_euler_bernoulli():
    """Cubic ANCF elements: the frequency error falls like h^4, and 8 elements are within 1e-5."""
    exact = clamped_free_roots(1)[0] ** 2 * _bending_scale(TABLE1)
    errors = [exudyn_model.natural_frequencies(TABLE1, None, n, 1)[0] / exact - 1.0
              for n in (2, 4, 8)]
    assert 0.0 < errors[2] < 1e-5
    assert errors[0] / errors[1] > 10.0 and errors[1] / errors[2] > 10.0


@requires_exudyn
def test_non_rotating_first_frequency_with_tip_mass():
    mu = 0.5
    tip = TipMass(mass=mu * TABLE1.rhoA * TABLE1.L, position=TABLE1.L)
    exact = tip_mass_frequency_roots(mu, 1)[0] ** 2 * _bending_scale(TABLE1)
    assert exudyn_model.natural_frequencies(TABLE1, tip, 8, 1)[0] == pytest.approx(exact,
                                                                                rel=1e-5)


@requires_exudyn
def test_slow_spin_up_tip_deflection_agrees_with_foam():
    """A gentle spin-up (0.5 rad/s in 10 s) of an 8-element model against FOAM and TLAM.

    FOAM keeps the kinematics to second order in the deformation, so it should differ from the
    geometrically exact beam by terms of relative order (v/L)^2, i.e. by at most about
    (v_peak / L)^2 v_peak (2.6e-5 m here); the discretisation error of the reference is measured
    by halving the elements. TLAM, without the centrifugal stiffening, must be far off.
    """
    from hubbeam.simulation.simulate import simulate

    wf, tf, t_end = 0.5, 10.0, 12.0
    coarse, fine = (exudyn_model.spin_up(TABLE1, None, wf, tf, t_end,
                                         exudyn_model.ExudynNumerics(elements=n, time_step=2e-3))
                    for n in (4, 8))
    reference = fine["tip_transverse"].values
    discretisation = np.max(np.abs(coarse["tip_transverse"].values - reference))
    assert discretisation < 1e-3 * np.max(np.abs(reference))

    theta = np.array([hub_motion(t, np.array([wf, tf]))[0] for t in fine["time"].values])
    np.testing.assert_allclose(fine["theta"].values, theta, rtol=0.0, atol=1e-9)

    def model(name):
        case = {"name": f"exudyn_test_{name}", "model": name, "t_end": t_end, "modes": 5,
                "maneuver": {"kind": "prescribed", "wf": wf, "tf": tf},
                "tip_mass": {"mass": 0.0, "position": TABLE1.L}}
        ds = simulate(case, TABLE1, NUMERICS)
        np.testing.assert_allclose(ds["time"].values, fine["time"].values, atol=1e-9)
        return ds["tip_transverse"].values

    peak = np.max(np.abs(reference))
    foam = np.max(np.abs(model("FOAM") - reference))
    assert foam <= (peak / TABLE1.L) ** 2 * peak + discretisation
    assert np.max(np.abs(model("TLAM") - reference)) > 20.0 * foam


@requires_exudyn
def test_tip_mass_must_sit_on_a_node():
    with pytest.raises(ValueError, match="tip_mass.position"):
        exudyn_model.build_model(TABLE1, TipMass(mass=0.1, position=7.9), None, elements=4)


def test_missing_exudyn_names_the_extra(monkeypatch):
    real_import = builtins.__import__

    def no_exudyn(name, *args, **kwargs):
        if name == "exudyn" or name.startswith("exudyn."):
            raise ImportError("No module named 'exudyn'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_exudyn)
    with pytest.raises(exudyn_model.ExudynNotInstalled, match=r"pip install -e \.\[validation\]"):
        exudyn_model.require_exudyn()


@pytest.mark.parametrize("settings, key", [
    ({"elements": 0}, "elements"),
    ({"time_step": -1e-3}, "time_step"),
    ({"spectral_radius": 1.0}, "spectral_radius"),
    ({"newton_tolerance": float("nan")}, "newton_tolerance"),
    ({"time_step": 3e-3}, "output_step"),
])
def test_numerics_are_checked(settings, key):
    with pytest.raises(ValueError, match=key):
        exudyn_model.ExudynNumerics(**settings)


def test_tip_metrics_ignore_samples_after_a_divergence():
    from hubbeam.validation.comparison import tip_metrics

    time = np.linspace(0.0, 4.0, 9)
    v = np.array([0.0, -0.2, -0.5, 0.1, 0.3, np.nan, np.nan, np.nan, np.nan])
    metrics = tip_metrics(time, v, tf=1.6)
    assert metrics == {"peak": 0.5, "peak_time": 1.0, "residual": 0.3}
    assert np.isnan(tip_metrics(time, v, tf=2.4)["residual"])


def test_convergence_table_compares_each_study_with_its_finest_run():
    import xarray as xr

    from hubbeam.validation.comparison import convergence_table

    production = {"elements": 16, "time_step": 1e-3, "newton_tolerance": 1e-10}
    time = np.linspace(0.0, 2.0, 5)

    def run(elements, time_step, offset):
        return xr.Dataset({"tip_transverse": ("time", np.sin(time) + offset)},
                          coords={"time": time},
                          attrs={"exudyn_elements": elements, "exudyn_time_step": time_step,
                                 "exudyn_newton_tolerance": 1e-10, "exudyn_newton_iterations": 1,
                                 "exudyn_cpu_time_s": 0.1,
                                 "maneuver": '{"kind": "prescribed", "wf": 1.0, "tf": 1.0}'})

    runs = {"a": run(8, 1e-3, 1e-3), "b": run(16, 1e-3, 1e-4), "c": run(32, 1e-3, 0.0),
            "d": run(16, 2e-3, 3e-4)}
    table = convergence_table(runs, production).set_index(["study", "value"])
    np.testing.assert_allclose(table.loc[("elements", 8), "max_abs_difference_to_finest_m"], 1e-3)
    np.testing.assert_allclose(table.loc[("elements", 8), "max_abs_difference_to_next_finer_m"],
                               9e-4)
    np.testing.assert_allclose(table.loc[("time_step", 2e-3), "max_abs_difference_to_finest_m"],
                               2e-4)
    assert table.loc[("elements", 16), "production"] == 1
    assert ("newton_tolerance", 1e-10) not in table.index  # a study needs two runs


# -- the validation of a study: planned under the study's own folder -----------------------------

@requires_exudyn
@pytest.mark.workflow
def test_validate_plans_a_studys_exudyn_jobs_in_its_own_folder(tmp_path):
    """`snakemake -n validate` with a study that has a `validation` section plans the Exudyn
    jobs and the non-uniform checks under results/<name>/ and logs/<name>/ only: never the
    paper's results/validation/ nor its published-table check."""
    import copy
    import re
    import subprocess
    import sys
    from pathlib import Path

    import yaml
    from test_study import TINY_STUDY

    pytest.importorskip("pybmodes")
    repo = Path(__file__).resolve().parents[1]
    study = copy.deepcopy(TINY_STUDY)
    study["validation"] = {
        "exudyn": {"elements": 4, "time_step": 5.0e-3, "spectral_radius": 0.9,
                   "newton_tolerance": 1.0e-10},
        "models": ["FOAM", "TLAM"],
        "mode_study": [1, 2],
        "cases": {"v_spin": {"maneuver": {"kind": "prescribed", "wf": 2.0, "tf": 1.0}, "t_end": 1.5}},
        "convergence": {"case": "v_spin", "elements": [2, 4], "time_steps": [1.0e-2, 5.0e-3],
                        "newton_tolerances": [1.0e-8, 1.0e-10]},
    }
    config = tmp_path / "tiny.yaml"
    config.write_text(yaml.safe_dump(study))
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(repo / "Snakefile"),
               "--directory", str(tmp_path), "--cores", "1", "--configfile", str(config),
               "-n", "validate"]
    run = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=600,
                         check=False)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    jobs = re.findall(r"^rule (\w+):", run.stdout, flags=re.MULTILINE)
    assert sorted(set(jobs)) == sorted({
        "validate", "validate_exudyn", "validate_models", "validate_case", "validate_comparison",
        "validate_modes", "validate_convergence", "validate_nonuniform", "validation_report"})
    paths = [path.strip() for line in re.findall(r"^\s+(?:output|log): (.*)$", run.stdout,
                                                 flags=re.MULTILINE)
             for path in line.split(",")]
    assert "results/tiny/validation/runs/exudyn_v_spin.nc" in paths
    assert "results/tiny/validation/nonuniform_pybmodes.csv" in paths  # the beam is off the axis
    assert "results/tiny/report/validation_exudyn.html" in paths
    assert paths and all(path.startswith(("results/tiny/", "logs/tiny/")) for path in paths), paths


def test_a_sectioned_beam_is_refused_by_the_exudyn_model_naming_the_key():
    from hubbeam.validation.nonuniform import tapered_beam

    with pytest.raises(ValueError, match=r"beam.sections: the Exudyn reference models a uniform beam"):
        exudyn_model.build_model(tapered_beam(TABLE1))

"""Fixture factory: small synthetic result files that follow the dataset contract exactly.

The figures, tables, report and archive are built and tested against these files until (and
besides) the real simulations exist. The signals are smooth closed-form stand-ins (a quasi-static
lag during the maneuver plus a residual sinusoid of known amplitude and phase), not physics; what
matters is that names, dimensions, units and attributes are those of ``docs/architecture.md``
(the variable table is ``hubbeam.simulation.simulate.VARIABLES`` itself, so a renamed variable reaches the
figure code through these files and breaks its tests on purpose).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr

from hubbeam.results.variables import HIGH_ORDER_VARIABLES, VARIABLES

BEAM = {"length": 8.0, "density": 2.7667e3, "area": 7.2968e-5, "youngs_modulus": 6.8952e10,
        "second_moment": 8.2189e-9, "hub_inertia": 200.0, "hub_radius": 0.5}

#: the contract's variables (name -> (dims, units, long_name)), from the simulation module itself
SIMULATION_VARIABLES = VARIABLES


def residual_signal(t, tf, amplitude, omega, phase):
    """``amplitude * cos(omega (t - tf) + phase)`` for t > tf, 0 before: the known residual."""
    return np.where(t > tf, amplitude * np.cos(omega * (t - tf) + phase), 0.0)


def hub_motion(maneuver: dict, t: np.ndarray):
    """theta, theta_dot, theta_ddot of Eq. 43 (note 1) or a rest-to-rest stand-in for Eq. 44."""
    tf = maneuver["tf"]
    s = np.clip(t, 0.0, tf)
    if maneuver["kind"] == "prescribed":
        wf = maneuver["wf"]
        thd = wf / tf * s - wf / (2 * np.pi) * np.sin(2 * np.pi * s / tf)
        thdd = np.where(t <= tf, wf / tf * (1 - np.cos(2 * np.pi * s / tf)), 0.0)
        th = wf / tf * s**2 / 2 + wf * tf / (4 * np.pi**2) * (np.cos(2 * np.pi * s / tf) - 1)
        th = th + np.where(t > tf, wf * (t - tf), 0.0)
        return th, thd, thdd
    tau = maneuver["tau_max"] * np.where(t <= tf, np.sin(2 * np.pi * s / tf), 0.0)
    thdd = tau / 230.0
    thd = np.cumsum(thdd) * (t[1] - t[0])
    th = np.cumsum(thd) * (t[1] - t[0])
    return th, thd, thdd


def simulation_dataset(case: str, spec: dict, *, n_modes: int | None = None, t_end: float | None = None,
                       dt: float = 0.05, residual: tuple[float, float, float] | None = None,
                       diverge_at: float | None = None, high_order: bool | None = None) -> xr.Dataset:
    """A contract-conforming simulation dataset for ``case`` with configuration ``spec``.

    ``residual = (amplitude, omega, phase)`` fixes the residual vibration of the tip deflection
    after t_f; ``diverge_at`` makes a diverged run (NaN from that time on, ``diverged = 1``);
    ``high_order`` adds the CFOAM variables (default: when the model is CFOAM).
    """
    n = n_modes or spec.get("modes", 5)
    t_end = t_end or spec["t_end"]
    man = spec["maneuver"]
    model = spec["model"]
    t = np.round(np.arange(0.0, t_end + dt / 2, dt), 10)
    th, thd, thdd = hub_motion(man, t)
    tf = man["tf"]
    amp, omega, phase = residual or (0.01 * (1 + (model == "TLAM")), 2.9, 0.3)
    quasi_static = -0.02 * thdd / max(np.max(np.abs(thdd)), 1e-12) * (1 + (model == "TLAM"))
    tip = quasi_static + residual_signal(t, tf, amp, omega, phase)
    if diverge_at is not None:
        tip = tip * np.exp(np.clip(t - tf, 0, None) * 0.3)
    shape = 1.0 / np.arange(1, n + 1) ** 3
    q2 = np.outer(tip / 0.35, shape)
    q1 = np.outer(-1e-4 * tip**2 - 1e-5 * thd**2, shape)
    data = {
        "theta": th, "theta_dot": thd, "theta_ddot": thdd,
        "hub_torque": 230.0 * thdd,
        "Q_theta": np.zeros_like(t) if model == "SFOAM" else -0.01 * thd * np.gradient(tip, t),
        "q1": q1, "q2": q2,
        "tip_transverse": tip, "tip_axial": q1.sum(axis=1) * 0.35,
        "tip_foreshortening": -0.6 * tip**2 / 8.0,
        "body_transverse": tip, "body_axial": q1.sum(axis=1) * 0.35 - 0.6 * tip**2 / 8.0,
        "energy": 0.5 * 230.0 * thd**2, "angular_momentum": 230.0 * thd,
    }
    variables = dict(SIMULATION_VARIABLES)
    if high_order if high_order is not None else model == "CFOAM":
        data |= {"dM_thth": 1e-3 * tip**3, "dQ_theta": 1e-3 * thd * tip**2,
                 "dQ_q1": np.outer(1e-2 * tip**2, shape), "dQ_q2": np.outer(1e-2 * thd * tip**2, shape)}
        variables |= HIGH_ORDER_VARIABLES
    if diverge_at is not None:
        after = t >= diverge_at
        for value in data.values():
            value[after] = np.nan
    ds = xr.Dataset(
        {name: (dims, np.asarray(data[name], dtype=float), {"units": units, "long_name": long_name})
         for name, (dims, units, long_name) in variables.items()},
        coords={"time": ("time", t, {"units": "s", "long_name": "time", "standard_name": "time"}),
                "mode": ("mode", np.arange(1, n + 1), {"units": "1", "long_name": "mode number"})},
    )
    tip_mass = spec.get("tip_mass", {"mass": 0.0, "position": BEAM["length"]})
    ds.attrs = {
        "model": model, "maneuver": json.dumps(man), "tip_mass_kg": float(tip_mass["mass"]),
        "tip_position_m": float(tip_mass["position"]), "n_modes": n, **BEAM,
        "diverged": int(diverge_at is not None),
        "diverged_at_s": float("nan") if diverge_at is None else float(diverge_at),
        "validity": "valid" if diverge_at is None else "diverged", "left_range": 0,
        "large_deflection": int(diverge_at is not None), "small_deflection_limit": 0.1,
        "max_deflection_ratio": float(np.nanmax(np.abs(tip)) / BEAM["length"]),
        "stopped_at_s": float(t[-1]) if diverge_at is None else float(diverge_at),
        "case_config": json.dumps(spec), "Conventions": "CF-1.11", "title": f"hubbeam case {case}",
        "source": "tests/synthetic_results.py (synthetic stand-in)", "history": "synthetic",
        "references": "Bai et al. 2009", "hubbeam_version": "0.1.0", "git_commit": "synthetic",
        "n_steps": 100, "n_rejected": 0, "n_rhs": 800, "rtol": 1e-9, "atol": 1e-11, "warnings": "",
    }
    return ds


def write_dataset(ds: xr.Dataset, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(path, engine="netcdf4", format="NETCDF4")
    return path


CONFIG_FILE = Path(__file__).resolve().parents[1] / "config" / "config.yaml"


def small_study(name: str = "small") -> dict:
    """config/config.yaml made a study of its own (folder results/<name>/) that also asks for the
    paper's products, and shrunk to seconds of computing: every rule of `all`, the paper's and a
    study's, in one configuration. Cases of 6 s with the maneuver over 4 s and at most 2 modes (as
    the tiny workflow of tests/test_archive.py), coarse integrator and grids, no convergence check,
    one measure reading (it simulates nothing), one 2 x 2 sweep of FOAM in one chunk, the
    published-table validation with few modes, the linear models without a tip mass."""
    import yaml

    config = yaml.safe_load(CONFIG_FILE.read_text())
    config["study"] = {"name": name, "title": "A small study",
                       "comparisons": {"spinups": ["fig05_foam_wf2p8", "fig05_tlam_wf2p8"]}}
    del config["numerics"]["convergence_check"]
    config["numerics"] |= {"quadrature_points": 16, "rtol": 1e-6, "atol": 1e-8, "output_step": 0.05}
    config["eigen"] |= {"speeds": {"start": 0.0, "stop": 4.0, "num": 5},
                        "positions": {"start": 0.0, "stop": config["beam"]["length"], "num": 3}}
    config["linear"] |= {"speeds": {"start": 0.0, "stop": 2.0, "num": 3}, "tip_masses": [0.0], "bode_speeds": [1.0],
                         "frequencies": {"start": 1.0, "stop": 100.0, "num": 5}, "shapes": 2}
    for case in config["cases"].values():
        case["t_end"] = 6.0
        case["maneuver"]["tf"] = 4.0
        case["modes"] = min(case.get("modes", 2), 2)
    config["readings"] = {name: reading for name, reading in config["readings"].items()
                          if "measure" in reading["change"]}
    config["readings"] = dict([next(iter(config["readings"].items()))])
    config["sweeps"]["maps"] = {"spinup": {
        "models": ["FOAM"], "maneuver": {"kind": "prescribed"},
        "grid": {"wf": {"start": 1.0, "stop": 2.0, "num": 2}, "tf": {"start": 2.0, "stop": 4.0, "num": 2}},
        "t_after": 1.0, "outputs": ["peak_tip_deflection"], "figure": {"kind": "peak"}}}
    config["validation"]["published"] = {"modes": [6, 8, 10], "gammas": {"start": 0.0, "stop": 10.0, "num": 5}}
    return config


def paper_cases() -> dict[str, dict]:
    """The cases of the project's ``config/config.yaml`` (so the fixtures follow the config)."""
    import yaml

    return yaml.safe_load(CONFIG_FILE.read_text())["cases"]


def write_simulations(directory: Path, cases: dict[str, dict] | None = None, *, dt: float = 0.05,
                      n_modes: int | None = None, overrides: dict[str, dict] | None = None) -> dict[str, Path]:
    """Write ``<directory>/<case>.nc`` for every case (default: all cases of the paper).

    TLAM at 3.5 rad/s and TLAM with 0.5 kg diverge (as the paper says they fail); ``overrides``
    passes extra keyword arguments of :func:`simulation_dataset` per case.
    """
    cases = cases or paper_cases()
    overrides = {"fig05_tlam_wf3p5": {"diverge_at": 41.3}, "fig10_tlam_mt0p5": {"diverge_at": 44.0},
                 **(overrides or {})}
    paths = {}
    for case, spec in cases.items():
        kwargs = {"dt": dt, "n_modes": n_modes and min(n_modes, spec.get("modes", n_modes))}
        kwargs |= overrides.get(case, {})
        paths[case] = write_dataset(simulation_dataset(case, spec, **kwargs), Path(directory) / f"{case}.nc")
    return paths


def write_eigen(directory: Path, n_modes: int = 5, n_quad: int = 24) -> dict[str, Path]:
    """The eigen-analysis products on small grids, written by :mod:`hubbeam.model.eigen` itself:
    ``eigen/{k22,critical_speeds,campbell}.nc`` and ``tables/{table2,critical_speeds}.csv``."""
    from hubbeam.model import eigen
    from hubbeam.model.parameters import BeamParameters

    directory = Path(directory)
    params = BeamParameters.from_config({"beam": BEAM})
    masses, positions, speeds = [0.0, 0.1, 0.5], np.linspace(0.0, 8.0, 5), np.linspace(0.0, 4.0, 9)
    datasets = {
        "k22": eigen.k22_sweep(params, masses, positions, speeds, n_modes, n_quad),
        "critical_speeds": eigen.critical_speed_sweep(params, masses, positions, n_modes, 20.0, n_quad),
        "campbell": eigen.campbell(params, masses, speeds, n_modes, n_quad),
    }
    paths = {name: write_dataset(ds, directory / "eigen" / f"{name}.nc") for name, ds in datasets.items()}
    (directory / "tables").mkdir(parents=True, exist_ok=True)
    paths["table2"] = directory / "tables" / "table2.csv"
    eigen.table2(params, 1.0, n_modes, n_quad).to_csv(paths["table2"], index=False)
    paths["critical_speeds_csv"] = directory / "tables" / "critical_speeds.csv"
    eigen.critical_speed_table(params, masses, n_modes, 20.0, n_quad).to_csv(
        paths["critical_speeds_csv"], index=False)
    return paths


# --- running a workflow script without Snakemake ----------------------------------------------

REPO = Path(__file__).resolve().parents[1]
SCRIPTS = REPO / "workflow" / "scripts"


class Section(dict):
    """Stand-in for Snakemake's named lists: attribute access, ``items()``, iteration over values."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __iter__(self):
        return iter(self.values())

    def __getitem__(self, key):
        return list(self.values())[key] if isinstance(key, int) else super().__getitem__(key)


def case_of(cfg: dict, name: str, **changes):
    """The case ``name`` of the checked configuration ``cfg`` as the workflow hands it to a job
    (:class:`hubbeam.configuration.settings.Case`), with ``changes`` to its fields."""
    import dataclasses

    from hubbeam.configuration.settings import case_from_config

    return dataclasses.replace(case_from_config(cfg, name), **changes)


def simulation_params(cfg: dict, case, convergence_check: bool = False) -> dict:
    """The ``params`` the simulation rule hands ``simulate_case.py`` for ``case`` of the checked
    configuration ``cfg``: the objects of its one check."""
    from hubbeam.configuration.settings import from_config

    settings = from_config(cfg)
    return {"beam": settings.beam, "case": case, "numerics": settings.numerics.simulation(),
            "convergence_check": settings.numerics.convergence_check if convergence_check else None}


def rig_run(case, params, numerics, *, motor=None, loop=None, feedback=None):
    """One integration (``hubbeam.simulation.simulate.run``) of the case mapping ``case`` with the
    drive ``motor`` (a ``DcMotor``, put in the case), a given sampled ``loop`` or the continuous law
    of ``feedback`` (``(case, sm) -> (law, attributes)``): the kernel's arrays, and its matrices as
    ``.matrices``."""
    from types import SimpleNamespace

    from hubbeam.configuration.settings import simulation_settings
    from hubbeam.simulation.simulate import Resolved, case_matrices, run

    if motor is not None:
        case = dict(case, drive=motor.to_dict())
    checked, numerics = simulation_settings(case, numerics, params.L)
    sm = case_matrices(checked, params, numerics)
    law = None if feedback is None else feedback(checked, sm)[0]
    result = run(checked, params, numerics, sm, Resolved(law=law, loop=loop))
    return SimpleNamespace(**result._asdict(), matrices=sm)


def run_script(job: str, *, input=None, output=None, params=None, log=None) -> None:
    """Execute the workflow's script on the job function ``job`` (``"module:function"``) with a
    ``snakemake`` object as Snakemake would (the log goes to ``log`` or, by default, beside the
    first output)."""
    import runpy
    from types import SimpleNamespace

    output = dict(output or {})
    log = log or str(Path(next(iter(output.values()))).with_suffix(".log"))
    snakemake = SimpleNamespace(input=Section(input or {}), output=Section(output),
                                params=Section({"job": job, **(params or {})}), log=Section({"log": log}))
    runpy.run_path(str(SCRIPTS / "run_job.py"), init_globals={"snakemake": snakemake}, run_name="__snakemake__")


# --- validation results (files of rule validate_published and of `snakemake validate`) ----------

#: published rows (source, direction, gamma, alpha, printed, ours with 20 modes, modal change); the
#: Hamza-Cherif and Houmat rows are read as truncated, the last one is deliberately not reproduced
PUBLISHED_ROWS = (
    ("wright1982+hodges1981", "flapwise", 0.0, float("nan"), "3.5160", 3.516015, 0.0),
    ("wright1982+hodges1981", "flapwise", 3.0, float("nan"), "4.7973", 4.797279, 1e-7),
    ("wright1982+hodges1981", "flapwise", 6.0, float("nan"), "7.3604", 7.360374, 1e-7),
    ("hamza-cherif2004", "flapwise", 6.0, 70.0, "7.3603", 7.360374, 1e-7),
    ("hamza-cherif2004", "chordwise", 8.0, 70.0, "4.6105", 4.610587, 1e-6),
    ("hamza-cherif2004", "chordwise", 4.0, 70.0, "3.888", 3.9, 1e-6),
)
#: Exudyn comparison rows: case -> (wf, tip mass, reference peak, reference residual,
#: {model: (max difference, peak, residual, diverged at or None)})
COMPARISON_ROWS = {
    "spin_a": (2.0, 0.0, 0.15, 5e-4, {"FOAM": (2e-5, 0.15001, 5.005e-4, None),
                                      "CFOAM": (5e-5, 0.15004, 5.1e-4, None),
                                      "TLAM": (6e-2, 0.18, 1.85e-3, None)}),
    "spin_b": (3.0, 0.5, 0.30, 2e-3, {"FOAM": (1e-4, 0.3001, 1.996e-3, None),
                                      "CFOAM": (3e-4, 0.3003, 2.1e-3, None),
                                      "TLAM": (8.0, 8.0, float("nan"), 27.6)}),
}


def write_validation(directory: Path) -> dict[str, Path]:
    """Small validation result files in the producers' formats, with known content.

    Keys: ``published``, ``tip_mass``, ``curves``, ``published_figure`` (rule validate_published)
    and ``comparison``, ``mode_study``, ``convergence``, ``exudyn_figure``, ``ritz_fe``,
    ``pybmodes`` (``snakemake validate``).
    """
    import pandas as pd

    from hubbeam.validation.published import ROUNDING
    from hubbeam.validation.rotating_eigen import allowed_interval

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    rows = []
    for source, direction, gamma, alpha, printed, ours, change in PUBLISHED_ROWS:
        low, high = allowed_interval(printed, ROUNDING[source], change)
        difference = ours - float(printed)
        rows.append({"source": source, "direction": direction, "gamma": gamma, "alpha": alpha,
                     "delta": 0.0, "printed": printed, "published": float(printed),
                     "rounding": ROUNDING[source], "omega_n15": ours + change, "omega_n20": ours,
                     "modal_change": change, "difference": difference, "allowed_low": low,
                     "allowed_high": high, "agrees": bool(low <= difference <= high)})
    paths = {"published": directory / "published_comparison.csv",
             "tip_mass": directory / "tip_mass_comparison.csv",
             "curves": directory / "rotating_eigen.nc",
             "published_figure": directory / "rotating_frequencies.png",
             "comparison": directory / "exudyn_comparison.csv",
             "mode_study": directory / "exudyn_mode_study.csv",
             "convergence": directory / "exudyn_convergence.csv",
             "exudyn_figure": directory / "exudyn_comparison.png",
             "ritz_fe": directory / "nonuniform_ritz_fe.csv",
             "pybmodes": directory / "nonuniform_pybmodes.csv"}
    pd.DataFrame(rows).to_csv(paths["published"], index=False)
    tip = []
    for mu, printed, root, change in ((0.0, "1.87510", 1.875104, 0.0), (1.0, "1.24792", 1.247918, 1e-7)):
        low, high = allowed_interval(printed, "rounded", change)
        tip.append({"mu": mu, "printed": printed, "published": float(printed), "root_n15": root + change,
                    "root_n20": root, "modal_change": change, "difference": root - float(printed),
                    "allowed_low": low, "allowed_high": high,
                    "agrees": bool(low <= root - float(printed) <= high)})
    pd.DataFrame(tip).to_csv(paths["tip_mass"], index=False)
    gammas = np.array([0.0, 2.0, 4.0, 6.0, 8.0])
    curves = xr.Dataset({name: ("gamma", values, {"units": "1"}) for name, values in (
        ("omega_flapwise", np.array([3.516, 4.137, 5.585, 7.360, 9.257])),
        ("omega_chordwise", np.array([3.516, 3.620, 3.888, 4.239, 4.611])),
        ("omega_chordwise_uncoupled", np.array([3.516, 3.622, 3.9, 4.263, 4.6572])))},
        coords={"gamma": ("gamma", gammas, {"units": "1"})},
        attrs={"alpha": 70.0, "delta": 0.0, "n_modes": 20})
    write_dataset(curves, paths["curves"])
    comparison, modes = [], []
    for case, (wf, mass, ref_peak, ref_residual, models) in COMPARISON_ROWS.items():
        for model, (difference, peak, residual, diverged_at) in models.items():
            comparison.append({
                "case": case, "model": model, "wf": wf, "tf": 30.0, "tip_mass_kg": mass, "n_modes": 5,
                "max_abs_difference_m": difference, "max_abs_difference_rel_peak": difference / ref_peak,
                "peak_m": peak, "peak_reference_m": ref_peak, "peak_time_s": 14.8,
                "peak_time_reference_s": 14.8, "residual_m": residual, "residual_reference_m": ref_residual,
                "residual_ratio": residual / ref_residual, "diverged": int(diverged_at is not None),
                "diverged_at_s": float("nan") if diverged_at is None else diverged_at})
            if diverged_at is None:
                for n, factor in ((3, 1.5), (5, 1.0), (10, 0.95 if case == "spin_a" else 1.1)):
                    modes.append({"case": case, "model": model, "n_modes": n,
                                  "max_abs_difference_m": factor * difference,
                                  "max_abs_difference_rel_peak": factor * difference / ref_peak})
    pd.DataFrame(comparison).to_csv(paths["comparison"], index=False)
    pd.DataFrame(modes).to_csv(paths["mode_study"], index=False)
    convergence = []
    for study, values, production, errors in (("elements", (8, 16, 32), 16, (5e-6, 1e-7, 0.0)),
                                              ("time_step", (2e-3, 1e-3, 5e-4), 1e-3, (3e-6, 8e-7, 0.0)),
                                              ("newton_tolerance", (1e-8, 1e-10), 1e-10, (4e-13, 0.0))):
        for index, (value, error) in enumerate(zip(values, errors)):
            settings = {"elements": 16, "time_step": 1e-3, "newton_tolerance": 1e-10, study: value}
            convergence.append({
                "study": study, "value": value, "elements": settings["elements"],
                "time_step_s": settings["time_step"], "newton_tolerance": settings["newton_tolerance"],
                "production": int(value == production), "max_abs_difference_to_finest_m": error,
                "max_abs_difference_to_next_finer_m": error if index + 1 < len(values) else float("nan"),
                "peak_m": 0.217, "residual_m": 7.9e-4, "newton_iterations": 1000 * (index + 1),
                "cpu_time_s": 2.0 * (index + 1)})
    pd.DataFrame(convergence).to_csv(paths["convergence"], index=False)
    # non-uniform checks: |ritz / fe - 1| = error * (speed + 1) / 3 * mode / 2, largest at the
    # last speed (2) and mode (2): the error itself, 4e-3 / 2e-5 (bare) and 1e-2 / 3e-4 (tip mass)
    ritz_fe = []
    for case, mass, errors in (("bare", 0.0, {5: 4e-3, 20: 2e-5}), ("tip_mass", 4.5, {5: 1e-2, 20: 3e-4})):
        for direction in ("flapwise", "inplane"):
            for speed in (0.0, 1.0, 2.0):
                for mode in (1, 2):
                    for n, error in errors.items():
                        rel = error * (speed + 1.0) / 3.0 * mode / 2.0 * (1 if direction == "inplane" else 0.5)
                        ritz_fe.append({"direction": direction, "speed_rad_s": speed, "mode": mode,
                                        "n_modes": n, "ritz_hz": mode * (1.0 + rel), "fe_hz": float(mode),
                                        "rel_diff": rel, "case": case, "tip_mass_kg": mass})
    pd.DataFrame(ritz_fe).to_csv(paths["ritz_fe"], index=False)
    pd.DataFrame([{"direction": "flapwise", "speed_rad_s": speed, "mode": 1, "pybmodes_hz": 1.0,
                   "order": order, "rel_diff_ritz": ritz, "rel_diff_fe": fe}
                  for speed, order, ritz, fe in ((0.0, 1.99, -1e-8, -3e-9), (1.0, 1.9, 2e-6, -5e-7))]
                 ).to_csv(paths["pybmodes"], index=False)
    for key in ("published_figure", "exudyn_figure"):
        paths[key].write_bytes(b"\x89PNG stand-in")
    return paths

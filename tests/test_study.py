"""Studies end to end: the measures of the study report against closed forms, and a tiny study
run by Snakemake into its own folder with every general product (``workflow`` marker)."""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from hubbeam.configuration.settings import Study
from hubbeam.model.parameters import BeamParameters
from hubbeam.reporting import archive
from hubbeam.results.reader import maneuver_end
from hubbeam.study import MARKER
from hubbeam.study.report import study_html, study_markdown
from hubbeam.study.summary import COLUMNS, case_summary

REPO = Path(__file__).resolve().parents[1]


def dataset(tip, t, maneuver, **attrs) -> xr.Dataset:
    """A minimal simulation dataset: the variables and attributes the summary reads."""
    base = {"model": "FOAM", "maneuver": json.dumps(maneuver), "n_modes": 3, "tip_mass_kg": 0.0,
            "diverged": 0, "diverged_at_s": math.nan, "validity": "valid", "left_range": 0,
            "max_deflection_ratio": float(np.nanmax(np.abs(tip))), "stopped_at_s": float(t[-1])}
    return xr.Dataset({"tip_transverse": ("time", tip)}, coords={"time": t}, attrs=base | attrs)


@pytest.mark.parametrize("maneuver, end", [
    ({"kind": "prescribed", "wf": 2.0, "tf": 3.0}, 3.0),
    ({"kind": "torque", "tau_max": 1.0, "tf": 4.0}, 4.0),
    ({"kind": "speed_table", "time": [0.0, 1.0, 2.5], "speed": [0.0, 1.0, 1.0]}, 2.5),
    ({"kind": "torque_table", "time": [0.0, 1.5], "torque": [1.0, 0.0]}, 1.5),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0, "reference": {"kind": "prescribed", "wf": 1.0, "tf": 6.0}}, 6.0),
    ({"kind": "pd", "kp": 1.0, "kd": 1.0, "reference": {"kind": "angle_table", "time": [0.0, 7.0],
                                                        "angle": [0.0, 1.0]}}, 7.0),
])
def test_the_maneuver_ends_where_its_input_stops_changing(maneuver, end):
    assert maneuver_end(maneuver) == end


def test_peak_and_residual_of_a_decaying_sinusoid():
    """v(L) = e^(-t/4) sin(2 pi t): the peak is near t = 1/4 (exactly where tan(2 pi t) = 8 pi),
    the residual amplitude after t = 3 s near t = 3.25 s."""
    t = np.linspace(0.0, 6.0, 600001)
    tip = np.exp(-t / 4) * np.sin(2 * np.pi * t)
    row = case_summary("decay", dataset(tip, t, {"kind": "prescribed", "wf": 1.0, "tf": 3.0}))
    t_peak = math.atan(8 * math.pi) / (2 * math.pi)
    assert row["peak_time_s"] == pytest.approx(t_peak, abs=1e-5)
    peak = math.exp(-t_peak / 4) * math.sin(2 * math.pi * t_peak)
    assert row["peak_tip_deflection_m"] == pytest.approx(peak, rel=1e-9)
    t_residual = 3.0 + t_peak
    assert row["residual_amplitude_m"] == pytest.approx(
        math.exp(-t_residual / 4) * math.sin(2 * math.pi * t_residual), rel=1e-9)
    assert row["maneuver_end_s"] == 3.0 and row["diverged"] is False
    assert row["convergence"] == "not checked" and math.isnan(row["convergence_modes_diff_m"])
    assert list(row) == list(COLUMNS)


def test_a_diverged_run_and_a_failed_convergence_check_are_reported(tmp_path):
    t = np.linspace(0.0, 2.0, 21)
    tip = np.where(t <= 1.0, t, np.nan)
    ds = dataset(tip, t, {"kind": "prescribed", "wf": 5.0, "tf": 1.5}, diverged=1, diverged_at_s=1.0,
                 validity="diverged",
                 convergence_check="{}", convergence_tolerance_diff_m=1e-6, convergence_modes_diff_m=2e-3,
                 warnings="not converged in the modes: ...")
    row = case_summary("boom", ds)
    assert row["diverged"] is True and row["diverged_at_s"] == 1.0
    assert row["peak_tip_deflection_m"] == 1.0 and row["peak_time_s"] == 1.0
    assert math.isnan(row["residual_amplitude_m"])  # nothing finite after t_f
    assert row["convergence"] == "NOT converged" and row["convergence_modes_diff_m"] == 2e-3
    markdown = study_markdown(Study("s"), BeamParameters(L=1.0, rho=1.0, A=1.0, E=1.0, I=1.0, Jh=1.0, rA=0.0),
                              [row], {"cases": {"boom": "../figures/case_boom.png"}})
    assert "| boom | FOAM | prescribed | 3 |" in markdown and "| diverged at 1.00 s |" in markdown
    assert "NOT converged (tolerance 1e-06 m, modes 0.002 m)" in markdown
    figure = tmp_path / "figures" / "case_boom.png"
    figure.parent.mkdir()
    figure.write_bytes(b"png bytes")
    html = study_html(markdown, "s", tmp_path / "report")
    assert "<table>" in html and '<img alt="case boom" src="data:image/png;base64,' in html


TINY_STUDY = {
    "study": {"name": "tiny", "title": "Tiny study", "description": "Two short runs.",
              "comparisons": {"models": ["spin_foam", "spin_tlam"]}},
    "beam": {"length": 2.0, "density": 2700.0, "area": 1.0e-4, "youngs_modulus": 7.0e+10,
             "second_moment": 1.0e-9, "hub_inertia": 1.0, "hub_radius": 0.1},
    "numerics": {"modes": 2, "quadrature_points": 16, "rtol": 1.0e-7, "atol": 1.0e-9,
                 "output_step": 0.05, "max_steps": 100000, "step_warning": 50000,
                 "divergence_limit": 1.0,
                 "convergence_check": {"tolerance_factor": 0.1, "extra_modes": 1, "threshold_m": 1.0e-4}},
    "eigen": {"speeds": {"start": 0.0, "stop": 4.0, "num": 5},
              "positions": {"start": 0.0, "stop": 2.0, "num": 3},
              "tip_masses": [0.0, 0.1], "critical_speed_search_max": 50.0},
    "cases": {
        "spin_foam": {"model": "FOAM", "maneuver": {"kind": "prescribed", "wf": 2.0, "tf": 1.0}, "t_end": 1.5},
        "spin_tlam": {"model": "TLAM", "maneuver": {"kind": "prescribed", "wf": 2.0, "tf": 1.0}, "t_end": 1.5,
                      "tip_mass": {"mass": 0.1}},
    },
}


def run_study(root: Path, study: dict) -> Path:
    """Run ``study`` (written to root/studies/<name>.yaml) with Snakemake in ``root``; its folder,
    checked to be the only one under root/results."""
    name = study["study"]["name"]
    config = root / "studies" / f"{name}.yaml"
    config.write_text(yaml.safe_dump(study))
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"),
               "--directory", str(root), "--cores", "2", "--configfile", str(config)]
    run = subprocess.run(command, cwd=root, capture_output=True, text=True, timeout=1500, check=False)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert sorted(p.name for p in (root / "results").iterdir()) == [name]  # nothing else
    return root / "results" / name


@pytest.mark.workflow
def test_a_tiny_study_builds_every_general_product_in_its_own_folder(tmp_path):
    (tmp_path / "studies").mkdir()
    folder = run_study(tmp_path, TINY_STUDY)
    cases = sorted(TINY_STUDY["cases"])
    expected = [f"simulations/{case}.nc" for case in cases] + ["matrices/mt0.nc", "matrices/mt0p1_l2.nc"]
    expected += ["eigen/beam.nc"]
    figures = [f"case_{case}" for case in cases] + ["compare_models", "beam_properties"]
    # the plants (hubbeam.pipeline.families.plants): one per tip mass, named after its first case
    plants = {"spin_foam": ("spin_foam",), "spin_tlam": ("spin_tlam",)}
    assert {case for group in plants.values() for case in group} == set(cases)
    products = ("campbell", "mode_shapes", "poles_zeros", "bode")
    figures += [f"plant_{product}_{plant}" for plant in plants for product in products]
    expected += [f"figures/{name}.{ext}" for name in figures for ext in ("pdf", "png")]
    expected += [f"plants/{plant}/{name}.nc" for plant in plants for name in (*products, "plant")]
    expected += [f"plants/{plant}/models/{model}_{hub}.{ext}" for plant in plants
                 for model in ("TLAM", "FOAM", "SFOAM", "CFOAM") for hub in ("free", "prescribed")
                 for ext in ("nc", "mat")]
    expected += ["report/report.md", "report/report.html", "report/summary.csv", "tiny-results.tar.gz", MARKER]
    written = sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file())
    assert written == sorted(expected)

    with open(folder / "report" / "summary.csv", newline="") as handle:
        rows = {row["case"]: row for row in csv.DictReader(handle)}
    assert sorted(rows) == cases
    for case in cases:  # the summary is the dataset's own peak
        with xr.open_dataset(folder / "simulations" / f"{case}.nc") as ds:
            assert float(rows[case]["peak_tip_deflection_m"]) == float(np.nanmax(np.abs(ds["tip_transverse"].values)))
        assert rows[case]["convergence"] in ("converged", "NOT converged")
    markdown = (folder / "report" / "report.md").read_text()
    assert all(f"(../figures/{name}.png)" in markdown for name in figures)
    html = (folder / "report" / "report.html").read_text()
    assert html.count('src="data:image/png;base64,') == len(figures)

    assert archive.verify_archive(folder / "tiny-results.tar.gz", "tiny-results") == []


@pytest.mark.workflow
def test_a_study_of_files_only_runs_a_tabulated_beam_and_maneuver_with_damping(tmp_path):
    """A study written only as files (no code): a tapered beam and a hub-speed profile from CSV,
    a tip mass inside the span, modal damping. Its runs come out in its folder, they record the
    tables they were given, and the energy balance holds with the damping's dissipation."""
    studies = tmp_path / "studies"
    studies.mkdir()
    (studies / "beam.csv").write_text("x,rhoA,EI,EA\n0.0,0.3,80.0,7.0e6\n1.0,0.25,60.0,6.0e6\n"
                                      "2.0,0.2,40.0,5.0e6\n")
    (studies / "speed.csv").write_text("# a ramp up and a hold\ntime,speed\n0.0,0.0\n0.5,1.0\n"
                                       "1.0,2.0\n1.5,2.0\n")
    study = {key: TINY_STUDY[key] for key in ("numerics", "eigen")}
    # a fine output grid: the work and the dissipation are integrated on it (Simpson's rule)
    study["numerics"] = {**TINY_STUDY["numerics"], "output_step": 0.005}
    study["study"] = {"name": "files"}
    study["beam"] = {"length": 2.0, "hub_inertia": 1.0, "hub_radius": 0.1,
                     "sections": {"file": "beam.csv"}}
    study["cases"] = {"ramp": {"model": "FOAM", "maneuver": {"kind": "speed_table", "file": "speed.csv"},
                               "t_end": 2.0, "tip_mass": {"mass": 0.05, "position": 1.5},
                               "damping": {"kind": "modal", "axial": 0.01, "transverse": 0.05}}}
    folder = run_study(tmp_path, study)
    for product in ("report/report.html", "figures/case_ramp.png", "figures/plant_campbell_ramp.png",
                    "files-results.tar.gz"):
        assert (folder / product).is_file(), product
    with xr.open_dataset(folder / "simulations" / "ramp.nc", decode_times=False) as ds:
        assert json.loads(ds.attrs["maneuver"])["speed"] == [0.0, 1.0, 2.0, 2.0]
        assert list(ds.attrs["sections_EI"]) == [80.0, 60.0, 40.0]
        assert ds.attrs["validity"] == "valid"
        assert float(ds["theta_dot"].values[-1]) == pytest.approx(2.0, rel=1e-9)
        energy, work, dissipated = (ds[name].values for name in ("energy", "work", "dissipated_energy"))
    assert dissipated[-1] > 0.0
    assert np.max(np.abs(energy - energy[0] - (work - dissipated))) < 1e-6 * np.max(np.abs(work))

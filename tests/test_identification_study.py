"""The ``identify`` section in a study: checked with the rest before any job, fitted once when the
plan is made, kept while its inputs are unchanged, and the fitted plant run by the cases of
``apply_to`` (their records, their plant), written as a fragment that gives the same records when
merged by hand, drawn and reported (hubbeam.calibration, hubbeam.pipeline.families.identification).

The study is small and fast: the synthetic rig's tap test and one frequency response (the shipped
data, ``studies/identification_rig``), three parameters of the case, two starts.
"""

from __future__ import annotations

import copy
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from hubbeam import calibration
from hubbeam.api import load
from hubbeam.check import check_configuration
from hubbeam.configuration.load import ConfigError
from hubbeam.identification.synthetic import TRUTH
from hubbeam.pipeline.plan import PlanError, build_plan
from hubbeam.pipeline.runner import job_function, run_job
from hubbeam.results.paths import study_paths
from hubbeam.study.identification import identification_markdown

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "studies" / "identification_rig"
#: the fitted parameters of the small study
FITTED = ("root_spring.stiffness", "damping.transverse", "drive.motor_constant_factor")


def small_study() -> dict:
    """The shipped study's rig, two cases (one runs the fitted plant), three case parameters fitted
    to the tap test and the deflection's frequency response, the free tap test held out. The rig's
    other values the data were made with are set to their true ones (EI, the viscous friction), so
    that the model can match the data."""
    shipped = yaml.safe_load((DATA / "study.yaml").read_text())
    rig = shipped["cases"]["rig"] | {"t_end": 0.2, "maneuver": {"kind": "voltage_table", "time": [0.0, 0.2],
                                                                   "voltage": [0.0, 0.0]}}
    rig["drive"] = rig["drive"] | {"viscous_friction": TRUTH["drive.viscous_friction"]}
    beam = shipped["beam"] | {"EI": shipped["beam"]["EI"] * TRUTH["beam.EI_factor"]}
    experiments = shipped["identify"]["experiments"]
    return {
        "study": {"name": "small_identification", "title": "identify a few case parameters"},
        "beam": beam, "numerics": shipped["numerics"], "eigen": shipped["eigen"],
        "cases": {"rig": rig, "drawn": copy.deepcopy(rig)},
        "identify": {"case": "rig",
                     "experiments": {name: experiments[name] for name in ("tap_held", "frf_deflection", "tap_free")},
                     "parameters": {key: {"lower": low, "upper": high} for key, (low, high) in {
                         "root_spring.stiffness": (10.0, 60.0), "damping.transverse": (0.001, 0.1),
                         "drive.motor_constant_factor": (0.7, 1.3)}.items()},
                     "fit": ["tap_held", "frf_deflection"], "validate": ["tap_free"], "starts": 2,
                     "apply_to": ["rig"]}}


@pytest.fixture
def study_dir(tmp_path, monkeypatch):
    """A folder holding the data files, the working directory of the test (results go under it)."""
    for name in ("tap_held.csv", "frf_deflection.csv", "tap_free.csv"):
        shutil.copy(DATA / name, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def write(folder: Path, config: dict, name: str = "study.yaml") -> Path:
    path = folder / name
    path.write_text(yaml.safe_dump(config, sort_keys=False))
    return path


def fitted_values(path: str | Path) -> dict[str, float]:
    with xr.open_dataset(path) as fit:
        return dict(zip(fit["parameter"].values.tolist(), fit["value"].values.tolist()))


def test_the_plan_runs_the_cases_of_apply_to_on_the_fitted_plant(study_dir):
    path = write(study_dir, small_study())
    plan = build_plan(yaml.safe_load(path.read_text()), [path], REPO)
    paths = study_paths("small_identification")
    values = fitted_values(paths.identification_fit())
    for key in FITTED:  # the data pin the case's parameters: each near the truth
        assert values[key] == pytest.approx(TRUTH[key], rel=0.02), key
    rig, drawn = plan.settings.case("rig"), plan.settings.case("drawn")
    assert rig.root_spring.stiffness == values["root_spring.stiffness"] and drawn.root_spring.stiffness == 30.0
    assert rig.damping.transverse == values["damping.transverse"] and drawn.damping.transverse == 0.02
    assert rig.drive.torque_constant == pytest.approx(0.00768 * values["drive.motor_constant_factor"], rel=1e-15)
    # the plant products of the fitted case are its own plant's, apart from the drawn case's
    assert plan.settings.plant_of("rig") != plan.settings.plant_of("drawn")
    assert plan.settings.plant_of("rig").root_spring == rig.root_spring
    # the fit's files, its figures (one per experiment and the parameters) and the report reading them
    figures = plan.steps["identification_figures"].job()
    assert figures.input["fit"] == paths.identification_fit()
    assert sorted(Path(p).name for p in figures.output["files"]) == sorted(
        f"{name}.{ext}" for name in ("tap_held", "frf_deflection", "tap_free", "parameters") for ext in ("pdf", "png"))
    report = plan.steps["study_report"].job()
    assert report.input["identification"] == paths.identification_fit()
    assert {paths.identification_fit(), paths.identified_plant(), *figures.output["files"]} <= set(plan.targets)


def test_the_fit_is_kept_until_an_input_changes(study_dir, monkeypatch):
    path = write(study_dir, small_study())
    checked = check_configuration(yaml.safe_load(path.read_text()), [path])
    paths = study_paths("small_identification")
    calibration.calibrated(checked, paths)
    first = Path(paths.identification_fit()).stat().st_mtime_ns

    def no_fit(*args, **kwargs):
        raise AssertionError("fitted again with unchanged inputs")

    monkeypatch.setattr(calibration.section, "identify", no_fit)
    again = calibration.calibrated(checked, paths)
    assert Path(paths.identification_fit()).stat().st_mtime_ns == first
    assert again.settings.case("rig").root_spring.stiffness == fitted_values(paths.identification_fit())[
        "root_spring.stiffness"]
    # a changed data file changes the fingerprint: the fit runs again
    before = calibration.inputs_fingerprint(checked)
    tap = study_dir / "tap_held.csv"
    tap.write_text(tap.read_text() + "\n")
    assert calibration.inputs_fingerprint(checked) != before
    with pytest.raises(AssertionError, match="fitted again"):
        calibration.calibrated(checked, paths)


def test_the_fitted_fragment_merged_by_hand_gives_the_cases_the_workflow_runs(study_dir):
    """``fitted.yaml`` merged onto another study of the same rig (one without the section, a
    design study say) gives the records the workflow gives the cases of ``apply_to``."""
    config = small_study()
    config["identify"]["apply_to"] = []
    path = write(study_dir, config)
    as_drawn = load(path)  # no case runs the fit: the fit is written, the cases are as drawn
    assert as_drawn.case("rig").root_spring.stiffness == 30.0
    fragment = study_paths("small_identification").identified_plant()
    other = {key: value for key, value in config.items() if key != "identify"}
    other["study"] = {"name": "designed_on_the_fit"}
    by_hand = load([write(study_dir, other, "other.yaml"), fragment])
    config["identify"]["apply_to"] = ["rig"]
    by_workflow = load(write(study_dir, config))
    assert by_hand.case("rig") == by_workflow.case("rig") != as_drawn.case("rig")
    assert by_hand.case("drawn") == as_drawn.case("drawn")


def test_the_api_fit_is_the_workflows(study_dir):
    path = write(study_dir, small_study())
    configuration = load(path, identified=False)
    result, fit = configuration.identify()
    stored = fitted_values(study_paths("small_identification").identification_fit()) if Path(
        study_paths("small_identification").identification_fit()).exists() else None
    assert stored is None  # identified=False neither fits nor writes
    load(path)
    stored = fitted_values(study_paths("small_identification").identification_fit())
    assert result.values == pytest.approx(stored, rel=1e-12)
    assert np.all(fit["upper_95"].values > fit["lower_95"].values)


def test_the_figures_and_the_report_section_show_the_fit(study_dir):
    path = write(study_dir, small_study())
    plan = build_plan(yaml.safe_load(path.read_text()), [path], REPO)
    job = plan.steps["identification_figures"].job()
    run_job(job_function(job.params["job"]), job)
    assert all(Path(file).stat().st_size > 1000 for file in job.output["files"])
    with xr.open_dataset(study_paths("small_identification").identification_fit()) as fit:
        text = identification_markdown(fit, {"parameters": "../identification/parameters.png"}, ["rig"],
                                       "../identification/fitted.yaml")
    for fragment in ("`root_spring.stiffness`", "95 % interval", "| tap_free | modal | held out (predicted) |",
                     "The cases `rig` run on the fitted values", "![parameters](../identification/parameters.png)"):
        assert fragment in text, fragment
    assert "nan" not in text.lower()


def refused(config: dict, folder: Path) -> str:
    """The one check's message on ``config`` written in ``folder``."""
    path = write(folder, config)
    with pytest.raises(ConfigError) as error:
        check_configuration(yaml.safe_load(path.read_text()), [path])
    return str(error.value)


def _inverted(config):
    config["identify"]["parameters"]["root_spring.stiffness"] = {"lower": 60.0, "upper": 10.0}


def _not_a_parameter(config):
    config["identify"]["parameters"]["root_spring.colour"] = {"lower": 0.0, "upper": 1.0}


def _bad_file(folder):
    def change(config):
        (folder / "bad.csv").write_text("mode [1],frequency [Hz]\n1,3.1\n2,nan\n")
        config["identify"]["experiments"]["tap_held"]["file"] = "bad.csv"
    return change


def _no_drive(config):
    for case in config["cases"].values():
        del case["drive"]
        case["maneuver"] = {"kind": "torque", "tau_max": 0.01, "tf": 0.1}
    del config["identify"]["parameters"]["drive.motor_constant_factor"]


def _beam_key_not_everywhere(config):
    config["identify"]["parameters"]["beam.EI_factor"] = {"lower": 0.7, "upper": 1.3}


def _unknown_case(config):
    config["identify"]["apply_to"] = ["rig", "gig"]


def _case_without_the_section(config):
    del config["cases"]["drawn"]["root_spring"]
    config["identify"]["apply_to"] = ["rig", "drawn"]


@pytest.mark.parametrize("change, fragments", [
    (_inverted, ["identify.parameters.root_spring.stiffness: lower = 60.0, upper = 10.0; allowed: lower < upper"]),
    (_not_a_parameter, ["identify.parameters.'root_spring.colour': not a parameter; allowed: beam.EI_factor"]),
    ("bad file", ["identify.experiments.tap_held.file: file ",
                  "bad.csv, line 3, column frequency: 'nan'; allowed: a finite number"]),
    (_no_drive, ["identify.experiments.frf_deflection: experiment frf_deflection: input voltage, but case 'rig' "
                 "has no drive"]),
    (_beam_key_not_everywhere, ["identify.apply_to = ['rig']: the fitted beam.EI_factor changes the beam every "
                                "case runs, but 'drawn' is not listed"]),
    (_unknown_case, ["identify.apply_to: 'gig' is not a case; allowed: drawn, rig"]),
    (_case_without_the_section, ["identify.apply_to: 'drawn' cannot run the fitted", "root_spring"]),
], ids=["bounds_inverted", "not_a_parameter", "nan_in_file", "no_drive", "beam_key", "unknown_case",
        "case_without_section"])
def test_a_bad_section_is_refused_by_the_one_check_naming_the_key(study_dir, change, fragments):
    config = small_study()
    (_bad_file(study_dir) if change == "bad file" else change)(config)
    message = refused(config, study_dir)
    assert all(fragment in message for fragment in fragments), message
    assert not Path("results").exists()


def test_snakemake_refuses_a_bad_section_before_any_job(study_dir):
    import subprocess
    import sys

    config = small_study()
    _inverted(config)
    path = write(study_dir, config)
    workdir = study_dir / "work"
    workdir.mkdir()
    run = subprocess.run([sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"), "--directory",
                          str(workdir), "--dry-run", "--configfile", str(path)],
                         cwd=REPO, capture_output=True, text=True, timeout=300)
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "identify.parameters.root_spring.stiffness: lower = 60.0, upper = 10.0" in output, output
    assert "Traceback" not in output and "Building DAG" not in output
    assert sorted(p.name for p in workdir.iterdir()) in ([], [".snakemake"])


def test_a_fitted_plant_the_cases_cannot_run_is_refused_by_the_plan(study_dir, monkeypatch):
    """The configuration with the fitted values is checked again: a fit whose values a case of
    ``apply_to`` cannot run (here a stiffness the check refuses) stops the plan naming it."""
    path = write(study_dir, small_study())
    monkeypatch.setattr(calibration, "stored_values", lambda *args: {
        "root_spring.stiffness": -1.0, "damping.transverse": 0.02, "drive.motor_constant_factor": 1.0})
    with pytest.raises(PlanError) as error:
        build_plan(yaml.safe_load(path.read_text()), [path], REPO)
    assert "root_spring.stiffness" in str(error.value)


def test_a_free_decay_entry_is_the_courseware_procedure_on_the_raw_record(tmp_path):
    """The ``free_decay`` kind reads a held-hub free oscillation as recorded and gives its first
    frequency and damping ratio by the logarithmic decrement: on the shipped record (made by the
    true plant, read by the strain gauge) within 1 % and 10 % of the true plant's first held mode;
    a record of two signals is refused naming the file and the line."""
    from hubbeam.identification.section import SectionError, read_entry
    from hubbeam.identification.synthetic import rig_plant

    entry = {"kind": "free_decay", "file": "held_oscillation.csv", "hub": "held", "lowpass": 10.0}
    test = read_entry("ring", entry, DATA)
    frequency, damping = rig_plant().modes(TRUTH, "held")
    assert test.mode.tolist() == [1] and test.hub == "held"
    assert test.frequency[0] == pytest.approx(frequency[0], rel=0.01)
    assert test.damping_ratio[0] == pytest.approx(damping[0], rel=0.10)
    (tmp_path / "two.csv").write_text("time [s],hub_angle [rad],deflection_angle [rad]\n"
                                      + "".join(f"{0.002 * k},0,{0.01 * (-0.9) ** k}\n" for k in range(40)))
    with pytest.raises(SectionError, match=r"identify.experiments.ring.file: file .*two.csv, line 1: 2 measured "
                                           r"signals; allowed: exactly one of hub_angle \[rad\]"):
        read_entry("ring", {"kind": "free_decay", "file": "two.csv"}, tmp_path)

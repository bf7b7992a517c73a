"""Config loading and validation: every kind of bad input is reported with key, value and what is
allowed; the Snakefile stops on a bad config before any rule; a new case needs no code change."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from hubbeam.configuration.load import (
    ConfigError,
    check_schema,
    load_config,
    read_config_file,
)
from hubbeam.configuration.schema import CASE_NAME_PATTERN, SCHEMA
from hubbeam.configuration.settings import Case, case_from_config, from_config
from hubbeam.model.maneuvers import SpinUp
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.printed import TABLE1


def set_at(cfg: dict, dotted: str, value) -> None:
    *parents, last = dotted.split(".")
    for key in parents:
        cfg = cfg[key]
    cfg[last] = value


def delete_at(cfg: dict, dotted: str) -> None:
    *parents, last = dotted.split(".")
    for key in parents:
        cfg = cfg[key]
    del cfg[last]


def problems_of(cfg: dict, files=()) -> list[str]:
    with pytest.raises(ConfigError) as caught:
        check_schema(cfg, files=files)
    message = str(caught.value)
    assert all(str(problem) in message for problem in caught.value.problems)
    return [str(problem) for problem in caught.value.problems]


def assert_reported(problems: list[str], path: str, *fragments: str) -> None:
    """One problem starts with the key path and contains every fragment (value, what is allowed)."""
    matching = [problem for problem in problems if problem.startswith(f"{path}: ")]
    assert matching, f"no problem reported at {path}: {problems}"
    assert any(all(fragment in problem for fragment in fragments) for problem in matching), matching


# ---------------------------------------------------------------------------------------------
# the study config


def test_study_config_is_valid_and_transcribes_table1(study_config):
    assert check_schema(study_config) is study_config
    assert BeamParameters.from_config(study_config) == BeamParameters(**TABLE1)
    params = BeamParameters.from_config(study_config)
    assert params.rhoA == TABLE1["rho"] * TABLE1["A"]
    assert params.EI == TABLE1["E"] * TABLE1["I"]


def test_a_case_gets_the_defaults_of_numerics_and_of_its_tip_mass(study_config):
    length = study_config["beam"]["length"]
    assert case_from_config(study_config, "fig04_foam") == Case(
        name="fig04_foam", model="FOAM", maneuver=SpinUp(wf=3.0, tf=30.0), t_end=50.0,
        modes=study_config["numerics"]["modes"], tip_mass=TipMass(0.0, length))
    assert case_from_config(study_config, "fig06_foam_n1").modes == 1
    assert case_from_config(study_config, "fig10_tlam_mt0p5").tip_mass == TipMass(0.5, 8.0)

    study_config["cases"]["mid_mass"] = {"model": "TLAM", "maneuver": {"kind": "torque", "tau_max": 5.0, "tf": 2.0},
                                         "t_end": 3.0, "tip_mass": {"mass": 0.2}}
    check_schema(study_config)
    assert case_from_config(study_config, "mid_mass").tip_mass == TipMass(0.2, length)


def test_unknown_case_names_the_defined_ones(study_config):
    with pytest.raises(ConfigError, match=r"cases\.nope: unknown case; defined: .*fig04_foam"):
        from_config(study_config).case("nope")


def test_case_names_are_sorted_and_usable_as_wildcards(study_config):
    names = list(from_config(study_config).cases)
    assert names == sorted(study_config["cases"])
    assert all(re.fullmatch(CASE_NAME_PATTERN, name) for name in names)


# ---------------------------------------------------------------------------------------------
# one kind of bad value at a time: (key path, bad value, fragments the problem must contain)

BAD_VALUES = [
    ("beam.length", 0.0, ["got 0.0", "allowed: a number > 0"]),
    ("beam.length", -8.0, ["got -8.0", "> 0"]),
    ("beam.density", -2.7e3, ["got -2700.0", "> 0"]),
    ("beam.area", 0, ["got 0", "> 0"]),
    ("beam.youngs_modulus", 0.0, ["got 0.0", "> 0"]),
    ("beam.second_moment", -8.2e-9, ["got -8.2e-09", "> 0"]),
    ("beam.hub_inertia", -1.0, ["got -1.0", ">= 0"]),
    ("beam.hub_radius", -0.5, ["got -0.5", ">= 0"]),
    ("beam.length", "eight", ["got 'eight' (text)", "a number > 0"]),
    ("beam.length", math.inf, ["got inf", "a finite number"]),
    ("numerics.atol", math.nan, ["got nan", "a finite number"]),
    ("numerics.rtol", "fast", ["got 'fast' (text)", "a number >= 2.220446049250313e-14 and < 1",
                               "100 machine epsilons"]),
    ("numerics.rtol", "nan", ["got 'nan' (text)", "a number >= 2.220446049250313e-14"]),
    ("numerics.modes", "5", ["got '5' (text)", "an integer >= 1 and <= 20"]),
    ("numerics.rtol", 1e-15, ["got 1e-15", "a number >= 2.220446049250313e-14"]),
    ("sweeps.numerics.rtol", 0.0, ["got 0.0", "a number >= 2.220446049250313e-14"]),
    ("numerics.rtol", 1.0, ["got 1.0", "< 1"]),
    ("numerics.modes", 0, ["got 0", "an integer >= 1 and <= 20"]),
    ("numerics.modes", 21, ["got 21", "an integer >= 1 and <= 20"]),
    ("numerics.modes", 5.0, ["got 5.0 (decimal number)", "an integer >= 1"]),
    ("numerics.quadrature_points", 7, ["got 7", "an integer >= 8 and <= 1000"]),
    ("numerics.quadrature_points", 1001, ["got 1001", "an integer >= 8 and <= 1000"]),
    ("numerics.output_step", 0.0, ["got 0.0", "> 0"]),
    ("numerics.step_warning", 2_000_000, ["got 2000000", "at most numerics.max_steps = 1000000"]),
    ("cases.fig06_foam_n3.modes", 25, ["got 25", "an integer >= 1 and <= 20"]),
    ("cases.fig06_foam_n3.modes", True, ["got True (boolean)", "an integer"]),
    ("cases.fig04_foam.t_end", 0.0, ["got 0.0", "> 0"]),
    ("cases.fig04_foam.t_end", 0.005, ["got 0.005", "at least one output step", "numerics.output_step = 0.01"]),
    ("cases.fig04_foam.maneuver.tf", 0.0, ["got 0.0", "> 0"]),
    ("cases.fig04_foam.maneuver.wf", -3.0, ["got -3.0", "> 0"]),
    ("cases.fig04_foam.maneuver.wf", "fast", ["got 'fast' (text)", "a number > 0"]),
    ("cases.tab3_foam_tau50.maneuver.tf", -10.0, ["got -10.0", "> 0"]),
    ("cases.tab3_foam_tau50.maneuver.tau_max", 0.0, ["got 0.0", "> 0"]),
    ("cases.fig04_foam.model", "FEM", ["got 'FEM'", "one of TLAM, FOAM, SFOAM, CFOAM"]),
    ("cases.fig04_foam.maneuver.kind", "ramp", ["got 'ramp'", "one of prescribed, torque"]),
    ("cases.fig04_foam.maneuver", "spin-up", ["got 'spin-up' (text)", "a mapping with a kind (prescribed, "
                                              "torque, speed_table, torque_table, voltage_table, pd, "
                                              "state_feedback) and the keys of its kind"]),
    ("cases.fig10_foam_mt0p1.tip_mass.position", 8.5, ["got 8.5", "0 <= position <= beam.length = 8.0"]),
    ("cases.fig10_foam_mt0p1.tip_mass.position", -0.1, ["got -0.1", ">= 0"]),
    ("cases.fig10_foam_mt0p1.tip_mass.mass", -0.1, ["got -0.1", "a number >= 0"]),
    ("eigen.positions.stop", 9.0, ["got 9.0", "<= beam.length = 8.0"]),
    ("eigen.speeds.start", 5.0, ["got 4.0", "> eigen.speeds.start = 5.0"]),
    ("eigen.speeds.num", 1, ["got 1", "an integer >= 2"]),
    ("eigen.tip_masses", [0.1, 0.1], ["got [0.1, 0.1]", "distinct values"]),
    ("eigen.tip_masses", [], ["got []", "a list of at least 1"]),
]


def reported_path(dotted: str) -> str:
    """Where the problem is reported: a grid's start/stop clash is reported at its stop."""
    return "eigen.speeds.stop" if dotted == "eigen.speeds.start" else dotted


@pytest.mark.parametrize("dotted, value, fragments", BAD_VALUES, ids=[f"{d}={v!r}" for d, v, _ in BAD_VALUES])
def test_bad_value_names_key_value_and_allowed(study_config, dotted, value, fragments):
    set_at(study_config, dotted, value)
    assert_reported(problems_of(study_config), reported_path(dotted), *fragments)


NUMBERS_AS_TEXT = [  # YAML 1.1 reads the first two as text
    ("numerics.rtol", "1e-9", 1e-9),
    ("beam.density", "2.7667e3", 2766.7),
    ("cases.fig04_foam.t_end", "2.0", 2.0),
    ("cases.fig04_foam.maneuver.wf", " 3 ", 3.0),
    ("eigen.tip_masses", [0.0, "1e-1"], [0.0, 0.1]),
]


@pytest.mark.parametrize("dotted, text, number", NUMBERS_AS_TEXT, ids=[d for d, _, _ in NUMBERS_AS_TEXT])
def test_numbers_written_as_text_are_accepted_as_numbers(study_config, dotted, text, number):
    set_at(study_config, dotted, text)
    validated = check_schema(study_config)
    *parents, last = dotted.split(".")
    for key in parents:
        validated = validated[key]
    assert validated[last] == number  # kept in the config the workflow hands its rules


def test_yaml_exponent_forms_read_as_text_load_as_numbers(tmp_path, study_config):
    text = yaml.safe_dump(study_config).replace("rtol: 1.0e-09", "rtol: 1e-9", 1)
    assert "rtol: 1e-9" in text
    path = tmp_path / "config.yaml"
    path.write_text(text, encoding="utf-8")
    assert yaml.safe_load(text)["numerics"]["rtol"] == "1e-9"
    cfg = load_config(path)
    assert cfg["numerics"]["rtol"] == 1e-9 and from_config(cfg).cases["fig04_foam"].t_end > 0


VALIDATION_PROBLEMS = [
    ("validation.published.modes", [20, 10], "validation.published.modes",
     ["got [20, 10]", "increasing integers"]),
    ("validation.published.gammas.start", 60.0, "validation.published.gammas.stop",
     ["got 50.0", "> validation.published.gammas.start = 60.0"]),
    ("validation.exudyn.time_step", 3.0e-3, "validation.exudyn.time_step",
     ["got 0.003", "divides numerics.output_step = 0.01"]),
    ("validation.convergence.time_steps", [5.0e-3, 3.0e-3], "validation.convergence.time_steps[1]",
     ["got 0.003", "divides numerics.output_step = 0.01"]),
    ("validation.cases.spinup_wf2p0.t_end", 50.005, "validation.cases.spinup_wf2p0.t_end",
     ["got 50.005", "a multiple of numerics.output_step = 0.01"]),
    ("validation.cases.spinup_wf2p0_mt0p5.tip_mass.position", 7.7,
     "validation.cases.spinup_wf2p0_mt0p5.tip_mass.position",
     ["got 7.7", "a node of the Exudyn mesh", "beam.length / validation.exudyn.elements = 0.5 m"]),
    ("validation.cases.spinup_wf2p0_mt0p5.tip_mass.position", 8.5,
     "validation.cases.spinup_wf2p0_mt0p5.tip_mass.position", ["got 8.5", "<= beam.length = 8.0"]),
]


@pytest.mark.parametrize("dotted, value, path, fragments", VALIDATION_PROBLEMS,
                         ids=[f"{d}={v!r}" for d, v, _, _ in VALIDATION_PROBLEMS])
def test_validation_section_is_checked_at_startup(study_config, dotted, value, path, fragments):
    """What the validation rules would only find inside a job (mode counts, steps that do not fit
    the output grid, a tip mass off the Exudyn mesh) stops the workflow before any rule runs."""
    set_at(study_config, dotted, value)
    assert_reported(problems_of(study_config), path, *fragments)


def test_convergence_meshes_must_hold_the_tip_mass_of_their_case(study_config):
    validation = study_config["validation"]
    validation["convergence"]["case"] = "spinup_wf2p0_mt0p5"
    validation["cases"]["spinup_wf2p0_mt0p5"]["tip_mass"]["position"] = 7.5  # a node of 16, not of 4
    assert_reported(problems_of(study_config), "validation.cases.spinup_wf2p0_mt0p5.tip_mass.position",
                    "got 7.5", "beam.length / validation.convergence.elements[0] = 2 m")
    validation["convergence"]["elements"] = [16, 32]
    check_schema(study_config)


INITIAL_PROBLEMS = [
    ({"q2": [0.0]}, "cases.fig04_foam.initial.q2", ["got [0.0]", "a list of 2 numbers, one per mode"]),
    ({"hub_speed": 1.0}, "cases.fig04_foam.initial.hub_speed",
     ["got 1.0", "0.0 rad s-1, the speed at t = 0 of the prescribed maneuver"]),
]


@pytest.mark.parametrize("initial, path, fragments", INITIAL_PROBLEMS, ids=[p for _, p, _ in INITIAL_PROBLEMS])
def test_a_case_initial_state_is_checked_at_startup(study_config, initial, path, fragments):
    """A case's initial state that it cannot start from stops the workflow before any rule runs;
    a case without ``modes`` has ``numerics.modes`` of them."""
    study_config["numerics"]["modes"] = 2
    study_config["cases"]["fig04_foam"]["initial"] = initial
    assert_reported(problems_of(study_config), path, *fragments)


def test_a_start_speed_against_a_broken_speed_table_reports_the_table_only(study_config):
    """The maneuver's speed at t = 0 is only evaluated on a table in order."""
    study_config["cases"]["fig04_foam"]["maneuver"] = {"kind": "speed_table", "time": [5.0, 0.0], "speed": [1.0, 1.0]}
    study_config["cases"]["fig04_foam"]["initial"] = {"hub_speed": 2.0}
    problems = problems_of(study_config)
    assert_reported(problems, "cases.fig04_foam.maneuver.time", "got [5.0, 0.0]", "strictly increasing")
    assert not [problem for problem in problems if ".initial" in problem]


def test_bad_list_item_is_named_by_index(study_config):
    study_config["eigen"]["tip_masses"] = [0.0, -0.1]
    assert_reported(problems_of(study_config), "eigen.tip_masses[1]", "got -0.1", ">= 0")


def test_tip_mass_beyond_a_shortened_beam(study_config):
    """The position bound is the configured length, not the paper's 8 m."""
    study_config["beam"]["length"] = 6.0
    problems = problems_of(study_config)
    for name in ("fig10_foam_mt0p1", "fig10_tlam_mt0p5"):
        assert_reported(problems, f"cases.{name}.tip_mass.position", "got 8.0", "beam.length = 6.0")


MISSING = [
    ("beam.length", ["missing (required)", "a number > 0"]),
    ("cases", ["missing (required)", "a mapping"]),
    ("cases.fig04_foam.t_end", ["missing (required)", "a number > 0"]),
    ("cases.fig04_foam.model", ["missing (required)", "one of TLAM, FOAM, SFOAM, CFOAM"]),
    ("cases.fig04_foam.maneuver.wf", ["missing (required when kind is 'prescribed')", "a number > 0"]),
    ("cases.fig04_foam.maneuver.kind", ["missing (required)", "one of prescribed, torque"]),
    ("cases.tab3_foam_tau50.maneuver.tau_max", ["missing (required when kind is 'torque')"]),
    ("cases.tab3_foam_tau50.maneuver.tf", ["missing (required when kind is 'torque')"]),
    ("eigen.speeds.num", ["missing (required)", "an integer >= 2"]),  # a grid given is given whole
]


@pytest.mark.parametrize("dotted, fragments", MISSING, ids=[d for d, _ in MISSING])
def test_missing_key_is_named(study_config, dotted, fragments):
    delete_at(study_config, dotted)
    assert_reported(problems_of(study_config), dotted, *fragments)


@pytest.mark.parametrize("case, key, kind, allowed", [
    ("tab3_foam_tau50", "wf", "torque", "kind, tau_max, tf"),
    ("fig04_foam", "tau_max", "prescribed", "kind, wf, tf"),
])
def test_key_of_the_other_maneuver_kind(study_config, case, key, kind, allowed):
    study_config["cases"][case]["maneuver"][key] = 3.0
    assert_reported(problems_of(study_config), f"cases.{case}.maneuver.{key}",
                    "got 3.0", f"not allowed when kind is '{kind}'", allowed)


@pytest.mark.parametrize("section, key, allowed", [
    ("cases.fig04_foam", "t_ned", "model, maneuver, t_end, modes, tip_mass"),
    ("beam", "colour", "length, density, area"),
    ("cases.fig10_foam_mt0p1.tip_mass", "radius", "mass, position, inertia, offset"),
])
def test_unknown_key_is_named(study_config, section, key, allowed):
    set_at(study_config, f"{section}.{key}", 1.5)
    assert_reported(problems_of(study_config), f"{section}.{key}", "unknown key (value 1.5)", allowed)


@pytest.mark.parametrize("name", ["bad name", "a/b", "x.y", "case*", "é"])
def test_illegal_case_name(study_config, name):
    study_config["cases"][name] = study_config["cases"]["fig04_foam"]
    assert_reported(problems_of(study_config), f"cases.{name}", f"illegal case name {name!r}",
                    "letters, digits, '_' and '-'")


def test_case_names_differing_only_in_letter_case(study_config):
    study_config["cases"]["FIG04_foam"] = study_config["cases"]["fig04_foam"]
    assert_reported(problems_of(study_config), "cases.FIG04_foam", "'FIG04_foam' differs from 'fig04_foam'",
                    "distinct ignoring case")


def test_case_name_read_as_a_number(study_config):
    study_config["cases"][2024] = study_config["cases"]["fig04_foam"]
    assert_reported(problems_of(study_config), "cases.2024", "read by YAML as integer", 'write "2024"')


def test_no_cases(study_config):
    study_config["cases"] = {}
    assert_reported(problems_of(study_config), "cases", "got no entries", "at least one case")


def test_every_problem_in_one_message(study_config):
    set_at(study_config, "cases.fig05_tlam_wf2p8.maneuver.wf", -2.8)
    set_at(study_config, "cases.fig10_foam_mt0p5.tip_mass.position", 8.01)
    set_at(study_config, "numerics.rtol", 2.0)
    with pytest.raises(ConfigError) as caught:
        check_schema(study_config)
    message = str(caught.value)
    assert message.startswith("invalid hubbeam configuration, 3 problems:")
    for fragment in ("cases.fig05_tlam_wf2p8.maneuver.wf: got -2.8",
                     "cases.fig10_foam_mt0p5.tip_mass.position: got 8.01",
                     "numerics.rtol: got 2.0"):
        assert fragment in message


def test_top_level_must_be_a_mapping():
    assert_reported(problems_of([1, 2]), "<top level>", "got [1, 2] (list)", "a mapping with keys beam")


# ---------------------------------------------------------------------------------------------
# files: repeated keys, syntax, merging


def write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def test_repeated_yaml_keys_are_rejected(tmp_path, repo_root):
    extra = write(tmp_path / "extra.yaml", "cases:\n"
                  "  spin: {model: FOAM, maneuver: {kind: prescribed, wf: 1.0, tf: 5.0}, t_end: 9.0}\n"
                  "  spin: {model: TLAM, maneuver: {kind: prescribed, wf: 1.0, tf: 5.0}, t_end: 9.0}\n"
                  "numerics:\n  rtol: 1.0e-8\n  rtol: 1.0e-6\n")
    with pytest.raises(ConfigError) as caught:
        load_config([repo_root / "config" / "config.yaml", extra])
    problems = [str(problem) for problem in caught.value.problems]
    assert_reported(problems, "cases.spin", f"repeated key in {extra} (lines 2 and 3)", "each key once")
    assert_reported(problems, "numerics.rtol", "(lines 5 and 6)")
    with pytest.raises(ConfigError, match="repeated key"):
        read_config_file(extra)


def test_repeated_keys_found_even_when_the_merged_config_is_valid(tmp_path, study_config):
    """Snakemake's YAML loader keeps the last of two repeated keys; the Snakefile passes the files."""
    extra = write(tmp_path / "extra.yaml", "numerics:\n  modes: 3\n  modes: 4\n")
    study_config["numerics"]["modes"] = 4
    assert_reported(problems_of(study_config, files=[extra]), "numerics.modes", "repeated key")


@pytest.mark.parametrize("text, fragment", [
    ("beam: {length: 8.0\n", "is not valid YAML at line"),
    ("- 1\n- 2\n", "got [1, 2]; allowed: a mapping of keys at the top level"),
    ("", "got null"),
])
def test_unreadable_file_is_named(tmp_path, text, fragment):
    path = write(tmp_path / "broken.yaml", text)
    assert_reported(problems_of({}, files=[path]), f"file {path}", fragment)


def test_missing_file_is_named(tmp_path):
    with pytest.raises(ConfigError, match=r"file .*nowhere\.yaml: cannot be read"):
        load_config(tmp_path / "nowhere.yaml")


def test_extra_file_adds_a_case_and_overrides_like_snakemake(tmp_path, repo_root):
    extra = write(tmp_path / "extra.yaml", "numerics:\n  modes: 3\ncases:\n"
                  "  my_spinup:\n    model: FOAM\n    maneuver: {kind: prescribed, wf: 1.5, tf: 5.0}\n"
                  "    t_end: 8.0\n    tip_mass: {mass: 0.2, position: 4.0}\n"
                  "  fig04_foam: {t_end: 40.0}\n")
    cfg = load_config([repo_root / "config" / "config.yaml", extra])
    cases = from_config(cfg).cases
    assert cases["my_spinup"] == Case(name="my_spinup", model="FOAM", maneuver=SpinUp(wf=1.5, tf=5.0), t_end=8.0,
                                      modes=3, tip_mass=TipMass(0.2, 4.0))
    assert cases["fig04_foam"].t_end == 40.0  # merged into the existing case
    assert cases["fig04_foam"].maneuver == SpinUp(wf=3.0, tf=30.0)
    assert cases["fig06_foam_n1"].modes == 1  # a case's own modes win


# ---------------------------------------------------------------------------------------------
# the Snakefile


def snakemake(repo_root: Path, workdir: Path, *args: str) -> subprocess.CompletedProcess:
    """Run Snakemake on the repository's Snakefile in an empty working directory."""
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(repo_root / "Snakefile"),
               "--directory", str(workdir), *args]
    return subprocess.run(command, cwd=repo_root, capture_output=True, text=True, timeout=300)


def test_snakefile_stops_on_a_bad_config_before_any_rule(tmp_path, repo_root):
    bad = write(tmp_path / "bad.yaml", "cases:\n"
                "  fig05_tlam_wf2p8: {maneuver: {wf: -2.8}}\n"
                "  my_case: {model: FOAM, maneuver: {kind: torque, tau_max: 1.0, tf: 1.0}, t_end: 2.0}\n"
                "  my_case: {model: FOAM, maneuver: {kind: torque, tau_max: 1.0, tf: 1.0}, t_end: 2.0}\n")
    workdir = tmp_path / "work"
    workdir.mkdir()
    run = snakemake(repo_root, workdir, "--cores", "1", "--configfile",
                    str(repo_root / "config" / "config.yaml"), str(bad))
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "invalid hubbeam configuration" in output
    assert "cases.fig05_tlam_wf2p8.maneuver.wf: got -2.8; allowed: a number > 0" in output
    assert f"cases.my_case: repeated key in {bad}" in output
    assert "Traceback" not in output and 'File "' not in output
    assert not (workdir / "results").exists()
    assert "Building DAG" not in output and "Job stats" not in output


def test_dry_run_plans_every_case(tmp_path, repo_root, study_config):
    run = snakemake(repo_root, tmp_path, "--dry-run", "--configfile", str(repo_root / "config" / "config.yaml"))
    assert run.returncode == 0, run.stderr
    output = run.stdout + run.stderr
    assert "This was a dry-run" in output
    for name in study_config["cases"]:
        assert f"results/simulations/{name}.nc" in output


def test_a_case_added_in_an_extra_config_file_builds_without_code_change(tmp_path, repo_root):
    extra = write(tmp_path / "extra.yaml", yaml.safe_dump({"cases": {"my_spinup": {
        "model": "SFOAM", "maneuver": {"kind": "prescribed", "wf": 1.0, "tf": 2.0}, "t_end": 3.0}}}))
    workdir = tmp_path / "work"
    workdir.mkdir()
    run = snakemake(repo_root, workdir, "results/simulations/my_spinup.nc", "--dry-run",
                    "--configfile", str(repo_root / "config" / "config.yaml"), str(extra))
    assert run.returncode == 0, run.stderr
    assert "results/simulations/my_spinup.nc" in run.stdout + run.stderr


def test_a_config_without_the_cases_of_a_figure_stops_with_one_clear_message(tmp_path, repo_root,
                                                                               study_config):
    reduced = dict(study_config)
    reduced["cases"] = {name: case for name, case in study_config["cases"].items()
                        if not name.startswith(("fig03_", "tab3_"))}
    config = write(tmp_path / "reduced.yaml", yaml.safe_dump(reduced))
    workdir = tmp_path / "work"
    workdir.mkdir()
    run = snakemake(repo_root, workdir, "--dry-run", "--configfile", str(config))
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "the config `cases` does not define" in output
    assert "  - cases: product fig03 reads fig03_cfoam_n1, which the config `cases` does not define\n" in output
    assert ("  - cases: product table3 reads tab3_foam_tau100, tab3_foam_tau200, tab3_foam_tau400, tab3_foam_tau50, "
            "which the config `cases` does not define\n") in output
    assert "Traceback" not in output and 'File "' not in output


def test_schema_takes_its_limits_from_the_limits_module():
    """The schema file states no bound of hubbeam.model.limits; the loaded schema has exactly those."""
    from hubbeam.configuration import schema as config_schema
    from hubbeam.core import radau
    from hubbeam.model import limits
    from hubbeam.simulation import simulate

    raw = yaml.safe_load(config_schema.SCHEMA_RESOURCE.read_text(encoding="utf-8"))
    for keys, bounds in config_schema.SCHEMA_LIMITS.items():
        raw_node, node = raw, config_schema.SCHEMA
        for key in keys:
            raw_node, node = raw_node[key], node[key]
        stated = {"minimum", "maximum", "exclusiveMinimum"} & set(raw_node)
        assert not stated, f"{'.'.join(keys)} restates {stated} in the schema file"
        assert {key: node[key] for key in bounds} == bounds
    assert config_schema.SCHEMA["$defs"]["modes"]["maximum"] == limits.MAX_MODES == simulate.MAX_MODES
    assert limits.MIN_RTOL == 100 * radau.UROUND == simulate.MIN_RTOL


#: bad values of every kind of schema rule: (key, value to set, fragment of the one message at the key)
SCHEMA_RULES = [
    ("cases.fig04_foam.model", "XFOAM", "allowed: one of TLAM, FOAM, SFOAM, CFOAM"),          # enum
    ("cases.fig04_foam.maneuver.kind", "ramp", "allowed: one of prescribed, torque"),         # enum of kinds
    ("cases.fig04_foam.damping", "none", "allowed: a mapping"),                               # type
    ("cases.fig04_foam.damping", {"kind": "modal", "axial": 0.1}, "required when kind is 'modal'"),
    ("cases.fig04_foam.maneuver.tau_max", 3.0, "not allowed when kind is 'prescribed'"),     # branch keys
    ("sweeps.maps.spinup_peak.figure.model", "FOAM", "not allowed when kind is 'peak'"),      # not
    ("sweeps.maps.spinup_peak.in_all", "yes", "allowed: true or false"),                      # boolean
    ("study", {"name": "../evil"}, "allowed: letters, digits, '_' and '-' only"),             # pattern
    ("readings", {"bad name": {}}, "allowed: letters, digits and '_' only"),                  # propertyNames
]


@pytest.mark.parametrize("dotted, value, fragment", SCHEMA_RULES, ids=[rule[0] for rule in SCHEMA_RULES])
def test_no_message_dumps_the_schema(study_config, dotted, value, fragment):
    """Every schema rule is told in words: no message shows a piece of the schema as JSON."""
    set_at(study_config, dotted, value)
    problems = problems_of(study_config)
    assert any(fragment in problem for problem in problems), problems
    assert not [problem for problem in problems
                if re.search(r'"(type|pattern|description|enum|properties|required)"', problem)], problems


@pytest.mark.parametrize("path", ["config/config.yaml", "studies/spinup10m.yaml", "studies/tapered_pd.yaml"])
def test_a_checked_configuration_becomes_frozen_objects_that_give_back_its_cases(repo_root, path):
    """hubbeam.configuration.settings.from_config: one object per section; each case gives back its resolved
    mapping (what a dataset records), and no object can be changed."""
    import dataclasses

    from hubbeam.configuration.settings import Case, from_config, simulation_settings
    from hubbeam.configuration.tabular import resolve_files
    from hubbeam.model.beam import beam_from_config

    cfg = check_schema(resolve_files(read_config_file(repo_root / path), (repo_root / path).parent))
    settings = from_config(cfg)
    assert settings.beam == beam_from_config(cfg["beam"])
    assert (settings.study is None) == ("study" not in cfg)
    assert settings.numerics.rtol == cfg["numerics"]["rtol"]
    assert settings.eigen.speeds.num == cfg["eigen"]["speeds"]["num"]
    assert list(settings.cases) == sorted(cfg["cases"])
    for case in settings.cases.values():
        assert isinstance(case, Case)
        # the API's path from the resolved mapping gives the same object
        assert simulation_settings(case.to_dict(), cfg["numerics"], settings.beam.L)[0] == case
    with pytest.raises(dataclasses.FrozenInstanceError):
        case.t_end = 1.0
    with pytest.raises(TypeError):
        settings.cases["x"] = case


def test_every_pattern_of_the_schema_is_said_in_words():
    """explain says a pattern in words (config_schema._PATTERNS): each one the schema uses has them."""
    from hubbeam.configuration.schema import _PATTERNS

    def patterns(node):
        if isinstance(node, dict):
            yield from ([node["pattern"]] if isinstance(node.get("pattern"), str) else [])
            for value in node.values():
                yield from patterns(value)
        elif isinstance(node, list):
            for value in node:
                yield from patterns(value)

    used = set(patterns(SCHEMA))
    assert used and used <= set(_PATTERNS), used - set(_PATTERNS)


def test_a_tip_body_is_read_with_its_inertia_and_offset(study_config):
    study_config["cases"]["fig10_foam_mt0p1"]["tip_mass"] |= {"inertia": 5e-4, "offset": 0.02}
    check_schema(study_config)
    case = from_config(study_config).cases["fig10_foam_mt0p1"]
    assert case.tip_mass == TipMass(0.1, 8.0, 5e-4, 0.02)
    assert case.to_dict()["tip_mass"] == {"mass": 0.1, "position": 8.0, "inertia": 5e-4, "offset": 0.02}
    assert "inertia" not in from_config(study_config).cases["fig10_tlam_mt0p1"].to_dict()["tip_mass"]


@pytest.mark.parametrize("changes, key, fragments", [
    ({"inertia": -1e-3}, "inertia", ["got -0.001", "allowed: a number >= 0"]),
    ({"position": 2.0, "offset": -2.5}, "offset", ["got -2.5", "allowed: offset >= -position = -2.0"]),
])
def test_a_tip_body_with_a_negative_inertia_or_a_centre_in_the_hub_is_refused(study_config, changes, key, fragments):
    cases = study_config["cases"]
    last = sorted(cases)[-1]
    cases[last]["tip_mass"] = {"mass": 0.1} | changes
    assert_reported(problems_of(study_config), f"cases.{last}.tip_mass.{key}", *fragments)

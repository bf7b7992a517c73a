"""Study configs: every bad input of the new keys (study, beam sections, table maneuvers, pd,
damping) is one clear message naming the key, the value and what is allowed, before anything
runs; CSV tables are read with messages naming the file and the line; two config files cannot
share a results folder."""

from __future__ import annotations

import copy
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.configuration.settings import case_from_config
from hubbeam.configuration.tabular import SECTION_COLUMNS, TableError, read_table, resolve_files
from hubbeam.model.damping import ModalDamping
from hubbeam.model.maneuvers import AngleTable, PdControl
from hubbeam.results.paths import IN_RESULTS, PAPER_FOLDERS, StudyPaths, study_paths
from hubbeam.study import (
    MARKER,
    StudyError,
    claim_results_dir,
)

REPO = Path(__file__).resolve().parents[1]

TINY = {
    "study": {"name": "tiny", "comparisons": {"both": ["spin", "table"]}},
    "beam": {"length": 2.0, "density": 2700.0, "area": 1.0e-4, "youngs_modulus": 7.0e10,
             "second_moment": 1.0e-9, "hub_inertia": 1.0, "hub_radius": 0.1},
    "numerics": {"modes": 2, "quadrature_points": 16, "rtol": 1.0e-7, "atol": 1.0e-9,
                 "output_step": 0.05, "max_steps": 100000, "step_warning": 50000,
                 "divergence_limit": 1.0},
    "eigen": {"speeds": {"start": 0.0, "stop": 4.0, "num": 5},
              "positions": {"start": 0.0, "stop": 2.0, "num": 3},
              "tip_masses": [0.0, 0.1], "critical_speed_search_max": 50.0},
    "cases": {
        "spin": {"model": "FOAM", "maneuver": {"kind": "prescribed", "wf": 2.0, "tf": 1.0}, "t_end": 2.0},
        "table": {"model": "FOAM", "maneuver": {"kind": "speed_table", "time": [0.0, 1.0, 2.0],
                                                "speed": [0.0, 1.0, 1.0]}, "t_end": 2.0},
        "pd": {"model": "FOAM", "t_end": 2.0,
               "maneuver": {"kind": "pd", "kp": 10.0, "kd": 5.0,
                            "reference": {"kind": "angle_table", "time": [0.0, 1.0], "angle": [0.0, 0.5]}},
               "damping": {"kind": "modal", "axial": 0.01, "transverse": 0.02}},
        "torque": {"model": "FOAM", "maneuver": {"kind": "torque_table", "time": [0.0, 1.0],
                                                 "torque": [1.0, 0.0]}, "t_end": 2.0,
                   "damping": {"kind": "rayleigh", "mass_coefficient": 0.0, "stiffness_coefficient": 1.0e-4}},
    },
}
SECTIONS = {"x": [0.0, 1.0, 2.0], "rhoA": [0.3, 0.25, 0.2], "EI": [80.0, 60.0, 40.0],
            "EA": [7.0e6, 6.0e6, 5.0e6]}


@pytest.fixture
def study():
    return copy.deepcopy(TINY)


@pytest.fixture
def sectioned(study):
    for key in ("density", "area", "youngs_modulus", "second_moment"):
        del study["beam"][key]
    study["beam"]["sections"] = copy.deepcopy(SECTIONS)
    return study


def problems_of(cfg) -> list[str]:
    with pytest.raises(ConfigError) as caught:
        check_schema(cfg)
    return [str(problem) for problem in caught.value.problems]


def assert_reported(problems, path, *fragments):
    matching = [p for p in problems if p.startswith(f"{path}: ")]
    assert matching, f"no problem at {path}: {problems}"
    assert any(all(f in p for f in fragments) for p in matching), matching


def test_the_tiny_study_and_the_shipped_studies_are_valid(study, sectioned):
    check_schema(study)
    check_schema(sectioned)
    for name in ("spinup10m", "tapered_pd"):
        path = REPO / "studies" / f"{name}.yaml"
        cfg = resolve_files(yaml.safe_load(path.read_text()), path.parent)
        check_schema(cfg, files=[path])
        assert cfg["study"]["name"] == name and study_paths(cfg["study"]["name"]).results == f"results/{name}"


def test_the_paper_keeps_its_folders_and_needs_table2_speed(study):
    paper = yaml.safe_load((REPO / "config" / "config.yaml").read_text())
    assert study_paths(None).results == "results" and "study" not in paper
    del paper["eigen"]["table2_speed"]
    assert_reported(problems_of(paper), "eigen.table2_speed", "missing", "Table 2")
    check_schema(study)  # a study has no Table 2


# --- the study section -------------------------------------------------------------------------

@pytest.mark.parametrize("name", ["my study", "a/b", "..", "tiny!", ""])
def test_a_study_name_that_is_no_folder_name_is_rejected(study, name):
    study["study"]["name"] = name
    assert_reported(problems_of(study), "study.name", f"got {name!r}", "letters, digits, '_' and '-' only")


@pytest.mark.parametrize("name", PAPER_FOLDERS)
def test_a_study_name_of_a_paper_folder_is_rejected(study, name):
    study["study"]["name"] = name
    assert_reported(problems_of(study), "study.name", f"got {name!r}", "folder of the paper")


def test_every_folder_the_paper_writes_is_a_name_no_study_may_take():
    """Each kind of file of a results folder (every path method of StudyPaths, called with
    placeholder names) lies in one of PAPER_FOLDERS (the linear models' folder among them), or is
    the archive itself."""
    import inspect

    tops = set()
    for name, method in inspect.getmembers(IN_RESULTS, inspect.ismethod):
        if name.startswith("_") or name in ("result", "log", "figures"):
            continue
        parameters = inspect.signature(method).parameters
        path = method(*(["x"] * sum(p.default is inspect.Parameter.empty for p in parameters.values())))
        tops.add(path.split("/")[0])
    assert tops - set(PAPER_FOLDERS) == {StudyPaths().archive().split("/")[-1]}
    assert "linear" in PAPER_FOLDERS


def test_a_comparison_of_an_unknown_case_is_rejected(study):
    study["study"]["comparisons"]["both"] = ["spin", "spni"]
    assert_reported(problems_of(study), "study.comparisons.both[1]", "got 'spni'", "a name of cases")


def test_a_comparison_needs_two_cases(study):
    study["study"]["comparisons"]["both"] = ["spin"]
    assert_reported(problems_of(study), "study.comparisons.both", "got [\"spin\"]")


def test_the_eigen_positions_of_a_study_reach_the_tip(study):
    study["eigen"]["positions"]["stop"] = 1.5
    assert_reported(problems_of(study), "eigen.positions.stop", "got 1.5", "beam.length = 2.0")


def test_two_config_files_cannot_share_a_results_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    marker = claim_results_dir("results/tiny", "studies/tiny.yaml")
    assert marker == Path("results/tiny", MARKER) and marker.read_text() == "studies/tiny.yaml\n"
    claim_results_dir("results/tiny", "studies/tiny.yaml")  # the owner may run again
    with pytest.raises(StudyError, match=r"study.name: the folder results/tiny belongs to the "
                                         r"study of studies/tiny.yaml .* not to other/tiny.yaml"):
        claim_results_dir("results/tiny", "other/tiny.yaml")


# --- beam sections -----------------------------------------------------------------------------

def test_stations_must_increase_from_the_root_to_the_tip(sectioned):
    sectioned["beam"]["sections"]["x"] = [0.0, 1.5, 1.0]
    problems = problems_of(sectioned)
    assert_reported(problems, "beam.sections.x", "got [0.0, 1.5, 1.0]", "strictly increasing")
    assert_reported(problems, "beam.sections.x", "ends at 1.0", "beam.length = 2.0")
    sectioned["beam"]["sections"]["x"] = [0.5, 1.0, 2.0]
    assert_reported(problems_of(sectioned), "beam.sections.x", "starts at 0.5", "x = 0")


@pytest.mark.parametrize("column, value", [("rhoA", 0.0), ("EI", -60.0), ("EA", 0.0)])
def test_zero_or_negative_section_properties_are_rejected(sectioned, column, value):
    sectioned["beam"]["sections"][column][1] = value
    assert_reported(problems_of(sectioned), f"beam.sections.{column}[1]", f"got {value}", "> 0")


def test_section_columns_must_have_one_value_per_station(sectioned):
    sectioned["beam"]["sections"]["EI"] = [80.0, 60.0]
    assert_reported(problems_of(sectioned), "beam.sections.EI", "got 2 values", "(3)")


def test_a_beam_is_not_both_uniform_and_sectioned(sectioned):
    sectioned["beam"]["density"] = 2700.0
    assert_reported(problems_of(sectioned), "beam.density", "not allowed together with beam.sections")


def test_a_uniform_beam_needs_every_uniform_key(study):
    del study["beam"]["second_moment"]
    assert_reported(problems_of(study), "beam.second_moment", "missing", "uniform beam")


@pytest.fixture
def by_products(study):
    for key in ("density", "area", "youngs_modulus", "second_moment"):
        del study["beam"][key]
    study["beam"] |= {"rhoA": 0.27, "EI": 70.0, "EA": 7.0e6}
    return study


def test_a_uniform_beam_may_be_given_by_its_products(by_products):
    check_schema(by_products)
    del by_products["beam"]["EA"]
    assert_reported(problems_of(by_products), "beam.EA", "missing (required for a uniform beam given by "
                    "its products)", "a number > 0")


@pytest.mark.parametrize("key, value", [("density", 2700.0), ("second_moment", 1e-9)])
def test_a_beam_is_not_given_both_by_its_factors_and_by_its_products(by_products, key, value):
    by_products["beam"][key] = value
    assert_reported(problems_of(by_products), f"beam.{key}", f"got {value}", "not allowed together with "
                    "beam.rhoA", "density, area, youngs_modulus, second_moment", "rhoA, EI, EA")


def test_the_products_give_the_matrices_of_the_factors():
    """spinup10m gives its beam by the products; the factors it gave before (any area A) assemble
    the same matrices up to the rounding of the products rho A, E A, E I (a few units in the last
    place of each entry: every entry is linear in one product)."""
    import numpy as np

    from hubbeam.model.beam import beam_attributes, beam_from_attributes, beam_from_config
    from hubbeam.model.matrices import assemble
    from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass

    beam = yaml.safe_load((REPO / "studies" / "spinup10m.yaml").read_text())["beam"]
    products = beam_from_config(beam)
    assert isinstance(products, BeamProducts)
    assert beam_from_attributes(beam_attributes(products)) == products
    factors = BeamParameters(L=10.0, rho=1.2e4, A=1.0e-4, E=2.8e11, I=5.0e-8, Jh=1.0, rA=0.0)
    tip = TipMass(mass=0.5, position=7.0)
    for name, a, b in zip(assemble(products, tip, 7, 64)._fields, assemble(products, tip, 7, 64),
                          assemble(factors, tip, 7, 64)):
        scale = np.max(np.abs(b)) if np.size(b) else 0.0
        np.testing.assert_allclose(a, b, rtol=0, atol=16 * np.finfo(float).eps * scale, err_msg=name)


# --- maneuvers and damping ---------------------------------------------------------------------

def test_a_time_table_must_increase(study):
    study["cases"]["table"]["maneuver"]["time"] = [0.0, 2.0, 1.0]
    assert_reported(problems_of(study), "cases.table.maneuver.time", "got [0.0, 2.0, 1.0]",
                    "strictly increasing")
    study["cases"]["pd"]["maneuver"]["reference"]["time"] = [0.0, 0.0]
    assert_reported(problems_of(study), "cases.pd.maneuver.reference.time", "strictly increasing")


def test_a_time_table_starts_at_zero_or_later_and_matches_its_values(study):
    study["cases"]["torque"]["maneuver"]["time"] = [-1.0, 1.0]
    assert_reported(problems_of(study), "cases.torque.maneuver.time", "starts at -1.0", ">= 0")
    study["cases"]["torque"]["maneuver"]["time"] = [0.0, 1.0]
    study["cases"]["torque"]["maneuver"]["torque"] = [1.0, 0.5, 0.0]
    assert_reported(problems_of(study), "cases.torque.maneuver.torque", "got 3 values", "(2)")


@pytest.mark.parametrize("gain", ["kp", "kd"])
def test_negative_gains_are_rejected(study, gain):
    study["cases"]["pd"]["maneuver"][gain] = -1.0
    assert_reported(problems_of(study), f"cases.pd.maneuver.{gain}", "got -1.0", ">= 0")


def test_a_pd_maneuver_needs_its_gains_and_reference(study):
    del study["cases"]["pd"]["maneuver"]["reference"]
    assert_reported(problems_of(study), "cases.pd.maneuver.reference", "missing",
                    "required when kind is 'pd'")


@pytest.mark.parametrize("key, value", [("axial", 1.0), ("transverse", -0.1), ("axial", 1.5)])
def test_damping_ratios_outside_zero_one_are_rejected(study, key, value):
    study["cases"]["pd"]["damping"][key] = value
    assert_reported(problems_of(study), f"cases.pd.damping.{key}", f"got {value}", ">= 0", "< 1")


def test_negative_rayleigh_coefficients_are_rejected(study):
    study["cases"]["torque"]["damping"]["stiffness_coefficient"] = -1.0e-4
    assert_reported(problems_of(study), "cases.torque.damping.stiffness_coefficient", "got -0.0001", ">= 0")


@pytest.mark.parametrize("case, entry, key, kind", [
    ("table", "maneuver", "wf", "speed_table"),
    ("pd", "maneuver", "time", "pd"),
    ("pd", "damping", "mass_coefficient", "modal"),
    ("torque", "damping", "axial", "rayleigh"),
])
def test_a_key_of_another_kind_is_rejected(study, case, entry, key, kind):
    study["cases"][case][entry][key] = 1.0
    assert_reported(problems_of(study), f"cases.{case}.{entry}.{key}", "got 1.0",
                    f"not allowed when kind is '{kind}'")


def test_a_case_holds_its_tables_references_and_damping_as_records(study):
    pd = case_from_config(study, "pd")
    assert pd.maneuver == PdControl(kp=10.0, kd=5.0, reference=AngleTable(time=(0.0, 1.0), angle=(0.0, 0.5)))
    assert pd.damping == ModalDamping(axial=0.01, transverse=0.02)
    assert case_from_config(study, "spin").damping is None


# --- CSV tables --------------------------------------------------------------------------------

def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


def test_tables_are_read_in_the_header_order_with_comments_and_blank_lines(tmp_path):
    table = write(tmp_path / "t.csv", "# stations\nEA,x,EI,rhoA\n\n7e6,0,80,0.3\n5e6,2,40,0.2\n")
    assert read_table(table, SECTION_COLUMNS) == {"x": [0.0, 2.0], "rhoA": [0.3, 0.2],
                                                   "EI": [80.0, 40.0], "EA": [7e6, 5e6]}


@pytest.mark.parametrize("text, fragments", [
    ("x,rhoA,EI\n0,1,2\n", ["line 1", "header x,rhoA,EI", "x,rhoA,EI,EA"]),
    ("x,rhoA,EI,EA\n0,1,2,3\n2,1,two,3\n", ["line 3", "column EI", "'two' is not a number"]),
    ("x,rhoA,EI,EA\n0,1,2,3\n2,1,2\n", ["line 3", "3 values", "allowed: 4"]),
    ("x,rhoA,EI,EA\n0,1,nan,3\n", ["line 2", "column EI", "a finite number"]),
    ("x,rhoA,EI,EA\n", ["no rows after the header"]),
    ("", ["empty"]),
])
def test_a_malformed_table_names_the_file_and_the_line(tmp_path, text, fragments):
    table = write(tmp_path / "bad.csv", text)
    with pytest.raises(TableError) as caught:
        read_table(table, SECTION_COLUMNS)
    message = str(caught.value)
    assert message.startswith(f"file {table}")
    assert all(fragment in message for fragment in fragments), message


def test_files_are_resolved_relative_to_the_config_file(tmp_path, sectioned):
    write(tmp_path / "tables" / "beam.csv", "x,rhoA,EI,EA\n0,0.3,80,7e6\n1,0.25,60,6e6\n2,0.2,40,5e6\n")
    write(tmp_path / "tables" / "speed.csv", "time,speed\n0,0\n1,1\n2,1\n")
    write(tmp_path / "tables" / "angle.csv", "time,angle\n0,0\n1,0.5\n")
    sectioned["beam"]["sections"] = {"file": "tables/beam.csv"}
    sectioned["cases"]["table"]["maneuver"] = {"kind": "speed_table", "file": "tables/speed.csv"}
    sectioned["cases"]["pd"]["maneuver"]["reference"] = {"kind": "angle_table", "file": "tables/angle.csv"}
    resolved = resolve_files(sectioned, tmp_path)
    assert resolved["beam"]["sections"] == SECTIONS
    assert resolved["cases"]["table"]["maneuver"] == TINY["cases"]["table"]["maneuver"]
    assert resolved["cases"]["pd"]["maneuver"] == TINY["cases"]["pd"]["maneuver"]
    assert sectioned["beam"]["sections"] == {"file": "tables/beam.csv"}  # the input is not changed
    check_schema(resolved)


def test_missing_or_malformed_files_are_reported_under_their_keys(tmp_path, sectioned):
    write(tmp_path / "speed.csv", "time,speed\n0,0\n1,fast\n")
    sectioned["beam"]["sections"] = {"file": "nowhere.csv"}
    sectioned["cases"]["table"]["maneuver"] = {"kind": "speed_table", "file": "speed.csv"}
    sectioned["cases"]["torque"]["maneuver"] = {"kind": "torque_table", "file": "speed.csv",
                                                "torque": [1.0]}
    with pytest.raises(ConfigError) as caught:
        resolve_files(sectioned, tmp_path)
    problems = [str(problem) for problem in caught.value.problems]
    assert_reported(problems, "beam.sections.file", f"file {tmp_path / 'nowhere.csv'}", "cannot be read")
    assert_reported(problems, "cases.table.maneuver.file", f"file {tmp_path / 'speed.csv'}, line 3",
                    "'fast' is not a number")
    assert_reported(problems, "cases.torque.maneuver.file", "given together with torque")


# --- the Snakefile -----------------------------------------------------------------------------

def snakemake_dry_run(workdir: Path, *configfiles: Path) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "--snakefile", str(REPO / "Snakefile"),
               "--directory", str(workdir), "--dry-run", "--cores", "1",
               "--configfile", *map(str, configfiles)]
    return subprocess.run(command, cwd=workdir, capture_output=True, text=True, timeout=300, check=False)


def test_a_study_inherits_nothing_from_the_paper_and_plans_only_its_folder(tmp_path, study):
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "config.yaml").write_text((REPO / "config" / "config.yaml").read_text())
    config = write(tmp_path / "studies" / "tiny.yaml", yaml.safe_dump(study))
    run = snakemake_dry_run(tmp_path, config)
    output = run.stdout + run.stderr
    assert run.returncode == 0, output
    planned = {line.split()[1] for line in output.splitlines() if line.strip().startswith("output:")}
    assert "results/tiny/tiny-results.tar.gz" in output and "results/tiny/report/report.html" in output
    assert "fig04" not in output and "table1" not in output and "validate" not in output
    assert not any(path.startswith("results/") and not path.startswith("results/tiny/")
                   for entry in planned for path in entry.split(","))
    assert (tmp_path / "results" / "tiny" / MARKER).read_text() == "studies/tiny.yaml\n"


def test_the_snakefile_rejects_a_second_study_of_the_same_name(tmp_path, study):
    first = write(tmp_path / "studies" / "tiny.yaml", yaml.safe_dump(study))
    second = write(tmp_path / "other" / "tiny.yaml", yaml.safe_dump(study))
    assert snakemake_dry_run(tmp_path, first).returncode == 0
    run = snakemake_dry_run(tmp_path, second)
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert "results/tiny belongs to the study of studies/tiny.yaml" in output
    assert "Traceback" not in output


def test_the_snakefile_reports_a_bad_table_file_before_any_rule(tmp_path, study):
    study["cases"]["table"]["maneuver"] = {"kind": "speed_table", "file": "speed.csv"}
    write(tmp_path / "studies" / "speed.csv", "time,speed\n0,0\n1\n")
    config = write(tmp_path / "studies" / "tiny.yaml", yaml.safe_dump(study))
    run = snakemake_dry_run(tmp_path, config)
    output = run.stdout + run.stderr
    assert run.returncode != 0
    assert f"cases.table.maneuver.file: file {tmp_path}/studies/speed.csv, line 3: 1 values" in output
    assert "Traceback" not in output and not (tmp_path / "results").exists()


# --- the beam a study's rules build ------------------------------------------------------------

def test_beam_from_config_builds_the_uniform_beam_of_table1_and_a_sectioned_study_beam(sectioned):
    from hubbeam.model.beam import BeamSections, beam_from_config
    from hubbeam.model.parameters import BeamParameters
    from hubbeam.model.printed import TABLE1

    paper = yaml.safe_load((REPO / "config" / "config.yaml").read_text())
    assert beam_from_config(paper["beam"]) == BeamParameters.from_config(paper)
    assert beam_from_config(paper["beam"]) == BeamParameters(**TABLE1)
    beam = beam_from_config(sectioned["beam"])
    assert isinstance(beam, BeamSections)
    assert beam.L == sectioned["beam"]["length"]
    assert list(beam.x) == sectioned["beam"]["sections"]["x"]

"""Cases generated from grids (``case_grids``, hubbeam.configuration.grids): the product of the axes,
the entries of an axis together, names from the template, every generated case checked as a written
one, and the refusals of a grid that cannot name its cases apart."""

from __future__ import annotations

import copy
from pathlib import Path

import pytest
import yaml

from hubbeam.configuration.grids import expand_case_grids, name_token
from hubbeam.configuration.load import ConfigError, check_schema, load_config

REPO = Path(__file__).resolve().parents[1]


def study(grid: dict, **cases) -> dict:
    return {"beam": {"length": 2.0, "rhoA": 1.0, "EI": 50.0, "EA": 1e6, "hub_inertia": 1.0, "hub_radius": 0.1},
            "numerics": {"modes": 2}, "study": {"name": "grid"}, "cases": dict(cases), "case_grids": {"g": grid}}


BASE = {"model": "FOAM", "t_end": 2.0, "maneuver": {"kind": "prescribed", "tf": 1.0}}
GRID = {"name": "{model}_w{speed}",
        "case": BASE,
        "axes": [{"model": {"keys": ["model"], "values": ["FOAM", "TLAM"]}},
                 {"speed": {"keys": ["maneuver.wf"], "values": [0.5, 1.25, 2.0]}}]}


@pytest.mark.parametrize("value, token", [(1.5, "1p5"), (2.0, "2"), (-0.25, "m0p25"), (1e-5, "1em05"),
                                          ("FOAM", "foam"), (3, "3")])
def test_a_value_is_written_into_a_name_as_a_wildcard_may_hold_it(value, token):
    assert name_token(value) == token


def test_the_axes_combine_in_every_way_and_each_case_gets_its_values():
    cfg = check_schema(study(copy.deepcopy(GRID)))
    cases = cfg["cases"]
    assert sorted(cases) == sorted(f"{m}_w{w}" for m in ("foam", "tlam") for w in ("0p5", "1p25", "2"))
    assert cases["tlam_w1p25"]["model"] == "TLAM" and cases["tlam_w1p25"]["maneuver"] == {
        "kind": "prescribed", "tf": 1.0, "wf": 1.25}
    assert "wf" not in BASE["maneuver"]  # the base case itself is left as it was


def test_the_entries_of_an_axis_vary_together_and_set_several_keys():
    grid = dict(GRID, name="{model}_{design}_w{speed}",
                case={"model": "FOAM", "t_end": 2.0,
                      "maneuver": {"kind": "state_feedback", "reference": {"kind": "prescribed", "tf": 1.0},
                                   "design": {"torque_weight": 1.0, "weights": {"theta": 1.0}}}},
                axes=[{"model": {"keys": ["model"], "values": ["FOAM", "SFOAM"]},
                       "design": {"keys": ["maneuver.design.model"], "values": ["SFOAM", "FOAM"]}},
                      {"speed": {"keys": ["maneuver.reference.wf", "maneuver.design.speed"], "values": [0.5, 1.0]}}])
    cases = check_schema(study(grid))["cases"]
    assert sorted(cases) == ["foam_sfoam_w0p5", "foam_sfoam_w1", "sfoam_foam_w0p5", "sfoam_foam_w1"]
    case = cases["sfoam_foam_w0p5"]
    assert case["maneuver"]["design"]["model"] == "FOAM" and case["model"] == "SFOAM"
    assert case["maneuver"]["reference"]["wf"] == case["maneuver"]["design"]["speed"] == 0.5


def test_the_controller_study_expands_to_its_thirty_cases():
    cfg = load_config(REPO / "studies" / "controller_trust.yaml")
    names = [f"{d}_on_{m}_w{w}" for w in ("1", "1p5", "1p75", "2", "2p5")
             for d, m in (("tlam", "cfoam"), ("tlam", "tlam"), ("sfoam", "cfoam"), ("sfoam", "sfoam"),
                          ("foam", "cfoam"), ("foam", "foam"))]
    assert sorted(cfg["cases"]) == sorted(names)
    case = cfg["cases"]["sfoam_on_cfoam_w1p75"]
    assert case["model"] == "CFOAM" and case["maneuver"]["design"]["model"] == "SFOAM"
    assert case["maneuver"]["reference"]["wf"] == case["maneuver"]["design"]["speed"] == 1.75


def test_a_configuration_with_its_cases_expanded_expands_to_itself():
    """The archive records the completed configuration (config.used.yaml: the grid and its cases);
    reading it again adds nothing and refuses nothing."""
    cfg = check_schema(study(copy.deepcopy(GRID)))
    again = yaml.safe_load(yaml.safe_dump(cfg))
    assert expand_case_grids(again) == []
    assert again["cases"] == cfg["cases"]


def problems_of(cfg: dict) -> list[str]:
    with pytest.raises(ConfigError) as error:
        check_schema(cfg)
    return [str(problem) for problem in error.value.problems]


def test_a_bad_value_in_a_generated_case_names_the_generated_case():
    grid = dict(GRID, axes=[GRID["axes"][0], {"speed": {"keys": ["maneuver.wf"], "values": [0.5, -1.0]}}])
    found = problems_of(study(grid))
    assert [problem.split(" -- ")[0] for problem in found] == [
        "cases.foam_wm1.maneuver.wf: got -1.0; allowed: a number > 0",
        "cases.tlam_wm1.maneuver.wf: got -1.0; allowed: a number > 0"]


@pytest.mark.parametrize("change, key, fragment", [
    ({"name": "{model}"}, "case_grids.g.name", "each entry of the axes once"),
    ({"name": "{model}_{speed}_{other}"}, "case_grids.g.name", "each entry of the axes once"),
    ({"axes": [{"model": {"keys": ["model"], "values": ["FOAM", "TLAM"]},
                "speed": {"keys": ["maneuver.wf"], "values": [1.0]}}], "name": "{model}_{speed}"},
     "case_grids.g.axes[0]", "one length in an axis"),
    ({"axes": [{"model": {"keys": ["model.kind"], "values": ["FOAM"]}}], "name": "{model}"},
     "case_grids.g.axes", "holds as a value, not a mapping"),
    ({"axes": [{"model": {"keys": ["maneuver wf"], "values": [1.0]}}], "name": "{model}"},
     "case_grids.g.axes[0].model.keys[0]", "got 'maneuver wf'"),
])
def test_a_grid_that_cannot_make_its_cases_is_refused(change, key, fragment):
    found = problems_of(study(dict(GRID, **change)))
    assert any(problem.startswith(key + ":") and fragment in problem for problem in found), found


def test_a_generated_name_that_clashes_with_a_case_is_refused():
    other = dict(BASE, maneuver={"kind": "prescribed", "wf": 9.0, "tf": 1.0})
    found = problems_of(study(copy.deepcopy(GRID), foam_w2=other))
    assert any(problem.startswith("case_grids.g.name:") and "'foam_w2', a case given apart" in problem
               for problem in found), found

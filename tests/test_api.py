"""The Python API on the checked objects (``hubbeam.api``): the README's example as written, the
same check as the workflow's, and each answer against the route it stands for."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import yaml
from test_rig_config import KALMAN, SENSORS, sampled_case, study

from hubbeam.api import load
from hubbeam.configuration.load import ConfigError
from hubbeam.control.feedback import design_plant
from hubbeam.control.implementation import controller_system, read_implementation
from hubbeam.linear.statespace import linear_model
from hubbeam.model.beam import beam_from_config
from hubbeam.model.parameters import BeamParameters
from hubbeam.simulation.simulate import simulate

ROOT = Path(__file__).resolve().parents[1]


def readme_example() -> str:
    """The README's Python example (its one ``python`` block)."""
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(encoding="utf-8"), re.S)
    assert len(blocks) == 1, "the README shows one Python example"
    return blocks[0]


def write_study(tmp_path: Path, cfg: dict) -> Path:
    path = tmp_path / "rig.yaml"
    path.write_text(yaml.safe_dump(cfg), encoding="utf-8")
    return path


def test_the_readme_example_runs_and_its_run_is_the_object_route(monkeypatch, capsys):
    monkeypatch.chdir(ROOT)
    namespace: dict = {}
    exec(compile(readme_example(), "README.md", "exec"), namespace)
    printed = capsys.readouterr().out
    assert printed.strip(), "the example prints its answer"
    study_ = namespace["study"]
    case = study_.case("spinup")
    # the same run through the mapping adapter of simulate(): the case and numerics as written
    direct = simulate(case.to_dict(), study_.beam, study_.settings.numerics.to_dict())
    np.testing.assert_array_equal(namespace["ds"]["tip_transverse"].values, direct["tip_transverse"].values)
    # the plant is the linear model of the case's model and matrices at the speed asked
    lin = linear_model(study_.beam, study_.matrices("spinup"), "FOAM", 6.0)
    np.testing.assert_array_equal(namespace["plant"].A, lin.A)


def test_load_refuses_a_bad_last_case_with_its_key(tmp_path):
    # the design model's second mode lies above half the sampling frequency: found on its matrices
    cfg = study(good=sampled_case(KALMAN, SENSORS), bad=sampled_case(KALMAN, SENSORS, sample_time=0.05))
    with pytest.raises(ConfigError) as error:
        load(write_study(tmp_path, cfg))
    assert [problem.path for problem in error.value.problems] == ["cases.bad.maneuver.sampling"]
    assert "half the sampling frequency" in str(error.value)


def test_a_case_with_a_drive_is_linearised_with_the_voltage_as_its_input(tmp_path):
    rig = load(write_study(tmp_path, study(lqg=sampled_case(estimator=KALMAN, sensors=SENSORS))))
    lin = rig.linear("lqg", speed=0.0)
    assert lin.inputs == ("voltage",)
    torque = linear_model(rig.beam, rig.matrices("lqg"), "FOAM", 0.0)
    # the same mechanics: B is the torque's column times the drive's torque gain
    np.testing.assert_allclose(lin.B, torque.B * rig.case("lqg").drive.torque_gain, rtol=1e-14)
    assert rig.design_plant("lqg").model == design_plant(rig.case("lqg"), rig.beam, rig.matrices("lqg")).model


def test_an_exported_controller_reads_back_as_the_designed_one(tmp_path):
    rig = load(write_study(tmp_path, study(lqg=sampled_case(estimator=KALMAN, sensors=SENSORS))))
    mat, text = rig.export_controller("lqg", tmp_path / "lqg")
    designed = controller_system(rig.controller("lqg"))
    for path in (mat, text):
        controller, _ = read_implementation(path)
        np.testing.assert_allclose(controller.A, designed.A, rtol=0, atol=1e-12 * np.abs(designed.A).max())
        assert controller.dt == designed.dt == 0.002


def test_a_case_without_a_sampled_design_has_no_controller(tmp_path):
    cfg = study(move={"model": "FOAM", "t_end": 0.5, "maneuver": {"kind": "prescribed", "wf": 1.0, "tf": 0.4}})
    rig = load(write_study(tmp_path, cfg))
    with pytest.raises(ValueError, match=r"cases\.move\.maneuver: kind 'prescribed' without a design"):
        rig.controller("move")
    with pytest.raises(ConfigError, match="unknown case; defined: move"):
        rig.case("other")


def test_beam_readers_name_what_they_take():
    products = {"beam": {"length": 1.0, "rhoA": 1.0, "EI": 1.0, "EA": 1e6, "hub_inertia": 1.0, "hub_radius": 0.0}}
    with pytest.raises(ValueError, match="beam is missing density, area, youngs_modulus, second_moment"):
        BeamParameters.from_config(products)
    with pytest.raises(ValueError, match=r"takes the beam section.*beam_from_config\(cfg\['beam'\]\)"):
        beam_from_config(products)
    assert beam_from_config(products["beam"]).L == 1.0


def test_a_root_spring_is_a_key_of_the_case_checked_with_the_rest(tmp_path):
    """``cases.<name>.root_spring`` reaches the case as a :class:`RootSpring` through the one check; the
    linear model then carries the hub angle (one more coordinate) and a negative stiffness in the last
    case is refused before anything runs, by its key."""
    move = {"model": "FOAM", "t_end": 0.5, "maneuver": {"kind": "torque", "tau_max": 0.01, "tf": 0.4}}
    spring = {"stiffness": 2.0, "damping": 0.001, "clamp_inertia": 1e-5}
    rig = load(write_study(tmp_path, study(rigid=move, compliant=dict(move, root_spring=spring))))
    assert rig.case("rigid").root_spring is None
    assert rig.case("compliant").root_spring.to_dict() == spring
    rigid, compliant = rig.linear("rigid", speed=0.0), rig.linear("compliant", speed=0.0)
    assert compliant.A.shape[0] == rigid.A.shape[0] + 2
    bad = dict(move, root_spring=dict(spring, stiffness=-2.0))
    with pytest.raises(ConfigError) as error:
        load(write_study(tmp_path, study(rigid=move, bad=bad)))
    assert [problem.path for problem in error.value.problems] == ["cases.bad.root_spring.stiffness"]

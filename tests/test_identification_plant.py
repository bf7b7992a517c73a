"""The adapter from a case and parameter values to the model (``hubbeam.identification.plant``), and the
parameters' records (``hubbeam.identification.parameters``).

* the fast route's matrices (``EI`` scaling ``K2``, a mass affine, the hub inertia replaced) equal
  those assembled for the case with the values applied, to rounding;
* applying values gives the records the configuration builds from the fragment merged onto the case;
* the batched frequency response equals python-control's of the state-space model of
  ``hubbeam.linear`` (voltage and torque inputs, four outputs), and the hub-held modes without damping
  are ``hubbeam.model.eigen.natural_frequencies``; a per-mode damping ratio is its mode's ratio.
"""

from __future__ import annotations

import copy

import control as ct
import numpy as np
import pytest

from hubbeam.configuration.settings import simulation_settings
from hubbeam.identification.parameters import apply, fragment
from hubbeam.identification.plant import CasePlant
from hubbeam.identification.synthetic import RIG_BEAM, RIG_CASE, RIG_NUMERICS, TRUTH, rig_case
from hubbeam.linear.statespace import linear_model
from hubbeam.linear.voltage import voltage_model
from hubbeam.model.beam import beam_from_config
from hubbeam.model.damping import damping_matrices
from hubbeam.model.eigen import natural_frequencies
from hubbeam.simulation.simulate import case_matrices

VALUES = {"beam.EI_factor": 1.1, "beam.hub_inertia": 0.0025, "tip_mass.mass": 0.02, "tip_mass.inertia": 1e-6,
          "root_spring.stiffness": 25.0, "root_spring.damping": 0.003, "damping.transverse": 0.03,
          "damping.transverse_modes.2": 0.012, "drive.motor_constant_factor": 0.9, "drive.viscous_friction": 0.02}


@pytest.fixture(scope="module")
def plant():
    return CasePlant(*rig_case())


def _merged(base: dict, part: dict) -> dict:
    merged = copy.deepcopy(base)
    for key, value in part.items():
        merged[key] = _merged(merged[key], value) if isinstance(value, dict) and key in merged else value
    return merged


def test_the_fast_matrices_are_those_assembled_with_the_values(plant):
    case, beam, sm = plant.system(VALUES)
    assembled = case_matrices(case, beam, plant.numerics)
    for name, fast, slow in zip(sm._fields, sm, assembled):
        scale = max(np.max(np.abs(slow)), 1e-300)
        assert np.max(np.abs(np.asarray(fast) - np.asarray(slow))) <= 1e-13 * scale, name


def test_the_values_give_the_records_the_configuration_builds_from_the_fragment(plant):
    case, beam = apply(plant.case, plant.beam, VALUES)
    part = fragment("rig", VALUES, plant.case, plant.beam)
    assert set(part) == {"beam", "cases"}
    assert set(part["cases"]["rig"]) == {"damping", "root_spring", "tip_mass", "drive"}
    configured, _ = simulation_settings({"name": "rig", **_merged(RIG_CASE, part["cases"]["rig"])}, RIG_NUMERICS,
                                        RIG_BEAM["length"])
    assert configured == case
    assert beam_from_config(_merged(RIG_BEAM, part["beam"])) == beam
    assert configured.damping.transverse_modes == (0.03, 0.012)
    assert configured.drive.torque_constant == pytest.approx(0.9 * plant.case.drive.torque_constant, rel=1e-15)
    assert fragment("rig", {"sensors.hub_angle.gain": 1.01}, plant.case, plant.beam) == {}


@pytest.mark.parametrize("input", ["voltage", "hub_torque"])
def test_the_batched_response_is_python_controls(plant, input):
    case, beam, sm = plant.system(TRUTH, drive=input == "voltage")
    damping = damping_matrices(case.damping, sm)
    outputs = ["hub_angle", "deflection_angle", "tip_deflection", "tip_acceleration"]
    model = (voltage_model(beam, sm, case.model, case.drive, 0.0, damping, outputs, case.root_spring)
             if input == "voltage" else linear_model(beam, sm, case.model, 0.0, "free", damping, outputs,
                                                     case.root_spring))
    system = model.to_control()
    frequency = np.logspace(-1, 2.5, 300)
    for k, output in enumerate(outputs):
        expected = np.asarray(ct.frequency_response(system[k, 0], 2 * np.pi * frequency).complex).ravel()
        found = plant.frequency_response(TRUTH, input, output, frequency)
        np.testing.assert_allclose(found, expected, rtol=1e-9, err_msg=output)


def test_the_undamped_held_modes_are_the_natural_frequencies_and_a_mode_takes_its_own_ratio(plant):
    undamped = {"damping.transverse": 0.0, "damping.axial": 0.0, "root_spring.damping": 0.0}
    case, _, sm = plant.system(undamped)
    frequency, zeta = plant.modes(undamped, "held")
    np.testing.assert_allclose(frequency, natural_frequencies(sm, case.root_spring) / (2 * np.pi), rtol=1e-10)
    assert np.abs(zeta).max() < 1e-10
    rigid = CasePlant(*rig_case({key: value for key, value in RIG_CASE.items() if key != "root_spring"}))
    _, zeta = rigid.modes({"damping.transverse": 0.02, "damping.transverse_modes.2": 0.05}, "held")
    np.testing.assert_allclose(zeta[:3], [0.02, 0.05, 0.02], rtol=1e-9)
    free, _ = plant.modes(TRUTH, "free")
    held, _ = plant.modes(TRUTH, "held")
    assert free[0] > held[0]  # the free hub stiffens the first mode (it turns against the hub's inertia)

"""The rig in a configuration: a drive, voltage tables, sampled controllers and shapers as keys of a
case, checked with the configuration or, where their matrices are needed, before any job
(``hubbeam.control.cases.case_problems``), and run from the objects of the one check.

Each refusal is the last case of a study (the workflow must refuse it before its first job) and is
named by its key; each run is checked against what it must be: a voltage table's hub voltage, the
sampled controller's applied command held by the plant, a shaper's impulses from their closed form.
"""

from __future__ import annotations

import copy
import json
import math

import numpy as np
import pytest

from hubbeam.configuration.load import ConfigError, check_schema
from hubbeam.configuration.settings import from_config
from hubbeam.control.cases import case_problems, simulate_case
from hubbeam.model.drive import QUANSER_SRV02

SRV02 = QUANSER_SRV02.to_dict()
ENCODER = 2.0 * math.pi / 4096
#: a rest-to-rest move of the hub angle
MOVE = {"kind": "angle_table", "time": [0.0, 0.4, 0.8], "angle": [0.0, 0.3, 0.3]}
DAMPED = {"kind": "modal", "axial": 0.01, "transverse": 0.01}
WEIGHTS = {"hub_angle": 160.0, "deflection_angle": 60.0, "hub_speed": 0.25, "deflection_rate": 1.0}


def study(**cases) -> dict:
    """A study of a Quanser-like link (steel, 0.419 m, 65 g) with the given cases, checked."""
    cfg = {"beam": {"length": 0.419, "rhoA": 0.1551, "EI": 200e9 * 9.32e-13, "EA": 200e9 * 0.1551 / 7850.0,
                    "hub_inertia": 0.0022, "hub_radius": 0.0},
           "numerics": {"modes": 2, "rtol": 1e-8, "atol": 1e-11, "output_step": 0.002},
           "study": {"name": "rig"}, "cases": cases}
    return cfg


def sampled_case(estimator=None, sensors=None, **sampling) -> dict:
    spec = {"sample_time": 0.002, **sampling}
    if estimator is not None:
        spec["estimator"] = estimator
    if sensors is not None:
        spec["sensors"] = sensors
    return {"model": "FOAM", "t_end": 0.8, "drive": SRV02, "damping": DAMPED,
            "maneuver": {"kind": "state_feedback", "reference": MOVE,
                         "design": {"model": "SFOAM", "speed": 0.0, "voltage_weight": 1.0, "weights": WEIGHTS},
                         "sampling": spec}}


KALMAN = {"kind": "kalman", "input_noise": 0.1}
SENSORS = [{"signal": "hub_angle", "quantum": ENCODER, "mode": "edges"}, {"signal": "deflection_angle", "noise": 2e-4}]


def problems(cfg: dict) -> list[str]:
    """Every problem of ``cfg``: the configuration's checks, then those needing its matrices."""
    try:
        check_schema(cfg)
    except ConfigError as error:
        return [str(problem) for problem in error.problems]
    return [str(problem) for problem in case_problems(from_config(cfg))]


def assert_refused(cfg: dict, key: str, *fragments: str) -> None:
    found = problems(cfg)
    assert len(found) == 1, found
    assert found[0].startswith(key + ":"), found
    for fragment in fragments:
        assert fragment in found[0], found


# --- refused with the configuration -----------------------------------------------------------

@pytest.mark.parametrize("case, key, fragments", [
    ({"model": "FOAM", "t_end": 1.0, "maneuver": {"kind": "voltage_table", "time": [0, 1], "voltage": [0, 1]}},
     "cases.z.maneuver.kind", ["got 'voltage_table' without a drive"]),
    ({"model": "FOAM", "t_end": 1.0, "drive": SRV02, "maneuver": {"kind": "torque", "tau_max": 1.0, "tf": 0.5}},
     "cases.z.drive", ["an open-loop torque"]),
    ({"model": "FOAM", "t_end": 1.0, "drive": {**SRV02, "resistance": -1.0},
      "maneuver": {"kind": "voltage_table", "time": [0, 1], "voltage": [0, 1]}},
     "cases.z.drive.resistance", ["got -1.0", "> 0"]),
    (dict(sampled_case(), maneuver=dict(sampled_case()["maneuver"],
                                        design={"model": "SFOAM", "speed": 0.0, "torque_weight": 1.0,
                                                "weights": WEIGHTS})),
     "cases.z.maneuver.design.torque_weight", ["given with a drive", "voltage_weight"]),
    (dict(sampled_case(), maneuver=dict(sampled_case()["maneuver"],
                                        design={"model": "lumped", "speed": 0.0, "voltage_weight": 1.0,
                                                "weights": {"theta": 1.0}})),
     "cases.z.maneuver.design.held_frequency", ["missing for the lumped model"]),
    (sampled_case({"kind": "filtered_differences", "cutoff": 50.0}, SENSORS),
     "cases.z.maneuver.sampling.estimator.kind", ["'filtered_differences' with a design on a hub-beam model"]),
    (sampled_case(sensors=SENSORS), "cases.z.maneuver.sampling.sensors", ["given with the exact estimator"]),
    (sampled_case(KALMAN), "cases.z.maneuver.sampling.sensors", ["missing for the kalman estimator"]),
    (sampled_case(KALMAN, [{"signal": "tip_speed"}]), "cases.z.maneuver.sampling.sensors[0].signal",
     ["got 'tip_speed'"]),
])
def test_bad_rig_keys_are_refused_with_the_configuration(case, key, fragments):
    cfg = study(a=sampled_case(), z=case)
    with pytest.raises(ConfigError) as error:
        check_schema(cfg)
    found = [str(problem) for problem in error.value.problems]
    assert any(text.startswith(key + ":") and all(f in text for f in fragments) for text in found), found


# --- refused before any job, from the case's matrices --------------------------------------------

def test_a_design_mode_above_half_the_sampling_frequency_is_refused_naming_it():
    """The link's second vibration mode (22.3 Hz at rest with this hub, free) lies above half of a
    20 Hz sampling: the Kalman filter of a 2-mode design is refused, its frequency and Ts named."""
    cfg = study(a=sampled_case(KALMAN, SENSORS), z=sampled_case(KALMAN, SENSORS, sample_time=0.05))
    cfg["cases"]["z"]["maneuver"]["design"]["modes"] = 2
    assert_refused(cfg, "cases.z.maneuver.sampling", "vibration mode 2 (22.3",
                   "above half the sampling frequency 10 Hz", "Ts = 0.05 s")


def test_a_design_model_too_large_for_the_sampling_is_designed_on_its_truncation():
    """FOAM's axial modes (kHz) lie far above half of a 500 Hz sampling: its Kalman filter is
    refused, unless the design is made on the model truncated below that frequency, whose
    frequency-response error up to there is recorded."""
    full = sampled_case(KALMAN, SENSORS)
    full["maneuver"]["design"]["model"] = "FOAM"
    reduced = copy.deepcopy(full)
    reduced["maneuver"]["sampling"]["reduce"] = True
    assert_refused(study(a=reduced, z=full), "cases.z.maneuver.sampling", "above half the sampling frequency 250 Hz",
                   "mostly q1_")
    cfg = study(a=reduced)
    check_schema(cfg)
    settings = from_config(cfg)
    ds = simulate_case(settings.cases["a"], settings.beam, settings.numerics)
    assert ds.attrs["integrator_status"] == "success"
    assert all(name.startswith("mode_") for name in ds.estimate_state.values)
    assert 0.0 < ds.attrs["design_reduction_error"] < 1.0


def test_a_mode_the_sensors_cannot_see_is_refused():
    """The deflection angle alone does not see the hub angle (the rigid-body mode on the unit
    circle): undetectable."""
    cfg = study(a=sampled_case(KALMAN, SENSORS), z=sampled_case(KALMAN, SENSORS[1:]))
    assert_refused(cfg, "cases.z.maneuver.sampling", "is undetectable from the measured signals", "rigid")


def test_process_noise_that_leaves_the_rigid_mode_undisturbed_is_refused():
    """No process noise at all (input_noise left at 0) is refused at the key to set, before any
    matrix; noise on a state that does not move the rigid-body mode, once the filter is designed."""
    cfg = study(a=sampled_case(KALMAN, SENSORS), z=sampled_case({"kind": "kalman"}, SENSORS))
    assert_refused(cfg, "cases.z.maneuver.sampling.estimator.input_noise", "missing (default 0) with no state_noise",
                   "allowed: input_noise > 0")
    elastic = {"kind": "kalman", "state_noise": {"q2_1": 1.0}}
    assert_refused(study(a=sampled_case(KALMAN, SENSORS), z=sampled_case(elastic, SENSORS)),
                   "cases.z.maneuver.sampling",
                   "is left undisturbed by the process noise (estimator.input_noise, estimator.state_noise)")


def test_a_shaper_above_the_sampling_limit_is_refused():
    """A ZV shaper on 400 rad/s (64 Hz) needs impulses 7.9 ms apart: fine at 2 ms, refused at 20 ms
    (half the sampling frequency 25 Hz)."""
    shaped = dict(sampled_case(), shaper={"kind": "ZV", "frequencies": [400.0]})
    slow = dict(sampled_case(sample_time=0.02), shaper={"kind": "ZV", "frequencies": [400.0]})
    assert problems(study(a=shaped)) == []
    assert_refused(study(a=shaped, z=slow), "cases.z.shaper", "half the sampling frequency")


# --- runs -------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def kalman_run():
    cfg = study(a=sampled_case(KALMAN, SENSORS))
    check_schema(cfg)
    settings = from_config(cfg)
    return simulate_case(settings.cases["a"], settings.beam, settings.numerics)


def test_a_sampled_case_records_what_its_controller_saw_and_applied(kalman_run):
    ds = kalman_run
    assert ds.attrs["integrator_status"] == "success"
    assert list(ds.sensor.values) == ["hub_angle", "deflection_angle"]
    assert list(ds.estimate_state.values) == ["theta", "q2_1", "q2_2", "theta_dot", "q2_1_dot", "q2_2_dot"]
    np.testing.assert_array_equal(ds.applied, np.clip(ds.command, -10.0, 10.0))
    # the encoder counts edges: its reading is a whole number of counts, below the angle by less than one
    counts = ds.measured.sel(sensor="hub_angle").values / ENCODER
    np.testing.assert_allclose(counts, np.round(counts), rtol=0, atol=1e-9)
    gap = ds.sensed.sel(sensor="hub_angle").values - ds.measured.sel(sensor="hub_angle").values
    assert np.all(gap > -1e-12) and np.all(gap < ENCODER)
    # the drive receives the held command: on the output grid (a sample at every output time, no
    # delay) the hub voltage is the command applied at that sample
    np.testing.assert_array_equal(ds.hub_voltage.values, ds.applied.values)


def test_a_seed_is_recorded_and_reproduces_the_noise(kalman_run):
    cfg = study(a=sampled_case(KALMAN, SENSORS, seed=0), b=sampled_case(KALMAN, SENSORS, seed=1))
    check_schema(cfg)
    settings = from_config(cfg)
    again = simulate_case(settings.cases["a"], settings.beam, settings.numerics)
    other = simulate_case(settings.cases["b"], settings.beam, settings.numerics)
    assert again.attrs["noise_seed"] == 0 and other.attrs["noise_seed"] == 1
    np.testing.assert_array_equal(again.measured, kalman_run.measured)
    assert not np.array_equal(other.measured, kalman_run.measured)


def test_a_voltage_table_drives_the_hub_through_the_motor():
    """A constant voltage after a ramp: the hub voltage output is the table's, and the hub torque
    the motor law's at the hub's speed (its closed form, hubbeam.model.drive)."""
    case = {"model": "FOAM", "t_end": 0.5, "drive": SRV02,
            "maneuver": {"kind": "voltage_table", "time": [0.0, 0.1], "voltage": [0.0, 2.0]}}
    cfg = study(v=case)
    check_schema(cfg)
    settings = from_config(cfg)
    ds = simulate_case(settings.cases["v"], settings.beam, settings.numerics)
    t = ds.time.values
    np.testing.assert_allclose(ds.hub_voltage, np.interp(t, [0.0, 0.1], [0.0, 2.0]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(ds.hub_torque, QUANSER_SRV02.torque(ds.hub_voltage.values, ds.theta_dot.values),
                               rtol=1e-12, atol=1e-15)
    assert ds.attrs["drive"]


def test_a_shaper_on_given_frequencies_has_its_closed_form_impulses():
    """ZV on an undamped mode of 20 rad/s: impulses 1/2 at 0 and pi / 20 s (Singer & Seering)."""
    case = {"model": "FOAM", "t_end": 1.0, "maneuver": {"kind": "prescribed", "wf": 0.5, "tf": 0.5},
            "shaper": {"kind": "ZV", "frequencies": [20.0]}}
    cfg = study(s=case)
    check_schema(cfg)
    settings = from_config(cfg)
    ds = simulate_case(settings.cases["s"], settings.beam, settings.numerics)
    shaper = json.loads(ds.attrs["shaper"])
    np.testing.assert_allclose(shaper["times"], [0.0, math.pi / 20.0], rtol=1e-15)
    np.testing.assert_allclose(shaper["amplitudes"], [0.5, 0.5], rtol=1e-15)

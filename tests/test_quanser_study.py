"""The Quanser Rotary Flexible Link study (studies/quanser_rotflex.yaml) and its control analyses.

Each analysis is checked against what it must be: the sample-time sweep's loop against the
continuous loop as the sample time tends to 0 (its eigenvalues tend to exp(lambda Ts), at first
order in Ts); the robustness map's loop at the nominal plant against the design's own closed-loop
poles where the design model is the truth's linear model (FOAM and CFOAM coincide at rest); the
exported controller of the study's job against the loop it was designed to close.
"""

from __future__ import annotations

import copy
import dataclasses
import math

import control as ct
import numpy as np
import pytest

from hubbeam.configuration.load import ConfigError, check_schema, read_config_file
from hubbeam.configuration.settings import from_config
from hubbeam.control import robustness as rb
from hubbeam.control import sample_time as st
from hubbeam.control.analyses import control_problems, sampled_cases
from hubbeam.control.cases import sampled_controller, sampled_loop
from hubbeam.control.implementation import read_implementation
from hubbeam.control.sampled import sensor_rows
from hubbeam.pipeline.jobs.control import control_export
from hubbeam.pipeline.runner import Job
from hubbeam.simulation.simulate import case_matrices

STUDY = "studies/quanser_rotflex.yaml"
DESIGNED = ("lumped_exact", "lumped_filtered", "lumped_kalman", "foam1_exact", "foam1_kalman", "foam3_exact",
            "foam3_kalman")


@pytest.fixture(scope="module")
def raw(repo_root) -> dict:
    return read_config_file(repo_root / STUDY)


def checked(cfg: dict) -> dict:
    cfg = copy.deepcopy(cfg)
    check_schema(cfg)
    return cfg


@pytest.fixture(scope="module")
def settings(raw):
    return from_config(checked(raw))


def test_the_study_validates_and_its_cases_are_the_labs(raw, settings):
    """The published parameters reach the cases: 65 g over 0.419 m, EI = 200 GPa x 9.32e-13 m4, the
    hub's 0.00208 + 0.0002 kg m2, the SRV02 with Beq = 0.015 and 10 V, the 2 ms loop, the encoder of
    4096 counts and the lab's weights, each design model once per estimator."""
    beam = settings.beam
    assert math.isclose(beam.rhoA * beam.L, 0.065, rel_tol=1e-3)  # the measured mass, 4 digits
    assert math.isclose(beam.EI, 200e9 * 9.32e-13, rel_tol=1e-12) and math.isclose(beam.Jh, 0.00228, rel_tol=1e-12)
    assert sampled_cases(settings) == sorted(DESIGNED)
    for name in DESIGNED:
        case = settings.cases[name]
        sampling, design = case.maneuver.sampling, case.maneuver.design
        assert case.model == "CFOAM" and case.modes == 3
        assert (case.drive.viscous_friction, case.drive.voltage_limit, case.drive.rotor_inertia) == (0.015, 10.0, 0.0)
        assert (sampling.sample_time, sampling.delay, sampling.gain) == (0.002, 0.0, "continuous")
        assert dict(design.weights) == {"hub_angle": 160.0, "deflection_angle": 60.0, "hub_speed": 0.25,
                                        "deflection_rate": 1.0} and design.input_weight == 1.0
        assert sampling.estimator.kind == name.partition("_")[2].replace("filtered", "filtered_differences")
        if sampling.sensors:
            assert math.isclose(sampling.sensors[0].quantum * 4096, 2.0 * math.pi, rel_tol=1e-15)
    assert [settings.cases[name].maneuver.design.modes for name in ("foam1_exact", "foam3_exact")] == [1, 3]
    assert settings.cases["lumped_exact"].maneuver.design.held_frequency == 3.0
    assert control_problems(settings) == []
    times = settings.control.sample_time.sample_times.values
    assert times.size == 30 and math.isclose(times[0], 0.002) and math.isclose(times[-1], 0.1)


@pytest.mark.parametrize("change, key, fragment", [
    (lambda c: c["control"]["sample_time"]["cases"].append("held_oscillation"),
     "control.sample_time.cases[3]", "got 'held_oscillation'; allowed: a case with maneuver.sampling"),
    (lambda c: c["control"]["robustness"].update(cases=["foam1_exact", "nowhere"]),
     "control.robustness.cases[1]", "got 'nowhere'"),
    (lambda c: c["control"]["sample_time"].update(sample_times={"start": 0.1, "stop": 0.002, "num": 5}),
     "control.sample_time.sample_times", "start 0.1 >= stop 0.002"),
    (lambda c: c["control"]["robustness"]["ranges"].update(EI_factor=[0.0, 2.0]),
     "control.robustness.ranges.EI_factor", "a factor's low > 0"),
])
def test_a_bad_control_variant_is_refused_naming_its_key(raw, change, key, fragment):
    cfg = copy.deepcopy(raw)
    change(cfg)
    found = [str(problem) for problem in control_problems(from_config(checked(cfg)))]
    assert len(found) == 1 and found[0].startswith(key + ":") and fragment in found[0], found


def test_a_range_outside_the_schema_is_refused_naming_its_key(raw):
    cfg = copy.deepcopy(raw)
    cfg["control"]["robustness"]["ranges"]["hub_inertia"] = [0.001, 0.003]
    with pytest.raises(ConfigError) as error:
        check_schema(cfg)
    assert any(str(problem).startswith("control.robustness.ranges") and "hub_inertia" in str(problem)
               for problem in error.value.problems), error.value.problems


def test_the_sampled_loop_tends_to_the_continuous_one_at_first_order_in_ts(settings):
    """The lumped design's continuous gain through the hold on the truth (CFOAM, 3 modes, the drive),
    no delay: the loop's eigenvalues z tend to exp(lambda Ts) of the continuous loop A - B K C. With
    a zero-order hold z = exp(lambda Ts) + O(Ts^2) (Franklin, Powell and Workman 1998, Ch. 6: the
    hold's B_d = B Ts + A B Ts^2 / 2 + ...), so ln(z) / Ts - lambda is O(Ts): halving Ts halves it
    (ratio 2 within 10 %, the next order's share at these Ts). Compared on the modes below 200 rad/s;
    the axial modes (> 18000 rad/s) are not asymptotic at these Ts."""
    case = settings.cases["lumped_exact"]
    sm = case_matrices(case, settings.beam, settings.numerics)
    truth = st.truth_model(case, settings.beam, settings.numerics, sm)
    steps = (4e-4, 2e-4, 1e-4)
    errors, continuous = [], None
    for Ts in steps:
        controller = st.state_feedback(case, settings.beam, sm, truth, Ts, 0.0, "continuous")
        A, n = st.loop_matrix(truth, controller)
        assert A.shape == (n, n)  # no delay: the loop has the truth's states only
        if continuous is None:  # the continuous gain does not depend on Ts; the loop A - B K C on the truth
            columns = [st.kernel_layout(truth).index(name) for name in truth.states]
            rows = controller.sensor_rows[:, columns] * np.array([s.gain for s in controller.sensors])[:, None]
            b = np.asarray(truth.B)[:, 0]
            continuous = np.linalg.eigvals(np.asarray(truth.A) - np.outer(b, controller.K @ controller.F @ rows))
            slow = continuous[np.abs(continuous) < 200.0]
            assert slow.size >= 6  # the rigid body, the drive and the first two bending modes, closed
        z = np.linalg.eigvals(A)
        estimated = np.log(z.astype(complex)) / Ts
        errors.append(max(np.min(np.abs(estimated - value)) for value in slow))
    assert errors[-1] < 1e-2 * np.max(np.abs(slow))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all(np.abs(ratios - 2.0) < 0.2), (errors, ratios)
    sweep = st.sample_time_sweep(case, settings.beam, settings.numerics, sm, [1e-4, 2e-4], delays=(0.0,),
                                 gains=("continuous",))
    assert math.isclose(sweep.radius[0, 0, 0], np.max(np.abs(np.exp(continuous * 1e-4))), rel_tol=1e-5)


def test_the_robustness_map_at_the_nominal_plant_is_the_designs_loop(settings):
    """The three-mode FOAM design on exact readings of its states, run on CFOAM with three modes:
    CFOAM's linear model at rest is FOAM's, so at the nominal plant the loop's poles are the
    design's closed-loop poles (to rounding: 1e-10 of |z| <= 1), and the map's nominal point (the
    grid's first: no payload) has their spectral radius."""
    case = settings.cases["foam3_exact"]
    sm = case_matrices(case, settings.beam, settings.numerics)
    controller = sampled_controller(case, settings.beam, sm)
    truth = st.truth_model(case, settings.beam, settings.numerics, sm)
    A, _ = st.loop_matrix(truth, controller, sensor_rows(truth, controller.sensors))
    loop = np.linalg.eigvals(A)
    assert loop.size == controller.poles.size
    assert max(np.min(np.abs(loop - pole)) for pole in controller.poles) < 1e-10
    found = rb.robustness_map(case, settings.beam, settings.numerics, {"tip_mass": (0.0, 0.1)}, 3)
    assert math.isclose(found.radius["tip_mass"][0], np.max(np.abs(controller.poles)), rel_tol=1e-12)
    assert math.isclose(found.nominal_radius, np.max(np.abs(controller.poles)), rel_tol=1e-12)
    assert found.nominal["tip_mass"] == 0.0


def test_a_run_reads_the_controller_s_signals_through_its_own_case_s_sensors(settings):
    """A margin's confirmation runs the Kalman design with its sensors quiet (no noise, no
    quantisation), so that the envelope's growth is the loop's, not the noise's: the compiled loop
    carries the run's sensors, the design keeps the noise it was designed for."""
    case = settings.cases["foam3_kalman"]
    controller = sampled_controller(case, settings.beam, case_matrices(case, settings.beam, settings.numerics))
    sampling = case.maneuver.sampling
    assert any(sensor.noise > 0.0 or sensor.quantum > 0.0 for sensor in sampling.sensors)
    quiet = tuple(dataclasses.replace(sensor, noise=0.0, quantum=0.0) for sensor in sampling.sensors)
    run = dataclasses.replace(case, maneuver=dataclasses.replace(
        case.maneuver, sampling=dataclasses.replace(sampling, sensors=quiet)))
    assert [(s.noise, s.quantum) for s in sampled_loop(run, controller).sensors] == [(0.0, 0.0)] * len(quiet)
    assert ([(s.noise, s.quantum) for s in sampled_loop(case, controller).sensors]
            == [(s.noise, s.quantum) for s in sampling.sensors])
    assert [(s.noise, s.quantum) for s in controller.sensors] == [(s.noise, s.quantum) for s in sampling.sensors]


def test_the_exported_controller_closes_the_designed_loop(settings, tmp_path):
    """The study's export job writes the LQG controller of the lumped design; rebuilt in
    python-control from either file, the controller and the design's sampled plant close the loop
    the design predicts (1e-8 of |z| <= 1: simple poles, rounding times their condition)."""
    files = {ext: str(tmp_path / f"lumped_kalman.{ext}") for ext in ("mat", "json")}
    job = Job(input={}, output=files,
              params={"settings": settings, "case": "lumped_kalman"}, log=str(tmp_path / "export.log"))
    control_export(job)
    case = settings.cases["lumped_kalman"]
    controller = sampled_controller(case, settings.beam, case_matrices(case, settings.beam, settings.numerics))
    for path in job.output.values():
        K, P = read_implementation(path)
        p = len(controller.sensors)
        loop = ct.feedback(P, K[:, list(range(p))], sign=1)
        poles = ct.poles(loop)
        assert max(np.min(np.abs(poles - pole)) for pole in controller.poles) < 1e-8, path


# --- the report's section, from synthetic results ----------------------------------------------------

def synthetic_runs() -> dict:
    """A held-hub run whose tip rings at 3.5 Hz with 1 % damping and a sampled run of the SRV02 whose
    command reaches 12.5 V (beyond the 10 V limit) and whose hub ends 0.01 rad short of 0.5 rad."""
    import json

    import xarray as xr

    from hubbeam.model.drive import QUANSER_SRV02

    t = np.arange(0.0, 3.0, 0.002)
    f, zeta = 3.5, 0.01
    omega = 2.0 * math.pi * f
    sigma = zeta * omega / math.sqrt(1.0 - zeta**2)
    held = xr.Dataset({"tip_transverse": ("time", 0.01 * np.exp(-sigma * t) * np.cos(omega * t))},
                      coords={"time": t},
                      attrs={"model": "CFOAM", "case_config": json.dumps(
                          {"maneuver": {"kind": "speed_table", "time": [0, 3], "speed": [0, 0]}})})
    samples = np.linspace(0.0, 2.0, 1001)
    reference = {"kind": "angle_table", "time": [0.0, 0.5], "angle": [0.0, 0.5]}
    maneuver = {"kind": "state_feedback", "reference": reference,
                "design": {"model": "lumped", "speed": 0.0, "weights": {"hub_angle": 1.0}, "held_frequency": 3.0}}
    tip = np.where(t < 0.5, 0.02 * np.sin(omega * t), 0.001 * np.sin(omega * t))
    run = xr.Dataset({"tip_transverse": ("time", tip), "theta": ("time", np.full(t.size, 0.49)),
                      "applied": ("sample", np.where(samples < 0.1, 12.5, 1.0))},
                     coords={"time": t, "sample_time": ("sample", samples)},
                     attrs={"model": "CFOAM", "drive": json.dumps(QUANSER_SRV02.to_dict()),
                            "controller_kind": "LQR on the true state", "integrator_status": "success",
                            "controller_poles_real": [0.99, 0.5], "controller_poles_imag": [0.0, 0.1],
                            "maneuver": json.dumps(maneuver), "case_config": json.dumps({"maneuver": maneuver})})
    return {"held": held, "move": run}


def test_the_report_section_reads_its_numbers_from_the_results():
    from hubbeam.reporting.formatting import number
    from hubbeam.study.controllers import controllers_markdown, held_frequency_rows, performance_rows

    runs = synthetic_runs()
    rows = held_frequency_rows(runs)
    assert math.isclose(rows[0]["frequency_hz"], 3.5, rel_tol=1e-6) and math.isclose(rows[0]["damping"], 0.01,
                                                                                     rel_tol=1e-4)
    assert rows[0]["source"].startswith("model") and rows[1]["source"].startswith("measured")
    assert rows[1]["frequency_hz"] == 3.0
    sweep = st.sweep_dataset([st.SampleTimeSweep(
        design="move", sample_times=np.array([0.002, 0.05]), gains=("continuous",), delays=(0.0,),
        radius=np.array([[[0.99, 1.2]]]), pole=np.array([[[0.99, -1.2]]], dtype=complex),
        mode=np.array([[["bending 2", "drive"]]], dtype=object), boundary=np.array([[0.0377]]),
        boundary_mode=np.array([["drive"]], dtype=object), design_frequencies=np.array([3.75]))],
        st.PlantModes(values=np.array([]), vectors=np.zeros((0, 0)), labels=(), names=("bending 1", "bending 2"),
                      frequencies=np.array([4.6, 22.3])))
    robustness = rb.robustness_dataset([rb.RobustnessMap(
        case="move", values={"tip_mass": np.array([0.0, 0.1, 0.2])}, radius={"tip_mass": np.array([0.99, 0.995, 1.01])},
        mode={"tip_mass": np.array(["drive"] * 3, dtype=object)}, nominal={"tip_mass": 0.0},
        margins={"tip_mass": (0.0, 0.15)}, nominal_radius=1.002)],
        [rb.MarginRun("move", "tip_mass", "highest", where, value, radius, math.log(radius) / 0.002, rate, "success")
         for where, value, radius, rate in (("inside", 0.1425, 0.9995, -0.21), ("outside", 0.1575, 1.0004, 0.17))])
    text = controllers_markdown(runs, sweep, robustness, {"move": ("../control/move.mat", "../control/move.json")})
    performance = performance_rows(runs, robustness)[0]
    assert math.isclose(performance["final_error_rad"], -0.01, abs_tol=1e-12)
    assert performance["saturated"] and performance["peak_voltage"] == 12.5
    assert math.isclose(performance["predicted_radius"], 0.99) and performance["truth_radius"] == 1.002
    assert math.isclose(performance["residual_tip_m"], 0.001, rel_tol=1e-2)  # after the reference's end, 0.5 s
    # the drive's record: 0.069 N m s/rad of back-EMF damping against Beq = 0.015 (Quanser's numbers)
    assert f"= {number(0.06902982498461538, 3)} N m s/rad" in text and "0.069 N m s/rad" in text
    assert "wrong: predicted stable, unstable on the truth" in text  # prediction apart from performance
    assert "37.7 ms" in text and "lacks the truth's bending 2 (22.3 Hz)" in text
    assert "0 .. 0.15*" in text and "[move.mat](../control/move.mat)" in text
    assert "| move | tip_mass | highest | outside | 0.1575 | 1.0004 | 0.2 | 0.17 | success |" in text
    assert text.index("### Prediction") < text.index("### Performance")


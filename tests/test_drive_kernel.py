"""The hub's DC drive in the kernels (``hubbeam.core.drive``, ``hubbeam.simulation.simulate.run`` with a motor).

* the kernel evaluates the law of ``DcMotor`` (torque, and its inverse, the voltage) from the
  packed array;
* a constant voltage on a free hub carrying the damped beam settles at the closed-form speed
  ``torque_gain V / hub_damping`` (the beam in steady spin needs no torque), FOAM and CFOAM; the
  rotor's reflected inertia changes the transient, not the speed;
* with Coulomb friction the hub creeps below the breakaway voltage, at most at ``eps atanh(V /
  V_b)``, and turns at ``(torque_gain V - Fc) / hub_damping`` above it;
* a prescribed hub reports the voltage it needs (``DcMotor.voltage`` of its torque and speed), and
  the rotor's reflected inertia adds exactly ``J_r theta''`` to the torque it needs.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq
from synthetic_results import rig_run

from hubbeam.core import drive
from hubbeam.core.integrate import output_columns
from hubbeam.model.drive import QUANSER_SRV02, DcMotor

#: tight tolerances: the closed forms below hold to the integrator's error
NUMERICS = {"rtol": 1e-10, "atol": 1e-12, "output_step": 0.01, "max_steps": 10**6, "step_warning": 10**6,
            "divergence_limit": 0.5, "quadrature_points": 40}
#: damping of every mode: the slowest beam mode (3.7 Hz) then decays as exp(-2.3 t), to 1e-12
#: of its start by t_end = 12 s, and the hub (time constant J / hub_damping = 0.06 s) sooner
DAMPED = {"kind": "modal", "axial": 0.1, "transverse": 0.1}
#: the SRV02 with its rotor counted apart from the hub (its manual's rotor inertia, 3.9e-7 kg m2)
WITH_ROTOR = dataclasses.replace(QUANSER_SRV02, rotor_inertia=3.9e-7)


def _constant_voltage(model, volts, t_end=12.0):
    return {"name": "drive", "model": model, "modes": 2, "t_end": t_end, "damping": DAMPED,
            "maneuver": {"kind": "voltage_table", "time": [0.0, 1.0], "voltage": [volts, volts]}}


def test_the_kernel_evaluates_the_motor_law():
    motor = DcMotor(resistance=2.0, torque_constant=0.01, back_emf_constant=0.012, gear_ratio=50.0,
                    motor_efficiency=0.8, gearbox_efficiency=0.85, viscous_friction=0.01,
                    coulomb_friction=0.02, coulomb_smoothing=0.05, voltage_limit=12.0)
    packed = motor.packed()
    for volts in np.linspace(-20.0, 20.0, 9):  # beyond the limit too
        for speed in np.linspace(-4.0, 4.0, 9):
            # the same operations in the same order; only tanh (numpy's and the C library's)
            # may differ in the last bit
            assert drive.drive_torque(packed, volts, speed) == pytest.approx(
                float(motor.torque(volts, speed)), rel=1e-15, abs=1e-17)
            torque = float(motor.torque(volts, speed))
            assert drive.required_voltage(packed, torque, speed) == pytest.approx(
                float(motor.voltage(torque, speed)), rel=1e-15, abs=1e-15)
    # without a drive the command is the torque, untouched
    assert drive.drive_torque(np.zeros(0), 1.2345, 7.0) == 1.2345


@pytest.mark.parametrize("model", ["FOAM", "CFOAM"])
def test_a_constant_voltage_spins_the_free_hub_at_the_closed_form_speed(flexible_link, model):
    volts = 3.0
    expected = QUANSER_SRV02.torque_gain * volts / QUANSER_SRV02.hub_damping
    columns = output_columns(2)
    for motor in (QUANSER_SRV02, WITH_ROTOR):
        run = rig_run(_constant_voltage(model, volts), flexible_link, NUMERICS, motor=motor)
        assert run.status == 0
        end = run.out[-1]
        # the transients have decayed to 1e-12 (DAMPED); the integrator's error is of rtol
        assert end[columns["theta_dot"]] == pytest.approx(expected, rel=1e-9)
        assert abs(end[columns["hub_torque"]]) < 1e-9 * QUANSER_SRV02.torque_gain * volts
        assert end[columns["hub_voltage"]] == volts
        assert end[columns["motor_torque"]] == pytest.approx(
            float(QUANSER_SRV02.friction(end[columns["theta_dot"]])), rel=1e-9)
    assert run.matrices.Jh == pytest.approx(flexible_link.Jh + WITH_ROTOR.reflected_inertia, rel=1e-15)


def test_coulomb_friction_holds_the_hub_below_the_breakaway_voltage(flexible_link):
    eps = 1e-3
    motor = dataclasses.replace(QUANSER_SRV02, coulomb_friction=0.05, coulomb_smoothing=eps)
    breakaway = motor.breakaway_voltage
    speed = output_columns(2)["theta_dot"]
    for fraction in (0.5, 0.9, 2.0):
        volts = fraction * breakaway
        run = rig_run(_constant_voltage("FOAM", volts), flexible_link, NUMERICS, motor=motor)
        final = run.out[-1, speed]
        # the hub's steady speed is the drive's zero torque, found apart by brentq
        steady = brentq(lambda w, v=volts: motor.torque(v, w), 0.0, 100.0, xtol=1e-15)
        assert final == pytest.approx(steady, rel=1e-8)
        if fraction < 1.0:
            assert 0.0 < final <= eps * math.atanh(fraction)
        else:
            expected = (motor.torque_gain * volts - motor.coulomb_friction) / motor.hub_damping
            assert final == pytest.approx(expected, rel=1e-8)  # tanh(w / eps) = 1 - 1e-500


def test_a_prescribed_hub_reports_the_voltage_it_needs(flexible_link):
    case = {"name": "prescribed", "model": "FOAM", "modes": 2, "t_end": 3.0, "damping": DAMPED,
            "maneuver": {"kind": "prescribed", "wf": 2.0, "tf": 2.0}}
    motor = dataclasses.replace(WITH_ROTOR, coulomb_friction=0.02, coulomb_smoothing=0.05)
    columns = output_columns(2)
    driven = rig_run(case, flexible_link, NUMERICS, motor=motor).out
    bare = rig_run(case, flexible_link, NUMERICS).out
    torque, speed = driven[:, columns["hub_torque"]], driven[:, columns["theta_dot"]]
    np.testing.assert_allclose(driven[:, columns["hub_voltage"]], motor.voltage(torque, speed), rtol=1e-14,
                               atol=1e-14)
    np.testing.assert_allclose(driven[:, columns["motor_torque"]], torque + motor.friction(speed), rtol=1e-14,
                               atol=1e-16)
    assert np.all(np.isnan(bare[:, columns["hub_voltage"]]))
    # the hub's inertia does not enter the elastic equations of a prescribed hub: the same states,
    # and a torque larger by the rotor's share of theta'' (to the rounding of the hub row)
    np.testing.assert_array_equal(driven[:, columns["q2"]], bare[:, columns["q2"]])
    extra = motor.reflected_inertia * driven[:, columns["theta_ddot"]]
    np.testing.assert_allclose(torque - bare[:, columns["hub_torque"]], extra, rtol=0,
                               atol=1e-12 * np.abs(torque).max())

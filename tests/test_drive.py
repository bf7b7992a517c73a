"""The DC drive (hubbeam.model.drive): its linear reading, its inverse and its friction."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from hubbeam.model.drive import QUANSER_SRV02, DcMotor


def test_the_srv02_back_emf_damps_the_hub_more_than_its_friction():
    # eta_g Kg eta_m kt / Rm = 0.9 * 70 * 0.69 * 7.68e-3 / 2.6, times Kg km = 70 * 7.68e-3
    gain = 0.9 * 70 * 0.69 * 7.68e-3 / 2.6
    assert QUANSER_SRV02.torque_gain == pytest.approx(gain, rel=1e-15)
    assert QUANSER_SRV02.back_emf_damping == pytest.approx(gain * 70 * 7.68e-3, rel=1e-15)
    assert QUANSER_SRV02.back_emf_damping == pytest.approx(0.0690, abs=5e-5)
    assert QUANSER_SRV02.back_emf_damping / QUANSER_SRV02.viscous_friction == pytest.approx(4.6, abs=0.01)


def test_voltage_is_the_inverse_of_torque_below_the_limit():
    motor = DcMotor(resistance=2.0, torque_constant=0.01, back_emf_constant=0.012, gear_ratio=50.0,
                    motor_efficiency=0.8, gearbox_efficiency=0.85, viscous_friction=0.01,
                    coulomb_friction=0.02, coulomb_smoothing=0.05, voltage_limit=12.0)
    speeds = np.linspace(-3.0, 3.0, 13)
    voltages = np.linspace(-9.0, 9.0, 13)
    torques = motor.torque(voltages, speeds)
    np.testing.assert_allclose(motor.voltage(torques, speeds), voltages, rtol=0, atol=1e-12)


def test_the_voltage_limit_clips_the_command():
    assert QUANSER_SRV02.torque(25.0, 0.0) == pytest.approx(QUANSER_SRV02.torque_gain * 10.0, rel=1e-15)
    assert QUANSER_SRV02.torque(-25.0, 0.0) == pytest.approx(-QUANSER_SRV02.torque_gain * 10.0, rel=1e-15)


def test_steady_speed_of_an_unloaded_hub_is_the_closed_form():
    """At steady speed the drive's torque is zero: gain (V - Kg km w) = B w, so w = gain V /
    (gain Kg km + B) without Coulomb friction."""
    V = 3.0
    w = brentq(lambda s: QUANSER_SRV02.torque(V, s), 0.0, 100.0, xtol=1e-14)
    assert w == pytest.approx(QUANSER_SRV02.torque_gain * V / QUANSER_SRV02.hub_damping, rel=1e-12)


def test_coulomb_friction_holds_the_hub_below_the_breakaway_voltage():
    eps = 1e-3
    motor = DcMotor(resistance=2.6, torque_constant=7.68e-3, back_emf_constant=7.68e-3, gear_ratio=70.0,
                    motor_efficiency=0.69, gearbox_efficiency=0.9, viscous_friction=0.015,
                    coulomb_friction=0.05, coulomb_smoothing=eps)
    breakaway = motor.breakaway_voltage
    assert breakaway == pytest.approx(0.05 / motor.torque_gain, rel=1e-15)

    def steady(V):
        return brentq(lambda s: motor.torque(V, s), 0.0, 100.0, xtol=1e-15)

    # below: the regularised friction lets the hub creep, at most at eps atanh(V / V_b) (where
    # Fc tanh(w / eps) alone balances the torque); above: it turns at (gain V - Fc) / (gain Kg km
    # + B), the friction saturated
    for fraction in (0.5, 0.9):
        assert 0.0 < steady(fraction * breakaway) <= eps * math.atanh(fraction)
    above = 2.0 * breakaway
    expected = (motor.torque_gain * above - motor.coulomb_friction) / motor.hub_damping
    assert steady(above) == pytest.approx(expected, rel=1e-6)
    assert math.tanh(expected / eps) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("key, value", [("resistance", 0.0), ("gear_ratio", -70.0), ("motor_efficiency", 1.2),
                                        ("coulomb_smoothing", 0.0), ("voltage_limit", math.nan),
                                        ("viscous_friction", math.inf), ("torque_constant", "7e-3 N m/A")])
def test_a_motor_out_of_range_is_refused_naming_the_parameter(key, value):
    with pytest.raises(ValueError, match=f"DcMotor.{key} = .*allowed"):
        DcMotor(**{"resistance": 2.6, "torque_constant": 7.68e-3, "back_emf_constant": 7.68e-3, key: value})


def test_the_packed_drive_holds_the_law_s_constants():
    packed = QUANSER_SRV02.packed()
    assert packed.tolist() == [QUANSER_SRV02.torque_gain, 70.0 * 7.68e-3, 0.015, 0.0, 0.01, 10.0]

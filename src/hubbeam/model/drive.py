"""The hub's actuator: a DC motor with a gearbox, driven by an amplifier's voltage.

The armature inductance is neglected (its time constant, ``La / Rm``, is well below a
millisecond on servo motors of this size), so the current follows the voltage at once and the
torque the gearbox delivers to the hub is

    tau = eta_g Kg eta_m kt (V_sat - Kg km theta') / Rm  -  B theta'  -  Fc tanh(theta' / eps)

with ``V_sat`` the commanded voltage clipped to the amplifier's limit ``+-V_max``; ``Rm`` the
armature resistance, ``kt`` the torque constant, ``km`` the back-EMF constant, ``eta_m`` the
motor efficiency, ``Kg`` the gear ratio and ``eta_g`` the gearbox efficiency; ``B`` the viscous
and ``Fc`` the Coulomb friction on the hub (the latter regularised by ``tanh`` with the speed
``eps``, so that the equations stay smooth; below about ``eps`` the friction acts like a stiff
viscous damper of ``Fc / eps``). This is the servo model of the Quanser SRV02 manual (and of most
teaching rigs); the numbers of that rig are :data:`QUANSER_SRV02`.

Read as a linear law at the hub, the drive is a torque gain and a damper:

    tau = torque_gain V - (back_emf_damping + B) theta'         (below the limit, Fc = 0)

``torque_gain = eta_g Kg eta_m kt / Rm`` (N m V-1), ``back_emf_damping = torque_gain Kg km``
(N m s rad-1). For the SRV02 the back-EMF alone damps the hub with 0.069 N m s rad-1, 4.6 times its
viscous friction. The rotor's inertia reaches the hub multiplied by ``eta_g Kg^2``
(:attr:`DcMotor.reflected_inertia`); a manual's "equivalent" hub inertia often holds it already,
in which case ``rotor_inertia`` is 0 here so that it is counted once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from hubbeam.core import drive as kernel_drive

#: the ranges of the parameters: name -> (test, what is allowed)
_RANGES = {
    "positive": (lambda x: 0.0 < x < math.inf, "a finite value > 0"),
    "non-negative": (lambda x: 0.0 <= x < math.inf, "a finite value >= 0"),
    "efficiency": (lambda x: 0.0 < x <= 1.0, "an efficiency in (0, 1]"),
    "limit": (lambda x: x > 0.0, "a voltage > 0 (inf: no limit)"),
}
#: the range of every field of :class:`DcMotor`
_FIELD_RANGES = {"resistance": "positive", "torque_constant": "positive", "back_emf_constant": "non-negative",
                 "gear_ratio": "positive", "motor_efficiency": "efficiency", "gearbox_efficiency": "efficiency",
                 "rotor_inertia": "non-negative", "viscous_friction": "non-negative",
                 "coulomb_friction": "non-negative", "coulomb_smoothing": "positive", "voltage_limit": "limit"}


def _checked(name: str, value) -> float:
    """``value`` as a float in the range of the field ``name``; ``ValueError`` naming both."""
    test, allowed = _RANGES[_FIELD_RANGES[name]]
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not test(number):
        raise ValueError(f"DcMotor.{name} = {value!r}; allowed: {allowed}")
    return number


@dataclass(frozen=True)
class DcMotor:
    """A DC servo motor with gearbox and amplifier, every parameter in SI units (module docstring).

    ``coulomb_smoothing`` is the speed ``eps`` (rad s-1) of the ``tanh`` regularisation of the
    Coulomb friction; ``voltage_limit`` the amplifier's saturation ``V_max`` (V, ``inf``: none).
    """

    resistance: float
    torque_constant: float
    back_emf_constant: float
    gear_ratio: float = 1.0
    motor_efficiency: float = 1.0
    gearbox_efficiency: float = 1.0
    rotor_inertia: float = 0.0
    viscous_friction: float = 0.0
    coulomb_friction: float = 0.0
    coulomb_smoothing: float = 0.01
    voltage_limit: float = math.inf

    def __post_init__(self) -> None:
        for item in fields(self):
            object.__setattr__(self, item.name, _checked(item.name, getattr(self, item.name)))

    def to_dict(self) -> dict:
        """The parameters as a configuration writes them (``voltage_limit`` left out when there is none)."""
        return {item.name: getattr(self, item.name) for item in fields(self)
                if not (item.name == "voltage_limit" and math.isinf(self.voltage_limit))}

    @property
    def torque_gain(self) -> float:
        """``eta_g Kg eta_m kt / Rm``: hub torque per volt at rest, N m V-1."""
        return (self.gearbox_efficiency * self.gear_ratio * self.motor_efficiency * self.torque_constant
                / self.resistance)

    @property
    def back_emf_damping(self) -> float:
        """``torque_gain Kg km``: the hub damping of the back-EMF, N m s rad-1."""
        return self.torque_gain * self.gear_ratio * self.back_emf_constant

    @property
    def hub_damping(self) -> float:
        """The whole linear damping of the hub: back-EMF plus viscous friction, N m s rad-1."""
        return self.back_emf_damping + self.viscous_friction

    @property
    def reflected_inertia(self) -> float:
        """``eta_g Kg^2 J_m``: the rotor's inertia as the hub feels it, kg m2."""
        return self.gearbox_efficiency * self.gear_ratio**2 * self.rotor_inertia

    @property
    def breakaway_voltage(self) -> float:
        """``Fc / torque_gain``: the voltage whose torque at rest equals the Coulomb friction, V."""
        return self.coulomb_friction / self.torque_gain

    def packed(self) -> np.ndarray:
        """The drive as the kernels read it (``hubbeam.core.drive``: ``[torque_gain, Kg km, B, Fc,
        eps, V_max]``), so that the kernel evaluates :meth:`torque` with the same operations."""
        packed = np.empty(kernel_drive.DRIVE_SIZE)
        packed[kernel_drive.TORQUE_GAIN] = self.torque_gain
        packed[kernel_drive.BACK_EMF] = self.gear_ratio * self.back_emf_constant
        packed[kernel_drive.VISCOUS] = self.viscous_friction
        packed[kernel_drive.COULOMB] = self.coulomb_friction
        packed[kernel_drive.SMOOTHING] = self.coulomb_smoothing
        packed[kernel_drive.VOLTAGE_LIMIT] = self.voltage_limit
        return packed

    def saturate(self, voltage):
        """``voltage`` clipped to the amplifier's limit."""
        return np.clip(voltage, -self.voltage_limit, self.voltage_limit)

    def friction(self, speed):
        """Friction torque on the hub at ``speed`` (rad s-1), opposing it, N m."""
        speed = np.asarray(speed, dtype=float)
        return self.viscous_friction * speed + self.coulomb_friction * np.tanh(speed / self.coulomb_smoothing)

    def torque(self, voltage, speed):
        """Torque on the hub (N m) at the commanded ``voltage`` (V) and hub ``speed`` (rad s-1)."""
        speed = np.asarray(speed, dtype=float)
        return (self.torque_gain * (self.saturate(voltage) - self.gear_ratio * self.back_emf_constant * speed)
                - self.friction(speed))

    def voltage(self, torque, speed):
        """The voltage (V, before saturation) that makes the drive deliver ``torque`` (N m) to a hub
        turning at ``speed``: the inverse of :meth:`torque` below the limit (what a prescribed hub
        would ask of the amplifier)."""
        speed = np.asarray(speed, dtype=float)
        return ((np.asarray(torque, dtype=float) + self.friction(speed)) / self.torque_gain
                + self.gear_ratio * self.back_emf_constant * speed)


#: the Quanser SRV02 servo (high-gear configuration) as its user manual lists it; its equivalent
#: hub inertia (0.00208 kg m2 without load) already holds the rotor, so ``rotor_inertia`` is 0
QUANSER_SRV02 = DcMotor(resistance=2.6, torque_constant=7.68e-3, back_emf_constant=7.68e-3, gear_ratio=70.0,
                        motor_efficiency=0.69, gearbox_efficiency=0.9, rotor_inertia=0.0,
                        viscous_friction=0.015, coulomb_friction=0.0, voltage_limit=10.0)

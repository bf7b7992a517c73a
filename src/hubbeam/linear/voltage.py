"""Linear models of a free hub driven by a DC motor: the amplifier's voltage as the input.

The drive (:class:`hubbeam.model.drive.DcMotor`) delivers to the hub the torque

    tau = kV (V - Kg km theta') - B theta' - Fc tanh(theta' / eps),      kV = torque_gain,

below the amplifier's limit. About a steady spin at ``theta' = Omega`` it needs the operating-point
voltage ``V0 = motor.voltage(0, Omega)`` (the steady spin needs no torque at the hub:
``hubbeam.linear.statespace``; the drive must still cover its back-EMF and friction), and to first
order in the deviations ``u = V - V0``, ``theta' - Omega``:

    tau = kV u - c theta',     c = kV Kg km + B + (Fc / eps) sech^2(Omega / eps),

the back-EMF and the viscous friction (``DcMotor.hub_damping``) plus the slope of the regularised
Coulomb friction at the operating speed. About rest that slope is ``Fc / eps``: the regularised
friction acts like a stiff damper there (the linear model of the smooth drive, not of stick-slip).
Far from rest (``Omega >> eps``) it vanishes and Coulomb friction only shifts ``V0``.

The free-hub equations of ``hubbeam.linear.statespace`` with this torque become

    M z'' + (G + C + c e_theta e_theta^T) z' + K z = e_theta kV u,

so ``B_V = kV B_tau`` and the hub row is damped by ``c``; the torque models are unchanged. An LQR
design on volts minimises ``x' Q x + R_V u^2``; a torque design's cost ``x' Q x + R_tau tau^2``
with ``tau = kV u`` is the same cost for ``R_V = kV^2 R_tau`` (weights on states and outputs stay
as they are), though the gains differ because the voltage model holds the drive's damping.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hubbeam.linear.statespace import (
    LinearModel,
    accelerations,
    check_matrices,
    check_request,
    check_speed,
    model_states,
    spin_equations,
    state_space_matrices,
)
from hubbeam.model.drive import DcMotor
from hubbeam.model.root import checked_spring

#: the name of the drive's input (its unit: ``statespace.INPUT_UNITS``)
VOLTAGE = "voltage"


@dataclass(frozen=True, eq=False)
class DrivenModel(LinearModel):
    """A :class:`LinearModel` whose input is the drive's voltage deviation ``V - V0`` (V).

    ``motor`` the drive, ``operating_voltage`` ``V0`` (V) that holds the steady spin,
    ``hub_damping`` the linearised damping ``c`` (N m s rad-1) the drive adds to the hub row.
    """

    motor: DcMotor | None = None
    operating_voltage: float = 0.0
    hub_damping: float = 0.0

    @property
    def name(self) -> str:
        """The python-control name: the torque model's with ``_voltage`` appended."""
        return super().name + "_voltage"


def check_motor(motor) -> DcMotor:
    """``motor`` unchanged; ``ValueError`` unless it is a :class:`DcMotor` with a positive torque gain."""
    if not isinstance(motor, DcMotor):
        raise ValueError(f"motor = {motor!r}; allowed: a hubbeam.model.drive.DcMotor")
    values = (motor.resistance, motor.torque_constant, motor.torque_gain)
    if not all(math.isfinite(value) and value > 0.0 for value in values):
        raise ValueError(f"motor = {motor!r}; allowed: a positive resistance, torque constant and gain")
    return motor


def linearised_damping(motor: DcMotor, speed: float) -> float:
    """``c = kV Kg km + B + (Fc / eps) sech^2(speed / eps)``: minus the slope of the drive's torque
    with the hub speed at ``speed`` (rad s-1), N m s rad-1 (module docstring)."""
    x = abs(speed) / motor.coulomb_smoothing
    sech2 = 4.0 * math.exp(-2.0 * x) / (1.0 + math.exp(-2.0 * x)) ** 2  # 1 / cosh(x)^2, without overflow
    coulomb = motor.coulomb_friction / motor.coulomb_smoothing * sech2
    return motor.hub_damping + coulomb


def operating_voltage(motor: DcMotor, speed: float) -> float:
    """``V0``: the voltage (V) that holds the hub's steady spin at ``speed`` (zero net torque);
    ``ValueError`` when it exceeds the amplifier's limit."""
    volts = float(motor.voltage(0.0, speed))
    if abs(volts) > motor.voltage_limit:
        raise ValueError(f"speed = {speed!r}: the steady spin needs {volts:.6g} V, beyond the amplifier's "
                         f"limit {motor.voltage_limit:g} V; allowed: a speed the drive can hold")
    return volts


def voltage_model(beam, sm, model: str, motor: DcMotor, speed: float = 0.0, damping=None,
                  outputs=None, root_spring=None) -> DrivenModel:
    """The free-hub linear model of ``model`` with the voltage of ``motor`` as its input.

    Arguments as :func:`hubbeam.linear.statespace.linear_model` (free hub; the drive on the hub's
    side of a ``root_spring``); ``motor`` a :class:`~hubbeam.model.drive.DcMotor` whose inertia the
    hub inertia of ``beam`` already holds (``DcMotor.reflected_inertia`` is added to nothing here).
    Every argument is checked first.
    """
    root_spring = checked_spring(root_spring)
    traits, names = check_request(model, "free", outputs, root_spring is not None)
    speed = check_speed(speed)
    check_motor(motor)
    check_matrices(beam, sm)
    volts = operating_voltage(motor, speed)
    c = linearised_damping(motor, speed)
    M, G, C, K, q1s, hub = spin_equations(sm, traits, speed, damping, root_spring)
    C = C.copy()
    C[hub, hub] += c
    Az, Av, Bu = accelerations(M, G, C, K, "free", hub)
    A, B, Cy, D = state_space_matrices(beam, sm, traits, speed, names, q1s, (Az, Av, motor.torque_gain * Bu),
                                       root_spring)
    return DrivenModel(model=traits.name, hub="free", speed=speed, A=A, B=B, C=Cy, D=D,
                       states=model_states(traits, sm.M2.shape[0], root_spring), inputs=(VOLTAGE,), outputs=names,
                       root_spring=root_spring, motor=motor, operating_voltage=volts, hub_damping=c)


def voltage_weight(torque_weight: float, motor: DcMotor) -> float:
    """``R_V = kV^2 R_tau``: the weight on volts^2 that prices a volt as ``torque_weight`` prices the
    torque it makes at rest (module docstring)."""
    return check_motor(motor).torque_gain ** 2 * float(torque_weight)


__all__ = ["VOLTAGE", "DrivenModel", "linearised_damping", "operating_voltage", "voltage_model",
           "voltage_weight"]

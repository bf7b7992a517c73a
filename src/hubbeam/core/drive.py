"""The hub's DC drive in the kernels: the torque law of ``hubbeam.model.drive.DcMotor`` evaluated
from a packed float array (``DcMotor.packed``, the layout below).

With a drive, a free hub's maneuver gives the amplifier's command ``V`` (volts) and the hub receives

    tau = torque_gain (V_sat - Kg km theta') - B theta' - Fc tanh(theta' / eps),

``V_sat`` the command clipped to ``+-V_max`` (the law and its symbols: ``hubbeam.model.drive``).
Packed as ``[torque_gain, Kg km, B, Fc, eps, V_max]`` (:data:`TORQUE_GAIN` ... :data:`VOLTAGE_LIMIT`).
An empty array (``hubbeam.core.inputs.NO_DRIVE``) is an ideal torque actuator: the command is the
torque, and no floating-point operation is added to a run without a drive.

Every kernel that needs a free hub's torque takes it from :func:`free_hub_torque`: the maneuver's
command, shaped (``hubbeam.core.shaping``), through this law.
"""

import math

from hubbeam.core.jit import borrowing_kernel
from hubbeam.core.shaping import shaped_torque

TORQUE_GAIN, BACK_EMF, VISCOUS, COULOMB, SMOOTHING, VOLTAGE_LIMIT = range(6)
#: values of a packed drive
DRIVE_SIZE = 6


@borrowing_kernel
def terminal_voltage(drive, command):
    """The command clipped to the amplifier's limit: the voltage across the motor."""
    return min(max(command, -drive[VOLTAGE_LIMIT]), drive[VOLTAGE_LIMIT])


@borrowing_kernel
def friction_torque(drive, speed):
    """Viscous and regularised Coulomb friction on the hub at ``speed``, opposing it (N m)."""
    return drive[VISCOUS] * speed + drive[COULOMB] * math.tanh(speed / drive[SMOOTHING])


@borrowing_kernel
def motor_torque(drive, command, speed):
    """The gearbox's torque on the hub before friction, ``torque_gain (V_sat - Kg km theta')``."""
    return drive[TORQUE_GAIN] * (terminal_voltage(drive, command) - drive[BACK_EMF] * speed)


@borrowing_kernel
def drive_torque(drive, command, speed):
    """The torque on a free hub turning at ``speed`` under the maneuver's output ``command``:
    the drive's law (volts in), or ``command`` itself without a drive (an empty ``drive``)."""
    if drive.shape[0] == 0:
        return command
    return motor_torque(drive, command, speed) - friction_torque(drive, speed)


@borrowing_kernel
def free_hub_torque(drive, kind, t, y, v, mp, shaper, hub):
    """The torque a free hub receives at ``t`` in the state ``(y, y')``: the maneuver's shaped
    command (:func:`hubbeam.core.shaping.shaped_torque`: a controller's law on the hub's angle
    ``y[hub]``, or the shaped open-loop torque or voltage of Eq. 44 and its tables) through the
    drive at the hub's speed ``v[hub]`` (:func:`drive_torque`; without a drive, the command).
    ``hub`` is 0 on a rigid root, the hub angle's index with a compliant one (``hubbeam.core.root``)."""
    return drive_torque(drive, shaped_torque(kind, t, y, v, mp, shaper, hub), v[hub])


@borrowing_kernel
def required_voltage(drive, torque, speed):
    """The voltage (before the limit) that makes the drive deliver ``torque`` to a hub turning at
    ``speed``: the inverse of the law, what a prescribed hub asks of the amplifier."""
    return (torque + friction_torque(drive, speed)) / drive[TORQUE_GAIN] + drive[BACK_EMF] * speed

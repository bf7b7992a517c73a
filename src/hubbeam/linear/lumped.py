"""A single-link flexible arm rig and the two-degree-of-freedom model its courseware builds.

:class:`FlexibleLinkRig` holds the numbers of a rig: the link (length, mass, Young's modulus,
second moment of area, density), the hub (the servo's equivalent inertia, which holds the
reflected rotor, plus the link's clamp), the measured free oscillation of the link on a held hub,
and the drive (:class:`hubbeam.model.drive.DcMotor`). :data:`QUANSER_ROTARY_FLEXIBLE_LINK` is the
Quanser Rotary Flexible Link on the SRV02 servo.

The lumped model (:func:`lumped_model`) is the one of the Quanser courseware (Rotary Flexible
Link workbook, and its script ``setup_flexlink_exp.m`` with ``config_flexgage_exp.m``): the link is
a rigid rod of inertia ``Jl = m L^2 / 3`` about the hub axis, hinged on a torsion spring of
stiffness ``Ks = (2 pi f)^2 Jl`` fitted to the measured free oscillation ``f`` of the link with the
hub held. The coordinates are the hub angle ``theta`` and the link's deflection angle ``alpha``
relative to the hub; Lagrange's equations with ``T = Jeq theta'^2 / 2 + Jl (theta' + alpha')^2 / 2``,
``V = Ks alpha^2 / 2`` and the drive's linear torque ``kV V - c theta'`` on the hub
(:mod:`hubbeam.linear.voltage`) give

    [[Jeq + Jl, Jl], [Jl, Jl]] [theta'', alpha''] + [[c, 0], [0, 0]] [theta', alpha']
        + [[0, 0], [0, Ks]] [theta, alpha] = [kV, 0] V,

with states ``(theta, alpha, theta', alpha')``, the held-hub frequency ``f`` and the free-hub one
``f sqrt((Jeq + Jl) / Jeq)``. :meth:`FlexibleLinkRig.beam` is the same link as an Euler-Bernoulli
beam (``hubbeam.model.parameters.BeamProducts``) for the assumed-modes models.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubbeam.linear.voltage import VOLTAGE, DrivenModel, check_motor, linearised_damping
from hubbeam.model.drive import QUANSER_SRV02, DcMotor
from hubbeam.model.parameters import BeamProducts

#: the lumped model's states: the hub angle, the link's deflection angle, their rates
LUMPED_STATES = ("theta", "alpha", "theta_dot", "alpha_dot")
#: the lumped model's outputs (``statespace.OUTPUTS`` names) and their rows on its states; the tip
#: rows are the rigid rod's, ``v(L) = L alpha`` (small angles)
LUMPED_OUTPUTS = ("hub_angle", "deflection_angle", "hub_speed", "deflection_rate", "tip_deflection", "tip_arc")
#: the measured signal each state of the lumped model is (its gains act on these signals of a beam model)
LUMPED_SIGNALS = dict(zip(LUMPED_STATES, LUMPED_OUTPUTS[:4]))


@dataclass(frozen=True)
class FlexibleLinkRig:
    """A flexible link on a driven hub, every number in SI units (module docstring).

    ``length`` (m) and ``link_mass`` (kg) of the link, ``youngs_modulus`` (Pa),
    ``second_moment`` (m4) and ``density`` (kg m-3) of its section; ``hub_inertia`` the servo's
    equivalent inertia at the load shaft (kg m2, with the reflected rotor), ``clamp_inertia`` the
    link's clamp (kg m2); ``held_frequency`` the measured free oscillation of the link with the hub
    held (Hz); ``motor`` the drive.
    """

    length: float
    link_mass: float
    youngs_modulus: float
    second_moment: float
    density: float
    hub_inertia: float
    clamp_inertia: float
    held_frequency: float
    motor: DcMotor

    def __post_init__(self) -> None:
        for name in ("length", "link_mass", "youngs_modulus", "second_moment", "density", "held_frequency"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} = {value!r}; allowed: a finite number > 0")
        for name in ("hub_inertia", "clamp_inertia"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name} = {value!r}; allowed: a finite number >= 0")
        check_motor(self.motor)

    @property
    def mass_per_length(self) -> float:
        """``rho A = m / L`` from the measured mass, kg m-1."""
        return self.link_mass / self.length

    @property
    def link_inertia(self) -> float:
        """``Jl = m L^2 / 3``: the link as a rigid rod about the hub axis, kg m2."""
        return self.link_mass * self.length**2 / 3.0

    @property
    def hub(self) -> float:
        """``Jeq``: the servo's equivalent inertia plus the clamp's, kg m2."""
        return self.hub_inertia + self.clamp_inertia

    @property
    def spring_stiffness(self) -> float:
        """``Ks = (2 pi f)^2 Jl``: the torsion spring fitted to the held-hub oscillation, N m rad-1."""
        return (2.0 * math.pi * self.held_frequency) ** 2 * self.link_inertia

    @property
    def free_frequency(self) -> float:
        """The lumped model's free-hub frequency without damping, ``f sqrt((Jeq + Jl) / Jeq)``, Hz."""
        return self.held_frequency * math.sqrt((self.hub + self.link_inertia) / self.hub)

    def beam(self) -> BeamProducts:
        """The link as a uniform beam clamped at the hub axis (``rA = 0``): ``rhoA = m / L``,
        ``EI = E I``, ``EA = E rhoA / density``, hub inertia ``Jeq``."""
        rhoA = self.mass_per_length
        return BeamProducts(L=self.length, rhoA=rhoA, EI=self.youngs_modulus * self.second_moment,
                            EA=self.youngs_modulus * rhoA / self.density, Jh=self.hub, rA=0.0)


#: the Quanser Rotary Flexible Link on the SRV02 (high gear): a steel link of 0.419 m and 65 g
#: (Quanser's user manual), ``E = 200 GPa``, ``I = 9.32e-13 m4``, steel's 7850 kg m-3 for the
#: axial stiffness; the SRV02's equivalent inertia 0.00208 kg m2 (with the rotor) and the clamp's
#: 0.0002 kg m2 (``config_servo_exp.m``, load type ``FLEX_LINK``); the link's measured free
#: oscillation of 3 Hz on a held hub (``config_flexgage_exp.m``); the SRV02 drive
QUANSER_ROTARY_FLEXIBLE_LINK = FlexibleLinkRig(length=0.419, link_mass=0.065, youngs_modulus=200e9,
                                               second_moment=9.32e-13, density=7850.0, hub_inertia=0.00208,
                                               clamp_inertia=0.0002, held_frequency=3.0, motor=QUANSER_SRV02)


def lumped_matrices(rig: FlexibleLinkRig, speed: float = 0.0):
    """``(M, C, K, b)`` of the lumped model's second-order equations (module docstring) with the
    drive linearised at the hub ``speed`` (rad s-1; ``hubbeam.linear.voltage.linearised_damping``)."""
    Jl, Jeq = rig.link_inertia, rig.hub
    M = np.array([[Jeq + Jl, Jl], [Jl, Jl]])
    C = np.diag([linearised_damping(rig.motor, speed), 0.0])
    K = np.diag([0.0, rig.spring_stiffness])
    b = np.array([rig.motor.torque_gain, 0.0])
    return M, C, K, b


def lumped_model(rig: FlexibleLinkRig = QUANSER_ROTARY_FLEXIBLE_LINK, outputs=None) -> DrivenModel:
    """The courseware's four-state model of ``rig`` at rest, voltage in (module docstring); outputs a
    name or names among :data:`LUMPED_OUTPUTS` (all by default)."""
    names = LUMPED_OUTPUTS if outputs is None else ((outputs,) if isinstance(outputs, str) else tuple(outputs))
    unknown = [name for name in names if name not in LUMPED_OUTPUTS]
    if unknown or not names:
        raise ValueError(f"outputs = {list(names)!r}; allowed: a non-empty list of {', '.join(LUMPED_OUTPUTS)}")
    M, C, K, b = lumped_matrices(rig)
    solved = np.linalg.solve(M, np.column_stack([-K, -C, b]))
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [solved[:, :4]]])
    B = np.concatenate([np.zeros(2), solved[:, 4]])[:, None]
    L = rig.length
    rows = {"hub_angle": [1.0, 0.0, 0.0, 0.0], "deflection_angle": [0.0, 1.0, 0.0, 0.0],
            "hub_speed": [0.0, 0.0, 1.0, 0.0], "deflection_rate": [0.0, 0.0, 0.0, 1.0],
            "tip_deflection": [0.0, L, 0.0, 0.0], "tip_arc": [L, L, 0.0, 0.0]}
    return DrivenModel(model="lumped", hub="free", speed=0.0, A=A, B=B, C=np.array([rows[name] for name in names]),
                       D=np.zeros((len(names), 1)), states=LUMPED_STATES, inputs=(VOLTAGE,), outputs=names,
                       motor=rig.motor, operating_voltage=0.0, hub_damping=float(C[0, 0]))


__all__ = ["LUMPED_OUTPUTS", "LUMPED_SIGNALS", "LUMPED_STATES", "QUANSER_ROTARY_FLEXIBLE_LINK", "FlexibleLinkRig",
           "lumped_matrices", "lumped_model"]

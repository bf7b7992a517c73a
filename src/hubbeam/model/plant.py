"""The plant: the arm as its cases run it, one record of what the eigen-analysis and the
linearisation need.

A :class:`Plant` holds the beam, the assumed modes (their number and the transverse functions) and
the Gauss nodes of their quadrature, the tip body (mass, position, rotary inertia, offset; a mass of
0 at the tip for none), the compliant root (:class:`~hubbeam.model.root.RootSpring`, None: clamped to
the hub), the hub's drive (:class:`~hubbeam.model.drive.DcMotor`, None: an ideal torque actuator)
and the structural damping. Every case has one (``hubbeam.configuration.settings.Settings``);
cases that share a plant share its products. :func:`plant_matrices` gives its system matrices, the
drive rotor's reflected inertia counted in the hub's: the matrices every product and every run of
the plant reads.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from hubbeam.model.damping import ModalDamping, RayleighDamping, damping_to_dict
from hubbeam.model.drive import DcMotor
from hubbeam.model.matrices import assemble
from hubbeam.model.modes import CLAMPED_FREE
from hubbeam.model.parameters import TipMass
from hubbeam.model.root import RootSpring


@dataclass(frozen=True)
class Plant:
    """The arm as built (module docstring). ``name`` is the plant's readable name in products and
    reports (the first case that uses it); it takes no part in comparing plants."""

    beam: object
    modes: int
    quadrature_points: int
    tip: TipMass
    functions: str = CLAMPED_FREE
    root_spring: RootSpring | None = None
    drive: DcMotor | None = None
    damping: ModalDamping | RayleighDamping | None = None
    name: str = field(default="", compare=False)

    @property
    def has_body(self) -> bool:
        """Whether the tip mass is a body (rotary inertia or offset), not a point."""
        return not self.tip.is_point

    def describe(self) -> dict:
        """What the plant holds, as plain values (a report's table and a dataset's attributes)."""
        tip = self.tip
        plain = {"modes": self.modes, "transverse_functions": self.functions, "tip_mass_kg": tip.mass,
                 "tip_position_m": tip.position, "tip_inertia_kg_m2": tip.inertia, "tip_offset_m": tip.offset}
        plain["root_spring"] = {} if self.root_spring is None else self.root_spring.to_dict()
        plain["drive"] = {} if self.drive is None else self.drive.to_dict()
        plain["damping"] = damping_to_dict(self.damping)
        return plain


def plant_matrices(plant: Plant):
    """The system matrices of ``plant`` (``hubbeam.model.matrices.assemble``: its tip body, modes,
    functions and quadrature), the rotor of its drive reflected into the hub's inertia
    (:func:`with_drive`)."""
    sm = assemble(plant.beam, plant.tip, plant.modes, plant.quadrature_points, plant.functions)
    return with_drive(sm, plant.drive)


def with_drive(sm, motor: DcMotor | None):
    """``sm`` with the rotor's reflected inertia (``DcMotor.reflected_inertia``) added to the hub's
    ``Jh`` (``sm`` itself without a motor, or with a rotor already counted in the hub's inertia)."""
    if motor is None or motor.reflected_inertia == 0.0:
        return sm
    return sm._replace(Jh=float(sm.Jh) + motor.reflected_inertia)

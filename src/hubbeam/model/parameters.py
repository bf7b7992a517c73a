"""Physical parameters of the hub-beam system (Table 1 of the paper) and of the tip mass.

A uniform beam is given either by the paper's factors (:class:`BeamParameters`: density, area,
Young's modulus, second moment of area) or by the products the equations use
(:class:`BeamProducts`: ``rho A``, ``E I``, ``E A``); both are a :class:`UniformBeam`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields

import numpy as np

#: BeamParameters field -> key of the ``beam`` section of the config.
CONFIG_KEYS = {
    "L": "length",
    "rho": "density",
    "A": "area",
    "E": "youngs_modulus",
    "I": "second_moment",
    "Jh": "hub_inertia",
    "rA": "hub_radius",
}
#: BeamProducts field -> key of the ``beam`` section of the config.
PRODUCT_KEYS = {"L": "length", "rhoA": "rhoA", "EI": "EI", "EA": "EA", "Jh": "hub_inertia", "rA": "hub_radius"}


class UniformBeam:
    """What a uniform beam offers (``hubbeam.model.matrices`` uses nothing else), from its length ``L``,
    hub radius ``rA`` and the products ``rhoA``, ``EI``, ``EA`` of a subclass."""

    L: float
    rA: float
    rhoA: float
    EI: float
    EA: float

    @property
    def beam_mass(self) -> float:
        """Mass of the beam, kg."""
        return self.rhoA * self.L

    @property
    def rhoA_ref(self) -> float:
        """Mass per unit length that normalises the admissible functions (``hubbeam.model.modes``)."""
        return self.rhoA

    @property
    def stations(self) -> tuple[float, float]:
        """Abscissae (m) between which the properties are smooth: the two ends."""
        return (0.0, self.L)

    def rhoA_at(self, x):
        """Mass per unit length (kg m-1) at abscissae ``x``: the constant ``rho A``."""
        return np.full(np.shape(x), self.rhoA)

    def EI_at(self, x):
        """Bending stiffness (N m2) at abscissae ``x``: the constant ``E I``."""
        return np.full(np.shape(x), self.EI)

    def EA_at(self, x):
        """Axial stiffness (N) at abscissae ``x``: the constant ``E A``."""
        return np.full(np.shape(x), self.EA)

    def outboard_moment(self, x):
        """``int_x^L rho A (rA + s) ds`` (kg m) at ``x``: the centrifugal tension per ``Omega^2``.

        The weight ``g`` of ``D`` (Eq. 18, order of integration swapped) times ``rho A``.
        """
        x = np.asarray(x, dtype=float)
        return self.rhoA * (self.rA * (self.L - x) + 0.5 * (self.L**2 - x**2))


@dataclass(frozen=True)
class BeamProducts(UniformBeam):
    """Uniform Euler-Bernoulli beam clamped radially to a rigid hub, by its products (SI units).

    ``L`` length (m), ``rhoA`` mass per unit length (kg m-1), ``EI`` bending stiffness (N m2),
    ``EA`` axial stiffness (N), ``Jh`` hub inertia (kg m2), ``rA`` hub radius (m); stored as float.
    """

    L: float
    rhoA: float
    EI: float
    EA: float
    Jh: float
    rA: float

    def __post_init__(self) -> None:
        _store_floats(self)


@dataclass(frozen=True)
class BeamParameters(UniformBeam):
    """Uniform Euler-Bernoulli beam clamped radially to a rigid hub (Table 1, SI units).

    ``L`` length (m), ``rho`` density (kg m-3), ``A`` cross-section area (m2), ``E`` Young's
    modulus (N m-2), ``I`` second moment of area (m4), ``Jh`` hub inertia (kg m2), ``rA`` hub
    radius (m). Values are stored as float and not checked here: user input is checked by
    ``hubbeam.configuration.load``, and the functions that use the parameters check what they rely on.
    """

    L: float
    rho: float
    A: float
    E: float
    I: float  # noqa: E741 (the paper's symbol)
    Jh: float
    rA: float

    def __post_init__(self) -> None:
        _store_floats(self)

    @classmethod
    def from_config(cls, cfg: Mapping) -> BeamParameters:
        """Build from a validated config whose ``beam`` section gives the factors (``density``,
        ``area``, ...); a ``ValueError`` naming the keys otherwise (a beam of any form:
        ``hubbeam.model.beam.beam_from_config(cfg["beam"])``, or ``hubbeam.api.load``)."""
        beam = cfg["beam"]
        missing = [key for key in CONFIG_KEYS.values() if key not in beam]
        if missing:
            raise ValueError(f"beam is missing {', '.join(missing)}: BeamParameters takes a beam by its factors "
                             f"{', '.join(CONFIG_KEYS.values())}; allowed: such a beam, or "
                             "hubbeam.model.beam.beam_from_config(cfg['beam']) for a beam of any form")
        return cls(**{name: beam[key] for name, key in CONFIG_KEYS.items()})

    @property
    def rhoA(self) -> float:
        """Mass per unit length, kg m-1."""
        return self.rho * self.A

    @property
    def EI(self) -> float:
        """Bending stiffness, N m2."""
        return self.E * self.I

    @property
    def EA(self) -> float:
        """Axial stiffness, N."""
        return self.E * self.A


@dataclass(frozen=True)
class TipMass:
    """The body at the beam's end or along it: mass ``mass`` (kg) attached at distance ``position``
    (m) from the clamped root, ``0 <= position <= L``, with rotary inertia ``inertia`` (kg m2)
    about its centre of mass, which lies ``offset`` (m) beyond the attachment point along the
    beam's end tangent there (``docs/tip-body.md``).

    The defaults ``inertia = offset = 0`` give the paper's point tip mass (Section 4.4, Appendix);
    ``inertia`` is the moment of inertia about the axis of the hub (normal to the plane of
    rotation). The body turns with the hub and with the slope ``v'(position)`` of the beam. The
    values are stored as float and checked by :func:`check_tip` where they are used.
    """

    mass: float
    position: float
    inertia: float = 0.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        _store_floats(self)

    @property
    def is_point(self) -> bool:
        """Whether this is the paper's point mass: no rotary inertia, centre at the attachment."""
        return self.inertia == 0.0 and self.offset == 0.0


def check_tip(tip: TipMass, length: float) -> None:
    """``ValueError`` naming the first bad field of ``tip`` on a beam of length ``length`` (m).

    Allowed: a finite ``mass >= 0``, ``0 <= position <= L``, a finite ``inertia >= 0`` and a
    finite ``offset`` that keeps the centre on the beam's side of the clamped root,
    ``position + offset >= 0`` (a centre behind the root would lie inside the hub).
    """
    mass, position, inertia, offset = tip.mass, tip.position, tip.inertia, tip.offset
    if not (math.isfinite(mass) and mass >= 0.0):
        raise ValueError(f"tip_mass.mass = {mass!r}: expected a finite mass >= 0 kg")
    if not (math.isfinite(position) and 0.0 <= position <= length):
        raise ValueError(f"tip_mass.position = {position!r}: expected 0 <= position <= L = {length} m")
    if not (math.isfinite(inertia) and inertia >= 0.0):
        raise ValueError(f"tip_mass.inertia = {inertia!r}: expected a finite rotary inertia >= 0 kg m2 "
                         "about the body's centre")
    if not (math.isfinite(offset) and position + offset >= 0.0):
        raise ValueError(f"tip_mass.offset = {offset!r}: expected a finite offset (m) with position + "
                         f"offset >= 0 (position = {position} m): the body's centre on the beam's side "
                         "of the clamped root")


def _store_floats(instance) -> None:
    for field in fields(instance):
        object.__setattr__(instance, field.name, float(getattr(instance, field.name)))


#: a steel ruler on a servo hub, close to the link of a Quanser rotary flexible link: 0.419 m
#: long, 21.6 mm x 0.79 mm (0.056 kg, first clamped bending mode 3.7 Hz), on the SRV02's hub
#: (its inertia without load, 0.00208 kg m2, ``hubbeam.model.drive.QUANSER_SRV02``) with a 2 cm
#: clamp; the drive's torque of 0.13 N m per volt turns it at a few rad/s
FLEXIBLE_LINK = BeamParameters(L=0.419, rho=7850.0, A=0.0216 * 0.00079, E=200e9, I=0.0216 * 0.00079**3 / 12.0,
                               Jh=0.00208, rA=0.02)

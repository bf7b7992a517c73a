"""A compliant root: a torsional spring and damper between the hub and the beam's root.

Rigs clamp the link to the hub through a bracket, a hub screw or a harmonic drive whose compliance
lowers the measured frequencies below the clamped theory; a flexible-joint arm puts a torsion
spring there on purpose. :class:`RootSpring` states such a root: the stiffness ``k`` (N m rad-1) and
damping ``c`` (N m s rad-1) of a hinge at the beam's root, on the hub at the hub radius ``a = rA``,
and the rotary inertia ``J_c`` (kg m2) of the clamp that turns with the beam's root. The hub's own
inertia ``Jh`` (with a drive's rotor) stays on the motor side, where the hub torque acts. The hub
angle ``phi`` then joins the coordinates, ``y = (theta, q1, q2, phi)``, and ``theta`` is the
root's angle, the angle every output that reads the beam is measured from
(``docs/compliant-root.md``; the kernels' equations: ``hubbeam.core.root``).

This module gives the kernels their inputs (:func:`joint_inputs`: the link's matrices about its
hinge, :func:`link_matrices`, and the packed :class:`~hubbeam.core.inputs.RootJoint`) and the
equations about a steady spin (:func:`joint_second_order`), which the eigen-analysis
(``hubbeam.model.eigen.root_frequencies``) and the linear models (``hubbeam.linear.statespace``)
share.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from hubbeam.core.inputs import NO_ROOT, RootJoint
from hubbeam.model.linearised import axial_stretch, spin_matrices

#: the name of the hub angle among the states (``theta`` is the root's angle)
HUB_COORDINATE = "phi"


@dataclass(frozen=True)
class RootSpring:
    """A torsional spring ``stiffness`` (N m rad-1) and damper ``damping`` (N m s rad-1) between the
    hub and the beam's root, which carries the clamp's rotary inertia ``clamp_inertia`` (kg m2).

    Every value must be finite and ``>= 0`` (a zero stiffness is a pinned root); a ``ValueError``
    names the field, its value and what is allowed. A rigid root is no ``RootSpring`` (None)."""

    stiffness: float
    damping: float = 0.0
    clamp_inertia: float = 0.0

    def __post_init__(self) -> None:
        units = {"stiffness": "N m rad-1", "damping": "N m s rad-1", "clamp_inertia": "kg m2"}
        for field in fields(self):
            value = getattr(self, field.name)
            number = (isinstance(value, (int, float, np.integer, np.floating))
                      and not isinstance(value, bool))
            if not (number and math.isfinite(value) and value >= 0.0):
                raise ValueError(f"root_spring.{field.name} = {value!r}; allowed: a finite number >= 0 "
                                 f"({units[field.name]})")
            object.__setattr__(self, field.name, float(value))

    def to_dict(self) -> dict:
        """The spring as a mapping of its fields (what a dataset records)."""
        return {field.name: getattr(self, field.name) for field in fields(self)}

    def attributes(self) -> dict:
        """Dataset attributes: ``root_stiffness_N_m_rad-1``, ``root_damping_N_m_s_rad-1``,
        ``root_clamp_inertia_kg_m2``."""
        return {"root_stiffness_N_m_rad-1": self.stiffness, "root_damping_N_m_s_rad-1": self.damping,
                "root_clamp_inertia_kg_m2": self.clamp_inertia}


def checked_spring(root_spring) -> RootSpring | None:
    """``root_spring`` if it is a :class:`RootSpring` or None; a ``ValueError`` naming it otherwise."""
    if root_spring is None or isinstance(root_spring, RootSpring):
        return root_spring
    raise ValueError(f"root_spring = {root_spring!r}; allowed: a hubbeam.model.root.RootSpring, or None "
                     "(the rigid root)")


def hinge_levers(sm) -> dict:
    """The point-cloud sums the hinge's terms need, times the hub radius ``a = sm.rA``
    (``hubbeam.core.root``): ``mass`` ``a^2 sum w``, ``moment`` ``a sum w x`` (kg m2), ``p1`` ``a sum
    w f1``, ``p2`` ``a sum w f2`` (kg1/2 m) and ``E`` ``a sum w S`` (1), exactly symmetric."""
    a = float(sm.rA)
    w = np.asarray(sm.w, dtype=float)
    E = np.einsum("k,kij->ij", w, sm.S)
    return {"mass": a * a * float(np.sum(w)), "moment": a * float(w @ sm.x), "p1": a * (w @ sm.F1),
            "p2": a * (w @ sm.F2), "E": a * 0.5 * (E + E.T)}


def link_matrices(sm, spring: RootSpring):
    """The :class:`~hubbeam.model.matrices.SystemMatrices` of the link about its hinge: the beam's
    matrices with the hub radius taken out of the first moments and the inertia (``Jb - a^2 m - 2 a
    s0 = sum w x^2``, ``V1 - p1``, ``V2 - p2``, ``D - E``, ``rA = 0``) and the clamp's inertia in place
    of the hub's, so that every model's equations of them are the link's (``hubbeam.core.root``).
    ``sm`` is assembled with the hub radius (its ``Jh`` the hub's, the motor side)."""
    levers = hinge_levers(sm)
    return sm._replace(Jh=float(spring.clamp_inertia), Jb=float(sm.Jb) - levers["mass"] - 2.0 * levers["moment"],
                       V1=sm.V1 - levers["p1"], V2=sm.V2 - levers["p2"], D=sm.D - levers["E"], rA=0.0)


def joint_inputs(sm, spring: RootSpring | None):
    """What the kernels receive for the root ``spring``: ``(matrices, RootJoint)``; ``sm`` and
    :data:`~hubbeam.core.inputs.NO_ROOT` for the rigid root (None), else the link's matrices about
    its hinge (:func:`link_matrices`) and the packed joint (its hub inertia ``sm.Jh``, the levers of
    :func:`hinge_levers`)."""
    spring = checked_spring(spring)
    if spring is None:
        return sm, NO_ROOT
    levers = hinge_levers(sm)
    scalars = np.array([spring.stiffness, spring.damping, float(sm.Jh), levers["mass"], levers["moment"]])
    joint = RootJoint(scalars, np.ascontiguousarray(levers["p1"], dtype=float),
                      np.ascontiguousarray(levers["p2"], dtype=float), np.ascontiguousarray(levers["E"], dtype=float))
    return link_matrices(sm, spring), joint


def state_names(traits, n: int) -> tuple[str, ...]:
    """The states with a compliant root: the model's coordinates (``theta`` the root's angle), the
    hub angle :data:`HUB_COORDINATE`, then their rates ``*_dot``."""
    coordinates = traits.state_names(n)[:len(traits.state_names(n)) // 2] + (HUB_COORDINATE,)
    return coordinates + tuple(f"{c}_dot" for c in coordinates)


def joint_second_order(sm, spring: RootSpring, traits, speed: float, damping: np.ndarray):
    """``(M, G, C, K, q1s)`` of the equations with the compliant root ``spring`` linearised about the
    steady spin at ``speed``: ``M z'' + (G + C) z' + K z = e_phi tau`` in the deviations ``z =
    (theta, [q1 - q1s], q2, phi)`` (``theta = phi = Omega t`` at the operating point: a straight
    link needs no spring torque).

    The link's block is the model's linearisation of its matrices about the hinge
    (:func:`link_matrices`, ``hubbeam.model.linearised.spin_matrices``) at the stretch ``q1s`` of
    the whole beam (the hinge's centrifugal force ``Omega^2 p1`` completes ``Omega^2 (V1 - p1)``).
    The hinge (``hubbeam.core.root``) linearised at ``alpha = phi - theta = 0``, ``q2 = 0``, with
    the lever ``h = a s0 + p1 . q1s``:

    * ``M``: ``J_h + a^2 m`` on the hub, ``h`` between hub and root, ``p2`` between hub and ``q2``;
    * ``K``: the lag stiffness ``k + Omega^2 h`` on ``alpha`` (the spring and the centrifugal force
      on the link's first moment about the hinge), ``Omega^2 p2`` between ``alpha`` and ``q2``
      (signs as ``alpha``), ``Omega^2 E`` on ``q2`` (with the link's ``K22`` the whole beam's);
    * ``G``: ``-2 Omega p1`` on the ``q1`` rows from the hub rate, ``2 Omega p1`` on the hub row from
      the ``q1`` rates (the hinge's Coriolis torque; deleted in SFOAM, which has no ``q1``);
    * ``C``: the damper ``c`` on ``alpha``.

    ``damping`` the ``(2, n, n)`` matrices ``[C1, C2]``; ``traits`` a ``hubbeam.model.models.Model``.
    """
    n = sm.M2.shape[0]
    levers = hinge_levers(sm)
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(n)
    link = spin_matrices(link_matrices(sm, spring), traits, speed, damping, q1s)
    N = link[0].shape[0] + 1
    M, G, C, K = (np.zeros((N, N)) for _ in range(4))
    for big, small in zip((M, G, C, K), link):
        big[:-1, :-1] = small
    q2 = slice(N - 1 - n, N - 1)
    lever = levers["moment"] + levers["p1"] @ q1s
    w2 = speed**2
    M[-1, -1] = float(sm.Jh) + levers["mass"]
    M[0, -1] = M[-1, 0] = lever
    M[-1, q2] = M[q2, -1] = levers["p2"]
    lag = np.array([[1.0, -1.0], [-1.0, 1.0]])
    ends = np.ix_([0, N - 1], [0, N - 1])
    K[ends] += (spring.stiffness + w2 * lever) * lag
    C[ends] += spring.damping * lag
    for row, sign in ((0, 1.0), (N - 1, -1.0)):
        K[row, q2] += sign * w2 * levers["p2"]
        K[q2, row] += sign * w2 * levers["p2"]
    c_S = 1.0 if traits.softening_terms else 0.0
    K[q2, q2] += w2 * c_S * levers["E"]
    if traits.keeps_axial:
        G[1:1 + n, -1] = -2.0 * speed * levers["p1"]
        if traits.hub_velocity_force:
            G[-1, 1:1 + n] = 2.0 * speed * levers["p1"]
    return M, G, C, K, q1s

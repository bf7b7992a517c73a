"""Linear state-space models of TLAM, FOAM, SFOAM and CFOAM about a steady spin (assembled route).

Operating point: the hub spins at ``theta_dot = Omega`` under zero torque, the axial coordinates
sit at their centrifugal stretch ``q1s = Omega^2 (K1 - Omega^2 M1)^-1 V1`` (models that keep
``q1``), ``q2 = 0``. Every model's equations of motion (Eq. 24 with Eqs. 25-34; Eq. 40 for SFOAM;
the exact kinetic energy for CFOAM) linearised about it give, in the deviations
``z = (theta, [q1 - q1s], q2)`` of the coordinates from the steady spin,

    M z'' + (G + C) z' + K z = b u,

with (``p = V1 + M1 q1s``; derivation in ``docs/linear-models.md``)

* ``M``: ``M_thth = Jh + Jb + 2 V1 q1s + q1s^T M1 q1s`` (Eq. 25 at the operating point),
  ``M_thq1 = 0``, ``M_thq2 = V2 + R^T q1s`` (Eq. 27), ``diag(M1, M2)`` below, and a tip body's
  rotary inertia ``Jt``, ``Jt g``, ``Jt g^T g`` on the hub, hub-``q2`` and ``q2`` entries
  (``g = f2'(l)``, ``core.system_matrices.rotary_mass``, ``docs/tip-body.md``);
* ``G``: Eq. (29) in the elastic block and the hub couplings ``G_thq1 = 2 Omega p^T`` (``Q_theta``
  of Eq. 32 linearised; deleted with it in SFOAM) and ``G_q1th = -2 Omega p`` (the centrifugal
  force ``theta_dot^2 p`` of Eq. 33 linearised in the hub speed): skew-symmetric;
* ``K``: Eqs. (30)-(31), zero hub row and column (theta is cyclic); CFOAM adds
  ``Omega^2 E(q1s)``, ``E = sum_k w_k (f1(x_k) q1s) S(x_k)``, to ``K22``: the stretch moves the
  mass outward, which scales its foreshortening term (the one high-order term of first order);
* ``C``: the damping matrices ``diag(0, C1, C2)`` of ``hubbeam.model.damping`` (elastic coordinates
  only, so the steady spin still needs no torque).

Free hub: the input is the hub torque, ``b = e_theta``. Prescribed hub: the input is the hub's
angular acceleration ``theta'' = u``; ``theta`` and ``theta_dot`` stay states (integrators of the
input), because a change of hub speed changes the centrifugal force on ``q1`` (``G_q1th``).
States ``x = (z, z')``, ``x' = A x + B u``, ``y = C x + D u``.

With a compliant root (``root_spring``, ``hubbeam.model.root``; ``docs/compliant-root.md``) the hub
angle ``phi`` is appended, ``z = (theta, [q1 - q1s], q2, phi)``, ``theta`` the beam's root angle;
``M, G, C, K`` are ``hubbeam.model.root.joint_second_order``'s, the input acts on the hub (``b =
e_phi``, or ``phi'' = u``), ``hub_angle`` and ``hub_speed`` are the hub's, and the outputs
``root_angle``, ``root_speed`` and ``spring_torque`` (:data:`ROOT_OUTPUTS`) join.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hubbeam.configuration.settings import damping_settings
from hubbeam.model.damping import damping_matrices
from hubbeam.model.linearised import axial_stretch, spin_matrices
from hubbeam.model.matrices import assemble, functions_load
from hubbeam.model.models import model as model_traits
from hubbeam.model.modes import transverse_modes
from hubbeam.model.root import RootSpring, checked_spring, joint_second_order, state_names

#: hub conditions -> name of the input
HUBS = {"free": "hub_torque", "prescribed": "hub_acceleration"}
#: outputs -> units (UDUNITS) and long name
OUTPUTS = {
    "hub_angle": ("rad", "hub angle from the steady spin theta - Omega t"),
    "hub_speed": ("rad s-1", "hub speed from the steady spin theta_dot - Omega"),
    "tip_deflection": ("m", "transverse tip deflection v(L) = f2(L) q2"),
    "tip_arc": ("m", "arc position of the tip (rA + L) theta + v(L)"),
    "root_moment": ("N m", "root bending moment EI(0) v''(0)"),
    "tip_acceleration": ("m s-2", "transverse inertial acceleration of the beam tip"),
    "deflection_angle": ("rad", "link deflection angle alpha = v(L) / L (a root strain gauge's reading)"),
    "deflection_rate": ("rad s-1", "rate of the link deflection angle v'(L) / L"),
}
#: outputs of a model with a compliant root only (``hub_angle``, ``hub_speed`` are then the hub's,
#: the motor side) -> units and long name
ROOT_OUTPUTS = {
    "root_angle": ("rad", "beam root angle from the steady spin theta - Omega t"),
    "root_speed": ("rad s-1", "beam root speed from the steady spin theta_dot - Omega"),
    "spring_torque": ("N m", "torque of the root's spring and damper on the link k (phi - theta) + c (phi' - "
                             "theta')"),
}
#: units of the inputs (``voltage``: the drive's input, ``hubbeam.linear.voltage``)
INPUT_UNITS = {"hub_torque": "N m", "hub_acceleration": "rad s-2", "voltage": "V"}


@dataclass(frozen=True, eq=False)
class LinearModel:
    """``x' = A x + B u``, ``y = C x + D u`` of ``model`` about the steady spin at ``speed``.

    The states are deviations from the operating point (module docstring), named in ``states``;
    ``inputs`` is ``("hub_torque",)`` (free hub) or ``("hub_acceleration",)`` (prescribed hub).
    """

    model: str
    hub: str
    speed: float
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: tuple[str, ...]
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    root_spring: RootSpring | None = None

    @property
    def name(self) -> str:
        """``<model>_<hub>_hub_<speed>rad_s`` (``p`` for the decimal point, which python-control
        does not allow in a name; ``_root`` appended with a compliant root), the name of the
        python-control system."""
        speed = f"{self.speed:.10g}".replace(".", "p").replace("+", "")
        return f"{self.model}_{self.hub}_hub_{speed}rad_s" + ("" if self.root_spring is None else "_root")

    def to_control(self):
        """The model as a :class:`control.StateSpace` with its named states, inputs, outputs."""
        import control as ct

        return ct.ss(self.A, self.B, self.C, self.D, states=list(self.states),
                     inputs=list(self.inputs), outputs=list(self.outputs), name=self.name)


def check_request(model: str, hub: str, outputs, joint: bool = False) -> tuple:
    """The model's traits and the output names, after checking every argument by name (with a
    compliant root, ``joint``, :data:`ROOT_OUTPUTS` are allowed and among the default ones)."""
    traits = model_traits(model)
    if hub not in HUBS:
        raise ValueError(f"hub = {hub!r}; allowed: one of {', '.join(HUBS)}")
    allowed = OUTPUTS | (ROOT_OUTPUTS if joint else {})
    names = tuple(allowed) if outputs is None else (
        (outputs,) if isinstance(outputs, str) else tuple(outputs))
    unknown = [name for name in names if name not in allowed]
    if unknown or not names:
        raise ValueError(f"outputs = {list(names)!r}; allowed: a non-empty list of "
                         f"{', '.join(allowed)}" + ("" if joint else f" ({', '.join(ROOT_OUTPUTS)} with a "
                                                                    "root_spring only)"))
    return traits, names


def check_speed(speed) -> float:
    """``speed`` as a float; ``ValueError`` unless it is a finite number >= 0 (rad s-1)."""
    number = (isinstance(speed, (int, float, np.integer, np.floating))
              and not isinstance(speed, bool))
    if not (number and math.isfinite(speed) and speed >= 0.0):
        raise ValueError(f"speed = {speed!r}; allowed: a finite hub speed >= 0 rad s-1")
    return float(speed)


def check_speeds(speeds) -> np.ndarray:
    """The grid ``speeds`` as floats; ``ValueError`` unless a non-empty, strictly increasing list
    of hub speeds, each finite and >= 0 rad s-1 (the message names the first bad entry)."""
    allowed = ("allowed: a non-empty, strictly increasing list of hub speeds, each finite and "
               ">= 0 rad s-1")
    values = np.asarray(speeds).tolist() if np.ndim(speeds) == 1 else []
    if not values:
        raise ValueError(f"speeds = {speeds!r}; {allowed}")
    for k, speed in enumerate(values):
        try:
            check_speed(speed)
        except ValueError:
            raise ValueError(f"speeds[{k}] = {speed!r}; {allowed}") from None
        if k and not speed > values[k - 1]:
            raise ValueError(f"speeds[{k}] = {speed!r} after {values[k - 1]!r}; {allowed}")
    return np.array(values, dtype=float)


def checked_damping(damping, n: int) -> np.ndarray:
    """``damping`` as ``(2, n, n)`` floats (zeros for None); ``ValueError`` unless usable."""
    if damping is None:
        return np.zeros((2, n, n))
    C = np.asarray(damping, dtype=float)
    if C.shape != (2, n, n) or not np.all(np.isfinite(C)):
        raise ValueError(f"damping of shape {C.shape}; allowed: the finite (2, {n}, {n}) "
                         "matrices [C1, C2] of hubbeam.model.damping.damping_matrices")
    return C


def second_order(sm, traits, speed: float, damping=None):
    """``(M, G, C, K, q1s)`` of ``M z'' + (G + C) z' + K z = e_theta tau`` (module docstring;
    ``hubbeam.model.linearised.spin_matrices``)."""
    n = sm.M2.shape[0]
    Cd = checked_damping(damping, n)
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(n)
    return (*spin_matrices(sm, traits, speed, Cd, q1s), q1s)


def accelerations(M, G, C, K, hub: str, index: int = 0):
    """``(Az, Av, Bu)`` of the accelerations ``z'' = Az z + Av z' + Bu u`` for the hub condition,
    the hub's angle the coordinate ``index`` of ``z`` (0; the last with a compliant root).

    Free hub: ``M z'' = -K z - (G + C) z' + e_hub tau``. Prescribed hub: ``z_hub'' = u`` and the
    other rows ``M_rr z_r'' = -K_r z - (G + C)_r z' - M_r,hub u``.
    """
    N = M.shape[0]
    E = G + C
    if hub == "free":
        Az, Av, Bu = np.split(np.linalg.solve(M, np.hstack([-K, -E, np.eye(N)[:, index:index + 1]])),
                              [N, 2 * N], axis=1)
        return Az, Av, Bu
    Az, Av, Bu = np.zeros((N, N)), np.zeros((N, N)), np.zeros((N, 1))
    Bu[index, 0] = 1.0
    rest = np.delete(np.arange(N), index)
    solved = np.linalg.solve(M[np.ix_(rest, rest)], np.hstack([-K[rest], -E[rest], -M[rest, index:index + 1]]))
    Az[rest], Av[rest], Bu[rest] = np.split(solved, [N, 2 * N], axis=1)
    return Az, Av, Bu


def check_matrices(beam, sm) -> None:
    """``ValueError`` unless ``sm`` was assembled for ``beam`` (its hub radius and tip modes, in
    either transverse functions, ``hubbeam.model.matrices.functions_load``)."""
    if float(sm.rA) != float(beam.rA):
        raise ValueError("sm: system matrices assembled for another beam; allowed: "
                         "hubbeam.model.matrices.assemble(beam, tip, n_modes) of this beam")
    functions_load(beam, sm)


@dataclass(frozen=True)
class RowContext:
    """What the output rows need: the length ``N`` of ``z``, the slices of ``q1`` and ``q2`` in it,
    the beam, its matrices, the model's traits, the speed, the axial stretch ``q1s``, where the
    hub's angle is in ``z`` (``hub``: 0, the last with a compliant root) and the root spring."""

    N: int
    q1: slice
    q2: slice
    beam: object
    sm: object
    traits: object
    speed: float
    q1s: np.ndarray
    hub: int = 0
    root_spring: RootSpring | None = None


def _hub_angle(c: RowContext, z, v, a) -> None:
    z[c.hub] = 1.0


def _hub_speed(c: RowContext, z, v, a) -> None:
    v[c.hub] = 1.0


def _root_angle(c: RowContext, z, v, a) -> None:
    z[0] = 1.0


def _root_speed(c: RowContext, z, v, a) -> None:
    v[0] = 1.0


def _spring_torque(c: RowContext, z, v, a) -> None:
    z[c.hub], z[0] = c.root_spring.stiffness, -c.root_spring.stiffness
    v[c.hub], v[0] = c.root_spring.damping, -c.root_spring.damping


def _tip_deflection(c: RowContext, z, v, a) -> None:
    z[c.q2] = c.sm.f2L


def _tip_arc(c: RowContext, z, v, a) -> None:
    z[0], z[c.q2] = c.sm.rA + c.beam.L, c.sm.f2L
    if c.hub:  # the root's hinge on the hub's radius, the beam turning about it
        z[0], z[c.hub] = c.beam.L, c.sm.rA


def _root_moment(c: RowContext, z, v, a) -> None:
    n = c.sm.M2.shape[0]
    load = functions_load(c.beam, c.sm)
    z[c.q2] = float(c.beam.EI_at(0.0)) * transverse_modes(0.0, n, c.beam, derivative=2, load=load)[0]


def _tip_acceleration(c: RowContext, z, v, a) -> None:
    a[0] = c.sm.rA + c.beam.L + c.sm.f1L @ c.q1s
    a[c.q2] = c.sm.f2L
    z[c.q2] = -c.speed**2 * c.sm.f2L
    if c.traits.keeps_axial:
        v[c.q1] = 2.0 * c.speed * c.sm.f1L
    if c.hub:  # the hinge's acceleration across the beam, rA (phi'' - Omega^2 (phi - theta))
        a[0] -= c.sm.rA
        a[c.hub] = c.sm.rA
        z[c.hub] = -c.speed**2 * c.sm.rA
        z[0] = c.speed**2 * c.sm.rA


def _deflection_angle(c: RowContext, z, v, a) -> None:
    z[c.q2] = c.sm.f2L / c.beam.L


def _deflection_rate(c: RowContext, z, v, a) -> None:
    v[c.q2] = c.sm.f2L / c.beam.L


#: output name -> the function filling its rows ``(z, v, a)`` (one per name of :data:`OUTPUTS` and
#: :data:`ROOT_OUTPUTS`)
ROW_BUILDERS = {
    "hub_angle": _hub_angle,
    "hub_speed": _hub_speed,
    "tip_deflection": _tip_deflection,
    "tip_arc": _tip_arc,
    "root_moment": _root_moment,
    "tip_acceleration": _tip_acceleration,
    "deflection_angle": _deflection_angle,
    "deflection_rate": _deflection_rate,
    "root_angle": _root_angle,
    "root_speed": _root_speed,
    "spring_torque": _spring_torque,
}


def output_rows(beam, sm, traits, speed: float, q1s, names, root_spring: RootSpring | None = None):
    """``(Cz, Cv, Ca)``: each output is ``Cz z + Cv z' + Ca z''`` (rows in the order of ``names``).

    Each name's rows come from its builder in :data:`ROW_BUILDERS`; an unknown name is a
    ``ValueError``. The tip's transverse acceleration in the rotating frame is ``a_y = v'' +
    2 theta' u' + theta'' (rA + L + u) - theta'^2 v`` at ``x = L``, linearised about the steady
    spin: ``f2(L) q2'' + 2 Omega f1(L) q1' + (rA + L + f1(L) q1s) theta'' - Omega^2 f2(L) q2``
    (``u = f1 q1``; the foreshortening part of the axial displacement is of second order). The
    link deflection angle is ``alpha = v(L) / L`` (the rotation of the chord from the clamp to the
    tip relative to the hub, what the Quanser courseware calls ``alpha``), its rate ``v'(L) / L``.

    With a compliant root (``root_spring``; ``z = (theta, [q1], q2, phi)``) the hub's outputs read
    ``phi``, the root's ``theta``, the spring's torque is ``k (phi - theta) + c (phi' - theta')``, the
    tip's arc ``rA phi + L theta + v(L)`` and its acceleration gains the hinge's, ``rA (phi'' -
    Omega^2 (phi - theta))``, in place of ``rA theta''`` (the hinge on the hub's radius, the beam
    turning about it).
    """
    unknown = [name for name in names if name not in ROW_BUILDERS]
    if unknown:
        raise ValueError(f"outputs = {list(names)!r}: {unknown[0]!r} is unknown; allowed: names among "
                         f"{', '.join(ROW_BUILDERS)}")
    n = sm.M2.shape[0]
    N = 1 + (2 if traits.keeps_axial else 1) * n
    hub = 0
    if root_spring is not None:
        hub = N
        N += 1
    elif any(name in ROOT_OUTPUTS for name in names):
        raise ValueError(f"outputs = {list(names)!r}: {', '.join(ROOT_OUTPUTS)} are a compliant root's; "
                         "allowed with a root_spring only")
    q2 = slice(N - n - (1 if hub else 0), N - (1 if hub else 0))
    context = RowContext(N=N, q1=slice(1, 1 + n), q2=q2, beam=beam, sm=sm, traits=traits,
                         speed=speed, q1s=q1s, hub=hub, root_spring=root_spring)
    rows = {name: (np.zeros(N), np.zeros(N), np.zeros(N)) for name in names}
    for name, (z, v, a) in rows.items():
        ROW_BUILDERS[name](context, z, v, a)
    return tuple(np.array([rows[name][k] for name in names]) for k in range(3))


def linear_model(beam, sm, model: str, speed: float, hub: str = "free", damping=None,
                 outputs=None, root_spring: RootSpring | None = None) -> LinearModel:
    """The :class:`LinearModel` of ``model`` about the steady spin at ``speed`` (rad s-1).

    ``beam`` (``BeamParameters`` or ``BeamSections``) and ``sm`` (``hubbeam.model.matrices.assemble``
    of it, with the tip mass as configured); ``hub``: ``"free"`` (input hub torque) or
    ``"prescribed"`` (input hub angular acceleration); ``damping``: the ``(2, n, n)`` matrices of
    ``hubbeam.model.damping.damping_matrices`` or None; ``outputs``: a name or a list of names of
    :data:`OUTPUTS` (all by default); ``root_spring``: a compliant root
    (:class:`hubbeam.model.root.RootSpring`; module docstring) or None, the beam clamped to the hub.
    Every argument is checked before anything is computed. A TLAM operating point
    above its critical speed is a valid, unstable plant.
    """
    root_spring = checked_spring(root_spring)
    traits, names = check_request(model, hub, outputs, root_spring is not None)
    speed = check_speed(speed)
    check_matrices(beam, sm)
    M, G, C, K, q1s, index = spin_equations(sm, traits, speed, damping, root_spring)
    return state_space(beam, sm, traits, hub, speed, names, q1s, accelerations(M, G, C, K, hub, index), root_spring)


def spin_equations(sm, traits, speed: float, damping=None, root_spring: RootSpring | None = None):
    """``(M, G, C, K, q1s, index)``: the equations about the steady spin at ``speed`` of the beam
    clamped to the hub (:func:`second_order`) or on the compliant root ``root_spring``
    (``hubbeam.model.root.joint_second_order``), and where the hub's angle is in ``z`` (0, or the
    last coordinate with a root spring)."""
    if root_spring is None:
        return (*second_order(sm, traits, speed, damping), 0)
    M, G, C, K, q1s = joint_second_order(sm, root_spring, traits, speed, checked_damping(damping, sm.M2.shape[0]))
    return M, G, C, K, q1s, M.shape[0] - 1


def model_states(traits, n: int, root_spring: RootSpring | None = None) -> tuple[str, ...]:
    """The state names of ``traits``'s model with ``n`` modes, with a root spring's hub angle
    (``hubbeam.model.root.state_names``)."""
    return traits.state_names(n) if root_spring is None else state_names(traits, n)


def state_space_matrices(beam, sm, traits, speed, names, q1s, rates, root_spring: RootSpring | None = None):
    """``(A, B, C, D)`` from the accelerations ``rates = (Az, Av, Bu)`` of either route
    (``z'' = Az z + Av z' + Bu u``) and the output rows of :func:`output_rows`."""
    Az, Av, Bu = rates
    N = Az.shape[0]
    A = np.block([[np.zeros((N, N)), np.eye(N)], [Az, Av]])
    B = np.vstack([np.zeros((N, 1)), Bu])
    Cz, Cv, Ca = output_rows(beam, sm, traits, speed, q1s, names, root_spring)
    return A, B, np.hstack([Cz + Ca @ Az, Cv + Ca @ Av]), Ca @ Bu


def state_space(beam, sm, traits, hub, speed, names, q1s, rates, root_spring: RootSpring | None = None) -> LinearModel:
    """The :class:`LinearModel` of :func:`state_space_matrices` with the input of the hub condition
    (and the states of a compliant root, ``hubbeam.model.root.state_names``)."""
    A, B, C, D = state_space_matrices(beam, sm, traits, speed, names, q1s, rates, root_spring)
    return LinearModel(model=traits.name, hub=hub, speed=speed, A=A, B=B, C=C, D=D,
                       states=model_states(traits, sm.M2.shape[0], root_spring), inputs=(HUBS[hub],), outputs=names,
                       root_spring=root_spring)


def plant(beam, model: str, speed: float, hub: str = "free", tip=None, n_modes: int = 5,
          damping=None, outputs=None, n_quad: int = 64, root_spring: RootSpring | None = None):
    """The python-control ``StateSpace`` of ``model`` for a case's beam, tip mass and damping.

    ``tip``: a ``TipMass`` or None; ``damping``: a case's ``damping`` mapping
    (``hubbeam.model.damping``) or None; ``n_modes`` and ``n_quad`` as in
    :func:`hubbeam.model.matrices.assemble`. The other arguments as :func:`linear_model`; all are checked
    before the matrices are assembled.
    """
    root_spring = checked_spring(root_spring)
    check_request(model, hub, outputs, root_spring is not None)
    check_speed(speed)
    damping = damping_settings(damping)
    sm = assemble(beam, tip, n_modes, n_quad)
    return linear_model(beam, sm, model, speed, hub, damping_matrices(damping, sm),
                        outputs, root_spring).to_control()

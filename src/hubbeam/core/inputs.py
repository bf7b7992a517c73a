"""The values the kernels receive, as numba-friendly named tuples (importable without numba).

* :class:`ModelTraits`: what a model computes, as flags the kernels branch on (built from the one
  table of models, ``hubbeam.model.models``, which the core does not import);
* :class:`SimulationInputs`: the problem of one simulation (model traits, maneuver, damping,
  system matrices, drive, command shaper, compliant root);
* :class:`RootJoint`: a torsional spring and damper between the hub and the beam's root
  (:mod:`hubbeam.core.root`);
* :class:`IntegratorSettings`: tolerances, the watched tip limit and the step budget of
  :func:`hubbeam.core.radau.radau5`;
* :class:`State` and :class:`Trajectory`: a state of ``y = (theta, q1, q2)`` and the dense
  output of the integrated coordinates on a time grid;
* :class:`LoopArrays` (:class:`LoopMatrices`, :class:`LoopSensors`, :class:`LoopTiming`,
  :class:`SampleRecords`): a sampled digital controller around the hub
  (:mod:`hubbeam.core.sampled`).

Grouping them keeps every kernel entry point at a handful of arguments, where numba would not
notice two swapped floats among a dozen.
"""

from typing import NamedTuple

import numpy as np

from hubbeam.core.system_matrices import SystemMatrices

#: the hub without a drive, an ideal torque actuator (``hubbeam.core.drive``): the maneuver's output
#: is the hub torque
NO_DRIVE = np.zeros(0)


class ModelTraits(NamedTuple):
    """What the equations of a model keep (Section 3; ``hubbeam.model.models`` states them per model)."""

    keeps_axial: bool  # q1 integrated (SFOAM holds q1 = 0, Eq. 40)
    softening_terms: bool  # the underlined D terms of Eqs. (25), (31), (32) (all but TLAM)
    hub_velocity_force: bool  # Q_theta of Eq. (32) acts on the hub (SFOAM deletes it, Eq. 40)
    exact_kinetic_energy: bool  # the exact kinetic energy of Eqs. (8)-(9) (CFOAM)


#: the compiled kernel families: the constant modal mass inverted once, or the exact kinetic energy
FAMILIES = ("foam", "cfoam")


def family(traits: ModelTraits) -> str:
    """The kernel family (:data:`FAMILIES`) that integrates a model with ``traits``."""
    return FAMILIES[int(traits.exact_kinetic_energy)]


#: the identity command shaper: one impulse of amplitude 1 at t = 0 (``hubbeam.core.shaping``;
#: writable, as every shaper the kernels receive, so that numba compiles one kernel for all; never
#: written)
IDENTITY_SHAPER = np.array([[0.0], [1.0]])


class RootJoint(NamedTuple):
    """A torsional spring and damper between the hub and the beam's root, as the kernels receive
    it (:mod:`hubbeam.core.root`; built by ``hubbeam.model.root.joint_inputs``): ``scalars`` the
    stiffness ``k`` (N m rad-1), the damping ``c`` (N m s rad-1), the hub's own inertia ``J_h``
    (kg m2, the motor side), ``a^2 m`` (kg m2) and ``a s0`` (kg m2); the hinge's levers ``p1 = a
    sum w f1``, ``p2 = a sum w f2`` (n,) and ``Ea = a sum w S`` (n, n) over the point cloud, ``a``
    the hub radius. Empty arrays (:data:`NO_ROOT`) are the rigid root."""

    scalars: np.ndarray
    p1: np.ndarray
    p2: np.ndarray
    Ea: np.ndarray


#: the rigid root: the beam clamped to the hub, ``y = (theta, q1, q2)`` (no floating-point operation
#: of a run changes)
NO_ROOT = RootJoint(np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((0, 0)))


class SimulationInputs(NamedTuple):
    """The problem of one simulation: model, maneuver (``hubbeam.core.maneuver``), damping
    matrices ``C = [C1, C2]`` (``eom.add_damping``), system matrices, the hub's packed DC drive
    ``drive`` (``hubbeam.core.drive``; empty, the default: an ideal torque actuator), the command
    shaper (``hubbeam.core.shaping``: impulse times in row 0, amplitudes in row 1; default the
    identity, which leaves the maneuver unshaped) and the compliant root ``root``
    (:class:`RootJoint`; default :data:`NO_ROOT`, the beam clamped to the hub; with a joint ``sm``
    holds the link's matrices about its hinge, ``hubbeam.model.root.joint_inputs``)."""

    traits: ModelTraits
    kind: int
    mp: np.ndarray
    C: np.ndarray
    sm: SystemMatrices
    drive: np.ndarray = NO_DRIVE
    shaper: np.ndarray = IDENTITY_SHAPER
    root: RootJoint = NO_ROOT


class IntegratorSettings(NamedTuple):
    """Settings of :func:`hubbeam.core.radau.radau5`.

    ``rtol`` and ``atol`` apply to every integrated position and velocity; the run stops (status
    ``left_range``) after the first step with ``|watch . y| > tip_limit``; ``max_steps`` is the
    budget of attempted steps; ``first_step`` the first step size (``<= 0``: automatic) and
    ``fixed_step`` turns the error control off (convergence studies)."""

    rtol: float
    atol: float
    tip_limit: float
    max_steps: int
    first_step: float = 0.0
    fixed_step: bool = False


class State(NamedTuple):
    """Positions and velocities of ``y = (theta, q1, q2)`` (``(theta, q1, q2, phi)`` with a compliant
    root), or of the integrated coordinates."""

    y: np.ndarray
    v: np.ndarray


class Trajectory(NamedTuple):
    """Output times ``t`` and the positions ``y`` and velocities ``v`` there, shape
    ``(len(t), N)``."""

    t: np.ndarray
    y: np.ndarray
    v: np.ndarray


class LoopMatrices(NamedTuple):
    """The controller of a sampled loop (``docs/sampled-control.md``): ``xhat_k = E xc_k + F e_k``,
    ``u_cmd_k = U_r . rho_k - K . xhat_k``, ``xc_{k+1} = Ac xc_k + Bc e_k + Bu (u_k - U_r .
    rho_k)`` with ``e_k = m_k - R_m rho_k``; shapes ``Ac (nc, nc)``, ``Bc (nc, p)``, ``Bu (nc,)``,
    ``E (ns, nc)``, ``F (ns, p)``, ``K (ns,)``, ``R_m (p, 3)``, ``U_r (3,)``, ``xc0 (nc,)``."""

    Ac: np.ndarray
    Bc: np.ndarray
    Bu: np.ndarray
    E: np.ndarray
    F: np.ndarray
    K: np.ndarray
    R_m: np.ndarray
    U_r: np.ndarray
    xc0: np.ndarray


class LoopSensors(NamedTuple):
    """The ``p`` sensors of a sampled loop: ``s_j = gain_j (rows_j . (y_f, v_f)) + offset_j`` on
    the integrated coordinates and rates, an analog low-pass of time constant ``tau_j`` (0: none),
    the noise ``sigma_j noise[k, j]`` (``noise``: standard normal, ``(n_samples, p)``), the
    quantum ``quantum_j`` (0: none) and the quantisation ``mode_j`` (``sampled.ROUND`` or
    ``sampled.EDGES``)."""

    rows: np.ndarray
    gain: np.ndarray
    offset: np.ndarray
    sigma: np.ndarray
    tau: np.ndarray
    quantum: np.ndarray
    mode: np.ndarray
    noise: np.ndarray


class LoopTiming(NamedTuple):
    """When a sampled loop acts: the sample times ``t_k = k Ts``, the times ``(k + D) Ts`` at which
    the command of sample ``k`` reaches the plant (both ``(n_samples,)``) and the saturation
    ``u_max`` of the command."""

    sample_times: np.ndarray
    switch_times: np.ndarray
    u_max: float


class SampleRecords(NamedTuple):
    """What a sampled loop records per sample (caller-allocated, NaN where not reached): the time
    ``t`` (n,), the measurements ``measured`` (n, p), the noise-free sensor values ``sensed``
    (n, p), the estimate ``estimate`` (n, ns), the law's command ``command`` and the applied,
    saturated ``applied`` (n,)."""

    t: np.ndarray
    measured: np.ndarray
    sensed: np.ndarray
    estimate: np.ndarray
    command: np.ndarray
    applied: np.ndarray


class LoopArrays(NamedTuple):
    """A sampled digital controller around the hub: :class:`LoopMatrices`, :class:`LoopSensors`,
    :class:`LoopTiming`, the reference packed as ``[kind, parameters...]`` (a ``PD`` maneuver's
    reference, ``hubbeam.core.maneuver``), the :class:`SampleRecords` it writes and the command
    shaper of its reference (``hubbeam.core.shaping``; the identity leaves it unshaped)."""

    matrices: LoopMatrices
    sensors: LoopSensors
    timing: LoopTiming
    reference: np.ndarray
    records: SampleRecords
    shaper: np.ndarray

"""The integrator's right-hand side of CFOAM, from the pre-contracted point-cloud tensors.

CFOAM's mass matrix depends on the whole configuration (Eqs. 8-9 and the high-order terms of
Eqs. 35-39, ``docs/cfoam.md``), so every evaluation assembles ``M(y)`` and ``F(y, y')`` --
with :func:`hubbeam.core.cfoam_tensors.cfoam_system`, which contracts the state with tensors
summed over the point cloud once per simulation instead of summing over the cloud at every
call -- and solves Eq. (24) for the free accelerations by a Cholesky factorisation: the elastic
block with the prescribed ``theta_ddot`` moved to the right-hand side (Eq. 43, a speed table),
or the whole system for a free hub (Eq. 44, a torque table, PD, state feedback or a held input,
through the hub's drive if it has one); the damping forces of
the elastic coordinates (``C``, :func:`hubbeam.core.eom.add_damping`) join the force. These are
the equations :func:`hubbeam.core.eom.accelerations` solves with the point-cloud kernel; the tests
hold the two to rounding error.

With a compliant root (``hubbeam.core.root``) the tensors are the link's about its hinge and the
joint's terms (``hubbeam.core.root.add_joint``) join ``M`` and ``F`` of ``(theta, q1, q2, phi)``;
theta is always integrated, the hub angle phi unless the maneuver prescribes it; one right-hand
side (:func:`cfoam_rhs`) serves both roots.
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.cfoam_tensors import cfoam_system, cfoam_tensors
from hubbeam.core.drive import free_hub_torque
from hubbeam.core.eom import add_damping, solve_spd
from hubbeam.core.jit import borrowing_kernel, kernel
from hubbeam.core.radau import register_rhs
from hubbeam.core.root import add_joint, has_joint, joint_rows, packed_joint, unpacked_joint
from hubbeam.core.shaping import shaped_motion

#: CFOAM as a radau5 problem: maneuver ``kind`` and parameters ``mp``, damping matrices ``C``,
#: the tensors ``ct``, and work arrays: full-length ``y, v``, the mass matrix ``M`` and force ``F``
#: of Eq. (24); ``drive`` the hub's packed drive (``hubbeam.core.drive``; empty: none); ``shaper``
#: the command shaper (``hubbeam.core.shaping``); ``joint`` the compliant root packed
#: (``hubbeam.core.root.packed_joint``; empty: rigid) with the two rows its terms pass through
#: (``hubbeam.core.root.add_joint``).
CfoamProblem = namedtuple("CfoamProblem", "kind mp C ct y v M F drive shaper joint")


@kernel
def cfoam_problem(inputs):
    """The :data:`CfoamProblem` of CFOAM for the :class:`~hubbeam.core.inputs.SimulationInputs`
    ``inputs`` (maneuver, damping matrices ``C`` and ``SystemMatrices`` ``sm``; with a compliant
    root, the link's and the joint)."""
    sm = inputs.sm
    n = sm.M1.shape[0]
    N = 1 + 2 * n
    joint = np.zeros((0, 0))
    if has_joint(inputs.root):
        N += 1
        joint = packed_joint(inputs.traits, inputs.root, 2)
    return CfoamProblem(inputs.kind, inputs.mp, inputs.C, cfoam_tensors(sm), np.zeros(N), np.zeros(N),
                        np.empty((N, N)), np.empty(N), inputs.drive, inputs.shaper, joint)


@borrowing_kernel
def cfoam_rhs(t, yf, vf, af, problem):
    """Accelerations ``af`` of the free coordinates ``(yf, vf)``: Eq. (24) with ``M`` and ``F`` from
    the tensors, solved on the free block.

    The hub's coordinate is theta on the rigid root (an empty ``problem.joint``) and the hub angle
    phi, the last, with a compliant root, whose terms then join ``M`` and ``F`` (the link's
    equations about its hinge, the hub torque on phi: ``hubbeam.core.root.add_joint``). A free hub
    receives the torque of its shaped command through its drive; a prescribed hub's coordinate is
    not integrated (on the rigid root the free coordinates then start at q1) and its shaped
    acceleration moves to the right-hand side: ``M_ff a_f = F_f - M_fh theta_ddot``."""
    y, v, M, F = problem.y, problem.v, problem.M, problem.F
    joint = problem.joint
    nf = yf.shape[0]
    N = y.shape[0]
    hub = N - 1 if joint.shape[0] > 0 else 0
    o = 0  # the index in y of the first free coordinate
    hdd = 0.0
    tau = 0.0
    if nf < N:
        y[hub], v[hub], hdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)
        if hub == 0:
            o = 1
    else:
        tau = free_hub_torque(problem.drive, problem.kind, t, yf, vf, problem.mp, problem.shaper, hub)
    for i in range(nf):
        y[o + i] = yf[i]
        v[o + i] = vf[i]
    if joint.shape[0] > 0:
        cfoam_system(y, v, 0.0, problem.ct, M, F)
        traits, root = unpacked_joint(joint)
        first = joint_rows(joint)
        add_joint(traits, root, y, v, tau, M, F, joint[first:first + 2])
    else:
        cfoam_system(y, v, tau, problem.ct, M, F)
    add_damping(problem.C, v, F)
    for i in range(nf):
        af[i] = F[o + i] - M[o + i, hub] * hdd
    # the free block is factored where it lies (M is rebuilt at every call)
    if not solve_spd(M[o:o + nf, o:o + nf], af):
        for i in range(nf):
            af[i] = np.nan


register_rhs(CfoamProblem, cfoam_rhs)

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
theta is always integrated, the hub angle phi unless the maneuver prescribes it
(:func:`joint_cfoam_rhs`).
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
def joint_cfoam_rhs(t, yf, vf, af, problem):
    """:func:`cfoam_rhs` with a compliant root: accelerations of ``(theta, q1, q2)`` and, unless
    prescribed, of the hub angle phi (the last free coordinate)."""
    y, v, M, F = problem.y, problem.v, problem.M, problem.F
    nf = yf.shape[0]
    hub = y.shape[0] - 1
    phdd = 0.0
    tau = 0.0
    if nf == hub:
        y[hub], v[hub], phdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)
    else:
        tau = free_hub_torque(problem.drive, problem.kind, t, yf, vf, problem.mp, problem.shaper, hub)
    for i in range(nf):
        y[i] = yf[i]
        v[i] = vf[i]
    cfoam_system(y, v, 0.0, problem.ct, M, F)
    traits, root = unpacked_joint(problem.joint)
    first = joint_rows(problem.joint)
    add_joint(traits, root, y, v, tau, M, F, problem.joint[first:first + 2])
    add_damping(problem.C, v, F)
    for i in range(nf):
        af[i] = F[i] - M[i, hub] * phdd
    if not solve_spd(M[:nf, :nf], af):
        for i in range(nf):
            af[i] = np.nan


@borrowing_kernel
def cfoam_rhs(t, yf, vf, af, problem):
    """Accelerations ``af`` of the free coordinates (theta first unless prescribed, then q1, q2;
    with a compliant root :func:`joint_cfoam_rhs`)."""
    if problem.joint.shape[0] > 0:
        joint_cfoam_rhs(t, yf, vf, af, problem)
        return
    y, v, M, F = problem.y, problem.v, problem.M, problem.F
    nf = yf.shape[0]
    o = y.shape[0] - nf  # 1: theta is prescribed
    thdd = 0.0
    tau = 0.0
    if o == 1:
        y[0], thd, thdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)
        v[0] = thd
    else:
        tau = free_hub_torque(problem.drive, problem.kind, t, yf, vf, problem.mp, problem.shaper, 0)
    for i in range(nf):
        y[o + i] = yf[i]
        v[o + i] = vf[i]
    cfoam_system(y, v, tau, problem.ct, M, F)
    add_damping(problem.C, v, F)
    for i in range(nf):
        af[i] = F[o + i] - M[o + i, 0] * thdd
    # the free block is factored where it lies (M is rebuilt at every call)
    if not solve_spd(M[o:, o:], af):
        for i in range(nf):
            af[i] = np.nan


register_rhs(CfoamProblem, cfoam_rhs)

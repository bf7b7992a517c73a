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
"""

from collections import namedtuple

import numpy as np

from hubbeam.core.cfoam_tensors import cfoam_system, cfoam_tensors
from hubbeam.core.drive import drive_torque
from hubbeam.core.eom import add_damping, solve_spd
from hubbeam.core.jit import borrowing_kernel, kernel
from hubbeam.core.radau import register_rhs
from hubbeam.core.shaping import shaped_motion, shaped_torque

#: CFOAM as a radau5 problem: maneuver ``kind`` and parameters ``mp``, damping matrices ``C``,
#: the tensors ``ct``, and work arrays: full-length ``y, v``, the mass matrix ``M`` and force ``F``
#: of Eq. (24); ``drive`` the hub's packed drive (``hubbeam.core.drive``; empty: none); ``shaper``
#: the command shaper (``hubbeam.core.shaping``).
CfoamProblem = namedtuple("CfoamProblem", "kind mp C ct y v M F drive shaper")


@kernel
def cfoam_problem(inputs):
    """The :data:`CfoamProblem` of CFOAM for the :class:`~hubbeam.core.inputs.SimulationInputs`
    ``inputs`` (maneuver, damping matrices ``C`` and ``SystemMatrices`` ``sm``)."""
    sm = inputs.sm
    N = 1 + 2 * sm.M1.shape[0]
    return CfoamProblem(inputs.kind, inputs.mp, inputs.C, cfoam_tensors(sm), np.zeros(N), np.zeros(N),
                        np.empty((N, N)), np.empty(N), inputs.drive, inputs.shaper)


@borrowing_kernel
def cfoam_rhs(t, yf, vf, af, problem):
    """Accelerations ``af`` of the free coordinates (theta first unless prescribed, then q1, q2)."""
    y, v, M, F = problem.y, problem.v, problem.M, problem.F
    nf = yf.shape[0]
    o = y.shape[0] - nf  # 1: theta is prescribed
    thdd = 0.0
    tau = 0.0
    if o == 1:
        y[0], thd, thdd = shaped_motion(problem.kind, t, problem.mp, problem.shaper)
        v[0] = thd
    else:
        tau = drive_torque(problem.drive, shaped_torque(problem.kind, t, yf, vf, problem.mp, problem.shaper), vf[0])
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

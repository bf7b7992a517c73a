"""The equations of motion as the first-order system a general-purpose ODE solver takes.

``z = (y_f, v_f)`` (free positions and velocities, see ``eom.free_dofs``), ``z' = f(t, z) =
(v_f, a_f(t, y_f, v_f))`` with the accelerations (Eq. 24 solved for y'') of the problem hubbeam's
integrator runs (:func:`hubbeam.core.integrate.integration_problem`), and its Jacobian
``df/dz = [[0, I], [da/dy, da/dv]]`` by the forward differences hubbeam's Radau IIA uses
(:func:`hubbeam.core.radau.jacobian`, ``2 N`` evaluations of ``a`` inside one call). These are
what a user would hand to ``scipy.integrate.solve_ivp`` (``fun`` and ``jac``); the benchmark
(``benchmarks/``) times scipy's methods with them.
"""

import numpy as np

from hubbeam.core.jit import kernel
from hubbeam.core.radau import STAT_NAMES, jacobian, problem_rhs, workspace


@kernel
def first_order_rhs(t, z, problem):
    """``f(t, z) = (v, a(t, y, v))`` for ``z = (y, v)`` of a radau5 problem (a new array)."""
    nf = z.shape[0] // 2
    dz = np.empty(2 * nf)
    problem_rhs(t, z[:nf], z[nf:], dz[nf:], problem)
    dz[:nf] = z[nf:]
    return dz


@kernel
def first_order_jacobian(t, z, problem):
    """``df/dz`` at ``(t, z)`` by forward differences (``2 N + 1`` evaluations of ``a``)."""
    nf = z.shape[0] // 2
    w = workspace(nf)
    y = z[:nf].copy()
    v = z[nf:].copy()
    problem_rhs(t, y, v, w.a, problem)
    jacobian(problem, t, y, v, w, np.zeros(len(STAT_NAMES), np.int64))
    jac = np.zeros((2 * nf, 2 * nf))
    for i in range(nf):
        jac[i, nf + i] = 1.0
        for j in range(nf):
            jac[nf + i, j] = w.Ka[i, j]
            jac[nf + i, nf + j] = w.Ca[i, j]
    return jac

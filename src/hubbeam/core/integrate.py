"""The whole hub-beam simulation in one kernel per family of models: Radau IIA over the
equations of motion.

:func:`simulate_kernel` integrates the free coordinates of ``y = (theta, q1, q2)`` (theta is
dropped for a prescribed maneuver, q1 for SFOAM; see ``eom.free_dofs``) from rest with
:func:`hubbeam.core.radau.radau5`, then evaluates every output of the simulation dataset on the
uniform output grid from the interpolated states. Nothing returns to Python per step. TLAM,
FOAM and SFOAM share one compiled kernel, CFOAM has its own (:data:`FAMILY_KERNELS`): each holds
one specialisation of the integrator, and two processes compile them in half the time one
process takes for both.

The integrator runs on right-hand sides built for speed (:mod:`hubbeam.core.foam_rhs`,
:mod:`hubbeam.core.cfoam_rhs`), and the outputs come from the same equations: for TLAM, FOAM and
SFOAM the hub row of Eq. (24) with the constant modal mass (``foam_rhs.foam_outputs``), for CFOAM
the full mass matrix and force from its pre-contracted tensors
(:mod:`hubbeam.core.cfoam_tensors`). The tests hold both to the general equations of
:mod:`hubbeam.core.eom`.
``kind, mp`` is the maneuver (:mod:`hubbeam.core.maneuver`), ``C`` the damping matrices
``[C1, C2]`` of the elastic coordinates (:func:`hubbeam.core.eom.add_damping`; zeros: undamped).
"""

import numpy as np

from hubbeam.core.cfoam_rhs import cfoam_problem
from hubbeam.core.cfoam_tensors import cfoam_system, cfoam_tensors
from hubbeam.core.eom import (
    CFOAM,
    add_damping,
    dissipation_rate,
    free_dofs,
    high_order_terms,
    impose_constraints,
    outputs,
    strain_energy,
    tip_outputs,
    workspace,
)
from hubbeam.core.foam_rhs import foam_outputs, foam_problem
from hubbeam.core.jit import borrowing_kernel, inline_kernel, kernel
from hubbeam.core.radau import radau5

#: Columns of the output array: these, then ``q1[0..n-1]``, ``q2[0..n-1]``, then the CFOAM
#: high-order terms ``dM_thth``, ``dQ_theta``, ``dQ_q1[0..n-1]``, ``dQ_q2[0..n-1]`` (NaN for the
#: other models); see :func:`output_columns`. ``dissipation_rate`` is the power of the damping
#: forces (:func:`hubbeam.core.eom.dissipation_rate`).
SCALAR_OUTPUTS = ("theta", "theta_dot", "theta_ddot", "hub_torque", "Q_theta", "tip_transverse",
                  "tip_axial", "tip_foreshortening", "energy", "angular_momentum",
                  "dissipation_rate")
N_SCALAR = len(SCALAR_OUTPUTS)


def output_columns(n):
    """``{name: column index or slice}`` of the output array for ``n`` modes."""
    columns = {name: k for k, name in enumerate(SCALAR_OUTPUTS)}
    columns["q1"] = slice(N_SCALAR, N_SCALAR + n)
    columns["q2"] = slice(N_SCALAR + n, N_SCALAR + 2 * n)
    columns["dM_thth"] = N_SCALAR + 2 * n
    columns["dQ_theta"] = N_SCALAR + 2 * n + 1
    columns["dQ_q1"] = slice(N_SCALAR + 2 * n + 2, N_SCALAR + 3 * n + 2)
    columns["dQ_q2"] = slice(N_SCALAR + 3 * n + 2, N_SCALAR + 4 * n + 2)
    return columns


def n_output_columns(n):
    """Width of the output array for ``n`` modes."""
    return N_SCALAR + 4 * n + 2


def integration_problem(model, kind, mp, C, sm):
    """The radau5 problem :func:`integrate_free` runs for ``model`` (for callers outside numba,
    such as the benchmark's scipy runs, which must integrate the same equations)."""
    if model == CFOAM:
        return cfoam_problem(kind, mp, C, sm)
    return foam_problem(model, kind, mp, C, sm)


@kernel
def tip_watch(free, sm):
    """Weights ``w`` with ``w . y_free = f2(L) q2``, the tip deflection watched for leaving the range of the models."""
    n = sm.f2L.shape[0]
    w = np.zeros(free.shape[0])
    for i in range(free.shape[0]):
        if free[i] >= 1 + n:
            w[i] = sm.f2L[free[i] - 1 - n]
    return w


@borrowing_kernel
def _start_row(out, k, free, y_out, v_out, y, v):
    """Fill row ``k`` of ``out`` with NaN; if the states of output time ``k`` are finite (the run
    got there), write them into the full-length ``y, v`` (the rest zero) and return True."""
    for j in range(out.shape[1]):
        out[k, j] = np.nan
    if not np.isfinite(y_out[k, 0]):
        return False
    for i in range(y.shape[0]):
        y[i] = 0.0
        v[i] = 0.0
    for i in range(free.shape[0]):
        y[free[i]] = y_out[k, i]
        v[free[i]] = v_out[k, i]
    return True


@inline_kernel
def _write_row(out_row, y, v, a, torque, q_theta, tip, e, p, dissipation):
    """The columns of :data:`SCALAR_OUTPUTS` and ``q1``, ``q2`` of one output time: ``tip`` is
    ``eom.tip_outputs``, ``e`` the total energy, ``p`` the angular momentum and ``dissipation``
    the dissipation rate of the state."""
    out_row[0] = y[0]
    out_row[1] = v[0]
    out_row[2] = a[0]
    out_row[3] = torque
    out_row[4] = q_theta
    out_row[5] = tip[0]
    out_row[6] = tip[1]
    out_row[7] = tip[2]
    out_row[8] = e
    out_row[9] = p
    out_row[10] = dissipation
    for i in range(y.shape[0] - 1):
        out_row[N_SCALAR + i] = y[1 + i]


# Outputs of an undamped run (C = 0) have a dissipation rate of exactly zero, not summed.
# TLAM, FOAM and SFOAM fill their rows in a loop compiled without numba's reference counting
# (``jit.borrowing_kernel``; its work arrays are rows of ``work``): with the counts the loop took
# twice as long. CFOAM's loop, whose rows cost more, measured faster with them.
@borrowing_kernel
def _foam_rows(problem, model, kind, mp, C, damped, sm, free, t_out, y_out, v_out, out, work):
    y = work[0]
    v = work[1]
    a = work[2]
    af = work[3, :free.shape[0]]
    for k in range(t_out.shape[0]):
        if not _start_row(out, k, free, y_out, v_out, y, v):
            continue
        impose_constraints(model, kind, mp, t_out[k], y, v, a)
        torque, q_theta, kinetic, p = foam_outputs(t_out[k], y_out[k], v_out[k], af, problem)
        for i in range(free.shape[0]):
            a[free[i]] = af[i]
        _write_row(out[k], y, v, a, torque, q_theta, tip_outputs(y, sm),
                   kinetic + strain_energy(y, sm.K1, sm.K2), p,
                   dissipation_rate(C, v) if damped else 0.0)


@kernel
def _fill_rows_foam(problem, model, kind, mp, C, sm, free, t_out, y_out, v_out, out):
    """:func:`fill_outputs` of TLAM, FOAM or SFOAM from its ``FoamProblem``: the accelerations
    and the hub row from the constant modal mass (``foam_rhs.foam_outputs``), no mass matrix."""
    work = np.zeros((4, 1 + 2 * sm.K1.shape[0]))
    _foam_rows(problem, model, kind, mp, C, np.any(C != 0.0), sm, free, t_out, y_out, v_out,
               out, work)


@kernel
def _fill_rows_cfoam(ct, kind, mp, C, sm, free, t_out, y_out, v_out, out):
    """:func:`fill_outputs` of CFOAM from its tensors ``ct``: one mass matrix and force of
    Eq. (24) per output time gives the accelerations, the torque, the energy, the angular
    momentum and the high-order terms."""
    n = sm.K1.shape[0]
    N = 1 + 2 * n
    y = np.zeros(N)
    v = np.zeros(N)
    a = np.zeros(N)
    dQ = np.zeros(N)
    Mf = np.empty((N, N))
    Ff = np.empty(N)
    ws = workspace(sm, free)
    damped = np.any(C != 0.0)
    for k in range(t_out.shape[0]):
        if not _start_row(out, k, free, y_out, v_out, y, v):
            continue
        tau = impose_constraints(CFOAM, kind, mp, t_out[k], y, v, a)
        cfoam_system(y, v, tau, ct, ws.M, ws.F)
        add_damping(C, v, ws.F)
        torque, q_theta, e, p = outputs(kind, tau, y, v, sm, free, a, ws)
        _write_row(out[k], y, v, a, torque, q_theta, tip_outputs(y, sm), e, p,
                   dissipation_rate(C, v) if damped else 0.0)
        out[k, N_SCALAR + 2 * n] = high_order_terms(ws.M, ws.F, tau, y, v, a, sm, C, Mf, Ff, dQ)
        for i in range(N):
            out[k, N_SCALAR + 2 * n + 1 + i] = dQ[i]


@kernel
def fill_outputs(model, kind, mp, C, sm, free, t_out, y_out, v_out, out):
    """Every output at the times ``t_out`` from the free positions and velocities ``y_out``,
    ``v_out`` (rows with NaN give NaN rows): columns as in :func:`output_columns`.

    TLAM, FOAM and SFOAM take the accelerations, the torque, the energy and the angular momentum
    from the hub row of Eq. (24) with the constant modal mass (``foam_rhs.foam_outputs``); CFOAM
    from its mass matrix and force, built from the pre-contracted tensors
    (``core/cfoam_tensors.py``), with its high-order terms. The tests hold both to the general
    equations of :mod:`hubbeam.core.eom`.
    """
    if model == CFOAM:
        _fill_rows_cfoam(cfoam_tensors(sm), kind, mp, C, sm, free, t_out, y_out, v_out, out)
    else:
        _fill_rows_foam(foam_problem(model, kind, mp, C, sm), model, kind, mp, C, sm, free, t_out,
                        y_out, v_out, out)


@inline_kernel
def _integrate(problem, free, sm, t_out, t_stops, rtol, atol, tip_limit, max_steps, y_out, v_out,
               stats):
    """radau5 on ``problem`` (a ``FoamProblem`` or a ``CfoamProblem``) from rest; see
    :func:`integrate_free`."""
    nf = free.shape[0]
    watch = tip_watch(free, sm)
    atol_z = np.full(2 * nf, atol)
    status, t_stop = radau5(problem, np.zeros(nf), np.zeros(nf), t_out, t_stops, rtol, atol_z,
                            watch, tip_limit, max_steps, 0.0, False, y_out, v_out, stats)
    return status, t_stop, watch


@inline_kernel
def integrate_free(model, kind, mp, C, sm, t_out, t_stops, rtol, atol, tip_limit, max_steps, y_out,
                   v_out, stats):
    """Simulate from rest (``y = 0``, ``y' = 0``) and write the free positions and velocities
    (``eom.free_dofs``) on ``t_out`` into ``y_out``, ``v_out`` (shape ``(len(t_out), n_free)``;
    NaN after a stop).

    TLAM, FOAM and SFOAM run on :data:`hubbeam.core.foam_rhs.FoamProblem` (constant modal mass
    inverted once), CFOAM on :data:`hubbeam.core.cfoam_rhs.CfoamProblem` (point-cloud sums
    contracted once). ``rtol`` and the scalar ``atol`` apply to every
    free position and velocity (see ``radau5``); the run stops (status ``left_range``) once
    ``|tip deflection| > tip_limit``. ``stats`` (int64, ``len(radau.STAT_NAMES)``) receives
    radau5's counters. Returns radau5's ``(status, t_stop)`` and the weights ``w`` with
    ``w . y_free = v(L)``.
    """
    free = free_dofs(model, kind, sm.K1.shape[0])
    if model == CFOAM:
        return _integrate(cfoam_problem(kind, mp, C, sm), free, sm, t_out, t_stops, rtol, atol,
                          tip_limit, max_steps, y_out, v_out, stats)
    return _integrate(foam_problem(model, kind, mp, C, sm), free, sm, t_out, t_stops, rtol, atol,
                      tip_limit, max_steps, y_out, v_out, stats)


@inline_kernel
def _states(problem, model, kind, sm, t_out, t_stops, rtol, atol, tip_limit, max_steps, stats):
    """:func:`integrate_free` on ``problem``: ``(status, t_stop, free, y_out, v_out)``."""
    free = free_dofs(model, kind, sm.K1.shape[0])
    y_out = np.empty((t_out.shape[0], free.shape[0]))
    v_out = np.empty_like(y_out)
    status, t_stop, _ = _integrate(problem, free, sm, t_out, t_stops, rtol, atol, tip_limit,
                                   max_steps, y_out, v_out, stats)
    return status, t_stop, free, y_out, v_out


@kernel
def simulate_foam_family(model, kind, mp, C, sm, t_out, t_stops, rtol, atol, tip_limit,
                         max_steps, out, stats):
    """:func:`simulate_kernel` of TLAM, FOAM and SFOAM (``FoamProblem``)."""
    problem = foam_problem(model, kind, mp, C, sm)
    status, t_stop, free, y_out, v_out = _states(problem, model, kind, sm, t_out, t_stops, rtol,
                                                 atol, tip_limit, max_steps, stats)
    _fill_rows_foam(problem, model, kind, mp, C, sm, free, t_out, y_out, v_out, out)
    return status, t_stop


@kernel
def simulate_cfoam_family(model, kind, mp, C, sm, t_out, t_stops, rtol, atol, tip_limit,
                          max_steps, out, stats):
    """:func:`simulate_kernel` of CFOAM (``CfoamProblem``, outputs from its tensors)."""
    problem = cfoam_problem(kind, mp, C, sm)
    status, t_stop, free, y_out, v_out = _states(problem, model, kind, sm, t_out, t_stops, rtol,
                                                 atol, tip_limit, max_steps, stats)
    _fill_rows_cfoam(problem.ct, kind, mp, C, sm, free, t_out, y_out, v_out, out)
    return status, t_stop


#: the compiled kernel of each family of models: one radau5 specialisation each, so that two
#: processes compile them at the same time (the workflow's simulation_kernel_<family> jobs)
FAMILY_KERNELS = {"foam": simulate_foam_family, "cfoam": simulate_cfoam_family}


def model_family(model):
    """The family (key of :data:`FAMILY_KERNELS`) of the model id ``model``."""
    return "cfoam" if model == CFOAM else "foam"


def simulate_kernel(model, kind, mp, C, sm, t_out, t_stops, rtol, atol, tip_limit, max_steps,
                    out, stats):
    """Simulate from rest over ``t_out`` (:func:`integrate_free`) and fill ``out``
    (:func:`fill_outputs`), in the compiled kernel of the model's family.

    ``model``, ``kind``: ids of ``eom`` and ``maneuver``; ``mp``: maneuver parameters; ``C``:
    damping matrices (2, n, n); ``sm``:
    SystemMatrices; ``t_stops``: times no step may cross (end of the maneuver); tolerances and
    ``tip_limit`` as in :func:`integrate_free`. ``out`` has shape
    ``(len(t_out), n_output_columns(n))``, columns as in :func:`output_columns`; rows after the
    stop are NaN. ``stats`` (int64, ``len(radau.STAT_NAMES)``) receives radau5's counters.
    Returns radau5's ``(status, t_stop)``.
    """
    return FAMILY_KERNELS[model_family(model)](model, kind, mp, C, sm, t_out, t_stops, rtol, atol,
                                               tip_limit, max_steps, out, stats)

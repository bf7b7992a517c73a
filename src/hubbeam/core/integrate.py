"""The whole hub-beam simulation in one kernel per family of models: Radau IIA over the
equations of motion.

:func:`simulate_kernel` integrates the free coordinates of ``y = (theta, q1, q2)`` (theta is
dropped for a prescribed maneuver, q1 for SFOAM; see ``eom.free_dofs``) from a given initial
state (rest, or a steady spin, ``hubbeam.simulation.simulate``) with :func:`hubbeam.core.radau.radau5`,
then evaluates every output of the simulation dataset on the uniform output grid from the
interpolated states. Nothing returns to Python per step. TLAM,
FOAM and SFOAM share one compiled kernel, CFOAM has its own (:data:`FAMILY_KERNELS`): each holds
one specialisation of the integrator, and two processes compile them in half the time one
process takes for both.

The integrator runs on right-hand sides built for speed (:mod:`hubbeam.core.foam_rhs`,
:mod:`hubbeam.core.cfoam_rhs`), and the outputs come from the same equations: for TLAM, FOAM and
SFOAM the hub row of Eq. (24) with the constant modal mass (``foam_rhs.foam_outputs``), for CFOAM
the full mass matrix and force from its pre-contracted tensors
(:mod:`hubbeam.core.cfoam_tensors`). The tests hold both to the general equations of
:mod:`hubbeam.core.eom`.
The problem is one :class:`~hubbeam.core.inputs.SimulationInputs` ``inputs``: the model's traits,
the maneuver ``kind, mp`` (:mod:`hubbeam.core.maneuver`), the damping matrices ``C = [C1, C2]``
of the elastic coordinates (:func:`hubbeam.core.eom.add_damping`; zeros: undamped) and the
system matrices ``sm``; the integrator settings are one
:class:`~hubbeam.core.inputs.IntegratorSettings`.
"""

import numpy as np

from hubbeam.core.cfoam_rhs import cfoam_problem
from hubbeam.core.cfoam_tensors import cfoam_system, cfoam_tensors
from hubbeam.core.drive import friction_torque, motor_torque, required_voltage, terminal_voltage
from hubbeam.core.eom import (
    add_damping,
    body_outputs,
    coordinate_count,
    equations,
    free_coordinates,
    high_order_terms,
    impose_constraints,
    inputs_workspace,
    joint_dissipation,
    outputs,
    strain_energy,
    tip_outputs,
)
from hubbeam.core.foam_rhs import foam_outputs, foam_problem
from hubbeam.core.inputs import FAMILIES, Trajectory, family
from hubbeam.core.jit import borrowing_kernel, inline_kernel, kernel
from hubbeam.core.maneuver import prescribed
from hubbeam.core.radau import radau5
from hubbeam.core.root import add_joint, has_joint, hub_index, spring_torque
from hubbeam.core.shaping import shaped_torque

#: Columns of the output array: these, then ``q1[0..n-1]``, ``q2[0..n-1]``, then the CFOAM
#: high-order terms ``dM_thth``, ``dQ_theta``, ``dQ_q1[0..n-1]``, ``dQ_q2[0..n-1]`` (NaN for the
#: other models); see :func:`output_columns`. ``dissipation_rate`` is the power of the damping
#: forces (:func:`hubbeam.core.eom.dissipation_rate`); ``body_transverse`` and ``body_axial`` the
#: displacement of the tip body's centre (:func:`hubbeam.core.eom.body_outputs`). With a drive
#: (``hubbeam.core.drive``) ``hub_torque`` is the torque the drive delivers to the hub, ``hub_voltage``
#: the voltage across the motor (a free hub's command clipped to the limit, or what a prescribed
#: motion needs, not clipped) and ``motor_torque`` the gearbox's torque before the hub's friction;
#: both are NaN without a drive.
SCALAR_OUTPUTS = ("theta", "theta_dot", "theta_ddot", "hub_torque", "Q_theta", "tip_transverse",
                  "tip_axial", "tip_foreshortening", "energy", "angular_momentum",
                  "dissipation_rate", "body_transverse", "body_axial", "hub_voltage", "motor_torque")
N_SCALAR = len(SCALAR_OUTPUTS)
HUB_VOLTAGE = SCALAR_OUTPUTS.index("hub_voltage")
MOTOR_TORQUE = SCALAR_OUTPUTS.index("motor_torque")
#: Columns a run with a compliant root (``hubbeam.core.root``) appends: the hub's angle, rate and
#: acceleration (the motor side; ``theta`` is then the beam's root angle) and the torque the spring
#: and damper pass from the hub to the link. ``hub_torque`` is the torque on the hub,
#: ``angular_momentum`` that of hub and link, ``energy`` includes the spring's and
#: ``dissipation_rate`` the damper's power.
JOINT_OUTPUTS = ("hub_angle", "hub_speed", "hub_acceleration", "spring_torque")


def output_columns(n, joint=False):
    """``{name: column index or slice}`` of the output array for ``n`` modes (with ``joint``, a
    compliant root's columns :data:`JOINT_OUTPUTS` too)."""
    columns = {name: k for k, name in enumerate(SCALAR_OUTPUTS)}
    columns["q1"] = slice(N_SCALAR, N_SCALAR + n)
    columns["q2"] = slice(N_SCALAR + n, N_SCALAR + 2 * n)
    columns["dM_thth"] = N_SCALAR + 2 * n
    columns["dQ_theta"] = N_SCALAR + 2 * n + 1
    columns["dQ_q1"] = slice(N_SCALAR + 2 * n + 2, N_SCALAR + 3 * n + 2)
    columns["dQ_q2"] = slice(N_SCALAR + 3 * n + 2, N_SCALAR + 4 * n + 2)
    if joint:
        columns |= {name: N_SCALAR + 4 * n + 2 + k for k, name in enumerate(JOINT_OUTPUTS)}
    return columns


def n_output_columns(n, joint=False):
    """Width of the output array for ``n`` modes (with ``joint``, a compliant root's)."""
    return N_SCALAR + 4 * n + 2 + (len(JOINT_OUTPUTS) if joint else 0)


def integration_problem(inputs):
    """The radau5 problem :func:`integrate_free` runs for ``inputs`` (for callers outside numba,
    such as the benchmark's scipy runs, which must integrate the same equations)."""
    if inputs.traits.exact_kinetic_energy:
        return cfoam_problem(inputs)
    return foam_problem(inputs)


@kernel
def tip_watch(free, sm):
    """Weights ``w`` with ``w . y_free = f2(L) q2``, the tip deflection watched for leaving the range of the models."""
    n = sm.f2L.shape[0]
    w = np.zeros(free.shape[0])
    for i in range(free.shape[0]):
        if 1 + n <= free[i] < 1 + 2 * n:
            w[i] = sm.f2L[free[i] - 1 - n]
    return w


@borrowing_kernel
def _start_row(out, k, free, states, y, v):
    """Fill row ``k`` of ``out`` with NaN; if the states of output time ``k`` (``states``, a
    :class:`~hubbeam.core.inputs.Trajectory` of the free coordinates) are finite (the run got
    there), write them into the full-length ``y, v`` (the rest zero) and return True."""
    for j in range(out.shape[1]):
        out[k, j] = np.nan
    if not np.isfinite(states.y[k, 0]):
        return False
    for i in range(y.shape[0]):
        y[i] = 0.0
        v[i] = 0.0
    for i in range(free.shape[0]):
        y[free[i]] = states.y[k, i]
        v[free[i]] = states.v[k, i]
    return True


@inline_kernel
def _write_row(out_row, y, v, a, hub, ends, dissipation):
    """The columns of :data:`SCALAR_OUTPUTS` and ``q1``, ``q2`` of one output time: ``hub`` is
    ``(torque, Q_theta, total energy, angular momentum)``, ``ends`` is ``(eom.tip_outputs,
    eom.body_outputs)`` and ``dissipation`` the dissipation rate of the state."""
    torque, q_theta, e, p = hub
    tip, body = ends
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
    out_row[11] = body[0]
    out_row[12] = body[1]
    for i in range(2 * ((y.shape[0] - 1) // 2)):
        out_row[N_SCALAR + i] = y[1 + i]


@borrowing_kernel
def _drive_columns(out_row, inputs, t, y, v, torque):
    """``hub_voltage`` and ``motor_torque`` of one output time (see :data:`SCALAR_OUTPUTS`) from
    the state ``(y, v)`` (full length, constraints imposed) and the hub torque ``torque``."""
    drive = inputs.drive
    hub = hub_index(inputs.root, y.shape[0])
    if drive.shape[0] == 0:
        out_row[HUB_VOLTAGE] = np.nan
        out_row[MOTOR_TORQUE] = np.nan
    elif prescribed(inputs.kind):
        out_row[HUB_VOLTAGE] = required_voltage(drive, torque, v[hub])
        out_row[MOTOR_TORQUE] = torque + friction_torque(drive, v[hub])
    else:
        command = shaped_torque(inputs.kind, t, y, v, inputs.mp, inputs.shaper, hub)
        out_row[HUB_VOLTAGE] = terminal_voltage(drive, command)
        out_row[MOTOR_TORQUE] = motor_torque(drive, command, v[hub])


@kernel
def _summed_dissipation(inputs):
    """Whether the outputs sum the dissipation rate (:func:`hubbeam.core.eom.joint_dissipation`):
    for damping matrices or a compliant root (its damper); an undamped run on the rigid root records
    exactly zero, not a sum."""
    return has_joint(inputs.root) or np.any(inputs.C != 0.0)


@borrowing_kernel
def _output_row(out_row, inputs, t, state, hub, summed):
    """The columns of one output time ``t`` (:func:`output_columns`) from the state ``state = (y,
    v, a)`` (full length, constraints imposed, accelerations solved) and ``hub = (torque, Q_theta,
    energy, angular momentum)``; the dissipation rate summed if ``summed``
    (:func:`_summed_dissipation`); with a compliant root its columns :data:`JOINT_OUTPUTS`."""
    y, v, a = state
    sm = inputs.sm
    _write_row(out_row, y, v, a, hub, (tip_outputs(y, sm), body_outputs(y, sm)),
               joint_dissipation(inputs, v) if summed else 0.0)
    _drive_columns(out_row, inputs, t, y, v, hub[0])
    if has_joint(inputs.root):
        first = N_SCALAR + 4 * sm.K1.shape[0] + 2
        last = y.shape[0] - 1
        out_row[first] = y[last]
        out_row[first + 1] = v[last]
        out_row[first + 2] = a[last]
        out_row[first + 3] = spring_torque(inputs.root, y, v)


# TLAM, FOAM and SFOAM fill their rows in a loop compiled without numba's reference counting
# (``jit.borrowing_kernel``; its work arrays are rows of ``work``): with the counts the loop took
# twice as long. CFOAM's loop, whose rows cost more, measured faster with them.
@borrowing_kernel
def _foam_rows(problem, inputs, summed, free, states, out, work):
    """:func:`fill_outputs` of TLAM, FOAM or SFOAM on the rigid root (:func:`_fill_rows_foam`), its
    work arrays the rows of ``work``."""
    y = work[0]
    v = work[1]
    a = work[2]
    af = work[3, :free.shape[0]]
    sm = inputs.sm
    t_out = states.t
    for k in range(t_out.shape[0]):
        if not _start_row(out, k, free, states, y, v):
            continue
        impose_constraints(inputs, t_out[k], y, v, a)
        torque, q_theta, kinetic, p = foam_outputs(t_out[k], states.y[k], states.v[k], af, problem)
        for i in range(free.shape[0]):
            a[free[i]] = af[i]
        _output_row(out[k], inputs, t_out[k], (y, v, a),
                    (torque, q_theta, kinetic + strain_energy(y, sm.K1, sm.K2), p), summed)


@kernel
def _joint_rows_foam(inputs, free, states, out):
    """:func:`fill_outputs` of TLAM, FOAM or SFOAM with a compliant root: the general equations
    (:func:`hubbeam.core.eom.equations`, :func:`hubbeam.core.eom.outputs`) at every output time."""
    N = coordinate_count(inputs)
    y = np.zeros(N)
    v = np.zeros(N)
    a = np.zeros(N)
    ws = inputs_workspace(inputs, free)
    t_out = states.t
    for k in range(t_out.shape[0]):
        if not _start_row(out, k, free, states, y, v):
            continue
        tau = impose_constraints(inputs, t_out[k], y, v, a)
        equations(inputs, y, v, tau, ws)
        _output_row(out[k], inputs, t_out[k], (y, v, a), outputs(inputs, tau, y, v, free, a, ws), True)


@kernel
def _fill_rows_foam(problem, inputs, free, states, out):
    """:func:`fill_outputs` of TLAM, FOAM or SFOAM from its ``FoamProblem``: the accelerations
    and the hub row from the constant modal mass (``foam_rhs.foam_outputs``), no mass matrix
    (with a compliant root, whose two hub rows ``foam_outputs`` does not solve, the general
    equations: :func:`_joint_rows_foam`)."""
    if has_joint(inputs.root):
        _joint_rows_foam(inputs, free, states, out)
        return
    work = np.zeros((4, 1 + 2 * inputs.sm.K1.shape[0]))
    _foam_rows(problem, inputs, _summed_dissipation(inputs), free, states, out, work)


@kernel
def _fill_rows_cfoam(ct, inputs, free, states, out):
    """:func:`fill_outputs` of CFOAM from its tensors ``ct``: one mass matrix and force of
    Eq. (24) per output time gives the accelerations, the torque, the energy, the angular
    momentum (:func:`hubbeam.core.eom.outputs`) and the high-order terms
    (:func:`hubbeam.core.eom.high_order_terms`).

    With a compliant root (``inputs.root``; empty: the rigid root) the tensors give the link's
    equations about its hinge, the joint's terms join them with the hub torque on the hub angle
    (``hubbeam.core.root.add_joint``), and the high-order terms are the link's, from its own
    equations without the joint (the joint's terms are the same in FOAM)."""
    sm = inputs.sm
    C = inputs.C
    n = sm.K1.shape[0]
    link = 1 + 2 * n
    N = coordinate_count(inputs)
    joint = has_joint(inputs.root)
    y = np.zeros(N)
    v = np.zeros(N)
    a = np.zeros(N)
    dQ = np.zeros(link)
    Mc = np.empty((link, link))
    Fc = np.empty(link)
    Mf = np.empty((link, link))
    Ff = np.empty(link)
    ws = inputs_workspace(inputs, free)
    summed = _summed_dissipation(inputs)
    t_out = states.t
    for k in range(t_out.shape[0]):
        if not _start_row(out, k, free, states, y, v):
            continue
        tau = impose_constraints(inputs, t_out[k], y, v, a)
        link_tau = 0.0 if joint else tau  # with a joint the hub torque acts on the hub angle
        cfoam_system(y, v, link_tau, ct, ws.M, ws.F)
        if joint:
            add_joint(inputs.traits, inputs.root, y, v, tau, ws.M, ws.F, ws.joint)
        add_damping(C, v, ws.F)
        _output_row(out[k], inputs, t_out[k], (y, v, a), outputs(inputs, tau, y, v, free, a, ws), summed)
        M_link = ws.M
        F_link = ws.F
        if joint:
            cfoam_system(y, v, 0.0, ct, Mc, Fc)
            add_damping(C, v, Fc)
            M_link = Mc
            F_link = Fc
        out[k, N_SCALAR + 2 * n] = high_order_terms(M_link, F_link, link_tau, (y, v, a), inputs, Mf, Ff, dQ)
        for i in range(link):
            out[k, N_SCALAR + 2 * n + 1 + i] = dQ[i]


@kernel
def fill_outputs(inputs, free, states, out):
    """Every output at the times ``states.t`` from the free positions and velocities
    ``states.y``, ``states.v`` (a :class:`~hubbeam.core.inputs.Trajectory`; rows with NaN give
    NaN rows): columns as in :func:`output_columns`.

    TLAM, FOAM and SFOAM take the accelerations, the torque, the energy and the angular momentum
    from the hub row of Eq. (24) with the constant modal mass (``foam_rhs.foam_outputs``); CFOAM
    from its mass matrix and force, built from the pre-contracted tensors
    (``core/cfoam_tensors.py``), with its high-order terms. The tests hold both to the general
    equations of :mod:`hubbeam.core.eom`.
    """
    if inputs.traits.exact_kinetic_energy:
        _fill_rows_cfoam(cfoam_tensors(inputs.sm), inputs, free, states, out)
    else:
        _fill_rows_foam(foam_problem(inputs), inputs, free, states, out)


@inline_kernel
def _integrate(problem, free, sm, start, t_stops, settings, states, stats):
    """radau5 on ``problem`` (a ``FoamProblem`` or a ``CfoamProblem``) from the free entries of
    the full-length ``start``; see :func:`integrate_free`."""
    nf = free.shape[0]
    watch = tip_watch(free, sm)
    y0 = np.empty(nf)
    v0 = np.empty(nf)
    for i in range(nf):
        y0[i] = start.y[free[i]]
        v0[i] = start.v[free[i]]
    status, t_stop = radau5(problem, (y0, v0), t_stops, settings, watch, states, stats)
    return status, t_stop, watch


@inline_kernel
def integrate_free(inputs, start, t_stops, settings, states, stats):
    """Simulate from the initial state ``start`` (a :class:`~hubbeam.core.inputs.State` of the
    full-length ``y = (theta, q1, q2)``; its constrained entries are not read) and write the free
    positions and velocities (``eom.free_dofs``) on ``states.t`` into ``states.y``, ``states.v``
    (a :class:`~hubbeam.core.inputs.Trajectory`, shape ``(len(t), n_free)``; NaN after a stop).
    With a compliant root ``y = (theta, q1, q2, phi)`` (``eom.free_coordinates``).

    TLAM, FOAM and SFOAM run on :data:`hubbeam.core.foam_rhs.FoamProblem` (constant modal mass
    inverted once), CFOAM on :data:`hubbeam.core.cfoam_rhs.CfoamProblem` (point-cloud sums
    contracted once). ``settings`` (:class:`~hubbeam.core.inputs.IntegratorSettings`): ``rtol``
    and ``atol`` apply to every free position and velocity (see ``radau5``); the run stops
    (status ``left_range``) once ``|tip deflection| > tip_limit``. ``stats`` (int64,
    ``len(radau.STAT_NAMES)``) receives radau5's counters. Returns radau5's
    ``(status, t_stop)`` and the weights ``w`` with ``w . y_free = v(L)``.
    """
    free = free_coordinates(inputs)
    if inputs.traits.exact_kinetic_energy:
        return _integrate(cfoam_problem(inputs), free, inputs.sm, start, t_stops, settings, states,
                          stats)
    return _integrate(foam_problem(inputs), free, inputs.sm, start, t_stops, settings, states,
                      stats)


@inline_kernel
def _states(problem, inputs, start, t_out, t_stops, settings, stats):
    """:func:`integrate_free` on ``problem``: ``(status, t_stop, free, states)`` with the
    :class:`~hubbeam.core.inputs.Trajectory` ``states`` of the free coordinates on ``t_out``."""
    free = free_coordinates(inputs)
    y_out = np.empty((t_out.shape[0], free.shape[0]))
    states = Trajectory(t_out, y_out, np.empty_like(y_out))
    status, t_stop, _ = _integrate(problem, free, inputs.sm, start, t_stops, settings, states,
                                   stats)
    return status, t_stop, free, states


@kernel
def simulate_foam_family(inputs, start, t_out, t_stops, settings, out, stats):
    """:func:`simulate_kernel` of TLAM, FOAM and SFOAM (``FoamProblem``)."""
    problem = foam_problem(inputs)
    status, t_stop, free, states = _states(problem, inputs, start, t_out, t_stops, settings,
                                           stats)
    _fill_rows_foam(problem, inputs, free, states, out)
    return status, t_stop


@kernel
def simulate_cfoam_family(inputs, start, t_out, t_stops, settings, out, stats):
    """:func:`simulate_kernel` of CFOAM (``CfoamProblem``, outputs from its tensors)."""
    problem = cfoam_problem(inputs)
    status, t_stop, free, states = _states(problem, inputs, start, t_out, t_stops, settings,
                                           stats)
    _fill_rows_cfoam(problem.ct, inputs, free, states, out)
    return status, t_stop


#: the compiled kernel of each family of models (``inputs.FAMILIES``): one radau5 specialisation
#: each, so that two processes compile them at the same time (the workflow's
#: simulation_kernel_<family> jobs)
FAMILY_KERNELS = dict(zip(FAMILIES, (simulate_foam_family, simulate_cfoam_family)))


def simulate_kernel(inputs, start, t_out, t_stops, settings, out, stats):
    """Simulate from the initial state ``start`` over ``t_out`` (:func:`integrate_free`) and fill
    ``out`` (:func:`fill_outputs`), in the compiled kernel of the model's family.

    ``inputs``: :class:`~hubbeam.core.inputs.SimulationInputs`; ``start``: the
    :class:`~hubbeam.core.inputs.State` at ``t_out[0]``; ``t_stops``: times no step may cross
    (end of the maneuver); ``settings``: :class:`~hubbeam.core.inputs.IntegratorSettings` as in
    :func:`integrate_free`. ``out`` has shape ``(len(t_out), n_output_columns(n))``, columns as
    in :func:`output_columns`; rows after the stop are NaN. ``stats`` (int64,
    ``len(radau.STAT_NAMES)``) receives radau5's counters. Returns radau5's ``(status, t_stop)``.
    """
    return FAMILY_KERNELS[family(inputs.traits)](inputs, start, t_out, t_stops, settings, out,
                                                 stats)

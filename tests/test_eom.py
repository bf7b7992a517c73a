"""The jitted equations of motion against independent evaluations.

* FOAM/TLAM/SFOAM against a plain numpy transcription of Eqs. (24)-(34), (40) (notes 2).
* Every model against Lagrange's equations obtained by numerically differentiating its kinetic
  energy: CFOAM from the exact kinetic energy of Eqs. (8)-(9) on a point cloud, FOAM from its
  quadratic truncation (the terms of order <= 2 in the elastic coordinates), TLAM from FOAM's
  kinetic energy without the foreshortening term -theta_dot^2 q2^T D q2 / 2.

The point cloud and matrices here are synthetic but consistent (every matrix is the point-cloud
sum of its integrand), so these tests check the algebra of the models independently of the mode
shapes and quadrature. Every test runs on a cloud whose last point is a point mass and on one
whose last point carries a tip body's rotary inertia ``Jt`` (turning with the slope ``dF2t . q2``,
kinetic energy ``Jt (theta' + dF2t . q2')^2 / 2``, docs/tip-body.md).
"""

import numpy as np
import pytest

from hubbeam.core import eom
from hubbeam.core.inputs import SimulationInputs, Trajectory
from hubbeam.core.integrate import N_SCALAR, fill_outputs, integration_problem, n_output_columns
from hubbeam.core.maneuver import PRESCRIBED, TORQUE
from hubbeam.core.radau import problem_rhs
from hubbeam.model.maneuvers import maneuver_from_dict
from hubbeam.model.matrices import SystemMatrices
from hubbeam.model.models import MODELS

#: the kernels' traits of every model
TRAITS = {name: m.traits for name, m in MODELS.items()}

# The synthetic cloud uses the package's own SystemMatrices type: numba's on-disk cache records
# the argument types of every compiled signature, and a type defined in a test module would make
# that cache unreadable to any process that cannot import the test module.
Cloud = SystemMatrices


def _spd(rng, n, scale):
    a = rng.normal(size=(n, n))
    return scale * (a @ a.T + n * np.eye(n))


def make_cloud(n=3, npts=9, seed=0, tip_mass=0.3, rotary_inertia=0.0):
    rng = np.random.default_rng(seed)
    rA = 0.5
    x = np.sort(rng.uniform(0.0, 8.0, npts))
    w = rng.uniform(0.05, 0.3, npts)
    x = np.append(x, 6.0)
    w = np.append(w, tip_mass)
    F1 = rng.normal(size=(npts + 1, n))
    F2 = rng.normal(size=(npts + 1, n))
    S = np.array([_spd(rng, n, 0.1) for _ in range(npts + 1)])
    r = rA + x
    return Cloud(
        Jh=200.0,
        Jb=float(np.sum(w * r**2)),
        K1=_spd(rng, n, 50.0),
        K2=_spd(rng, n, 2.0),
        M1=np.einsum("k,ki,kj->ij", w, F1, F1),
        M2=np.einsum("k,ki,kj->ij", w, F2, F2),
        V1=np.einsum("k,ki->i", w * r, F1),
        V2=np.einsum("k,ki->i", w * r, F2),
        D=np.einsum("k,kij->ij", w * r, S),
        R=np.einsum("k,ki,kj->ij", w, F1, F2),
        rA=rA,
        x=x,
        w=w,
        F1=F1,
        F2=F2,
        S=S,
        f1L=F1[-1].copy(),
        f2L=F2[-1].copy(),
        SL=S[-1].copy(),
        Jt=rotary_inertia,
        dF2t=rng.normal(size=n),
    )


def split(y, n):
    return y[0], y[1 : 1 + n], y[1 + n :]


def exact_kinetic_energy(sm, y, v):
    """Eqs. (8)-(9): T = Jh thd^2/2 + sum_k w_k |r_k'|^2 / 2 on the point cloud."""
    n = sm.M1.shape[0]
    _, q1, q2 = split(y, n)
    thd, q1d, q2d = split(v, n)
    Sq2 = np.einsum("kij,j->ki", sm.S, q2)
    X = sm.rA + sm.x + sm.F1 @ q1 - 0.5 * Sq2 @ q2
    Y = sm.F2 @ q2
    Xd = sm.F1 @ q1d - Sq2 @ q2d
    Yd = sm.F2 @ q2d
    speed2 = (Xd - thd * Y) ** 2 + (Yd + thd * X) ** 2
    rotation = thd + sm.dF2t @ q2d  # the tip body's angular rate
    return 0.5 * sm.Jh * thd**2 + 0.5 * np.sum(sm.w * speed2) + 0.5 * sm.Jt * rotation**2


def truncated_kinetic_energy(sm, y, v, order=2):
    """The part of the exact T of order <= ``order`` in (q, q') (theta, theta_dot are O(1))."""
    n = sm.M1.shape[0]
    eps = np.array([0.5, 1.0, 1.5, 2.0, 2.5])
    scale = np.concatenate([[1.0], np.full(2 * n, 1.0)])
    vals = []
    for e in eps:
        s = scale.copy()
        s[1:] = e
        vals.append(exact_kinetic_energy(sm, y * s, v * s))
    coeffs = np.linalg.solve(np.vander(eps, 5, increasing=True), np.array(vals))
    return float(np.sum(coeffs[: order + 1]))


def tlam_kinetic_energy(sm, y, v):
    n = sm.M1.shape[0]
    _, _, q2 = split(y, n)
    return truncated_kinetic_energy(sm, y, v) + 0.5 * v[0] ** 2 * q2 @ sm.D @ q2


def lagrange_equations(T, sm, y, v, h=1e-5):
    """M and F of Lagrange's equations of kinetic energy T (numerical derivatives)."""
    N = y.size
    n = sm.M1.shape[0]
    eye = np.eye(N)

    def mass(yy):  # T is quadratic in v: polarisation gives M(y) exactly
        t = np.array([T(sm, yy, eye[i]) for i in range(N)])
        return np.array([[T(sm, yy, eye[i] + eye[j]) - t[i] - t[j] for j in range(N)] for i in range(N)])

    M = mass(y)

    def p(yy):  # generalised momentum dT/dv = M(y) v
        return mass(yy) @ v

    dp_dt = (p(y + h * v) - p(y - h * v)) / (2 * h)  # (d/dy (M v)) v
    dT_dy = np.array([(T(sm, y + h * eye[i], v) - T(sm, y - h * eye[i], v)) / (2 * h) for i in range(N)])
    K = np.zeros((N, N))
    K[1 : 1 + n, 1 : 1 + n] = sm.K1
    K[1 + n :, 1 + n :] = sm.K2
    F = -(dp_dt - dT_dy) - K @ y
    return M, F


def jitted_system(model, sm, y, v, tau=0.0):
    N = y.size
    M = np.empty((N, N))
    F = np.empty(N)
    eom.mass_matrix_and_force(model, y, v, tau, sm, M, F)
    return M, F


def rotary_mass(sm):
    """The mass matrix of the tip body's rotation, ``Jt e^T e`` with ``e = (1, 0, dF2t)``."""
    n = sm.M1.shape[0]
    e = np.concatenate([[1.0], np.zeros(n), sm.dF2t])
    return sm.Jt * np.outer(e, e)


def paper_foam(sm, y, v, tau, with_D=True):
    """Plain numpy transcription of Eqs. (24)-(34) (FOAM) and of TLAM (with_D=False), with the
    tip body's rotary inertia."""
    n = sm.M1.shape[0]
    _, q1, q2 = split(y, n)
    thd, q1d, q2d = split(v, n)
    c = 1.0 if with_D else 0.0
    M_thth = sm.Jh + sm.Jb + q1 @ sm.M1 @ q1 + q2 @ sm.M2 @ q2 + 2 * sm.V1 @ q1 - c * q2 @ sm.D @ q2
    M_thq1 = -q2 @ sm.R.T
    M_thq2 = sm.V2 + q1 @ sm.R
    M = np.block(
        [
            [np.array([[M_thth]]), M_thq1[None, :], M_thq2[None, :]],
            [M_thq1[:, None], sm.M1, np.zeros((n, n))],
            [M_thq2[:, None], np.zeros((n, n)), sm.M2],
        ]
    ) + rotary_mass(sm)
    G = np.block(
        [
            [np.zeros((1, 1)), np.zeros((1, n)), np.zeros((1, n))],
            [np.zeros((n, 1)), np.zeros((n, n)), -sm.R],
            [np.zeros((n, 1)), sm.R.T, np.zeros((n, n))],
        ]
    )
    K = np.block(
        [
            [np.zeros((1, 1)), np.zeros((1, n)), np.zeros((1, n))],
            [np.zeros((n, 1)), sm.K1 - thd**2 * sm.M1, np.zeros((n, n))],
            [np.zeros((n, 1)), np.zeros((n, n)), sm.K2 - thd**2 * sm.M2 + c * thd**2 * sm.D],
        ]
    )
    Q_theta = -2 * thd * (q1 @ sm.M1 @ q1d + q2 @ sm.M2 @ q2d + sm.V1 @ q1d - c * q2 @ sm.D @ q2d)
    Q = np.concatenate([[Q_theta + tau], thd**2 * sm.V1, np.zeros(n)])
    F = Q - 2 * thd * G @ v - K @ y
    return M, F


@pytest.fixture(scope="module", params=[0.0, 7.5], ids=["point_mass", "body"])
def sm(request):
    return make_cloud(rotary_inertia=request.param)


@pytest.fixture(scope="module")
def state():
    rng = np.random.default_rng(42)
    n = 3
    y = np.concatenate([[0.7], 0.05 * rng.normal(size=2 * n)])
    v = np.concatenate([[2.3], 0.2 * rng.normal(size=2 * n)])
    return y, v


@pytest.mark.parametrize("model,with_D", [(TRAITS["FOAM"], True), (TRAITS["TLAM"], False)])
def test_foam_and_tlam_match_numpy_transcription_of_the_paper(sm, state, model, with_D):
    y, v = state
    M, F = jitted_system(model, sm, y, v, tau=12.5)
    M_ref, F_ref = paper_foam(sm, y, v, 12.5, with_D)
    np.testing.assert_allclose(M, M_ref, rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(F, F_ref, rtol=1e-13, atol=1e-11)


def test_sfoam_is_equation_40(sm, state):
    """SFOAM: FOAM with q1 = 0, the q1 rows decoupled, and no Q_theta on the hub row."""
    n = sm.M1.shape[0]
    y, v = state
    y0 = y.copy()
    v0 = v.copy()
    y0[1 : 1 + n] = 0.0
    v0[1 : 1 + n] = 0.0
    M, F = jitted_system(TRAITS["SFOAM"], sm, y0, v0, tau=3.0)
    _, q2 = y0[0], y0[1 + n :]
    thd = v0[0]
    hub = [0] + list(range(1 + n, 1 + 2 * n))
    M40 = np.block(
        [
            [np.array([[sm.Jh + sm.Jb + q2 @ (sm.M2 - sm.D) @ q2]]), sm.V2[None, :]],
            [sm.V2[:, None], sm.M2],
        ]
    ) + rotary_mass(sm)[np.ix_(hub, hub)]
    F40 = np.concatenate([[3.0], -(sm.K2 - thd**2 * sm.M2 + thd**2 * sm.D) @ q2])
    np.testing.assert_allclose(M[np.ix_(hub, hub)], M40, rtol=1e-13)
    np.testing.assert_allclose(F[hub], F40, rtol=1e-13, atol=1e-12)
    np.testing.assert_array_equal(M[0, 1 : 1 + n], 0.0)


@pytest.mark.parametrize(
    "model,kinetic_energy",
    [
        (TRAITS["CFOAM"], exact_kinetic_energy),
        (TRAITS["FOAM"], truncated_kinetic_energy),
        (TRAITS["TLAM"], tlam_kinetic_energy),
    ],
)
def test_models_are_lagrange_equations_of_their_kinetic_energy(sm, state, model, kinetic_energy):
    y, v = state
    M, F = jitted_system(model, sm, y, v)
    M_ref, F_ref = lagrange_equations(kinetic_energy, sm, y, v)
    scale_F = np.max(np.abs(F_ref))
    np.testing.assert_allclose(M, M_ref, rtol=1e-9, atol=1e-9 * np.max(np.abs(M_ref)))
    np.testing.assert_allclose(F, F_ref, rtol=0, atol=2e-7 * scale_F)


def test_cfoam_minus_foam_is_of_second_order_in_the_elastic_coordinates(sm, state):
    """Dropping CFOAM's cubic and quartic kinetic-energy terms gives FOAM exactly (note 5)."""
    y, v = state
    ratios = []
    for eps in (1e-1, 1e-2, 1e-3):
        ys = y.copy()
        vs = v.copy()
        ys[1:] *= eps
        vs[1:] *= eps
        Mc, Fc = jitted_system(TRAITS["CFOAM"], sm, ys, vs)
        Mf, Ff = jitted_system(TRAITS["FOAM"], sm, ys, vs)
        ratios.append(np.max(np.abs(Fc - Ff)) / eps**2)
        # the mass matrices differ by quadratic terms in q only
        assert np.max(np.abs(Mc - Mf)) < 50 * eps**2 * np.max(np.abs(Mf[1:, 1:]))
    # F difference is O(eps^2): the ratio settles to a constant (not O(1/eps))
    assert ratios[2] == pytest.approx(ratios[1], rel=0.05)


def test_energy_is_half_v_M_v_plus_strain_energy(sm, state):
    y, v = state
    n = sm.M1.shape[0]
    U = 0.5 * y[1 : 1 + n] @ sm.K1 @ y[1 : 1 + n] + 0.5 * y[1 + n :] @ sm.K2 @ y[1 + n :]
    assert eom.energy(TRAITS["CFOAM"], y, v, sm) == pytest.approx(exact_kinetic_energy(sm, y, v) + U, rel=1e-13)
    assert eom.energy(TRAITS["FOAM"], y, v, sm) == pytest.approx(truncated_kinetic_energy(sm, y, v) + U, rel=1e-10)
    dv = np.zeros_like(v)
    dv[0] = 0.1  # T is quadratic in v: the central difference is exact
    p_ref = (exact_kinetic_energy(sm, y, v + dv) - exact_kinetic_energy(sm, y, v - dv)) / 0.2
    assert eom.angular_momentum(TRAITS["CFOAM"], y, v, sm) == pytest.approx(p_ref, rel=1e-12)


def test_accelerations_solve_the_equations_with_constraints(sm, state):
    n = sm.M1.shape[0]
    y, v = state
    mp = np.array([3.0, 30.0])
    for model in TRAITS.values():
        for kind in (PRESCRIBED, TORQUE):
            yy, vv = y.copy(), v.copy()
            a = np.zeros_like(y)
            free = eom.free_dofs(model, kind, n)
            inputs = SimulationInputs(model, kind, mp, _undamped(sm), sm)
            torque, q_theta = eom.accelerations(inputs, 7.0, yy, vv, free, a)
            M, F = jitted_system(model, sm, yy, vv)
            residual = M @ a - F  # F without torque: the hub row's residual is the torque
            elastic = free[free > 0]
            np.testing.assert_allclose(residual[elastic], 0.0, atol=1e-9 * np.max(np.abs(F)))
            if model.hub_velocity_force:
                assert q_theta == pytest.approx(F[0], rel=1e-12)
            assert residual[0] == pytest.approx(torque, rel=1e-9, abs=1e-9)
            if not model.keeps_axial:
                assert np.all(yy[1 : 1 + n] == 0.0) and np.all(a[1 : 1 + n] == 0.0)


def test_high_order_terms_vanish_to_second_order(sm, state):
    y, v = state
    a = np.ones_like(y)
    N = y.size
    dQ = np.empty_like(y)
    Mc, Fc, Mf, Ff = np.empty((N, N)), np.empty(N), np.empty((N, N)), np.empty(N)
    sizes = []
    for eps in (1e-2, 1e-3):
        ys, vs, as_ = y.copy(), v.copy(), a.copy()
        ys[1:] *= eps
        vs[1:] *= eps
        as_[1:] *= eps
        eom.mass_matrix_and_force(TRAITS["CFOAM"], ys, vs, 3.0, sm, Mc, Fc)
        inputs = SimulationInputs(TRAITS["CFOAM"], TORQUE, np.zeros(2), _undamped(sm), sm)
        dM = eom.high_order_terms(Mc, Fc, 3.0, (ys, vs, as_), inputs, Mf, Ff, dQ)
        sizes.append((abs(dM), np.max(np.abs(dQ))))
    # Delta M_thth (Eq. 35) is cubic in q; the dropped generalised forces are quadratic
    assert sizes[1][0] == pytest.approx(sizes[0][0] / 1000, rel=0.05)
    assert sizes[1][1] == pytest.approx(sizes[0][1] / 100, rel=0.05)


#: every maneuver kind (hubbeam.model.maneuvers), each with rows around the times the tests use
MANEUVERS = [
    {"kind": "prescribed", "wf": 2.8, "tf": 30.0},
    {"kind": "torque", "tau_max": 200.0, "tf": 10.0},
    {"kind": "speed_table", "time": [0.0, 2.0, 5.0, 9.0], "speed": [0.0, 1.0, 2.5, 2.0]},
    {"kind": "torque_table", "time": [0.5, 3.0, 8.0], "torque": [10.0, -40.0, 5.0]},
    {"kind": "pd", "kp": 300.0, "kd": 80.0,
     "reference": {"kind": "angle_table", "time": [0.0, 3.0, 6.0], "angle": [0.0, 1.0, 1.5]}},
    {"kind": "pd", "kp": 300.0, "kd": 80.0,
     "reference": {"kind": "prescribed", "wf": 1.0, "tf": 8.0}},
]


def _label(maneuver):
    return maneuver["kind"] + maneuver.get("reference", {}).get("kind", "")


def _undamped(sm):
    n = sm.M1.shape[0]
    return np.zeros((2, n, n))


def _damping(sm):
    """Symmetric positive semi-definite damping matrices of the size of ``sm``."""
    n = sm.M1.shape[0]
    B = np.random.default_rng(11).normal(size=(2, n, n))
    return np.ascontiguousarray(0.05 * np.einsum("bij,bkj->bik", B, B))


#: a command shaper (hubbeam.core.shaping) whose delayed copies fall on both sides of the knots
SHAPER = np.array([[0.0, 1.3, 3.1], [0.3, 0.5, 0.2]])


@pytest.mark.parametrize("maneuver", MANEUVERS, ids=_label)
@pytest.mark.parametrize("model", TRAITS.values(), ids=TRAITS)
@pytest.mark.parametrize("amplitude", [0.05, 2.0])
@pytest.mark.parametrize("damped", [False, True])
@pytest.mark.parametrize("shaped", [False, True])
def test_integrator_rhs_equals_the_general_solve(sm, state, maneuver, model, amplitude, damped, shaped):
    """The integrator's right-hand side -- foam_rhs (modal mass inverted once, hub row by a Schur
    complement) or cfoam_rhs (pre-contracted tensors) -- equals accelerations (full mass matrix
    from the point cloud, Cholesky), also far outside the small-deformation range, unshaped and
    under a shaped command."""
    n = sm.M1.shape[0]
    kind, mp = maneuver_from_dict(maneuver).kernel_parameters()
    C = _damping(sm) if damped else _undamped(sm)
    y, v = state
    y = np.concatenate([y[:1], amplitude / 0.05 * y[1:]])
    free = eom.free_dofs(model, kind, n)
    a_ref = np.zeros_like(y)
    yy, vv = y.copy(), v.copy()  # constrained entries overwritten by the maneuver
    inputs = SimulationInputs(model, kind, mp, C, sm)
    if shaped:
        inputs = inputs._replace(shaper=SHAPER)
    eom.accelerations(inputs, 4.0, yy, vv, free, a_ref)
    a = np.full(free.size, np.nan)
    problem_rhs(4.0, yy[free], vv[free], a, integration_problem(inputs))
    np.testing.assert_allclose(a, a_ref[free], rtol=1e-12, atol=1e-12 * np.max(np.abs(a_ref)))


def test_outputs_give_energy_and_momentum_of_the_state(sm, state):
    n = sm.M1.shape[0]
    y, v = state
    mp = np.array([200.0, 10.0])
    for model in TRAITS.values():
        free = eom.free_dofs(model, TORQUE, n)
        yy, vv, a = y.copy(), v.copy(), np.zeros_like(y)
        ws = eom.workspace(sm, free)
        inputs = SimulationInputs(model, TORQUE, mp, _undamped(sm), sm)
        tau = eom.impose_constraints(inputs, 4.0, yy, vv, a)
        eom.mass_matrix_and_force(model, yy, vv, tau, sm, ws.M, ws.F)
        torque, q_theta, e, p = eom.outputs(inputs, tau, yy, vv, free, a, ws)
        assert e == pytest.approx(eom.energy(model, yy, vv, sm), rel=1e-13)
        assert p == pytest.approx(eom.angular_momentum(model, yy, vv, sm), rel=1e-13)
        assert torque == pytest.approx(200.0 * np.sin(2 * np.pi * 4.0 / 10.0), rel=1e-13)


@pytest.mark.parametrize("maneuver", MANEUVERS, ids=_label)
@pytest.mark.parametrize("model", TRAITS.values(), ids=TRAITS)
def test_dataset_outputs_equal_the_general_equations(sm, state, maneuver, model):
    """fill_outputs (CFOAM from the pre-contracted tensors) against the point-cloud equations of
    eom, output by output, at states far outside the small-deformation range too."""
    n = sm.M1.shape[0]
    N = 1 + 2 * n
    kind, mp = maneuver_from_dict(maneuver).kernel_parameters()
    C = _damping(sm)
    y, v = state
    free = eom.free_dofs(model, kind, n)
    t = np.array([1.0, 4.0, 12.0])
    scales = np.array([1.0, 10.0, 40.0])[:, None]
    y_out = np.ascontiguousarray(scales * y[free])
    v_out = np.ascontiguousarray(scales * v[free])
    out = np.empty((t.size, n_output_columns(n)))
    inputs = SimulationInputs(model, kind, mp, C, sm)
    fill_outputs(inputs, free, Trajectory(t, y_out, v_out), out)
    expected = np.full_like(out, np.nan)
    ws = eom.workspace(sm, free)
    Mf, Ff, dQ = np.empty((N, N)), np.empty(N), np.empty(N)
    for k in range(t.size):
        yy, vv, a = np.zeros(N), np.zeros(N), np.zeros(N)
        yy[free], vv[free] = y_out[k], v_out[k]
        tau = eom.impose_constraints(inputs, t[k], yy, vv, a)
        eom.mass_matrix_and_force(model, yy, vv, tau, sm, ws.M, ws.F)
        eom.add_damping(C, vv, ws.F)
        torque, q_theta, e, p = eom.outputs(inputs, tau, yy, vv, free, a, ws)
        dissipation = vv[1:1 + n] @ C[0] @ vv[1:1 + n] + vv[1 + n:] @ C[1] @ vv[1 + n:]
        q1, q2 = yy[1:1 + n], yy[1 + n:]  # the body's centre is the last point of the cloud
        body = (sm.F2[-1] @ q2, sm.F1[-1] @ q1 - 0.5 * q2 @ sm.S[-1] @ q2)
        expected[k, :N_SCALAR] = (yy[0], vv[0], a[0], torque, q_theta,
                                  *eom.tip_outputs(yy, sm), e, p, dissipation, *body, np.nan, np.nan)
        expected[k, N_SCALAR:N_SCALAR + 2 * n] = yy[1:]
        if model.exact_kinetic_energy:
            dM = eom.high_order_terms(ws.M, ws.F, tau, (yy, vv, a), inputs, Mf, Ff, dQ)
            expected[k, N_SCALAR + 2 * n:] = (dM, *dQ)
    assert np.array_equal(np.isnan(out), np.isnan(expected))
    # every column to rounding error of its own size
    size = np.nanmax(np.abs(expected), axis=0, initial=0.0)
    bound = np.broadcast_to(1e-11 * size + 1e-300, out.shape)
    np.testing.assert_array_less(np.nan_to_num(np.abs(out - expected)), bound)

"""The Radau IIA kernel (``hubbeam.core.radau``) on problems with closed-form solutions.

* the coefficients are those of the 3-stage Radau IIA method (order conditions, transformation);
* the dense output reproduces quintic polynomials exactly;
* with fixed steps the method converges with order 5 in positions and velocities;
* the embedded error estimate behaves as O(h^4) and bounds the true local error;
* on a stiff, damped, coupled linear oscillator (frequencies 1 to 3e4 rad/s) the adaptive
  integrator follows the exact solution at a small multiple of the tolerance with steps set by
  the slow motion; the global error shrinks with the tolerance;
* divergence, the step budget and a finite-time blow-up end the run with a status, not an error.

All problems use ``radau.ForcedOscillator``: ``y'' = -K y - C y' + g cos(omega t) + 2 nl y y'``.
"""

import math
from collections import namedtuple

import numpy as np
import pytest

from hubbeam.core import radau
from hubbeam.core.inputs import IntegratorSettings, Trajectory


def tan_problem():
    """``y'' = 2 y y'`` with y(0) = 0, y'(0) = 1: ``y = tan t``, ``y' = 1 + tan^2 t``."""
    zero = np.zeros((1, 1))
    return radau.ForcedOscillator(zero, zero.copy(), np.zeros(1), 0.0, 1.0)


def run(problem, y0, v0, t_out, rtol=1e-8, atol=1e-10, *, h_init=0.0, fixed_step=False,
        watch=None, watch_limit=np.inf, max_steps=10**6, t_stops=None):
    t_stops = np.empty(0) if t_stops is None else t_stops
    n = len(y0)
    y_out = np.empty((len(t_out), n))
    v_out = np.empty((len(t_out), n))
    stats = np.zeros(len(radau.STAT_NAMES), np.int64)
    watch = np.zeros(n) if watch is None else np.asarray(watch, float)
    settings = IntegratorSettings(float(rtol), float(atol), float(watch_limit), int(max_steps),
                                  float(h_init), bool(fixed_step))
    status, t_stop = radau.radau5(problem, (np.asarray(y0, float), np.asarray(v0, float)), t_stops,
                                  settings, watch, Trajectory(np.asarray(t_out, float), y_out, v_out),
                                  stats)
    return status, t_stop, y_out, v_out, stats


# --------------------------------------------------------------------------- coefficients
def test_coefficients_satisfy_the_radau_iia_order_conditions():
    c, A = radau.C, radau.A_RADAU
    assert c[2] == 1.0 and np.allclose(np.sort(c), c)
    b = A[2]  # stiffly accurate: the last stage is the solution
    for k in range(1, 6):  # B(5): quadrature of order 5
        assert np.isclose(b @ c ** (k - 1), 1.0 / k, rtol=0, atol=1e-14)
    for k in range(1, 4):  # C(3): stage order 3
        assert np.allclose(A @ c ** (k - 1), c**k / k, rtol=0, atol=1e-14)


def test_transformation_block_diagonalises_the_inverse_matrix():
    g, a, b = radau.GAMMA, radau.ALPHA, radau.BETA
    lam = np.array([[g, 0, 0], [0, a, b], [0, -b, a]])
    A_inv = np.linalg.inv(radau.A_RADAU)
    assert np.allclose(radau.T_INV_RADAU @ A_inv @ radau.T_RADAU, lam, atol=1e-12)
    # gamma is the real eigenvalue and alpha +- i beta the complex pair of A^-1
    eig = np.linalg.eigvals(A_inv)
    assert np.isclose(eig[np.argmin(abs(eig.imag))].real, radau.GAMMA)
    assert np.isclose(max(eig.imag), radau.BETA)


def test_hermite_interpolation_reproduces_quintic_polynomials():
    rng = np.random.default_rng(1)
    coeffs = rng.normal(size=(6, 3))  # three quintics, one per coordinate
    p = [np.polynomial.Polynomial(coeffs[:, i]) for i in range(3)]
    t0, h = 0.7, 0.4

    def values(t, d):
        return np.array([q.deriv(d)(t) if d else q(t) for q in p])

    y_out, v_out = np.empty(3), np.empty(3)
    for s in (0.0, 0.13, 0.5, 0.91, 1.0):
        radau.hermite_interpolate(s, h, (values(t0, 0), values(t0, 1), values(t0, 2)),
                                  (values(t0 + h, 0), values(t0 + h, 1), values(t0 + h, 2)),
                                  y_out, v_out)
        assert np.allclose(y_out, values(t0 + s * h, 0), rtol=1e-13, atol=1e-13)
        assert np.allclose(v_out, values(t0 + s * h, 1), rtol=1e-12, atol=1e-12)


# --------------------------------------------------------------------------- order
def test_fixed_steps_converge_with_order_five():
    t_out = np.linspace(0.0, 1.0, 11)
    errors = []
    for h in (0.05, 0.025, 0.0125):
        status, _, y, v, stats = run(tan_problem(), [0.0], [1.0], t_out, rtol=1e-13, atol=1e-13,
                                     h_init=h, fixed_step=True)
        assert status == radau.SUCCESS
        assert stats[radau.ACCEPTED] == round(1.0 / h)  # really fixed steps
        errors.append((abs(y[-1, 0] - math.tan(1.0)), abs(v[-1, 0] - 1.0 / math.cos(1.0) ** 2)))
    errors = np.array(errors)
    orders = np.log2(errors[:-1] / errors[1:])
    assert np.all((orders > 4.6) & (orders < 5.6)), orders


def test_error_estimate_is_fourth_order_and_bounds_the_local_error():
    t0 = 0.4
    y0, v0 = np.array([math.tan(t0)]), np.array([1.0 + math.tan(t0) ** 2])
    estimate, local_error = [], []
    for h in (0.04, 0.02, 0.01):
        y1, v1, ey, ev = (np.empty(1) for _ in range(4))
        converged, _ = radau.single_step(tan_problem(), t0, y0, v0, h,
                                         IntegratorSettings(1e-13, 1e-13, np.inf, 1),
                                         (y1, v1, ey, ev))
        assert converged
        estimate.append(np.hypot(ey[0], ev[0]))
        exact = math.tan(t0 + h)
        local_error.append(np.hypot(y1[0] - exact, v1[0] - (1.0 + exact**2)))
    estimate, local_error = np.array(estimate), np.array(local_error)
    est_order = np.log2(estimate[:-1] / estimate[1:])
    true_order = np.log2(local_error[:-1] / local_error[1:])
    assert np.all((est_order > 3.6) & (est_order < 4.4)), est_order  # O(h^4) estimate
    assert np.all((true_order > 5.4) & (true_order < 6.6)), true_order  # O(h^6) local error
    assert np.all(estimate > local_error)


# --------------------------------------------------------------------------- stiff oscillator
class GyroscopicOscillator:
    """``y'' + (D + G) y' + K y = g cos(Omega t)``: slow and stiff modes coupled by a skew
    (Coriolis-like) matrix G, as the axial modes of the hub-beam are driven by the transverse ones.

    The closed-form solution is the steady forced response plus free vibrations of the slow
    eigenmodes only, so the stiff modes carry no free oscillation of their own (they follow the
    slow motion, like the hub-beam's axial modes).
    """

    def __init__(self, omega, zeta, coupling, g, Omega, slow_amplitudes):
        n = len(omega)
        self.K = np.diag(np.asarray(omega, float) ** 2)
        self.C = np.diag(2.0 * np.asarray(zeta) * omega) + coupling - coupling.T
        self.problem = radau.ForcedOscillator(self.K, self.C, np.asarray(g, float), float(Omega),
                                              0.0)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-self.K, -self.C]])
        b = np.concatenate([np.zeros(n), g])
        self.P = np.linalg.solve(1j * Omega * np.eye(2 * n) - A, b)  # forced: Re(P e^{i W t})
        self.Omega = Omega
        lam, vec = np.linalg.eig(A)
        slow = [k for k in np.argsort(abs(lam)) if lam[k].imag > 0][:len(slow_amplitudes)]
        self.lam, self.vec = lam[slow], vec[:, slow] * np.asarray(slow_amplitudes)
        self.n = n

    def exact(self, t):
        t = np.asarray(t)[:, None]
        z = np.real(self.P * np.exp(1j * self.Omega * t))
        z += 2.0 * np.real(np.exp(t * self.lam) @ self.vec.T)
        return z[:, :self.n], z[:, self.n:]


@pytest.fixture(scope="module")
def stiff():
    """Frequencies 1, 3, 3e3, 3e4 rad/s (stiffness ratio 1e9, like the axial/transverse split)."""
    coupling = np.zeros((4, 4))
    coupling[0, 2], coupling[1, 3], coupling[0, 3], coupling[0, 1] = 2.0, 1.0, 0.5, 0.3
    return GyroscopicOscillator([1.0, 3.0, 3e3, 3e4], [0.02, 0.01, 0.0, 0.001], coupling,
                                g=[0.5, 0.2, 3e4, 1e6], Omega=0.7, slow_amplitudes=[0.3, 0.1])


@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_stiff_oscillator_follows_the_exact_solution(stiff, rtol):
    t_out = np.linspace(0.0, 20.0, 2001)
    y0, v0 = stiff.exact(t_out[:1])
    status, t_stop, y, v, stats = run(stiff.problem, y0[0], v0[0], t_out, rtol=rtol,
                                      atol=1e-2 * rtol)
    assert status == radau.SUCCESS and t_stop == 20.0
    y_exact, v_exact = stiff.exact(t_out)
    # global error at a small multiple of the tolerance, on every output point (dense output)
    assert np.max(abs(y - y_exact)) < 10 * rtol * np.max(abs(y_exact))
    assert np.max(abs(v - v_exact)) < 10 * rtol * np.max(abs(v_exact))
    # the step follows the slow motion: an explicit method would need h < ~3 / 3e4 s for
    # stability alone, i.e. > 2e5 steps; ask for 20 times fewer
    assert stats[radau.ACCEPTED] < 20.0 / (3.0 / 3e4) / 20


def test_global_error_shrinks_with_the_tolerance():
    t_out = np.linspace(0.0, 1.2, 13)
    errors, steps = [], []
    for rtol in (1e-5, 1e-7, 1e-9, 1e-11):
        status, _, y, _, stats = run(tan_problem(), [0.0], [1.0], t_out, rtol=rtol, atol=rtol)
        assert status == radau.SUCCESS
        errors.append(np.max(abs(y[:, 0] - np.tan(t_out))))
        steps.append(stats[radau.ACCEPTED])
    assert all(e < rtol * np.tan(1.2) for e, rtol in zip(errors, (1e-5, 1e-7, 1e-9, 1e-11)))
    assert np.all(np.diff(errors) < 0) and np.all(np.diff(steps) > 0)
    # error ~ rtol^(5/4) at fixed order 5 with an O(h^4) estimate: 4 decades -> > 3 decades
    assert errors[0] / errors[-1] > 1e3


# --------------------------------------------------------------------------- stopping
def test_watched_quantity_beyond_its_limit_stops_the_run_as_left_range():
    unstable = radau.ForcedOscillator(-np.eye(1), np.zeros((1, 1)), np.zeros(1), 0.0, 0.0)
    t_out = np.linspace(0.0, 10.0, 1001)  # y = sinh t passes 10 at t = asinh(10) = 2.998
    status, t_stop, y, v, _ = run(unstable, [0.0], [1.0], t_out, watch=[1.0], watch_limit=10.0)
    assert status == radau.LEFT_RANGE
    assert math.asinh(10.0) <= t_stop < math.asinh(10.0) + 0.5
    valid = t_out <= t_stop
    assert np.all(np.isnan(y[~valid])) and np.all(np.isnan(v[~valid]))
    assert np.allclose(y[valid, 0], np.sinh(t_out[valid]), rtol=1e-6, atol=1e-9)


def test_step_budget_ends_the_run_with_a_status():
    t_out = np.linspace(0.0, 1.0, 11)
    status, t_stop, y, _, stats = run(tan_problem(), [0.0], [1.0], t_out, max_steps=5)
    assert status == radau.TOO_MANY_STEPS and 0.0 <= t_stop < 1.0
    assert stats[radau.ACCEPTED] + stats[radau.REJECTED] + stats[radau.NEWTON_FAILURES] == 5
    assert np.isnan(y[-1, 0]) and y[0, 0] == 0.0


def test_finite_time_blow_up_ends_the_run_with_a_status():
    t_out = np.linspace(0.0, 2.0, 21)  # tan t is singular at pi/2
    status, t_stop, y, _, _ = run(tan_problem(), [0.0], [1.0], t_out, rtol=1e-6, atol=1e-6)
    assert status in (radau.NON_FINITE, radau.STEP_UNDERFLOW)
    assert abs(t_stop - math.pi / 2) < 1e-3
    assert np.all(np.isnan(y[t_out > math.pi / 2]))
    assert np.allclose(y[t_out < 1.5, 0], np.tan(t_out[t_out < 1.5]), rtol=1e-5)


def test_stops_inside_the_span_leave_the_solution_unchanged():
    """Steps that land on stops (and on output times) follow the same solution."""
    t_out = np.linspace(0.0, 1.0, 11)
    _, _, y_plain, _, stats_plain = run(tan_problem(), [0.0], [1.0], t_out, rtol=1e-10,
                                        atol=1e-10)
    stops = np.array([-1.0, 0.3337, 0.5, 0.8, 1.0, 3.0])  # those outside (0, 1) are ignored
    status, _, y_stops, _, stats = run(tan_problem(), [0.0], [1.0], t_out, rtol=1e-10,
                                       atol=1e-10, t_stops=stops)
    assert status == radau.SUCCESS
    assert np.allclose(y_stops, y_plain, rtol=1e-8)
    assert stats[radau.ACCEPTED] > stats_plain[radau.ACCEPTED]


def test_problem_rhs_dispatches_on_the_registered_problem_type():
    n = 3
    rng = np.random.default_rng(5)
    problem = radau.ForcedOscillator(np.diag([1.0, 4.0, 9.0]), 0.1 * np.eye(n), np.ones(n), 2.0,
                                     0.0)
    y, v = rng.normal(size=(2, n))
    a = np.empty(n)
    radau.problem_rhs(0.3, y, v, a, problem)  # from Python: the registered rhs
    expected = np.cos(2.0 * 0.3) - problem.K @ y - problem.C @ v
    np.testing.assert_allclose(a, expected, rtol=1e-14)
    Unregistered = namedtuple("Unregistered", "K")
    with pytest.raises(TypeError, match="no right-hand side is registered"):
        radau.registered_rhs(Unregistered)
    with pytest.raises(TypeError, match="expected a namedtuple class"):
        radau.register_rhs(dict, radau.forced_oscillator_rhs)

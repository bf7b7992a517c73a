"""Linear state-space models about a steady spin (``hubbeam.linear``).

* the assembled and the Jacobian routes agree to the accuracy of the central differences, every
  model, with and without tip mass and damping, at rest, at a middle speed and near TLAM's
  critical speed; the steady spin needs no torque;
* limits with a closed form: a very heavy hub gives the held-hub frequencies of
  ``hubbeam.model.linearised`` (error falling like 1/Jh), no hub inertia and radius give the
  pinned-free beam (tan(beta L) = tanh(beta L)), the paper's hub gives the roots of the frequency
  equation of a uniform beam clamped to a rigid hub of inertia Jh at radius rA;
* the collocated identity: the zeros of hub torque -> hub angle are the poles of the
  prescribed-hub model, and for TLAM and FOAM the gyroscopic frequencies of ``linearised.py``;
* modal damping at rest with the hub held gives each mode its ratio;
* the tip's acceleration at rest is the second derivative of its arc position (feedthrough from
  the torque included);
* linear against nonlinear: a hub-torque pulse from rest (the relative difference quarters when
  the pulse halves) and from a steady spin at the linearisation's speed (it halves);
* python-control accepts the StateSpace (bode, poles, zeros, names); bad input is refused by name.
"""

import dataclasses
import re

import control as ct
import matplotlib
import matplotlib.pyplot
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.io import loadmat
from scipy.linalg import eig, eigh
from scipy.optimize import brentq, linear_sum_assignment

from benchmarks.linear import linear_rows
from hubbeam.linear import HUBS, OUTPUTS, linear_model, plant
from hubbeam.linear.export import to_dataset, write_dataset, write_mat
from hubbeam.linear.jacobian import (
    RELATIVE_STEP,
    coordinate_scales,
    jacobian_model,
    nonlinear_accelerations,
    steady_state,
)
from hubbeam.model.damping import damping_from_dict, damping_matrices
from hubbeam.model.eigen import critical_speed
from hubbeam.model.linearised import axial_stretch, frequencies
from hubbeam.model.matrices import assemble
from hubbeam.model.models import MODELS
from hubbeam.model.parameters import BeamParameters, TipMass
from hubbeam.model.plant import Plant
from hubbeam.results.io import open_result
from hubbeam.simulation.simulate import simulate

EPS = np.finfo(float).eps
TIP = TipMass(mass=0.5, position=8.0)
#: a tip body: the mass with rotary inertia and its centre beyond the tip (docs/tip-body.md)
BODY = TipMass(mass=0.5, position=8.0, inertia=2.0, offset=0.3)
MODAL = {"kind": "modal", "axial": 0.02, "transverse": 0.05}


@pytest.fixture(scope="module")
def beam(_study_config):
    return BeamParameters.from_config(_study_config)


@pytest.fixture(scope="module")
def matrices(beam):
    cache = {}

    def get(tip=None, n=5):
        if (tip, n) not in cache:
            cache[tip, n] = assemble(beam, tip, n)
        return cache[tip, n]
    return get


def elastic_frequencies(lm, rigid=0):
    """``|Im lambda|`` of the poles, one per pair, ascending, less the ``rigid`` slowest pairs."""
    poles = np.linalg.eigvals(lm.A)
    return np.sort(np.abs(poles.imag))[::2][rigid:]


def scaled(lm, sm):
    """``A`` in the coordinates scaled by :func:`coordinate_scales` (rates by the first bending
    frequency), where its entries are accelerations of comparable size."""
    n = sm.M2.shape[0]
    kept = np.arange(1 + 2 * n) if "q1_1" in lm.states else np.r_[0, 1 + n:1 + 2 * n]
    scales = coordinate_scales(sm)[kept]
    S = np.concatenate([scales, scales * np.sqrt(sm.K2[0, 0] / sm.M2[0, 0])])
    return lm.A * S[None, :] / S[:, None]


# --- the two routes ---------------------------------------------------------------------------


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("tip", [None, TIP, BODY], ids=["no_tip", "tip", "body"])
@pytest.mark.parametrize("damping", [None, MODAL], ids=["undamped", "modal"])
@pytest.mark.parametrize("hub", HUBS)
def test_assembled_and_jacobian_routes_agree(beam, matrices, model, tip, damping, hub):
    """Central differences with the step ``eps^(1/3)`` of each coordinate's nonlinearity scale
    have truncation and rounding errors of ``~ eps^(2/3) = 4e-11`` times factors of order one
    (the third derivative over the first in scaled units, the terms that cancel at the operating
    point over the result): per row of the scaled ``A`` the bound ``100 eps^(2/3) = 4e-9`` leaves
    those factors up to 100 (measured: at most 3e-10, CFOAM's foreshortening). ``B`` is linear in
    the input: rounding only, ``100 eps``."""
    sm = matrices(tip)
    C = damping_matrices(damping, sm)
    critical = critical_speed("TLAM", beam, tip, 5, search_max=20.0)
    for speed in (0.0, 0.5 * critical, 0.95 * critical):
        assembled = linear_model(beam, sm, model, speed, hub, C)
        differenced = jacobian_model(beam, sm, model, speed, hub, C)
        a, d = scaled(assembled, sm), scaled(differenced, sm)
        row = np.max(np.abs(a), axis=1, keepdims=True)
        assert np.all(np.abs(a - d) <= 100 * RELATIVE_STEP**2 * row)
        np.testing.assert_allclose(differenced.B, assembled.B, rtol=0,
                                   atol=100 * EPS * np.abs(assembled.B).max())
        np.testing.assert_allclose(differenced.C, assembled.C, rtol=0,
                                   atol=100 * RELATIVE_STEP**2 * np.abs(assembled.C).max())


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("tip", [None, TIP, BODY], ids=["no_tip", "tip", "body"])
def test_steady_spin_needs_no_torque(beam, matrices, model, tip):
    """At the operating point with zero torque every acceleration of the nonlinear equations
    vanishes, damping included (it acts on the elastic rates, zero there): what is left is the
    rounding of the cancelling centrifugal and elastic forces, ``eps`` times ``K1 q1s`` over
    the mass."""
    sm = matrices(tip)
    C = damping_matrices(MODAL, sm)
    speed = 3.0
    traits = MODELS[model]
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(5)
    y, v, kept = steady_state(sm, traits, speed, q1s)
    a = nonlinear_accelerations(traits.traits, sm, C, "free", y, v, 0.0, kept)
    forces = np.abs(sm.K1) @ np.abs(q1s) + speed**2 * np.abs(sm.V1)
    assert np.all(np.abs(a) <= 100 * EPS * max(forces.max(), EPS))


# --- limits with a closed form -------------------------------------------------------------------


@pytest.mark.parametrize("model", ["TLAM", "FOAM"])
def test_heavy_hub_tends_to_the_held_hub(beam, matrices, model):
    """The hub's inertia couples to each mode through ``M_thq2`` and shifts its frequency by a
    relative amount ``c / (Jh + J*)`` (``J*`` of the order of Jb, 77 kg m2 here): ten times the
    inertia, a tenth of the error, up to ``1 + 2 Jb / Jh`` (the next term of the expansion)."""
    sm = matrices(TIP)
    speed = 1.5
    held = frequencies(sm, model, speed, axial=True)
    inertias = (1e4, 1e5, 1e6)
    errors = []
    for Jh in inertias:
        heavy = dataclasses.replace(beam, Jh=Jh)
        free = elastic_frequencies(linear_model(heavy, sm._replace(Jh=Jh), model, speed), rigid=1)
        errors.append(np.max(np.abs(free - held) / held))
    for (J, e), e_next in zip(zip(inertias, errors), errors[1:]):
        assert abs(e / e_next / 10 - 1) <= 2 * sm.Jb / J


def _pinned_free_frequencies(beam, count):
    """Roots of ``tan(beta L) = tanh(beta L)``, one in each ``(k pi, k pi + pi / 2)``, k >= 1."""
    roots = [brentq(lambda z: np.tan(z) - np.tanh(z), k * np.pi, k * np.pi + np.pi / 2 - 1e-9,
                    xtol=1e-15) for k in range(1, count + 1)]
    return (np.array(roots) / beam.L) ** 2 * np.sqrt(beam.EI / beam.rhoA)


def ritz_errors(params, exact, modes=(5, 10, 20)):
    """Relative errors of the free hub's first elastic frequencies at rest (no tip mass) against
    ``exact``, one row per number of modes."""
    errors = []
    for n in modes:
        ritz = elastic_frequencies(linear_model(params, assemble(params, None, n), "FOAM", 0.0),
                                   rigid=1)
        errors.append((ritz[:exact.size] - exact) / exact)
    return np.array(errors)


def test_pinned_free_beam(beam):
    """Omega = 0, rA = 0, Jh = 0, no tip mass: the free hub is a pin. The Ritz basis (the rigid
    rotation and clamped-free modes) misses only the pin's zero root moment, a natural condition,
    so the frequencies are upper bounds that converge algebraically: each doubling of n must
    divide the error of the first four by at least 2^4 (measured: 2^7)."""
    pinned = dataclasses.replace(beam, rA=0.0, Jh=0.0)
    errors = ritz_errors(pinned, _pinned_free_frequencies(pinned, 4))
    assert np.all(errors > -1e-12)  # upper bounds, up to the rounding of the eigenvalues
    assert np.all(errors[1:] <= errors[:-1] / 2**4)


def _hub_beam_frequencies(beam, count):
    """Roots of the frequency equation of a uniform beam clamped to a rigid hub of inertia ``Jh``
    at radius ``rA``, not spinning. ``W = a1 cosh + a2 sinh + a3 cos + a4 sin`` of ``beta x``,
    ``beta^4 = rho A omega^2 / EI``; the conditions (``Theta = W'(0)`` the hub angle):
    ``W(0) = rA W'(0)``, the hub's balance ``-Jh omega^2 W'(0) = EI W''(0) - rA EI W'''(0)``,
    ``W''(L) = W'''(L) = 0``; the determinant of the 4 x 4 system, rows scaled to unit size."""
    EI, L, rA = beam.EI, beam.L, beam.rA

    def basis(beta, k, x):
        z = beta * x
        hyperbolic = (np.cosh(z), np.sinh(z)) if k % 2 == 0 else (np.sinh(z), np.cosh(z))
        trig = ((np.cos(z), np.sin(z)), (-np.sin(z), np.cos(z)), (-np.cos(z), -np.sin(z)),
                (np.sin(z), -np.cos(z)))[k % 4]
        return np.array([*hyperbolic, *trig]) * beta**k

    def determinant(beta):
        omega2 = beta**4 * EI / beam.rhoA
        rows = np.array([basis(beta, 0, 0) - rA * basis(beta, 1, 0),
                         -beam.Jh * omega2 * basis(beta, 1, 0) - EI * basis(beta, 2, 0)
                         + rA * EI * basis(beta, 3, 0),
                         basis(beta, 2, L), basis(beta, 3, L)])
        return np.linalg.det(rows / np.abs(rows).max(axis=1, keepdims=True))

    grid = np.linspace(1e-3, (count + 2) * np.pi / L, 4000)
    values = np.array([determinant(b) for b in grid])
    change = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))[:count]
    betas = np.array([brentq(determinant, grid[i], grid[i + 1], xtol=1e-15) for i in change])
    return betas**2 * np.sqrt(EI / beam.rhoA)


def test_beam_on_a_hub_of_finite_inertia(beam):
    """The paper's hub (Jh, rA) at rest against the closed-form frequency equation: upper bounds
    (Rayleigh-Ritz) whose error falls by at least 2^4 from n = 5 to 10 and by at least 2^3 from 10
    to 20, where the rounding of the eigenvalues (``eps |A| / omega``, 1e-12 relative) starts to
    show (measured: 2^6 and 2^5.4)."""
    errors = ritz_errors(beam, _hub_beam_frequencies(beam, 4))
    assert np.all(errors > -1e-12)
    assert np.all(errors[1] <= errors[0] / 2**4)
    assert np.all(errors[2] <= errors[1] / 2**3)


@pytest.mark.parametrize("tip", [None, TIP], ids=["no_tip", "tip"])
def test_quasi_static_root_moment_and_tip_deflection(beam, tip):
    """At rest a slow hub acceleration ``alpha`` loads the beam with its own inertia,
    ``p(x) = -rho A (rA + x) alpha`` and ``-m_t (rA + l) alpha`` at the tip mass: a cantilever, whose
    root moment is ``EI v''(0) = int p(xi) xi dxi`` and whose tip deflection is ``int p(xi)
    xi^2 (3 L - xi) / (6 EI) dxi``. The prescribed-hub model's response at ``s = 1e-4 i`` rad/s is
    quasi-static to ``(s / omega_1)^2 = 1e-9``. The Ritz series of a second derivative at the
    boundary converges slowly (like ``n^-2``: each doubling of n quarters it; bound: halves), the
    deflection fast (bound: quarters)."""
    L, rA, rhoA, EI = beam.L, beam.rA, beam.rhoA, beam.EI
    mass = 0.0 if tip is None else tip.mass

    def compliance(xi):
        return xi**2 * (3 * L - xi) / (6 * EI)

    moment = -rhoA * (rA * L**2 / 2 + L**3 / 3) - mass * (rA + L) * L
    deflection = quad(lambda xi: -rhoA * (rA + xi) * compliance(xi), 0.0, L)[0] \
        - mass * (rA + L) * compliance(L)
    errors = []
    for n in (5, 10, 20):
        sm = assemble(beam, tip, n)
        plant = linear_model(beam, sm, "FOAM", 0.0, "prescribed",
                             outputs=["root_moment", "tip_deflection"]).to_control()
        gain = ct.evalfr(plant, 1e-4j).real.ravel()
        errors.append(np.abs(gain / [moment, deflection] - 1.0))
    errors = np.array(errors)
    first = np.sqrt(eigh(sm.K2, sm.M2, eigvals_only=True)[0])  # the held beam's, rad s-1
    quasi_static = 2 * (1e-4 / first) ** 2
    assert np.all(errors[1:, 0] <= errors[:-1, 0] / 2 + quasi_static)
    assert np.all(errors[1:, 1] <= errors[:-1, 1] / 4 + quasi_static)


# --- the collocated identity ---------------------------------------------------------------------


def _matched(a, b):
    """``a`` and ``b`` (complex, same size) paired by least total distance."""
    rows, cols = linear_sum_assignment(np.abs(a[:, None] - b[None, :]))
    return a[rows], b[cols]


def conditioned_poles(A):
    """The eigenvalues of ``A`` and their first-order error bounds ``eps |A| kappa`` (``kappa =
    1 / |y^H x|``, unit left and right eigenvectors: the eigenvalue's condition number)."""
    poles, left, right = eig(A, left=True, right=True)
    kappa = 1.0 / np.abs(np.sum(left.conj() * right, axis=0))
    return poles, EPS * np.linalg.norm(A, 2) * kappa


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("tip", [None, TIP], ids=["no_tip", "tip"])
def test_collocated_zeros_are_the_held_hub_poles(beam, matrices, model, tip):
    """Holding the hub angle at zero is holding the hub: the zeros of hub torque -> hub angle are
    the poles of the prescribed-hub model (less its two integrators at 0), and for TLAM and FOAM
    the gyroscopic frequencies of ``linearised.py``; at rest, at half and at 1.2 times TLAM's
    critical speed (an unstable plant there). A backward-stable solver is off by at most about
    its eigenvalue's bound ``eps |A| kappa`` (:func:`conditioned_poles`); bound 10 of it for the
    two computations (python-control's zeros, the eigenvalues)."""
    sm = matrices(tip)
    critical = critical_speed("TLAM", beam, tip, 5, search_max=20.0)
    for speed in (0.0, 0.5 * critical, 1.2 * critical):
        free = linear_model(beam, sm, model, speed, outputs=["hub_angle"]).to_control()
        poles, bound = conditioned_poles(linear_model(beam, sm, model, speed, "prescribed").A)
        elastic = np.argsort(np.abs(poles))[2:]
        rows, cols = linear_sum_assignment(np.abs(poles[elastic][:, None] - ct.zeros(free)))
        zeros, poles, bound = ct.zeros(free)[cols], poles[elastic][rows], bound[elastic][rows]
        assert np.all(np.abs(zeros - poles) <= 10 * bound)
        if model in ("TLAM", "FOAM"):
            reference = frequencies(sm, model, speed, axial=True)
            pair = np.argsort(np.abs(zeros.imag))[::2]  # one of each pair, as the reference
            assert np.all(np.abs(np.abs(zeros.imag[pair]) - reference) <= 10 * bound[pair])


# --- damping, outputs -----------------------------------------------------------------------------


def test_modal_damping_ratio_of_each_held_mode(beam, matrices):
    """At rest with the hub held the axial and transverse blocks decouple and modal damping makes
    each mode ``lambda = omega (-zeta +- i sqrt(1 - zeta^2))`` with ``omega`` an eigenfrequency
    of its block: ``|lambda|`` tells the block, ``-Re lambda / |lambda|`` is its ``zeta``, to the
    eigenvalue's error bound over ``|lambda|`` (:func:`conditioned_poles`, 10 of it)."""
    sm = matrices(TIP)
    damping = {"kind": "modal", "axial": 0.01, "transverse": 0.07}
    held = linear_model(beam, sm, "FOAM", 0.0, "prescribed", damping_matrices(damping, sm))
    poles, bound = conditioned_poles(held.A)
    elastic = np.argsort(np.abs(poles))[2:]
    poles, bound = poles[elastic], bound[elastic]
    blocks = {0.01: np.sqrt(eigh(sm.K1, sm.M1, eigvals_only=True)),
              0.07: np.sqrt(eigh(sm.K2, sm.M2, eigvals_only=True))}
    expected = np.empty(poles.size)
    for zeta, omega in blocks.items():
        of_block = np.min(np.abs(np.abs(poles)[:, None] - omega), axis=1) <= 10 * bound
        expected[of_block] = zeta
        assert np.sum(of_block) == 2 * omega.size
    assert np.all(np.abs(-poles.real / np.abs(poles) - expected) <= 10 * bound / np.abs(poles))


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("hub", HUBS)
def test_tip_acceleration_at_rest_is_the_arc_position_twice_differentiated(beam, matrices,
                                                                            model, hub):
    """At rest the tip's transverse acceleration is ``d^2/dt^2 ((rA + L) theta + v(L))``: with
    ``y = C x``, ``y'' = C A^2 x + C A B u`` (``C B = 0``: positions do not feel the input), so the
    rows must equal ``C_arc A^2`` and ``C_arc A B``, to the rounding of ``A^2`` (``eps |C||A|^2``).
    A free hub has the feedthrough of the torque (the hub's angular acceleration)."""
    lm = linear_model(beam, matrices(TIP), model, 0.0, hub, outputs=["tip_arc", "tip_acceleration"])
    arc, acceleration = lm.C
    scale = 10 * EPS * np.abs(arc).max() * np.linalg.norm(lm.A, 2) ** 2
    np.testing.assert_allclose(acceleration, arc @ lm.A @ lm.A, rtol=0, atol=scale)
    np.testing.assert_allclose(lm.D[1], arc @ lm.A @ lm.B, rtol=1e-12)
    assert lm.D[1, 0] != 0.0 and lm.D[0, 0] == 0.0


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("hub", HUBS)
def test_tip_acceleration_linearises_the_rotating_frame_kinematics(beam, matrices, model, hub):
    """Spinning, the accelerometer's row against central differences of the exact kinematics
    ``a_y = v'' + 2 theta' u' + theta'' (rA + L + u) - theta'^2 v`` at the tip, with the nonlinear
    kernel's accelerations; same steps and bound as the route test (``100 eps^(2/3)`` of the
    row's scaled size)."""
    sm = matrices(TIP)
    traits, speed = MODELS[model], 1.5
    lm = linear_model(beam, sm, model, speed, hub, outputs=["tip_acceleration"])
    q1s = axial_stretch(sm, speed) if traits.keeps_axial else np.zeros(5)
    y0, v0, kept = steady_state(sm, traits, speed, q1s)
    n = 5

    def reading(x, u):
        y, v = y0.copy(), v0.copy()
        y[kept] += x[:kept.size]
        v[kept] += x[kept.size:]
        a = np.zeros(y.size)
        a[kept] = nonlinear_accelerations(traits.traits, sm, np.zeros((2, n, n)), hub, y, v,
                                          u, kept)
        q1, q2 = slice(1, 1 + n), slice(1 + n, 1 + 2 * n)
        return (sm.f2L @ a[q2] + 2 * v[0] * sm.f1L @ v[q1]
                + a[0] * (sm.rA + beam.L + sm.f1L @ y[q1]) - v[0] ** 2 * sm.f2L @ y[q2])

    scales = coordinate_scales(sm)[kept]
    frequency = np.sqrt(sm.K2[0, 0] / sm.M2[0, 0])
    steps = RELATIVE_STEP * np.concatenate([scales, scales * frequency])
    row = np.array([(reading(h * e, 0.0) - reading(-h * e, 0.0)) / (2 * h)
                    for h, e in zip(steps, np.eye(steps.size))])
    u = RELATIVE_STEP * frequency**2 * (sm.Jh + sm.Jb if hub == "free" else 1.0)
    feedthrough = (reading(0 * steps, u) - reading(0 * steps, -u)) / (2 * u)
    size = np.abs(lm.C[0] * steps).max()
    assert np.all(np.abs((row - lm.C[0]) * steps) <= 100 * RELATIVE_STEP**2 * size)
    assert feedthrough == pytest.approx(lm.D[0, 0], rel=100 * RELATIVE_STEP**2)


def test_python_control_accepts_the_model(beam, matrices):
    lm = linear_model(beam, matrices(TIP), "FOAM", 2.0)
    sys = lm.to_control()
    assert sys.state_labels == list(lm.states) and sys.input_labels == ["hub_torque"]
    assert sys.output_labels == list(OUTPUTS)
    assert sys.name == "FOAM_free_hub_2rad_s"
    collocated = sys["hub_angle", "hub_torque"]
    response = ct.frequency_response(collocated, np.logspace(-1, 3, 50))
    assert np.all(np.isfinite(response.magnitude))
    matplotlib.use("Agg")
    ct.bode_plot(response)
    matplotlib.pyplot.close("all")
    assert sys.poles().size == len(lm.states)
    assert ct.zeros(collocated).size == len(lm.states) - 2  # relative degree two
    case = plant(beam, "FOAM", 2.0, tip=TIP, damping={"kind": "modal", "axial": 0.0,
                                                       "transverse": 0.0})
    np.testing.assert_array_equal(case.A, lm.A)  # zero damping is no damping
    single = linear_model(beam, matrices(TIP), "FOAM", 2.0, outputs="tip_deflection")
    assert single.outputs == ("tip_deflection",) and single.C.shape == (1, len(lm.states))
    held = linear_model(beam, matrices(TIP), "SFOAM", 1.5, "prescribed").to_control()
    assert held.input_labels == ["hub_acceleration"] and "q1_1" not in held.state_labels
    assert held.name == "SFOAM_prescribed_hub_1p5rad_s"


@pytest.mark.parametrize(("change", "message"), [
    ({"model": "XFOAM"}, "model = 'XFOAM'; allowed: one of TLAM, FOAM, SFOAM, CFOAM"),
    ({"hub": "clamped"}, "hub = 'clamped'; allowed: one of free, prescribed"),
    ({"outputs": ["tip_deflection", "tip_speed"]}, "outputs = ['tip_deflection', 'tip_speed']"),
    ({"outputs": []}, "outputs = []; allowed: a non-empty list"),
    ({"speed": -1.0}, "speed = -1.0; allowed: a finite hub speed >= 0"),
    ({"speed": float("nan")}, "speed = nan; allowed"),
    ({"damping": np.zeros((2, 3, 3))}, "damping of shape (2, 3, 3); allowed"),
])
def test_bad_input_is_named(beam, matrices, change, message):
    arguments = {"model": "FOAM", "speed": 1.0, "hub": "free", "damping": None, "outputs": None}
    arguments |= change
    for route in (linear_model, jacobian_model):
        with pytest.raises(ValueError, match=re.escape(message)):
            route(beam, matrices(), **arguments)


def test_bad_case_damping_is_named_before_assembly(beam):
    with pytest.raises(ValueError, match=re.escape("damping.kind: got 'viscous'; allowed: one of modal, rayleigh")):
        plant(beam, "FOAM", 1.0, damping={"kind": "viscous"})


def test_matrices_of_another_beam_are_refused(beam, matrices):
    other = dataclasses.replace(beam, L=7.0)
    with pytest.raises(ValueError, match="sm: system matrices assembled for another beam"):
        linear_model(other, matrices(), "FOAM", 1.0)


# --- linear against nonlinear -------------------------------------------------------------------

SPIN = 1.0  # rad s-1: the steady spin of the spinning start, below TLAM's critical speed
#: damping of the spinning runs: the pulse moves the spin, and with it the bending frequencies,
#: by a term of order a; undamped, the phase error it makes would grow through the run
SPIN_DAMPING = {"kind": "modal", "axial": 0.3, "transverse": 0.3}


def _pulse_runs(beam, numerics, sm, model, speed, amplitudes, damping=None):
    """The relative differences between the nonlinear and the linear responses (hub angle, tip
    deflection) to a hub-torque pulse of each amplitude, applied at ``t = 0`` to the hub-beam in
    steady spin at ``speed`` (at rest for 0), which stays there without the pulse: the nonlinear
    deviation from it is ``theta - speed t`` and the tip deflection."""
    plant = linear_model(beam, sm, model, speed, hub="free", damping=damping_matrices(damping, sm),
                         outputs=["hub_angle", "tip_deflection"]).to_control()
    differences = []
    for amplitude in amplitudes:
        case = {"name": "pulse", "model": model, "modes": 3, "t_end": 8.0,
                "tip_mass": {"mass": TIP.mass, "position": TIP.position}, "initial": {"hub_speed": speed},
                "maneuver": {"kind": "torque_table", "time": [0.0, 0.5, 1.0], "torque": [0.0, amplitude, 0.0]}}
        ds = simulate(case | ({"damping": damping} if damping else {}), beam, numerics, sm)
        t = ds.time.values
        nonlinear = np.array([ds.theta.values - speed * t, ds.tip_transverse.values])
        linear = ct.forced_response(plant, t, ds.hub_torque.values).outputs
        differences.append(np.max(np.abs(nonlinear - linear), axis=1)
                           / np.max(np.abs(linear), axis=1))
    return np.array(differences)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("spinning", [False, True], ids=["from_rest", "spinning"])
def test_linear_model_against_the_nonlinear_kernel(_study_config, beam, model, spinning):
    """A pulse of amplitude a differs from the linear response by terms of higher order: about a
    steady spin the quadratic ones, so the relative difference ``r`` is proportional to ``a``
    (halve the pulse, ``r`` halves); at rest the mirror image of the hub-beam (``theta, v -> -theta,
    -v``) answers ``-a`` with the mirrored motion, the response is odd in ``a``, its first
    nonlinear term cubic and ``r`` proportional to ``a^2`` (halve, it quarters). With
    ``r(a) / r(a / 2) = p (1 + d)``, ``d`` is itself a term of the next order: the amplitudes keep
    ``r`` below 6 percent, so ``|d| <= 0.1``, and ``d`` must fall from one halving to the next
    (bound 0.6, expected 1/2 spinning, 1/4 at rest). The spinning run starts in steady spin at
    the linearisation's speed (``initial.hub_speed``); the pulse's input is the run's torque at
    its output times, where the piecewise-linear table is interpolated exactly. The integrator's
    tolerance (1e-10) is far below the smallest ``r`` (about 1e-5)."""
    numerics = dict(_study_config["numerics"], output_step=0.002, rtol=1e-10, atol=1e-12)
    sm = assemble(beam, TIP, 3, numerics["quadrature_points"])
    amplitudes = (40.0, 20.0, 10.0) if spinning else (50.0, 25.0, 12.5)
    r = (_pulse_runs(beam, numerics, sm, model, SPIN, amplitudes, SPIN_DAMPING) if spinning
         else _pulse_runs(beam, numerics, sm, model, 0.0, amplitudes))
    p = 2.0 if spinning else 4.0
    d = r[:-1] / r[1:] / p - 1.0
    assert np.all(r < 0.06)
    assert np.all(np.abs(d[0]) <= 0.1)
    assert np.all(np.abs(d[1]) <= 0.6 * np.abs(d[0]))


# --- export --------------------------------------------------------------------------------------


def test_netcdf_and_mat_files_hold_the_models(beam, matrices, tmp_path):
    """Both files give back, at every speed, the model :func:`linear_model` returns (the netCDF
    float encoding is lossless; the .mat file stores doubles)."""
    speeds = [0.0, 1.0, 2.5]  # TLAM's critical speed with this tip mass is 1.94 rad s-1
    ds = to_dataset(Plant(beam=beam, modes=5, quadrature_points=64, tip=TIP, damping=damping_from_dict(MODAL)),
                    "TLAM", speeds, "free")
    stored = open_result(write_dataset(ds, tmp_path / "linear.nc"))
    mat = loadmat(write_mat(ds, tmp_path / "linear.mat"))
    assert stored.attrs["Conventions"] == "CF-1.11" and stored.attrs["model"] == "TLAM"
    assert stored.attrs["tip_mass_kg"] == TIP.mass and stored.attrs["n_modes"] == 5
    assert [str(cell[0]) for cell in mat["states"][:, 0]] == list(ds.state.values)
    for k, speed in enumerate(speeds):
        lm = linear_model(beam, matrices(TIP), "TLAM", speed, damping=damping_matrices(MODAL, matrices(TIP)))
        for name in "ABCD":
            np.testing.assert_array_equal(stored[name].values[k], getattr(lm, name))
            np.testing.assert_array_equal(mat[name][:, :, k], getattr(lm, name))
        assert list(stored.state.values) == list(lm.states)
        assert list(stored.output.values) == list(lm.outputs)
    np.testing.assert_array_equal(mat["speed"][:, 0], speeds)
    unstable = stored.growth_rate.values > 1e-6  # rounding leaves ~1e-12 on the stable side
    assert unstable.tolist() == [False, False, True]


@pytest.mark.parametrize(("speeds", "message"), [
    ([], "speeds = []; allowed: a non-empty, strictly increasing list of hub speeds, each "
         "finite and >= 0 rad s-1"),
    ([1.0, -0.5], "speeds[1] = -0.5; allowed"),
    ([1.0, float("inf")], "speeds[1] = inf; allowed"),
    ([1.0, 2.0, 2.0], "speeds[2] = 2.0 after 2.0; allowed"),
])
def test_bad_speed_grid_is_named(beam, matrices, speeds, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        to_dataset(Plant(beam=beam, modes=5, quadrature_points=64, tip=TipMass(0.0, beam.L)), "FOAM", speeds)


def test_benchmark_rows(_study_config, beam):
    rows = linear_rows(_study_config, beam, repeats=1, budget=1.0)
    assert [row["states"] for row in rows] == [42, 42, 42]
    assert all(row["wall_s"] > 0 for row in rows)

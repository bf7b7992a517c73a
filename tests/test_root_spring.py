"""The compliant root (``RootSpring``: a torsional spring and damper between the hub and the beam's
root, docs/compliant-root.md) against closed forms, Lagrange's equations, conservation laws and a
second route.

* the restrained root's frequency equation (``hubbeam.validation.root_spring``): its limits (the
  clamped beam, the pinned beam), hubbeam's frequencies at rest converging to it in the modes, and
  the rigid limit, in which both approach the clamped beam as ``1 / k`` with the slope ``-2 EI /
  (k L)`` of first-order perturbation;
* a rigid link (a very stiff beam) on the spring: the lag-hinge frequency at speed, the
  centrifugal term of the hub radius included, with the hub held; the two-mass frequency on a free
  hub;
* the joint's equations against Lagrange's equations of the hinged link's kinetic energy (TLAM,
  FOAM, CFOAM), the integrator's right-hand sides against the general equations (every model, a
  free and a prescribed hub, the controllers on the hub's angle);
* simulations: energy and angular momentum conserved, the work-energy balance with the damper, the
  rigid limit in time, the outputs and what the dataset records;
* the linear models of both routes with the spring; the drive and a sampled controller on the
  hub; bad input named.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from synthetic_results import rig_run
from test_eom import exact_kinetic_energy, make_cloud, truncated_kinetic_energy
from test_simulate import assert_conserved_after

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.settings import simulation_settings
from hubbeam.core import eom
from hubbeam.core.inputs import SimulationInputs
from hubbeam.core.integrate import integration_problem, output_columns
from hubbeam.core.radau import problem_rhs
from hubbeam.linear.datasets import tracked_modes
from hubbeam.linear.jacobian import RELATIVE_STEP, jacobian_model
from hubbeam.linear.statespace import linear_model
from hubbeam.model import eigen
from hubbeam.model.damping import damping_matrices
from hubbeam.model.drive import QUANSER_SRV02
from hubbeam.model.maneuvers import FeedbackLaw, SensorSpec, maneuver_from_dict
from hubbeam.model.matrices import assemble
from hubbeam.model.models import MODELS
from hubbeam.model.modes import clamped_free_roots
from hubbeam.model.parameters import BeamParameters, BeamProducts, TipMass
from hubbeam.model.root import RootSpring, joint_inputs, joint_second_order
from hubbeam.simulation.errors import SimulationError
from hubbeam.simulation.sampled import SampledLoop
from hubbeam.simulation.simulate import Resolved, case_matrices, run, simulate
from hubbeam.validation import root_spring as closed
from hubbeam.validation.tip_body import body_frequency_roots

EPS = np.finfo(float).eps
#: a light link (De Luca and Siciliano's, 0.5 m, 0.2 kg/m, EI = 1 N m2) on a 2 cm hub
LINK = BeamProducts(L=0.5, rhoA=0.2, EI=1.0, EA=1.0e4, Jh=0.01, rA=0.02)
#: a payload with rotary inertia and its centre 2 cm beyond the tip
PAYLOAD = TipMass(0.1, 0.5, 0.0005, 0.02)
MODAL = {"kind": "modal", "axial": 0.01, "transverse": 0.02}


@pytest.fixture(scope="module")
def paper_beam(_study_config):
    return BeamParameters.from_config(_study_config)


# --- the restrained root in closed form -----------------------------------------------------


def test_the_frequency_equation_has_the_clamped_and_the_pinned_limits():
    """A root spring of 1e12 EI / L is the clamped beam (clamped-free roots, and with a tip body
    the tip-body equation's roots, to 1e-9: the spring's compliance moves them by ``2 / kappa`` =
    2e-12 relative); without spring and clamp the root is pinned, whose beam frequencies are the
    roots of ``tan z = tanh z`` (3.9266, 7.0686, ...)."""
    beam = BeamProducts(L=1.0, rhoA=1.0, EI=1.0, EA=1e6, Jh=1.0, rA=0.0)  # omega = z^2
    stiff = closed.restrained_frequencies(beam, RootSpring(1e12), 4)
    np.testing.assert_allclose(np.sqrt(stiff), clamped_free_roots(4), rtol=1e-9)
    body = TipMass(0.3, 1.0, 0.02, 0.1)
    np.testing.assert_allclose(np.sqrt(closed.restrained_frequencies(beam, RootSpring(1e12), 4, body)),
                               body_frequency_roots(0.3, 0.02, 0.1, 4), rtol=1e-9)
    pinned = np.sqrt(closed.restrained_frequencies(beam, RootSpring(0.0), 3))
    for root in pinned:
        assert math.tan(root) == pytest.approx(math.tanh(root), abs=1e-12)
    assert pinned[0] == pytest.approx(3.926602312, abs=1e-9)


@pytest.mark.parametrize("stiffness", [0.5, 5.0, 500.0])
@pytest.mark.parametrize("tip", [None, PAYLOAD], ids=["free_end", "payload"])
def test_hubbeam_at_rest_converges_to_the_restrained_root(stiffness, tip):
    """hubbeam's frequencies at rest, hub held (``natural_frequencies`` with the spring: the root
    angle and the clamped-free functions), against the closed form: the error of each of the first
    three frequencies falls at least as ``N^-2.5`` from 10 to 20 modes (measured rates 2.9 to 3.1
    without a body: the root's moment is carried by the root angle, the tip is free as the
    functions' is; with the body the rate is the tip body's, ``N^-1``, docs/tip-body.md, checked
    there) where it is above the eigensolver's rounding (1e-11; a stiff spring's first frequency is
    exact to 1e-13 with 10 modes), and is below 1e-7 with 20 modes."""
    spring = RootSpring(stiffness, 0.0, 1e-4)
    exact = closed.restrained_frequencies(LINK, spring, 3, tip)
    errors = {n: np.abs(eigen.natural_frequencies(assemble(LINK, tip, n), spring)[:3] / exact - 1.0)
              for n in (10, 20)}
    if tip is None:
        assert np.all(errors[20] <= 1e-7)
        resolved = errors[10] > 1e-11
        rates = np.log(errors[10] / errors[20]) / np.log(2.0)
        assert np.all(rates[resolved] >= 2.5) and resolved.sum() >= 2
    else:
        rates = np.log(errors[10] / errors[20]) / np.log(2.0)
        assert np.all((0.9 <= rates) & (rates <= 1.5))  # measured 1.01 to 1.33


def test_the_rigid_limit_falls_as_one_over_the_stiffness():
    """As ``k`` grows each frequency tends to the clamped beam's from below by ``-2 EI / (k L)``
    relative (first order: the clamped mode's root moment ``EI f''(0)`` bends the spring by ``EI
    f''(0) / k``, which lowers ``omega^2`` by ``(EI f''(0))^2 / k``; ``f''(0) = 2 beta^2 / sqrt(rho A
    L)`` for unit modal mass): the remainder ``k (omega / omega_c - 1) + 2 EI / L`` is ``O(1 / k)``,
    tenfold smaller per decade of ``k`` (within 5 %) from 1e3 to 1e6 N m/rad. hubbeam (12 modes,
    against its own rigid root) has the closed form's remainder at 1e3 and 1e4 N m/rad to 1e-5 (its
    Ritz error, 1e-10 relative, times ``k``; beyond, ``k`` times the rounding of the frequencies
    swamps the remainder)."""
    clamped = clamped_free_roots(3) ** 2 * math.sqrt(LINK.EI / (LINK.rhoA * LINK.L**4))
    sm = assemble(LINK, None, 12)
    rigid = eigen.natural_frequencies(sm)[:3]
    slope = -2.0 * LINK.EI / LINK.L
    remainders = {k: k * (closed.restrained_frequencies(LINK, RootSpring(k), 3) / clamped - 1.0) - slope
                  for k in (1e3, 1e4, 1e5, 1e6)}
    for k in (1e3, 1e4, 1e5):
        np.testing.assert_allclose(remainders[k] / remainders[10 * k], 10.0, rtol=0.05)
    for k in (1e3, 1e4):
        ours = k * (eigen.natural_frequencies(sm, RootSpring(k))[:3] / rigid - 1.0) - slope
        np.testing.assert_allclose(ours, remainders[k], rtol=0, atol=1e-5)


# --- a rigid link on the spring ---------------------------------------------------------------


def _stiff(EI, rA=LINK.rA, EA=1e12):
    """The link made stiff: its bending (and axial) frequencies far above the spring's (at speed
    the Coriolis forces of the swing couple it to the stretch, whose share falls as ``1 / EA``:
    1e-10 at 1e12 N)."""
    return dataclasses.replace(LINK, EI=EI, EA=EA, rA=rA)


@pytest.mark.parametrize("model", MODELS)
def test_a_rigid_link_on_the_spring_swings_at_the_lag_frequency(model):
    """Hub held at 0, 10 and 30 rad/s: the slowest frequency of the link on the spring is the lag
    hinge's, ``sqrt((k + Omega^2 a S) / I)`` (the centrifugal term of the hub radius raises it 30 %
    at 30 rad/s). The beam's bending lowers it by its participation, ``(omega_lag / omega_b)^2``:
    1.6e-5 at EI = 1e4 N m2, a hundredth of it at 1e6, bounded here by 2e-7 and checked to fall
    as ``1 / EI``. The Jacobian route (central differences of the kernels' equations) swings at
    the same frequency (its own error, ``1e-9``, well below the bound)."""
    spring = RootSpring(2.0, 0.0, 1e-4)
    errors = {}
    for EI in (1e4, 1e6):
        beam = _stiff(EI)
        sm = assemble(beam, PAYLOAD, 4)
        for speed in (0.0, 10.0, 30.0):
            lag = closed.lag_frequency(beam, spring, speed, PAYLOAD)
            errors[EI, speed] = eigen.root_frequencies(sm, spring, model, speed, "held")[0] / lag - 1.0
            if EI == 1e6:
                lin = jacobian_model(beam, sm, model, speed, "prescribed", root_spring=spring)
                poles = np.sort(np.abs(np.linalg.eigvals(lin.A).imag))
                assert poles[poles > 1e-6 * lag][0] == pytest.approx(lag, rel=2e-7)
    assert closed.lag_frequency(_stiff(1e6), spring, 30.0, PAYLOAD) > 1.25 * closed.lag_frequency(
        _stiff(1e6), spring, 0.0, PAYLOAD)
    for speed in (0.0, 10.0, 30.0):
        assert abs(errors[1e6, speed]) <= 2e-7
        assert errors[1e4, speed] / errors[1e6, speed] == pytest.approx(100.0, rel=0.05)


@pytest.mark.parametrize("rA", [0.0, 0.05])
def test_a_stiff_link_on_a_free_hub_is_the_two_mass_arm(rA):
    """Free hub at rest: a rigid-body mode (frequency 0, to the square root of the rounding of its
    double zero eigenvalue: bound 1e-4 of the next) and the two-mass frequency, ``k (1 / J + 1 /
    I)`` without a hub radius (the flexible-joint arm), ``k J_axis / ((J + a^2 m) I - a^2 S^2)`` with
    one; the bending's share falls as ``1 / EI`` (1.6e-7 at EI = 1e6). At rest the stretch does
    not couple; an axial stiffness of 1e8 N keeps the axial modes' scale near the bending's, where
    the eigensolver resolves the two-mass frequency to 1e-9."""
    spring = RootSpring(2.0, 0.0, 1e-4)
    errors = []
    for EI in (1e4, 1e6):
        beam = _stiff(EI, rA, EA=1e8)
        frequencies = eigen.root_frequencies(assemble(beam, PAYLOAD, 4), spring, "FOAM", 0.0, "free")
        assert frequencies[0] <= 1e-4 * frequencies[1]
        errors.append(frequencies[1] / closed.two_mass_frequency(beam, spring, PAYLOAD) - 1.0)
    if rA == 0.0:
        link = closed.rigid_link(LINK, spring, PAYLOAD)
        textbook = math.sqrt(spring.stiffness * (1.0 / LINK.Jh + 1.0 / link["I"]))
        assert closed.two_mass_frequency(_stiff(1e6, 0.0), spring, PAYLOAD) == pytest.approx(textbook, rel=1e-14)
    assert abs(errors[1]) <= 3e-7
    assert errors[0] / errors[1] == pytest.approx(100.0, rel=0.05)


# --- the joint's equations ----------------------------------------------------------------------


def hinged_kinetic_energy(cloud, spring, y, v):
    """The exact kinetic energy of hub and hinged link: the points of the cloud at ``a (cos phi,
    sin phi) + R(theta) (x + u, v)`` (inertial), the hub's and the clamp's inertia, the tip body's
    rotation; ``y = (theta, q1, q2, phi)``."""
    n = cloud.M1.shape[0]
    theta, q1, q2, phi = y[0], y[1:1 + n], y[1 + n:1 + 2 * n], y[-1]
    thd, q1d, q2d, phd = v[0], v[1:1 + n], v[1 + n:1 + 2 * n], v[-1]
    Sq2 = np.einsum("kij,j->ki", cloud.S, q2)
    X = cloud.x + cloud.F1 @ q1 - 0.5 * Sq2 @ q2
    Y = cloud.F2 @ q2
    Xd = cloud.F1 @ q1d - Sq2 @ q2d - thd * Y  # the velocity about the hinge in the root's frame
    Yd = cloud.F2 @ q2d + thd * X
    c, s = math.cos(theta), math.sin(theta)
    a = cloud.rA
    vx = -a * phd * math.sin(phi) + c * Xd - s * Yd
    vy = a * phd * math.cos(phi) + s * Xd + c * Yd
    rotation = thd + cloud.dF2t @ q2d
    return (0.5 * cloud.Jh * phd**2 + 0.5 * spring.clamp_inertia * thd**2 + 0.5 * np.sum(cloud.w * (vx**2 + vy**2))
            + 0.5 * cloud.Jt * rotation**2)


def link_kinetic_energy(cloud, spring, y, v):
    """The link's kinetic energy about a fixed hinge (the hub radius zero, the clamp's inertia as
    the hub's), coordinates ``(theta, q1, q2)``."""
    return exact_kinetic_energy(cloud._replace(rA=0.0, Jh=spring.clamp_inertia), y, v)


def model_kinetic_energy(model, cloud, spring, y, v):
    """The kinetic energy of ``model`` with the joint: CFOAM's exact; FOAM's the link's truncated at
    second order in the deformation plus the hinge's exact terms; TLAM's without the foreshortening
    (in the link and in the hinge's lever)."""
    if model == "CFOAM":
        return hinged_kinetic_energy(cloud, spring, y, v)
    bare = cloud if model == "FOAM" else cloud._replace(S=np.zeros_like(cloud.S))
    hinge = hinged_kinetic_energy(bare, spring, y, v) - link_kinetic_energy(bare, spring, y[:-1], v[:-1])
    link = cloud._replace(rA=0.0, Jh=spring.clamp_inertia)
    T = truncated_kinetic_energy(link, y[:-1], v[:-1])
    if model == "TLAM":  # FOAM's less -theta'^2 q2^T D q2 / 2 of the link, D = sum w x S about the hinge
        n = cloud.M1.shape[0]
        q2 = y[1 + n:1 + 2 * n]
        T += 0.5 * v[0] ** 2 * q2 @ np.einsum("k,kij->ij", cloud.w * cloud.x, cloud.S) @ q2
    return T + hinge


def lagrange(T, y, v, stiffness, h=1e-5):
    """``M`` and ``F`` of Lagrange's equations of ``T(y, v)`` (numerical derivatives; ``T`` is
    quadratic in ``v``, so polarisation gives ``M``) with the potential ``y^T K y / 2``."""
    N = y.size
    eye = np.eye(N)

    def mass(yy):
        t = np.array([T(yy, eye[i]) for i in range(N)])
        return np.array([[T(yy, eye[i] + eye[j]) - t[i] - t[j] for j in range(N)] for i in range(N)])

    M = mass(y)
    dp_dt = (mass(y + h * v) @ v - mass(y - h * v) @ v) / (2 * h)
    dT_dy = np.array([(T(y + h * eye[i], v) - T(y - h * eye[i], v)) / (2 * h) for i in range(N)])
    return M, dT_dy - dp_dt - stiffness @ y


def _state(n, seed):
    rng = np.random.default_rng(seed)
    y = np.concatenate([[0.4], 0.02 * rng.normal(size=2 * n), [0.55]])
    v = np.concatenate([[1.3], 0.3 * rng.normal(size=2 * n), [0.9]])
    return y, v


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
@pytest.mark.parametrize("rotary_inertia", [0.0, 0.7], ids=["point", "body"])
def test_the_joint_follows_lagrange_s_equations(model, rotary_inertia):
    """The mass matrix and force of the kernels (``eom.equations``: the link's equations about its
    hinge, ``add_joint``) against Lagrange's equations of the kinetic energy written in inertial
    coordinates (the hinge on the hub's radius, the link turned by theta about it), with the
    spring's potential, the damper and the hub torque on phi. ``M`` by polarisation is exact to
    rounding; ``F`` by central differences of step 1e-5 has errors ``~ h^2 T''' ~ 1e-9`` of its
    size: bounds 1e-12 and 1e-7 relative to the largest entry."""
    cloud = make_cloud(n=3, rotary_inertia=rotary_inertia)
    spring = RootSpring(40.0, 3.0, 0.8)
    link, root = joint_inputs(cloud, spring)
    n = 3
    y, v = _state(n, 7)
    stiffness = np.zeros((2 * n + 2, 2 * n + 2))
    stiffness[1:1 + n, 1:1 + n] = cloud.K1
    stiffness[1 + n:1 + 2 * n, 1 + n:1 + 2 * n] = cloud.K2
    stiffness[np.ix_([0, -1], [0, -1])] += spring.stiffness * np.array([[1.0, -1.0], [-1.0, 1.0]])
    M_ref, F_ref = lagrange(lambda yy, vv: model_kinetic_energy(model, cloud, spring, yy, vv), y, v, stiffness)
    damper = spring.damping * (v[-1] - v[0])
    tau = 2.5
    F_ref[0] += damper
    F_ref[-1] += tau - damper
    inputs = SimulationInputs(MODELS[model].traits, 1, np.array([1.0, 1.0]), np.zeros((2, n, n)), link, root=root)
    ws = eom.inputs_workspace(inputs, np.arange(2 * n + 2))
    eom.equations(inputs, y.copy(), v.copy(), tau, ws)
    np.testing.assert_allclose(ws.M, M_ref, rtol=0, atol=1e-12 * np.abs(M_ref).max())
    np.testing.assert_allclose(ws.F, F_ref, rtol=0, atol=1e-7 * np.abs(F_ref).max())


MANEUVERS = {
    "torque_table": {"kind": "torque_table", "time": [0.0, 10.0], "torque": [3.0, 3.0]},
    "prescribed": {"kind": "prescribed", "wf": 1.0, "tf": 20.0},
    "pd": {"kind": "pd", "kp": 50.0, "kd": 20.0, "reference": {"kind": "prescribed", "wf": 1.0, "tf": 20.0}},
}


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("maneuver", MANEUVERS)
def test_the_fast_right_hand_sides_solve_the_general_equations(paper_beam, model, maneuver):
    """The integrator's right-hand side with the joint (TLAM, FOAM, SFOAM: the two hub rows of the
    constant modal mass, ``foam_rhs.joint_rhs``; CFOAM: its tensors and ``add_joint``) gives the
    accelerations of the general equations (``eom.accelerations``: the full mass matrix) to
    rounding (1e-12 relative), under a free hub's torque, a prescribed hub and PD on the hub's
    angle, with damping and a tip body."""
    sm = assemble(paper_beam, TipMass(0.5, 8.0, 2.0, 0.3), 3)
    link, root = joint_inputs(sm, RootSpring(1e4, 5.0, 30.0))
    kind, mp = maneuver_from_dict(MANEUVERS[maneuver]).kernel_parameters()
    inputs = SimulationInputs(MODELS[model].traits, kind, mp, damping_matrices(MODAL, sm), link, root=root)
    free = eom.free_coordinates(inputs)
    problem = integration_problem(inputs)
    for seed in range(3):
        y, v = _state(3, seed)
        if not MODELS[model].keeps_axial:
            y[1:4] = v[1:4] = 0.0
        a = np.zeros(y.size)
        eom.accelerations(inputs, 4.0, y, v, free, a)
        fast = np.zeros(free.size)
        problem_rhs(4.0, y[free].copy(), v[free].copy(), fast, problem)
        np.testing.assert_allclose(fast, a[free], rtol=0, atol=1e-12 * np.abs(a[free]).max())


def test_a_state_feedback_acts_on_the_hub_and_references_its_angle(paper_beam):
    """``tau = J theta_r'' - K (x - x_r)`` on ``x = (theta, q1, q2, phi)`` and rates: the hub angle
    ``phi`` (last) is referenced like ``theta``; ``PD`` is the law with gains on ``phi`` and ``phi'``
    only, and both give the same accelerations."""
    n = 3
    sm = assemble(paper_beam, None, n)
    link, root = joint_inputs(sm, RootSpring(1e4, 5.0, 30.0))
    reference = {"kind": "prescribed", "wf": 1.0, "tf": 20.0}
    gains = np.zeros(2 * (2 + 2 * n))
    gains[1 + 2 * n], gains[-1] = 50.0, 20.0
    law = FeedbackLaw(gains, np.zeros(n), 0.0)
    feedback = maneuver_from_dict({"kind": "state_feedback", "reference": reference,
                                   "gains": {"theta": 1.0}}).kernel_parameters(law)
    pd = maneuver_from_dict(MANEUVERS["pd"]).kernel_parameters()
    y, v = _state(n, 3)
    results = []
    for kind, mp in (feedback, pd):
        inputs = SimulationInputs(MODELS["FOAM"].traits, kind, mp, np.zeros((2, n, n)), link, root=root)
        a = np.zeros(y.size)
        results.append(eom.accelerations(inputs, 4.0, y.copy(), v.copy(), eom.free_coordinates(inputs), a) + (a,))
    assert results[0][0] == pytest.approx(results[1][0], rel=1e-14)
    np.testing.assert_allclose(results[0][2], results[1][2], rtol=1e-14)


# --- simulations --------------------------------------------------------------------------------


def _case(model, maneuver, t_end, modes=3, spring=None, **extra):
    """A case mapping of the paper's beam with a 0.5 kg tip mass, on the root ``spring`` if given."""
    root = {} if spring is None else {"root_spring": spring.to_dict()}
    return {"name": f"root_{model}", "model": model, "modes": modes, "t_end": t_end, "maneuver": maneuver,
            "tip_mass": {"mass": 0.5, "position": 8.0}, **root, **extra}


def _hub(beam):
    """The paper's hub split: half its inertia on the motor side, half in the clamp."""
    return dataclasses.replace(beam, Jh=beam.Jh / 2.0)


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
def test_energy_and_angular_momentum_are_conserved_on_the_spring(_study_config, paper_beam, model):
    """A torque pulse (Eq. 44) on the hub sets hub, spring and link swinging (0.016 rad of twist);
    once it has ended the free, undamped system keeps its energy (with the spring's) and its
    angular momentum (hub and link) to the integrator's tolerance (``rtol`` times their size, as
    without the spring; measured 7e-12 and 2e-12), and the rest-to-rest pulse leaves no net
    momentum."""
    rtol = 1e-9
    numerics = dict(_study_config["numerics"], rtol=rtol, atol=1e-2 * rtol)
    spring = RootSpring(2e3, 0.0, paper_beam.Jh / 2.0)
    ds = simulate(_case(model, {"kind": "torque", "tau_max": 40.0, "tf": 5.0}, 12.0, spring=spring), _hub(paper_beam),
                  numerics)
    assert float(abs(ds.hub_angle - ds.theta).max()) > 1e-3  # the spring did twist
    assert_conserved_after(ds, 5.0, rtol)


@pytest.mark.parametrize("model", ["TLAM", "FOAM", "CFOAM"])
@pytest.mark.parametrize("maneuver", ["torque_table", "prescribed"])
def test_the_work_of_the_hub_torque_is_the_energy_and_the_dissipation(_study_config, paper_beam, model, maneuver):
    """``energy(t) - energy(0) = work(t) - dissipated(t)``: the work of the hub torque on the hub's
    rate (applied to a free hub, required by a prescribed one), the energy with the spring's, the
    dissipation of the modal damping and of the root's damper. Simpson's rule on the 0.005 s grid
    and the run's ``rtol`` of 1e-10 leave 2e-9 of the largest work (measured), bound 2e-8."""
    numerics = dict(_study_config["numerics"], output_step=0.005, rtol=1e-10, atol=1e-12)
    maneuvers = {"torque_table": {"kind": "torque_table", "time": [0.0, 1.0, 2.0, 3.0],
                                  "torque": [0.0, 60.0, -30.0, 0.0]},
                 "prescribed": {"kind": "prescribed", "wf": 1.0, "tf": 2.0}}
    spring = RootSpring(2e3, 8.0, paper_beam.Jh / 2.0)
    ds = simulate(_case(model, maneuvers[maneuver], 4.0, spring=spring, damping=MODAL), _hub(paper_beam), numerics)
    assert float(ds.dissipated_energy[-1]) > 1e-3 * float(abs(ds.work).max())
    balance = ds.energy.values - ds.energy.values[0] - ds.work.values + ds.dissipated_energy.values
    np.testing.assert_allclose(balance, 0.0, atol=2e-8 * np.abs(ds.work.values).max())


@pytest.mark.parametrize("model", MODELS)
def test_a_stiffening_spring_approaches_the_rigid_root_as_one_over_k(_study_config, paper_beam, model):
    """The run on a spring of stiffness ``k`` (the clamp's inertia and the hub's summing to the
    rigid hub's) differs from the rigid run by ``O(1 / k)``: the largest difference of the tip
    deflection falls a hundredfold (within 5 %) when ``k`` grows a hundredfold, from 1e4 to 1e6
    N m/rad (the run's tolerance, 1e-10, is far below the 1e-6 m difference at 1e6)."""
    numerics = dict(_study_config["numerics"], output_step=0.01, rtol=1e-10, atol=1e-12)
    case = _case(model, {"kind": "torque_table", "time": [0.0, 1.0, 2.0, 3.0], "torque": [0.0, 60.0, -30.0, 0.0]},
                 4.0, damping=MODAL)
    rigid = simulate(case, paper_beam, numerics).tip_transverse.values
    differences = []
    for k in (1e4, 1e6):
        ds = simulate(dict(case, root_spring=RootSpring(k, 0.0, paper_beam.Jh / 2.0).to_dict()), _hub(paper_beam),
                      numerics)
        differences.append(np.max(np.abs(ds.tip_transverse.values - rigid)))
    assert differences[0] / differences[1] == pytest.approx(100.0, rel=0.05)


def test_the_dataset_holds_the_hub_and_the_spring(_study_config, paper_beam):
    """A prescribed maneuver moves the hub (``hub_angle`` is Eq. 43's), the link swings on the
    spring (``theta`` lags), ``spring_torque`` is ``k (phi - theta) + c (phi' - theta')``, the work
    is the hub torque's on the hub's rate, and the spring is recorded."""
    numerics = dict(_study_config["numerics"], output_step=0.01)
    spring = RootSpring(2e3, 8.0, paper_beam.Jh / 2.0)
    wf, tf = 1.0, 2.0
    ds = simulate(_case("FOAM", {"kind": "prescribed", "wf": wf, "tf": tf}, 3.0, spring=spring), _hub(paper_beam),
                  numerics)
    t = ds.time.values
    inside = t <= tf
    phase = 2.0 * math.pi * t[inside] / tf
    angle = wf / (2 * tf) * t[inside] ** 2 + wf * tf / (4 * math.pi**2) * (np.cos(phase) - 1.0)
    np.testing.assert_allclose(ds.hub_angle.values[inside], angle, rtol=0, atol=1e-14)
    assert float(abs(ds.hub_angle - ds.theta).max()) > 1e-4
    torque = spring.stiffness * (ds.hub_angle - ds.theta) + spring.damping * (ds.hub_speed - ds.theta_dot)
    np.testing.assert_allclose(ds.spring_torque.values, torque.values, rtol=0,
                               atol=1e-12 * float(abs(ds.spring_torque).max()))
    assert ds.attrs["root_stiffness_N_m_rad-1"] == spring.stiffness
    assert ds.attrs["root_clamp_inertia_kg_m2"] == spring.clamp_inertia
    assert ds.theta.attrs["long_name"] == "beam root angle theta"
    assert ds.hub_speed.attrs["units"] == "rad s-1"


def test_pd_reads_the_hub_angle(_study_config, paper_beam):
    """A PD controller with a root spring acts on the hub: its torque is ``kp (theta_r - phi) + kd
    (theta_r' - phi')`` of the hub's outputs, to rounding."""
    numerics = dict(_study_config["numerics"], output_step=0.01)
    maneuver = {"kind": "pd", "kp": 400.0, "kd": 300.0, "reference": {"kind": "prescribed", "wf": 1.0, "tf": 2.0}}
    ds = simulate(_case("CFOAM", maneuver, 3.0, spring=RootSpring(2e3, 8.0, paper_beam.Jh / 2.0)), _hub(paper_beam),
                  numerics)
    t = ds.time.values
    phase = 2.0 * math.pi * np.minimum(t, 2.0) / 2.0
    reference = np.where(t < 2.0, 0.25 * t**2 + 2.0 / (4 * math.pi**2) * (np.cos(phase) - 1.0), 1.0 + (t - 2.0))
    rate = np.where(t < 2.0, 0.5 * t - np.sin(phase) / (2 * math.pi), 1.0)
    expected = 400.0 * (reference - ds.hub_angle.values) + 300.0 * (rate - ds.hub_speed.values)
    np.testing.assert_allclose(ds.hub_torque.values, expected, rtol=0, atol=1e-9 * np.abs(expected).max())


# --- linear models ---------------------------------------------------------------------------


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("hub", ["free", "prescribed"])
def test_the_linear_routes_agree_with_the_spring(paper_beam, model, hub):
    """The assembled linear model with the spring (``hubbeam.model.root.joint_second_order``) and
    the Jacobian route (central differences of the kernels' joint) agree as without it: per row of
    ``A`` ``100 eps^(2/3)`` of the row's largest entry (the bound of ``test_linear``; measured
    5e-11), ``B`` to 100 eps, ``C`` to ``100 eps^(2/3)``; at rest and at 2 rad/s, with a tip body
    and damping."""
    sm = assemble(paper_beam, TipMass(0.5, 8.0, 2.0, 0.3), 3)
    C = damping_matrices(MODAL, sm)
    spring = RootSpring(2e3, 3.0, 10.0)
    for speed in (0.0, 2.0):
        assembled = linear_model(paper_beam, sm, model, speed, hub, C, root_spring=spring)
        differenced = jacobian_model(paper_beam, sm, model, speed, hub, C, root_spring=spring)
        row = np.max(np.abs(assembled.A), axis=1, keepdims=True)
        assert np.all(np.abs(assembled.A - differenced.A) <= 100 * RELATIVE_STEP**2 * row)
        np.testing.assert_allclose(differenced.B, assembled.B, rtol=0, atol=100 * EPS * np.abs(assembled.B).max())
        np.testing.assert_allclose(differenced.C, assembled.C, rtol=0,
                                   atol=100 * RELATIVE_STEP**2 * np.abs(assembled.C).max())
    states = assembled.states
    assert (states[0], states[len(states) // 2 - 1], states[-1]) == ("theta", "phi", "phi_dot")
    assert {"root_angle", "root_speed", "spring_torque"} <= set(assembled.outputs)


def test_the_linear_model_s_outputs_read_hub_root_and_spring(paper_beam):
    """``hub_angle`` reads ``phi``, ``root_angle`` ``theta``, ``spring_torque`` ``k (phi - theta) + c
    (phi' - theta')``; the input drives the hub's row (free hub) or is its acceleration
    (prescribed)."""
    sm = assemble(paper_beam, None, 2)
    spring = RootSpring(2e3, 3.0, 10.0)
    free = linear_model(paper_beam, sm, "FOAM", 1.0, "free", root_spring=spring)
    index = {name: k for k, name in enumerate(free.states)}
    rows = dict(zip(free.outputs, free.C))
    assert rows["hub_angle"][index["phi"]] == 1.0 and np.count_nonzero(rows["hub_angle"]) == 1
    assert rows["root_angle"][index["theta"]] == 1.0 and np.count_nonzero(rows["root_angle"]) == 1
    torque = rows["spring_torque"]
    assert (torque[index["phi"]], torque[index["theta"]]) == (spring.stiffness, -spring.stiffness)
    assert (torque[index["phi_dot"]], torque[index["theta_dot"]]) == (spring.damping, -spring.damping)
    held = linear_model(paper_beam, sm, "FOAM", 1.0, "prescribed", root_spring=spring)
    assert held.B[index["phi_dot"], 0] == 1.0 and held.inputs == ("hub_acceleration",)
    M = joint_second_order(sm, spring, MODELS["FOAM"], 1.0, np.zeros((2, 2, 2)))[0]
    torque = M @ free.B[len(free.states) // 2:, 0]  # M z'' = e_phi tau
    np.testing.assert_allclose(torque, np.eye(M.shape[0])[-1], rtol=0, atol=1e-12)


def test_a_stiff_spring_s_linear_model_approaches_the_rigid_one(paper_beam):
    """With ``k`` growing the free hub's poles at 1 rad/s approach the rigid root's (the hub's
    inertia split between hub and clamp): the two slowest bending frequencies move by ``O(1 / k)``,
    measured tenfold less per decade of ``k`` (within 5 %), from 1e6 N m/rad, where the pair the
    spring adds (the hub against the link) lies above the third bending mode; that pair rises as
    ``sqrt(k)``, tenfold per two decades (within 1 %)."""
    sm = assemble(paper_beam, None, 3)
    rigid = np.sort(np.abs(np.linalg.eigvals(linear_model(paper_beam, sm, "FOAM", 1.0).A).imag))[::2]
    hub = _hub(paper_beam)
    sm_hub = assemble(hub, None, 3)
    gaps, added = [], []
    for k in (1e6, 1e7, 1e8):
        spring = RootSpring(k, 0.0, paper_beam.Jh / 2.0)
        lin = linear_model(hub, sm_hub, "FOAM", 1.0, root_spring=spring)
        poles = np.sort(np.abs(np.linalg.eigvals(lin.A).imag))[::2]
        gaps.append(np.abs(poles[1:3] / rigid[1:3] - 1.0))  # past the rigid-body pair
        added.append(np.setdiff1d(poles, poles[np.argmin(np.abs(poles[:, None] - rigid[None, :]), axis=0)])[0])
    np.testing.assert_allclose(gaps[0] / gaps[1], 10.0, rtol=0.05)
    np.testing.assert_allclose(gaps[1] / gaps[2], 10.0, rtol=0.05)
    assert added[2] / added[0] == pytest.approx(10.0, rel=0.01)


# --- bad input ----------------------------------------------------------------------------------


@pytest.mark.parametrize("field, value", [("stiffness", -1.0), ("damping", -0.1), ("clamp_inertia", -2.0),
                                          ("stiffness", math.inf), ("damping", math.nan), ("clamp_inertia", "1")])
def test_a_bad_spring_is_named(field, value):
    arguments = dict(dict(stiffness=1.0, damping=0.0, clamp_inertia=0.0), **{field: value})
    with pytest.raises(ValueError, match=f"root_spring.{field} = .*; allowed: a finite number >= 0"):
        RootSpring(**arguments)


def test_what_is_not_a_spring_is_refused(_study_config, paper_beam):
    case = dict(_case("FOAM", {"kind": "torque", "tau_max": 1.0, "tf": 1.0}, 0.1), root_spring={"stiffness": -1.0})
    with pytest.raises(ConfigError, match=r"cases\.root_FOAM\.root_spring\.stiffness"):
        simulate(case, paper_beam, _study_config["numerics"])
    sm = assemble(paper_beam, None, 2)
    with pytest.raises(ValueError, match="spring_torque with a root_spring only"):
        linear_model(paper_beam, sm, "FOAM", 1.0, outputs=["spring_torque"])
    with pytest.raises(ValueError, match="hub = 'loose'; allowed: one of held, free"):
        eigen.root_frequencies(sm, RootSpring(1.0), hub="loose")


def test_a_rigid_law_on_the_spring_is_refused(_study_config, paper_beam):
    """A law of the rigid root's ``2 N`` gains handed to a run on the spring directly
    (``simulate.run``: ``2 (N + 1)`` states) is named before the integration."""
    n = 2
    maneuver = {"kind": "state_feedback", "reference": {"kind": "prescribed", "wf": 1.0, "tf": 2.0},
                "gains": {"theta": 1.0}}
    numerics = _study_config["numerics"]
    rigid, checked_numerics = simulation_settings(_case("FOAM", maneuver, 0.1, modes=n), numerics, paper_beam.L)
    on_spring = dataclasses.replace(rigid, root_spring=RootSpring(1.0))
    law = FeedbackLaw(np.zeros(2 * (1 + 2 * n)), np.zeros(n), 0.0)
    with pytest.raises(SimulationError, match="10 feedback gains; allowed: 12, one per state of FOAM with 2 modes "
                                              "and the root spring's hub angle"):
        run(on_spring, paper_beam, checked_numerics, case_matrices(on_spring, paper_beam, checked_numerics),
            Resolved(law=law))


# --- the rig: the drive and a sampled controller on the hub ---------------------------------------


#: tight tolerances: the closed forms below hold to the integrator's error
RIG_NUMERICS = {"rtol": 1e-10, "atol": 1e-12, "output_step": 0.01, "max_steps": 10**6, "step_warning": 10**6,
                "divergence_limit": 0.5, "quadrature_points": 40}
#: the beam's modes and the root's damper decay to 1e-12 of their start by t_end = 12 s
RIG_DAMPED = {"kind": "modal", "axial": 0.1, "transverse": 0.1}


def test_a_constant_voltage_spins_hub_and_link_at_the_drive_s_speed(flexible_link):
    """The SRV02 drive at a constant 3 V on the hub, the link on a damped root spring: hub and root
    settle at ``torque_gain V / hub_damping`` (the beam in steady spin needs no torque, so the spring
    is relaxed and the hub torque zero, to 1e-9 of the motor's), the rotor's reflected inertia stays
    on the hub's side (the run's matrices), the motor reads the hub's speed."""
    motor = dataclasses.replace(QUANSER_SRV02, rotor_inertia=3.9e-7)
    spring = RootSpring(0.5, 0.01, 2e-5)
    case = {"name": "rig", "model": "CFOAM", "modes": 2, "t_end": 12.0, "damping": RIG_DAMPED,
            "maneuver": {"kind": "voltage_table", "time": [0.0, 1.0], "voltage": [3.0, 3.0]},
            "root_spring": spring.to_dict()}
    run = rig_run(case, flexible_link, RIG_NUMERICS, motor=motor)
    columns = output_columns(2, joint=True)
    end = run.out[-1]
    expected = motor.torque_gain * 3.0 / motor.hub_damping
    assert run.status == 0
    assert end[columns["hub_speed"]] == pytest.approx(expected, rel=1e-9)
    assert end[columns["theta_dot"]] == pytest.approx(expected, rel=1e-9)
    assert abs(end[columns["spring_torque"]]) < 1e-9 * motor.torque_gain * 3.0
    assert abs(end[columns["hub_torque"]]) < 1e-9 * motor.torque_gain * 3.0
    assert end[columns["motor_torque"]] == pytest.approx(float(motor.friction(end[columns["hub_speed"]])), rel=1e-9)
    assert run.matrices.Jh == pytest.approx(flexible_link.Jh + motor.reflected_inertia, rel=1e-15)


def test_a_sampled_loop_reads_and_drives_the_hub(flexible_link):
    """A sampled PD loop on the hub's encoder (a sensor row on ``phi``, rows of ``2 (N + 1)``) with
    the root spring: its sensed values are the hub's angle at the samples (to 1e-12 rad, the dense
    output's error there) and its applied commands ``-K (m - R_m rho)`` reach the hub (no delay:
    ``hub_torque`` at every sample time is that sample's command, bit for bit)."""
    n = 2
    N = 2 + 2 * n
    row = np.zeros(2 * N)
    row[N - 1] = 1.0
    rate = np.zeros(2 * N)
    rate[2 * N - 1] = 1.0
    Ts = 0.01
    loop = SampledLoop([SensorSpec("encoder"), SensorSpec("tachometer")], np.array([row, rate]), np.zeros((0, 0)),
                       np.zeros((0, 2)), np.zeros(0), np.zeros((2, 0)), np.eye(2), np.array([0.05, 0.005]),
                       np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.zeros(3), np.zeros(0), Ts=Ts)
    case = {"name": "rig", "model": "FOAM", "modes": n, "t_end": 1.0, "damping": RIG_DAMPED,
            "maneuver": {"kind": "pd", "kp": 0.0, "kd": 0.0,
                         "reference": {"kind": "prescribed", "wf": 2.0, "tf": 0.5}},
            "root_spring": RootSpring(0.5, 0.01, 2e-5).to_dict()}
    run = rig_run(case, flexible_link, dict(RIG_NUMERICS, output_step=Ts), loop=loop)
    columns = output_columns(n, joint=True)
    records = run.records
    assert run.status == 0 and float(np.max(np.abs(records.applied))) > 1e-3
    np.testing.assert_allclose(records.sensed[:, 0], run.out[:, columns["hub_angle"]], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(run.out[:, columns["hub_torque"]], records.applied)
    rigid_rows = dataclasses.replace(loop, rows=loop.rows[:, :10])
    with pytest.raises(SimulationError, match="rows of length 10; allowed: 2 N = 12, the state .* and the root "
                                              "spring's hub angle"):
        rig_run(dict(case, root_spring={"stiffness": 0.5}), flexible_link, RIG_NUMERICS, loop=rigid_rows)


def test_the_tracked_modes_carry_the_spring(paper_beam):
    """The tracked eigen-analysis (``linear.datasets.tracked_modes``) with the spring, the hub held
    and free over a speed grid: undamped, its frequencies at each speed are the eigen-analysis's
    (``eigen.root_frequencies``: the same equations through the state matrix and through the
    quadratic pencil, to 1e-9; on the free hub the hub's swing against the link among them), and
    the states name the hub angle."""
    sm = assemble(paper_beam, None, 3)
    spring = RootSpring(2e3, 0.0, paper_beam.Jh / 2.0)
    speeds = np.array([0.0, 1.0, 2.0])
    for hub, held in (("prescribed", "held"), ("free", "free")):
        modes, names = tracked_modes(paper_beam, sm, "FOAM", hub, speeds, root_spring=spring)
        assert names[0] == "theta" and names[-1] == "phi"
        for k, speed in enumerate(speeds):
            pencil = eigen.root_frequencies(sm, spring, "FOAM", speed, held)
            state = np.sort(modes.frequency[k])
            vibrating = pencil > 1e-6 * pencil.max()
            np.testing.assert_allclose(state[-vibrating.sum():], pencil[vibrating], rtol=1e-9)

"""State feedback on a free hub: the gains of a ``state_feedback`` maneuver, given or designed.

A ``state_feedback`` maneuver (:class:`hubbeam.model.maneuvers.StateFeedback`; kernel
:func:`hubbeam.core.maneuver.feedback_torque`) applies ``tau = J theta_r'' - K (x - x_r)`` to the
hub. Its gains ``K`` act on states by name (:meth:`hubbeam.model.models.Model.state_names`:
``theta, q1_i, q2_i`` and their rates ``*_dot``) and come from one of

* ``gains``: given on states of the simulated model; states not named have gain zero;
* ``output_feedback``: given on measured signals ``y = c x`` with ``c`` the simulated model's
  linear output rows (``hubbeam.linear.statespace.output_rows``), so ``K = sum_j k_j c_j``; only
  outputs without feedthrough (``D = 0``) are allowed, their rows do not depend on the speed;
* ``design``: LQR (``control.lqr``) on the linear model (free hub, hub torque) of a design model
  about its steady spin at the design speed, with the case's beam, tip mass, modes and damping,
  ``Q`` diagonal weights on states plus ``w c' c`` for weighted outputs, ``R`` the torque weight.
  The design's gains on states the simulated model lacks (``q1`` of a FOAM design run on SFOAM)
  are dropped; states the design model lacks (``q1`` of an SFOAM design) get gain zero.

The reference ``x_r`` holds ``q1`` at the centrifugal stretch of the reference speed,
``theta_r'^2 s`` with ``s = (K1 - W^2 M1)^-1 V1`` at the reference's final speed ``W`` (the
stretch ``hubbeam.model.linearised.axial_stretch`` is ``W^2 s``): exact once the spin-up has ended, so
that a controller with gains on ``q1`` holds the steady spin without a torque offset.

The names of the gains and weights, the weights' signs and the feedforward's reference are checked
with the configuration (``hubbeam.configuration.checks``). What needs the case's matrices is
checked here, for every case of a configuration before any job runs
(``hubbeam.control.cases.case_problems``): a design speed where the design model has a steady
spin (``K1 - W^2 M1`` positive definite for a model that keeps ``q1``; TLAM beyond its critical
speed has one, unstable, and LQR may stabilise it), the plant's stabilisability (the PBH test on
every eigenvalue with ``Re >= 0``) and a stabilising Riccati solution. With a drive the design's
input is the voltage (``hubbeam.linear.voltage``), and the lumped model of the Quanser courseware
may be designed on (``hubbeam.linear.lumped``).
"""

from __future__ import annotations

import json

import numpy as np
import scipy.linalg

from hubbeam.configuration.schema import MEASURED_SIGNALS, Problem
from hubbeam.configuration.settings import Case
from hubbeam.control.sampling import weight_matrix
from hubbeam.linear.lumped import LUMPED_SIGNALS, FlexibleLinkRig, lumped_model
from hubbeam.linear.statespace import linear_model, model_states
from hubbeam.linear.voltage import voltage_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.maneuvers import FeedbackLaw
from hubbeam.model.matrices import assemble
from hubbeam.model.models import DESIGN_ONLY_MODELS
from hubbeam.model.models import model as model_traits
from hubbeam.model.plant import with_drive
from hubbeam.simulation.errors import SimulationError
from hubbeam.simulation.simulate import quadrature_points

#: relative size below which a left eigenvector's projection on the input counts as zero (PBH)
UNCONTROLLABLE = 1e-9


class FeedbackError(SimulationError):
    """A feedback law that cannot be resolved: ``problem`` names the configuration key and says
    what was found and what is allowed."""

    def __init__(self, key: str, text: str):
        self.problem = Problem(key, text)
        super().__init__(str(self.problem))


def coordinate_names(n: int, root_spring=None) -> tuple[str, ...]:
    """The names of ``x = (y, y')``, ``y = (theta, q1, q2)`` with ``n`` modes, and the hub angle
    ``phi`` last with a ``root_spring`` (the kernel's order, ``hubbeam.model.root.state_names``)."""
    return model_states(model_traits("FOAM"), n, root_spring)


def _where(case: Case) -> str:
    return f"cases.{case.label}.maneuver"


def steady_spin_check(key: str, sm, traits, speed: float) -> None:
    """:class:`FeedbackError` (naming the configuration ``key`` of ``speed``) unless the model has a
    steady spin at ``speed``: the axial stiffness ``K1 - speed^2 M1`` positive definite for a
    model that keeps ``q1`` (Eqs. 29-30)."""
    if not traits.keeps_axial:
        return
    lowest = scipy.linalg.eigh(sm.K1, sm.M1, eigvals_only=True)[0]
    if speed**2 >= lowest:
        raise FeedbackError(key, f"got {speed!r}; allowed: a speed below {np.sqrt(lowest):.6g} rad s-1, where "
                            "the centrifugal stretch of q1 has a steady state (K1 - speed^2 M1 positive definite)")


def stabilisability_check(where: str, lin) -> None:
    """:class:`FeedbackError` naming the first mode with ``Re(lambda) >= 0`` that the hub torque
    cannot move (PBH: a left eigenvector orthogonal to ``B``)."""
    values, left = scipy.linalg.eig(lin.A, left=True, right=False)
    scale = np.abs(values).max() + 1.0
    for k in np.argsort(-values.real):
        if values[k].real < -1e-12 * scale:
            break
        w = left[:, k]
        if abs(np.conj(w) @ lin.B[:, 0]) <= UNCONTROLLABLE * np.linalg.norm(w) * np.linalg.norm(lin.B):
            state = lin.states[int(np.argmax(np.abs(w)))]
            raise FeedbackError(
                f"{where}.model", f"got {lin.model!r} at speed {lin.speed!r} rad s-1: not stabilisable "
                f"from the hub torque: its mode at lambda = {values[k]:.6g} (mostly {state}) is "
                "uncontrollable and not stable; allowed: a plant whose unstable and undamped "
                "modes the torque moves (add damping, or another speed or model)")


def lumped_rig(beam, motor, held_frequency: float) -> FlexibleLinkRig:
    """The courseware's lumped rig of ``beam`` (its mass and length, its hub inertia as the servo's
    equivalent inertia, no separate clamp), driven by ``motor``, its spring fitted to the held-hub
    frequency ``held_frequency`` (Hz); the section's ``E I`` as its modulus on a unit moment, and the
    density that keeps its ``E A`` (``FlexibleLinkRig.beam`` gives ``beam`` back)."""
    EI, EA, rhoA = (float(getattr(beam, f"{name}_at")(0.0)) for name in ("EI", "EA", "rhoA"))
    return FlexibleLinkRig(length=beam.L, link_mass=beam.beam_mass, youngs_modulus=EI, second_moment=1.0,
                           density=EI * rhoA / EA, hub_inertia=beam.Jh, clamp_inertia=0.0,
                           held_frequency=held_frequency, motor=motor)


def design_matrices(case: Case, beam, sm):
    """The system matrices of the design model: ``sm`` (the run's, with the drive's rotor in the hub
    inertia), or, for a design with modes of its own, those assembled with that many modes on the
    Gauss nodes of ``sm``."""
    modes = case.maneuver.design.modes
    if modes is None or modes == sm.M1.shape[0]:
        return sm
    matrices = assemble(beam, case.tip_mass, modes, quadrature_points(sm), case.transverse_functions)
    return with_drive(matrices, case.drive)


def design_plant(case: Case, beam, sm):
    """The continuous linear model (free hub) a case's LQR is designed on: the design model with
    its modes about its steady spin at the design speed, the case's damping and root spring (the
    hub angle ``phi`` and the root's angle ``theta`` both states), the voltage as input with a drive
    (``hubbeam.linear.voltage``); or the courseware's lumped model (:func:`lumped_rig`, a rigid
    root); the measured signals among its outputs."""
    spec = case.maneuver.design
    if spec.model in DESIGN_ONLY_MODELS:
        return lumped_model(lumped_rig(beam, case.drive, spec.held_frequency))
    dsm = design_matrices(case, beam, sm)
    steady_spin_check(f"{_where(case)}.design.speed", dsm, model_traits(spec.model), spec.speed)
    damping = damping_matrices(case.damping, dsm)
    if case.drive is not None:
        return voltage_model(beam, dsm, spec.model, case.drive, spec.speed, damping, list(MEASURED_SIGNALS),
                             case.root_spring)
    return linear_model(beam, dsm, spec.model, spec.speed, "free", damping, list(MEASURED_SIGNALS), case.root_spring)


def lqr_design(case: Case, beam, sm) -> tuple[dict, dict]:
    """The LQR gains by state name of the design model (:func:`design_plant`) and the attributes of
    the design (settings, closed-loop poles, the Riccati solution ``P`` as a list): module docstring."""
    import control as ct

    where = f"{_where(case)}.design"
    spec = case.maneuver.design
    lin = design_plant(case, beam, sm)
    stabilisability_check(where, lin)
    try:
        Q = weight_matrix(lin, spec.weights)
    except ValueError as error:
        raise FeedbackError(f"{where}.weights", str(error)) from None
    try:
        K, P, poles = ct.lqr(lin.A, lin.B, Q, spec.input_weight)
    except ValueError as error:  # the Riccati solver's Hamiltonian has imaginary eigenvalues
        raise FeedbackError(
            where, f"the Riccati equation of the {spec.model} design at {spec.speed!r} rad s-1 has "
            f"no stabilising solution ({error}); allowed: weights and damping that leave no "
            "undamped mode unseen (add damping, e.g. of the axial modes, or weight their states)"
        ) from None
    attributes = {"feedback_design": json.dumps(spec.to_dict(), sort_keys=True),
                  "feedback_design_poles": json.dumps([[p.real, p.imag] for p in poles]),
                  "feedback_design_riccati": json.dumps(np.asarray(P).tolist())}
    return dict(zip(lin.states, np.asarray(K)[0].tolist(), strict=True)), attributes


def signal_gains(case: Case, beam, sm, signals) -> dict:
    """State gains of gains on measured signals: ``sum_j k_j c_j`` over the simulated model's
    states (``c_j`` its linear output rows, which do not depend on the speed; with a root spring
    ``hub_angle`` reads the hub, ``phi``)."""
    lin = linear_model(beam, sm, case.model, 0.0, "free", outputs=list(signals), root_spring=case.root_spring)
    K = np.array([signals[name] for name in lin.outputs]) @ lin.C
    return dict(zip(lin.states, K.tolist(), strict=True))


def feedback_law(case: Case, sm, beam) -> tuple[FeedbackLaw, dict]:
    """The :class:`~hubbeam.model.maneuvers.FeedbackLaw` of the ``state_feedback`` case ``case`` with
    the system matrices ``sm`` of ``beam``, and the dataset attributes that record it."""
    maneuver = case.maneuver
    n = sm.M1.shape[0]
    traits = model_traits(case.model)
    attributes = {}
    if maneuver.design is not None:
        by_name, attributes = lqr_design(case, beam, sm)
        if maneuver.design.model in DESIGN_ONLY_MODELS:  # its states are measured signals
            by_name = signal_gains(case, beam, sm, {LUMPED_SIGNALS[name]: value for name, value in by_name.items()})
    elif maneuver.output_feedback is not None:
        by_name = signal_gains(case, beam, sm, maneuver.output_feedback)
    else:
        by_name = dict(maneuver.gains)
    kept = model_states(traits, n, case.root_spring)
    names = coordinate_names(n, case.root_spring)
    gains = np.array([float(by_name.get(name, 0.0)) if name in kept else 0.0 for name in names])
    speed = maneuver.reference.final_speed
    steady_spin_check(f"{_where(case)}.reference.wf", sm, traits, speed)
    stretch = np.linalg.solve(sm.K1 - speed**2 * sm.M1, sm.V1) if traits.keeps_axial else np.zeros(n)
    inertia, damping = feedforward(case, sm) if maneuver.feedforward else (0.0, 0.0)
    attributes["feedback_gains"] = json.dumps(
        {name: value for name, value in zip(names, gains.tolist(), strict=True)
         if name in kept})
    return FeedbackLaw(gains, stretch, inertia, damping), attributes


def rigid_inertia(case: Case, sm) -> float:
    """The whole rigid body's inertia about the hub axis (kg m2): the hub with the drive's rotor,
    the beam, a tip body's rotary inertia, and a root spring's clamp, which turns with the link."""
    inertia = float(sm.Jh + sm.Jb + sm.Jt)
    return inertia if case.root_spring is None else inertia + case.root_spring.clamp_inertia


def feedforward(case: Case, sm) -> tuple[float, float]:
    """The rigid feedforward's coefficients on the reference's acceleration and rate: the whole
    rigid inertia ``J`` (:func:`rigid_inertia`) and 0 for a
    torque; ``J / kV`` and the drive's damping ``c / kV`` for a voltage (its torque gain ``kV``,
    ``hubbeam.model.drive``; Coulomb friction is not fed forward)."""
    inertia = rigid_inertia(case, sm)
    if case.drive is None:
        return inertia, 0.0
    return inertia / case.drive.torque_gain, case.drive.hub_damping / case.drive.torque_gain

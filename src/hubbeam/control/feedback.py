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
checked here, for every case of a configuration before any job runs (:func:`feedback_problems`):
a design speed where the design model has a steady spin (``K1 - W^2 M1`` positive definite for a
model that keeps ``q1``; TLAM beyond its critical speed has one, unstable, and LQR may stabilise
it), the plant's stabilisability (the PBH test on every eigenvalue with ``Re >= 0``) and a
stabilising Riccati solution.
"""

from __future__ import annotations

import functools
import json

import numpy as np
import scipy.linalg

from hubbeam.configuration.load import ConfigError
from hubbeam.configuration.schema import MEASURED_SIGNALS, Problem
from hubbeam.configuration.settings import Case, Settings
from hubbeam.control.sampling import weight_matrix
from hubbeam.linear.statespace import linear_model
from hubbeam.model.damping import damping_matrices
from hubbeam.model.maneuvers import FeedbackLaw, StateFeedback
from hubbeam.model.matrices import assemble
from hubbeam.model.models import model as model_traits
from hubbeam.simulation.simulate import SimulationError, simulate

#: relative size below which a left eigenvector's projection on the input counts as zero (PBH)
UNCONTROLLABLE = 1e-9


class FeedbackError(SimulationError):
    """A feedback law that cannot be resolved: ``problem`` names the configuration key and says
    what was found and what is allowed."""

    def __init__(self, key: str, text: str):
        self.problem = Problem(key, text)
        super().__init__(str(self.problem))


def coordinate_names(n: int) -> tuple[str, ...]:
    """The names of ``x = (y, y')``, ``y = (theta, q1, q2)`` with ``n`` modes (the kernel's order)."""
    return model_traits("FOAM").state_names(n)


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


def lqr_design(case: Case, beam, sm) -> tuple[dict, dict]:
    """The LQR gains by state name of the design model and the attributes of the design
    (settings, closed-loop poles, the Riccati solution ``P`` as a list): module docstring."""
    import control as ct

    where = f"{_where(case)}.design"
    spec = case.maneuver.design
    design_model = model_traits(spec.model)
    steady_spin_check(f"{where}.speed", sm, design_model, spec.speed)
    names = design_model.state_names(sm.M1.shape[0])
    lin = linear_model(beam, sm, spec.model, spec.speed, "free", damping_matrices(case.damping, sm),
                       outputs=list(MEASURED_SIGNALS))
    stabilisability_check(where, lin)
    Q = weight_matrix(lin, spec.weights)
    try:
        K, P, poles = ct.lqr(lin.A, lin.B, Q, spec.torque_weight)
    except ValueError as error:  # the Riccati solver's Hamiltonian has imaginary eigenvalues
        raise FeedbackError(
            where, f"the Riccati equation of the {spec.model} design at {spec.speed!r} rad s-1 has "
            f"no stabilising solution ({error}); allowed: weights and damping that leave no "
            "undamped mode unseen (add damping, e.g. of the axial modes, or weight their states)"
        ) from None
    attributes = {"feedback_design": json.dumps(spec.to_dict(), sort_keys=True),
                  "feedback_design_poles": json.dumps([[p.real, p.imag] for p in poles]),
                  "feedback_design_riccati": json.dumps(np.asarray(P).tolist())}
    return dict(zip(names, np.asarray(K)[0].tolist(), strict=True)), attributes


def output_gains(case: Case, beam, sm) -> dict:
    """The state gains of ``output_feedback``: ``sum_j k_j c_j`` over the simulated model's states."""
    signals = case.maneuver.output_feedback
    lin = linear_model(beam, sm, case.model, 0.0, "free", outputs=list(signals))
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
    elif maneuver.output_feedback is not None:
        by_name = output_gains(case, beam, sm)
    else:
        by_name = dict(maneuver.gains)
    kept = traits.state_names(n)
    gains = np.array([float(by_name.get(name, 0.0)) if name in kept else 0.0
                      for name in coordinate_names(n)])
    speed = maneuver.reference.final_speed
    steady_spin_check(f"{_where(case)}.reference.wf", sm, traits, speed)
    stretch = np.linalg.solve(sm.K1 - speed**2 * sm.M1, sm.V1) if traits.keeps_axial else np.zeros(n)
    inertia = float(sm.Jh + sm.Jb + sm.Jt) if maneuver.feedforward else 0.0  # the rigid inertia, a body's too
    attributes["feedback_gains"] = json.dumps(
        {name: value for name, value in zip(coordinate_names(n), gains.tolist(), strict=True)
         if name in kept})
    return FeedbackLaw(gains, stretch, inertia), attributes


def feedback_problems(settings: Settings) -> list[Problem]:
    """What would stop a state-feedback case of ``settings`` once its matrices are known (module
    docstring), found by resolving its law with the matrices of the case (``numerics.quadrature_points``
    Gauss nodes), one problem per case."""
    problems = []
    for case in settings.cases.values():
        if not isinstance(case.maneuver, StateFeedback):
            continue
        sm = assemble(settings.beam, case.tip_mass, case.modes, settings.numerics.quadrature_points)
        try:
            feedback_law(case, sm, settings.beam)
        except FeedbackError as error:
            problems.append(error.problem)
    return problems


def check_feedback(settings: Settings, sources=()) -> None:
    """:class:`~hubbeam.configuration.load.ConfigError` listing :func:`feedback_problems`, if any."""
    problems = feedback_problems(settings)
    if problems:
        raise ConfigError(problems, sources)


def simulate_case(case, params, numerics, matrices=None, **options):
    """:func:`hubbeam.simulation.simulate.simulate` of any case, a ``state_feedback`` one with its gains
    resolved (:func:`feedback_law`) for the matrices of every run."""
    return simulate(case, params, numerics, matrices,
                    feedback=functools.partial(feedback_law, beam=params), **options)

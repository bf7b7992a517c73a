"""Tuning a command shaper from the linear models: the frequency and damping of the mode a
maneuver's command excites.

A shaper (:mod:`hubbeam.model.shapers`) cancels the vibration of the modes it is tuned to; on the
rotating beam those move with the hub speed (dynamic stiffening) and differ between the models
(TLAM's first frequency falls to zero at its critical speed, where its steady spin turns
divergent), so the tuning reads the linear model (:func:`hubbeam.linear.statespace.linear_model`)
of the chosen model about the steady spin at a chosen speed, with the loop the command drives
(:data:`LOOPS`):

* ``held``: a prescribed hub (Eq. 43, a speed table): the modes with the hub angle held, the
  model with the hub's acceleration as its input;
* ``free``: a torque on a free hub (Eq. 44, a torque table): the modes of the free hub-beam;
* ``closed``: a controller's reference (``pd``, ``state_feedback``): the modes of the linear
  closed loop ``A - B K`` of the free hub under the controller's gains ``K`` (by state name, as
  ``hubbeam.control.feedback`` resolves them).

The modes are those of ``hubbeam.linear.tracking.state_modes``: one per complex pair of
eigenvalues ``lambda = -zeta omega + i omega sqrt(1 - zeta^2)``, so ``omega = |lambda|`` (the
natural frequency a shaper takes) and ``zeta = -Re lambda / |lambda|`` (0 for an undamped mode,
whose computed real part is rounding of either sign). Mode ``k`` is the ``k``-th vibration by
frequency, or the one with the label ``k`` (``"bending 1"``: dominant coordinate group, numbered
by frequency in the group, ``hubbeam.linear.tracking``); rigid-body modes (the free hub's rotation, the held hub's
integrators of its input) and stable non-oscillating pairs (an overdamped hub under feedback) are
not vibrations and are not counted. Refused, naming the argument: a mode number beyond the
vibrations the model has, and any model with a growing mode (TLAM beyond its critical speed, an
unstable loop), where a shaper, which only cancels decaying or steady vibration, cannot help.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from hubbeam.configuration.settings import Case
from hubbeam.control.feedback import coordinate_names, feedback_law
from hubbeam.linear.datasets import HUB_NAMES, mode_weights
from hubbeam.linear.statespace import linear_model
from hubbeam.linear.tracking import dominant_content, numbered_by_frequency, state_modes
from hubbeam.model.damping import damping_matrices
from hubbeam.model.maneuvers import PRESCRIBED_HUB, Maneuver, PdControl, Tracking
from hubbeam.model.root import HUB_COORDINATE

#: the loop a command drives -> the hub of the linear model: the datasets' hub conditions
#: (``held``, ``free``) and a closed loop, whose plant has a free hub
LOOPS = {**HUB_NAMES, "closed": HUB_NAMES["free"]}


class ShapingMode(NamedTuple):
    """A mode to shape: natural frequency ``omega`` (rad s-1) and damping ratio ``zeta``, the
    eigenvalue it comes from, its label by dominant content (``bending 1``, ``hub``, ...) and
    where it was found (model, loop, speed)."""

    omega: float
    zeta: float
    eigenvalue: complex
    label: str
    model: str
    loop: str
    speed: float


def _gain_row(lin, gains: Mapping) -> np.ndarray:
    """The closed loop's ``K`` in the order of ``lin.states``: ``gains`` by state name, zero
    where not named; names the model lacks must have zero gain (``q1`` on SFOAM)."""
    unknown = [name for name, value in gains.items() if name not in lin.states and value != 0.0]
    if unknown:
        raise ValueError(f"gains.{unknown[0]} = {gains[unknown[0]]!r}: {lin.model} has no such "
                         f"state; allowed: {', '.join(lin.states)}")
    return np.array([[float(gains.get(name, 0.0)) for name in lin.states]])


def linear_shaping_mode(beam, sm, model: str, speed: float, loop: str = "held", *,
                        mode: int | str = 1, damping=None, gains: Mapping | None = None,
                        root_spring=None) -> ShapingMode:
    """The ``mode``-th vibration (by frequency, from 1; or the one labelled ``mode``, such as
    ``"bending 1"``) of ``model`` about its steady spin at ``speed`` (rad s-1) in the ``loop``
    (:data:`LOOPS`), from its linear model.

    ``beam`` and ``sm`` (its system matrices, with the tip mass) as in
    :func:`hubbeam.linear.statespace.linear_model`; ``damping`` the ``(2, n, n)`` matrices of
    ``hubbeam.model.damping`` or None; ``gains`` the controller's gains by state name (``theta``,
    ``q2_1``, ``theta_dot``, ...), required for ``loop = "closed"`` only; ``root_spring`` a compliant
    root (``hubbeam.model.root.RootSpring``; its hub angle ``phi`` then the held or driven one).
    """
    if loop not in LOOPS:
        raise ValueError(f"loop = {loop!r}; allowed: one of {', '.join(LOOPS)}")
    if (gains is not None) != (loop == "closed"):
        raise ValueError(f"gains = {gains!r} with loop = {loop!r}; allowed: gains for the closed "
                         "loop, and only for it")
    numbered = isinstance(mode, (int, np.integer)) and not isinstance(mode, bool)
    if not ((numbered and mode >= 1) or isinstance(mode, str)):
        raise ValueError(f"mode = {mode!r}; allowed: a mode number 1, 2, ... (by frequency) or a "
                         "label such as 'bending 1'")
    lin = linear_model(beam, sm, model, speed, LOOPS[loop], damping, outputs=["tip_deflection"],
                       root_spring=root_spring)
    A = lin.A - lin.B @ _gain_row(lin, gains) if loop == "closed" else lin.A
    N = A.shape[0] // 2
    weights = mode_weights(sm, model, root_spring)  # kinetic-energy weights of the labels
    modes = state_modes(A[None], weights)
    where = f"{model} ({loop} loop) at speed {lin.speed!r} rad s-1"
    growing = np.flatnonzero(~modes.stable[0])
    if growing.size:
        value = modes.eigenvalue[0, growing[0]]
        raise ValueError(f"model = {model!r}, speed = {lin.speed!r}: {where} has a growing mode "
                         f"(eigenvalue {value:.6g} 1/s; beyond a critical speed, or an unstable "
                         "loop); allowed: a model and speed whose modes all decay or persist")
    vibrating = np.flatnonzero(~modes.rigid[0] & ~modes.divergent[0])
    vibrating = vibrating[np.argsort(modes.frequency[0, vibrating], kind="stable")]
    labels = numbered_by_frequency(dominant_content(modes.shape, lin.states[:N], weights, modes.rigid)[0])[0]
    names = [str(labels[k]) for k in vibrating]
    if (numbered and mode > vibrating.size) or (not numbered and mode not in names):
        listed = ", ".join(f"{name} {modes.frequency[0, k]:.6g} rad s-1" for name, k in zip(names, vibrating))
        raise ValueError(f"mode = {mode!r}: {where} has {vibrating.size} vibration modes ({listed}); "
                         f"allowed: 1..{vibrating.size} or one of these labels")
    k = vibrating[mode - 1 if numbered else names.index(mode)]
    value = complex(modes.eigenvalue[0, k])
    zeta = max(-value.real / abs(value), 0.0)  # stable: a positive real part is rounding
    return ShapingMode(abs(value), zeta, value, str(labels[k]), model, loop, lin.speed)


def maneuver_loop(maneuver: Maneuver) -> str:
    """The loop a maneuver's command drives (:data:`LOOPS`): ``held`` (the modes of the hub held)
    for a prescribed hub, ``closed`` for a controller's reference, ``free`` for a torque."""
    if isinstance(maneuver, Tracking):
        return "closed"
    return "held" if maneuver.hub == PRESCRIBED_HUB else "free"


def case_shaping_mode(case: Case, beam, sm, speed: float, *, mode: int = 1,
                      model: str | None = None) -> ShapingMode:
    """:func:`linear_shaping_mode` of the mode ``case``'s command excites: the loop of its
    maneuver (:func:`maneuver_loop`), its damping, its compliant root, and for a controller its
    gains (``pd``: ``kp`` on the hub angle, ``theta`` or with a root spring ``phi``, ``kd`` on its
    rate; ``state_feedback``: resolved by :func:`hubbeam.control.feedback.feedback_law` for
    ``sm``), of ``model`` (default the case's) about the steady spin at ``speed``."""
    maneuver = case.maneuver
    loop = maneuver_loop(maneuver)
    gains = None
    if isinstance(maneuver, PdControl):
        hub = "theta" if case.root_spring is None else HUB_COORDINATE
        gains = {hub: maneuver.kp, f"{hub}_dot": maneuver.kd}
    elif loop == "closed":
        law = feedback_law(case, sm, beam)[0]
        gains = dict(zip(coordinate_names(sm.M1.shape[0]), law.gains.tolist(), strict=True))
    return linear_shaping_mode(beam, sm, model or case.model, speed, loop, mode=mode,
                               damping=damping_matrices(case.damping, sm), gains=gains, root_spring=case.root_spring)

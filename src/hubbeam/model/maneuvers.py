"""Hub maneuvers of a case: the kernel's parameter array and the times no step may cross.

A case's ``maneuver`` (checked with the configuration: schema ``maneuver``, one branch of keys per
kind) has a ``kind``:

* ``prescribed`` ``{wf, tf}``: the spin-up of Eq. (43); ``torque`` ``{tau_max, tf}``: the torque
  pulse of Eq. (44);
* ``speed_table`` ``{time, speed}`` (s, rad s-1): a prescribed hub speed, a clamped cubic spline
  with zero slope at both ends (theta_ddot continuous and zero at the ends; theta its exact
  integral from theta(0) = 0), the first speed held before the table and the last after it;
* ``torque_table`` ``{time, torque}`` (s, N m): the torque on a free hub, linear between the rows,
  the first value held before the table and the last after it;
* ``pd`` ``{kp, kd, reference}`` (N m rad-1, N m s rad-1): a free hub under ``tau = kp (theta_r -
  theta) + kd (theta_r' - theta')`` tracking ``reference`` = ``{kind: prescribed, wf, tf}``
  (Eq. 43) or ``{kind: angle_table, time, angle}`` (s, rad; clamped cubic spline as above);
* ``state_feedback`` ``{reference, feedforward, gains | output_feedback | design}``: a free hub
  under feedback of its whole state towards ``reference`` (as for ``pd``); its gains, the
  stretch of the reference and the feedforward inertia are a :class:`FeedbackLaw`, which
  ``hubbeam.control.feedback`` resolves from the case (a design needs the linear models).

The kernels (:mod:`hubbeam.core.maneuver`) take an integer kind and a float array; the splines'
coefficients are computed here once per run (scipy's ``CubicSpline``, ``bc_type="clamped"``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

import numpy as np
from scipy.interpolate import CubicSpline

from hubbeam.core import maneuver as kernels

#: kinds with scalar parameters -> (kernel id, parameters in the order of the kernel's ``mp``)
MANEUVERS = {"prescribed": (kernels.PRESCRIBED, ("wf", "tf")),
             "torque": (kernels.TORQUE, ("tau_max", "tf"))}
#: tabulated kinds -> (kernel id, value column, interpolation: "spline" or "linear")
TABLES = {"speed_table": (kernels.SPEED_TABLE, "speed", "spline"),
          "torque_table": (kernels.TORQUE_TABLE, "torque", "linear")}
#: reference kinds of ``pd`` -> (kernel id, parameters in the order of the kernel's reference)
REFERENCES = {"prescribed": (kernels.PRESCRIBED, ("wf", "tf")),
              "angle_table": (kernels.ANGLE_TABLE, ("time", "angle"))}


#: the kinds whose controller tracks a ``reference`` motion
TRACKING = ("pd", "state_feedback")


class FeedbackLaw(NamedTuple):
    """The resolved gains of a ``state_feedback`` maneuver in the coordinates ``x = (y, y')``,
    ``y = (theta, q1, q2)`` of the simulated model (``2 N`` gains, positions then rates; zero on
    the ``q1`` of a model that keeps none), the ``q1`` reference per squared reference speed
    ``stretch`` (``n`` values) and the feedforward inertia (0: no feedforward)."""

    gains: np.ndarray
    stretch: np.ndarray
    inertia: float


def packed_table(time, values, interpolation: str) -> np.ndarray:
    """The table layout of :mod:`hubbeam.core.maneuver`: ``[m, t, I, c (per interval), last]``.

    ``interpolation`` is ``"spline"`` (clamped cubic spline, zero slope at both ends) or
    ``"linear"``; ``I_k`` is the exact integral of the interpolant from 0 (the first value held
    before ``t_0``) to ``t_k``.
    """
    t = np.asarray(time, dtype=float)
    y = np.asarray(values, dtype=float)
    h = np.diff(t)
    if interpolation == "spline":
        coefficients = CubicSpline(t, y, bc_type="clamped").c[::-1].T  # rows (c0, c1, c2, c3)
    else:
        slope = np.diff(y) / h
        coefficients = np.column_stack([y[:-1], slope, np.zeros_like(h), np.zeros_like(h)])
    c0, c1, c2, c3 = coefficients.T
    pieces = h * (c0 + h * (c1 / 2.0 + h * (c2 / 3.0 + h * c3 / 4.0)))
    integrals = y[0] * t[0] + np.concatenate([[0.0], np.cumsum(pieces)])
    return np.concatenate([[t.size], t, integrals, coefficients.ravel(), [y[-1]]])


def maneuver_parameters(maneuver: Mapping, law: FeedbackLaw | None = None) -> tuple[int, np.ndarray]:
    """Kernel id and parameter array ``mp`` of a checked maneuver (:mod:`hubbeam.core.maneuver`);
    a ``state_feedback`` maneuver needs its resolved ``law``."""
    kind = maneuver["kind"]
    if kind in MANEUVERS:
        code, keys = MANEUVERS[kind]
        return code, np.array([float(maneuver[key]) for key in keys])
    if kind in TABLES:
        code, column, interpolation = TABLES[kind]
        return code, packed_table(maneuver["time"], maneuver[column], interpolation)
    reference = maneuver["reference"]
    ref_code, keys = REFERENCES[reference["kind"]]
    if ref_code == kernels.ANGLE_TABLE:
        ref = packed_table(reference["time"], reference["angle"], "spline")
    else:
        ref = np.array([float(reference[key]) for key in keys])
    if kind == "pd":
        head = [float(maneuver["kp"]), float(maneuver["kd"]), float(ref_code)]
        assert len(head) == kernels.PD_REFERENCE
        return kernels.PD, np.concatenate([head, ref])
    if law is None:
        raise ValueError("maneuver.kind = 'state_feedback' without its feedback law; allowed: "
                         "hubbeam.control.feedback.simulate_case, which resolves the gains")
    head = [float(law.gains.size // 2), float(law.inertia)]
    assert len(head) == kernels.FEEDBACK_GAINS
    return kernels.STATE_FEEDBACK, np.concatenate([head, law.gains, law.stretch, [ref_code], ref])


def start_speed(maneuver: Mapping) -> float | None:
    """The hub speed at ``t = 0`` (rad s-1) of a checked maneuver that prescribes the hub (Eq. 43
    or a speed table); None for a free hub (a torque, a table of torques, a controller)."""
    if maneuver["kind"] in TRACKING:
        return None
    kind, mp = maneuver_parameters(maneuver)
    return float(kernels.prescribed_motion(kind, 0.0, mp)[1]) if kernels.prescribed(kind) else None


def maneuver_stops(maneuver: Mapping) -> np.ndarray:
    """Sorted times where the maneuver's forcing is not smooth: the end ``tf`` of Eq. (43)/(44),
    or the rows of a table (spline knots, kinks of a linear table)."""
    if maneuver["kind"] in TRACKING:
        maneuver = maneuver["reference"]
    if "tf" in maneuver:
        return np.array([float(maneuver["tf"])])
    return np.asarray(maneuver["time"], dtype=float)

"""Validity of a run: inside the small-deflection range of the models, beyond it, out of the range
they describe, or diverged. The one place that classifies a run (simulations, sweeps, claims,
figures and reports read its result).

All four models (TLAM, FOAM, SFOAM, CFOAM) describe a beam whose elastic deformation is small:
the deformation field is a sum of assumed modes of the straight beam (Eqs. 7-8) and the strain
energy is the linear-elastic one of the undeformed geometry (Eqs. 14-17); FOAM and CFOAM keep the
foreshortening to second order (Eqs. 11-13, 35), and nothing of higher order. A run is

* ``valid``: its largest tip deflection ``max |v(L)| / L`` stays within
  ``numerics.small_deflection_limit`` (default 0.1, :data:`hubbeam.model.limits.SMALL_DEFLECTION_LIMIT`);
* ``large_deflection``: it completes, but beyond that limit, where the models' small-deformation
  assumption no longer holds and the numbers are the models', not the beam's;
* ``left_range``: it was stopped when ``|v(L)|`` exceeded ``numerics.divergence_limit * L``
  (radau status ``left_range``) although the model's linearised stiffness stays positive: a
  bounded response that the models cannot describe;
* ``stopped`` (a single run's, not a sweep's category: a sweep counts its stopped runs apart): the
  integrator's step budget ``numerics.max_steps`` ran out before the end of the run; what it
  computed is kept, the rest is NaN, and nothing is known of the run after ``t_stop``;
* ``diverged``: unbounded growth. The transverse stiffness ``K22(Omega)`` of Eq. (31) of the
  model's linearisation (TLAM's for TLAM, FOAM's for FOAM, SFOAM and CFOAM, which keep the
  stiffening term ``Omega^2 D``) lost positive definiteness at the highest hub speed of the run,
  i.e. the run went beyond its critical speed and ``q2`` grows exponentially (TLAM above
  2.91 rad/s without tip mass, Section 4.2); or the state became non-finite or the step vanished.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from hubbeam.core import radau
from hubbeam.model import linearised, models

CATEGORIES = ("valid", "large_deflection", "left_range", "diverged")
VALID, LARGE_DEFLECTION, LEFT_RANGE, DIVERGED = range(len(CATEGORIES))
#: a short text of each category for legends, figure notes and reports
LABELS = {
    "valid": "within the small-deflection range",
    "large_deflection": "large deflection (beyond the small-deflection range of the models)",
    "left_range": "left the range of the models (stopped, bounded response)",
    "diverged": "diverged (beyond the critical speed, unbounded growth)",
}
#: a single run stopped by its step budget (:func:`run_attributes`; a sweep counts such runs apart)
STOPPED = "stopped"
LABELS[STOPPED] = "stopped by the step budget before its end"
#: the integrator statuses of a blown-up state
BLOWN_UP = (radau.NON_FINITE, radau.STEP_UNDERFLOW)


def stiffness_lost(K2: np.ndarray, M2: np.ndarray, D: np.ndarray, model: str, speed: float) -> bool:
    """``K22(speed)`` of Eq. (31) for ``model``'s linearisation (``hubbeam.model.models``) is not
    positive definite."""
    if not math.isfinite(speed):
        return False
    K22 = linearised.transverse_stiffness(K2, M2, D, models.model(model).linearisation, speed)
    return bool(np.linalg.eigvalsh(K22)[0] <= 0.0)


def classify(status: int, lost_stiffness: bool, deflection_ratio: float, small_limit: float) -> int:
    """The category (:data:`CATEGORIES` index) of a run from its radau ``status``, whether its
    linearised stiffness was lost (:func:`stiffness_lost`) and ``max |v(L)| / L``."""
    if status in BLOWN_UP or (status == radau.LEFT_RANGE and lost_stiffness):
        return DIVERGED
    if status == radau.LEFT_RANGE:
        return LEFT_RANGE
    return LARGE_DEFLECTION if deflection_ratio > small_limit else VALID


def run_attributes(status: int, t_stop: float, model: str, sm, theta_dot: np.ndarray,
                   tip: np.ndarray, length: float, small_limit: float, t_end: float = math.nan,
                   max_steps: int | None = None) -> dict:
    """The validity attributes of a simulation dataset: ``validity`` (a :data:`CATEGORIES` name),
    ``diverged``, ``diverged_at_s``, ``left_range``, ``large_deflection`` (1 when the deflection
    exceeded the small-deflection limit, also in a run that was stopped), ``max_deflection_ratio``
    (``max |v(L)| / L`` over the outputs) and ``small_deflection_limit``; plus ``warning``, the
    sentence for the dataset's ``warnings`` (empty for a valid run; for a run stopped by the step
    budget ``max_steps`` before ``t_end``, what stopped it and what to change)."""
    finite = np.isfinite(tip)
    ratio = float(np.max(np.abs(tip[finite])) / length) if finite.any() else math.nan
    speeds = np.abs(theta_dot[np.isfinite(theta_dot)])
    speed = float(speeds.max()) if speeds.size else math.nan
    category = classify(status, stiffness_lost(sm.K2, sm.M2, sm.D, model, speed), ratio, small_limit)
    name = CATEGORIES[category]
    if status == radau.TOO_MANY_STEPS:
        budget = "" if max_steps is None else f" = {max_steps}"
        return {"validity": STOPPED, "diverged": 0, "diverged_at_s": math.nan, "left_range": 0,
                "large_deflection": int(ratio > small_limit), "max_deflection_ratio": ratio,
                "small_deflection_limit": float(small_limit),
                "warning": f"stopped at t = {t_stop:.6g} s of {t_end:.6g} s: the step budget numerics.max_steps"
                           f"{budget} ran out; allowed: a larger numerics.max_steps (or a looser numerics.rtol, "
                           "fewer modes, a shorter t_end); the run is not valid after it"}
    warning = {
        VALID: "",
        LARGE_DEFLECTION: f"large deflection: max |v(L)| = {ratio:.3g} L exceeds numerics."
                          f"small_deflection_limit = {small_limit:g} L, beyond the small-deformation "
                          "range the models assume",
        LEFT_RANGE: f"left the range of the models at t = {t_stop:.6g} s (|v(L)| beyond "
                    "numerics.divergence_limit * L, stopped) with a positive linearised stiffness: "
                    "a bounded response the models cannot describe",
        DIVERGED: f"diverged at t = {t_stop:.6g} s ({radau.STATUS_NAMES[status]}"
                  + (f"; K22 of Eq. 31 not positive definite at the hub speed {speed:.4g} rad/s"
                     if status == radau.LEFT_RANGE else "") + ")",
    }[category]
    return {
        "validity": name,
        "diverged": int(category == DIVERGED),
        "diverged_at_s": float(t_stop) if category == DIVERGED else math.nan,
        "left_range": int(category == LEFT_RANGE),
        "large_deflection": int(category != VALID),
        "max_deflection_ratio": ratio,
        "small_deflection_limit": float(small_limit),
        "warning": warning,
    }


def describe(attrs: Mapping) -> str:
    """A report cell for the simulation dataset attributes ``attrs``: ``valid``, ``large
    deflection (0.54 L)``, ``left range at 12.3 s (0.98 L)`` or ``diverged at 41.2 s``."""
    name = str(attrs["validity"])
    ratio = f"{float(attrs['max_deflection_ratio']):.2g} L"
    if name == "valid":
        return name
    if name == "large_deflection":
        return f"large deflection ({ratio})"
    if name == "left_range":
        return f"left range at {float(attrs['stopped_at_s']):.2f} s ({ratio})"
    if name == STOPPED:
        return f"stopped at {float(attrs['stopped_at_s']):.2f} s by numerics.max_steps"
    return f"diverged at {float(attrs['diverged_at_s']):.2f} s"

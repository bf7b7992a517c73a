"""State feedback for a sampled loop: discrete LQR, or the continuous LQR gain applied through the hold.

Both act on a :class:`hubbeam.linear.discrete.DiscreteModel` (the plant sampled with a zero-order
hold every ``Ts`` seconds, its delayed inputs among the states) with one input, ``u_k = -K x_k``:

* :func:`discrete_lqr`: ``control.dlqr`` minimises ``sum_k x_k^T Q x_k + R u_k^2`` subject to the
  discrete model; ``Q`` from weights on named states (the delayed inputs' too) or outputs, as
  ``hubbeam.control.feedback`` builds it (:func:`hubbeam.control.sampling.weight_matrix`), ``R``
  on the input's unit squared (volts^2 for a drive: ``hubbeam.linear.voltage.voltage_weight``
  translates a torque weight). Scaling ``Q`` and ``R`` together leaves ``K`` unchanged, so the same
  weights as a continuous design give gains that tend to the continuous ones as ``Ts -> 0``
  (the discrete Riccati solution times ``Ts`` tends to the continuous one).
* :func:`continuous_lqr`: ``control.lqr`` on the continuous model and its gain used at the samples
  (zero on the delayed inputs), what the Quanser courseware does; the poles are those of the
  sampled loop, ``eig(Ad - Bd K)``.

Checked before anything is solved, each a ``ValueError``: the weights (names, ``>= 0``), ``R > 0``,
one input, and that every mode of the discrete model that is not asymptotically stable can be
moved by the input (PBH on its left eigenvectors); a Riccati equation without a stabilising
solution, and a gain that leaves a pole of the sampled loop on or outside the unit circle (what
the solvers return when the weights do not see a mode there, such as the rigid-body mode without
a weight on the hub angle; or a continuous gain too fast for the sample time), are reported with
the weights to change.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from hubbeam.control.sampling import positive_weight, reachability_check, stability_check, weight_matrix


@dataclass(frozen=True, eq=False)
class LqrDesign:
    """``u_k = -K x_k`` on the states of ``model`` (a ``DiscreteModel``): ``K`` (states,), the Riccati
    solution ``P`` (discrete for :func:`discrete_lqr`, continuous for :func:`continuous_lqr`), the
    sampled loop's poles ``eig(Ad - Bd K)``, the weights and the method."""

    model: object
    K: np.ndarray
    P: np.ndarray
    poles: np.ndarray
    weights: dict
    input_weight: float
    method: str


def _checked(dm, weights: Mapping[str, float], input_weight, model) -> tuple[np.ndarray, float]:
    if len(dm.inputs) != 1:
        raise ValueError(f"{dm.name} has inputs {list(dm.inputs)}; allowed: one input")
    Q = weight_matrix(model, weights)
    R = positive_weight(input_weight, "input_weight")
    reachability_check(dm, dm.B, f"the LQR design on {dm.name}", "the input")
    return Q, R


def _solved(solve, what: str):
    try:
        return solve()
    except ValueError as error:  # the Hamiltonian or symplectic pencil has eigenvalues on the boundary
        raise ValueError(f"{what}: the Riccati equation has no stabilising solution ({error}); allowed: weights "
                         "that leave no undamped mode unseen (weight its states or outputs, or damp it)") from None


def discrete_lqr(dm, weights: Mapping[str, float], input_weight: float) -> LqrDesign:
    """``control.dlqr`` on the discrete model ``dm`` (module docstring)."""
    import control as ct

    Q, R = _checked(dm, weights, input_weight, dm)
    K, P, poles = _solved(lambda: ct.dlqr(dm.A, dm.B, Q, R), f"the discrete LQR design on {dm.name}")
    stability_check(dm, poles, f"the discrete LQR design on {dm.name}")
    return LqrDesign(model=dm, K=np.asarray(K)[0], P=np.asarray(P), poles=np.asarray(poles), weights=dict(weights),
                     input_weight=R, method="discrete LQR (control.dlqr)")


def continuous_lqr(dm, weights: Mapping[str, float], input_weight: float, check: bool = True) -> LqrDesign:
    """``control.lqr`` on ``dm.continuous`` with its gain applied at the samples (module docstring);
    ``check=False`` returns the gain even when the sampled loop of ``dm`` is not stable (a sweep of
    the sample time looks for where it stops being so)."""
    import control as ct

    lm = dm.continuous
    Q, R = _checked(dm, weights, input_weight, lm)
    K, P, _ = _solved(lambda: ct.lqr(lm.A, lm.B, Q, R), f"the continuous LQR design on {lm.name}")
    gains = np.zeros(dm.A.shape[0])
    gains[:dm.plant_states] = np.asarray(K)[0]
    poles = np.linalg.eigvals(dm.A - np.outer(dm.B[:, 0], gains))
    if check:
        stability_check(dm, poles, f"the continuous LQR design on {lm.name} sampled every {dm.Ts:g} s")
    return LqrDesign(model=dm, K=gains, P=np.asarray(P), poles=poles, weights=dict(weights), input_weight=R,
                     method="continuous LQR (control.lqr) through the hold")


__all__ = ["LqrDesign", "continuous_lqr", "discrete_lqr"]
